"""Golden model of the difference vector and ``2x``, Lyon (1993) Figure 7c: ``2x = n·D·D``.

``D = R - L`` with ``x = (n/2)·D·D`` ("Phong Specularity Reformulation"); the
figure computes ``2x`` so that no divide by two is needed before the shape function.

Bit growth (defaults): ``R - L`` of two ``S1.10`` is exact in ``S2.10``; ``D`` is
saturated back to ``S1.10`` (10 fraction bits on direction vectors, as the Figure 7a
text says; 12 bits, the paper's "three 12×12 multipliers").  ``|D| = 2`` only at
α = 180°, where a component of exactly -2 is held but +2 saturates to 2 - 2^-10;
``x`` is huge there for any useful ``n`` and the specular amount 0 (only at ``n = 1``
does it show: ``f_2`` gives 2056 instead of 2048 LSB of ``1.15``).  Each square
``S1.10 × S1.10`` is exact in ``S3.20``, their sum in ``S5.20``; ``D·D`` keeps all 20
fraction bits in ``dd`` = ``2.20`` (the paper's 22 bits) and saturates just below 4,
which only α near 180° reaches.  ``n`` is an integer ``13.0`` (1..8000); the
``13×22`` product (the paper's "14×22" counts a sign bit) is exact in ``15.20`` and
rounded once to ``x2`` = ``13.12``, saturating: any ``2x >= 2^(k+1)`` (``k <= 4``)
already gives a specular amount of 0, so a clamped ``2x`` changes nothing.

Error against exact ``n·|R-L|²`` on the same codes, when nothing saturates:
``D`` and ``D·D`` are exact, ``2x`` is within 1/2 LSB (``2^-13``).

With :attr:`~phongfx.config.DifferenceConfig.n_const` set, ``n`` is that constant in the
same format ``n`` (:func:`~phongfx.golden.shininess.shininess_input`): the product and its
rounding are those of feeding it on the port.
"""

from .shininess import shininess_input

__all__ = ["difference"]


def difference(config, r, l, n=None):
    """``2x = n·(R-L)·(R-L)`` for reflected view ``r``, light ``l`` and shininess ``n``.

    Parameters
    ----------
    config : DifferenceConfig
    r, l : Fixed, shape (count, 3), format ``config.vec``
    n : Fixed, shape (count,), format ``config.n``, integers 1..``config.n_max``
        Exactly when ``config.n_const`` is 0 (``n`` is a port); otherwise None.

    Returns
    -------
    dict
        ``{"x2": Fixed (count,) in config.x2}``
    """
    n = shininess_input(config, n, len(r))
    d = (r - l).quantize(config.d, config.rounding, "saturate", op="difference D")
    dd = d.dot(d).quantize(config.dd, config.rounding, "saturate", op="difference D·D")
    return {"x2": (n * dd).quantize(config.x2, config.rounding, "saturate", op="difference 2x")}
