"""What each FPGA part holds: LUT4s, DSP multipliers and block RAM (:func:`device_resources`).

The compiler refuses a design that does not fit its part, before any synthesis, so it
needs the part's capacity beside the area proxy's estimate.  The counts are nextpnr's
("Device utilisation" and "Logic utilisation before packing" lines, which
:mod:`.fpga` parses for a run that does not fit), and agree with Lattice's data sheets:

* ECP5 (FPGA-DS-02012): LFE5U-25F 24,288 LUT4s, 28 MULT18X18D, 56 DP16KD blocks of
  18 Kbit (1,008 Kbit); LFE5U-45F 43,848, 72, 108 (1,944 Kbit); LFE5U-85F 83,640, 156,
  208 (3,744 Kbit);
* iCE40 (FPGA-DS-02008, DS1040): iCE40UP5K 5,280 LUT4s, 8 SB_MAC16, 30 SB_RAM40_4K of
  4 Kbit (its four 256-Kbit SPRAMs are single-port RAM, not counted here); iCE40HX8K
  7,680, none, 32; iCE40HX1K 1,280, none, 16.
"""

__all__ = ["DEVICE_RESOURCES", "device_resources"]

#: target -> device -> (part, LUT4s, DSPs, block RAMs, bits per block RAM).
DEVICE_RESOURCES = {
    "ecp5": {"25k": ("LFE5U-25F", 24288, 28, 56, 18432),
             "45k": ("LFE5U-45F", 43848, 72, 108, 18432),
             "85k": ("LFE5U-85F", 83640, 156, 208, 18432)},
    "ice40": {"up5k": ("iCE40UP5K", 5280, 8, 30, 4096),
              "hx8k": ("iCE40HX8K", 7680, 0, 32, 4096),
              "hx1k": ("iCE40HX1K", 1280, 0, 16, 4096)},
}


def device_resources(target, device):
    """``{part, lut4, dsp, bram_blocks, bram_bits}`` of FPGA ``device`` (``"45k"``,
    ``"up5k"`` ...) of ``target`` (``"ecp5"``, ``"ice40"``); ValueError naming the
    allowed ones otherwise."""
    if target not in DEVICE_RESOURCES:
        raise ValueError(f"target must be one of {', '.join(DEVICE_RESOURCES)}, not {target!r}")
    devices = DEVICE_RESOURCES[target]
    if device not in devices:
        raise ValueError(f"device must be one of {', '.join(devices)}, not {device!r}")
    part, lut4, dsp, blocks, bits = devices[device]
    return {"part": part, "lut4": lut4, "dsp": dsp, "bram_blocks": blocks, "bram_bits": blocks * bits}
