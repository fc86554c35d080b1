"""What a compiled design costs, and when two costs are too close to call.

:func:`cost` prices one shader on the target asked for: synthesized (cached,
:func:`phongfx.explore.synth.fpga.synth`) or by the tool-free proxies of
:mod:`phongfx.explore.synth.proxy`.  A choice between methods whose costs differ by less
than the cost model can resolve is no choice: :func:`tie` flags it, with what decided it
and the runner-up, rather than presenting a 0.15% margin as a winner.
"""

from phongfx.core.registry import get_block
from phongfx.explore.synth.fpga import SynthError

from . import run as runs

__all__ = ["COST_UNITS", "TIE_MARGIN", "utilisation", "cost", "costed", "tie"]

#: Costs closer than this share of the chosen one are a tie.  The proxy misprices single
#: blocks by more (the blend about 5×, carry chains at 0), and on an FPGA a LUT-eq weighs
#: a DSP by a convention (958 LUT4s); nextpnr's placer seed moves Fmax by about ±10%.
TIE_MARGIN = 0.10

#: Per target: the key of the compared cost and its unit.
COST_UNITS = {"ecp5": ("lut_eq", "LUT-eq"), "ice40": ("lut_eq", "LUT-eq"), "asic": ("area_um2", "µm²")}


def utilisation(placed):
    """``{resource: {"used", "available", "percent"}}`` of nextpnr's placed counts (the
    synthesis harness included), the share of the device a user plans around."""
    return {name: {"used": used, "available": available,
                   "percent": round(100 * used / available, 2) if available else None}
            for name, (used, available) in placed.items()}


def cost(method, config, synth=False, copies=1, *, target="ecp5", device=None, freq=150, seed=1,
         progress=None):
    """Cost of ``copies`` of ``method``'s block at ``config`` on ``target``: synthesis
    (``synth``) or the tool-free proxy.  ``cost`` is the compared number for every copy
    (LUT-eq on an FPGA, µm² on standard cells), also under its own key (``lut_eq`` or
    ``area_um2``); the other keys are per copy, and ``target``, ``device``, ``freq``,
    ``seed`` and ``model`` say what produced it (synthesized on an FPGA: also ``part`` and
    ``utilisation``).  ``progress``: the synthesis flow's stages."""
    from phongfx.explore.synth.asic import DEFAULT_LIBRARY

    block = get_block(runs.block_name(method), config=config)
    key, unit_name = COST_UNITS[target]
    if target == "asic":
        device = device or DEFAULT_LIBRARY
    where = {"target": target, "device": device, "freq": freq if synth else None,
             "seed": seed if synth and target != "asic" else None,
             "model": f"{target}-synth" if synth else f"{target}-proxy", "unit": unit_name}
    if not synth:
        from phongfx.explore.synth.proxy import proxy_estimate
        unit = proxy_estimate(block, target, device)
    else:
        from phongfx.explore.synth.fpga import synth as run_synth
        result = run_synth(block.name, config=config, target=target, device=device, freq=freq, seed=seed,
                           progress=progress)
        if target == "asic":
            keys = ("area_um2", "cell_count", "ff", "fmax_mhz", "latency", "critical_path")
            unit = {k: result[k] for k in keys}
        else:
            keys = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "latency")
            unit = {"lut_eq": result["lut4"] + 958 * result["dsp"], **{k: result[k] for k in keys},
                    "part": result.get("part"), "utilisation": utilisation(result.get("placed", {}))}
    total = copies * unit[key]
    return {**unit, key: total, "cost": total, "copies": copies, **where}


def costed(method, config, synth, **options):
    """:func:`cost`, or, when a tool fails, ``{"cost": None, "why": ..., "log": ...}``: the
    failure costs that design only (it is chosen only if nothing else meets the requirement)."""
    try:
        return cost(method, config, synth, 1, **options)
    except (ValueError, SynthError) as error:
        first = str(error).splitlines()[0]
        why, _, log = first.partition("; log ")
        out = {"cost": None, "why": why.rstrip(":")}
        if log:
            out["log"] = log.rstrip(":")
        return out


def tie(ranked, margin=TIE_MARGIN):
    """``ranked`` (feasible results, cheapest first): None, or the runner-up within
    ``margin`` of the chosen cost and what decided: ``{"chosen", "runner_up", "margin",
    "within", "decided_by", "runner_up_cost", "runner_up_max", "runner_up_mean"}``."""
    if len(ranked) < 2 or any(r["cost"]["cost"] is None for r in ranked[:2]):
        return None
    first, second = ranked[:2]
    gap = (second["cost"]["cost"] - first["cost"]["cost"]) / first["cost"]["cost"]
    if gap > margin:
        return None
    model = first["cost"]["model"]
    return {"chosen": first["method"], "runner_up": second["method"], "margin": gap, "within": margin,
            "decided_by": f"the {model} cost alone, {gap:.2%} apart, less than the {margin:.0%} that "
                          f"model can resolve: compare both by synthesis on the target (--synth) "
                          f"and by their error",
            "runner_up_cost": second["cost"]["cost"], "runner_up_max": second["max"],
            "runner_up_mean": second["mean"]}
