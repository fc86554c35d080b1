"""Halfway-vector difference component, Lyon (1993) Figure 5 and Figure 9 rows 7–10."""

from functools import cached_property

from phongfx.config import HalfwayConfig

from .block import PipelinedBlock, unbuilt
from .dsp import product
from .fixed import cut, delay, quantize_cut, stage
from .normalize import Normalize

__all__ = ["Halfway"]


class Halfway(PipelinedBlock):
    """``p`` and ``q`` with ``D = p - q`` from ``H = V + L`` (or ``(L + V)/2``), per variant.

    ``H`` is an adder (the halving is wiring).  g2proj and g2 feed it to a
    :class:`~phongfx.hdl.normalize.Normalize` built from ``config.normalize`` (Lyon's
    ``g2``, not re-implemented here) for ``H*``.  The projecting variants (d1, d2, d3,
    g2proj) then have the two multiplier levels of Figure 7b: three 12×12 (``V·N``,
    ``L·N``) or 14×12 (``H·N``, ``H*·N``) for the dot, three 15×12 for ``dot × N``; the
    doubling of d1/d2 with ``h = "sum"`` is a shift.  Formats, bit growth and error
    bounds are as in :func:`phongfx.golden.halfway.halfway`.

    Latency: ``front + 4 + [pipeline ≥ 1] + [pipeline ≥ 2] + 2·[pipeline ≥ 3] + 4·[pipeline ≥ 4]`` for d1,
    d2, d3, g2proj (products; the rounded dot; products ``dot × N_i``; the rounded ``p``)
    and ``front + 1 + [pipeline ≥ 3]`` for g2 (the rounded ``q``).  ``front`` is
    ``2·[pipeline ≥ 2] + [pipeline ≥ 3]`` (the sum ``V + L``, its rounding and its
    clamp, cut apart) plus the normalizer's latency for g2proj and g2, and 0 for d1 and
    d2 (they project ``V`` or ``L``, not ``H``): 4, 4, 4, 8, 5 at the defaults.  Depth 1
    registers the first multipliers' inputs; depth 2 also cuts the dot's adder tree
    from its rounding; depth 3 each rounding from its clamp.  ``N`` and ``q`` wait
    (automatically) to meet ``p``; ``valid`` follows the normalizer's own.

    Ports: ``i.payload`` = ``n``, ``l``, ``v`` (3 × ``config.vec``);
    ``o.payload`` = ``p``, ``q`` (3 × ``config.out``).
    """

    config_class = HalfwayConfig

    def __init__(self, config):
        super().__init__(config)
        self._normalize = None
        if config.variant in ("g2proj", "g2"):
            # owned here: only an unused Halfway should warn
            self._normalize = unbuilt(Normalize(config.normalize))

    @property
    def _front(self):
        if self.config.variant in ("d1", "d2"):
            return 0
        front = 2 * (self.config.pipeline >= 2) + (self.config.pipeline >= 3)
        return front + (self._normalize.latency if self._normalize is not None else 0)

    @cached_property
    def latency(self):
        depth = self.config.pipeline
        if self.config.variant == "g2":
            return self._front + 1 + (depth >= 3)
        return self._front + 4 + (depth >= 1) + (depth >= 2) + 2 * (depth >= 3) + 4 * (depth >= 4)

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        n, l, v = i["n"], i["l"], i["v"]
        h = cut(m, v + l, depth >= 2, "hsum")
        if cfg.h == "mean":
            h = h.shift(-1)
        h = quantize_cut(m, h, cfg.hvec, cfg.rounding, "saturate", depth >= 3, "h_round", depth >= 4)
        h = cut(m, h, depth >= 2, "h")
        valid = delay(m, self.i.valid, h.cycle, "valid_h")
        if self._normalize is not None:
            m.submodules.normalize = self._normalize
            self._normalize.feed(m, valid, {"n": h})
            # the normalizer's valid pipeline serves this block too: no second one
            h, valid = self._normalize.results()["n"], self._normalize.o.valid
        # rounded before waiting for p: its registers hold out's bits, not hvec's
        q = quantize_cut(m, h, cfg.out, cfg.rounding, "saturate", depth >= 3, "q_round", depth >= 4)
        if cfg.variant == "g2":
            # N waits in vec and widens to out (exactly) at the port
            q = stage(m, q, "q")
            return {"p": n.at(q.cycle).quantize(cfg.out, cfg.rounding, "saturate"), "q": q,
                    "valid": delay(m, valid, q.cycle - h.cycle, "valid")}
        x = {"d1": v, "d2": l}.get(cfg.variant, h)
        n_in = cut(m, n, depth >= 1, "n_in")
        products = product(m, cut(m, x, depth >= 1, "x_in"), n_in, name="products", isolate=depth >= 4)
        total = cut(m, products.sum(), depth >= 2, "total")
        dot = stage(m, quantize_cut(m, total, cfg.dot, cfg.rounding, "saturate", depth >= 3, "dot_round", depth >= 4),
                    "dot")
        if cfg.variant in ("d1", "d2") and cfg.h == "sum":
            dot = dot << 1  # the paper's 2V (2L); "mean" halves it away
        p = stage(m, quantize_cut(m, product(m, n_in, dot, name="np", isolate=depth >= 4), cfg.out, cfg.rounding, "saturate",
                                  depth >= 3, "p_round", depth >= 4), "p")
        return {"p": p, "q": q.at(p.cycle), "valid": delay(m, valid, p.cycle - h.cycle, "valid")}
