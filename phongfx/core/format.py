"""Fixed-point formats in Lyon's notation: the single source of truth for widths.

Lyon (Apple TR #43, "Pixel Shading Hardware Datapaths") writes ``n.m`` for an
unsigned value with ``n`` integer and ``m`` fraction bits (``n+m`` bits in all)
and ``Sn.m`` for a two's complement value of ``1+n+m`` bits.  A :class:`Format`
is that pair of numbers plus the sign; the golden model (:mod:`phongfx.golden.fixed`)
and the hardware (:mod:`phongfx.hdl.fixed`) both take their widths from it, and
the result format of every exact operation is computed here, once, for both.

Raw values are held in numpy ``int64`` by the golden model, so a format wider
than 63 bits (unsigned) or 64 bits (signed) is refused.
"""

import re
from dataclasses import dataclass
from functools import cached_property, lru_cache

__all__ = ["Format", "ROUNDINGS", "OVERFLOWS", "check_rounding", "check_overflow"]

#: Rounding modes accepted by every ``quantize`` (golden and HDL).
#: ``truncate`` drops low bits (towards -inf), ``round_half_up`` adds half an
#: LSB first (ties towards +inf), ``round_half_even`` breaks ties to even.
ROUNDINGS = ("truncate", "round_half_up", "round_half_even")

#: Overflow policies: ``saturate`` clamps to the format's range, ``wrap`` keeps
#: the low bits (two's complement), ``error`` declares that overflow cannot
#: happen: the golden model raises if it does, the hardware keeps the low bits.
OVERFLOWS = ("saturate", "wrap", "error")

_PATTERN = re.compile(r"^(S?)([0-9]+)\.([0-9]+)$")

#: The result format of an operation is asked for once per array operation of a golden
#: model, thousands of times per batch, always for the same few formats: a Format is
#: frozen, so each answer is kept (``lru_cache`` keys on the operands' fields).
_operation = lru_cache(maxsize=8192)


def check_rounding(rounding):
    if rounding not in ROUNDINGS:
        raise ValueError(f"rounding must be one of {', '.join(ROUNDINGS)}, not {rounding!r}")
    return rounding


def check_overflow(overflow):
    if overflow not in OVERFLOWS:
        raise ValueError(f"overflow must be one of {', '.join(OVERFLOWS)}, not {overflow!r}")
    return overflow


@dataclass(frozen=True)
class Format:
    """A fixed-point format: ``int_bits`` integer and ``frac_bits`` fraction bits.

    :param int int_bits: bits left of the binary point, not counting the sign bit (``n``).
    :param int frac_bits: bits right of the binary point (``m``).
    :param bool signed: two's complement with one extra sign bit (Lyon's ``S`` prefix).

    A raw integer ``r`` stands for the value ``r * 2**-frac_bits``.
    """

    int_bits: int
    frac_bits: int
    signed: bool = False

    def __post_init__(self):
        for name in ("int_bits", "frac_bits"):
            value = getattr(self, name)
            if not isinstance(value, int) or isinstance(value, bool) or value < 0:
                raise ValueError(f"{name} must be a non-negative integer, not {value!r}")
        if not isinstance(self.signed, bool):
            raise TypeError(f"signed must be a bool, not {self.signed!r}")
        limit = 64 if self.signed else 63
        if self.width > limit:
            raise ValueError(
                f"format {self} is {self.width} bits wide; raw values are held in numpy int64, "
                f"so {'a signed' if self.signed else 'an unsigned'} format may have at most "
                f"{limit} bits")
        if self.width == 0:
            raise ValueError("format 0.0 has no bits")
        # hashed by every cached operation on it, thousands of times per golden-model call
        object.__setattr__(self, "_hash", hash((self.int_bits, self.frac_bits, self.signed)))

    def __hash__(self):
        return self._hash

    @classmethod
    def parse(cls, text):
        """Parse ``"S1.10"``, ``"2.20"``, ``"0.10"``; a :class:`Format` is returned as is."""
        if isinstance(text, Format):
            return text
        if not isinstance(text, str):
            raise TypeError(f"format must be a string like 'S1.10' or a Format, not {text!r}")
        if cls is not Format:
            return cls(*_fields(text))
        return _parsed(text)

    def __str__(self):
        return f"{'S' if self.signed else ''}{self.int_bits}.{self.frac_bits}"

    def __repr__(self):
        return f"Format({str(self)!r})"

    # the properties below are asked for on every array operation of a golden model; a
    # Format is frozen, so each is computed once (kept in the instance, not a field)
    @cached_property
    def width(self):
        """Total bits: ``n+m``, or ``1+n+m`` when signed."""
        return self.int_bits + self.frac_bits + (1 if self.signed else 0)

    @cached_property
    def min_raw(self):
        return -(1 << (self.int_bits + self.frac_bits)) if self.signed else 0

    @cached_property
    def max_raw(self):
        return (1 << (self.int_bits + self.frac_bits)) - 1

    @property
    def lsb(self):
        """Value of one raw step, ``2**-frac_bits``."""
        return 2.0 ** -self.frac_bits

    @cached_property
    def one(self):
        """Raw code of 1.0 (whether or not the format can hold it)."""
        return 1 << self.frac_bits

    def exact_raw(self, value, what="constant"):
        """Raw code of the number ``value``, which this format's fraction bits must hold exactly."""
        raw = value * self.one
        if raw != int(raw):
            raise ValueError(f"{what} {value} is not exactly representable in {self}")
        return int(raw)

    def holds_one(self):
        return self.int_bits >= 1

    def shape(self):
        """The Amaranth shape holding this format's raw integers."""
        from amaranth.hdl import signed, unsigned
        return signed(self.width) if self.signed else unsigned(self.width)

    # -- result formats of exact operations -------------------------------------------------
    # Each is the smallest format that holds every exact result of the operation
    # over the operand formats' whole ranges, so hardware built to it never overflows.

    @classmethod
    def covering(cls, lo, hi, frac_bits):
        """Smallest format with ``frac_bits`` that holds raw integers ``lo..hi``."""
        if lo < 0:
            int_bits = max(max(-lo - 1, hi).bit_length() - frac_bits, 0)
            return cls(int_bits, frac_bits, True)
        # 0..0 without fraction bits still needs one bit: "0.0" is no format
        return cls(max(hi.bit_length() - frac_bits, 0 if frac_bits else 1), frac_bits, False)

    def _aligned(self, frac_bits):
        scale = 1 << (frac_bits - self.frac_bits)
        return self.min_raw * scale, self.max_raw * scale

    @_operation
    def add(self, other):
        """Format of ``self + other`` (binary points aligned)."""
        f = max(self.frac_bits, other.frac_bits)
        (alo, ahi), (blo, bhi) = self._aligned(f), other._aligned(f)
        return Format.covering(alo + blo, ahi + bhi, f)

    @_operation
    def sub(self, other):
        """Format of ``self - other`` (always signed: hardware subtractors are)."""
        f = max(self.frac_bits, other.frac_bits)
        (alo, ahi), (blo, bhi) = self._aligned(f), other._aligned(f)
        result = Format.covering(alo - bhi, ahi - blo, f)
        return Format(result.int_bits, f, True) if not result.signed else result

    @_operation
    def mul(self, other):
        """Format of ``self * other``: fraction bits add, range from the corner products."""
        corners = [a * b for a in (self.min_raw, self.max_raw) for b in (other.min_raw, other.max_raw)]
        return Format.covering(min(corners), max(corners), self.frac_bits + other.frac_bits)

    @_operation
    def neg(self):
        """Format of ``-self``."""
        return Format.covering(-self.max_raw, -self.min_raw, self.frac_bits).as_signed()

    def as_signed(self):
        return self if self.signed else Format(self.int_bits, self.frac_bits, True)

    @_operation
    def shift(self, amount):
        """Format of ``self * 2**amount``: the raw bits do not move, only the point.

        A shift the fraction (left) or integer (right) part cannot absorb widens the
        other part instead; see :meth:`shift_raw` for how raw codes follow.
        """
        if amount >= 0:
            return Format(self.int_bits + amount, max(self.frac_bits - amount, 0), self.signed)
        return Format(max(self.int_bits + amount, 0), self.frac_bits - amount, self.signed)

    def shift_raw(self, amount):
        """How far raw codes move left when shifting by ``amount`` (0 unless the
        fraction part is used up by a left shift)."""
        return max(amount - self.frac_bits, 0) if amount >= 0 else 0


def _fields(text):
    """``(int_bits, frac_bits, signed)`` of a format string (:meth:`Format.parse`)."""
    match = _PATTERN.match(text.strip())
    if match is None:
        raise ValueError(f"format must look like 'n.m' (unsigned) or 'Sn.m' (signed), not {text!r}")
    return int(match.group(2)), int(match.group(3)), bool(match.group(1))


# A Format is frozen, so one instance per distinct string serves every caller: the configs
# keep their formats as strings and an emission asks for the same few hundred times over.
@lru_cache(maxsize=4096)
def _parsed(text):
    return Format(*_fields(text))

