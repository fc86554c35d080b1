"""Gappa's proof of the rounding error of Lyon's Figure 7c–d chain, from ``D·D`` to the
specular amount.

Between its quantizes, Figure 7c–d is polynomial (Lyon 1993, "Pixel Shading Hardware
Datapaths"): ``D = R - L`` is exact, ``D·D`` is rounded to ``dd``, ``2x = n·D·D`` to ``x2``,
the shape function's ``1 - x/2^k`` (a shift and a subtraction, Figure 7d) to ``t``, and each of
its ``k`` squarings to ``t`` again.  :func:`gappa_script` writes that chain twice, as the
hardware rounds it and exactly, from the configuration's formats and rounding modes, and
asks Gappa (Melquiond; Debian package ``gappa``) for an enclosure of
``|spec_hw - f_k(n·D·D/2)|``, the hardware's amount against the exact shape function of the
*same* ``R`` and ``L`` codes: the chain's rounding error, not the shape's distance from
``cos^n`` (the approximation) nor the error of the codes ``R`` and ``L`` themselves.

Rounding modes.  The golden model's ``round_half_up`` is ``floor(x + 1/2)`` on the exact
value (:func:`phongfx.golden.fixed.quantize_raw` adds 1 to the floor when the dropped part is
at least one half), round to nearest with ties toward +∞: Gappa's ``nu``, exactly;
``round_half_even`` is ``ne``; ``truncate`` drops bits of a two's-complement code, toward
−∞: ``dn``.  Every mode the golden model has therefore maps to a Gappa mode with the same
rounding function, not merely a covering error bound.

What the proof assumes (the script's hypotheses, stated in its header): ``D·D`` is a
multiple of ``2^-2f`` in ``[0, dd_max]`` (``D`` exact in ``f`` fraction bits: ``difference.d``
keeps the bits of ``difference.vec``, and no component of ``D`` nor ``D·D`` saturates, which
only ``α`` near 180° reaches), ``n`` is an integer in the ``n`` range given, and both the
hardware's and the exact ``x/2^k`` lie in ``[0, 1]``.  Where exactly one of them reaches 1
(one side outputs 0, the comparator of Figure 7d), the other is within the ``x2`` rounding
of 1, and :func:`edge_bound` bounds that case exactly; the bound returned is the larger.
"""

import math
import re
import shutil
import subprocess
import tempfile
from fractions import Fraction
from pathlib import Path

from phongfx.config.shape import FIG7

__all__ = ["GAPPA_MODES", "GappaError", "gappa_script", "run_gappa", "edge_bound", "gappa_bound", "specular_levels"]

#: The golden model's rounding modes as Gappa's (module docstring: the same functions).
GAPPA_MODES = {"round_half_up": "nu", "round_half_even": "ne", "truncate": "dn"}
#: Seconds Gappa may take (it takes well under one on this chain).
TIMEOUT = 60


class GappaError(RuntimeError):
    """Gappa is missing, failed, timed out or proved nothing."""


def _unit(config):
    """The Figure 7 datapath config of ``config`` (a DatapathConfig or a ShaderConfig)."""
    unit = config.units[0] if hasattr(config, "units") else config
    if getattr(unit, "unit", None) is not FIG7:
        raise ValueError(f"the Gappa model is Figure 7's chain (specular fig7), not "
                         f"{getattr(unit, 'specular', type(unit).__name__)!r}")
    return unit


def _mode(rounding, field):
    if rounding not in GAPPA_MODES:
        raise ValueError(f"{field} must be one of {', '.join(GAPPA_MODES)}, not {rounding!r}")
    return GAPPA_MODES[rounding]


def _power(exponent):
    """``2^exponent`` as a Gappa constant."""
    return f"1b{exponent}"


def _n_range(diff, ranges):
    if diff.shininess_const:
        return diff.shininess_range  # the one n built into the hardware
    lo, hi = ranges.get("n", diff.shininess_range)
    if not (isinstance(lo, int) and isinstance(hi, int) and 1 <= lo <= hi <= diff.n_max):
        raise ValueError(f"ranges n must be integers lo <= hi in 1..{diff.n_max}, not {(lo, hi)!r}")
    return lo, hi


def gappa_script(config, ranges, part="chain"):
    """The Gappa script of Figure 7c–d's rounding error under ``config``'s formats and modes.

    :param config: a Figure 7 ``DatapathConfig`` (or its ``ShaderConfig``).
    :param ranges: ``{"n": (lo, hi)}``, the integer shininess range (a hardware constant
        ``difference.n_const`` overrides it), and optionally ``"dd": (lo, hi)``, the range of
        ``D·D`` (default ``0`` to ``dd``'s largest value).
    :param part: ``"chain"`` (from ``D·D`` and ``n``) or ``"shape"`` (from the ``x2`` code:
        the shape function alone).
    """
    unit = _unit(config)
    diff, shape = unit.difference, unit.shape
    vec, d, dd, x2, t = (diff.fmt("vec"), diff.fmt("d"), diff.fmt("dd"), shape.fmt("x2"), shape.fmt("t"))
    if d.frac_bits != vec.frac_bits:
        raise ValueError(f"the Gappa model takes D exact: difference.d ({d}) must keep the fraction bits "
                         f"of difference.vec ({vec})")
    k, f = shape.k, d.frac_bits
    rd, rs = _mode(diff.rounding, "difference.rounding"), _mode(shape.rounding, "shape.rounding")
    dd_max = Fraction(dd.max_raw, dd.one)
    lo_dd, hi_dd = ranges.get("dd", (0, dd_max))
    lines = ["# Lyon 1993, Figure 7c-d between its quantizes: hardware (lower case) and exact (upper)",
             f"# difference {diff.rounding} -> {rd}, shape {shape.rounding} -> {rs} (same functions)",
             f"@rdd = fixed<{-dd.frac_bits},{rd}>;", f"@rx2 = fixed<{-x2.frac_bits},{rd}>;",
             f"@rt = fixed<{-t.frac_bits},{rs}>;"]
    if part == "chain":
        lo, hi = _n_range(diff, ranges)
        lines += ["# n: an integer; DD = |R - L|^2 of two codes of 2^-f: a multiple of 2^-2f",
                  "n = fixed<0,dn>(N);", f"D2 = fixed<{-2 * f},dn>(DD);", "dd = rdd(D2);",
                  "x2 = rx2(n * dd);", "X2 = n * D2;"]
        hypotheses = [f"N in [{lo},{hi}]", f"DD in [{_exact(lo_dd)},{_exact(min(Fraction(hi_dd), dd_max))}]"]
    elif part == "shape":
        lines += ["# the x2 code itself: exact for both", f"x2 = fixed<{-x2.frac_bits},dn>(X2in);", "X2 = x2;"]
        hypotheses = [f"X2in in [0,{_exact(Fraction(x2.max_raw, x2.one))}]"]
    else:
        raise ValueError(f"part must be chain or shape, not {part!r}")
    lines += [f"v = x2 * {_power(-(k + 1))};", f"V = X2 * {_power(-(k + 1))};", "t0 = rt(1 - v);", "T0 = 1 - V;"]
    for i in range(k):
        lines += [f"t{i + 1} = rt(t{i} * t{i});", f"T{i + 1} = T{i} * T{i};"]
    hypotheses += ["v in [0,1]", "V in [0,1]"]
    lines.append("{ " + r" /\ ".join(hypotheses) + f" -> |t{k} - T{k}| in ? }}")
    return "\n".join(lines) + "\n"


def _exact(value):
    """A rational as an exact Gappa literal."""
    value = Fraction(value)
    if value.denominator == 1:
        return str(value.numerator)
    exponent = value.denominator.bit_length() - 1
    if value.denominator != 1 << exponent:
        raise ValueError(f"{value} is not a dyadic rational")
    return f"{value.numerator}b-{exponent}"


_NUMBER = r"(-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)(?:b(-?\d+))?"


def _parse(text):
    """The exact upper end of Gappa's ``... in [lo, hi]`` result, a Fraction."""
    found = re.search(rf"in \[{_NUMBER}\s*(?:\{{[^}}]*\}})?,\s*{_NUMBER}", text)
    if not found:
        raise GappaError(f"gappa proved no enclosure: {text.strip()[-300:]}")
    mantissa, exponent = found.group(3), found.group(4)
    return Fraction(mantissa) * Fraction(2) ** int(exponent or 0)


def run_gappa(script, *, timeout=TIMEOUT, coq=None):
    """Run Gappa on ``script`` in a temporary folder; the exact upper end of the enclosure
    it proves (a Fraction).  ``coq``: a file to write Gappa's Coq proof of it to."""
    gappa = shutil.which("gappa")
    if gappa is None:
        raise GappaError("gappa is not installed; as root: apt-get install gappa")
    with tempfile.TemporaryDirectory(prefix="phongfx-gappa-") as folder:
        path = Path(folder) / "chain.g"
        path.write_text(script)
        try:
            done = subprocess.run([gappa, path.name], cwd=folder, capture_output=True, text=True, timeout=timeout)
            proof = (subprocess.run([gappa, "-Bcoq", path.name], cwd=folder, capture_output=True, text=True,
                                    timeout=timeout) if coq else None)
        except subprocess.TimeoutExpired:
            raise GappaError(f"gappa took longer than {timeout:g} s") from None
    if done.returncode != 0:
        raise GappaError(f"gappa failed: {(done.stderr or done.stdout).strip()[-300:]}")
    bound = _parse(done.stderr + done.stdout)
    if coq:
        Path(coq).write_text(proof.stdout)
    return bound


def edge_bound(config, ranges, part="chain"):
    """Exact bound where only one of the hardware's ``v`` and the exact ``V = x/2^k`` reaches 1
    (that side's amount is 0; the other side's ``1 - v`` is within ``v``'s error of 0)."""
    unit = _unit(config)
    diff, shape = unit.difference, unit.shape
    k = shape.k

    def error(rounding, fmt):  # largest |rnd(x) - x| of one rounding to fmt
        ulp = Fraction(1, fmt.one)
        return ulp if rounding == "truncate" else ulp / 2
    if part == "chain":
        n_hi = _n_range(diff, ranges)[1]
        e_x2 = error(diff.rounding, diff.fmt("x2")) + n_hi * error(diff.rounding, diff.fmt("dd"))
    else:
        e_x2 = Fraction(0)
    e_v = e_x2 / 2 ** (k + 1)
    r_t = error(shape.rounding, shape.fmt("t"))
    t = e_v + r_t
    for _ in range(k):
        t = t * t + r_t
    return max(e_v ** (2 ** k), t)


def _up(value):
    """The least float >= the Fraction ``value``."""
    near = float(value)
    return near if Fraction(near) >= value else math.nextafter(near, math.inf)


def gappa_bound(config, ranges, *, part="chain", timeout=TIMEOUT, coq=None):
    """``(bound, script)``: a proven upper bound on ``|spec_hw - f_k(n·D·D/2)|`` (in units of
    the amount, 1.0 = a full highlight; a float at or above the exact value) over ``ranges``
    (:func:`gappa_script`), the larger of Gappa's and :func:`edge_bound`, and the script."""
    script = gappa_script(config, ranges, part)
    bound = max(run_gappa(script, timeout=timeout, coq=coq), edge_bound(config, ranges, part))
    return _up(bound), script


def specular_levels(bound, blend):
    """What an error of ``bound`` in every light's specular amount can move an output, in
    display levels: the blend (:class:`~phongfx.config.BlendConfig`) multiplies each amount
    by its coefficient code, so at most ``bound`` times the largest sum over the lights of a
    material's specular codes of one channel."""
    lsb = Fraction(1, blend.coef_format.one)
    worst = max(sum(Fraction(int(light[c])) for light in blend.coefficients(m)[2]) * lsb
                for m in range(blend.materials) for c in range(3))
    return _up(Fraction(bound) * worst)
