"""The colour blend's component against its golden model on the Amaranth and verilator-fast back
ends, at every pipeline depth; its latency; constant multiplies by shifts and adds; shared trees."""

import numpy as np
import pytest
from amaranth.back import rtlil
from amaranth.hdl import Fragment, Module, Signal
from amaranth.sim import Simulator

from phongfx.config import MAX_PIPELINE, BlendConfig, ReflectConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.explore.synth.proxy import rtlil_features, rtlil_of
from phongfx.hdl.blend import Blend, adder_tree, shift_add
from phongfx.hdl.fixed import FixedValue
from phongfx.sim.harness import check

DEPTHS = range(MAX_PIPELINE + 1)
BACKENDS = ["amaranth", pytest.param("verilator-fast", marks=pytest.mark.needs_verilator)]

GREY = dict(ambient=((0.05, 0.05, 0.05),), diffuse=(((0.6,) * 3, (0.3,) * 3),),
            specular=(((0.4,) * 3, (0.25,) * 3),))
COLOURED = dict(ambient=((0.05, 0.02, 0.1),), diffuse=(((0.6, 0.3, 0.1), (0.2, 0.25, 0.4)),),
                specular=(((0.4, 0.35, 0.3), (0.25, 0.2, 0.1)),))
#: three materials over three lights: red plastic, a grey one, and gold, which shares red's ambient
MATERIALS = dict(lights=3, ambient=((0.1, 0.0, 0.0), (0.05, 0.05, 0.05), (0.1, 0.0, 0.0)),
                 diffuse=(((0.7, 0.1, 0.1),) * 3, ((0.5,) * 3, (0.25,) * 3, (0.125,) * 3),
                          ((0.6, 0.45, 0.1), (0.3, 0.2, 0.05), (0.0, 0.0, 0.0))),
                 specular=(((0.3,) * 3,) * 3, ((0.2,) * 3,) * 3,
                           ((0.9, 0.8, 0.3), (0.5, 0.4, 0.2), (0.2, 0.1, 0.0))))
ONE_LIGHT = dict(lights=1, ambient=((0.0, 0.1, 0.2),), diffuse=(((0.8, 0.5, 0.3),),),
                 specular=(((0.7, 0.7, 0.7),),))
NO_DIFF = dict(diff="", gate=False, ambient=((0.2, 0.1, 0.0),), diffuse=(((0,) * 3,) * 2,),
               specular=(((0.8, 0.6, 0.4), (0.3, 0.3, 0.3)),))
CONFIGS = {"grey": GREY, "coloured": COLOURED, "materials": MATERIALS, "one light": ONE_LIGHT,
           "no diff": NO_DIFF}


def blend(pipeline=0, **changes):
    return get_block("blend", pipeline=pipeline, **changes)


def test_latency_and_ports():
    dut = Blend(BlendConfig())
    assert dut.latency == 1
    assert len(dut.i.payload.as_value()) == 2 * (11 + 16)
    assert len(dut.o.payload.as_value()) == 3 * 8 + 1  # and the overflow flag
    three = Blend(BlendConfig(**MATERIALS))
    assert len(three.i.payload.as_value()) == 3 * (11 + 16) + 2  # a 2-bit material code


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a BlendConfig, not ReflectConfig\("):
        Blend(ReflectConfig())


@pytest.mark.parametrize("name", sorted(CONFIGS))
@pytest.mark.parametrize("depth", DEPTHS)
def test_latency_formula_against_the_registers_built(name, depth):
    component = blend(depth, **CONFIGS[name]).component()
    Fragment.get(component, None)
    assert component.latency == 1 + depth
    assert set(component.output_cycles.values()) == {component.latency}


@pytest.mark.parametrize("config", [
    # no light reaches b, and red's ambient alone: b is a constant
    dict(ambient=((0.5, 0.0, 0.0),), diffuse=(((0.5, 0.5, 0.0),) * 2,), specular=(((0.5, 0.5, 0.0),) * 2,)),
    # no light at all: two constant colours, chosen by the material code alone
    dict(ambient=((0.5, 0.0, 0.0), (0.2, 0.2, 0.2)), diffuse=(((0,) * 3,) * 2,) * 2,
         specular=(((0,) * 3,) * 2,) * 2),
], ids=["constant b", "constant materials"])
@pytest.mark.parametrize("depth", DEPTHS)
def test_a_constant_output_leaves_at_the_latency_too(config, depth):
    block = blend(depth, **config)
    component = block.component()
    Fragment.get(component, None)
    assert set(component.output_cycles.values()) == {1 + depth}
    check(block, count=60, seed=depth).raise_on_mismatch()


@pytest.mark.parametrize("name", sorted(CONFIGS))
@pytest.mark.parametrize("depth", DEPTHS)
def test_harness_amaranth(name, depth):
    check(blend(depth, **CONFIGS[name]), count=120, seed=depth, bubbles=0.2).raise_on_mismatch()


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name, depth", [("grey", 0), ("coloured", 2), ("materials", 4), ("one light", 3),
                                         ("no diff", 1)])
def test_harness_verilator_fast(name, depth):
    check(blend(depth, **CONFIGS[name]), backend="verilator-fast", count=2000, seed=5,
          bubbles=0.1).raise_on_mismatch()


@pytest.mark.parametrize("backend", BACKENDS)
def test_harness_defaults(backend):
    check(blend(), backend=backend, count=300, seed=7, bubbles=0.3).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(rounding="truncate", coef_frac=0, bits=4),
    dict(rounding="round_half_even", coef_frac=16, bits=12, diff="2.8", spec="1.12"),
    dict(bits=1, coef_frac=3, gate=False),
])
def test_harness_other_formats(changes):
    check(blend(2, **COLOURED, **changes), count=200, seed=3).raise_on_mismatch()


def _features(**changes):
    return rtlil_features(rtlil_of(blend(**changes)))


@pytest.mark.parametrize("name", sorted(CONFIGS))
@pytest.mark.parametrize("depth", [0, 4])
def test_constant_multiplies_are_shifts_and_adds(name, depth):
    text = rtlil.convert(blend(depth, **CONFIGS[name]).component(), emit_src=False)
    assert "cell $mul " not in text and "cell $add " in text


def test_a_grey_scene_computes_one_channel_and_wires_it_to_three():
    grey, coloured = _features(**GREY), _features(**COLOURED)
    assert grey["mul_bits"] == coloured["mul_bits"] == 0
    # one adder tree and one output register for r, g and b
    assert 2.5 * grey["add_bits"] < coloured["add_bits"]
    assert 2.5 * grey["ff_bits"] < coloured["ff_bits"] + 2  # the valid bit is shared either way
    text = rtlil.convert(blend(**GREY).component(), emit_src=False)
    assert text.count("cell $dff ") == 2  # valid, and rgb


def test_materials_with_equal_coefficients_share_their_sums():
    # three materials of which two are equal: the sums of two, one multiplexer level
    same = dict(MATERIALS, ambient=MATERIALS["ambient"][:2] + MATERIALS["ambient"][:1],
                diffuse=MATERIALS["diffuse"][:2] + MATERIALS["diffuse"][:1],
                specular=MATERIALS["specular"][:2] + MATERIALS["specular"][:1])
    assert _features(**same)["add_bits"] < _features(**MATERIALS)["add_bits"]
    check(blend(1, **same), count=150, seed=2).raise_on_mismatch()


def _simulate(component, rows, cycles):
    """``o.payload`` after driving ``rows`` (payload dicts) one per clock, for ``cycles`` clocks."""
    got = []

    async def bench(ctx):
        for cycle in range(cycles):
            row = rows[min(cycle, len(rows) - 1)]
            ctx.set(component.i.valid, 1)
            for name, value in row.items():
                ctx.set(component.i.payload[name], value)
            await ctx.tick()
            got.append({name: ctx.get(component.o.payload[name]) for name in "rgb"})

    sim = Simulator(component)
    sim.add_clock(1e-6)
    sim.add_testbench(bench)
    sim.run()
    return got


@pytest.mark.parametrize("depth", [0, 3])
def test_a_material_code_past_the_last_selects_the_last(depth):
    block = blend(depth, **MATERIALS)  # 3 materials, 2-bit code: 3 is past the end
    lit = {"diff0": 1024, "spec0": 20000, "diff1": 512, "spec1": 30000, "diff2": 0, "spec2": 65535}
    rows = [dict(lit, material=3), dict(lit, material=2)]
    got = _simulate(block.component(), rows, block.latency + 2)
    assert got[block.latency - 1] == got[block.latency]
    golden = block.golden({name: np.array([value]) for name, value in rows[1].items()})
    assert got[block.latency] == {name: int(golden[name][0]) for name in "rgb"}


@pytest.mark.parametrize("code", [0, 1, 2, 3, 5, 7, 11, 130560, 2 ** 20 - 1, 0b1011_0111_0110_1101])
@pytest.mark.parametrize("fmt, frac", [("1.10", 10), ("S2.5", 0), ("0.8", 3)])
def test_shift_add_is_the_exact_product(code, fmt, frac):
    fmt = Format.parse(fmt)
    m = Module()
    x = Signal(fmt.shape())
    product = shift_add(FixedValue(x, fmt), code, frac)
    if code == 0:
        assert product is None
        return
    assert product.fmt == Format.covering(fmt.min_raw * code, fmt.max_raw * code, fmt.frac_bits + frac)
    out = Signal(product.fmt.shape())
    m.d.comb += out.eq(product.value)
    assert "$mul" not in rtlil.convert(m, ports=[x, out])
    values = sorted({fmt.min_raw, fmt.max_raw, 0, 1, fmt.max_raw // 3, fmt.min_raw // 2})

    async def bench(ctx):
        for value in values:
            ctx.set(x, value)
            assert ctx.get(out) == value * code  # raw codes: the product's fraction bits are fmt's + frac

    sim = Simulator(m)
    sim.add_testbench(bench)
    sim.run()


def test_shift_add_and_adder_tree_refuse_bad_arguments():
    value = FixedValue(Signal(4), "4.0")
    with pytest.raises(ValueError, match=r"^shift_add: code must be an integer >= 0, not -1$"):
        shift_add(value, -1)
    with pytest.raises(ValueError, match=r"^adder_tree needs at least one value$"):
        adder_tree([])
