"""Laws of :class:`phongfx.core.format.Format`: notation, limits, and minimal result formats."""

import itertools
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from phongfx.core.format import OVERFLOWS, ROUNDINGS, Format, check_overflow, check_rounding

SETTINGS = settings(deadline=None, derandomize=True, max_examples=150)


@st.composite
def formats(draw, max_width=64, min_width=1):
    """Any legal format of ``min_width..max_width`` bits (unsigned at most 63)."""
    signed = draw(st.booleans())
    limit = max_width if signed else min(max_width, 63)
    width = draw(st.integers(min_width, limit))
    frac = draw(st.integers(0, width - signed))
    return Format(width - signed - frac, frac, signed)


def tiny_formats(max_width=3):
    """Every format of at most ``max_width`` bits."""
    found = []
    for signed in (False, True):
        for n in range(max_width + 1):
            for m in range(max_width + 1):
                if 1 <= n + m + signed <= max_width:
                    found.append(Format(n, m, signed))
    return found


def codes(fmt):
    return range(fmt.min_raw, fmt.max_raw + 1)


def holds(fmt, raws):
    return all(fmt.min_raw <= r <= fmt.max_raw for r in raws)


def fits(int_bits, frac_bits, signed, raws):
    """Like ``holds`` but for any field values, even ones Format refuses (0.0, too wide)."""
    bits = int_bits + frac_bits
    lo, hi = (-(1 << bits), (1 << bits) - 1) if signed else (0, (1 << bits) - 1)
    return all(lo <= r <= hi for r in raws)


def brute_minimal(raws, frac_bits, signed_only=False):
    """The narrowest format with ``frac_bits`` holding every raw code, by search."""
    for width in itertools.count(1):
        for signed in ((True,) if signed_only else (False, True)):
            int_bits = width - signed - frac_bits
            if int_bits >= 0 and holds(Format(int_bits, frac_bits, signed), raws):
                return Format(int_bits, frac_bits, signed)


# -- notation -------------------------------------------------------------------------------

@pytest.mark.parametrize("text, fields, width", [
    ("S1.10", (1, 10, True), 12),
    ("2.20", (2, 20, False), 22),
    ("0.10", (0, 10, False), 10),
    ("S0.0", (0, 0, True), 1),
    ("1.0", (1, 0, False), 1),
    ("S0.63", (0, 63, True), 64),
    ("S63.0", (63, 0, True), 64),
    ("63.0", (63, 0, False), 63),
    ("0.63", (0, 63, False), 63),
])
def test_parse_examples(text, fields, width):
    fmt = Format.parse(text)
    assert (fmt.int_bits, fmt.frac_bits, fmt.signed) == fields
    assert fmt.width == width
    assert str(fmt) == text
    assert repr(fmt) == f"Format({text!r})"
    assert Format.parse(fmt) is fmt
    assert Format.parse(f"  {text}\n") == fmt  # surrounding blanks are ignored


@SETTINGS
@given(formats())
def test_print_parse_round_trip(fmt):
    text = str(fmt)
    assert re.fullmatch(r"S?[0-9]+\.[0-9]+", text)
    assert Format.parse(text) == fmt
    assert str(Format.parse(text)) == text
    assert hash(Format.parse(text)) == hash(fmt)


@pytest.mark.parametrize("text", [
    "", "S", "1", "S1", "1.", ".5", "S.5", "s1.10", "S-1.2", "-1.2", "1.-2", "1.2.3", "SS1.2",
    "1,2", "S1.10x", "xS1.10", "S 1.10", "1 .2", "+1.2", "1.2e3", "0x1.2", "1_0.2",
    "\u0661.\u0661",  # Arabic-Indic digits match \d but are not Lyon's notation
    "\uff11.\uff12",  # full-width digits
])
def test_bad_strings_are_refused(text):
    with pytest.raises(ValueError, match="^" + re.escape(
            f"format must look like 'n.m' (unsigned) or 'Sn.m' (signed), not {text!r}") + "$"):
        Format.parse(text)


@pytest.mark.parametrize("thing", [1.5, 3, None, b"S1.10", ("S", 1, 10)])
def test_non_strings_are_refused(thing):
    with pytest.raises(TypeError, match=r"^format must be a string like 'S1\.10' or a Format, not "):
        Format.parse(thing)


@pytest.mark.parametrize("text, width, kind, limit", [
    ("S40.30", 71, "a signed", 64),
    ("S63.1", 65, "a signed", 64),
    ("S0.64", 65, "a signed", 64),
    ("40.24", 64, "an unsigned", 63),
    ("64.0", 64, "an unsigned", 63),
    ("0.64", 64, "an unsigned", 63),
    ("100.100", 200, "an unsigned", 63),
])
def test_formats_wider_than_int64_are_refused(text, width, kind, limit):
    message = (f"^format {re.escape(text)} is {width} bits wide; raw values are held in numpy "
               f"int64, so {kind} format may have at most {limit} bits$")
    with pytest.raises(ValueError, match=message):
        Format.parse(text)
    n, m = (int(x) for x in text.lstrip("S").split("."))
    with pytest.raises(ValueError, match=message):
        Format(n, m, text.startswith("S"))


def test_format_without_bits_is_refused():
    with pytest.raises(ValueError, match=r"^format 0\.0 has no bits$"):
        Format.parse("0.0")
    with pytest.raises(ValueError, match=r"^format 0\.0 has no bits$"):
        Format(0, 0)


@pytest.mark.parametrize("kwargs, error, message", [
    (dict(int_bits=-1, frac_bits=2), ValueError, r"^int_bits must be a non-negative integer, not -1$"),
    (dict(int_bits=1, frac_bits=-3), ValueError, r"^frac_bits must be a non-negative integer, not -3$"),
    (dict(int_bits=1.0, frac_bits=2), ValueError, r"^int_bits must be a non-negative integer, not 1\.0$"),
    (dict(int_bits=True, frac_bits=2), ValueError, r"^int_bits must be a non-negative integer, not True$"),
    (dict(int_bits=1, frac_bits="2"), ValueError, r"^frac_bits must be a non-negative integer, not '2'$"),
    (dict(int_bits=1, frac_bits=2, signed=1), TypeError, r"^signed must be a bool, not 1$"),
])
def test_bad_fields_are_refused(kwargs, error, message):
    with pytest.raises(error, match=message):
        Format(**kwargs)


def test_rounding_and_overflow_names():
    assert ROUNDINGS == ("truncate", "round_half_up", "round_half_even")
    assert OVERFLOWS == ("saturate", "wrap", "error")
    for name in ROUNDINGS:
        assert check_rounding(name) == name
    for name in OVERFLOWS:
        assert check_overflow(name) == name
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'round'$"):
        check_rounding("round")
    with pytest.raises(ValueError, match=r"^overflow must be one of saturate, wrap, error, not None$"):
        check_overflow(None)


# -- ranges ---------------------------------------------------------------------------------

@SETTINGS
@given(formats())
def test_width_and_raw_range(fmt):
    n, m = fmt.int_bits, fmt.frac_bits
    assert fmt.width == n + m + fmt.signed
    # exactly 2**width codes, two's complement when signed
    assert fmt.max_raw - fmt.min_raw + 1 == 2 ** fmt.width
    if fmt.signed:
        assert fmt.min_raw == -(2 ** (fmt.width - 1)) and fmt.max_raw == 2 ** (fmt.width - 1) - 1
    else:
        assert fmt.min_raw == 0 and fmt.max_raw == 2 ** fmt.width - 1
    # every code fits numpy int64
    assert -(2 ** 63) <= fmt.min_raw and fmt.max_raw <= 2 ** 63 - 1
    # values: n integer bits hold magnitudes below 2**n
    assert fmt.max_raw * fmt.lsb == pytest.approx(2.0 ** n - 2.0 ** -m, rel=1e-15)
    assert fmt.lsb == 2.0 ** -m and fmt.one == 2 ** m
    assert fmt.holds_one() == (fmt.max_raw >= fmt.one)
    shape = fmt.shape()
    assert shape.width == fmt.width and shape.signed == fmt.signed


# -- result formats: sufficient and minimal ---------------------------------------------------

TINY = tiny_formats(3)
TINY_PAIRS = list(itertools.product(TINY, TINY))


def _brute_case(a, b, op):
    if op == "add":
        f = max(a.frac_bits, b.frac_bits)
        raws = {(x << (f - a.frac_bits)) + (y << (f - b.frac_bits)) for x in codes(a) for y in codes(b)}
        return a.add(b), raws, f, False
    if op == "sub":
        f = max(a.frac_bits, b.frac_bits)
        raws = {(x << (f - a.frac_bits)) - (y << (f - b.frac_bits)) for x in codes(a) for y in codes(b)}
        return a.sub(b), raws, f, True  # subtractors are signed by definition
    f = a.frac_bits + b.frac_bits
    return a.mul(b), {x * y for x in codes(a) for y in codes(b)}, f, False


@pytest.mark.parametrize("op", ["add", "sub", "mul"])
def test_binary_result_formats_match_brute_force(op):
    # every pair of formats of up to 3 bits, every pair of codes
    for a, b in TINY_PAIRS:
        fmt, raws, f, signed_only = _brute_case(a, b, op)
        assert fmt.frac_bits == f, (op, a, b)
        assert holds(fmt, raws), (op, a, b, fmt)
        assert fmt == brute_minimal(raws, f, signed_only), (op, a, b, fmt)
        assert fmt == (b.add(a) if op == "add" else b.mul(a) if op == "mul" else fmt)  # commutes


def test_neg_result_format_matches_brute_force():
    for a in tiny_formats(5):
        raws = {-x for x in codes(a)}
        fmt = a.neg()
        assert fmt.frac_bits == a.frac_bits and fmt.signed
        assert holds(fmt, raws) and fmt == brute_minimal(raws, a.frac_bits, signed_only=True), a


def test_shift_result_format_matches_brute_force():
    for a in tiny_formats(4):
        for amount in range(-6, 7):
            fmt = a.shift(amount)
            k = a.shift_raw(amount)
            assert k >= 0 and fmt.signed == a.signed
            # value preserved: raw r of a becomes r << k of fmt, worth r * 2**amount
            assert fmt.frac_bits == a.frac_bits - amount + k
            raws = {x << k for x in codes(a)}
            assert holds(fmt, raws)
            # the smallest format with these fraction bits and a's signedness
            assert fmt == brute_minimal(raws, fmt.frac_bits), (a, amount, fmt)
            # bits never move unless the fraction part is used up
            assert k == max(amount - a.frac_bits, 0)


def _corners(fmt):
    return (fmt.min_raw, fmt.max_raw)


def _check_minimal(fmt, raws, signed_only=False):
    """``fmt`` holds ``raws``; one integer bit fewer does not; nor does dropping the sign."""
    assert holds(fmt, raws)
    if fmt.int_bits > 0 and fmt.width > 1:
        assert not fits(fmt.int_bits - 1, fmt.frac_bits, fmt.signed, raws)
    if fmt.signed and not signed_only:
        assert not fits(fmt.int_bits, fmt.frac_bits, False, raws)
    if fmt.signed and not signed_only:
        assert min(raws) < 0


def _try(method, *args):
    try:
        return method(*args)
    except ValueError as error:
        assert re.fullmatch(r"format S?\d+\.\d+ is \d+ bits wide; raw values are held in numpy "
                            r"int64, so an? (un)?signed format may have at most 6[34] bits",
                            str(error)), str(error)
        return None


@SETTINGS
@given(formats(max_width=40), formats(max_width=40))
def test_result_formats_hold_corners_minimally(a, b):
    # extremes of + - * are at the corners of the operand ranges
    f = max(a.frac_bits, b.frac_bits)
    sa, sb = 1 << (f - a.frac_bits), 1 << (f - b.frac_bits)
    checks = [
        (_try(a.add, b), [x * sa + y * sb for x in _corners(a) for y in _corners(b)], False),
        (_try(a.sub, b), [x * sa - y * sb for x in _corners(a) for y in _corners(b)], True),
        (_try(a.mul, b), [x * y for x in _corners(a) for y in _corners(b)], False),
        (_try(a.neg), [-x for x in _corners(a)], True),
    ]
    for fmt, raws, signed_only in checks:
        if fmt is None:
            # refused only when the minimal format is wider than int64 allows
            lo, hi = min(raws), max(raws)
            if lo < 0 or signed_only:
                assert max(-lo - 1, hi).bit_length() + 1 > 64
            else:
                assert hi.bit_length() > 63
            continue
        _check_minimal(fmt, raws, signed_only)


@SETTINGS
@given(formats(max_width=60), st.integers(-70, 70))
def test_shift_format_law(a, amount):
    fmt = _try(a.shift, amount)
    k = a.shift_raw(amount)
    # independently: the point moves; integer and fraction parts never go below zero
    n, m = max(a.int_bits + amount, 0), max(a.frac_bits - amount, 0)
    if fmt is None:
        assert n + m + a.signed > (64 if a.signed else 63)
        return
    assert (fmt.int_bits, fmt.frac_bits) == (n, m)
    assert fmt.signed == a.signed
    # same value: (r << k) * 2**-fmt.frac == r * 2**-a.frac * 2**amount
    assert fmt.frac_bits - k == a.frac_bits - amount
    _check_minimal(fmt, [x << k for x in _corners(a)], signed_only=True)


def test_covering_is_smallest_for_its_range():
    for lo in range(-20, 21):
        for hi in range(max(lo, 0), 41):
            for frac in range(0, 4):
                fmt = Format.covering(lo, hi, frac)
                assert fmt.frac_bits == frac
                assert fmt == brute_minimal([lo, hi], frac), (lo, hi, frac)


def test_result_format_examples():
    p = Format.parse
    assert p("S1.10").add(p("S1.10")) == p("S2.10")
    assert p("1.10").add(p("0.4")) == p("2.10")
    assert p("2.2").sub(p("2.2")) == p("S2.2")
    assert p("S1.10").mul(p("S1.10")) == p("S3.20")  # -2 * -2 = +4 needs a third integer bit
    assert p("1.10").mul(p("0.8")) == p("1.18")
    assert p("S1.3").neg() == p("S2.3") and p("2.3").neg() == p("S2.3")
    assert p("S1.3").shift(2) == p("S3.1") and p("S1.3").shift(5) == p("S6.0")
    assert p("S1.3").shift(-1) == p("S0.4") and p("S1.3").shift(-3) == p("S0.6")
    with pytest.raises(ValueError, match=r"^format S63\.1 is 65 bits wide; .* at most 64 bits$"):
        p("S31.1").mul(p("S31.0"))
    assert p("S31.0").mul(p("S31.0")) == p("S63.0")  # -2**31 * -2**31 = 2**62: all 64 bits
    assert p("S30.0").mul(p("S31.0")) == p("S62.0")
