"""No code asks a unit's name what to do.

What a block or a method does differently is declared on its registry entries (its faces,
:mod:`phongfx.core.methods`) or on its config (``SHADES``, ``TERMS``, a
:class:`~phongfx.config.base.SpecularUnit`'s methods), so that adding one touches no
if-chain.  This test reads ``phongfx/``, ``golden/``, ``hdl/`` and ``sim/`` with :mod:`ast`
and fails on a comparison (``==``, ``!=``, ``in``, ``not in``) against a string that names a
registered block or method.  The few comparisons where such a string means something else
(a table's name, an error's, a part of a proof) are listed with why.
"""

import ast
import textwrap
from pathlib import Path

from phongfx.core.methods import METHODS
from phongfx.core.registry import REGISTRY

ROOT = Path(__file__).resolve().parent.parent
FOLDERS = ("phongfx", "golden", "hdl", "sim")
NAMES = frozenset(METHODS) | frozenset(REGISTRY)

#: (file, string) -> why the comparison is not about a unit
NOT_UNITS = {
    ("phongfx/certify/gappa.py", "shape"): "the part of Figure 7's chain a Gappa script proves",
    ("phongfx/papers/schlick.py", "schlick"): "the name of the table phongfx tables schlick runs",
    ("phongfx/render/lyon.py", "diffuse"): "the diffuse error of make sim's summary, not the block",
}


def compared_names(source, names=NAMES):
    """``[(line, string)]`` of the comparisons in ``source`` against a string of ``names``."""
    found = []
    for node in ast.walk(ast.parse(source)):
        if not isinstance(node, ast.Compare):
            continue
        strings = []
        for side in (node.left, *node.comparators):
            items = side.elts if isinstance(side, (ast.Tuple, ast.List, ast.Set)) else (side,)
            strings += [item.value for item in items if isinstance(item, ast.Constant) and isinstance(item.value, str)]
        found += [(node.lineno, s) for s in strings if s in names]
    return found


def test_no_comparison_against_a_unit_name():
    found, excused = [], set()
    for folder in FOLDERS:
        for path in sorted((ROOT / folder).rglob("*.py")):
            name = path.relative_to(ROOT).as_posix()
            for line, string in compared_names(path.read_text()):
                if (name, string) in NOT_UNITS:
                    excused.add((name, string))
                else:
                    found.append(f"{name}:{line}: {string!r}")
    assert found == []
    assert excused == set(NOT_UNITS)  # the list names only comparisons that are still there


def test_the_check_finds_an_if_chain():
    source = textwrap.dedent('''
        def decode(unit, x):
            if unit == "euler":
                return x
            if unit in ("blinn", "conventional"):
                return -x
            return "fig7" != unit
        ''')
    assert compared_names(source) == [(3, "euler"), (5, "blinn"), (5, "conventional"), (7, "fig7")]
    assert compared_names('part = "spec" if kind == "diff" else "x"') == []
