"""What a compiled design costs, and when two costs are too close to call.

:func:`cost` prices one shader on the target asked for: synthesized (cached,
:func:`phongfx.explore.synth.fpga.synth`) or by the tool-free proxies of
:mod:`phongfx.explore.synth.proxy`.  :func:`price_designs` prices many designs (method,
widths) each at its cheapest architecture meeting the speed asked
(:mod:`phongfx.explore.compile.architecture`): by the proxies, or, for those to be
synthesized, the few architectures the proxies rank best synthesized together, in
parallel (:func:`phongfx.explore.synth.parallel.synth_all`, the sweeps' Dask path), and
picked among by their synthesized area and clock.  A choice between methods whose costs
differ by less than the cost model can resolve is no choice: :func:`tie` flags it, with
what decided it and the runner-up, rather than presenting a 0.15% margin as a winner.
"""

from phongfx.core.registry import get_block
from phongfx.explore.synth.fpga import SynthError

from . import architecture as architectures
from .architecture import COST_UNITS
from . import fit as fits
from . import run as runs
from .workers import fork_imap

__all__ = ["TIE_MARGIN", "utilisation", "cost", "costed", "price_designs", "tie"]

#: Costs closer than this share of the chosen one are a tie.  The proxy misprices single
#: blocks by more (the blend about 5×, carry chains at 0), and on an FPGA a LUT-eq weighs
#: a DSP by a convention (958 LUT4s); nextpnr's placer seed moves Fmax by about ±10%.
TIE_MARGIN = 0.10

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
    block = get_block(runs.block_name(method), config=config)
    key = COST_UNITS[target][0]
    where = _where(target, device, freq, seed, synth)
    device = where["device"]
    if not synth:
        from phongfx.explore.synth.proxy import proxy_estimate
        unit = proxy_estimate(block, target, device)
    else:
        from phongfx.explore.synth.fpga import synth as run_synth
        result = run_synth(block.name, config=config, target=target, device=device, freq=freq, seed=seed,
                           progress=progress)
        unit = _synthesized(result, target)
    total = copies * unit[key]
    return {**unit, key: total, "cost": total, "copies": copies, **where}


def _synthesized(result, target):
    """The cost keys of a synthesis result (:func:`phongfx.explore.synth.fpga.synth`)."""
    if target == "asic":
        keys = ("area_um2", "cell_count", "ff", "fmax_mhz", "latency", "critical_path")
        return {k: result[k] for k in keys}
    keys = ("lut4", "ff", "carry", "dsp", "bram_bits", "fmax_mhz", "latency")
    return {"lut_eq": result["lut4"] + 958 * result["dsp"], **{k: result[k] for k in keys},
            "part": result.get("part"), "utilisation": utilisation(result.get("placed", {}))}


def costed(method, config, synth, **options):
    """:func:`cost`, or, when a tool fails, ``{"cost": None, "why": ..., "log": ...}``: the
    failure costs that design only (it is chosen only if nothing else meets the requirement)."""
    try:
        return cost(method, config, synth, 1, **options)
    except (ValueError, SynthError) as error:
        return _failure(error)


def _failure(error):
    first = str(error).splitlines()[0]
    why, _, log = first.partition("; log ")
    out = {"cost": None, "why": why.rstrip(":")}
    if log:
        out["log"] = log.rstrip(":")
    return out


def _where(target, device, freq, seed, synth):
    if target == "asic":
        from phongfx.explore.synth.asic import DEFAULT_LIBRARY
        device = device or DEFAULT_LIBRARY
    return {"target": target, "device": device, "freq": freq if synth else None,
            "seed": seed if synth and target != "asic" else None,
            "model": f"{target}-synth" if synth else f"{target}-proxy", "unit": COST_UNITS[target][1]}


def _figures(priced):
    """The timing figures and architecture of a priced architecture, for a cost dict."""
    keep = ("architecture", "interval", "latency", "latency_ns", "fmax_mhz", "clock_mhz", "clock_source",
            "pixel_rate_mpx", "requirement_mpx", "clock_required_mhz", "met", "missed_by_mhz", "missed_by_percent")
    return {k: priced[k] for k in keep if k in priced}


def _proxy_cost(priced, where, count):
    """The cost dict of an architecture priced by the proxies (:func:`architecture.price`)."""
    clock = priced["clock"]
    key = COST_UNITS[where["target"]][0]
    return {**priced["unit"], key: priced["cost"], "cost": priced["cost"], "copies": 1, **where,
            **_figures(priced), "clock_model": clock.get("model"), "clock_error": clock.get("error"),
            "clock_margin": clock.get("margin"),
            "clock_estimate_mhz": None if clock.get("estimate_mhz") is None else round(clock["estimate_mhz"], 2),
            "clock_path": clock.get("path"), "architectures_priced": count, "fit": priced.get("fit")}


def _summary(priced):
    """What the manifest keeps of an architecture that was not chosen."""
    return {"cost": priced["cost"], "fits": priced.get("fits", True), **_figures(priced)}


def price_designs(designs, analysis, speed, *, target="ecp5", device=None, freq=150, seed=1, progress=None,
                  scheduler=None, workers=None):
    """The cost dict of each design of ``designs`` (``(method, params, by_synth)``, or with a
    fourth item True: priced at :data:`~.architecture.DEFAULT` only), at its cheapest
    architecture meeting ``speed`` (an :class:`~.architecture.Speed`), in order.

    Every architecture :func:`~.architecture.candidates` proposes is priced by the proxies
    (and, on an FPGA, fitted to the part: :mod:`phongfx.explore.compile.fit`); a design not
    synthesized takes the cheapest that meets the speed and fits.  For those ``by_synth``,
    the :func:`~.architecture.proposals` of every design are synthesized together
    (:func:`phongfx.explore.synth.parallel.synth_all` on ``scheduler`` with ``workers``,
    ``progress`` ticking per candidate) and each design takes the cheapest synthesized one
    that meets the speed, else the fastest, flagged ``met: false``.  A design no
    architecture of which meets the speed (by the proxies) has ``met: false`` and
    ``fastest``; a tool failure gives :func:`costed`'s failure dict."""
    proxy_where = _where(target, device, freq, seed, False)
    results, jobs = [], []

    def by_proxies(design):  # every architecture of one design, priced and fitted (or the tool's error)
        method, params, _, *only_default = design
        offered = architectures.candidates(method, analysis, architectures.Speed() if any(only_default) else speed)
        try:
            priced = [architectures.price(method, params, analysis, a, speed, target=target, device=device)
                      for a in offered]
            return _fitted(priced, method, params, analysis, speed, target, device, not any(only_default))
        except (ValueError, SynthError) as error:
            return error

    # each design elaborated to RTLIL twice (area, clock) unless cached: the designs side by side
    many = len(designs) > 1 and not any(by_synth for _, _, by_synth, *_ in designs)
    for (method, params, by_synth, *only_default), priced in zip(
            designs, fork_imap(by_proxies, designs, workers) if many else map(by_proxies, designs)):
        if isinstance(priced, Exception):
            results.append(_failure(priced))
            continue
        chosen, fastest = architectures.pick(priced)
        out = _proxy_cost(chosen or fastest, proxy_where, len(priced))
        if chosen is None:
            out["fastest"] = _summary(fastest)
            out["why_not"] = "speed" if any(p["fits"] for p in priced) else "fit"
        if by_synth and out.get("why_not") != "fit":  # certainly over the part: minutes for nothing
            proposed = architectures.proposals(priced, speed)
            out = {"proxy": out, "proposed": proposed, "method": method}
            for p in proposed:
                label = f"{method}, {architectures.describe(p['architecture'])}, " + " ".join(
                    f"{k}={v}" for k, v in params.items())
                jobs.append({"name": runs.block_name(method), "config": p["config"], "target": target,
                             "device": device, "freq": freq, "seed": seed, "label": label})
        results.append(out)
    if not jobs:
        return results
    from phongfx.explore.synth.parallel import synth_all
    if len(jobs) == 1 and scheduler is None:
        workers = 1  # one candidate: in this process, without starting a cluster
    done = iter(synth_all(jobs, scheduler=scheduler, workers=workers, progress=progress))
    synth_where = _where(target, device, freq, seed, True)
    for index, out in enumerate(results):
        if "proposed" in out:
            results[index] = _synthesized_choice(out, [next(done) for _ in out["proposed"]], speed, synth_where)
    return results


def _fitted(priced, method, params, analysis, speed, target, device, widen):
    """``priced`` with each architecture's fit to the part; when none fits and ``widen``,
    every architecture of the method priced and fitted instead (fewer units taking turns
    can fit a part that the units side by side do not, at any speed when none is asked)."""
    for p in priced:
        p["fit"] = fits.by_proxy(p["unit"], target, device)
        p["fits"] = p["fit"] is None or p["fit"]["status"] != "over"
    if any(p["fits"] for p in priced) or not widen or speed.asked:
        return priced
    more = [architectures.price(method, params, analysis, a, speed, target=target, device=device)
            for a in runs.architectures(method, analysis) if a != architectures.DEFAULT]
    return priced + _fitted(more, method, params, analysis, speed, target, device, False)


def _synthesized_choice(pending, found, speed, where):
    """The cost dict of a design whose proposed architectures were synthesized (``found``:
    results or exceptions, in order): the cheapest that meets the speed, else the fastest."""
    key = COST_UNITS[where["target"]][0]
    done = []
    for priced, result in zip(pending["proposed"], found):
        if isinstance(result, BaseException):
            failure = _failure(result)
            continue
        unit = _synthesized(result, where["target"])
        figures = architectures.timing(unit["fmax_mhz"], priced["interval"], unit["latency"], speed, "synthesis")
        done.append({**priced, **figures, "unit": unit, "cost": unit[key], "synth": result})
    if not done:
        if failure["why"].startswith("design does not fit"):
            failure["fit"] = {**(pending["proxy"].get("fit") or {}), "status": "over", "source": "synthesis",
                              "why": failure["why"]}
        return {**failure, "proxy": pending["proxy"]}
    chosen, fastest = architectures.pick(done)
    best = chosen or fastest
    out = {**best["unit"], key: best["cost"], "cost": best["cost"], "copies": 1, **where, **_figures(best),
           "fit": fits.by_synthesis(best["synth"], where["target"], where["device"]),
           "proxy": {k: pending["proxy"].get(k) for k in ("cost", "fmax_mhz", "pixel_rate_mpx", "met",
                                                           "architecture", "clock_error", "architectures_priced")},
           "synthesized": [_summary(p) for p in done]}
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
