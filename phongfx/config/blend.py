"""Configuration of the colour blend: a shader's ambient, diffuse and specular terms summed per channel."""

from dataclasses import dataclass

from phongfx.core.format import Format

from .base import BlockConfig, check_format, check_int

__all__ = ["BlendConfig", "MAX_LIGHTS", "MAX_MATERIALS", "MAX_COEF_FRAC", "MAX_BITS", "MAX_VALUE", "CHANNELS"]

#: Most lights a blend sums over.
MAX_LIGHTS = 8
#: Most materials a blend selects between (a 4-bit ``material`` code).
MAX_MATERIALS = 16
#: Most fraction bits of the coefficients.
MAX_COEF_FRAC = 24
#: Widest output code, in bits per channel.
MAX_BITS = 16
#: Largest real value of a coefficient (``k·colour·intensity``; lights may be brighter than 1).
MAX_VALUE = 16
#: The output channels, in port order.
CHANNELS = ("r", "g", "b")


def _real(where, value):
    """``value`` as a float if it is a real number in ``0..MAX_VALUE`` (a bool is not)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not 0 <= value <= MAX_VALUE:
        raise ValueError(f"{where} must be a real number in 0..{MAX_VALUE}, not {value!r}")
    return float(value)


def _sequence(where, value, count, what):
    """``value`` as a tuple of ``count`` items (a list or tuple), else a ValueError naming ``what``."""
    if not isinstance(value, (tuple, list)):
        raise ValueError(f"{where} must be a tuple of {what}, not {value!r}")
    if len(value) != count:
        raise ValueError(f"{where} must have {count} {what}, not {len(value)}")
    return tuple(value)


def _rgb(where, value):
    values = _sequence(where, value, 3, "values (r, g, b)")
    return tuple(_real(f"{where}[{c}]", v) for c, v in enumerate(values))


def _materials(name, value, count):
    """The materials of table ``name``: a tuple of 1..MAX_MATERIALS entries, ``count`` of them
    if given (the count of ``ambient``)."""
    if not isinstance(value, (tuple, list)):
        raise ValueError(f"{name} must be a tuple with one entry per material, not {value!r}")
    if count is None and not 1 <= len(value) <= MAX_MATERIALS:
        raise ValueError(f"{name} must have 1..{MAX_MATERIALS} materials, not {len(value)}")
    if count is not None and len(value) != count:
        raise ValueError(f"{name} must have {count} material(s), as ambient has, not {len(value)}")
    return tuple(value)


@dataclass(frozen=True)
class BlendConfig(BlockConfig):
    """The final colour blend of a shader: per pixel and channel ``c`` of r, g, b,

        ``acc_c = A[m][c] + Σ_{i < lights} (D[m][i][c]·diff_i + S[m][i][c]·gate_i·spec_i)``,
        ``out_c = clip(round(acc_c), 0, 2^bits − 1)``,

    the sum that Phong's model (Phong 1975) and Lyon (1993, "Background") take over the
    lights: ambient plus, per light, its intensity times ``kd·diffuse + ks·specular``.
    ``m`` is the pixel's material (0 when there is one), ``gate_i = [diff_i > 0]`` when
    :attr:`gate` (the backside test: where ``N·L <= 0`` the light reaches neither term, as
    the diffuse unit's clamp says) and 1 otherwise.

    The coefficients are real values computed by the caller (the scene compiler):
    ``ambient[m][c] = ka·colour``, ``diffuse[m][i][c] = kd·colour·light i's RGB``,
    ``specular[m][i][c] = ks·colour·light i's RGB``.  The block holds them as unsigned
    integer codes of :attr:`coef_frac` fraction bits with the display scale folded in
    (:meth:`raw_code`): the display code of an intensity ``I`` is ``floor(I·(2^bits − 1)
    + 1/2)``, so with ``(2^bits − 1)`` inside the constants ``acc`` is already in output
    levels and the one rounding is to an integer, no multiply by 255 behind it.

    Fields:

    * ``lights`` [2]: ``1..MAX_LIGHTS``;
    * ``diff`` [``1.10``]: the format of every ``diff{i}`` input, unsigned, holding 1.0 (the
      diffuse unit's ``out``); ``""`` when the unit has no diffuse output: no ``diff`` ports,
      every diffuse coefficient 0 and :attr:`gate` False;
    * ``spec`` [``1.15``]: the format of every ``spec{i}`` input, unsigned (the shape unit's ``t``);
    * ``coef_frac`` [10]: ``0..MAX_COEF_FRAC`` fraction bits of the coefficients, the one
      width a scene compiler lowers; their integer bits follow from the largest (:attr:`coef_format`);
    * ``bits`` [8]: ``1..MAX_BITS`` bits per output channel;
    * ``ambient`` [one black material], ``diffuse``, ``specular`` [one material, two lights
      of 0.5 grey each]: per material an (r, g, b) triple (``ambient``) or one per light, every
      value a real number in ``0..MAX_VALUE``; lists are accepted and stored as tuples of
      floats, so that the config stays hashable and its ``repr`` stable (build caches key on it);
    * ``gate`` [True]: the backside test on the specular term;
    * ``rounding`` [``round_half_up``]: the output rounding; ``pipeline`` [0]: ``0..4``.

    Ports: ``diff{i}`` (``diff``, unless it is ``""``) and ``spec{i}`` (``spec``) per light,
    ``material`` (:attr:`material_format`) when there is more than one material; out ``r``,
    ``g``, ``b`` (:attr:`out_format`).
    """

    lights: int = 2
    diff: str = "1.10"
    spec: str = "1.15"
    coef_frac: int = 10
    bits: int = 8
    ambient: tuple = ((0.0, 0.0, 0.0),)
    diffuse: tuple = (((0.5, 0.5, 0.5), (0.5, 0.5, 0.5)),)
    specular: tuple = (((0.5, 0.5, 0.5), (0.5, 0.5, 0.5)),)
    gate: bool = True
    rounding: str = "round_half_up"
    pipeline: int = 0

    def validate(self):
        check_int("lights", self.lights, 1, MAX_LIGHTS)
        if self.diff != "":
            check_format("diff", self.diff, signed=False, holds_one=True)
        check_format("spec", self.spec, signed=False)
        check_int("coef_frac", self.coef_frac, 0, MAX_COEF_FRAC)
        check_int("bits", self.bits, 1, MAX_BITS)
        if not isinstance(self.gate, bool):
            raise ValueError(f"gate must be True or False, not {self.gate!r}")
        ambient = _materials("ambient", self.ambient, None)
        ambient = tuple(_rgb(f"ambient[{m}]", rgb) for m, rgb in enumerate(ambient))
        tables = {"ambient": ambient}
        for name in ("diffuse", "specular"):
            table = _materials(name, getattr(self, name), len(ambient))
            tables[name] = tuple(
                tuple(_rgb(f"{name}[{m}][{i}]", rgb) for i, rgb in enumerate(
                    _sequence(f"{name}[{m}]", per_light, self.lights, "lights (one (r, g, b) per light)")))
                for m, per_light in enumerate(table))
        for name, table in tables.items():
            object.__setattr__(self, name, table)
        if self.diff == "":
            for m, per_light in enumerate(self.diffuse):
                for i, rgb in enumerate(per_light):
                    for c, value in enumerate(rgb):
                        if value:
                            raise ValueError(f"diff is '' (no diffuse input): diffuse must be all 0, not "
                                             f"diffuse[{m}][{i}][{c}] = {value!r}")
            if self.gate:
                raise ValueError("diff is '' (no diffuse input): gate must be False, "
                                 "the backside test reads diff")
        try:
            self.sum_format
        except ValueError as error:
            raise ValueError(f"the exact sum of {self.lights} light(s) at coef_frac={self.coef_frac} "
                             f"(coefficients {self.coef_format}) does not fit: {error}") from None

    # -- the ports --------------------------------------------------------------------------

    @property
    def materials(self):
        """How many materials the tables hold."""
        return len(self.ambient)

    @property
    def material_format(self):
        """``ceil(log2 materials)``-bit unsigned integer format of the ``material`` port
        (None for one material: no port)."""
        return Format((self.materials - 1).bit_length(), 0) if self.materials > 1 else None

    @property
    def out_format(self):
        """The output code: ``bits.0``, unsigned."""
        return Format(self.bits, 0)

    @property
    def inputs(self):
        ports = {}
        for i in range(self.lights):
            if self.diff:
                ports[f"diff{i}"] = (self.fmt("diff"), 1)
            ports[f"spec{i}"] = (self.fmt("spec"), 1)
        if self.materials > 1:
            ports["material"] = (self.material_format, 1)
        return ports

    @property
    def outputs(self):
        return {name: (self.out_format, 1) for name in CHANNELS}

    # -- the coefficients -------------------------------------------------------------------

    @property
    def levels(self):
        """The top output code ``2^bits − 1``: the display scale folded into the coefficients."""
        return (1 << self.bits) - 1

    def raw_code(self, value):
        """The coefficient code of the real ``value``: ``floor(value·(2^bits − 1)·2^coef_frac
        + 1/2)``, exact (a float is a ratio of integers), the rule golden model and hardware share."""
        num, den = float(value).as_integer_ratio()
        scaled = num * self.levels << self.coef_frac
        return (2 * scaled + den) // (2 * den)

    def coefficients(self, material):
        """``(A, D, S)`` raw codes of ``material``: ``A`` a 3-tuple (r, g, b), ``D`` and ``S``
        ``lights`` 3-tuples; all codes of :attr:`coef_format`."""
        check_int("material", material, 0, self.materials - 1)
        return (tuple(self.raw_code(v) for v in self.ambient[material]),
                tuple(tuple(self.raw_code(v) for v in rgb) for rgb in self.diffuse[material]),
                tuple(tuple(self.raw_code(v) for v in rgb) for rgb in self.specular[material]))

    @property
    def coef_format(self):
        """The unsigned format every coefficient code is held in: :attr:`coef_frac` fraction
        bits and the integer bits the largest code needs."""
        values = [v for table in (self.ambient, self.diffuse, self.specular) for v in _flat(table)]
        return Format.covering(0, max(self.raw_code(v) for v in values), self.coef_frac)

    @property
    def sum_format(self):
        """The format of the exact sum as the golden model grows it (coefficient × input
        products added to the ambient constant); ValueError if it is wider than int64 holds."""
        coef = self.coef_format
        total = coef
        for _ in range(self.lights):
            for port in (("diff", "spec") if self.diff else ("spec",)):
                total = total.add(coef.mul(self.fmt(port)))
        return total


def _flat(table):
    if isinstance(table, float):
        yield table
    else:
        for item in table:
            yield from _flat(item)
