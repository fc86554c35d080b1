"""Per-pixel input streams of the stateful shading units for a rasterized frame.

A frame's :class:`~phongfx.scene.mesh.Spans` lists each scanline run of a triangle with its
unit end normals ``N_a`` (first pixel) and ``N_b`` (last pixel).  The scanline units
take one setup per span, loaded with ``init`` on the span's first pixel, then step
once per pixel; the host computes the setup (Hast, Barrera & Bengtsson §2–3; Szirmay-
Kalos et al. 2000 §3.2, §4).  The functions here lay those loads out in the Spans
pixel order (spans in row order, pixels left to right): ``init`` and the loads on each
span's first pixel, zeros elsewhere (the units ignore them; zeros keep the stream
free of junk so that a frame is reproducible).  The per-span setup math is that of
:mod:`phongfx.golden.euler_setup` and :mod:`phongfx.golden.spherical_setup`, called
once per span.

Schlick's unit (Schlick 1994) is stateless: it takes per pixel ``t = max(N·H, 0)``
with ``N`` the interpolated normal renormalized (Phong's own per-pixel work), so its
stream is that of an exact Phong shader fed to the rational specular term.

The Blinn–Phong and conventional Phong units are stateless too: they take the
interpolated normal as it is (they normalize it) and unit ``L`` and ``H`` or ``V``.

Lights are directional and the viewer at infinity (``V = (0, 0, 1)``), so the halfway
vector ``H = normalize(L + V)`` is one per frame (Blinn's form, which Schlick and
Szirmay-Kalos both use).
"""

import numpy as np

from phongfx.config import (BlinnConfig, ConventionalConfig, EulerConfig, GouraudConfig, SchlickConfig,
                            SphericalConfig)
from phongfx.core.methods import METHODS
from phongfx.core.registry import get_block
from phongfx.golden import euler_setup, spherical_setup
from phongfx.golden.fixed import Fixed

__all__ = ["VIEWER", "halfway", "first_pixels", "euler_inputs", "gouraud_inputs",
           "spherical_inputs", "schlick_inputs", "blinn_inputs", "blinn_codes", "conventional_inputs",
           "conventional_codes", "units", "check_unit", "inputs", "decode"]

#: Viewer direction in eye space (orthographic view along -z, viewer at infinity).
VIEWER = np.array([0.0, 0.0, 1.0])



def _check_n(n, config):
    if not isinstance(n, (int, np.integer)) or isinstance(n, bool) or not 1 <= n <= config.n_max:
        raise ValueError(f"n must be an integer in 1..{config.n_max}, not {n!r}")
    return int(n)


def _unit(name, vector):
    v = np.asarray(vector, dtype=np.float64)
    if v.shape != (3,) or not np.all(np.isfinite(v)) or np.linalg.norm(v) == 0:
        raise ValueError(f"{name} must be a finite nonzero 3-vector, not {vector!r}")
    return v / np.linalg.norm(v)


def halfway(light):
    """Blinn's halfway vector ``H = normalize(L + V)`` for the directional ``light``."""
    light = _unit("light", light)
    h = light + VIEWER
    if np.linalg.norm(h) < 1e-12:
        raise ValueError(f"light must not point straight away from the viewer, not {light.tolist()}")
    return h / np.linalg.norm(h)


def first_pixels(spans):
    """Index of each span's first pixel in the pixel order, and the pixel count ``P``."""
    length = np.asarray(spans.length, dtype=np.int64)
    if not len(length):
        raise ValueError("spans must hold at least one span, not 0")
    if np.any(length < 1):
        raise ValueError(f"span lengths must be positive integers, not {int(length.min())}")
    first = np.concatenate([[0], np.cumsum(length)[:-1]]).astype(np.int64)
    return first, int(length.sum())


def _stream(spans, loads):
    """``{port: (P,) or (P, lanes) int64}``: ``init`` and per-span ``loads`` (``(S,)`` or
    ``(S, 3)``) at each span's first pixel, zeros elsewhere."""
    first, count = first_pixels(spans)
    out = {"init": np.zeros(count, dtype=np.int64)}
    out["init"][first] = 1
    for name, values in loads.items():
        values = np.asarray(values, dtype=np.int64).reshape(len(first), -1)
        column = np.zeros((count, values.shape[1]), dtype=np.int64)
        column[first] = values
        out[name] = column if values.shape[1] > 1 else column[:, 0]
    return out


def _per_span(spans, setup):
    """``setup(na, nb, length)`` -> dict of raw ints, for every span, as arrays."""
    rows = [setup(a, b, int(n)) for a, b, n in zip(spans.na, spans.nb, spans.length)]
    names = rows[0].keys() if rows else ()
    return {name: np.array([row[name] for row in rows], dtype=np.int64) for name in names}


def euler_inputs(spans, light, config=EulerConfig(), compensate=False, *, n=None):
    """Raw inputs of the corrected Euler unit (Hast et al. equations 16–17) for a frame.

    Per span the float setup :func:`~phongfx.golden.euler_setup.span_setup` of the
    diffuse ``N·L`` curve, quantized by :func:`~phongfx.golden.euler_setup.quantize_setup`
    (``compensate`` as there).  Returns ``{init, p0, t0, ds}`` int64 arrays of ``P`` pixels.
    ``n`` is not used: the unit interpolates ``N·L``, no power (every unit's stream is asked
    for with its shininess).
    """
    light = _unit("light", light)
    loads = _per_span(spans, lambda a, b, n: euler_setup.quantize_setup(
        config, euler_setup.span_setup(a, b, light, n), compensate))
    return _stream(spans, loads)


def gouraud_inputs(spans, light, config=GouraudConfig(), *, n=None):
    """Raw inputs of the Gouraud unit: the chord from ``p_a = N_a·L`` to ``p_b = N_b·L``
    (:func:`~phongfx.golden.euler_setup.quantize_gouraud`).  ``{init, p0, dp}``; ``n`` not
    used, as for :func:`euler_inputs`."""
    light = _unit("light", light)
    loads = _per_span(spans, lambda a, b, n: euler_setup.quantize_gouraud(
        config, euler_setup.span_setup(a, b, light, n)))
    return _stream(spans, loads)


def _spherical_loads(config, spans, light, h, n, intensity, colour):
    """Raw loads of every span: specular ``cos^n`` of ``N·H`` as ``C·cos²(aθ)`` (Szirmay-Kalos
    equations 17–19; ``C = 0`` on a dark span, see
    :func:`~phongfx.golden.spherical_setup.span_setups`), diffuse ``N·L`` as
    ``A·cos(tγ - φ)`` (equation 17, ``a = 1``).

    The diffuse channel reads the ``cos`` ROM, so its angle is equation 17's own
    ``tγ - φ``: ``a = 1``, not ``a(1)`` (which fits ``cos²`` to ``cos``).
    """
    count = len(spans.length)
    ends = (spans.na, spans.nb)
    spec = spherical_setup.quantize_setup(config, spherical_setup.span_setups(
        *ends, np.broadcast_to(h, (count, 3)), np.broadcast_to(h, (count, 3)), n, spans.length,
        intensity))
    setup = spherical_setup.span_setups(*ends, np.broadcast_to(light, (count, 3)),
                                        np.broadcast_to(light, (count, 3)), 1, spans.length)
    slope = np.where(spans.length > 1, setup["gamma"] / np.maximum(spans.length - 1, 1), 0.0)
    diff = spherical_setup.quantize_setup(config, {**setup, "s": slope, "b": -setup["phi"]})
    cd = Fixed.from_float(intensity * setup["A"][:, None] * colour, config.c, "round_half_up",
                          "saturate").raw
    return {"b": spec["b"], "s": spec["s"], "c": spec["c"], "bd": diff["b"], "sd": diff["s"], "cd": cd}


def spherical_inputs(spans, light, n, config=SphericalConfig(), intensity=1.0, colour=(1.0, 1.0, 1.0)):
    """Raw inputs of the spherical interpolation unit (Szirmay-Kalos et al. Figure 12).

    Specular: ``u = N`` from ``N_a`` to ``N_b``, ``v = H`` constant, shininess ``n``,
    ``C = intensity·A^n``.  Diffuse: ``v = L``, ``C_rgb = intensity·colour·A``.
    Returns ``{init, b, s, c, bd, sd, cd}`` (``cd`` of shape ``(P, 3)``).
    """
    if not isinstance(n, (int, float)) or isinstance(n, bool) or not n > 0:
        raise ValueError(f"n must be a positive number, not {n!r}")
    light = _unit("light", light)
    h, colour = halfway(light), np.asarray(colour, dtype=np.float64)
    if colour.shape != (3,) or np.any(colour < 0):
        raise ValueError(f"colour must be 3 non-negative numbers, not {colour.tolist()!r}")
    first_pixels(spans)  # refuses an empty frame before any setup
    return _stream(spans, _spherical_loads(config, spans, light, h, n, intensity, colour))


def schlick_inputs(spans, light, n, config=SchlickConfig()):
    """Raw inputs of Schlick's unit: per pixel ``t = max(N·H, 0)``, ``N`` the interpolated
    normal renormalized, rounded half up to ``config.t`` (saturated at 1), and ``n``.
    Returns ``{t, n}``."""
    _check_n(n, config)
    first_pixels(spans)  # refuses an empty frame, as the stateful units do
    h = halfway(light)
    normals = spans.interpolated_normals()
    t = normals @ h / np.maximum(np.linalg.norm(normals, axis=-1), 1e-300)
    raw = Fixed.from_float(np.clip(t, 0.0, 1.0), config.t, "round_half_up", "saturate").raw
    return {"t": raw.astype(np.int64), "n": np.full(len(raw), int(n), dtype=np.int64)}


def blinn_inputs(spans, light, n, config=BlinnConfig()):
    """Raw inputs of the Blinn–Phong baseline: per pixel the interpolated normal
    ``N`` as it is (the unit normalizes it), unit ``L`` and ``H``, all rounded half up to
    ``config.vec`` (saturated: a component of exactly 1 is the largest code), and ``n``.
    Returns ``{normal, light, half, n}``."""
    _check_n(n, config)
    _, count = first_pixels(spans)
    light = np.broadcast_to(_unit("light", light), (count, 3))
    return blinn_codes(spans.interpolated_normals(), light, np.broadcast_to(halfway(light[0]), (count, 3)),
                              np.full(count, int(n), dtype=np.int64), config)


def blinn_codes(normals, lights, halves, n, config=BlinnConfig()):
    """:func:`blinn_inputs` from per-pixel (P, 3) ``normals`` (as interpolated),
    unit ``lights`` and ``halves`` (a local light or viewer: one of each per pixel) and
    integer ``n`` (P,)."""
    return _codes(config, n, normal=normals, light=lights, half=halves)


def conventional_inputs(spans, light, n, config=ConventionalConfig()):
    """Raw inputs of the conventional Phong unit: per pixel the interpolated normal ``N`` as
    it is (the unit normalizes it), the unit ``L`` and the viewer ``V`` (:data:`VIEWER`), all
    rounded half up to ``config.vec`` (saturated), and ``n``.  Returns ``{normal, light,
    view, n}``."""
    _check_n(n, config)
    _, count = first_pixels(spans)
    light = np.broadcast_to(_unit("light", light), (count, 3))
    return conventional_codes(spans.interpolated_normals(), light, np.broadcast_to(VIEWER, (count, 3)),
                              np.full(count, int(n), dtype=np.int64), config)


def conventional_codes(normals, lights, views, n, config=ConventionalConfig()):
    """:func:`conventional_inputs` from per-pixel (P, 3) ``normals`` (as interpolated),
    ``lights`` and ``views`` (unit, or un-normalized where the config's ``local_light`` /
    ``local_viewer`` has the unit normalize them) and integer ``n`` (P,)."""
    return _codes(config, n, normal=normals, light=lights, view=views)


def _codes(config, n, **vectors):
    """``{port: raw codes}`` of float (P, 3) ``vectors`` in ``config.vec`` (rounded half up,
    saturated), then ``n``."""
    out = {name: Fixed.from_float(v, config.vec, "round_half_up", "saturate").raw.astype(np.int64)
           for name, v in vectors.items()}
    return {**out, "n": np.asarray(n, dtype=np.int64)}


def units():
    """The names of the units with a stream built here: the methods with an ``inputs`` face,
    as the registry has them now (a method registered at run time too)."""
    return tuple(name for name, method in METHODS.items() if method.has("inputs"))


def check_unit(unit):
    """The :class:`~phongfx.core.methods.Method` of ``unit``; ValueError unless it is one of
    :func:`units`."""
    names = units()
    if unit not in names:
        raise ValueError(f"unit must be one of {', '.join(names)}, not {unit!r}")
    return METHODS[unit]


def inputs(unit, spans, light, *, n=32, config=None):
    """The stream of ``unit`` (one of :func:`units`) with
    its block's default config, shininess ``n``."""
    method = check_unit(unit)
    return method.load("inputs")(spans, light, n=n, config=config or get_block(method.block).config)


def decode(outputs, config, part="spec"):
    """Float per-pixel intensity of ``part`` (``"spec"`` or ``"diff"``) from a unit's raw
    ``outputs``: the port its config's :attr:`~phongfx.config.base.BlockConfig.SHADES` names
    for it (``(P, 3)`` for the spherical unit's coloured diffuse); a signed cosine (Euler,
    Gouraud) clamped to 0, as the shading formula clamps it."""
    port = config.SHADES.get(part)
    if port is None:
        raise ValueError(f"part must be one of {', '.join(config.SHADES)}, not {part!r}")
    fmt = config.outputs[port][0]
    value = np.asarray(outputs[port]) * fmt.lsb
    return np.maximum(value, 0.0) if fmt.signed else value
