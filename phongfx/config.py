"""Datapath configurations: plain data saying which formats each block uses.

A configuration is a frozen dataclass of format strings (Lyon's ``n.m`` / ``Sn.m``),
integers and names.  It is validated when built, so both the golden function and the
Amaranth component of a block see only sound parameters, and it declares the block's
ports (:attr:`BlockConfig.inputs`, :attr:`BlockConfig.outputs`): name -> (format,
lanes), lanes being 3 for an X, Y, Z vector.  The golden model, the component's
payload layouts and the checking harness all take port widths from there.

The default formats are our reconstruction of Lyon's Figure 7, whose bit annotations
are lost from our copy; each block's docstring says why each default was chosen.
"""

from dataclasses import dataclass, fields, replace

from .format import Format, check_rounding

__all__ = [
    "BlockConfig", "LirpConfig", "NormalizeConfig", "ReflectConfig", "DifferenceConfig",
    "ShapeConfig", "DiffuseConfig", "Fig7Config",
]


def _fmt(name, value, *, signed=None, holds_one=False):
    try:
        fmt = Format.parse(value)
    except (TypeError, ValueError) as error:
        raise ValueError(f"{name}: {error}") from None
    if signed is True and not fmt.signed:
        raise ValueError(f"{name} must be a signed format (Sn.m), not {fmt}")
    if signed is False and fmt.signed:
        raise ValueError(f"{name} must be an unsigned format (n.m), not {fmt}")
    if holds_one and not fmt.holds_one():
        raise ValueError(f"{name} must hold exactly 1.0 (at least 1 integer bit), not {fmt}")
    return fmt


def _int(name, value, lo, hi):
    if not isinstance(value, int) or isinstance(value, bool) or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in {lo}..{hi}, not {value!r}")
    return value


@dataclass(frozen=True)
class BlockConfig:
    """Base of block configurations: validation hook and port declarations.

    Leaf blocks carry a ``rounding`` field: the rounding of every quantize in the
    block that drops fraction bits.
    """

    def __post_init__(self):
        if hasattr(self, "rounding"):
            check_rounding(self.rounding)
        self.validate()

    def validate(self):
        pass

    def fmt(self, name):
        """The :class:`Format` of the string field ``name``."""
        return Format.parse(getattr(self, name))

    def replace(self, **changes):
        return replace(self, **changes)

    def as_dict(self):
        return {f.name: getattr(self, f.name) for f in fields(self)}

    @property
    def inputs(self):
        raise NotImplementedError

    @property
    def outputs(self):
        raise NotImplementedError


@dataclass(frozen=True)
class LirpConfig(BlockConfig):
    """Figure 7a linear interpolator ``N' = (1-a)·N0 + a·N1``."""

    vec: str = "S1.10"
    a: str = "1.10"
    out: str = "S1.10"
    rounding: str = "round_half_up"

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _fmt("a", self.a, signed=False, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def inputs(self):
        return {"n0": (self.fmt("vec"), 3), "n1": (self.fmt("vec"), 3), "a": (self.fmt("a"), 1)}

    @property
    def outputs(self):
        return {"n": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class NormalizeConfig(BlockConfig):
    """Figure 7a approximate normalizer ``N = g(N'·N')·N'`` with ``g1`` or ``g2``."""

    vec: str = "S1.10"
    order: int = 2
    z: str = "1.12"
    y2: str = "1.12"
    g: str = "1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _int("order", self.order, 1, 2)
        _fmt("z", self.z, signed=False, holds_one=True)
        _fmt("y2", self.y2, signed=False, holds_one=True)
        _fmt("g", self.g, signed=False, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def y2_overflow(self):
        """Overflow policy of the ``y²`` quantize: ``"error"`` where it provably cannot overflow.

        ``z`` saturates below 2 when it has one integer bit, so ``y > -1`` and
        ``y² <= 1``, which ``y2`` holds by validation.  A wider ``z`` lets junk
        reach ``y = 1 - 2**int_bits`` and ``y²`` well past 1: saturate there.
        """
        return "error" if self.fmt("z").int_bits == 1 else "saturate"

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"n": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class ReflectConfig(BlockConfig):
    """Figure 7b reflection ``R = 2(N·V)N - V``."""

    vec: str = "S1.10"
    dot: str = "S1.12"
    out: str = "S1.10"
    rounding: str = "round_half_up"

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _fmt("dot", self.dot, signed=True, holds_one=True)
        _fmt("out", self.out, signed=True)

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3), "v": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"r": (self.fmt("out"), 3)}


@dataclass(frozen=True)
class DifferenceConfig(BlockConfig):
    """Figure 7c difference vector and ``2x = n·D·D``; ``n`` is an integer ``1..n_max``."""

    vec: str = "S1.10"
    d: str = "S1.10"
    dd: str = "2.20"
    n: str = "13.0"
    n_max: int = 8000
    x2: str = "13.12"
    rounding: str = "round_half_up"

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _fmt("d", self.d, signed=True)
        _fmt("dd", self.dd, signed=False)
        n = _fmt("n", self.n, signed=False)
        if n.frac_bits:
            raise ValueError(f"n must be an integer format (m = 0), not {n}")
        _int("n_max", self.n_max, 1, n.max_raw)
        _fmt("x2", self.x2, signed=False)

    @property
    def inputs(self):
        return {"r": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3), "n": (self.fmt("n"), 1)}

    @property
    def outputs(self):
        return {"x2": (self.fmt("x2"), 1)}


@dataclass(frozen=True)
class ShapeConfig(BlockConfig):
    """Figure 7d shape function ``f_k(x) = (1 - x/2^k)^(2^k)``, zero for ``x/2^k >= 1``."""

    x2: str = "13.12"
    k: int = 2
    t: str = "1.15"
    rounding: str = "round_half_up"

    def validate(self):
        x2 = _fmt("x2", self.x2, signed=False)
        _int("k", self.k, 0, 4)
        if x2.int_bits < self.k + 2:
            raise ValueError(f"x2 must have at least k+2 = {self.k + 2} integer bits so that "
                             f"x/2^k reaches 1, not {x2}")
        _fmt("t", self.t, signed=False, holds_one=True)

    @property
    def inputs(self):
        return {"x2": (self.fmt("x2"), 1)}

    @property
    def outputs(self):
        return {"spec": (self.fmt("t"), 1)}


@dataclass(frozen=True)
class DiffuseConfig(BlockConfig):
    """Diffuse ``max(N·L, 0)`` (the backside test zeroes it)."""

    vec: str = "S1.10"
    out: str = "1.10"
    rounding: str = "round_half_up"

    def validate(self):
        _fmt("vec", self.vec, signed=True)
        _fmt("out", self.out, signed=False, holds_one=True)

    @property
    def inputs(self):
        return {"n": (self.fmt("vec"), 3), "l": (self.fmt("vec"), 3)}

    @property
    def outputs(self):
        return {"diff": (self.fmt("out"), 1)}


@dataclass(frozen=True)
class Fig7Config(BlockConfig):
    """Lyon's Figure 7 datapath: LIRP -> normalizer -> reflect -> difference/x -> shape,
    plus diffuse, for ``lights`` lights at infinity and a viewer at infinity.

    Blocks that depend on L (difference, shape, diffuse) are repeated per light;
    the sub-configs must agree on the formats where they connect.
    """

    lirp: LirpConfig = LirpConfig()
    normalize: NormalizeConfig = NormalizeConfig()
    reflect: ReflectConfig = ReflectConfig()
    difference: DifferenceConfig = DifferenceConfig()
    shape: ShapeConfig = ShapeConfig()
    diffuse: DiffuseConfig = DiffuseConfig()
    lights: int = 2

    def validate(self):
        for name, cls in (("lirp", LirpConfig), ("normalize", NormalizeConfig),
                          ("reflect", ReflectConfig), ("difference", DifferenceConfig),
                          ("shape", ShapeConfig), ("diffuse", DiffuseConfig)):
            if not isinstance(getattr(self, name), cls):
                raise TypeError(f"{name} must be a {cls.__name__}, not {getattr(self, name)!r}")
        _int("lights", self.lights, 1, 8)
        links = (
            ("lirp.out", self.lirp.out, "normalize.vec", self.normalize.vec),
            ("normalize.out", self.normalize.out, "reflect.vec", self.reflect.vec),
            ("reflect.out", self.reflect.out, "difference.vec", self.difference.vec),
            ("normalize.out", self.normalize.out, "diffuse.vec", self.diffuse.vec),
            ("difference.vec", self.difference.vec, "diffuse.vec", self.diffuse.vec),
            ("difference.x2", self.difference.x2, "shape.x2", self.shape.x2),
        )
        for a_name, a, b_name, b in links:
            if Format.parse(a) != Format.parse(b):
                raise ValueError(f"{a_name} ({a}) must equal {b_name} ({b}): they are connected")

    @property
    def inputs(self):
        ports = {
            "n0": (self.lirp.fmt("vec"), 3), "n1": (self.lirp.fmt("vec"), 3),
            "a": (self.lirp.fmt("a"), 1), "n": (self.difference.fmt("n"), 1),
            "v": (self.reflect.fmt("vec"), 3),
        }
        ports.update({f"l{i}": (self.difference.fmt("vec"), 3) for i in range(self.lights)})
        return ports

    @property
    def outputs(self):
        ports = {f"spec{i}": (self.shape.fmt("t"), 1) for i in range(self.lights)}
        ports.update({f"diff{i}": (self.diffuse.fmt("out"), 1) for i in range(self.lights)})
        return ports
