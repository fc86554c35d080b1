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

__all__ = ["UNITS", "encoding_error", "front", "constant", "shape", "unit_terms"]

#: The specular units bounded here (Lyon's Figure 7 and the halfway unit of Figure 5).
UNITS = ("fig7", "halfway")


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


_SPECULAR = {"fig7": _fig7_specular, "halfway": _halfway_specular}


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
