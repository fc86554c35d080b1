"""Laws of the golden fixed-point layer, against exact Python-int / Fraction references."""

import math
import re
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from phongfx.core.format import OVERFLOWS, ROUNDINGS, Format
from phongfx.golden.fixed import Fixed, FixedOverflowError, check_range, quantize_raw

SETTINGS = settings(deadline=None, derandomize=True, max_examples=150)

WIDE = r"format S?\d+\.\d+ is \d+ bits wide; raw values are held in numpy int64, " \
       r"so an? (un)?signed format may have at most 6[34] bits"


# -- strategies -------------------------------------------------------------------------------

@st.composite
def formats(draw, max_width=64, min_width=1):
    signed = draw(st.booleans())
    limit = max_width if signed else min(max_width, 63)
    width = draw(st.integers(min(min_width, limit), limit))
    frac = draw(st.integers(0, width - signed))
    return Format(width - signed - frac, frac, signed)


def raw_codes(fmt):
    """Codes of ``fmt``, the corners and their neighbours often."""
    corners = sorted({fmt.min_raw, fmt.max_raw, 0, min(fmt.min_raw + 1, fmt.max_raw),
                      max(fmt.max_raw - 1, fmt.min_raw), min(1, fmt.max_raw),
                      max(-1, fmt.min_raw), min(fmt.one, fmt.max_raw), min(fmt.one // 2, fmt.max_raw)})
    return st.one_of(st.sampled_from(corners), st.integers(fmt.min_raw, fmt.max_raw))


@st.composite
def fixed_arrays(draw, fmt=None, size=None, max_width=64):
    fmt = fmt if fmt is not None else draw(formats(max_width))
    n = size if size is not None else draw(st.integers(1, 8))
    return Fixed(draw(st.lists(raw_codes(fmt), min_size=n, max_size=n)), fmt)


@st.composite
def fixed_pairs(draw, max_width=40):
    a = draw(fixed_arrays(max_width=max_width))
    b = draw(fixed_arrays(size=len(a), max_width=max_width))
    return a, b


# -- exact references -----------------------------------------------------------------------

def values(x):
    """Exact values of a Fixed, as Fractions."""
    return [Fraction(int(r), x.fmt.one) for r in np.ravel(x.raw)]


def ref_round(x, rounding):
    if rounding == "truncate":
        return math.floor(x)
    if rounding == "round_half_up":
        return math.floor(x + Fraction(1, 2))
    return round(x)  # Python rounds a Fraction's ties to even


def ref_overflow(r, to, overflow):
    """The code ``to`` holds for an integer ``r`` (None: out of range under "error")."""
    if to.min_raw <= r <= to.max_raw:
        return r
    if overflow == "saturate":
        return min(max(r, to.min_raw), to.max_raw)
    if overflow == "wrap":
        return (r - to.min_raw) % (1 << to.width) + to.min_raw
    return None


def overflow_message(op, to, count, first):
    return (f"{op}: {count} value(s) overflow format {to} (range {to.min_raw * to.lsb}.."
            f"{to.max_raw * to.lsb}); first offending value {first / to.one} (raw {first})")


def exact_or_refused(thunk):
    """Run ``thunk``; None when it is refused because its result is wider than int64."""
    try:
        return thunk()
    except ValueError as error:
        assert re.fullmatch(WIDE, str(error)), str(error)
        return None


# -- exact arithmetic -----------------------------------------------------------------------

@SETTINGS
@given(fixed_pairs())
def test_add_sub_mul_neg_are_exact(pair):
    a, b = pair
    cases = [
        (lambda: a + b, lambda: a.fmt.add(b.fmt), lambda x, y: x + y),
        (lambda: a - b, lambda: a.fmt.sub(b.fmt), lambda x, y: x - y),
        (lambda: a * b, lambda: a.fmt.mul(b.fmt), lambda x, y: x * y),
        (lambda: -a, lambda: a.fmt.neg(), lambda x, y: -x),
    ]
    for op, fmt, exact in cases:
        result = exact_or_refused(op)
        if result is None:
            with pytest.raises(ValueError, match="^" + WIDE + "$"):
                fmt()
            continue
        assert result.fmt == fmt()
        assert result.raw.dtype == np.int64 and result.raw.shape == a.raw.shape
        assert values(result) == [exact(x, y) for x, y in zip(values(a), values(b))]


@pytest.mark.parametrize("expr, message", [
    (lambda: Fixed(0, "S63.0") + Fixed(0, "S63.0"), r"^format S64\.0 is 65 bits wide; "),
    (lambda: Fixed(0, "63.0") + Fixed(0, "1.0"), r"^format 64\.0 is 64 bits wide; (?=.*an unsigned)"),
    (lambda: Fixed(0, "S31.1") * Fixed(0, "S31.0"), r"^format S63\.1 is 65 bits wide; "),
    (lambda: -Fixed(0, "S0.63"), r"^format S1\.63 is 65 bits wide; "),
    (lambda: Fixed(0, "S10.53") - Fixed(0, "S10.53"), r"^format S11\.53 is 65 bits wide; "),
    (lambda: Fixed(0, "S10.50").shift(54), r"^format S64\.0 is 65 bits wide; "),
    (lambda: Fixed(0, "S10.3").shift(60), r"^format S70\.0 is 71 bits wide; "),
    (lambda: Fixed(0, "S10.3").shift(-61), r"^format S0\.64 is 65 bits wide; "),
    (lambda: Fixed(np.zeros((2, 3), dtype=int), "S32.30").sum(), r"^format S34\.30 is 65 bits wide; "),
    (lambda: Fixed(np.zeros(3, dtype=int), "S16.15").dot(Fixed(np.zeros(3, dtype=int), "S16.15")),
     r"^format S34\.30 is 65 bits wide; "),
])
def test_results_wider_than_int64_are_refused(expr, message):
    with pytest.raises(ValueError, match=message + ".*numpy int64.* at most 6[34] bits$"):
        expr()


def test_largest_results_still_exact():
    # every corner product of the widest operands that fit, exactly (no silent int64 wrap)
    a = Fixed([-(2 ** 31), 2 ** 31 - 1], "S31.0")
    p = a[:, None] * a[None, :]
    assert p.fmt == Format.parse("S63.0")
    assert p.raw.tolist() == [[2 ** 62, -(2 ** 62) + 2 ** 31], [-(2 ** 62) + 2 ** 31, (2 ** 31 - 1) ** 2]]
    s = Fixed([2 ** 62 - 1, 2 ** 62 - 1], "62.0") + Fixed([2 ** 62 - 1, 0], "62.0")
    assert s.fmt == Format.parse("63.0") and s.raw.tolist() == [2 ** 63 - 2, 2 ** 62 - 1]
    d = Fixed([0, 2 ** 62 - 1], "62.0") - Fixed([2 ** 62 - 1, 0], "62.0")
    assert d.fmt == Format.parse("S62.0") and d.raw.tolist() == [-(2 ** 62) + 1, 2 ** 62 - 1]


@SETTINGS
@given(fixed_arrays(max_width=62), st.integers(-70, 70))
def test_shift_is_exact(a, amount):
    result = exact_or_refused(lambda: a.shift(amount))
    if result is None:
        return
    assert result.fmt == a.fmt.shift(amount)
    assert values(result) == [x * Fraction(2) ** amount for x in values(a)]
    if amount >= 0:
        assert values(a << amount) == values(result)
    else:
        assert values(a >> -amount) == values(result)


@SETTINGS
@given(formats(max_width=20), st.integers(1, 3), st.integers(0, 6), st.data())
def test_sum_is_exact(fmt, rows, count, data):
    raws = [[data.draw(raw_codes(fmt)) for _ in range(count)] for _ in range(rows)]
    x = Fixed(np.array(raws, dtype=np.int64).reshape(rows, count), fmt)
    expected_fmt = fmt
    for _ in range(count - 1):
        expected_fmt = expected_fmt.add(fmt)
    total = x.sum()
    assert total.fmt == expected_fmt and total.shape == (rows,)
    assert values(total) == [sum(Fraction(r, fmt.one) for r in row) for row in raws]
    # the format holds the sum of count extreme codes, of either sign
    assert expected_fmt.max_raw >= max(count * fmt.max_raw, 0)
    assert expected_fmt.min_raw <= count * fmt.min_raw
    down = x.sum(axis=0)
    assert values(down) == [sum(Fraction(raws[i][j], fmt.one) for i in range(rows))
                            for j in range(count)]


@SETTINGS
@given(formats(max_width=24), formats(max_width=24), st.integers(1, 4), st.data())
def test_dot_is_exact(fa, fb, n, data):
    a = data.draw(fixed_arrays(fa, size=3 * n)).raw.reshape(n, 3)
    b = data.draw(fixed_arrays(fb, size=3 * n)).raw.reshape(n, 3)
    a, b = Fixed(a, fa), Fixed(b, fb)
    result = a.dot(b)
    assert result.fmt == fa.mul(fb).add(fa.mul(fb)).add(fa.mul(fb))
    assert result.shape == (n,)
    for i in range(n):
        assert Fraction(int(result.raw[i]), result.fmt.one) == sum(
            Fraction(int(a.raw[i, k]), fa.one) * Fraction(int(b.raw[i, k]), fb.one) for k in range(3))
    # against one shared vector (broadcast)
    shared = a.dot(b[0])
    assert values(shared) == [sum(values(a[i] * b[0])) for i in range(n)]


@SETTINGS
@given(fixed_pairs(max_width=62))
def test_comparisons_are_exact(pair):
    a, b = pair
    ge, lt = a >= b, a < b
    assert ge.tolist() == [x >= y for x, y in zip(values(a), values(b))]
    assert lt.tolist() == [x < y for x, y in zip(values(a), values(b))]


@SETTINGS
@given(fixed_arrays(max_width=40), st.integers(-(2 ** 45), 2 ** 45), st.integers(0, 8))
def test_comparisons_with_numbers(a, numerator, shift):
    constant = Fraction(numerator, 2 ** shift)
    if constant.denominator > a.fmt.one:
        with pytest.raises(ValueError, match=r"^comparison constant .* is not exactly "
                                             rf"representable in {re.escape(str(a.fmt))}$"):
            a >= constant
        return
    for c in {constant, float(constant)} if float(constant) == constant else {constant}:
        assert (a >= c).tolist() == [x >= constant for x in values(a)]
        assert (a < c).tolist() == [x < constant for x in values(a)]


def test_comparison_constant_message():
    with pytest.raises(ValueError, match=r"^comparison constant 0\.3 is not exactly representable "
                                         r"in S1\.2$"):
        Fixed([1], "S1.2") < 0.3


@pytest.mark.parametrize("expr, kind", [
    (lambda x: x + 1, "int"), (lambda x: 1 + x, "int"), (lambda x: x - 0.5, "float"),
    (lambda x: 0.5 - x, "float"), (lambda x: x * 2, "int"), (lambda x: 2.0 * x, "float"),
    (lambda x: x + np.int64(1), "int64"), (lambda x: np.arange(2) + x, "ndarray"),
    (lambda x: x.dot(np.ones(2)), "ndarray"), (lambda x: x.where(True, 0), "int"),
])
def test_operands_must_be_fixed(expr, kind):
    with pytest.raises(TypeError, match=rf"^fixed-point operands must be Fixed, not {kind}; "
                                        r"use Fixed\.const\(value, fmt\) for constants$"):
        expr(Fixed([1, 2], "2.2"))


def test_constructor_and_const_messages():
    with pytest.raises(ValueError, match=r"^raw codes must lie in -8\.\.7 for format S2\.1; "
                                         r"2 do not, first 9$"):
        Fixed([0, 9, 7, -9], "S2.1")
    with pytest.raises(TypeError, match=r"^raw codes must be integers, not float64$"):
        Fixed([0.5], "S2.1")
    assert Fixed.const(1, "1.10").raw == 1 << 10
    assert Fixed.const(-0.75, "S0.2").raw == -3
    with pytest.raises(ValueError, match=r"^constant 0\.3 is not exactly representable in S1\.2$"):
        Fixed.const(0.3, "S1.2")
    with pytest.raises(ValueError, match=r"^raw codes must lie in 0\.\.7 for format 1\.2; "
                                         r"1 do not, first 8$"):
        Fixed.const(2, "1.2")
    with pytest.raises(ValueError, match=r"^where: both sides must have the same format, "
                                         r"not 1\.2 and S1\.2$"):
        Fixed([1], "1.2").where(True, Fixed([1], "S1.2"))


# -- quantize -------------------------------------------------------------------------------

@st.composite
def quantize_cases(draw, max_width=64):
    # the widest formats often: that is where int64 intermediates could wrap
    frm = draw(st.one_of(formats(max_width), formats(max_width, min_width=max_width)))
    to = draw(st.one_of(formats(max_width), formats(max_width, min_width=max_width)))
    raws = draw(st.lists(raw_codes(frm), min_size=1, max_size=12))
    return frm, to, raws


def quantize_reference(raws, frm, to, rounding, overflow):
    """Exact result codes, and the out-of-range rounded codes."""
    scale = Fraction(to.one, frm.one)
    rounded = [ref_round(r * scale, rounding) for r in raws]
    return [ref_overflow(r, to, overflow) for r in rounded], [
        r for r in rounded if not to.min_raw <= r <= to.max_raw]


@SETTINGS
@given(quantize_cases(), st.sampled_from(ROUNDINGS), st.sampled_from(OVERFLOWS))
def test_quantize_matches_exact_reference(case, rounding, overflow):
    frm, to, raws = case
    more = to.frac_bits - frm.frac_bits
    if more > 0 and frm.width + more > (64 if frm.signed else 63):
        with pytest.raises(ValueError, match=rf"^quantize: {re.escape(str(frm))} moved to {more} "
                                             r"more fraction bits does not fit in int64$"):
            quantize_raw(raws, frm, to, rounding, overflow)
        return
    expected, bad = quantize_reference(raws, frm, to, rounding, overflow)
    if overflow == "error" and bad:
        with pytest.raises(FixedOverflowError, match="^" + re.escape(
                overflow_message("quantize", to, len(bad), bad[0])) + "$"):
            quantize_raw(raws, frm, to, rounding, overflow)
        return
    got = quantize_raw(raws, frm, to, rounding, overflow)
    assert got.dtype == np.int64
    assert got.tolist() == expected
    # the Fixed method is the same function
    assert Fixed(raws, frm).quantize(to, rounding, overflow).raw.tolist() == expected


@pytest.mark.parametrize("rounding", ROUNDINGS)
@pytest.mark.parametrize("overflow", OVERFLOWS)
@pytest.mark.parametrize("frm, to", [
    ("S32.31", "S32.0"), ("32.31", "32.0"), ("S0.63", "S0.0"), ("0.63", "0.1"), ("S0.63", "1.0"),
    ("S32.31", "S31.1"), ("61.1", "61.2"), ("S61.1", "S60.2"), ("S0.63", "S0.63"),
    ("63.0", "S62.0"), ("S63.0", "62.0"), ("S63.0", "S1.0"),
])
def test_quantize_at_the_int64_edges(frm, to, rounding, overflow):
    # the widest codes, where a rounding constant or a left shift could wrap int64
    frm, to = Format.parse(frm), Format.parse(to)
    raws = sorted({frm.min_raw, frm.min_raw + 1, -1 if frm.signed else 0, 0, 1,
                   frm.max_raw // 2, frm.max_raw // 2 + 1, frm.max_raw - 1, frm.max_raw})
    expected, bad = quantize_reference(raws, frm, to, rounding, overflow)
    if overflow == "error" and bad:
        with pytest.raises(FixedOverflowError):
            quantize_raw(raws, frm, to, rounding, overflow)
    else:
        assert quantize_raw(raws, frm, to, rounding, overflow).tolist() == expected


@pytest.mark.parametrize("frm, to, more", [("62.1", "61.2", 1), ("S62.1", "S61.2", 1),
                                           ("S1.0", "S0.63", 63), ("40.0", "S0.30", 30)])
def test_quantize_refuses_codes_moved_past_int64(frm, to, more):
    with pytest.raises(ValueError, match=rf"^scale: {re.escape(frm)} moved to {more} more "
                                         r"fraction bits does not fit in int64$"):
        quantize_raw([1], frm, to, "truncate", "saturate", op="scale")


def test_quantize_rounding_examples():
    # raw codes of 2.2 (quarters) to 2.0: -- ties at .5 are where the modes differ
    raws = np.arange(16)
    cases = {
        "truncate": [0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3],
        "round_half_up": [0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3, 3, 3],
        "round_half_even": [0, 0, 0, 1, 1, 1, 2, 2, 2, 2, 2, 3, 3, 3, 3, 3],
    }
    for rounding, expected in cases.items():
        assert quantize_raw(raws, "2.2", "2.0", rounding, "saturate").tolist() == expected
    # signed, negative ties: -2.5 -> -3 (floor), -2 (half up), -2 (even); -1.5 -> -2, -1, -2
    neg = [-10, -6]
    assert quantize_raw(neg, "S2.2", "S2.0", "truncate", "error").tolist() == [-3, -2]
    assert quantize_raw(neg, "S2.2", "S2.0", "round_half_up", "error").tolist() == [-2, -1]
    assert quantize_raw(neg, "S2.2", "S2.0", "round_half_even", "error").tolist() == [-2, -2]
    # to more fraction bits: exact, whatever the rounding
    assert quantize_raw([-3, 5], "S2.1", "S2.4", "truncate", "error").tolist() == [-24, 40]


def test_quantize_scalar_and_shape():
    assert int(quantize_raw(7, "3.1", "3.0", "round_half_up", "error")) == 4
    x = np.arange(24).reshape(2, 3, 4) - 12
    assert quantize_raw(x, "S4.1", "S3.0", "truncate", "wrap").shape == (2, 3, 4)


@SETTINGS
@given(quantize_cases(max_width=24), st.sampled_from(ROUNDINGS))
def test_saturate_clamps_and_is_monotone(case, rounding):
    frm, to, raws = case
    assume(frm.width + max(to.frac_bits - frm.frac_bits, 0) <= 63)
    raws = sorted(raws)
    got = quantize_raw(raws, frm, to, rounding, "saturate").tolist()
    assert got == sorted(got)  # monotone: never wraps round
    scale = Fraction(to.one, frm.one)
    for r, q in zip(raws, got):
        rounded = ref_round(r * scale, rounding)
        assert q == (to.max_raw if rounded > to.max_raw else
                     to.min_raw if rounded < to.min_raw else rounded)


@SETTINGS
@given(quantize_cases(max_width=24), st.sampled_from(ROUNDINGS))
def test_wrap_is_twos_complement_modulo_width(case, rounding):
    frm, to, raws = case
    assume(frm.width + max(to.frac_bits - frm.frac_bits, 0) <= 63)
    got = quantize_raw(raws, frm, to, rounding, "wrap").tolist()
    scale = Fraction(to.one, frm.one)
    for r, q in zip(raws, got):
        assert to.min_raw <= q <= to.max_raw
        assert (q - ref_round(r * scale, rounding)) % (1 << to.width) == 0
        # the low bits, read as to's signedness
        low = ref_round(r * scale, rounding) & ((1 << to.width) - 1)
        assert q == (low - (1 << to.width) if to.signed and low >> (to.width - 1) else low)


def test_overflow_error_message():
    with pytest.raises(FixedOverflowError, match=r"^lirp out: 2 value\(s\) overflow format S7\.0 "
                                                 r"\(range -128\.0\.\.127\.0\); first offending "
                                                 r"value 300\.0 \(raw 300\)$"):
        Fixed([0, 300, 5, -400], "S9.0").quantize("S7.0", "truncate", "error", op="lirp out")
    # the first offending value is the rounded one, in row-major order
    with pytest.raises(FixedOverflowError, match=r"^quantize: 3 value\(s\) overflow format 0\.2 "
                                                 r"\(range 0\.0\.\.0\.75\); first offending value "
                                                 r"-0\.25 \(raw -1\)$"):
        quantize_raw([[7, -1], [-9, 15]], "S2.3", "0.2", "truncate", "error")
    assert issubclass(FixedOverflowError, OverflowError)
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        quantize_raw([1], "2.2", "2.0", "nearest", "wrap")
    with pytest.raises(ValueError, match=r"^overflow must be one of saturate, wrap, error, "
                                         r"not 'clip'$"):
        Fixed([1], "2.2").quantize("2.0", "truncate", "clip")


# -- floats ---------------------------------------------------------------------------------

@st.composite
def float_cases(draw, inside):
    """A format and a float; near codes and exact ties often; inside the format if asked."""
    fmt = draw(st.one_of(formats(), formats(min_width=54)))  # wider than a float's mantissa too
    lo, hi = Fraction(fmt.min_raw, fmt.one), Fraction(fmt.max_raw, fmt.one)
    kind = draw(st.sampled_from(["tie", "near", "any"]))
    if kind == "any":
        x = draw(st.floats(allow_nan=False, allow_infinity=False) if not inside else
                 st.floats(float(lo), float(hi), allow_nan=False))
    else:
        span = 2 if inside else 2 ** 70
        anchors = [fmt.min_raw, fmt.max_raw, fmt.max_raw * 3 // 4, fmt.min_raw * 3 // 4]
        code = draw(st.one_of(  # near the ends of the range often: integers() favours small
            st.builds(int.__add__, st.sampled_from(anchors), st.integers(-span, span)),
            st.integers(fmt.min_raw - span, fmt.max_raw + span)))
        offset = Fraction(1, 2) if kind == "tie" else Fraction(draw(st.integers(-4, 4)), 8)
        x = float(Fraction(code, fmt.one) + offset / fmt.one)
    if inside:
        assume(lo <= Fraction(x) <= hi)
    return fmt, x


@SETTINGS
@given(float_cases(inside=True), st.sampled_from(ROUNDINGS))
def test_float_round_trip_within_half_an_lsb(case, rounding):
    fmt, x = case
    y = Fixed.from_float(x, fmt, rounding, "error")
    assert y.fmt == fmt and y.raw.dtype == np.int64
    back = y.to_float()
    error = Fraction(float(back)) - Fraction(x)
    lsb = Fraction(1, fmt.one)
    if rounding == "truncate":
        assert -lsb < error <= 0
    else:
        assert abs(error) <= lsb / 2
    assert int(y.raw) == ref_round(Fraction(x) * fmt.one, rounding)
    # codes that are exactly representable come back unchanged
    again = Fixed.from_float(back, fmt, rounding, "error")
    assert int(again.raw) == int(y.raw)


@SETTINGS
@given(float_cases(inside=False), st.sampled_from(ROUNDINGS), st.sampled_from(OVERFLOWS))
def test_from_float_matches_exact_reference(case, rounding, overflow):
    fmt, x = case
    rounded = ref_round(Fraction(x) * fmt.one, rounding)
    expected = ref_overflow(rounded, fmt, overflow)
    if expected is None:
        with pytest.raises(FixedOverflowError, match="^" + re.escape(
                overflow_message("from_float", fmt, 1, rounded)) + "$"):
            Fixed.from_float(x, fmt, rounding, overflow)
        return
    assert int(Fixed.from_float(x, fmt, rounding, overflow).raw) == expected
    # and as one element of an array
    arr = Fixed.from_float([0.0, x], fmt, rounding, overflow)
    assert arr.raw.tolist() == [0, expected]


@pytest.mark.parametrize("x, fmt, rounding, raw", [
    (0.49999999999999994, "2.0", "round_half_up", 0),  # float x + 0.5 rounds up to 1.0
    (2.0 ** 52 + 1, "53.0", "round_half_up", 2 ** 52 + 1),  # float x + 0.5 rounds to even
    (0.75, "S0.63", "round_half_up", 3 << 61),  # codes above 2**62 must not be clipped
    (-0.75, "S0.63", "truncate", -(3 << 61)),
    (0.75, "0.63", "round_half_even", 3 << 61),
    (-1.0, "S0.63", "round_half_even", -(2 ** 63)),
    (2.5, "2.0", "round_half_even", 2), (3.5, "2.0", "round_half_even", 3),  # 4 saturates
    (-2.5, "S2.0", "round_half_up", -2), (-2.5, "S2.0", "truncate", -3),
])
def test_from_float_examples(x, fmt, rounding, raw):
    assert int(Fixed.from_float(x, fmt, rounding, "saturate").raw) == raw


def test_from_float_huge_values():
    assert int(Fixed.from_float(1e300, "S0.63", overflow="saturate").raw) == 2 ** 63 - 1
    assert int(Fixed.from_float(-1e300, "0.63", overflow="saturate").raw) == 0
    assert int(Fixed.from_float(1e300, "S0.63", overflow="wrap").raw) == 0  # a multiple of 2**64
    assert int(Fixed.from_float(2.0 ** 64 + 2.0 ** 12, "S10.3", overflow="wrap").raw) == 0
    assert int(Fixed.from_float(2.0 ** 70 + 2.0 ** 60, "S63.0", overflow="wrap").raw) == 2 ** 60
    assert int(Fixed.from_float(2.0 ** 63, "S63.0", overflow="wrap").raw) == -(2 ** 63)
    with pytest.raises(FixedOverflowError, match=r"^from_float: 1 value\(s\) overflow format 1\.2 "
                                                 r"\(range 0\.0\.\.1\.75\); first offending value "
                                                 r"2\.0 \(raw 8\)$"):
        Fixed.from_float(1.9, "1.2")


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_from_float_refuses_non_finite(bad):
    with pytest.raises(ValueError, match=r"^from_float: values must be finite to convert to "
                                         r"S1\.10$"):
        Fixed.from_float([0.0, bad], "S1.10", overflow="saturate")


# -- check_range ----------------------------------------------------------------------------

def test_check_range_messages():
    x = Fixed([0, 16, 24, 20, -8], "S1.4")
    with pytest.raises(ValueError, match=r"^a must be in 0\.\.1; 3 value\(s\) are not, "
                                         r"first 1\.5 \(raw 24\)$"):
        check_range("a", x, 0, 1)
    with pytest.raises(ValueError, match=r"^n must be in 0\.25\.\.2; 2 value\(s\) are not, "
                                         r"first 0 \(raw 0\)$"):
        check_range("n", x, 0.25, 2)
    assert check_range("a", x, -0.5, 1.5) is x
    assert check_range("a", x, -np.inf, np.inf) is x
    with pytest.raises(ValueError, match=r"^a must be in -inf\.\.-1; 5 value\(s\) are not"):
        check_range("a", x, -np.inf, -1)


def test_check_range_is_exact_for_wide_formats():
    # 2**61 + 1 in S0.62 is 0.5 + 2**-62: float comparison would round it to 0.5
    with pytest.raises(ValueError, match=r"^x must be in 0\.\.0\.5; 1 value\(s\) are not, "
                                         r"first 0\.5 \(raw 2305843009213693953\)$"):
        check_range("x", Fixed([2 ** 61, 2 ** 61 + 1], "S0.62"), 0, 0.5)
    check_range("x", Fixed([2 ** 62 - 1], "0.62"), 0, 1)
    with pytest.raises(ValueError, match=r"^x must be in -0\.25\.\.0; 1 value\(s\) "):
        check_range("x", Fixed([-(2 ** 60), -(2 ** 60) - 1], "S0.62"), -0.25, 0)


@SETTINGS
@given(fixed_arrays(), st.integers(-(2 ** 66), 2 ** 66), st.integers(0, 2 ** 66), st.integers(0, 70))
def test_check_range_refuses_exactly_the_values_outside(x, lo_num, span, shift):
    lo = float(Fraction(lo_num, 2 ** shift))
    hi = float(Fraction(lo_num + span, 2 ** shift))
    outside = [v for v in values(x) if not Fraction(lo) <= v <= Fraction(hi)]
    if not outside:
        assert check_range("v", x, lo, hi) is x
        return
    first = int(np.ravel(x.raw)[[not Fraction(lo) <= v <= Fraction(hi) for v in values(x)]][0])
    with pytest.raises(ValueError, match="^" + re.escape(
            f"v must be in {lo:g}..{hi:g}; {len(outside)} value(s) are not, "
            f"first {first * x.fmt.lsb:g} (raw {first})") + "$"):
        check_range("v", x, lo, hi)
