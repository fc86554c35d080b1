"""Products mapped onto MULT18X18D: the behavioural model against ``*``, the mapping's
registers, and the mapped blocks against their golden models."""

import re

import numpy as np
import pytest
from amaranth.back import rtlil
from amaranth.hdl import Module
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.hdl.block import stream_signature
from phongfx.hdl.dsp import DSP_TARGETS, dsp_mapping, dsp_target, product, split_product
from phongfx.hdl.fixed import FixedValue, delay, stage
from phongfx.sim import fast_backend
from phongfx.sim.harness import check


class Probe(wiring.Component):
    """``p = a * b`` through :func:`product` (or :func:`split_product`), the operands
    registered first if ``inputs``: every register mode of the DSP."""

    def __init__(self, fa, fb, inputs, output, split=False, const_b=None):
        self.fa, self.fb = Format.parse(fa), Format.parse(fb)
        self.inputs, self.output, self.split, self.const_b = inputs, output, split, const_b
        self.fmt = self.fa.mul(self.fb)
        super().__init__({"i": In(stream_signature({"a": (self.fa, 1), "b": (self.fb, 1)})),
                          "o": Out(stream_signature({"p": (self.fmt, 1)}))})

    def elaborate(self, platform):
        m = Module()
        a = FixedValue(self.i.payload.a, self.fa, 0, m, "a")
        b = FixedValue(self.i.payload.b, self.fb, 0, m, "b")
        if self.inputs:
            a, b = stage(m, a, "a_reg"), stage(m, b, "b_reg")
        if self.const_b is not None:
            b = FixedValue.const(self.const_b, self.fb)
        p = split_product(m, a, b, True) if self.split else product(m, a, b, self.output)
        self.latency = p.cycle
        m.d.comb += [self.o.payload.p.eq(p.value), self.o.valid.eq(delay(m, self.i.valid, p.cycle))]
        return m


def _run(probe, xs, ys):
    """The probe's products of ``xs`` and ``ys`` under the ECP5 mapping, on Verilator."""
    fa, fb = probe.fa, probe.fb
    mask_a, mask_b = (1 << fa.width) - 1, (1 << fb.width) - 1
    payload = [(int(x) & mask_a) | (int(y) & mask_b) << fa.width for x, y in zip(xs, ys)]
    with dsp_mapping("ecp5"):
        design = rtlil.convert(probe, name="probe", emit_src=False)
        latency = probe.latency
        cycles = len(payload) + latency
        valid, out = fast_backend.run(probe, [1] * len(payload) + [0] * latency, payload + [0] * latency,
                                      cycles)
    width = probe.fmt.width
    got = [v - (1 << width) if probe.fmt.signed and v >> (width - 1) else v for v in out[latency:]]
    assert valid[latency:] == [1] * len(payload) and valid[:latency] == [0] * latency
    return design, latency, got


def _instances(design):
    return re.findall(r"cell \\MULT18X18D .*?\n  end", design, re.S)


def _clocked(cell, register):
    """Whether MULT18X18D ``cell`` (RTLIL text) has its ``register`` (INPUTA, OUTPUT ...) on."""
    return re.search(rf'parameter \\REG_{register}_CLK "(\w+)"', cell).group(1) == "CLK0"


def test_mapping_names_its_targets():
    assert dsp_target() is None
    with dsp_mapping("ecp5"):
        assert dsp_target() == "ecp5"
    assert dsp_target() is None and DSP_TARGETS == ("ecp5",)
    with pytest.raises(ValueError, match="DSP target must be one of 'ecp5' or None, not 'xc7'"):
        with dsp_mapping("xc7"):
            pass


@pytest.mark.needs_verilator
@pytest.mark.parametrize("inputs,output", [(True, True), (True, False), (False, True)])
@pytest.mark.parametrize("fmts", [("S7.0", "S6.0"), ("7.0", "S6.0"), ("6.0", "7.0")])
def test_model_is_the_product_exhaustively_on_small_operands(fmts, inputs, output):
    fa, fb = map(Format.parse, fmts)
    xs, ys = np.meshgrid(np.arange(fa.min_raw, fa.max_raw + 1), np.arange(fb.min_raw, fb.max_raw + 1))
    xs, ys = xs.ravel(), ys.ravel()
    probe = Probe(fa, fb, inputs, output)
    design, latency, got = _run(probe, xs, ys)
    cells = _instances(design)
    assert len(cells) == 1 and latency == inputs + output
    assert _clocked(cells[0], "INPUTA") == _clocked(cells[0], "INPUTB") == inputs
    assert _clocked(cells[0], "OUTPUT") == output
    assert got == (xs * ys).tolist()


def _extremes_and_random(fmt, count, rng):
    fixed = [fmt.min_raw, fmt.max_raw, 0, 1, -1 if fmt.signed else 2, fmt.min_raw + 1, fmt.max_raw - 1]
    return np.concatenate([np.repeat(fixed, len(fixed)), rng.integers(fmt.min_raw, fmt.max_raw + 1, count)])


@pytest.mark.needs_verilator
@pytest.mark.parametrize("fmts,dsps", [(("S17.0", "S17.0"), 1), (("17.0", "17.0"), 1), (("18.0", "S17.0"), 2),
                                       (("13.0", "22.0"), 2), (("S19.0", "S21.0"), 4)])
@pytest.mark.parametrize("split", [False, True])
def test_model_is_the_product_at_the_extremes_and_split(fmts, dsps, split):
    # every pair of the extremes of both operands, then seeded random codes
    fa, fb = map(Format.parse, fmts)
    rng = np.random.default_rng(11)
    xs, ys = _extremes_and_random(fa, 3000, rng), _extremes_and_random(fb, 3000, rng)
    xs[:49] = np.tile(xs[:7], 7)  # the 7 × 7 pairs of the extremes
    probe = Probe(fa, fb, True, True, split)
    design, latency, got = _run(probe, xs, ys)
    # the parts' registers are the DSPs' own where split_product splits (an operand wider
    # than 18 bits); a sum of DSPs in one stage is registered in the fabric after it
    inner = dsps == 1 or (split and max(fa.width, fb.width) > 18)
    assert len(_instances(design)) == dsps
    assert latency == (3 if split else 2)
    assert got == [int(x) * int(y) for x, y in zip(xs.tolist(), ys.tolist())]
    assert all(_clocked(cell, "OUTPUT") == inner and _clocked(cell, "INPUTB")
               for cell in _instances(design))


def test_constant_operands_and_unmapped_products_stay_multiplies():
    probe = Probe("S10.0", "4.0", True, True, const_b=3)
    with dsp_mapping("ecp5"):
        assert not _instances(rtlil.convert(probe, name="probe", emit_src=False))
    assert probe.latency == 2
    probe = Probe("S8.0", "S8.0", True, True)
    assert not _instances(rtlil.convert(probe, name="probe", emit_src=False))
    assert probe.latency == 2


# DSP instances per block at its default configuration (the registry's)
INSTANCES = {"lirp": 6, "normalize": 7, "reflect": 6, "difference": 5, "shape": 2, "diffuse": 3, "root": 7}


@pytest.mark.parametrize("name", sorted(INSTANCES))
@pytest.mark.parametrize("depth", [1, 3, 4])
def test_blocks_map_every_variable_product(name, depth):
    block = get_block(name, pipeline=depth)
    with dsp_mapping("ecp5"):
        cells = _instances(rtlil.convert(block.component(), name="b", emit_src=False))
    assert len(cells) == INSTANCES[name]
    # input registers absorbed wherever both operands are registers of the RTL
    registered = sum(_clocked(cell, "INPUTA") for cell in cells)
    assert registered >= INSTANCES[name] - 3
    assert get_block(name, pipeline=depth).latency == block.latency


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name,depth", [("lirp", 1), ("difference", 3), ("normalize", 2), ("root", 1),
                                        ("reflect", 4), ("difference", 4)])
def test_mapped_blocks_match_golden(name, depth):
    block = get_block(name, pipeline=depth)
    with dsp_mapping("ecp5"):
        result = check(block, backend="verilator-fast", count=400, seed=depth, bubbles=0.2)
    assert result.vectors > 0 and result.mismatch_count == 0, result.describe()


@pytest.mark.slow
@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", ["fig7", "fig8"])
@pytest.mark.parametrize("depth", [1, 2, 3, 4])
def test_mapped_datapaths_match_golden(name, depth):
    block = get_block(name, pipeline=depth)
    with dsp_mapping("ecp5"):
        result = check(block, backend="verilator-fast", count=300, seed=depth, bubbles=0.2)
    assert result.vectors > 0 and result.mismatch_count == 0, result.describe()
