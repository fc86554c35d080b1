"""Golden model of the spherical interpolation unit, Szirmay-Kalos et al. (2000) Figure 12.

Spherical interpolation turns the cosine between two interpolated vectors into
``A·cos(tγ - φ)`` (equation 17), and ``cos^n`` into ``cos²(a·x)`` (equation 19), so a
scanline needs per pixel one addition, one ROM read and one multiplication:

* **interpolator** (the paper's ``line_interpolator``): ``θ = b`` on a pixel with ``init``
  set, else ``θ(X) = θ(X-1) + s``; ``b`` and ``s`` are loaded at ``init`` (the slope is held
  with the constants, so the pixels after ``init`` carry no valid ``b``, ``s``, ``c``).
  The register ``theta`` [``S0.11``, 12 bits] holds ``θ/π``: ``θ ∈ [-π, π)``, and the sum
  wraps modulo ``2π`` like the hardware adder (no bit growth: the sum is kept in
  ``theta``'s width);
* **ROM**: the top ``addr_bits`` [6] of the register, a two's complement code ``c``,
  select the cell ``θ ∈ [c, c+1)·π/2^(A-1)``; the word is the function at the cell's
  centre, rounded half up to ``rom`` [``0.6``] and saturated (the centre of the peak cells
  is ``cos²(π/2^A) > 1 - 2^-6``).  Cells whose centre lies outside ``|θ| <= π/2`` hold 0
  (equation 19's "zero otherwise"; for the diffuse ``cos`` ROM it is the backside test).
  Only the cells of ``θ ∈ [-π/2, π/2)`` can be nonzero, so the ROM wraps at
  ``±π``, where both sides are 0: a span that leaves the window reads zeros until it has
  turned through ``π`` more; :func:`rom_contents` fills both this model and the HDL ROM;
* **multiplier**: ``C·w`` [``1.11 × 0.6`` exact in ``1.17``] rounded to ``out`` [``1.11``];
  ``C = I_in·k_s·A^n`` (equation 18) is one constant per scanline for specular, three
  (``C_r``, ``C_g``, ``C_b``) for the diffuse ``cos`` channel with its own interpolator.

Error of a ROM word against the function at any ``θ`` of its cell: the cell is
``δ = π/2^(A-1)`` wide and ``|d cos²θ/dθ| = |sin 2θ| <= 1`` (``|d cos θ/dθ| <= 1``), so
at most ``δ/2`` from the centre, plus the rounding (``2^-(D+1)``, ``D`` data bits) or the
saturation of the peak (below ``2^-D``): **at most** ``π/2^A + 2^-D``.  The boundary
cells of the window are within this too (the function is 0 at ``±π/2``).
"""

import math

import numpy as np

from phongfx.core.format import Format

from .fixed import Fixed, quantize_raw

__all__ = ["spherical", "rom_contents", "rom_angles", "interpolate", "rom_bound"]

#: The two ROM channels: squared cosine (specular, equation 19) and cosine (diffuse).
FUNCTIONS = {"cos2": lambda x: np.cos(x) ** 2, "cos": np.cos}


def rom_angles(addr_bits):
    """Angle (radians) at the centre of each ROM cell, indexed by the unsigned address."""
    code = np.arange(1 << addr_bits, dtype=np.int64)
    code = np.where(code >= 1 << (addr_bits - 1), code - (1 << addr_bits), code)
    return (code + 0.5) * math.pi / (1 << (addr_bits - 1))


def rom_contents(addr_bits, rom, function="cos2"):
    """Raw words of the ``function`` ROM (``"cos2"`` or ``"cos"``), unsigned address order.

    The one source of the ROM data: the golden model reads it, and the HDL fills its
    ``Memory`` with it at elaboration.
    """
    rom = Format.parse(rom)
    angle = rom_angles(addr_bits)
    value = np.where(np.abs(angle) <= math.pi / 2, FUNCTIONS[function](angle), 0.0)
    return Fixed.from_float(np.maximum(value, 0.0), rom, "round_half_up", "saturate").raw


def rom_bound(addr_bits, rom):
    """The docstring's bound on ``|word - function(θ)|`` over a cell: ``π/2^A + 2^-D``."""
    return math.pi / (1 << addr_bits) + Format.parse(rom).lsb


def interpolate(theta, init, b, s):
    """Raw ``θ`` of each pixel: ``b`` at the last ``init``, plus ``s`` per pixel since,
    modulo the register (0 before any ``init``, as after reset)."""
    init = np.asarray(init, dtype=bool)
    index = np.arange(len(init))
    last = np.maximum.accumulate(np.where(init, index, -1))
    loaded = last >= 0
    start = np.where(loaded, b[np.maximum(last, 0)], 0)
    slope = np.where(loaded, s[np.maximum(last, 0)], 0)
    # at most 2^11 · len(init) from 12-bit codes: exact in int64, then the adder's wrap
    raw = start + (index - last) * slope
    return quantize_raw(raw, Format(40, theta.frac_bits, True), theta, "truncate", "wrap")


def _channel(config, init, theta_raw, c_raw, function):
    rom = config.fmt("rom")
    shift = config.fmt("theta").width - config.addr_bits
    address = (theta_raw >> shift) & ((1 << config.addr_bits) - 1)
    word = rom_contents(config.addr_bits, rom, function)[address]
    # the constants held since the last init (0 before any, as after reset)
    last = np.maximum.accumulate(np.where(init, np.arange(len(init)), -1))
    held = np.where(last >= 0, c_raw[np.maximum(last, 0)].T, 0).T
    if c_raw.ndim > 1:  # one word for the three colour channels
        word = word[:, None]
    return (Fixed(held, config.c) * Fixed(word, rom)).quantize(
        config.out, config.rounding, config.out_overflow, op="spherical C·w")


def spherical(config, init, b, s, c, bd, sd, cd):
    """Specular ``C·cos²θ`` and diffuse ``C_rgb·max(cos θ_d, 0)`` of a sequence of pixels.

    Parameters
    ----------
    config : SphericalConfig
    init : Fixed, shape (count,), ``1.0``
        1 on the first pixel of a scanline: load ``b``, ``s``, ``c``, ``bd``, ``sd``, ``cd``.
    b, s, bd, sd : Fixed, shape (count,), ``config.theta``
        Start and slope of ``θ`` (specular) and ``θ_d`` (diffuse), in units of π.
    c : Fixed, shape (count,), ``config.c``
        ``C = I_in·k_s·A^n`` (equation 18).
    cd : Fixed, shape (count, 3), ``config.c``
        Diffuse constants ``C_r``, ``C_g``, ``C_b``.

    The arrays are the ordered sequence of valid pixels: the unit is stateful.

    Returns
    -------
    dict
        ``{"spec": Fixed (count,), "diff": Fixed (count, 3)}`` in ``config.out``
    """
    theta = config.fmt("theta")
    load = init.raw.astype(bool)
    spec_theta = interpolate(theta, load, b.raw, s.raw)
    diff_theta = interpolate(theta, load, bd.raw, sd.raw)
    return {"spec": _channel(config, load, spec_theta, c.raw, "cos2"),
            "diff": _channel(config, load, diff_theta, cd.raw, "cos")}
