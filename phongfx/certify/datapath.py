"""Lyon's datapaths run on :class:`~phongfx.certify.interval.Interval` values, box by box.

The golden blocks (:mod:`phongfx.golden`: normalize, reflect, difference, halfway, diffuse) run
unchanged on intervals; these steps are written here instead:

* **The inputs and the LIRP** (Figure 7a).  The host encodes the span-end unit normals ``n0``,
  ``n1`` and ``a`` (:func:`phongfx.sim.stimulus.datapath.encode`: rounded to nearest, each
  within ``e_n``, ``e_a`` of the float), and the LIRP computes ``(1-a_c)·n0_c + a_c·n1_c``
  exactly before its one rounding.  Against the exact ``N' = (1-a)·n0 + a·n1`` that differs by
  ``(1-a_c)(n0_c - n0) + a_c(n1_c - n1) + (a_c - a)(n1 - n0)``: at most
  ``e_n + e_a·|n1 - n0|`` per component, ``|n1 - n0| <= 2·sin(θ/2)`` for span ends up to the
  domain's ``θ`` apart (``= 2·√(1 - min_normal_length²)``), plus the LIRP's rounding.  (The
  interval rule for products would count ``e_n`` twice, once per end.)  ``L`` and ``V`` at
  infinity are constants: their codes, each within its own exact distance of the float; a point
  light's or local viewer's go through their own LIRP and normalizer (:func:`interpolated`,
  the bounds of :mod:`.cones`).
* **The shape function** (Figure 7d, :func:`phongfx.golden.shape.shape`), whose comparator
  ``v = x/2^k >= 1`` drives a multiplexer to 0 and whose "1-" block takes ``v``'s fraction
  (a wrap that only the masked case uses).  Where the hardware's ``v < 1`` the fraction is ``v``
  itself; so ``1 - u`` and the ``k`` squarings run on ``v`` restricted to ``[lo, 1)``, and the
  multiplexer's error is bounded by continuity: ``f_k(v) = (1 - v)^(2^k)`` is 0 at ``v = 1``,
  so where hardware and ideal fall on opposite sides (``|v_hw - v| <= e_v``) the side that
  gives 0 is within ``e_v^(2^k)`` of the other's formula, and where both are past 1 both give 0.
* **The root-shininess unit** (Figure 8, :func:`phongfx.golden.root.root`), whose augmented
  comparator (``any(u_i >= 1)``, a reduction over the lanes) zeroes the output, and whose
  squarers see only the fractions of ``u_i = m|D_i|/2^s``: as for the shape function, where the
  hardware's ``u_i`` are all below 1 the fractions are the ``u_i``, and where one reaches 1 the
  ideal's ``x/2^k >= (1 - e_u)^2``, whose ``f_k`` is at most ``(2e_u)^(2^k)``.  Its ideal is
  Figure 7's with ``n = m²`` (the comparator only zeroes where ``f_k`` is 0 already).
* **Reflect and difference with a point light or a local viewer** (:mod:`.cones`): ``L`` and
  ``V`` then range over cones, and interval arithmetic would let ``R`` and ``D·D`` wander far
  past what the geometry allows (and saturate there).  Their hardware ranges are cut to the
  ideal's geometric range widened by their deviation (:meth:`~.interval.Interval.within`) before the golden
  blocks' saturating quantizes, which are otherwise the golden ones; Figure 7's shape function
  runs per piece of the ideal ``|D|`` (:func:`_pieces`).  With lights and viewer at infinity
  the golden blocks run unchanged.
"""

import functools

import numpy as np

from phongfx.core.format import Format
from phongfx.golden.diffuse import diffuse
from phongfx.golden.difference import difference
from phongfx.golden.fixed import Fixed
from phongfx.golden.halfway import halfway
from phongfx.golden.normalize import normalize
from phongfx.golden.reflect import reflect
from phongfx.golden.shininess import shininess_input

from .approximation import PIECES, scale_range
from .cones import at_infinity
from .interval import Interval, rounding_error
from .sphere import cover, frame, product, projection

__all__ = ["SUB_CONES", "fig7_specular", "fig8_specular", "halfway_specular", "encoding_error", "lirp_error", "front", "interpolated", "constant", "shape", "magnitude", "root", "unit_terms"]

#: sub-cones of a local L or V (:func:`interpolated`): cuts in the angle from the axis and about it
SUB_CONES = (4, 16)


def encoding_error(fmt):
    """Largest distance from a float in [-1, 1] to its code in ``fmt`` (rounded to nearest,
    saturated, as :func:`phongfx.sim.stimulus.codes` encodes)."""
    top, low = fmt.max_raw * fmt.lsb, fmt.min_raw * fmt.lsb
    return max(fmt.lsb / 2, 1.0 - top, (low + 1.0) if low > -1 else 0.0)


def lirp_error(lirp, chord):
    """Bound on each component of the LIRP's output from the exact ``(1-a)·x0 + a·x1`` of unit
    span ends up to ``chord`` apart (module docstring)."""
    vec, a, out = lirp.fmt("vec"), lirp.fmt("a"), lirp.fmt("out")
    return (encoding_error(vec) + (a.lsb / 2) * chord + rounding_error(vec.mul(a), out, lirp.rounding)) * (1 + 1e-12)


def front(config, boxes, basis, min_normal_length):
    """The LIRP's output ``N'`` (B, 3) as an Interval over ``boxes`` (module docstring)."""
    out = config.lirp.fmt("out")
    chord = 2.0 * np.sqrt(max(0.0, 1.0 - min(1.0, min_normal_length) ** 2))
    e = lirp_error(config.lirp, chord)
    root = (np.sqrt(np.clip(boxes.z[:, 0], 0, 1)), np.sqrt(np.clip(boxes.z[:, 1], 0, 1)))
    lo, hi = [], []
    for axis in np.eye(3):
        part = product(root, projection(boxes, basis, axis))
        lo.append(part[0])
        hi.append(part[1])
    lo, hi = np.stack(lo, -1) - e, np.stack(hi, -1) + e
    # one shared symbol per component: the normalizer sees where an error points
    terms = np.broadcast_to(e * np.eye(3), lo.shape + (3,))
    return Interval(np.clip(lo, -1.0, 1.0), np.clip(hi, -1.0, 1.0), 0.0, out, terms=terms)


def interpolated(config, direction, count):
    """The hardware's normalized L (or V) toward a local :class:`~.cones.Direction` as an
    Interval (count, 3) whose deviation is from the ideal's ``s·unit(L')`` (the exact LIRP
    output normalized by the ideal normalizer; the sub-cones and bounds of :mod:`.cones`);
    ``config`` the datapath's (its ``lirp`` and ``direction_normalize``)."""
    lo, hi, err, faults = _interpolated(config.lirp, config.direction_normalize, direction)
    wide = (count, 3)
    return Interval(np.broadcast_to(lo, wide), np.broadcast_to(hi, wide), np.broadcast_to(err, wide),
                    config.direction_normalize.fmt("out"), faults)


@functools.lru_cache(maxsize=64)
def _interpolated(lirp, normalizer, direction):
    """``(lo, hi, err, faults)`` of :func:`interpolated`, each component over the sub-cones."""
    e = lirp_error(lirp, direction.chord)
    shortest = np.sqrt(max(0.0, 1.0 - direction.chord ** 2 / 4))
    cones = cover(np.cos(direction.half), 1.0, [(0, 0)], *SUB_CONES)
    basis, length = frame(direction.axis), (np.full(len(cones), shortest), np.ones(len(cones)))
    parts = [product(length, projection(cones, basis, axis)) for axis in np.eye(3)]
    lo = np.stack([part[0] for part in parts], -1) - e
    hi = np.stack([part[1] for part in parts], -1) + e
    terms = np.broadcast_to(e * np.eye(3), lo.shape + (3,))
    entry = Interval(np.clip(lo, -1.0, 1.0), np.clip(hi, -1.0, 1.0), 0.0, lirp.fmt("out"), terms=terms)
    unit = normalize(normalizer, entry)["n"]
    return unit.lo.min(axis=0), unit.hi.max(axis=0), float(np.max(unit.dev)) * (1 + 1e-12), unit.faults


def constant(vector, fmt, count):
    """A constant direction (a light or viewer at infinity) as the host encodes it, (count, 3)."""
    vector = np.asarray(vector, dtype=np.float64)
    code = Fixed.from_float(vector, fmt, rounding="round_half_up", overflow="saturate").to_float()
    wide = np.broadcast_to(code, (count, 3))
    return Interval(wide, wide, np.broadcast_to(np.abs(code - vector), (count, 3)), fmt)


def shape(config, x2):
    """Figure 7d on an Interval ``x2`` (module docstring): the ``spec`` Interval."""
    big = 2 ** config.k
    v = x2 >> (config.k + 1)
    frac = Format(0, v.fmt.frac_bits)
    top = frac.max_raw * frac.lsb
    used = v.lo < 1  # the hardware reaches the squarers for some point of the box
    u = Interval(np.clip(v.lo, 0.0, top), np.clip(np.minimum(v.hi, top), 0.0, top), v.err, frac, v.faults, v.terms)
    t = (Interval.exact(1.0, "1.0") - u).quantize(config.t, config.rounding, "error", op="shape 1-u")
    for _ in range(config.k):
        t = (t * t).quantize(config.t, config.rounding, "error", op="shape t²")
    e_v = v.dev
    near = np.maximum(0.0, np.minimum(v.hi, 1.0) + e_v - 1.0) ** big  # hardware < 1, ideal past 1
    past = np.maximum(0.0, 1.0 + e_v - np.maximum(v.lo, 1.0)) ** big  # hardware >= 1, ideal below
    masked = v.hi >= 1
    err = np.maximum(np.where(used, t.dev + near, 0.0), np.where(masked, past, 0.0))
    lo = np.where(used & ~masked, t.lo, 0.0)
    hi = np.where(used, t.hi, 0.0)
    # hardware and ideal both lie in [0, 1] (a shape function's value): never further apart
    err = np.minimum(err * (1 + 1e-12), np.maximum(hi, 1.0))
    return Interval(lo, hi, err, config.t, t.faults if np.any(used) else v.faults)


def magnitude(x):
    """``|x|`` of an Interval: 1-Lipschitz, so its deviation stays (its terms where the sign is
    known, as a remainder where the range holds 0)."""
    pos, neg = x.lo >= 0, x.hi <= 0
    lo = np.where(pos, x.lo, np.where(neg, -x.hi, 0.0))
    hi = np.maximum(np.abs(x.lo), np.abs(x.hi))
    err = np.where(pos | neg, x.err, x.dev)
    terms = None
    if x.terms is not None:
        sign = np.where(pos, 1.0, np.where(neg, -1.0, 0.0))
        terms = x.terms * sign[..., None]
    return Interval(lo, hi, err, x.fmt.neg(), x.faults, terms)


def root(config, r, l, m):
    """Figure 8 on Intervals (module docstring): the ``spec`` Interval; ``m`` the shininess
    codes (a Fixed per box)."""
    d = (r - l).quantize(config.d, config.rounding, "saturate", op="root D")
    mag = magnitude(d).quantize(Format(d.fmt.int_bits, d.fmt.frac_bits), config.rounding, "saturate",
                                op="root |D|")
    u = (mag * m[:, None]) >> config.shift
    frac = Format.parse(config.frac)
    top = 1.0 - 2.0 ** -u.fmt.frac_bits
    small = np.all(u.lo < 1, axis=-1)  # the hardware may pass every lane to the squarers
    big = np.any(u.hi >= 1, axis=-1)   # ... or zero the output
    kept = Interval(np.minimum(u.lo, top), np.minimum(u.hi, top), u.err, u.fmt, u.faults, u.terms)
    x2 = kept.quantize(frac, "truncate", "wrap", op="root u")
    x2 = x2.dot(x2) << 2 * config.shift
    spec = shape(config.shape, x2)
    e_u = np.max(u.dev, axis=-1)
    past = np.minimum(1.0, 2 * e_u) ** (2 ** config.k)
    err = np.maximum(np.where(small, spec.dev, 0.0), np.where(big, past, 0.0))
    lo = np.where(small & ~big, spec.lo, 0.0)
    hi = np.where(small, spec.hi, 0.0)
    err = np.minimum(err * (1 + 1e-12), np.maximum(hi, 1.0))  # both in [0, 1], as for shape
    return Interval(lo, hi, err, config.t, spec.faults if np.any(small) else u.faults)


def _shininess(config, n):
    """The shininess port's codes for ``n`` per box (None when the hardware fixes it)."""
    if config.shininess is None:
        return None
    name, fmt, top = config.shininess
    value = np.sqrt(n) if name == "m" else n
    return Fixed(np.clip(np.round(value), 1, top).astype(np.int64), fmt)


def _reflected(config, normal, view, hints):
    """:func:`phongfx.golden.reflect.reflect`'s ``R``, cut by :meth:`~.interval.Interval.within` to the ideal's range
    ``hints["r"]`` before its saturating quantize (``hints`` None: the golden block)."""
    if hints is None:
        return reflect(config.reflect, normal, view)["r"]
    cfg = config.reflect
    dot = normal.dot(view).quantize(cfg.dot, cfg.rounding, "saturate", op="reflect N·V")
    r = (normal * (dot << 1)[:, None] - view).within(*hints["r"])
    return r.quantize(cfg.out, cfg.rounding, "saturate", op="reflect R")


def _pieces(config, r, l, n, span):
    """The shape function's ``spec`` (Figure 7c–d) from ``R`` and ``L``, taken in
    :data:`~.approximation.PIECES` pieces ``[a, b]`` of the ideal ``|D|``'s range ``span``
    (``hints["d"]``): in each, ``D·D`` lies in ``[a² - dev, b² + dev]`` (:meth:`~.interval.Interval.within`) and
    ``|D·D - D'·D'| <= |δ|(2b + |δ|)`` for ``D`` within ``|δ|`` of the ideal ``D'``, so a
    large ``D`` (a steep ``x``) and a small one (a steep shape function) are bounded apart.
    Every point of a box lies in one piece: the box's Interval is their hull and their
    largest deviation."""
    n = shininess_input(config, n, len(r))
    d = (r - l).quantize(config.d, config.rounding, "saturate", op="difference D")
    dd = d.dot(d)
    count, cut = len(dd), np.linspace(0.0, 1.0, PIECES + 1)
    a = span[0][:, None] + (span[1] - span[0])[:, None] * cut[:-1]
    b = span[0][:, None] + (span[1] - span[0])[:, None] * cut[1:]
    a[:, 0], b[:, -1] = span[0], span[1]  # the pieces share their float ends: they cover the range
    norm = np.sqrt(np.sum(d.dev ** 2, axis=-1))[:, None]
    err = np.minimum(dd.dev[:, None], norm * (2 * b + norm)) * (1 + 1e-12)
    wide = Interval(np.repeat(dd.lo, PIECES), np.repeat(dd.hi, PIECES), err.ravel(), dd.fmt, dd.faults)
    dd = wide.within((a * a).ravel(), (b * b).ravel())
    dd = dd.quantize(config.dd, config.rounding, "saturate", op="difference D·D")
    x2 = (Fixed(np.repeat(n.raw, PIECES), n.fmt) * dd).quantize(config.x2, config.rounding, "saturate",
                                                                 op="difference 2x")
    return x2, count


def _hull(x, count):
    """One Interval per box from :func:`_pieces`' ``PIECES`` per box: their hull and largest deviation."""
    lo, hi, dev = (v.reshape(count, PIECES) for v in (x.lo, x.hi, x.dev))
    return Interval(lo.min(axis=-1), hi.max(axis=-1), dev.max(axis=-1), x.fmt, x.faults)


def halfway_specular(config, normal, view, lights, shininess, hints):
    scaled = shininess.shift(config.halfway_shift) if shininess is not None else None
    out = []
    for light in lights:
        d = halfway(config.halfway, normal, light, view)
        out.append(shape(config.shape, difference(config.difference, d["p"], d["q"], scaled)["x2"]))
    return out


def fig7_specular(config, normal, view, lights, shininess, hints):
    # as phongfx.golden.datapath.fig7: R once, then per light 2x → shape
    r = _reflected(config, normal, view, hints)
    if hints is None:
        return [shape(config.shape, difference(config.difference, r, light, shininess)["x2"]) for light in lights]
    return [_hull(shape(config.shape, x2), count)
            for x2, count in (_pieces(config.difference, r, light, shininess, span)
                              for light, span in zip(lights, hints["d"]))]


def fig8_specular(config, normal, view, lights, shininess, hints):
    # as phongfx.golden.datapath.fig8: R once, then per light the root-shininess unit
    r = _reflected(config, normal, view, hints)
    m = shininess_input(config.root, shininess, len(r))
    return [root(config.root, r, light, m) for light in lights]


def unit_terms(config, specular, boxes, basis, lights, min_normal_length, cones=None):
    """``(spec, diff)``: per light the Intervals (B,) of the unit's ``spec<i>`` and ``diff<i>``
    over ``boxes`` (directional ``lights``: unit vectors; the viewer ``basis[0]``); ``cones``
    (:class:`~.cones.Directions`), when given, says which are local instead.  ``specular``:
    the specular unit's own intervals after the normalizer (:func:`fig7_specular`,
    :func:`fig8_specular`, :func:`halfway_specular`), named by its bounding method."""
    count = len(boxes)
    vec = config.normalize.fmt("out")
    cones = cones or at_infinity(basis, lights, -1.0)
    normal = normalize(config.normalize, front(config, boxes, cones.basis, min_normal_length))["n"]

    def hardware(direction):
        if direction.local:
            return interpolated(config, direction, count)
        return constant(direction.axis, vec, count)

    view = hardware(cones.view)
    light_in = [hardware(light) for light in cones.lights]
    hints = None
    if cones.local:  # the geometry's ranges of R and D·D (:mod:`.cones`)
        s, order = scale_range(boxes.z, config.normalize.order), config.direction_normalize.order
        spans = []
        for index in range(len(cones.lights)):
            (lo, hi), delta = cones.difference(boxes, s, order, index)
            spans.append((np.maximum(lo - delta, 0.0), hi + delta))
        hints = {"r": cones.reflected(boxes, s, order), "d": spans}
    spec = specular(config, normal, view, light_in, _shininess(config, boxes.n), hints)
    diff = [diffuse(config.diffuse, normal, light)["diff"] for light in light_in]
    return spec, diff
