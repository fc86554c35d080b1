"""The one narrowing step of the golden models, on raw ``int64`` codes: rounding and overflow.

:meth:`Fixed.quantize <phongfx.golden.fixed.Fixed.quantize>` narrows through :func:`narrow`,
:meth:`Fixed.from_float <phongfx.golden.fixed.Fixed.from_float>` rounds floats to codes with
:func:`round_float`; :func:`quantize_raw` is the same step on any raw codes (the stateful units
wrap their registers with it).  :func:`phongfx.hdl.quantize.quantize` is its twin in Amaranth.
"""

from functools import lru_cache

import numpy as np

from phongfx.core.format import Format, check_overflow, check_rounding

__all__ = ["FixedOverflowError", "as_raw", "quantize_raw", "narrow", "overflow_error", "round_float"]


class FixedOverflowError(OverflowError):
    """A ``quantize`` with ``overflow="error"`` met a value outside its format."""


def as_raw(raw):
    """``raw`` as a read-only ``int64`` array; no copy when it already is one (the golden
    model's results are fresh arrays, and copying every one was a quarter of its time),
    so a caller must not change an array after wrapping it."""
    array = np.asarray(raw)
    if array.dtype.kind not in "iub":
        raise TypeError(f"raw codes must be integers, not {array.dtype}")
    view = array.astype(np.int64, copy=False).view()
    view.flags.writeable = False
    return view


_INT64_MAX = (1 << 63) - 1


def quantize_raw(raw, frm, to, rounding, overflow, op="quantize"):
    """Narrow raw codes of format ``frm`` to format ``to``.

    Parameters
    ----------
    raw : array of int64
    frm, to : Format
    rounding : {"truncate", "round_half_up", "round_half_even"}
        Applied when ``to`` has fewer fraction bits.
    overflow : {"saturate", "wrap", "error"}
        Applied when the rounded value falls outside ``to``.
    op : str
        Name of the operation, for the error message.
    """
    frm, to = Format.parse(frm), Format.parse(to)
    check_rounding(rounding)
    check_overflow(overflow)
    # the codes need not lie in ``frm`` (from_float wraps codes of any size through here)
    return narrow(as_raw(raw), frm, to, rounding, overflow, op, inside=False)


def narrow(raw, frm, to, rounding, overflow, op, inside):
    """:func:`quantize_raw` of an int64 array, its arguments checked; ``inside``: every code
    lies in ``frm`` (a :class:`Fixed`'s do), so the formats alone may show that none leaves ``to``."""
    drop = frm.frac_bits - to.frac_bits
    if drop > 0:
        if rounding == "truncate":
            raw = raw >> drop
        elif rounding == "round_half_up" and frm.max_raw + (1 << (drop - 1)) <= _INT64_MAX:
            # floor((x + half) / 2^drop) = floor(x / 2^drop) + (x mod 2^drop >= half): the
            # split below in two passes instead of five, where the sum cannot pass int64
            raw = raw + (1 << (drop - 1))
            raw >>= drop
        else:
            # split into kept part and dropped remainder: adding the rounding constant
            # to the raw code first could overflow int64 for 63/64-bit formats
            kept, rest = raw >> drop, raw & ((1 << drop) - 1)
            half = 1 << (drop - 1)
            if rounding == "round_half_up":
                kept += rest >= half
            else:
                kept += (rest > half) | ((rest == half) & (kept & 1).astype(bool))
            raw = kept
    elif drop < 0:
        # a signed code of w bits moved left by k needs w+k bits, an unsigned one
        # w+k bits plus the sign bit int64 always has
        if frm.width - drop > (64 if frm.signed else 63):
            raise ValueError(f"{op}: {frm} moved to {-drop} more fraction bits does not fit in int64")
        raw = raw << -drop
    if inside:
        lo, hi = _reach(frm, drop, rounding != "truncate")
        if lo >= to.min_raw and hi <= to.max_raw:
            return raw  # no code of ``frm`` can leave ``to``: decided by the formats, not the data
    if overflow == "wrap":
        # keeping the low bits leaves a code inside ``to`` as it is: no need to find the others
        if to.width < 64:  # 64 bits: int64 is already two's complement of that width
            raw = raw & ((1 << to.width) - 1)
            if to.signed:
                # subtract 2**width in two halves: 2**63 itself is no int64
                half = 1 << (to.width - 1)
                raw = np.where(raw >= half, (raw - half) - half, raw)
        return raw
    # one min/max pair finds whether anything is out; the mask only when something is
    if raw.size and (raw.min() < to.min_raw or raw.max() > to.max_raw):
        if overflow == "error":
            bad = (raw < to.min_raw) | (raw > to.max_raw)
            first = raw[bad].flat[0] if raw.ndim else raw
            raise overflow_error(op, to, int(np.count_nonzero(bad)), int(first))
        # np.clip's wrapper looks the dtype's limits up on every call: the two ufuncs
        raw = np.maximum(raw, to.min_raw)
        raw = np.minimum(raw, to.max_raw, out=raw if raw.ndim else None)
    return raw


@lru_cache(maxsize=4096)
def _reach(frm, drop, rounds):
    """``(lo, hi)``: what ``frm``'s codes can become moved ``drop`` fraction bits (rounded up one step at most)."""
    if drop > 0:
        return frm.min_raw >> drop, (frm.max_raw >> drop) + (1 if rounds else 0)
    return frm.min_raw << -drop, frm.max_raw << -drop


def overflow_error(op, to, count, first):
    # ``first`` is the first offending raw code, an exact int (it may be past int64:
    # int / int is correctly rounded where float(int) would overflow)
    return FixedOverflowError(
        f"{op}: {count} value(s) overflow format {to} "
        f"(range {to.min_raw * to.lsb}..{to.max_raw * to.lsb}); "
        f"first offending value {first / to.one} (raw {first})")


def round_float(scaled, rounding):
    """Float codes of ``scaled`` (a fresh array of values times ``2^frac``, overwritten)."""
    if rounding == "truncate":
        return np.floor(scaled)
    if rounding == "round_half_up":
        # floor(x + 0.5) in floats rounds the sum (0.49999999999999994 -> 1); x - floor(x) is exact
        floor = np.floor(scaled)
        scaled -= floor
        floor += scaled >= 0.5
        return floor
    return np.rint(scaled)  # ties to even
