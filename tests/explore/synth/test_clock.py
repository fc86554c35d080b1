"""The tool-free clock proxy (phongfx.explore.synth.clock) and the flattened graph it reads."""

import math

import pytest

from phongfx.core.registry import get_block
from phongfx.explore.synth.clock import COEFFICIENTS, ERROR, MARGIN, critical_path, proxy_clock
from phongfx.explore.synth.flatten import flatten


def _cell(kind, name, a, b, y, width):
    return (f"  cell {kind} {name}\n    parameter \\A_WIDTH {width}\n    parameter \\B_WIDTH {width}\n"
            f"    parameter \\Y_WIDTH {width + 1}\n    connect \\A {a}\n    connect \\B {b}\n    connect \\Y {y}\n  end\n")


def _dff(name, d, q, width):
    return (f"  cell $dff {name}\n    parameter \\WIDTH {width}\n    parameter \\CLK_POLARITY 1\n"
            f"    connect \\D {d}\n    connect \\CLK \\clk [0]\n    connect \\Q {q}\n  end\n")


#: Two registers a, b; s = a + b; t = s[8:0] + a; register r = t: one stage of two
#: carry chains (9 and 9 → 10 bits), inside a submodule joined to the top by its ports.
ADDER_CHAIN = (
    "module \\top.unit\n  wire width 1 input 0 \\clk\n  wire width 8 input 1 \\x\n  wire width 8 input 2 \\y\n"
    "  wire width 10 output 3 \\out\n  wire width 8 \\a\n  wire width 8 \\b\n  wire width 9 \\s\n  wire width 10 \\t\n"
    + _dff("$1", "\\x", "\\a", 8) + _dff("$2", "\\y", "\\b", 8)
    + _cell("$add", "$3", "\\a", "\\b", "\\s", 8)
    + _cell("$add", "$4", "\\s [8:0]", "{ 1'0 \\a }", "\\t", 9)
    + _dff("$5", "\\t", "\\out", 10) + "end\n"
    "module \\top\n  wire width 1 input 0 \\clk\n  wire width 16 input 1 \\i\n  wire width 10 output 2 \\o\n"
    "  cell \\top.unit \\unit\n    connect \\clk \\clk [0]\n    connect \\x \\i [7:0]\n    connect \\y \\i [15:8]\n"
    "    connect \\out \\o\n  end\nend\n")


def test_the_flattener_finds_the_adder_chain_between_two_registers():
    netlist = flatten(ADDER_CHAIN)
    assert sorted(node.type for node in netlist.nodes) == ["$add", "$add", "$dff", "$dff", "$dff"]
    coefficients = {"stage": 1.0, "carry": 2.0, "carry_bits": 0.5}
    ns, amounts, path = critical_path(netlist, coefficients)
    assert path == ["unit.a", "unit.s", "unit.t", "unit.out"]  # a launches both chains: the longer way
    assert amounts["carry"] == 2 and amounts["carry_bits"] == 9 + 10 and amounts["mul"] == 0
    assert ns == pytest.approx(1.0 + 2 * 2.0 + 0.5 * 19)


def _fanned(loads):
    """Register e drives one bit into ``loads`` adders (each adding it to input x), each
    registered: the net of e has ``loads`` loads."""
    cells = _dff("$e", "\\x [0]", "\\e", 1)
    for index in range(loads):
        cells += _cell("$add", f"$a{index}", "\\x", "{ 7'0 \\e }", f"\\s{index}", 8)
        cells += _dff(f"$r{index}", f"\\s{index}", f"\\o [{9 * index + 8}:{9 * index}]", 9)
    wires = "".join(f"  wire width 9 \\s{index}\n" for index in range(loads))
    return (f"module \\top\n  wire width 1 input 0 \\clk\n  wire width 8 input 1 \\x\n"
            f"  wire width {9 * loads} output 2 \\o\n  wire width 1 \\e\n{wires}{cells}end\n")


@pytest.mark.parametrize("loads", [1, 4, 64])
def test_a_net_of_many_loads_is_priced_by_its_fan_out(loads):
    """log2 of the loads of each net along the path (a buffer tree's depth), the inputs' own
    among them; the adders' outputs, one load each, add nothing."""
    netlist = flatten(_fanned(loads))
    assert netlist.fanins(netlist.nodes.index(next(n for n in netlist.nodes if n.name == "s0"))) == \
        {-1: loads + 1, next(i for i, n in enumerate(netlist.nodes) if n.name == "e"): loads}
    ns, amounts, path = critical_path(netlist, {"stage": 1.0, "carry_bits": 0.5, "fanout": 0.25})
    # x[0] reaches e and every adder: the input's net is the slower start, its log2 counted once
    assert amounts["fanout"] == pytest.approx(math.log2(loads + 1))
    assert path[0] == "s0" and amounts["carry_bits"] == 9
    assert ns == pytest.approx(1.0 + 0.5 * 9 + 0.25 * amounts["fanout"])


@pytest.mark.parametrize("width", [1, 24])
def test_a_select_steers_as_many_loads_as_its_multiplexer_has_bits(width):
    """A multiplexer is a LUT per output bit on an FPGA, a gate per bit in cells: its select
    bit reaches ``width`` of them, though it is one port of one word-level cell (the blend's
    gate of a two-light shader, missed by a count of cells)."""
    mux = (f"  cell $mux $m\n    parameter \\WIDTH {width}\n    connect \\A \\a\n    connect \\B \\b\n"
           f"    connect \\S \\e\n    connect \\Y \\y\n  end\n")
    text = (f"module \\top\n  wire width 1 input 0 \\clk\n  wire width {width} input 1 \\a\n"
            f"  wire width {width} input 2 \\b\n  wire width 1 input 3 \\s\n  wire width {width} output 4 \\o\n"
            f"  wire width 1 \\e\n  wire width {width} \\y\n"
            + _dff("$e", "\\s", "\\e", 1) + mux + _dff("$r", "\\y", "\\o", width) + "end\n")
    netlist = flatten(text)
    index = next(i for i, n in enumerate(netlist.nodes) if n.type == "$mux")
    assert netlist.fanins(index)[next(i for i, n in enumerate(netlist.nodes) if n.name == "e")] == width
    assert critical_path(netlist, {"fanout": 1.0})[1]["fanout"] == pytest.approx(math.log2(width))


def test_copies_on_the_same_inputs_are_one_copy():
    """Two instances of the unit fed the same bits merge, registers and adders alike."""
    twice = ADDER_CHAIN.replace(
        "    connect \\out \\o\n  end\nend\n",
        "    connect \\out \\o\n  end\n  cell \\top.unit \\copy\n    connect \\clk \\clk [0]\n"
        "    connect \\x \\i [7:0]\n    connect \\y \\i [15:8]\n    connect \\out \\p\n  end\nend\n").replace(
        "  wire width 10 output 2 \\o\n", "  wire width 10 output 2 \\o\n  wire width 10 output 3 \\p\n")
    netlist = flatten(twice)
    assert len(netlist.nodes) == 10 and len(netlist.merged()) == 5


@pytest.mark.parametrize("target", ["ecp5", "asic"])
def test_proxy_clock_rises_with_the_pipeline_depth_of_fig7(target):
    results = [proxy_clock(get_block("fig7", pipeline=depth), target) for depth in range(5)]
    fmax = [r["fmax_mhz"] for r in results]
    if target == "ecp5":  # synthesized: 42.0, 67.4, 79.2, 121.1, 189.5 MHz
        assert all(a <= b for a, b in zip(fmax, fmax[1:])) and fmax[-1] > 2 * fmax[0]
    else:  # on osu018 (buffered) an array multiplier bounds every depth past 0: 117.6, then 164 to 184 MHz
        assert fmax[0] < min(fmax[1:]) and 1.3 * fmax[0] < max(fmax) < 1.7 * fmax[0]
    assert results[0]["model"] == f"{target}-clock-proxy" and results[0]["error"] == ERROR[target]
    assert results[0]["period_ns"] == pytest.approx(1000 / fmax[0])
    assert "→" in results[0]["path"] and "ns" in results[0]["path"]


def test_proxy_clock_refuses_an_unknown_target_or_device():
    with pytest.raises(ValueError, match="target must be one of 'ecp5', 'asic', not 'ice40'"):
        proxy_clock(get_block("shape"), "ice40")
    with pytest.raises(ValueError, match="device must be one of 25k, 45k, 85k for the ecp5 clock proxy, not '12k'"):
        proxy_clock(get_block("shape"), "ecp5", "12k")


def test_every_target_has_every_coefficient():
    from phongfx.explore.synth.clock import FEATURES

    for target, coefficients in COEFFICIENTS.items():
        assert set(coefficients) == set(FEATURES) and min(coefficients.values()) >= 0
        assert 0 < ERROR[target] < 1 and 0 <= MARGIN[target] < 1
