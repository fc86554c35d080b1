"""Halfway-vector difference component, Lyon (1993) Figure 5 and Figure 9 rows 7–10."""

from ..config import HalfwayConfig
from .block import PipelinedBlock
from .fixed import delay, stage
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

    Latency: ``front + 4`` for d1, d2, d3, g2proj (products; the rounded dot; products
    ``dot × N_i``; the rounded ``p``) and ``front + 1`` for g2 (the rounded ``q``), where
    ``front`` is the normalizer's latency (4) for g2proj and g2 and 0 otherwise: 4, 4,
    4, 8, 5 at the defaults.  ``N`` and ``q`` are delayed to meet ``p``; ``valid`` follows
    the normalizer's own.

    Ports: ``i.payload`` = ``n``, ``l``, ``v`` (3 × ``config.vec``);
    ``o.payload`` = ``p``, ``q`` (3 × ``config.out``).
    """

    config_class = HalfwayConfig

    def __init__(self, config):
        super().__init__(config)
        self._normalize = None
        if config.variant in ("g2proj", "g2"):
            self._normalize = Normalize(config.normalize)
            self._normalize._MustUse__silence = True  # owned here: only an unused Halfway should warn

    @property
    def _front(self):
        return self._normalize.latency if self._normalize is not None else 0

    @property
    def latency(self):
        return self._front + (1 if self.config.variant == "g2" else 4)

    def datapath(self, m, i):
        cfg = self.config
        n, l, v = i["n"], i["l"], i["v"]
        h = v + l
        if cfg.h == "mean":
            h = h.shift(-1)
        h = h.quantize(cfg.hvec, cfg.rounding, "saturate")
        valid = self.i.valid
        if self._normalize is not None:
            m.submodules.normalize = self._normalize
            self._normalize.feed(m, self.i.valid, {"n": h})
            # the normalizer's valid pipeline serves this block too: no second one
            h, valid = self._normalize.results()["n"], self._normalize.o.valid
            n = delay(m, n, self._front, "n_front")
        # rounded before waiting for p: its registers hold out's bits, not hvec's
        q = h.quantize(cfg.out, cfg.rounding, "saturate")
        if cfg.variant == "g2":
            # N waits in vec and widens to out (exactly) at the port
            p = delay(m, n, 1, "p").quantize(cfg.out, cfg.rounding, "saturate")
            return {"p": p, "q": stage(m, q, "q"), "valid": delay(m, valid, 1, "valid")}
        products = stage(m, {"d1": v, "d2": l}.get(cfg.variant, h) * n, "products")
        dot = stage(m, products.sum().quantize(cfg.dot, cfg.rounding, "saturate"), "dot")
        if cfg.variant in ("d1", "d2") and cfg.h == "sum":
            dot = dot << 1  # the paper's 2V (2L); "mean" halves it away
        p = stage(m, delay(m, n, 2, "n") * dot, "np")
        return {"p": stage(m, p.quantize(cfg.out, cfg.rounding, "saturate"), "p"),
                "q": delay(m, q, 4, "q"), "valid": delay(m, valid, 4, "valid")}
