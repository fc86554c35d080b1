"""Whether a compiled design fits its FPGA part: LUT4s, DSP multipliers, block RAM.

A core that does not fit the part it is compiled for is no answer, so the compiler checks
the chosen design against the part's resources
(:func:`phongfx.explore.synth.fpga.device_resources`).  By the area proxy the counts are
estimates whose measured error (:data:`phongfx.explore.synth.proxy.RESOURCE_MARGIN`, the
largest relative error against synthesis over the registry's datapaths) is the margin:
a design over the part even with its counts lowered by that error is certainly over
(``"over"``: refused, with the smallest part that holds it); one within the margin of the
part's size is ``"margin"`` (shipped with a warning: synthesis, ``--synth``, settles it);
the rest ``"fits"``.  Synthesized, nextpnr has placed it, or said it does not fit; its
LUT4 sites are Yosys' LUT4 cells and two per CCU2C carry cell.
"""

from phongfx.explore.synth.fpga import TARGETS

__all__ = ["RESOURCES", "by_proxy", "by_synthesis", "check", "smallest_device"]

#: The checked resources: ``name -> (key of device_resources, label)``.
RESOURCES = {"lut4": ("lut4", "LUT4"), "dsp": ("dsp", "DSP"), "bram_bits": ("bram_bits", "block RAM bits")}


def _margins():
    from phongfx.explore.synth.proxy import RESOURCE_MARGIN
    return {"lut4": RESOURCE_MARGIN.get("lut4", 0.0), "dsp": RESOURCE_MARGIN.get("dsp", 0.0), "bram_bits": 0.0}


def check(need, target, device, margins, source):
    """``need`` (``{"lut4", "dsp", "bram_bits"}`` counts) against the part ``device`` of
    ``target``: ``{"part", "device", "source", "status", "resources": {name: {"need",
    "available", "margin", "low", "high"}}, "over": [names]}`` (module docstring)."""
    from phongfx.explore.synth.fpga import device_resources

    device = device or TARGETS[target].default_device
    part = device_resources(target, device)
    resources, over, near = {}, [], []
    for name, (key, _) in RESOURCES.items():
        value, available, margin = need.get(name, 0) or 0, part[key], margins.get(name, 0.0)
        low, high = value * (1 - margin), value * (1 + margin)
        resources[name] = {"need": value, "available": available, "margin": margin,
                           "low": round(low), "high": round(high)}
        if low > available:
            over.append(name)
        elif high > available:
            near.append(name)
    status = "over" if over else "margin" if near else "fits"
    return {"part": part["part"], "device": device, "source": source, "status": status,
            "resources": resources, "over": over or near}


def smallest_device(need, target, margins):
    """The smallest part of ``target`` (by LUT4s) that certainly holds ``need`` (``"fits"``),
    else the smallest within the margin, else None."""
    from phongfx.explore.synth.fpga import device_resources

    devices = sorted(TARGETS[target].devices, key=lambda d: (device_resources(target, d)["lut4"],
                                                            device_resources(target, d)["dsp"]))
    for wanted in ("fits", "margin"):
        for device in devices:
            if check(need, target, device, margins, "proxy")["status"] == wanted:
                return device
    return None


def _proxy_need(unit):
    """The proxy's counts: its LUT4 sites (logic and carry alike, as a part's capacity counts
    them), DSPs; ROMs are priced as LUTs, so no block RAM."""
    return {"lut4": unit.get("lut4", unit.get("lut", 0)), "dsp": unit.get("dsp", 0), "bram_bits": 0}


def by_proxy(unit, target, device):
    """The fit of a design priced by the area proxy (``unit``: :func:`proxy_estimate`'s dict)
    on an FPGA ``target``, with the smallest part when over; None on standard cells."""
    if target not in TARGETS:
        return None
    margins = _margins()
    need = _proxy_need(unit)
    found = check(need, target, device, margins, "proxy")
    if found["status"] != "fits":
        found["smallest_device"] = smallest_device(need, target, margins)
    return found


def by_synthesis(result, target, device):
    """The fit of a synthesized design (placed by nextpnr, so within its part; its counts are
    the bare block's, the harness aside); None on standard cells."""
    if target not in TARGETS:
        return None
    need = {"lut4": result.get("lut4", 0) + 2 * result.get("carry", 0), "dsp": result.get("dsp", 0),
            "bram_bits": result.get("bram_bits", 0)}  # a CCU2C carry cell fills two LUT4 sites
    return check(need, target, device, {}, "synthesis")
