"""The tool-free cost proxy read from RTLIL (phongfx.explore.synth.proxy)."""

from phongfx.core.registry import get_block
from phongfx.explore.synth.proxy import DSP_LUT_EQ, proxy_cost, rtlil_cost


def _mul(name, a, b, a_width, b_width):
    return (f"  cell $mul {name}\n    parameter \\A_WIDTH {a_width}\n    parameter \\B_WIDTH {b_width}\n"
            f"    parameter \\Y_WIDTH {a_width + b_width}\n    connect \\A {a}\n    connect \\B {b}\n"
            f"    connect \\Y {name}_y\n  end\n")


def test_multipliers_by_dsp_slices_and_constants_by_adders():
    wires = {"\\x": 12, "\\y": 12, "\\p": 19, "\\q": 36}
    wires.update({f"${i}_y": 56 for i in range(1, 6)})
    text = "module \\top\n" + "".join(f"  wire width {w} {name}\n" for name, w in wires.items()) + "".join([
        _mul("$1", "\\x", "\\y", 12, 12),          # one MULT18
        _mul("$2", "\\x", "\\y", 12, 12),          # the same inputs: merged
        _mul("$3", "\\p", "\\q", 19, 36),          # 19 = 18 + 1 (the 1 to logic): 1 x 2 slices
        _mul("$4", "\\x", "8'00010000", 12, 8),    # times 16: wiring
        _mul("$5", "\\x", "8'00000101", 12, 8),    # times 5: one 12-bit adder
    ]) + "end\n"
    cost = rtlil_cost(text)
    assert cost["dsp"] == 1 + 2 and cost["carry_bits"] == 12
    assert cost["lut_eq"] == cost["lut"] + DSP_LUT_EQ * cost["dsp"]


def test_a_constant_shininess_drops_the_n_multipliers():
    per_pixel = get_block("fig7")
    fixed = get_block("fig7", difference=per_pixel.config.difference.replace(n_const=16))
    # n·D·D (13 × 22 bits: 1 × 2 MULT18 slices) per light becomes a shift
    assert proxy_cost(per_pixel)["dsp"] - proxy_cost(fixed)["dsp"] == 2 * per_pixel.config.lights
