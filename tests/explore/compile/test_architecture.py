"""The architecture of a compiled design: its timing figures against the speed asked, the
cheapest that meets it, the proposals synthesized, and the fit to the FPGA part."""

import pytest

from phongfx.explore.compile import fit
from phongfx.explore.compile.architecture import Speed, pick, proposals, timing


def test_speed_is_checked_and_says_what_clock_an_interval_needs():
    assert not Speed().asked and Speed().required_clock(2) is None
    assert Speed(40).required_clock(1) == 40 and Speed(40).required_clock(2) == 80
    assert Speed(40, 100).required_clock(2) == 100 and Speed(60, 100).required_clock(2) == 120
    with pytest.raises(ValueError, match=r"^clock must be a number of MHz in \(0, 10000\], not 0$"):
        Speed(40, 0)
    with pytest.raises(ValueError, match=r"^throughput must be a number of Mpixel/s in \(0, 100000\], not -3$"):
        Speed(-3)


def test_timing_at_its_own_fmax_and_at_a_given_clock():
    got = timing(120.0, 2, 24, Speed(40), "proxy")
    assert got == {"interval": 2, "latency": 24, "latency_ns": 200.0, "fmax_mhz": 120.0, "clock_mhz": 120.0,
                   "clock_source": "proxy", "pixel_rate_mpx": 60.0, "requirement_mpx": 40,
                   "clock_required_mhz": 80, "met": True}
    missed = timing(90.0, 1, 9, Speed(150), "synthesis")
    assert missed["met"] is False and missed["missed_by_mhz"] == 60.0 and missed["missed_by_percent"] == 40.0
    # run at --clock 100: the rate is 100 / interval, whatever the Fmax above it
    given = timing(180.0, 2, 10, Speed(40, 100), "proxy")
    assert (given["clock_mhz"], given["pixel_rate_mpx"], given["met"]) == (100.0, 50.0, True)
    slow = timing(80.0, 1, 10, Speed(None, 100), "proxy")
    assert (slow["met"], slow["missed_by_mhz"], slow["missed_by_percent"]) == (False, 20.0, 20.0)
    # nothing asked: met, and the figures still reported
    free = timing(50.0, 1, 5, Speed(), "proxy")
    assert free["met"] is True and free["clock_required_mhz"] is None and free["pixel_rate_mpx"] == 50.0


def _priced(cost, fmax, interval=1, depth=0, speed=Speed(40), margin=0.2):
    """An architecture whose stated (promised) clock is ``fmax``: its fitted estimate is higher
    by the proxy's ``margin``."""
    return {"architecture": {"pipeline": depth, "interval": interval, "share": True}, "cost": cost,
            "clock": {"fmax_mhz": fmax, "estimate_mhz": fmax / (1 - margin), "margin": margin},
            **timing(fmax, interval, 5 + depth, speed, "proxy")}


def test_the_cheapest_that_meets_the_rate_is_picked_else_none_and_the_fastest():
    speed = Speed(40)
    slow = _priced(1000, 60, interval=2, speed=speed)    # 30 Mpixel/s
    half = _priced(1200, 90, interval=2, depth=2, speed=speed)  # 45 Mpixel/s
    wide = _priced(2000, 50, speed=speed)                # 50 Mpixel/s
    chosen, fastest = pick([slow, half, wide])
    assert chosen is half and fastest is wide
    chosen, fastest = pick([_priced(1000, 60, interval=2, speed=Speed(100))])
    assert chosen is None and fastest["pixel_rate_mpx"] == 30
    half["fits"] = False                                 # over the part: not chosen
    assert pick([slow, half, wide])[0] is wide


def test_synthesis_is_proposed_the_promise_and_the_cheaper_one_the_estimate_says_meets():
    speed = Speed(40)
    hopeful = _priced(1000, 34, speed=speed)             # 34 promised, 42.5 by the fitted estimate
    promised = _priced(1500, 60, depth=2, speed=speed)
    hopeless = _priced(800, 30, speed=speed)             # 37.5 even by the estimate
    assert pick([promised, hopeful, hopeless])[0] is promised
    assert proposals([promised, hopeful, hopeless], speed) == [promised, hopeful]
    assert proposals([promised, hopeless], speed) == [promised]
    too_slow = _priced(900, 20, speed=speed)
    assert proposals([too_slow], speed) == [too_slow]    # none meets: the fastest, to see what synthesis says


@pytest.fixture
def parts(monkeypatch):
    import phongfx.explore.synth.fpga as fpga
    import phongfx.explore.synth.proxy as proxy
    sizes = {"25k": ("LFE5U-25F", 24288, 28), "45k": ("LFE5U-45F", 43848, 72), "85k": ("LFE5U-85F", 83640, 156)}
    monkeypatch.setattr(fpga, "device_resources", lambda target, device: {
        "part": sizes[device][0], "lut4": sizes[device][1], "dsp": sizes[device][2], "bram_blocks": 108,
        "bram_bits": 108 * 18432}, raising=False)
    monkeypatch.setattr(proxy, "RESOURCE_MARGIN", {"lut4": 0.35, "dsp": 0.1}, raising=False)


def test_a_design_over_its_part_names_the_numbers_and_the_smallest_part(parts):
    over = fit.by_proxy({"lut": 12000, "dsp": 77}, "ecp5", "25k")
    assert over["status"] == "over" and over["part"] == "LFE5U-25F" and over["over"] == ["dsp"]
    assert over["resources"]["dsp"] == {"need": 77, "available": 28, "margin": 0.1, "low": 69, "high": 85}
    assert over["smallest_device"] == "85k"              # 45k's 72 DSPs are within the margin of 77
    near = fit.by_proxy({"lut": 12000, "dsp": 77}, "ecp5", "45k")
    assert near["status"] == "margin" and near["over"] == ["dsp"] and near["smallest_device"] == "85k"
    assert fit.by_proxy({"lut": 12000, "dsp": 39}, "ecp5", None)["status"] == "fits"
    assert fit.by_proxy({"lut": 12000, "dsp": 39}, "asic", "osu018") is None
    assert fit.by_synthesis({"lut4": 9000, "dsp": 59, "bram_bits": 0}, "ecp5", "45k")["status"] == "fits"


def test_without_a_clock_proxy_nothing_asked_is_met_and_a_rate_asked_is_unknown():
    free = timing(None, 1, 20, Speed(), "proxy")
    assert free["met"] is True and free["fmax_mhz"] is None and free["pixel_rate_mpx"] is None
    asked = timing(None, 2, 20, Speed(40), "proxy")
    assert asked["met"] is None and asked["clock_required_mhz"] == 80
    assert pick([{"cost": 1, "architecture": {}, **asked}]) == (None, {"cost": 1, "architecture": {}, **asked})


def test_of_equal_cost_and_rate_the_shallower_is_picked():
    deep, shallow = _priced(1000, 60, depth=3), _priced(1000, 60, depth=0)
    assert pick([deep, shallow]) == (shallow, shallow)
