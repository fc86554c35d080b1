"""Configuration of a whole shading datapath: Lyon's Figures 7, 8 and 5 as one record."""

from dataclasses import dataclass, replace

from phongfx.core.format import Format
from phongfx.core.methods import get_method, specular_units

from .base import MAX_VEC_FRAC, BlockConfig, check_int
from .difference import DifferenceConfig
from .diffuse import DiffuseConfig
from .halfway import HalfwayConfig
from .lirp import LirpConfig
from .normalize import NormalizeConfig
from .reflect import ReflectConfig
from .root import RootConfig
from .shape import ShapeConfig

__all__ = ["DatapathConfig", "SPECULAR_UNITS", "fig7_config", "fig8_config", "halfway_config"]

#: The specular units registered when this module was imported (Lyon's three);
#: :func:`phongfx.core.methods.specular_units` lists every registered one, a unit added
#: to the method registry later included, and is what ``specular`` is checked against.
SPECULAR_UNITS = specular_units()


@dataclass(frozen=True)
class DatapathConfig(BlockConfig):
    """A whole shading datapath (Lyon 1993, Figures 6–8 and 5): interpolated, approximately
    normalized N, then one specular unit and the diffuse term, for ``lights`` lights.

    ``specular`` picks the unit after the normalizer, a method of
    :data:`phongfx.core.methods.METHODS` with a ``unit`` face (:attr:`unit`); Lyon's are

    * ``"fig7"``: reflect → difference/x (``n``) → shape (Figure 7b–d);
    * ``"fig8"``: reflect → root-shininess unit (``m = √n``, Figure 8);
    * ``"halfway"``: halfway difference vector → difference/x with ``4n`` → shape
      (Figure 5; Figure 9 rows 7–10, as the appendix code scales ``n``).

    ``local_lights`` / ``local_viewer``: L / V are interpolated across the span with the
    same ``a`` and approximately normalized (``direction_normalize``, g1 or g2) like N;
    otherwise they are constant inputs and no LIRP or normalizer is built for them.
    ``local_lights`` is one switch for every light (True / False) or a tuple with one per
    light: a point light beside a directional one gets an interpolator and a normalizer,
    the directional one stays a constant input (:meth:`local_light`).
    Blocks that depend on L are repeated per light.  All direction vectors after the
    normalizers share the format ``normalize.out``; connected formats must agree.
    ``replace(vec_frac=12)`` (:meth:`~BlockConfig.with_vec_frac`) sets all of them, with
    their guard bits, from one vector width; :attr:`vec_frac` reads it back.

    ``pipeline`` raises the pipeline depth of every block config to at least its value
    (``fig7_config(pipeline=2)``, ``--set pipeline=2``); a block's own field may go deeper.

    A single shininess is fixed in the unit's own config: ``difference.n_const`` (Figure 7;
    for the halfway unit the scaled ``n·2^halfway_shift``) or ``root.m_const`` (Figure 8).
    Then :attr:`inputs` has no ``n`` / ``m`` port, :attr:`shininess` is None and
    :attr:`shininess_const` gives the constant.
    """

    specular: str = "fig7"
    lirp: LirpConfig = LirpConfig()
    normalize: NormalizeConfig = NormalizeConfig()
    reflect: ReflectConfig = ReflectConfig()
    difference: DifferenceConfig = DifferenceConfig()
    shape: ShapeConfig = ShapeConfig()
    root: RootConfig = RootConfig()
    halfway: HalfwayConfig = HalfwayConfig()
    diffuse: DiffuseConfig = DiffuseConfig()
    lights: int = 2
    local_lights: object = False  # bool, or a tuple of one bool per light
    local_viewer: bool = False
    direction_normalize: NormalizeConfig = NormalizeConfig()
    pipeline: int = 0

    PIPELINED = ("lirp", "normalize", "reflect", "difference", "shape", "root", "halfway",
                 "diffuse", "direction_normalize")
    #: Settings that :meth:`replace` takes besides the fields: each sets several fields at
    #: once (through ``with_NAME``) and is read back as a property, never stored.
    DERIVED_SETTINGS = ("vec_frac",)

    def validate(self):
        for name, cls in (("lirp", LirpConfig), ("normalize", NormalizeConfig),
                          ("reflect", ReflectConfig), ("difference", DifferenceConfig),
                          ("shape", ShapeConfig), ("root", RootConfig), ("halfway", HalfwayConfig),
                          ("diffuse", DiffuseConfig), ("direction_normalize", NormalizeConfig)):
            if not isinstance(getattr(self, name), cls):
                raise TypeError(f"{name} must be a {cls.__name__}, not {getattr(self, name)!r}")
        units = specular_units()
        if self.specular not in units:
            raise ValueError(f"specular must be one of {', '.join(units)}, not {self.specular!r}")
        check_int("lights", self.lights, 1, 8)
        if isinstance(self.local_lights, list):  # a list from a file or --set: a tuple stays hashable
            object.__setattr__(self, "local_lights", tuple(self.local_lights))
        local = self.local_lights
        if isinstance(local, tuple):
            if len(local) != self.lights or not all(isinstance(x, bool) for x in local):
                raise ValueError(f"local_lights must be True, False or {self.lights} of them (one per "
                                 f"light), not {local!r}")
        elif not isinstance(local, bool):
            raise ValueError(f"local_lights must be True or False, not {local!r}")
        if not isinstance(self.local_viewer, bool):
            raise ValueError(f"local_viewer must be True or False, not {self.local_viewer!r}")
        vec = ("normalize.out", self.normalize.out)
        links = [
            ("lirp.out", self.lirp.out, "normalize.vec", self.normalize.vec),
            (*vec, "diffuse.vec", self.diffuse.vec),
        ]
        if self.any_local:
            links += [("lirp.out", self.lirp.out, "direction_normalize.vec", self.direction_normalize.vec),
                      (*vec, "direction_normalize.out", self.direction_normalize.out)]
        unit = self.unit
        links += unit.links(self)
        unit.check(self)
        for a_name, a, b_name, b in links:
            if Format.parse(a) != Format.parse(b):
                raise ValueError(f"{a_name} ({a}) must equal {b_name} ({b}): they are connected")

    @property
    def unit(self):
        """The specular unit's :class:`~phongfx.config.base.SpecularUnit` (its method's
        ``unit`` face in :data:`phongfx.core.methods.METHODS`)."""
        return get_method(self.specular).load("unit")

    @property
    def used(self):
        """Names of the sub-configs the hardware uses: the front (``lirp``, ``normalize``),
        the specular unit's ``parts``, ``diffuse``, and ``direction_normalize`` when L or V
        is interpolated."""
        names = ("lirp", "normalize", *self.unit.parts, "diffuse")
        if self.any_local:
            names += ("direction_normalize",)
        return names

    def local_light(self, index):
        """Whether light ``index`` is interpolated (a point light) rather than a constant input."""
        local = self.local_lights
        return local[index] if isinstance(local, tuple) else local

    @property
    def any_local(self):
        """Whether some light or the viewer is interpolated (``direction_normalize`` is used)."""
        return self.local_viewer or any(self.local_light(i) for i in range(self.lights))

    def replace(self, **changes):
        """This config with fields ``changes``; a derived setting among them
        (:attr:`DERIVED_SETTINGS`, e.g. ``vec_frac=12``) is applied after the fields."""
        derived = {name: changes.pop(name) for name in self.DERIVED_SETTINGS if name in changes}
        config = replace(self, **changes)
        for name, value in derived.items():
            config = getattr(config, f"with_{name}")(value)
        return config

    def vec_frac_changes(self, frac):
        """The sub-configs of :meth:`with_vec_frac`: every connected direction-vector format
        at ``frac`` fraction bits (``1..MAX_VEC_FRAC``).

        Each used sub-config (:attr:`used`) sets the fields of its ``VECTOR_FIELDS``: the
        vectors themselves at ``frac`` and the guard bits the defaults have (the
        normalizer's ``z``, ``y2``, ``g`` and reflect's ``dot`` two more, the halfway unit's
        ``hvec`` one more and ``dot`` two more, ``D·D`` exact at ``2·frac``), integer bits
        kept; at 10 that is the default.  Idle sub-configs are left as they are, so the
        result is exactly the config a sweep of the vector width builds by hand.
        """
        check_int("vec_frac", frac, 1, MAX_VEC_FRAC)
        return {name: getattr(self, name).with_vec_frac(frac) for name in self.used}

    @property
    def vec_frac(self):
        """The vector width :meth:`with_vec_frac` would give this config (``normalize.out``'s
        fraction bits), or None when its connected formats are not that derivation."""
        frac = self.normalize.fmt("out").frac_bits
        if not 1 <= frac <= MAX_VEC_FRAC:
            return None
        return frac if self.with_vec_frac(frac) == self else None

    @property
    def shininess(self):
        """(port name, format, largest value) of the per-pixel shininess input, or None when
        the shininess is a constant of the hardware (:attr:`shininess_const`): no such port.

        The port is ``m = √n`` for Figure 8, else ``n``; for the halfway unit, ``n`` before
        its scaling by ``2^halfway_shift``.
        """
        if self.shininess_const:
            return None
        return self.unit.shininess(self)

    @property
    def shininess_const(self):
        """The shininess fixed in the hardware, in the port's terms (``m`` for Figure 8, else
        ``n``), or 0 when it is a per-pixel input.

        From ``root.m_const`` (Figure 8) or ``difference.n_const`` (Figure 7, halfway).  The
        halfway unit's difference block multiplies by ``n·2^halfway_shift``, so its
        ``n_const`` is that product (validated a multiple of ``2^halfway_shift``): the pixel
        sees ``n = difference.n_const >> halfway_shift``, bit for bit as if fed on the port.
        """
        return self.unit.shininess_const(self)

    @property
    def halfway_shift(self):
        """log2 of the shininess scale into the halfway unit's difference block.

        The appendix uses ``4n`` with ``H = (L+V)/2`` (``h="mean"``), whose difference
        vectors are half as long as with ``H = V + L``: ``x = (4n/2)|D/2|²`` equals
        ``(n/2)|D|²``.  So ``h="mean"`` shifts ``n`` by 2 (free wiring), ``h="sum"`` by 0.
        """
        return 2 if self.halfway.h == "mean" else 0

    @property
    def inputs(self):
        vec, end = self.normalize.fmt("out"), self.lirp.fmt("vec")
        ports = {"n0": (end, 3), "n1": (end, 3), "a": (self.lirp.fmt("a"), 1)}
        if self.shininess is not None:
            name, fmt, _ = self.shininess
            ports[name] = (fmt, 1)
        if self.local_viewer:
            ports.update({"v0": (end, 3), "v1": (end, 3)})
        else:
            ports["v"] = (vec, 3)
        for i in range(self.lights):
            ports.update({name: (end if self.local_light(i) else vec, 3) for name in self.light_inputs(i)})
        return ports

    def light_inputs(self, index):
        """The input ports of light ``index``: its span ends ``l<i>_0``, ``l<i>_1`` when it is
        interpolated, else its constant ``l<i>``; every other input is the same for all lights."""
        return (f"l{index}_0", f"l{index}_1") if self.local_light(index) else (f"l{index}",)

    @property
    def outputs(self):
        t = self.unit.spec_format(self)
        ports = {f"spec{i}": (t, 1) for i in range(self.lights)}
        ports.update({f"diff{i}": (self.diffuse.fmt("out"), 1) for i in range(self.lights)})
        return ports


def fig7_config(**changes):
    """Lyon's Figure 7 datapath (the default :class:`DatapathConfig`)."""
    return DatapathConfig(specular="fig7", **changes)


def fig8_config(**changes):
    """Figure 8: the root-shininess unit after reflect (``k = 1``, ``m = √n``)."""
    return DatapathConfig(specular="fig8", **changes)


def halfway_config(**changes):
    """A halfway-vector datapath (default: Lyon's row 8, ``g2proj``, ``k = 2``, ``4n``)."""
    changes.setdefault("difference", DifferenceConfig(vec="S2.10", n="15.0", n_max=32000))
    return DatapathConfig(specular="halfway", **changes)
