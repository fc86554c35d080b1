"""``phongfx tables szirmay``: Table 1 and the Figure 11 ROM error grid."""

import json
import re

import pytest

from phongfx.cli import main
from phongfx.papers.szirmay import BITS, PAPER_TABLE1, figure11, run_table, szirmay, table1


def test_table1_holds_for_every_n():
    rows = table1()
    assert [r["n"] for r in rows] == list(PAPER_TABLE1)
    assert all(r["holds"] and abs(r["difference"]) <= 1e-4 for r in rows)
    assert round(rows[-1]["measured"], 4) == 13.5535


def test_figure11_grid():
    cells = {(c["addr_bits"], c["data_bits"]): c for c in figure11()}
    assert sorted(cells) == [(a, d) for a in BITS for d in BITS]
    assert all(c["max"] <= c["bound"] and c["mean"] <= c["max"] for c in cells.values())
    assert cells[6, 6]["rom_bits"] == 384
    # more address bits, more data bits: the error falls (max within a rounding, mean strictly)
    assert cells[10, 10]["max"] < cells[6, 6]["max"] < cells[4, 4]["max"]
    assert cells[10, 10]["mean"] < cells[6, 6]["mean"] < cells[4, 4]["mean"]


def test_unknown_table():
    with pytest.raises(ValueError, match=r"^unknown table 'lyon'; valid tables: szirmay$"):
        run_table("lyon")


def test_cli_markdown(capsys):
    assert main(["tables", "szirmay"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"^\| 500 \| 13\.5535 \| 13\.5535 \| -4\.20e-05 \| yes \|$", out, re.M), out
    assert re.search(r"^\| A \\ D \| 3 \| 4 \| 5 \| 6 \| 7 \| 8 \| 9 \| 10 \|$", out, re.M), out
    assert re.search(r"^Paper's choice 6 × 6 = 384 bits: max 0\.0507, mean 0\.0166; .* holds in every "
                     r"cell: yes\.$", out, re.M), out


def test_cli_json(capsys):
    assert main(["tables", "szirmay", "--json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result == json.loads(json.dumps(szirmay()))
    assert len(result["figure11"]) == 64 and len(result["table1"]) == 7
