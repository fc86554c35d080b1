"""Each block's extreme-input rows beside its stimulus, and the checks they share."""

from fractions import Fraction

import numpy as np
import pytest

from phongfx.core.format import Format
from phongfx.core.registry import REGISTRY, block_names, get_block
from phongfx.sim.stimulus import perpendicular_pairs
from phongfx.sim.stimulus.extreme import Extreme, round_exact, wrap


@pytest.mark.parametrize("name", block_names())
def test_every_block_has_extreme_rows_of_its_own(name):
    rows = get_block(name).extremes()
    assert isinstance(rows, tuple) and rows
    assert all(isinstance(row, Extreme) for row in rows)
    assert {row.block for row in rows} == {name}
    assert len({row.name for row in rows}) == len(rows)


@pytest.mark.parametrize("name", block_names())
def test_rows_build_inputs_the_block_takes(name):
    block = get_block(name)
    for row in block.extremes():
        raw = row.build(block.config)
        assert set(raw) == set(block.config.inputs), row.name
        again = row.build(block.config)  # seeded per row: the same codes every time
        assert all(np.array_equal(raw[port], again[port]) for port in raw), row.name


def test_the_datapaths_share_one_function_that_takes_the_block_name():
    functions = {REGISTRY[name].load("extremes") for name in ("fig7", "fig8", "halfway_datapath")}
    assert len(functions) == 1
    spec = {name: [row.expected for row in get_block(name).extremes()]
            for name in ("fig7", "halfway_datapath")}
    # V = −L: no highlight through D = R − L, a full one through the halfway vector H = 0
    assert "spec = 0 " in spec["fig7"][-1] and "spec = 1 " in spec["halfway_datapath"][-1]


def test_perpendicular_pairs():
    first, second = perpendicular_pairs()
    assert first.shape == second.shape == (24, 3)
    assert np.all(np.sum(first * second, axis=-1) == 0)
    assert len({(tuple(a), tuple(b)) for a, b in zip(first, second)}) == 24


def test_round_exact_floors_or_rounds_half_up_and_saturates():
    fmt = Format.parse("1.2")
    assert round_exact(Fraction(3, 8), fmt, "truncate") == 1
    assert round_exact(Fraction(3, 8), fmt) == 2
    assert round_exact(Fraction(5, 1), fmt) == fmt.max_raw
    assert round_exact(Fraction(-1, 1), fmt) == fmt.min_raw


def test_wrap_is_twos_complement():
    fmt = Format.parse("S1.2")  # 4 bits: -8..7
    assert [wrap(code, fmt) for code in (7, 8, -9, 16, 3)] == [7, -8, 7, 0, 3]
    assert wrap(17, Format.parse("2.2")) == 1
