"""A whole shading datapath as one pipelined component (Lyon 1993, Figures 6–8 and 5)."""

from phongfx.config import DatapathConfig

from .block import PipelinedBlock, unbuilt
from .difference import Difference
from .diffuse import Diffuse
from .fixed import delay
from .halfway import Halfway
from .lirp import Lirp
from .normalize import Normalize
from .reflect import Reflect
from .root import Root
from .shape import Shape

__all__ = ["Datapath"]


class Datapath(PipelinedBlock):
    """Interpolated N (and L, V when local) → specular unit → spec, plus diffuse, per light.

    Only the blocks the configuration needs are built: with lights and viewer at
    infinity there is one LIRP and one normalizer (for N); each local light and a
    local viewer add their own pair.  ``specular`` picks reflect → difference → shape
    (Figure 7), reflect → root (Figure 8), or halfway → difference (4n with H = (L+V)/2) → shape
    (Figure 5).  Blocks depending on L are repeated per light.  Side inputs are
    delayed to meet the data where it is used; diffuse is padded to leave with spec.

    Latency: ``front + specular``, where ``front = lirp + normalize`` (the slower of
    the N and L/V fronts) and ``specular`` is ``reflect + difference + shape``,
    ``reflect + root`` or ``halfway + difference + shape``, each block's latency at its
    own pipeline depth (``DatapathConfig.pipeline`` sets them all at once: 17, 25, 34, 43
    cycles for Figure 7 and 15, 22, 31, 37 for Figure 8 at depths 0–3).  Side inputs
    wait by the cycle tags of :mod:`phongfx.hdl.fixed`, so any depth lines up.

    A constant shininess (``difference.n_const``, ``root.m_const``; see
    :attr:`~phongfx.config.DatapathConfig.shininess_const`) removes the ``n`` / ``m``
    port and its delay line; the unit multiplies by the constant, in the same cycles.
    """

    config_class = DatapathConfig

    def __init__(self, config):
        super().__init__(config)
        c = config
        # vector -> (LIRP, normalizer, span-start port, span-end port)
        self._fronts = {"n": (Lirp(c.lirp), Normalize(c.normalize), "n0", "n1")}
        if c.local_viewer:
            self._fronts["v"] = (Lirp(c.lirp), Normalize(c.direction_normalize), "v0", "v1")
        for index in (i for i in range(c.lights) if c.local_light(i)):
            self._fronts[f"l{index}"] = (Lirp(c.lirp), Normalize(c.direction_normalize),
                                         f"l{index}_0", f"l{index}_1")
        self._reflect = Reflect(c.reflect) if c.specular in ("fig7", "fig8") else None
        self._units = [self._specular_unit() for _ in range(c.lights)]
        self._diffuse = [Diffuse(c.diffuse) for _ in range(c.lights)]
        for sub in self._subs():
            unbuilt(sub)  # owned by this block: only an unused Datapath should warn

    def _specular_unit(self):
        c = self.config
        if c.specular == "fig8":
            return [Root(c.root)]
        head = [Halfway(c.halfway)] if c.specular == "halfway" else []
        return head + [Difference(c.difference), Shape(c.shape)]

    def _subs(self):
        yield from (block for front in self._fronts.values() for block in front[:2])
        if self._reflect is not None:
            yield self._reflect
        yield from (block for unit in self._units for block in unit)
        yield from self._diffuse

    @property
    def _front(self):
        return max(lirp.latency + norm.latency for lirp, norm, _, _ in self._fronts.values())

    @property
    def _to_unit(self):
        """Cycles from the input to the per-light unit's input."""
        return self._front + (self._reflect.latency if self._reflect is not None else 0)

    @property
    def latency(self):
        return self._to_unit + sum(block.latency for block in self._units[0])

    def datapath(self, m, i):
        c = self.config
        for index, sub in enumerate(self._subs()):
            m.submodules[f"{type(sub).__name__.lower()}{index}"] = sub
        vectors = {}
        for name, (lirp, norm, start, end) in self._fronts.items():
            lirp.feed(m, self.i.valid, {"n0": i[start], "n1": i[end], "a": i["a"]})
            norm.feed(m, lirp.o.valid, lirp.results())
            vectors[name] = delay(m, norm.results()["n"], self._front - lirp.latency - norm.latency, name)
        for name in ["v"] + [f"l{index}" for index in range(c.lights)]:
            if name not in vectors:
                vectors[name] = delay(m, i[name], self._front, name)
        lirp, norm = self._fronts["n"][:2]
        valid = delay(m, norm.o.valid, self._front - lirp.latency - norm.latency, "front_valid")
        normal, view = vectors["n"], vectors["v"]
        if self._reflect is not None:
            self._reflect.feed(m, valid, {"n": normal, "v": view})
            r, unit_valid = self._reflect.results()["r"], self._reflect.o.valid
        # a constant shininess (c.shininess None) lives in the unit's own config: no port
        side = {}
        if c.shininess is not None:
            name = c.shininess[0]
            side[name] = delay(m, i[name], self._to_unit, name)
        out = {}
        for index, (unit, diffuse) in enumerate(zip(self._units, self._diffuse)):
            light = vectors[f"l{index}"]
            if c.specular in ("fig7", "fig8"):
                unit[0].feed(m, unit_valid, {"r": r, "l": delay(m, light, self._reflect.latency),
                                             **side})
            else:
                unit[0].feed(m, valid, {"n": normal, "l": light, "v": view})
                scaled = {name: delay(m, value, unit[0].latency).shift(c.halfway_shift)
                          for name, value in side.items()}
                d = unit[0].results()
                unit[1].feed(m, unit[0].o.valid, {"r": d["p"], "l": d["q"], **scaled})
            if c.specular != "fig8":
                unit[-1].feed(m, unit[-2].o.valid, unit[-2].results())
            out[f"spec{index}"] = unit[-1].results()["spec"]
            diffuse.feed(m, valid, {"n": normal, "l": light})
            pad = self.latency - self._front - diffuse.latency
            if pad < 0:
                raise ValueError(f"the diffuse branch ({diffuse.latency} cycles) must not be "
                                 f"slower than the specular unit")
            out[f"diff{index}"] = delay(m, diffuse.results()["diff"], pad, f"diff{index}")
        out["valid"] = self._units[0][-1].o.valid
        return out
