"""Pipeline depth, which trades latency for clock frequency: same function, the stated
latency, any depth."""

import numpy as np
import pytest
from amaranth.hdl import Fragment, Module, Signal
from amaranth.sim import Simulator

from phongfx.cli import apply_settings
from phongfx.config import (DatapathConfig, HalfwayConfig, LirpConfig, NormalizeConfig, RootConfig,
                            ShapeConfig, fig7_config, fig8_config)
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.golden.fixed import quantize_raw
from phongfx.hdl.dsp import split_product
from phongfx.hdl.fixed import FixedValue, align, quantize_cut, stage
from phongfx.hdl.lirp import Lirp
from phongfx.sim.harness import check

# latency per depth 0..3, counted from the registers each depth adds (docstrings):
# depth 0 is the original design's, which the other hdl tests pin as well
LATENCY = {
    "lirp": (2, 3, 4, 4, 6),         # + inputs (1), + sum (2), no clamp to cut (3), + inputs, products (4)
    # + N', y, y·y, g·N' less the y² register (1); + Σ, z, y², y+y² (2); + 4 roundings (3);
    # + the inputs and products of 3 multiplier levels (4)
    "normalize": (4, 7, 11, 15, 21),
    "reflect": (4, 5, 7, 9, 13),      # + N, V (1); + Σ, 2(N·V)N - V (2); + 2 roundings (3); + 2 levels (4)
    "difference": (4, 5, 7, 10, 14),  # + D (1); + R - L, Σ (2); + 2 roundings, n·D·D split (3); + 2 levels (4)
    "shape": (3, 5, 5, 5, 9),         # k = 2: + each product (1); nothing more (2, 3); + 2 × 2 (4)
    "diffuse": (2, 3, 4, 5, 7),       # + N, L (1); + Σ (2); + the rounding (3); + N, L, N·L again (4)
    "root": (5, 7, 9, 9, 15),         # k = 1 shape (2, 3, 3, 3, 5) + 3, + |D|, m (1), + R - L, D (2), + 2 × 2 (4)
    # g2proj: normalizer + 4, + inputs (1), + V+L, H, Σ (2), + H, dot, p roundings (3), + 2 × 2 (4)
    "halfway": (8, 12, 19, 26, 36),
}
DEPTHS = [0, 1, 2, 3, 4]


def _sample(block, rows, seed):
    """``rows`` seeded rows of the block's own vectors (directed, swept and random)."""
    inputs = block.stimulus(count=rows, seed=seed)
    total = len(next(iter(inputs.values())))
    pick = np.random.default_rng(seed).choice(total, size=min(rows, total), replace=False)
    return {name: np.asarray(column)[pick] for name, column in inputs.items()}


@pytest.mark.parametrize("name", sorted(LATENCY))
@pytest.mark.parametrize("depth", DEPTHS)
def test_latency_formula(name, depth):
    assert get_block(name, pipeline=depth).latency == LATENCY[name][depth]


@pytest.mark.parametrize("name", sorted(LATENCY))
@pytest.mark.parametrize("depth", DEPTHS)
def test_harness(backend, name, depth):
    block = get_block(name, pipeline=depth)
    check(block, _sample(block, 300, depth), backend=backend, bubbles=0.2,
          seed=depth).raise_on_mismatch()


@pytest.mark.parametrize("variant", ["d1", "d2", "d3", "g2"])
@pytest.mark.parametrize("depth", [1, 2, 3])
def test_halfway_variants(variant, depth):
    block = get_block("halfway", variant=variant, pipeline=depth)
    h = 2 * (depth >= 2) + (depth >= 3)  # V + L, its rounding, its clamp
    front = {"d1": 0, "d2": 0, "d3": h, "g2": h + LATENCY["normalize"][depth]}
    tail = 1 + (depth >= 3) if variant == "g2" else 4 + min(depth, 2) + 2 * (depth >= 3)
    assert block.latency == front[variant] + tail
    check(block, _sample(block, 200, depth), bubbles=0.1, seed=depth).raise_on_mismatch()


@pytest.mark.parametrize("depth", [1, 2, 3])
def test_first_order_normalizer_keeps_the_latency(depth):
    block = get_block("normalize", order=1, pipeline=depth)
    assert block.latency == LATENCY["normalize"][depth]
    check(block, _sample(block, 200, depth), bubbles=0.1, seed=depth).raise_on_mismatch()


@pytest.mark.parametrize("name", ["fig7", "fig8"])
def test_datapath_latency_is_the_sum_of_its_blocks(name):
    for depth in DEPTHS:
        block = get_block(name, pipeline=depth)
        front = LATENCY["lirp"][depth] + LATENCY["normalize"][depth] + LATENCY["reflect"][depth]
        unit = (LATENCY["difference"][depth] + LATENCY["shape"][depth] if name == "fig7"
                else LATENCY["root"][depth])
        assert block.latency == front + unit


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", ["fig7", "fig8"])
@pytest.mark.parametrize("depth", [2, 3])
def test_datapath_deep_on_verilator(name, depth):
    block = get_block(name, pipeline=depth)
    check(block, backend="verilator-fast", bubbles=0.2, count=300, seed=5).raise_on_mismatch()


@pytest.mark.parametrize("name, depth", [("fig7", 2), ("fig8", 3)])
def test_datapath_deep_on_amaranth(name, depth):
    block = get_block(name, pipeline=depth, lights=1)
    check(block, _sample(block, 60, depth), bubbles=0.2, seed=depth).raise_on_mismatch()


def test_datapath_pipeline_reaches_every_block():
    config = fig7_config(pipeline=2)
    for name in ("lirp", "normalize", "reflect", "difference", "shape", "root", "halfway",
                 "diffuse", "direction_normalize"):
        assert getattr(config, name).pipeline == 2, name
    assert config.halfway.normalize.pipeline == 2
    assert RootConfig(pipeline=1).shape.pipeline == 1
    # a block's own depth may go deeper than the datapath's, not shallower
    deeper = fig8_config(pipeline=1, normalize=NormalizeConfig(pipeline=2))
    assert (deeper.normalize.pipeline, deeper.lirp.pipeline) == (2, 1)
    assert HalfwayConfig(pipeline=2).normalize.pipeline == 2
    assert DatapathConfig().lirp.pipeline == 0


def test_pipeline_from_the_command_line_settings():
    config = apply_settings(fig8_config(), ["pipeline=2"])
    assert config.pipeline == 2 and config.root.pipeline == 2
    assert get_block("fig7", pipeline=1).config.shape.pipeline == 1
    assert apply_settings(ShapeConfig(), ["pipeline=1"]).pipeline == 1


@pytest.mark.parametrize("cls", [LirpConfig, NormalizeConfig, ShapeConfig, RootConfig, DatapathConfig])
@pytest.mark.parametrize("bad", [-1, 5, True, "1"])
def test_pipeline_range(cls, bad):
    with pytest.raises(ValueError, match=rf"^pipeline must be an integer in 0\.\.4, not {bad!r}$"):
        cls(pipeline=bad)


@pytest.mark.parametrize("name", sorted(LATENCY) + ["fig7", "fig8"])
@pytest.mark.parametrize("depth", DEPTHS)
def test_every_output_leaves_at_the_stated_latency(name, depth):
    component = get_block(name, pipeline=depth).component()
    Fragment.get(component, None)
    assert set(component.output_cycles.values()) == {component.latency}


class _WrongLatency(Lirp):
    latency = 3


def test_output_cycles_expose_a_wrong_latency_formula():
    # a fixed 3 is right at depth 1 only: the registers built say where it is wrong
    for depth, cycle in ((0, 2), (1, 3), (2, 4)):
        component = _WrongLatency(LirpConfig(pipeline=depth))
        Fragment.get(component, None)
        assert component.output_cycles == {"n": cycle} and component.latency == 3


def test_operands_are_aligned_to_the_later_one():
    # x at cycle 0 plus y registered twice: x waits two registers, shared by a second use
    m = Module()
    a, b = Signal(8), Signal(8)
    x, y = FixedValue(a, "8.0", 0, m, "x"), FixedValue(b, "8.0", 0, m, "y")
    late = stage(m, stage(m, y))
    total, again = x + late, late + x
    assert (total.cycle, again.cycle, total.fmt.width) == (2, 2, 9)
    assert x.at(2) is x.at(2) and align(x, late)[0] is x.at(2)
    with pytest.raises(ValueError, match=r"^y is valid at cycle 0, it cannot be used at -1$"):
        y.at(-1)
    out = Signal(9)
    m.d.comb += out.eq(total.value)
    seen = []

    async def bench(ctx):
        for value in range(1, 8):
            ctx.set(a, value)
            ctx.set(b, 10 * value)
            await ctx.tick()
            seen.append(ctx.get(out))

    sim = Simulator(m)
    sim.add_clock(1e-6)
    sim.add_testbench(bench)
    sim.run()
    # read after tick v: the second register holds what was set before tick v - 1
    assert seen == [0] + [11 * v for v in range(1, 7)]


def test_untagged_values_align_with_anything():
    one = FixedValue.const(1, "2.0")
    m = Module()
    late = stage(m, stage(m, FixedValue(Signal(2), "2.0", 0, m)))
    assert (one + late).cycle == 2 and one.at(5) is one and (one + one).cycle is None


def _clocked(m, signals, rows, value):
    """``value`` read after each clock, ``signals`` set to each of ``rows`` in turn."""
    seen = []

    async def bench(ctx):
        for row in rows:
            for signal, code in zip(signals, row):
                ctx.set(signal, code)
            await ctx.tick()
            seen.append(ctx.get(value))

    sim = Simulator(m)
    sim.add_clock(1e-6)
    sim.add_testbench(bench)
    sim.run()
    return seen


@pytest.mark.parametrize("rounding", ["round_half_up", "round_half_even", "truncate"])
@pytest.mark.parametrize("bits", [False, True])
@pytest.mark.parametrize("fmts", [("S3.4", "S1.2"), ("S3.4", "1.2"), ("3.4", "S1.2"), ("3.4", "1.2"),
                                  ("S2.3", "S4.1"), ("2.3", "3.3")])
def test_quantize_cut_is_quantize_one_clock_later(rounding, bits, fmts):
    # every code of the source format: rounding carries into the top, then the clamp, by
    # comparators or (depth 4) by bit tests, to a signed or unsigned, narrower or wider format
    frm, to = map(Format.parse, fmts)
    m = Module()
    a = Signal(frm.shape())
    out = quantize_cut(m, FixedValue(a, frm, 0, m), to, rounding, "saturate", True, bits=bits)
    assert out.cycle == 1
    codes = np.arange(frm.min_raw, frm.max_raw + 1)
    seen = _clocked(m, [a], [(code,) for code in codes.tolist()], out.value)
    want = quantize_raw(codes, frm, to, rounding, "saturate")
    assert seen == want.tolist()


@pytest.mark.parametrize("fmts", [("S3.0", "S20.0"), ("4.0", "22.0"), ("S20.0", "3.0"), ("S2.0", "S2.0")])
def test_split_product_is_the_product_two_clocks_later(fmts):
    # extremes and seeded codes of a narrow and a wide (split at DSP_BITS) operand
    fa, fb = Format.parse(fmts[0]), Format.parse(fmts[1])
    rng = np.random.default_rng(3)
    xs = np.concatenate([[fa.min_raw, fa.max_raw, 0, fa.max_raw], rng.integers(fa.min_raw, fa.max_raw + 1, 60)])
    ys = np.concatenate([[fb.min_raw, fb.max_raw, fb.max_raw, fb.min_raw], rng.integers(fb.min_raw, fb.max_raw + 1, 60)])
    m = Module()
    a, b = Signal(fa.shape()), Signal(fb.shape())
    out = split_product(m, FixedValue(a, fa, 0, m), FixedValue(b, fb, 0, m), True)
    assert out.cycle == 2 and out.fmt == fa.mul(fb)
    seen = _clocked(m, [a, b], list(zip(xs.tolist() + [0, 0], ys.tolist() + [0, 0])), out.value)
    assert seen[1:-1] == [x * y for x, y in zip(xs.tolist(), ys.tolist())]
