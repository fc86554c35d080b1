"""Lyon's datapaths run on :class:`~phongfx.certify.interval.Interval` values, box by box.

The golden blocks (:mod:`phongfx.golden`: normalize, reflect, difference, halfway, diffuse) run
unchanged on intervals; two steps are written here instead:

* **The inputs and the LIRP** (Figure 7a).  The host encodes the span-end unit normals ``n0``,
  ``n1`` and ``a`` (:func:`phongfx.sim.stimulus.datapath.encode`: rounded to nearest, each
  within ``e_n``, ``e_a`` of the float), and the LIRP computes ``(1-a_c)·n0_c + a_c·n1_c``
  exactly before its one rounding.  Against the exact ``N' = (1-a)·n0 + a·n1`` that differs by
  ``(1-a_c)(n0_c - n0) + a_c(n1_c - n1) + (a_c - a)(n1 - n0)``: at most
  ``e_n + e_a·|n1 - n0|`` per component, ``|n1 - n0| <= 2·sin(θ/2)`` for span ends up to the
  domain's ``θ`` apart (``= 2·√(1 - min_normal_length²)``), plus the LIRP's rounding.  (The
  interval rule for products would count ``e_n`` twice, once per end.)  ``L`` and ``V`` at
  infinity are constants: their codes, each within its own exact distance of the float.
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
"""

import numpy as np

from phongfx.core.format import Format
from phongfx.golden.diffuse import diffuse
from phongfx.golden.difference import difference
from phongfx.golden.fixed import Fixed
from phongfx.golden.halfway import halfway
from phongfx.golden.normalize import normalize
from phongfx.golden.reflect import reflect

from .interval import Interval, rounding_error
from .sphere import product, projection

__all__ = ["UNITS", "encoding_error", "front", "constant", "shape", "magnitude", "root", "unit_terms"]

#: The specular units bounded here (Lyon's Figures 7 and 8 and the halfway unit of Figure 5).
UNITS = ("fig7", "fig8", "halfway")


def encoding_error(fmt):
    """Largest distance from a float in [-1, 1] to its code in ``fmt`` (rounded to nearest,
    saturated, as :func:`phongfx.sim.stimulus.codes` encodes)."""
    top, low = fmt.max_raw * fmt.lsb, fmt.min_raw * fmt.lsb
    return max(fmt.lsb / 2, 1.0 - top, (low + 1.0) if low > -1 else 0.0)


def front(config, boxes, basis, min_normal_length):
    """The LIRP's output ``N'`` (B, 3) as an Interval over ``boxes`` (module docstring)."""
    vec, a, out = config.lirp.fmt("vec"), config.lirp.fmt("a"), config.lirp.fmt("out")
    chord = 2.0 * np.sqrt(max(0.0, 1.0 - min(1.0, min_normal_length) ** 2))
    product_fmt = vec.mul(a)
    e = (encoding_error(vec) + (a.lsb / 2) * chord
         + rounding_error(product_fmt, out, config.lirp.rounding)) * (1 + 1e-12)
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
    return Interval(lo, hi, err * (1 + 1e-12), config.t, t.faults if np.any(used) else v.faults)


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
    return Interval(lo, hi, err * (1 + 1e-12), config.t, spec.faults if np.any(small) else u.faults)


def _shininess(config, n):
    """The shininess port's codes for ``n`` per box (None when the hardware fixes it)."""
    if config.shininess is None:
        return None
    name, fmt, top = config.shininess
    value = np.sqrt(n) if name == "m" else n
    return Fixed(np.clip(np.round(value), 1, top).astype(np.int64), fmt)


def _halfway_specular(config, normal, view, lights, shininess):
    scaled = shininess.shift(config.halfway_shift) if shininess is not None else None
    out = []
    for light in lights:
        d = halfway(config.halfway, normal, light, view)
        out.append(shape(config.shape, difference(config.difference, d["p"], d["q"], scaled)["x2"]))
    return out


def _fig7_specular(config, normal, view, lights, shininess):
    # as phongfx.golden.datapath.fig7: R once, then per light 2x → shape
    r = reflect(config.reflect, normal, view)["r"]
    return [shape(config.shape, difference(config.difference, r, light, shininess)["x2"]) for light in lights]


def _fig8_specular(config, normal, view, lights, shininess):
    # as phongfx.golden.datapath.fig8: R once, then per light the root-shininess unit
    r = reflect(config.reflect, normal, view)["r"]
    m = shininess if shininess is not None else Fixed(np.full(len(r), config.root.m_const), config.root.m)
    return [root(config.root, r, light, m) for light in lights]


_SPECULAR = {"fig7": _fig7_specular, "fig8": _fig8_specular, "halfway": _halfway_specular}


def unit_terms(config, boxes, basis, lights, min_normal_length):
    """``(spec, diff)``: per light the Intervals (B,) of the unit's ``spec<i>`` and ``diff<i>``
    over ``boxes`` (directional ``lights``: unit vectors; the viewer ``basis[0]``)."""
    count = len(boxes)
    vec = config.normalize.fmt("out")
    normal = normalize(config.normalize, front(config, boxes, basis, min_normal_length))["n"]
    view = constant(basis[0], vec, count)
    light_in = [constant(light, vec, count) for light in lights]
    spec = _SPECULAR[config.specular](config, normal, view, light_in, _shininess(config, boxes.n))
    diff = [diffuse(config.diffuse, normal, light)["diff"] for light in light_in]
    return spec, diff
