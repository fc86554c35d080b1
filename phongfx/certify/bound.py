"""A sound bound on a compiled design's error over a scene's domain: the ``"interval"`` method.

``B = rounding + approximation + 1/2`` at the shader's ``r``, ``g``, ``b`` outputs, in display
levels (:mod:`.outputs`): the hardware against the same datapath without its quantizes
(intervals through the golden blocks, :mod:`.datapath`), that ideal against the reference
(:mod:`.approximation`), and the output's own rounding.  Both are bounded on boxes of the
normals the domain presents (:mod:`.sphere`), one set per admissible ``n``; branch and bound
halves the boxes whose bound is within ``tolerance`` of the largest, round after round, until
the largest stops falling (or the time or box budget is spent).  Every box's bound holds for
every point in it, and the boxes cover the domain, so the largest bound over the boxes at any
round is sound; splitting only makes it tighter.

Covered: Lyon's Figure 7 and 8 datapaths (``fig7``, ``fig8``) and the halfway unit of Figure 5
(``halfway``, its ``g2proj`` and ``d3`` variants) with lights and viewer at infinity.  Point
lights and a local viewer (whose L and V normalizers add their own ``s_L``, ``s_V`` over the
cones the domain's ball gives) and the other units are not bounded yet: the certificate says so.
"""

import time

import numpy as np

from phongfx.explore.compile import run as runs
from phongfx.explore.compile.analysis import analyse
from phongfx.scene.geometry import frames

from .certificate import Certificate, meets
from .outputs import box_errors
from .sphere import Boxes, cover, frame

__all__ = ["BOUNDED", "certify", "shader_config", "bound_boxes"]

#: The methods :func:`certify` bounds (others get a certificate without a bound).
BOUNDED = ("fig7", "fig8", "halfway")


def shader_config(method, params, spec, analysis=None):
    """The compiler's ShaderConfig of ``method`` at ``params`` for the scene ``spec``."""
    if analysis is None:
        analysis = analyse(spec, frames(spec))
    return runs.build(method, params, analysis)


def _not_bounded(domain):
    """Why the domain is outside what the interval method covers (None when it is inside)."""
    if any(kind != "directional" for kind, _, _ in domain.lights):
        return "point lights are not bounded yet"
    if domain.camera[0] != "infinity":
        return "a local viewer is not bounded yet"
    if not any(values for _, values in domain.materials):
        return "the domain admits no shininess n"
    vectors = [vector for _, vector, _ in domain.lights] + [domain.camera[1]]
    if any(abs(float(np.linalg.norm(v)) - 1.0) > 1e-9 for v in vectors):
        return "the light and camera directions must be unit vectors, as the bound's geometry takes them"
    return None


def bound_boxes(shader, against, domain, *, tolerance=0.02, max_boxes=300_000, seconds=60.0, batch=2048,
                max_batch=65536, enough=None):
    """Branch and bound (module docstring): ``(bound, parts)``, ``bound`` inf when some box
    cannot be bounded (``parts["faults"]`` then names the quantizes that may overflow).

    Each round halves the boxes within ``tolerance`` of the largest bound (at least the
    ``batch`` largest, at most ``max_batch``); it stops when the largest has fallen by under
    0.2 % over four rounds that split every box near it, or once ``max_boxes`` boxes have been
    bounded (the budget that makes the result the same on every machine), or at ``seconds``, or
    as soon as the largest is below ``enough`` (a width search needs no tighter bound)."""
    basis = frame(domain.camera[1])
    lights = [np.asarray(vector, dtype=np.float64) for _, vector, _ in domain.lights]
    cases = [(n, m) for m, (_, values) in enumerate(domain.materials) for n in values]
    start, faults, history = time.perf_counter(), set(), []

    def evaluate(boxes):
        rounding, approximation, found, gate = box_errors(shader, against, boxes, basis, lights,
                                                          domain.min_normal_length)
        faults.update(found)
        total = np.max(rounding + approximation, axis=-1) + 0.5
        return boxes, np.nan_to_num(total, nan=np.inf), rounding, approximation, gate

    pool = evaluate(cover(domain.view_cos_min, domain.min_normal_length, cases))
    evaluated = len(pool[0])
    while True:
        boxes, total = pool[0], pool[1]
        top = float(total.max())
        near = total >= top - tolerance
        whole = np.count_nonzero(near) <= max_batch
        history.append((top, whole))
        settled = (len(history) > 4 and all(w for _, w in history[-4:])
                   and history[-5][0] - top <= 0.002 * max(top, 1.0))
        met = enough is not None and top < enough
        if met or settled or time.perf_counter() - start > seconds or evaluated > max_boxes:
            break
        count = min(max(np.count_nonzero(near), batch), max_batch, len(total))
        pick = np.zeros(len(total), dtype=bool)
        pick[np.argpartition(-total, count - 1)[:count]] = True
        children = _inherit(evaluate(boxes.take(pick).split()), [part[pick] for part in pool[1:]])
        evaluated += len(children[0])
        rest = [boxes.take(~pick)] + [part[~pick] for part in pool[1:]]
        pool = (_concat(rest[0], children[0]),) + tuple(np.concatenate([a, b]) for a, b in zip(rest[1:], children[1:]))
    bound, parts = _worst(*pool, domain)
    parts.update(boxes=int(evaluated), rounds=len(history))
    if faults:
        parts["faults"] = sorted(faults)
    return bound, parts


def _inherit(children, parents):
    """A child keeps its parent's bound where its own is larger: the parent's holds on it too
    (interval bounds need not shrink with the box, only hold on it)."""
    boxes, total, *rest = children
    # Boxes.split puts the low halves first, then the high ones: parents twice over
    worse = total > np.concatenate([parents[0], parents[0]])
    for mine, theirs in zip([total, *rest], parents):
        both = np.concatenate([theirs, theirs])
        mine[worse] = both[worse]
    return (boxes, total, *rest)


def _concat(a, b):
    return Boxes(*(np.concatenate([getattr(a, f), getattr(b, f)]) for f in ("theta", "phi", "z", "n", "material")))


def _box(boxes, i, domain, channel=None):
    """Where box ``i`` is: its ``n``, material, channel and ranges of θ, φ (degrees) and z."""
    out = {"n": int(boxes.n[i]), "material": domain.materials[int(boxes.material[i])][0]}
    if channel is not None:
        out["channel"] = "rgb"[channel]
    out.update(theta_deg=[round(float(np.degrees(x)), 4) for x in boxes.theta[i]],
               phi_deg=[round(float(np.degrees(x)), 4) for x in boxes.phi[i]],
               z=[round(float(x), 6) for x in boxes.z[i]])
    return out


def _worst(boxes, total, rounding, approximation, gate, domain):
    """``(bound, parts)``: the box with the largest total, its parts (they sum to the bound), and
    the largest of each part alone with its box."""
    i = int(np.argmax(total))
    c = int(np.argmax(rounding[i] + approximation[i]))
    parts = {"rounding": float(rounding[i, c]), "approximation": float(approximation[i, c]), "output": 0.5,
             "where": _box(boxes, i, domain, c)}
    if gate[i] > 0:
        parts["backside"] = float(gate[i])
    for name, part in (("rounding", rounding), ("approximation", approximation)):
        j = int(np.argmax(part.max(axis=-1)))
        parts[f"largest_{name}"] = {"levels": float(part[j].max()), "where": _box(boxes, j, domain)}
    return float(total[i]), parts


def certify(method, params, spec, domain, *, shader=None, analysis=None, max_boxes=300_000, early=False):
    """A :class:`~phongfx.certify.certificate.Certificate` for ``method`` at ``params`` (the
    compiler's, :func:`shader_config`) on the scene ``spec`` over ``domain``
    (:class:`phongfx.scene.domain.Domain`); ``shader``: the ShaderConfig when already built;
    ``max_boxes``: the branch and bound's budget (:func:`bound_boxes`); ``early``: stop refining
    as soon as the bound meets the requirement (for a width search, which asks only that)."""
    start = time.perf_counter()

    def done(certified, bound, parts=None, why=""):
        return Certificate(certified, bound, "interval", parts or {}, why, time.perf_counter() - start)

    if method not in BOUNDED:
        return done(False, None, why=f"no bounding method for the {method} unit yet")
    why = _not_bounded(domain)
    if why:
        return done(False, None, why=why)
    if shader is None:
        shader = shader_config(method, params, spec, analysis)
    halfway = shader.units[0].halfway
    if method == "halfway" and halfway.variant not in ("g2proj", "d3"):
        return done(False, None, why=f"the halfway unit's {halfway.variant} variant is not bounded yet")
    against = spec.requirement.against
    need = spec.requirement.max_error_levels
    # floor(B + 1/2) <= need exactly when B < floor(need) + 1/2
    bound, parts = bound_boxes(shader, against, domain, max_boxes=max_boxes,
                               enough=np.floor(need) + 0.5 if early else None)
    if not np.isfinite(bound):
        faults = ", ".join(parts.get("faults", [])) or "a quantize"
        return done(False, None, parts, f"{faults} may overflow or wrap somewhere in the domain")
    ok = meets(bound, need)
    why = "" if ok else (f"the bound {bound:.3f} levels rounds to {int(np.floor(bound + 0.5))}, over the "
                         f"required {need:g}")
    if not ok and "backside" in parts:
        why += (f"; at its largest the hardware's backside test may differ from the reference's: its "
                f"N·L error bound {parts['backside']:.4f} is wider than the terminator band "
                f"1/{(1 << spec.output.bits) - 1}")
    return done(ok, bound, parts, why)
