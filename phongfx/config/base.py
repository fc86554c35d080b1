"""The shared base of block configurations and the field checks they all use.

A block configuration is a frozen dataclass of format strings (Lyon's ``n.m`` / ``Sn.m``,
Apple TR #43), integers and names.  :class:`BlockConfig` validates it when it is built:
the ``rounding`` and ``pipeline`` fields wherever a class has them, then the class's own
:meth:`~BlockConfig.validate`, which uses the checks of this module.  It resolves the
class's port declarations (:attr:`~BlockConfig.INPUTS`, :attr:`~BlockConfig.OUTPUTS`)
into formats, and sets the class's direction-vector formats from one vector width
(:attr:`~BlockConfig.VECTOR_FIELDS`, :meth:`~BlockConfig.with_vec_frac`).
"""

from dataclasses import dataclass, fields, replace

from phongfx.core.format import Format, check_rounding
from phongfx.core.limits import MAX_VEC_FRAC

__all__ = ["BlockConfig", "ConstantShininess", "SpecularUnit", "floor_sqrt", "MAX_PIPELINE", "MAX_VEC_FRAC", "check_int", "check_format",
           "check_integer_format", "check_fraction_format", "check_step_formats"]

#: Deepest ``pipeline`` of a block (:class:`BlockConfig`).
MAX_PIPELINE = 4



def check_int(name, value, lo, hi):
    """``value`` if it is an integer in ``lo..hi`` (a bool is not), else ValueError."""
    if not isinstance(value, int) or isinstance(value, bool) or not lo <= value <= hi:
        raise ValueError(f"{name} must be an integer in {lo}..{hi}, not {value!r}")
    return value


def check_format(name, value, *, signed=None, holds_one=False):
    """The :class:`Format` of the field ``name`` (``value`` a format string): signed or
    unsigned if ``signed`` says so, with room for exactly 1.0 if ``holds_one``."""
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


def check_integer_format(name, value):
    """An unsigned integer format ``n.0`` (a shininess, for instance)."""
    fmt = check_format(name, value, signed=False)
    if fmt.frac_bits:
        raise ValueError(f"{name} must be an integer format (m = 0), not {fmt}")
    return fmt


def check_fraction_format(name, value):
    """An unsigned fraction-only format ``0.m`` (a value in ``[0, 1)``)."""
    fmt = check_format(name, value, signed=False)
    if fmt.int_bits:
        raise ValueError(f"{name} must be a fraction-only format (0.m), not {fmt}")
    return fmt


def check_step_formats(config, names):
    """Signed register formats whose fraction bits never fall along the adder chain
    ``names`` (each added into the next), so the recurrence adds exactly."""
    fmts = [check_format(name, getattr(config, name), signed=True) for name in names]
    for (a, fa), (b, fb) in zip(zip(names, fmts), zip(names[1:], fmts[1:])):
        if fa.frac_bits > fb.frac_bits:
            raise ValueError(f"{a} ({fa}) may not have more fraction bits than {b} ({fb}): "
                             f"{a} is added into {b} exactly")


@dataclass(frozen=True)
class BlockConfig:
    """Base of block configurations: the shared checks, port declarations, vector width.

    Leaf blocks carry a ``rounding`` field: the rounding of every quantize in the
    block that drops fraction bits.  The blocks of Lyon's datapaths also carry
    ``pipeline`` (``0..MAX_PIPELINE``, default 0): the depth of pipelining, so that a
    datapath takes one pixel per clock at a higher clock rate for more registers and
    latency.  0 is the original design; 1 registers every multiplier's inputs
    and outputs; 2 also cuts the carry chains, so that no stage holds more than one
    multiplier or one long carry chain; 3 also puts a register between each
    saturating quantize's rounding adder and its clamp; 4 also registers every multiplier's
    inputs and product once more, so that a DSP (an ECP5 MULT18X18D, whose own registers
    take the ones around it) meets only registers, and clamps by bit tests instead of
    comparators.  Only the latency changes with it (each component's docstring gives the
    formula); the function does not.  Both fields are checked here, for every class that
    has them.

    A class declares its ports in :attr:`INPUTS` and :attr:`OUTPUTS` and overrides
    :attr:`inputs` only where a port is conditional.
    """

    #: Input ports: name -> (format field name, or a fixed :class:`Format`; lanes), lanes
    #: being 3 for an X, Y, Z vector.  The golden model, the component's payload layouts
    #: and the checking harness all take port widths from the resolved :attr:`inputs`.
    INPUTS = None
    #: Output ports, declared as :attr:`INPUTS`.
    OUTPUTS = None
    #: The output ports a shading unit's picture is made of: part (``"diff"``, ``"spec"``) ->
    #: output port, read as an intensity by :func:`phongfx.scene.span_inputs.decode`; empty
    #: for a block that is not a whole unit.
    SHADES = {}
    #: Sub-config fields whose ``pipeline`` is raised to at least this config's own.
    PIPELINED = ()
    #: Direction-vector format fields: name -> (scale, guard), set by :meth:`with_vec_frac`
    #: to ``scale·f + guard`` fraction bits (integer bits and sign kept).
    VECTOR_FIELDS = {}

    def __post_init__(self):
        # a composite's depth is checked before its sub-configs are rebuilt with it, a
        # leaf's after its rounding: the first error named is the one it always was
        if self.PIPELINED:
            self._inherit_pipeline(check_int("pipeline", self.pipeline, 0, MAX_PIPELINE))
        if hasattr(self, "rounding"):
            check_rounding(self.rounding)
        if hasattr(self, "pipeline") and not self.PIPELINED:
            check_int("pipeline", self.pipeline, 0, MAX_PIPELINE)
        self.validate()

    def _inherit_pipeline(self, depth):
        # a sub-config of the wrong type is left for validate to name
        for name in self.PIPELINED:
            sub = getattr(self, name)
            if isinstance(sub, BlockConfig) and getattr(sub, "pipeline", depth) < depth:
                object.__setattr__(self, name, replace(sub, pipeline=depth))

    def validate(self):
        pass

    def fmt(self, name):
        """The :class:`Format` of the string field ``name``."""
        return Format.parse(getattr(self, name))

    def replace(self, **changes):
        return replace(self, **changes)

    def frac_changes(self, **fracs):
        """The field changes that put the format fields ``fracs`` (name -> fraction bits) at
        those fraction bits, their integer bits and sign kept: a width in the config's own
        terms (``shape.frac_changes(t=12)`` is ``{"t": "1.12"}`` from ``t = "1.15"``)."""
        changes = {}
        for name, frac in fracs.items():
            fmt = self.fmt(name)
            changes[name] = str(Format(fmt.int_bits, frac, fmt.signed))
        return changes

    def as_dict(self):
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def ports(self, declared):
        """``{name: (Format, lanes)}`` of a port declaration like :attr:`INPUTS`."""
        return {name: (field if isinstance(field, Format) else self.fmt(field), lanes)
                for name, (field, lanes) in declared.items()}

    @property
    def inputs(self):
        if self.INPUTS is None:
            raise NotImplementedError
        return self.ports(self.INPUTS)

    @property
    def outputs(self):
        if self.OUTPUTS is None:
            raise NotImplementedError
        return self.ports(self.OUTPUTS)

    def vec_frac_changes(self, frac):
        """The field changes of :meth:`with_vec_frac`: every field of :attr:`VECTOR_FIELDS`
        at ``scale·frac + guard`` fraction bits, its integer bits and sign kept."""
        check_int("vec_frac", frac, 1, MAX_VEC_FRAC)
        changes = {}
        for name, (scale, guard) in self.VECTOR_FIELDS.items():
            fmt = self.fmt(name)
            changes[name] = str(Format(fmt.int_bits, scale * frac + guard, fmt.signed))
        return changes

    def with_vec_frac(self, frac):
        """This config with its direction-vector formats at ``frac`` fraction bits and the
        guard bits the defaults have (Lyon's Figure 7 at 10 bits)."""
        changes = self.vec_frac_changes(frac)
        return replace(self, **changes) if changes else self


def floor_sqrt(n):
    """⌊√n⌋ of a non-negative integer, exactly."""
    root = int(n ** 0.5)
    while root * root > n:
        root -= 1
    while (root + 1) * (root + 1) <= n:
        root += 1
    return root


class SpecularUnit:
    """What a :class:`~phongfx.config.DatapathConfig` knows of the specular unit after its
    normalizer: the ``unit`` face of the unit's method (:data:`phongfx.core.methods.METHODS`),
    found in the config module of the unit's own block (``FIG7`` in :mod:`.shape`, ``FIG8`` in
    :mod:`.root`, ``HALFWAY`` in :mod:`.halfway`).  ``parts``: the datapath sub-configs its
    hardware uses after the normalizer (the others are idle defaults).  The defaults below
    are those of a unit ending in difference → shape (Figures 7 and 5)."""

    parts = ()
    #: Whether the specular is taken at the halfway vector ``H`` (Figure 5), not at ``R``.
    bisector = False

    def links(self, config):
        """``(name, format, name, format)`` of every pair of formats the unit connects
        (each must be equal), the shared normalized vector format being ``normalize.out``."""
        return []

    def vec(self, config):
        """The shared normalized direction-vector format the unit takes, named."""
        return "normalize.out", config.normalize.out

    def check(self, config):
        """Raise ValueError for a config the unit cannot take beyond its links."""

    def shininess_block(self, config):
        """The block config that takes the shininess, a port or a constant
        (:class:`ConstantShininess`): Figure 7c's difference block by default."""
        return config.difference

    def shininess(self, config):
        """``(port, format, largest value)`` of the per-pixel shininess input (the config
        asks only when :meth:`shininess_const` is 0)."""
        block = self.shininess_block(config)
        return block.SHININESS, block.fmt(block.SHININESS), block.shininess_max

    def shininess_const(self, config):
        """The shininess fixed in the hardware in the port's terms, 0 when it is a port."""
        return self.shininess_block(config).shininess_const

    def top_n(self, shininess):
        """The ``n`` of a shininess of the port's terms (``m = √n`` ports square it)."""
        return shininess

    def shininess_note(self, config):
        """What the input contract adds to "the pixel's shininess n itself" (a unit that scales
        its port itself says so)."""
        return ""

    def applied_n(self, config, n):
        """The shininess the hardware applies for the scene's float ``n`` array (what its
        float form is evaluated at)."""
        return n

    def spec_format(self, config):
        """The format of the ``spec<i>`` outputs."""
        return config.shape.fmt("t")

    def fit(self, config, n_hi, n_const):
        """``config`` with its shininess port narrowed to ``n`` up to ``n_hi``, or the
        shininess fixed in the hardware at ``n_const`` (0: a port)."""
        return config.replace(difference=config.difference.with_shininess(n_hi, n_const))

    def sweep(self, config, params):
        """``config`` at a sweep point's unit parameters (``params``: the method's, resolved;
        the datapath's ``vec_frac`` and ``lights`` are already applied)."""
        return config


class ConstantShininess:
    """A block's shininess: a per-pixel input port, or a constant built into the hardware.

    Lyon (1993) takes the shininess in two forms: Figure 7c scales ``D·D`` by ``n``
    (``x = (n/2)·D·D``), Figure 8 scales each ``|D_i|`` by the root shininess ``m = √n``.  A
    scene with a single shininess needs neither as a port: the value is fixed in the hardware
    and the multiplier by it becomes a constant one (shifts and adds,
    :func:`phongfx.hdl.constant.shininess_product`), with the codes and latency of feeding
    that value on the port.  This mixin is that choice, once, for both blocks: validation,
    the port it drops, the range of values the hardware takes, the narrowing of a fit.

    A mixin of a :class:`BlockConfig` (listed before it among the bases, so that
    :attr:`inputs` drops the port) with a shininess port :attr:`SHININESS` (``"n"`` for
    :class:`~phongfx.config.DifferenceConfig`, ``"m"`` for :class:`~phongfx.config.RootConfig`)
    and three fields named after it: ``<port>``, its integer format ``n.0``; ``<port>_max``,
    the largest value the port takes; ``<port>_const``, 0 (the default) for a per-pixel port,
    ``1..<port>_max`` for that value fixed in the hardware, with no port.
    """

    #: The shininess port, which names the three fields.
    SHININESS = None

    @property
    def shininess_max(self):
        """``<port>_max``: the largest shininess the port takes."""
        return getattr(self, f"{self.SHININESS}_max")

    @property
    def shininess_const(self):
        """``<port>_const``: the shininess fixed in the hardware, 0 when it is a port."""
        return getattr(self, f"{self.SHININESS}_const")

    @property
    def shininess_range(self):
        """``(lo, hi)`` of the shininess the hardware takes: ``1..<port>_max``, or the constant."""
        constant = self.shininess_const
        return (constant, constant) if constant else (1, self.shininess_max)

    def check_shininess(self):
        """Validate the three fields: ``<port>`` an integer format, ``<port>_max`` in
        ``1..`` its largest code, ``<port>_const`` in ``0..<port>_max``."""
        name = self.SHININESS
        top = check_int(f"{name}_max", self.shininess_max, 1, check_integer_format(name, getattr(self, name)).max_raw)
        check_int(f"{name}_const", self.shininess_const, 0, top)

    def with_shininess(self, top, constant=0):
        """This config with its port narrowed to ``1..top`` (the fewest integer bits that hold
        ``top``) and, unless ``constant`` is 0, the shininess fixed at ``constant``."""
        name = self.SHININESS
        changes = {name: f"{top.bit_length()}.0", f"{name}_max": top}
        if constant:
            changes[f"{name}_const"] = constant
        return self.replace(**changes)

    @property
    def inputs(self):
        ports = super().inputs
        if self.shininess_const:
            del ports[self.SHININESS]  # the constant is wired into the multiplier(s)
        return ports
