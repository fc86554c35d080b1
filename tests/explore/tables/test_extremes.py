"""The extremes table: every block at its extreme input classes (its stability where the
inputs are extreme), golden against the documented behaviour and RTL against golden, on
both back ends."""

import json
import re

import numpy as np
import pytest

from phongfx.cli import main
from phongfx.core.registry import block_names, get_block
from phongfx.explore.tables import extremes
from phongfx.explore.tables.extremes import all_rows, rows_for, run_block

#: Every row of the table, in order.
EXTREMES = all_rows()

#: The extreme input classes the table must cover, each a pattern some row's name must match.
CLASSES = [r"±1\.0", r"180°", r"n = 1", r"n_max", r"m = 1", r"m_max", r"\|D\| = 2", r"R = L",
           r"grazing", r"V = −L", r"span of 1 pixel", r"2048 pixels", r"wrap", r"smallest divisor",
           r"largest divisor", r"all-ones", r"all-zeros"]

#: Rows whose check is a bound or a sign, which flipping the LSB of every output can keep.
TOLERANT = {("normalize", "all-ones codes (|N'| up to 2√3)")}


@pytest.mark.parametrize("pattern", CLASSES)
def test_every_extreme_class_has_a_row(pattern):
    assert any(re.search(pattern, row.name) for row in EXTREMES), pattern


def test_every_block_has_rows():
    assert {row.block for row in EXTREMES} == set(block_names())


def test_rows_come_from_the_registry_in_its_order():
    def key(row):  # the build and holds closures are new on every call
        return row.block, row.name, row.expected
    assert [key(row) for row in EXTREMES] == [key(row) for name in block_names()
                                             for row in get_block(name).extremes()]
    assert [row.block for row in EXTREMES] == sorted((row.block for row in EXTREMES),
                                                     key=block_names().index)
    assert rows_for("no_such_block") == ()


@pytest.mark.parametrize("row", [r for r in EXTREMES if (r.block, r.name) not in TOLERANT],
                         ids=lambda r: f"{r.block}:{r.name}")
def test_expected_behaviour_check_can_fail(row):
    """Each row's check rejects golden outputs with the LSB of every code flipped."""
    block = get_block(row.block)
    inputs = {k: np.asarray(v, dtype=np.int64) for k, v in row.build(block.config).items()}
    outputs = block.golden(inputs)
    assert np.all(row.holds(block.config, inputs, outputs))
    flipped = {name: value ^ 1 for name, value in outputs.items()}
    assert not np.all(row.holds(block.config, inputs, flipped))


def _check_rows(backend, block):
    rows, _ = run_block(block, backend)
    assert len(rows) == len(rows_for(block))
    for row in rows:
        assert (row["golden"], row["rtl"]) == ("pass", "pass"), row


@pytest.mark.parametrize("block", block_names())
def test_extremes_amaranth(block):
    _check_rows("amaranth", block)


@pytest.mark.needs_verilator
@pytest.mark.parametrize("block", block_names())
def test_extremes_verilator(block):
    # verilator-fast: the cocotb back end checks the same Verilog (tests/conftest.py COCOTB_TESTS)
    _check_rows("verilator-fast", block)


def test_rtl_mismatch_is_attributed_to_its_row(monkeypatch):
    """A wrong golden output on one vector fails that row's RTL verdict only."""
    block = get_block("diffuse")
    real = type(block).golden

    total = sum(len(row.build(block.config)["n"]) for row in rows_for("diffuse"))

    def broken(self, raw):
        # only the harness's run of every row back to back; vector 2 is in the first row
        out = real(self, raw)
        if len(out["diff"]) == total:
            out["diff"] = out["diff"].copy()
            out["diff"][2] ^= 1
        return out

    monkeypatch.setattr(type(block), "golden", broken)
    rows, _ = run_block("diffuse")
    assert {row["golden"] for row in rows} == {"pass"}
    verdicts = {row["class"]: row["rtl"] for row in rows}
    assert verdicts.pop("exactly ±1.0, N = L") == "FAIL (1 cycles)"
    assert set(verdicts.values()) == {"pass"}


def test_cli_prints_the_table(tmp_path, capsys):
    assert main(["tables", "extremes", "--out", str(tmp_path)]) == 0
    text = capsys.readouterr().out
    lines = [line for line in text.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(lines) == len(EXTREMES) + 1  # header and one line per row
    assert all(line.count(" | ") == 5 for line in lines)  # |D| is escaped inside cells
    assert f"{len(EXTREMES)} rows over {len(block_names())} blocks; 0 failing." in text


def test_json_is_stable():
    result = extremes.run_table("extremes")
    again = extremes.run_table("extremes")
    assert extremes.to_json(result) == extremes.to_json(again)
    rows = json.loads(extremes.to_json(result))["rows"]
    assert [(r["block"], r["class"]) for r in rows] == [(r.block, r.name) for r in EXTREMES]


def test_unknown_table_name():
    with pytest.raises(ValueError, match=r"^unknown table 'extreme'; valid tables: extremes$"):
        extremes.run_table("extreme")
