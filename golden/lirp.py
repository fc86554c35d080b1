"""Golden model of the LIRP, Lyon (1993) Figure 7a: ``N' = (1-a)·N0 + a·N1``.

Bit growth (defaults): ``a`` is ``1.10`` so that 1.0 is exact; the "1-" block gives
``1-a`` exactly in the same format; each product ``S1.10 × 1.10`` is exact in
``S2.20``, their sum in ``S3.20``; one rounding brings ``N'`` back to ``S1.10``.
The sum is a convex combination of the end vectors, so it cannot leave their range:
the quantize declares ``overflow="error"``.
"""

from .fixed import Fixed, check_range

__all__ = ["lirp"]


def lirp(config, n0, n1, a):
    """Interpolate ``n0`` → ``n1`` by ``a`` (``a = 0`` gives ``n0``, ``a = 1`` gives ``n1``).

    Parameters
    ----------
    config : LirpConfig
    n0, n1 : Fixed, shape (count, 3), format ``config.vec``
    a : Fixed, shape (count,), format ``config.a``, values in 0..1

    Returns
    -------
    dict
        ``{"n": Fixed (count, 3) in config.out}``
    """
    check_range("a", a, 0, 1)
    b = (Fixed.const(1, config.a) - a).quantize(config.a, "truncate", "error", op="lirp 1-a")
    p = n0 * b[:, None] + n1 * a[:, None]
    return {"n": p.quantize(config.out, config.rounding, "error", op="lirp N'")}
