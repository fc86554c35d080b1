"""Golden model of the corrected Euler unit, Hast, Barrera & Bengtsson (equations 16–17),
and of the forward-difference recurrence it shares with the Gouraud unit.

Per pixel the unit outputs ``p`` and then steps ``p += t``, ``t += ds``: two adders and
three registers, nothing else (the paper's inner loop).  A pixel with ``init`` set loads
``p = p0``, ``t = t0``, ``ds`` first, so its output is ``p0``; ``p0``, ``t0``, ``ds`` of
the other pixels are ignored.  Over a scanline, ``k`` pixels after ``init``
(equation 14 with ``t0`` for ``di_a``)::

    p_k = p0 + k·t0 + k(k-1)/2·ds

Gouraud shading is the same recurrence one order lower, ``p += dp`` ("a forward
difference or recurrence sequence in just 1 addition in the inner loop", Hast et al. §1):
:func:`forward_differences` and :func:`forward_difference_unit` are the model of both
(:mod:`phongfx.golden.gouraud`), as the hardware shares one builder.

Formats (:class:`~phongfx.config.EulerConfig`): registers ``p`` [``S1.30``], ``t``
[``S3.30``], ``ds`` [``S3.30``].  Fraction bits never fall from ``ds`` to ``t`` to
``p``, so each sum is exact on the finer grid and has **no bit growth**: it is kept in
its register's width, wrapping modulo ``2^width`` like the hardware adder.  The model
is that modular recurrence exactly (a cumulative sum per scanline in ``uint64``, whose
wrap modulo ``2^64`` commutes with the final wrap to the register), so junk inputs
wrap as the registers do.  For the setups of :mod:`phongfx.golden.euler_setup` nothing
wraps: unit end normals give ``|p| <= 1`` at the ends, and the quantized setup raises
(``overflow="error"``) if a load or the float curve leaves its format.

``level`` is ``p`` truncated to ``out`` [``0.8``] and saturated: ``floor(256·p)``
clamped to ``0..255``, so a negative ``p`` (light behind the surface) gives 0 and
``p >= 1`` gives 255.  Hast's evaluation truncates ``255·p`` instead; ``256·p``
is free wiring.

Before any ``init`` the registers hold their reset value 0.
"""

import numpy as np

from phongfx.core.format import Format

from .fixed import Fixed, quantize_raw

__all__ = ["euler", "forward_difference_unit", "forward_differences", "segments"]


def segments(init):
    """Index of the last ``init`` at or before each pixel (-1 before any) and the
    pixel's step count ``k`` since it."""
    init = np.asarray(init, dtype=bool)
    index = np.arange(len(init))
    last = np.maximum.accumulate(np.where(init, index, -1))
    return last, index - last


def _held(raw, last):
    """``raw`` as loaded at pixel ``last`` (0, the reset value, where ``last`` is -1)."""
    return np.where(last >= 0, np.asarray(raw, dtype=np.int64)[np.maximum(last, 0)], 0)


def _as_uint(raw, shift=0):
    """Raw codes moved ``shift`` places left, as ``uint64`` modulo ``2^64``."""
    return np.asarray(raw, dtype=np.int64).view(np.uint64) << np.uint64(shift)


def _wrap(value, fmt):
    """``uint64`` residues modulo ``2^64`` to raw codes of ``fmt``, wrapped like its register."""
    full = Format(63 - fmt.frac_bits, fmt.frac_bits, True)
    return quantize_raw(np.asarray(value, dtype=np.uint64).view(np.int64), full, fmt, "truncate", "wrap")


def _exclusive_sums(step, last):
    """Sum of ``step`` (``uint64``) over the earlier pixels of each pixel's scanline."""
    before = np.cumsum(step, dtype=np.uint64) - step
    return before - before[np.maximum(last, 0)]


def forward_differences(init, loads):
    """The first of a chain of registers stepped as forward differences, per pixel.

    ``loads`` lists the :class:`Fixed` loads from the output down to the constant step
    (``p0, t0, ds`` for Euler's equations 16–17, ``p0, dp`` for Gouraud), each in its
    register's format, fraction bits never falling towards the output.  A pixel with
    ``init`` (raw, 1 or 0) outputs its ``p0`` and loads every register; on every pixel
    each register then takes itself plus the next one, wrapped in its own width, the
    last one holding: the twin of :func:`phongfx.hdl.euler.forward_differences`.

    Each register is the wrapped sum of its load and of the values of the next register
    on the scanline's earlier pixels; the registers are modelled from the constant step
    up, so a wrap of a middle register reaches the output as in the hardware.
    """
    last, _ = segments(init)
    value = fmt = None
    for load in reversed(loads):
        total = _as_uint(_held(load.raw, last))
        if value is not None:
            total = total + _exclusive_sums(_as_uint(value, load.fmt.frac_bits - fmt.frac_bits), last)
        value, fmt = _wrap(total, load.fmt), load.fmt
    return Fixed(value, fmt)


def forward_difference_unit(config, init, loads, op):
    """``{"p", "level"}`` of a unit built on :func:`forward_differences`: ``p`` and its
    intensity truncated and saturated to ``config.out`` (``op`` names that quantize)."""
    p = forward_differences(init.raw, loads)
    return {"p": p, "level": p.quantize(config.out, "truncate", "saturate", op=op)}


def euler(config, init, p0, t0, ds):
    """Corrected Euler intensities of a sequence of pixels.

    Parameters
    ----------
    config : EulerConfig
    init : Fixed, shape (count,), ``1.0``
        1 on the first pixel of a scanline: load ``p0``, ``t0``, ``ds``.
    p0, t0, ds : Fixed, shape (count,), ``config.p``, ``config.t``, ``config.ds``
        Start value, corrected first step ``t0 = di_a - dε`` and second difference.

    The arrays are the ordered sequence of valid pixels: the unit is stateful.

    Returns
    -------
    dict
        ``{"p": Fixed (count,) in config.p, "level": Fixed (count,) in config.out}``
    """
    return forward_difference_unit(config, init, (p0, t0, ds), "euler level")
