"""Golden model of the halfway-vector difference, Lyon (1993) Figure 5 and Figure 9 rows 7–10.

"The Half-way Vector Approach" replaces ``D = R - L`` by differences built on the
halfway vector ``H = V + L``; the output is a pair ``p, q`` with ``D = p - q`` (up to
the sign of the paper or the appendix code, as only ``|D|`` matters), which the
difference block (Figure 7c, ``n -> 4n``) and the shape block take from there:

* ``d1``: ``(2V·N)N - H`` (= ``R - L``); ``d2``: ``(2L·N)N - H`` (``|D2| = |D1|``);
* ``d3``: ``(H·N)N - H``, no normalization of ``H`` (row 7);
* ``g2proj``: ``H* - (H*·N)N`` with ``H* = g2(H·H)·H`` (the code's ``hv1``, rows 8 and 9);
* ``g2``: ``H* - N`` (row 10, which "loses the glancing hilite": a short ``H``
  leaves ``H*`` short too, so ``D`` never gets short; the projection fixes that).

``h = "mean"`` takes the code's ``H = (L + V)/2`` (``|H| <= 1``) and halves every term,
so d1/d2 project ``V`` and ``L`` rather than ``2V`` and ``2L``; ``"sum"`` is the text's.

Bit growth (defaults; the figure has no bit annotations, so these are our
reconstruction, :class:`~phongfx.config.HalfwayConfig`):

* ``N, L, V`` are ``S1.10``, as every direction vector of Figure 7.  ``V + L`` is exact
  in ``S2.10``; halving moves the point (``S1.11``, same bits).  ``hvec`` = ``S2.11``
  holds both exactly for every input code, so ``H`` is never rounded (its quantize
  saturates only for a narrower ``hvec``).
* ``H*``: :func:`phongfx.golden.normalize.normalize` with ``normalize`` (``vec = hvec``;
  14×14 squarers, ``z = 1.12``, ``g = 1.12``, ``H* = S2.11``: one guard bit over
  ``out``, two integer bits for ``|H*|`` up to 2).  ``z`` saturates just below 2, where
  ``g2 = 1``: ``H = V + L`` longer than √2 (``V``, ``L`` within 90°) leaves the
  normalizer unchanged, and between 1 and √2 ``g2`` only shrinks it by up to 1/8, so
  with ``"sum"`` ``H*`` is over-long, up to 2 — ``g2`` is a Taylor series about
  ``z = 1`` and does not fix it.  ``"mean"`` keeps ``z <= 1``, inside ``g2``'s range,
  though a short ``H`` (grazing light) comes out short: Lyon's point about row 10.
* dots: ``V·N``, ``L·N`` are three exact 12×12 products (``S3.20``, sum ``S5.20``);
  ``H·N``, ``H*·N`` three 14×12 (``S4.21``, sum ``S6.21``); one rounding to ``dot`` =
  ``S2.12``: two guard bits (as in reflect) and two integer bits, since ``H·N``
  reaches 2 with ``"sum"`` (``V = L = N``).  Junk codes reach 24: saturate.
* the doubling of ``2V·N`` is a shift (``S3.11``); each 15×12 product ``dot × N_i``
  is exact (``S4.22``; ``S5.21`` doubled) and rounded once to ``out`` = ``S2.10``, which
  holds every component of ``p`` and ``q`` for unit inputs (up to 2), so ``|D|`` up to
  2 (3 for g2 with ``"sum"``: ``V = L = -N`` gives ``H* = -2N``); ``q`` is ``H`` or ``H*``
  rounded to ``out``.  Junk codes take ``p`` to 16, which saturates; ``q`` cannot
  overflow at the defaults (its saturation guards narrower formats).

Error against float64 of the same formulas on the same codes (unit inputs, round
half up, in ``out`` LSBs; the ``g2`` reference clamps ``z`` at 2 as the hardware
does): ``p`` of d1/d2 3/4 (``"sum"``: the rounded dot is doubled) or 5/8, of d3 5/8;
``q = H`` 0 (``"sum"``) or 1/2 (``"mean"``, one fraction bit dropped).  ``H*`` is
within 0.53 LSB (``z``, ``y²`` and ``g`` 0.28, as in the normalizer, plus 1/4 for its
own rounding; 0.6 with ``"sum"``, whose ``|H|`` reaches √2 unsaturated), so ``q = H*``
is within 1.03 (1.1) and ``p`` of g2proj within √3·0.53 + 1/8 + 1/2 = 1.55 (1.67);
``p = N`` of g2 is exact.  Measured: p 0.61, 0.59, 0.60, 0.83, 0 and q 0.5, 0.5, 0.5,
0.87, 0.87 for d1, d2, d3, g2proj, g2 (``"mean"``); the length of ``D``'s error at
most 1.83 (``tests/golden/test_halfway.py``).

``V = -L`` gives ``H = 0``, handled without exception: ``z = 0`` saturates ``g2 = 2``
to ``2 - 2^-12`` and ``H* = 0``, so d3 and g2proj give ``D = 0`` (a full highlight,
Lyon's "feature or bug" of a short ``H``), g2 ``D = N`` and d1/d2 ``±(R - L) = ±2(V·N)N``
(halved with ``"mean"``).
"""

from .normalize import normalize

__all__ = ["halfway"]


def halfway(config, n, l, v):
    """Difference vector ``D = p - q`` from the halfway vector of ``l`` and ``v``.

    Parameters
    ----------
    config : HalfwayConfig
    n, l, v : Fixed, shape (count, 3), format ``config.vec``
        Normal, light and viewpoint directions.

    Returns
    -------
    dict
        ``{"p": Fixed (count, 3), "q": Fixed (count, 3)}``, both in ``config.out``.
    """
    cfg = config
    h = v + l
    if cfg.h == "mean":
        h = h.shift(-1)
    h = h.quantize(cfg.hvec, cfg.rounding, "saturate", op="halfway H")
    if cfg.variant in ("g2proj", "g2"):
        h = normalize(cfg.normalize, h)["n"]
    if cfg.variant == "g2":
        p = n
    else:
        w = {"d1": v, "d2": l}.get(cfg.variant, h)
        dot = w.dot(n).quantize(cfg.dot, cfg.rounding, "saturate", op="halfway dot")
        if cfg.variant in ("d1", "d2") and cfg.h == "sum":
            dot = dot << 1  # the paper's 2V (2L); "mean" halves it away
        p = n * dot[:, None]
    return {"p": p.quantize(cfg.out, cfg.rounding, "saturate", op="halfway p"),
            "q": h.quantize(cfg.out, cfg.rounding, "saturate", op="halfway q")}
