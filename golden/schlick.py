"""Golden model of Schlick's rational specular term (Schlick 1994, "A Fast Alternative
to Phong's Specular Model"): ``S_n(t) = t / (n - n·t + t)`` in place of ``t^n``.

``t = cos α`` lies in ``0..1`` and ``n`` is an integer ``1..n_max``; the paper's cost is
"1 addition, 1 subtraction, 1 multiplication and 1 division".  Datapath (defaults in
brackets):

* ``1 - t`` is exact in the unsigned format of ``t`` [``1.15``]: ``t <= 1``;
* ``n·(1 - t)`` [``13.0 × 1.15``] and ``+ t`` are exact; the divisor
  ``D = n(1 - t) + t`` lies in ``1..n_max`` (``D >= (1 - t) + t = 1``), held exactly in
  :attr:`SchlickConfig.den` [``13.15``, 28 bits];
* the quotient ``S = t/D <= 1`` (``t <= D``), so a restoring divider needs the bit of
  weight ``2^0`` and the ``F`` fraction bits of ``out`` [``1.15``]: ``Q = F + 1`` quotient
  bits [16], ``q = floor(t·2^(Q-1) / D)`` on raw codes (the scale of ``t`` cancels);
* ``round_half_up`` computes one more bit and returns ``(q + 1) >> 1``, which is
  ``floor(S·2^F + 1/2)``; ``S <= 1`` keeps it within ``out``.

Error against the exact rational ``S_n(t)`` of the codes: ``0 <= S - out < 1`` LSB for
``truncate`` (the floor), ``|S - out| <= 1/2`` LSB for ``round_half_up``.  Measured,
every ``t`` code of ``1.15`` for n = 1, 2, 6, 16, 64, 8000: max 0.99999 LSB (truncate),
0.49999 LSB (round half up).  ``S_n(1) = 1`` and ``S_1(t) = t`` exactly, ``S_n(0) = 0``;
floor and rounding are monotone, so the output never falls as ``t`` rises.
"""

from phongfx.core.format import Format

from .fixed import Fixed, check_range

__all__ = ["schlick", "divisor"]


def divisor(config, t, n):
    """The exact divisor ``D = n·(1 - t) + t`` in :attr:`SchlickConfig.den`."""
    unsigned_t = Format(config.fmt("t").int_bits, config.fmt("t").frac_bits)
    u = (Fixed.const(1, "1.0") - t).quantize(unsigned_t, "truncate", "error", op="schlick 1-t")
    return (n * u + t).quantize(config.den, "truncate", "error", op="schlick n(1-t)+t")


def schlick(config, t, n):
    """Specular amount ``S_n(t) = t / (n - n·t + t)``, the quotient floored or rounded.

    Parameters
    ----------
    config : SchlickConfig
    t : Fixed, shape (count,), format ``config.t``, values 0..1
    n : Fixed, shape (count,), format ``config.n``, integers 1..``config.n_max``

    Returns
    -------
    dict
        ``{"spec": Fixed (count,) in config.out}``
    """
    check_range("t", t, 0, 1)
    check_range("n", n, 1, config.n_max)
    den = divisor(config, t, n)
    # the divider's floor, on raw integers: no float ever rounds a quotient here
    bits = config.quotient_bits
    q = Fixed((t.raw << (bits - 1)) // den.raw, Format(1, bits - 1))
    # round_half_up drops the extra bit: (q + 1) >> 1; truncate drops nothing
    return {"spec": q.quantize(config.out, config.rounding, "error", op="schlick S")}
