"""Lyon's Figure 7 datapath as one pipelined component."""

from ..config import Fig7Config
from .block import PipelinedBlock
from .difference import Difference
from .diffuse import Diffuse
from .fixed import delay
from .lirp import Lirp
from .normalize import Normalize
from .reflect import Reflect
from .shape import Shape

__all__ = ["Fig7"]


class Fig7(PipelinedBlock):
    """LIRP → normalizer → reflect → difference/x → shape, plus diffuse (Lyon 1993, Figure 7a–d).

    The blocks that depend on ``L`` (difference, shape, diffuse) are repeated for
    each of ``config.lights`` lights, as the paper notes.  ``V``, ``L`` and ``n``
    are delayed to meet ``N`` and ``R`` where they are used; the diffuse result is
    delayed to leave with the specular one.

    Latency: ``lirp + normalize + reflect + difference + shape`` (the diffuse
    branch, ``lirp + normalize + diffuse``, is padded to match).
    """

    config_class = Fig7Config

    def __init__(self, config):
        super().__init__(config)
        c = config
        self._lirp, self._normalize, self._reflect = Lirp(c.lirp), Normalize(c.normalize), Reflect(c.reflect)
        self._difference = [Difference(c.difference) for _ in range(c.lights)]
        self._shape = [Shape(c.shape) for _ in range(c.lights)]
        self._diffuse = [Diffuse(c.diffuse) for _ in range(c.lights)]
        for sub in (self._lirp, self._normalize, self._reflect, *self._difference, *self._shape,
                    *self._diffuse):
            sub._MustUse__silence = True  # owned by this block: only an unused Fig7 should warn

    @property
    def _to_normal(self):
        return self._lirp.latency + self._normalize.latency

    @property
    def _to_reflection(self):
        return self._to_normal + self._reflect.latency

    @property
    def latency(self):
        return self._to_reflection + self._difference[0].latency + self._shape[0].latency

    def datapath(self, m, i):
        m.submodules.lirp, m.submodules.normalize = self._lirp, self._normalize
        m.submodules.reflect = self._reflect
        self._lirp.feed(m, self.i.valid, {"n0": i["n0"], "n1": i["n1"], "a": i["a"]})
        self._normalize.feed(m, self._lirp.o.valid, self._lirp.results())
        normal = self._normalize.results()["n"]
        v = delay(m, i["v"], self._to_normal, "v")
        self._reflect.feed(m, self._normalize.o.valid, {"n": normal, "v": v})
        r = self._reflect.results()["r"]
        n = delay(m, i["n"], self._to_reflection, "n")
        out = {}
        for index in range(self.config.lights):
            difference, shape, diffuse = self._difference[index], self._shape[index], self._diffuse[index]
            m.submodules[f"difference{index}"] = difference
            m.submodules[f"shape{index}"] = shape
            m.submodules[f"diffuse{index}"] = diffuse
            l = i[f"l{index}"]
            difference.feed(m, self._reflect.o.valid,
                            {"r": r, "l": delay(m, l, self._to_reflection, f"l{index}_r"), "n": n})
            shape.feed(m, difference.o.valid, difference.results())
            out[f"spec{index}"] = shape.results()["spec"]
            diffuse.feed(m, self._normalize.o.valid,
                         {"n": normal, "l": delay(m, l, self._to_normal, f"l{index}_n")})
            pad = self.latency - self._to_normal - diffuse.latency
            if pad < 0:
                raise ValueError(f"the diffuse branch ({diffuse.latency} cycles) must not be "
                                 f"slower than reflect + difference + shape")
            out[f"diff{index}"] = delay(m, diffuse.results()["diff"], pad, f"diff{index}")
        out["valid"] = self._shape[0].o.valid
        return out
