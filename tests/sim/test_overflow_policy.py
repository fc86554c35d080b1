"""No silent overflow, so that a wrong answer never looks like a right one: every quantize
in the golden models and the HDL names its overflow policy, and the golden model raises on
an undeclared overflow.

The scan reads the source of ``golden/*.py`` and ``hdl/*.py`` with :mod:`ast`: every
call of ``quantize``, ``quantize_raw``, ``quantize_cut``, ``.quantize(...)`` and
``Fixed.from_float`` must pass its ``overflow`` argument (no default), and that
argument must be one of :data:`~phongfx.core.format.OVERFLOWS` as a literal, a config
property named ``*_overflow`` (e.g. ``NormalizeConfig.y2_overflow``), or, inside a
function that itself takes ``overflow``, that parameter passed on.
"""

import ast
from pathlib import Path

import numpy as np
import pytest

from phongfx.core.format import OVERFLOWS
from phongfx.core.registry import get_block
from phongfx.golden.fixed import Fixed, FixedOverflowError, quantize_raw
from phongfx.hdl.overflow import overflow_checks
from phongfx.sim.harness import check

ROOT = Path(__file__).resolve().parents[2]
SOURCES = sorted([*ROOT.glob("golden/*.py"), *ROOT.glob("hdl/*.py")])

#: Narrowing call -> position of its ``overflow`` argument (after ``self`` for methods).
POSITION = {"quantize": 2, "quantize_raw": 4, "quantize_cut": 4, "from_float": 3}
#: ``quantize`` called as a free function is ``hdl.fixed.quantize(value, frm, to, rounding, overflow)``.
FREE_QUANTIZE_POSITION = 4


def _calls(tree):
    """(call, enclosing function's parameter names) for every narrowing call in ``tree``."""
    found = []

    def visit(node, params):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            params = {a.arg for a in node.args.args + node.args.kwonlyargs}
        if isinstance(node, ast.Call):
            func = node.func
            name = func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", None)
            if name in POSITION:
                found.append((node, name, isinstance(func, ast.Attribute), params))
        for child in ast.iter_child_nodes(node):
            visit(child, params)

    visit(tree, set())
    return found


def _overflow_argument(call, name, method):
    if name == "quantize":
        position = POSITION[name] if method else FREE_QUANTIZE_POSITION
    else:
        position = POSITION[name]
    for keyword in call.keywords:
        if keyword.arg == "overflow":
            return keyword.value
    return call.args[position] if len(call.args) > position else None


def _problem(call, name, method, params):
    """Why this call's overflow policy is not named, or None."""
    argument = _overflow_argument(call, name, method)
    if argument is None:
        return "no overflow argument (defaulted)"
    if isinstance(argument, ast.Constant):
        return None if argument.value in OVERFLOWS else f"unknown policy {argument.value!r}"
    if isinstance(argument, ast.Attribute) and argument.attr.endswith("overflow"):
        return None  # a config property that decides the policy from the formats
    if isinstance(argument, ast.Name) and argument.id == "overflow" and "overflow" in params:
        return None  # passed on from a caller that names it
    return f"policy {ast.unparse(argument)!r} is not a literal, config property or parameter"


def _scan(path):
    tree = ast.parse(path.read_text(), filename=str(path))
    problems, count = [], 0
    for call, name, method, params in _calls(tree):
        count += 1
        problem = _problem(call, name, method, params)
        if problem:
            problems.append(f"{path.relative_to(ROOT)}:{call.lineno}: {name}: {problem}")
    return count, problems


def test_sources_found():
    names = {f"{p.parent.name}/{p.name}" for p in SOURCES}
    assert {"golden/fixed.py", "golden/lirp.py", "hdl/fixed.py", "hdl/lirp.py"} <= names


def test_every_quantize_names_its_overflow_policy():
    counts, problems = {}, []
    for path in SOURCES:
        counts[f"{path.parent.name}/{path.stem}"], found = _scan(path)
        problems += found
    assert not problems, "\n".join(problems)
    # the scan sees every block's narrowing steps, not an empty set: in the block's own file, or
    # in the one it shares them from (Gouraud's recurrence is Euler's one order lower; Blinn's
    # unit is built of the table steps of hdl/tables.py, which conventional Phong shares)
    narrowing = ("lirp", "normalize", "reflect", "difference", "shape", "diffuse", "root",
                 "halfway", "schlick", "spherical", "euler", "gouraud", "blinn", "conventional")
    home = {("golden", "gouraud"): "euler", ("hdl", "gouraud"): "euler", ("hdl", "blinn"): "tables"}
    missing = [f"{side}/{name}" for side in ("golden", "hdl") for name in narrowing
               if not counts.get(f"{side}/{home.get((side, name), name)}")]
    assert not missing, missing


@pytest.mark.parametrize("source, problem", [
    ("x.quantize(fmt, 'truncate')", "no overflow argument (defaulted)"),
    ("Fixed.from_float(v, fmt, 'round_half_up')", "no overflow argument (defaulted)"),
    ("quantize_raw(r, a, b, 'truncate', 'clamp')", "unknown policy 'clamp'"),
    ("quantize(v, a, b, 'truncate', mode)",
     "policy 'mode' is not a literal, config property or parameter"),
    ("x.quantize(fmt, 'truncate', overflow=policy)",
     "policy 'policy' is not a literal, config property or parameter"),
])
def test_scan_rejects(source, problem):
    (call, name, method, params), = _calls(ast.parse(source))
    assert _problem(call, name, method, params) == problem


@pytest.mark.parametrize("source", [
    "x.quantize(fmt, 'truncate', 'saturate', op='y')",
    "quantize_cut(m, x, to, r, 'wrap', on)",
    "x.quantize(to, r, cfg.y2_overflow)",
    "def f(x, overflow):\n    return quantize(x, a, b, 'truncate', overflow)",
])
def test_scan_accepts(source):
    (call, name, method, params), = _calls(ast.parse(source))
    assert _problem(call, name, method, params) is None


def test_golden_raises_on_declared_error_overflow():
    # 2 − 2⁻¹⁰ doubled is 4 − 2⁻⁹: past S1.10, whose range is −2 .. 2 − 2⁻¹⁰
    x = Fixed(np.array([2047, 3]), "S1.10")
    with pytest.raises(FixedOverflowError, match=r"^double: 1 value\(s\) overflow format S1\.10 "
                                                 r"\(range -2\.0\.\.1\.9990234375\); first offending "
                                                 r"value 3\.998046875 \(raw 4094\)$"):
        (x + x).quantize("S1.10", "truncate", "error", op="double")
    assert (x + x).quantize("S1.10", "truncate", "saturate").raw.tolist() == [2047, 6]
    assert (x + x).quantize("S1.10", "truncate", "wrap").raw.tolist() == [4094 - 4096, 6]
    with pytest.raises(FixedOverflowError, match=r"^from_float: 1 value\(s\) overflow format 0\.8"):
        Fixed.from_float([0.5, 1.0], "0.8", "round_half_up", "error")
    with pytest.raises(FixedOverflowError):
        quantize_raw(np.array([-1]), "S1.10", "1.10", "truncate", "error")


def _lirp_narrow():
    """A LIRP whose output format cannot hold 1.0 (``out = S0.10``): its ``N'`` quantize is
    declared ``"error"`` (Lyon's unit vectors interpolate inside the unit ball)."""
    block = get_block("lirp", out="S0.10")
    inputs = {"n0": np.array([[1024, 0, 0]]), "n1": np.array([[1024, 0, 0]]), "a": np.array([0])}
    return block, inputs


def test_block_golden_raises_on_an_overflow_it_declared_impossible():
    block, inputs = _lirp_narrow()
    with pytest.raises(FixedOverflowError, match=r"^lirp N': 1 value\(s\) overflow format S0\.10"):
        block.golden(inputs)


def test_rtl_flags_a_declared_error_overflow():
    """The HDL behaviour of ``overflow="error"`` (:func:`phongfx.hdl.fixed.quantize`): the low
    bits are kept (+1.0 leaves an ``S0.10`` port as −1.0) and the block's overflow flag rises,
    so the harness reports the cycle even when handed the wrapped value as "expected"."""
    block, inputs = _lirp_narrow()
    wrapped = {"n": np.array([[-1024, 0, 0]])}  # 1024 in 11 bits, two's complement
    result = check(block, inputs, expected=wrapped, bubbles=0)
    assert result.mismatch_count == 1
    mm = result.mismatches[0]
    assert (mm.cycle, mm.what) == (block.latency, "RTL overflow that the golden model did not predict")
    assert mm.got == {"n": [-1024, 0, 0], "overflow": 1}
    with overflow_checks(False):  # as synthesized: the same low bits, no flag
        assert check(block, inputs, expected=wrapped, bubbles=0).ok