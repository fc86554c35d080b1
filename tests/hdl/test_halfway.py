import pytest

from phongfx.config import HALFWAY_VARIANTS, HalfwayConfig, NormalizeConfig, ReflectConfig
from phongfx.core.registry import get_block
from phongfx.hdl.halfway import Halfway
from phongfx.sim.harness import check

#: the projection alone (4); the normalizer (4) and then the projection, or the rounded q
LATENCY = {"d1": 4, "d2": 4, "d3": 4, "g2proj": 8, "g2": 5}


@pytest.mark.parametrize("h", ["mean", "sum"])
@pytest.mark.parametrize("variant", HALFWAY_VARIANTS)
def test_latency_and_ports(variant, h):
    dut = Halfway(HalfwayConfig(variant=variant, h=h))
    assert dut.latency == LATENCY[variant]
    assert len(dut.i.payload.as_value()) == 3 * 3 * 12
    assert len(dut.o.payload.as_value()) == 2 * 3 * 13 + 1  # and the overflow flag


def test_constructor_wants_its_config():
    with pytest.raises(TypeError, match=r"^config must be a HalfwayConfig, not "):
        Halfway(object())
    with pytest.raises(TypeError, match=r"^config must be a HalfwayConfig, not ReflectConfig\("):
        Halfway(ReflectConfig())


# Verilator builds cost seconds per design: three cover the three datapath shapes
# (normalizer + projection, projection with the "sum" doubling, normalizer alone)
@pytest.mark.parametrize("variant, h, bubbles", [
    ("g2proj", "mean", 0.0), ("g2proj", "mean", 0.3), ("d1", "sum", 0.2), ("g2", "sum", 0.2),
])
def test_harness(backend, variant, h, bubbles):
    check(get_block("halfway", variant=variant, h=h), backend=backend, bubbles=bubbles, count=200,
          seed=7).raise_on_mismatch()


@pytest.mark.parametrize("h", ["mean", "sum"])
@pytest.mark.parametrize("variant", HALFWAY_VARIANTS)
def test_harness_every_variant(variant, h):
    check(get_block("halfway", variant=variant, h=h), bubbles=0.2, count=200,
          seed=3).raise_on_mismatch()


@pytest.mark.parametrize("changes", [
    # "mean" in S1.10: H rounded (one bit dropped), a truncating first-order normalizer
    dict(variant="g2proj", hvec="S1.10", dot="S1.12", out="S1.10", rounding="truncate",
         normalize=NormalizeConfig(vec="S1.10", order=1, rounding="truncate")),
    # "sum" in S1.9: H saturates at 2, narrower dot and out, ties to even
    dict(variant="d3", h="sum", vec="S1.8", hvec="S1.9", dot="S1.10", out="S1.8",
         rounding="round_half_even", normalize=NormalizeConfig(vec="S1.9")),
    dict(variant="d2", h="sum", vec="S1.8", hvec="S2.8", dot="S1.9", out="S2.7", rounding="truncate",
         normalize=NormalizeConfig(vec="S2.8")),
])
def test_harness_other_formats(changes):
    check(get_block("halfway", **changes), bubbles=0.1, count=200, seed=1).raise_on_mismatch()
