import re

import pytest

from phongfx.config import ConventionalConfig
from phongfx.core.registry import get_block
from phongfx.hdl.conventional import LATENCY, LOCAL_LATENCY, Conventional
from phongfx.hdl.emit import verilog
from phongfx.sim.harness import check
from phongfx.sim.stimulus.conventional import stimulus

SMALL = dict(vec="S1.10", n="6.0", n_max=63, m="0.12", rsqrt_addr=6, y="1.12", nr="3.14",
             dot="S2.12", t="1.10", log_addr=5, log="0.14", exp_addr=6, exp="2.13", out="1.12",
             cos="S1.12")


@pytest.mark.parametrize("changes, latency, widths", [
    ({}, 15, (9 * 17 + 13, 2 * 16)),
    (dict(local_light=True), 18, (9 * 17 + 13, 2 * 16)),
    (dict(SMALL, local_viewer=True), 18, (9 * 12 + 6, 2 * 13)),
])
def test_latency_and_ports(changes, latency, widths):
    dut = Conventional(ConventionalConfig(**changes))
    assert dut.latency == latency and (LATENCY, LOCAL_LATENCY) == (15, 18)
    assert (len(dut.i.payload.as_value()), len(dut.o.payload.as_value()) - 1) == widths  # - the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a ConventionalConfig, not "):
        Conventional(object())


@pytest.mark.parametrize("changes, roms", [
    ({}, 5), (dict(local_light=True), 6), (dict(local_light=True, local_viewer=True), 7)])
def test_a_normalizer_per_local_vector(changes, roms):
    # the seed ROM of N and one per local vector, beside the four log/exp ROMs
    text = verilog(get_block("conventional", **changes).component(), "top", emit_src=False)
    seeds = set(re.findall(r"\b(\w*rsqrt)\b", text))
    assert len(seeds) == roms - 4
    assert ("light_rsqrt" in seeds, "view_rsqrt" in seeds) == (
        changes.get("local_light", False), changes.get("local_viewer", False))


@pytest.mark.parametrize("bubbles", [0.0, 0.25])
@pytest.mark.parametrize("changes", [{}, dict(local_light=True, local_viewer=True)])
def test_harness(backend, bubbles, changes):
    # the directed set (axes, zero and shortest N, R·V = 1, behind, grazing, every edge n) and
    # random highlights, spread and junk codes; local: zero and non-unit L and V
    block = get_block("conventional", **changes)
    check(block, backend=backend, bubbles=bubbles, count=300, seed=7).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    dict(rounding="truncate"),
    dict(rounding="round_half_even", t="1.16", out="2.16", cos="S2.18"),
    dict(local_light=True),
    dict(local_viewer=True, rounding="truncate"),
    # narrow formats everywhere: an 11-bit t, 64-word tables, n up to 63, one local vector
    SMALL,
    dict(SMALL, local_light=True),
])
def test_harness_other_formats(changes):
    block = get_block("conventional", **changes)
    inputs = stimulus(block.config, count=400, seed=2)
    check(block, inputs, bubbles=0.1, seed=2).raise_on_mismatch()
