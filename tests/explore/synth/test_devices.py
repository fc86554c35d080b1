"""The FPGA parts' capacities (phongfx.explore.synth.fpga.device_resources)."""

import pytest

from phongfx.explore.synth.fpga import TARGETS, device_resources


def test_the_ecp5_parts_hold_what_nextpnr_and_the_data_sheet_say():
    assert device_resources("ecp5", "25k") == {"part": "LFE5U-25F", "lut4": 24288, "dsp": 28, "bram_blocks": 56,
                                               "bram_bits": 56 * 18432}
    assert device_resources("ecp5", "45k")["lut4"] == 43848 and device_resources("ecp5", "45k")["dsp"] == 72
    assert device_resources("ecp5", "85k")["dsp"] == 156 and device_resources("ecp5", "85k")["bram_blocks"] == 208
    assert device_resources("ice40", "up5k") == {"part": "iCE40UP5K", "lut4": 5280, "dsp": 8, "bram_blocks": 30,
                                                 "bram_bits": 30 * 4096}


def test_every_device_the_flow_knows_has_its_resources_and_its_part():
    for target, info in TARGETS.items():
        for device, (part, *_) in info.devices.items():
            assert device_resources(target, device)["part"] == part


def test_an_unknown_device_or_target_is_named_with_the_allowed_ones():
    with pytest.raises(ValueError, match=r"^device must be one of 25k, 45k, 85k, not '12k'$"):
        device_resources("ecp5", "12k")
    with pytest.raises(ValueError, match=r"^target must be one of ecp5, ice40, not 'asic'$"):
        device_resources("asic", "osu018")
