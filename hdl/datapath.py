"""A whole shading datapath as one pipelined component (Lyon 1993, Figures 6–8 and 5)."""

from phongfx.config import DatapathConfig
from phongfx.core.methods import get_method

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

__all__ = ["Datapath", "SpecularUnit", "ReflectedUnit", "Fig7Unit", "Fig8Unit", "HalfwayUnit"]


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
        self._unit = get_method(c.specular).load("component")(c)
        self._diffuse = [Diffuse(c.diffuse) for _ in range(c.lights)]
        for sub in self._subs():
            unbuilt(sub)  # owned by this block: only an unused Datapath should warn

    def _subs(self):
        yield from (block for front in self._fronts.values() for block in front[:2])
        yield from self._unit.subs()
        yield from self._diffuse

    @property
    def _front(self):
        return max(lirp.latency + norm.latency for lirp, norm, _, _ in self._fronts.values())

    @property
    def latency(self):
        return self._front + self._unit.latency

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
        shared = self._unit.feed_shared(m, valid, normal, view)
        # a constant shininess (c.shininess None) lives in the unit's own config: no port
        side = {}
        if c.shininess is not None:
            name = c.shininess[0]
            side[name] = delay(m, i[name], self._front + self._unit.shared_latency, name)
        out = {}
        for index, diffuse in enumerate(self._diffuse):
            light = vectors[f"l{index}"]
            out[f"spec{index}"] = self._unit.feed_light(m, index, shared, valid, normal, view, light, side)
            diffuse.feed(m, valid, {"n": normal, "l": light})
            pad = self.latency - self._front - diffuse.latency
            if pad < 0:
                raise ValueError(f"the diffuse branch ({diffuse.latency} cycles) must not be "
                                 f"slower than the specular unit")
            out[f"diff{index}"] = delay(m, diffuse.results()["diff"], pad, f"diff{index}")
        out["valid"] = self._unit.valid
        return out


class SpecularUnit:
    """A specular unit's hardware inside :class:`Datapath` (its method's ``component`` face):
    ``shared`` blocks computed once for every light (the reflected R), then per light the
    blocks of ``lanes[index]``, the first fed by :meth:`feed_light`, each next one by the one
    before, the last one's ``spec_port`` the light's ``spec``.  Latency: the shared blocks'
    and one lane's."""

    spec_port = "spec"

    def __init__(self, config, shared, lanes):
        self.config, self.shared, self.lanes = config, shared, lanes

    def subs(self):
        yield from self.shared
        yield from (block for lane in self.lanes for block in lane)

    @property
    def shared_latency(self):
        return sum(block.latency for block in self.shared)

    @property
    def latency(self):
        return self.shared_latency + sum(block.latency for block in self.lanes[0])

    def feed_shared(self, m, valid, normal, view):
        """Feed the shared blocks; returns what :meth:`feed_light` takes of them."""
        return None

    def feed_light(self, m, index, shared, valid, normal, view, light, side):
        """Feed light ``index``'s lane (``side``: the shininess ports, delayed to the lane's
        input); returns its ``spec`` signal."""
        lane = self.lanes[index]
        lane[0].feed(m, *self.first(m, shared, valid, normal, view, light, side))
        for before, block in zip(lane, lane[1:]):
            block.feed(m, before.o.valid, before.results())
        return lane[-1].results()[self.spec_port]

    def first(self, m, shared, valid, normal, view, light, side):
        """``(valid, inputs)`` of a lane's first block."""
        raise NotImplementedError

    @property
    def valid(self):
        return self.lanes[0][-1].o.valid


class ReflectedUnit(SpecularUnit):
    """Figures 7 and 8: R = reflect(N, V) shared by every light's lane, which takes R and L."""

    def feed_shared(self, m, valid, normal, view):
        reflect, = self.shared
        reflect.feed(m, valid, {"n": normal, "v": view})
        return reflect.results()["r"], reflect.o.valid

    def first(self, m, shared, valid, normal, view, light, side):
        r, r_valid = shared
        return r_valid, {"r": r, "l": delay(m, light, self.shared_latency), **side}


class Fig7Unit(ReflectedUnit):
    """Figure 7b–d: reflect → difference/x → shape."""

    def __init__(self, c):
        super().__init__(c, [Reflect(c.reflect)],
                         [[Difference(c.difference), Shape(c.shape)] for _ in range(c.lights)])


class Fig8Unit(ReflectedUnit):
    """Figure 8: reflect → root-shininess unit."""

    def __init__(self, c):
        super().__init__(c, [Reflect(c.reflect)], [[Root(c.root)] for _ in range(c.lights)])


class HalfwayUnit(SpecularUnit):
    """Figure 5: halfway difference vector → difference/x (shininess scaled by
    ``2^halfway_shift``, free wiring) → shape."""

    def __init__(self, c):
        super().__init__(c, [], [[Halfway(c.halfway), Difference(c.difference), Shape(c.shape)]
                                 for _ in range(c.lights)])

    def feed_light(self, m, index, shared, valid, normal, view, light, side):
        head, difference, shape = self.lanes[index]
        head.feed(m, valid, {"n": normal, "l": light, "v": view})
        scaled = {name: delay(m, value, head.latency).shift(self.config.halfway_shift)
                  for name, value in side.items()}
        d = head.results()
        difference.feed(m, head.o.valid, {"r": d["p"], "l": d["q"], **scaled})
        shape.feed(m, difference.o.valid, difference.results())
        return shape.results()["spec"]
