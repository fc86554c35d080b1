import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.golden.chunks import CHUNK, chunked, stateless
from phongfx.golden.fixed import FixedOverflowError


def test_a_chunked_run_gives_the_whole_batch_outputs():
    fig7 = get_block("fig7")
    raw = fig7.stimulus(count=2500, seed=4)
    whole = fig7.golden(raw, whole=True)
    calls = []

    def counted(part):
        calls.append(len(part["a"]))
        return fig7.golden(part, whole=True)

    out = chunked(counted, raw, chunk=1000)
    assert calls[:2] == [1000, 1000] and sum(calls) == len(raw["a"])
    for name, value in whole.items():
        assert out[name].dtype == np.int64 and np.array_equal(out[name], value), name


def test_an_error_in_a_later_chunk_is_the_whole_batch_error():
    fig7 = get_block("fig7")
    raw = fig7.stimulus(count=2500, seed=4)
    raw["a"] = raw["a"].copy()
    raw["a"][[1500, 2100, 2200]] = fig7.config.inputs["a"][0].one + 1  # a > 1 in chunks 2 and 3
    with pytest.raises(ValueError) as whole:
        fig7.golden(raw, whole=True)
    with pytest.raises(ValueError) as cut:
        chunked(lambda part: fig7.golden(part, whole=True), raw, chunk=1000)
    assert str(cut.value) == str(whole.value)
    assert "3 value(s)" in str(whole.value)


def test_an_overflow_error_is_the_whole_batch_error():
    seen = []

    def model(part):
        seen.append(len(part["x"]))
        bad = np.flatnonzero(part["x"] > 9)
        if len(bad):
            raise FixedOverflowError(f"{len(bad)} value(s) overflow, first {part['x'][bad[0]]}")
        return {"y": part["x"] * 2}

    x = np.arange(30)
    with pytest.raises(FixedOverflowError, match="20 value"):
        chunked(model, {"x": x}, chunk=4)
    assert seen == [4, 4, 4, 30]  # the third chunk fails, then the whole batch runs


def test_short_and_ragged_batches_run_at_once():
    lengths = []

    def model(part):
        lengths.append({k: len(v) for k, v in part.items()})
        return {"y": part["x"]}

    chunked(model, {"x": np.arange(10)}, chunk=10)
    chunked(model, {"x": np.arange(30), "z": np.arange(3)}, chunk=10)
    chunked(model, {"x": np.arange(30)}, chunk=None)
    assert lengths == [{"x": 10}, {"x": 30, "z": 3}, {"x": 30}]


def test_only_a_unit_without_init_is_stateless():
    assert stateless(get_block("fig7").config.inputs)
    assert not stateless(get_block("euler").config.inputs)
    assert not stateless(["c0_init", "c0_b"]) and stateless(["initial"])
    assert CHUNK >= 4096


def test_the_stateful_euler_unit_is_not_cut():
    euler = get_block("euler")
    raw = euler.stimulus(count=1000, seed=2)  # about 5 pixels per span
    whole = euler.golden(raw, whole=True)
    cut = chunked(lambda part: euler.golden(part, whole=True), raw, chunk=1000)
    assert any(np.any(cut[name] != whole[name]) for name in whole)  # cutting a span changes it
    long = {name: np.tile(value, 14) for name, value in raw.items()}  # whole spans, over a chunk
    assert len(long["init"]) > CHUNK
    out = euler.golden(long)
    assert all(np.array_equal(out[name], np.tile(whole[name], 14)) for name in whole)
