"""Adaptive shading decisions: Hast's Gouraud test, Hammersley's highlight test, and the
specular term through the Euler unit.

**Gouraud or corrected Euler** (Hast, Barrera & Bengtsson §5, equations 23–24).  Over a
span of ``n`` steps Gouraud steps by ``d_p = (p_b - p_a)/n`` and corrected Euler by
``t_0 + m·ds`` at step ``m``; both start at ``p_a`` and end at ``p_b``.  Their
difference after ``m`` steps is ``δ(m) = m·d_p - (m·t_0 + (m² - m)/2·ds)``, which is
extreme where the steps agree, ``m = (d_p - t_0)/ds`` (equation 23); the recurrence
needs an integer, so ``m = trunc((d_p - t_0)/ds) + 1`` ("the whole step is done") and
``δ = δ(m)`` (equation 24).  Guards: ``ds = 0`` (Euler is the chord, ``δ = 0``) and
``m`` is clipped to ``0..n``.  Since corrected Euler ends at ``p_b``, ``d_p - t_0 =
(n - 1)/2·ds``, so the test always lands mid-span: ``m = trunc((n - 1)/2) + 1`` and
``δ = m(n - m)/2·ds``.  The span is shaded with Gouraud when ``|δ·255·K_d| < 1``.
That bounds the *float* difference by one level; it does not promise equal truncated
levels (a difference of 0.1 level can still cross a level boundary), so it is a
heuristic, measured against the per-pixel truth in the tests and ``tables hast``.

**Highlight test** (Hammersley, after Watt, "3D Computer Graphics"), per triangle with
unit vertex normals and a constant halfway vector ``H``: a highlight is possible if
``N·H >= threshold`` at any vertex, at any point of an edge, or if ``N·H`` has a
maximum inside *every* edge (the text says "for all edge": the peak is then likely
inside).  Along an edge ``a → b`` the Phong normal is ``N(s) = a + s(b - a)``,
normalized, so ``N̂·H = p/√q`` (Duff's form, Hast equation 4) with ``p = P0 + P1·s``,
``q = Q0 + Q1·s + Q2·s²``.  Setting the derivative to zero, ``2p'q - pq' = 0``, is
*linear* in ``s`` (the ``s²`` terms cancel)::

    s* = (P0·Q1 - 2·P1·Q0) / (P1·Q1 - 2·P0·Q2)

the one stationary point of ``p/√q`` on the half great circle the edge lies on.  The
edge maximum is ``max(f(0), f(1), f(s*))`` with ``s*`` counted only inside ``(0, 1)``
and only if it is a maximum (``f(s*)`` above both ends); that closed form is "any
point on an edge".  :func:`highlight_test` also gives the exact answer for comparison:
``N̂·H`` over the whole triangle peaks at 1 if ``H`` lies in the cone of the three
vertex normals, else on an edge.

**Specular through the Euler unit** (Hast §6.1): corrected Euler runs on ``N·H``
exactly as on ``N·L`` (the span setup with ``H`` in place of ``L``, one more unit per
span), and the unit's output is clamped at 0 and raised to the shininess ``n``:
``(max(0, e))^n``; the power is the shininess block's job, as after the Phong
``N̂·H``.  The error of ``e`` is multiplied by ``n·e^(n-1)`` near the highlight.
"""

import numpy as np

__all__ = ["adaptive_test", "edge_maximum", "highlight_test", "specular_euler", "levels"]


def levels(value, kd=1.0):
    """Hast's 8-bit level of an intensity: ``trunc(255·K_d·I)`` with ``I`` clamped to
    ``0..1`` (light behind the surface is black)."""
    return np.floor(255 * kd * np.clip(value, 0.0, 1.0)).astype(np.int64)


def adaptive_test(setups, kd=1.0):
    """Hast's equations 23–24 on spans from :func:`~phongfx.golden.euler_setup.span_setups`.

    Returns a dict of ``(S,)`` arrays: ``step`` (the integer ``m``), ``delta`` (``δ``)
    and ``gouraud`` (``|δ·255·K_d| < 1``: Gouraud will do).
    """
    if not np.isfinite(kd) or kd < 0:
        raise ValueError(f"kd must be a finite number >= 0, not {kd!r}")
    n = np.asarray(setups["n"], dtype=np.int64)
    nf = np.maximum(n, 1).astype(np.float64)
    t0, ds = np.asarray(setups["t0"], np.float64), np.asarray(setups["ds"], np.float64)
    dp = np.where(n > 0, (setups["p_b"] - setups["p_a"]) / nf, 0.0)
    flat = ds == 0
    ratio = np.divide(dp - t0, ds, out=np.zeros_like(ds), where=~flat)
    m = np.trunc(np.clip(ratio, -1.0, n)) + 1  # clip first: a tiny ds may give inf
    m = np.where(flat, 0.0, np.clip(m, 0, n))
    delta = m * dp - (m * t0 + (m * m - m) / 2 * ds)
    return {"step": m.astype(np.int64), "delta": delta, "gouraud": np.abs(delta * 255 * kd) < 1}


def edge_maximum(a, b, h):
    """Largest ``N̂·H`` on the edges ``a → b`` (``(E, 3)`` unit normals, ``h`` ``(3,)``),
    with the normals interpolated and normalized along the edge (module docstring).

    Returns a dict of ``(E,)`` arrays: ``s`` (the stationary point, ``nan`` if none),
    ``interior`` (``s`` in ``(0, 1)`` is a maximum above both ends) and ``value`` (the
    largest ``N̂·H`` on the closed edge).
    """
    a, b = np.atleast_2d(np.asarray(a, np.float64)), np.atleast_2d(np.asarray(b, np.float64))
    h = np.asarray(h, np.float64)
    d = b - a
    p0, p1 = a @ h, d @ h
    q0, q1, q2 = np.sum(a * a, -1), 2 * np.sum(a * d, -1), np.sum(d * d, -1)
    num, den = p0 * q1 - 2 * p1 * q0, p1 * q1 - 2 * p0 * q2
    s = np.divide(num, den, out=np.full_like(num, np.nan), where=den != 0)
    inside = (s > 0) & (s < 1)
    sc = np.where(inside, s, 0.0)
    q = q0 + q1 * sc + q2 * sc * sc
    f = np.divide(p0 + p1 * sc, np.sqrt(q), out=np.full_like(q, -np.inf), where=q > 0)
    fa, fb = p0 / np.sqrt(q0), (p0 + p1) / np.sqrt(q0 + q1 + q2)
    interior = inside & (f > np.maximum(fa, fb))
    return {"s": s, "interior": interior, "value": np.where(interior, f, np.maximum(fa, fb))}


def highlight_test(normals, h, threshold):
    """Hammersley's highlight test on triangles with unit vertex normals ``(T, 3, 3)``
    and unit halfway vector ``h`` (module docstring).

    Returns a dict of ``(T,)`` bool arrays: ``vertex`` (a vertex at or above
    ``threshold``), ``edge`` (some point of an edge at or above it), ``extremum``
    (``N̂·H`` peaks inside all three edges), ``highlight`` (any of the three, the test)
    and ``exact`` (the peak of ``N̂·H`` over the triangle is at or above ``threshold``).
    """
    if not -1 <= threshold <= 1:
        raise ValueError(f"threshold must be in -1..1, not {threshold!r}")
    normals = np.asarray(normals, np.float64).reshape(-1, 3, 3)
    h = np.asarray(h, np.float64)
    vertex = np.any(normals @ h >= threshold, axis=1)
    edges = [edge_maximum(normals[:, i], normals[:, (i + 1) % 3], h) for i in range(3)]
    edge = np.any([e["value"] >= threshold for e in edges], axis=0)
    extremum = np.all([e["interior"] for e in edges], axis=0)
    # H in the cone of the vertex normals: H = Σ w_i·n_i with every w_i >= 0
    det = np.linalg.det(normals)
    safe = np.abs(det) > 1e-12
    w = np.zeros((len(normals), 3))
    if safe.any():
        columns = np.swapaxes(normals[safe], 1, 2)
        w[safe] = np.linalg.solve(columns, np.broadcast_to(h[:, None], (safe.sum(), 3, 1)))[..., 0]
    cone = safe & np.all(w >= 0, axis=1)
    return {"vertex": vertex, "edge": edge, "extremum": extremum,
            "highlight": vertex | edge | extremum, "exact": vertex | edge | cone}


def specular_euler(setups_h, span, x, shininess):
    """Specular ``(N·H)^n`` of pixels through corrected Euler (Hast §6.1, module
    docstring): ``setups_h`` from :func:`~phongfx.golden.euler_setup.span_setups` with
    ``H`` as the light; ``span``, ``x`` the pixels' span index and step.  Returns the
    pair ``(euler, phong)`` of ``(P,)`` float arrays, the latter Duff's exact ``p/√q``
    raised likewise."""
    if isinstance(shininess, bool) or not isinstance(shininess, (int, float)) or shininess < 1:
        raise ValueError(f"shininess must be a number >= 1, not {shininess!r}")
    from .euler_setup import curves_at
    curves = curves_at(setups_h, span, x)
    return tuple(np.clip(curves[key], 0.0, 1.0) ** shininess for key in ("corrected", "phong"))
