"""The architecture of a compiled design, chosen at least cost to meet the scene's pixel rate.

A design is a method at widths; its architecture is how that arithmetic is laid out in
time: the pipeline depth (0…4 register stages in the unit and the blend), the initiation
interval (the lights computed in ``interval`` groups by ``ceil(lights / interval)`` units,
one pixel every ``interval`` clocks) and whether the light-independent inputs (N, V at
infinity, ``n``) enter once and fan out (``share``).  The golden output of every
architecture is the same codes (exact accumulation, one rounding: tested in
``tests/golden``), so the width search measures each design once and only its cost and its
speed depend on the architecture.

:func:`price` prices each architecture of a design that :func:`candidates` proposes: area by
the area proxy (:func:`phongfx.explore.synth.proxy.proxy_estimate`), clock by the clock proxy
(:func:`phongfx.explore.synth.clock.proxy_clock`), each on the target asked for;
:func:`timing` turns a clock into the figures a user plans around (the clock it runs at,
pixel rate = clock / interval, latency in ns, the requirement and whether it is met, and by
how much it is missed); :func:`pick` takes the cheapest that meets the requirement, or,
when none does, says so with the fastest.  The clock proxy states a promise (its fitted
estimate less the margin that keeps it at or below synthesis on every calibration point), so a
rate met by the proxies is met by synthesis wherever the calibration holds.  With synthesis
(``--synth``) :func:`proposals` names the few the proxies rank best, which are synthesized and picked among by their
synthesized figures (:mod:`phongfx.explore.compile.costing`).
"""

import math
from dataclasses import dataclass

from phongfx.core.registry import get_block

from . import run as runs

__all__ = ["COST_UNITS", "DEFAULT", "CLOCK_MAX", "Speed", "candidates", "timing", "price", "pick", "proposals", "describe",
           "eligible", "rank_key", "refusal", "config_of", "design_block", "timing_of"]

#: Per target: the key of the compared cost (:func:`price`'s ``cost``, the area proxy's number)
#: and its unit.
COST_UNITS = {"ecp5": ("lut_eq", "LUT-eq"), "ice40": ("lut_eq", "LUT-eq"), "asic": ("area_um2", "µm²")}
#: The architecture compiled when no speed is asked: one unit per light side by side,
#: unpipelined, the light-independent inputs taken once.
DEFAULT = {"pipeline": 0, "interval": 1, "share": True}
#: Largest ``--clock`` (MHz) accepted: beyond any FPGA or the OSU standard cells.
CLOCK_MAX = 10_000


@dataclass(frozen=True)
class Speed:
    """What speed is asked: a pixel rate (``mpx``, Mpixel/s; the scene's
    ``requirement.mpixels_per_second`` or ``--throughput``) and the clock the core will be
    run at (``clock_mhz``, ``--clock``; None: each design at its own Fmax)."""

    mpx: float = None
    clock_mhz: float = None

    def __post_init__(self):
        for name, value, hi in (("throughput", self.mpx, 100_000), ("clock", self.clock_mhz, CLOCK_MAX)):
            if value is not None and (isinstance(value, bool) or not isinstance(value, (int, float))
                                      or not math.isfinite(value) or not 0 < value <= hi):
                raise ValueError(f"{name} must be a number of {'Mpixel/s' if name == 'throughput' else 'MHz'} "
                                 f"in (0, {hi}], not {value!r}")

    @property
    def asked(self):
        """Whether any speed is asked (else the default architecture is kept)."""
        return self.mpx is not None or self.clock_mhz is not None

    def required_clock(self, interval):
        """The clock (MHz) an architecture of ``interval`` must reach: ``--clock``, and the
        pixel rate times the interval; None when nothing is asked."""
        needs = [c for c in (self.clock_mhz, self.mpx and self.mpx * interval) if c]
        return max(needs) if needs else None

    def as_dict(self):
        return {"mpixels_per_second": self.mpx, "clock_mhz": self.clock_mhz}


def describe(architecture):
    """``depth 2, interval 1, shared`` of an architecture dict."""
    a = {**DEFAULT, **(architecture or {})}
    return f"depth {a['pipeline']}, interval {a['interval']}, {'shared' if a['share'] else 'per-copy'} inputs"


def candidates(method, analysis, speed):
    """The architectures of ``method`` to price for ``speed``: :data:`DEFAULT` alone when no
    speed is asked, else every one :func:`phongfx.explore.compile.run.architectures` lists
    except the per-copy inputs (``share=False``) where the shared twin exists: taking an
    input once is never more hardware (the area proxy and Yosys count the shared logic
    once) and lengthens no registered path; the unshared form is kept to measure that
    saving (``phongfx tables``), not to be shipped."""
    if not speed.asked:
        return [dict(DEFAULT)]
    found = [{**DEFAULT, **a} for a in runs.architectures(method, analysis)]
    shared = {(a["pipeline"], a["interval"]) for a in found if a["share"]}
    return [a for a in found if a["share"] or (a["pipeline"], a["interval"]) not in shared] or [dict(DEFAULT)]


def timing(fmax_mhz, interval, latency, speed, source):
    """The figures of an architecture of ``interval`` and ``latency`` (cycles) whose clock
    reaches ``fmax_mhz`` by ``source`` (``"proxy"`` or ``"synthesis"``) against ``speed``.

    The clock it runs at is ``--clock`` when given (capped by what it reaches), else its
    Fmax; its pixel rate that clock / ``interval``.  ``met``: the clock reaches both
    ``--clock`` and the pixel rate times the interval (True when nothing is asked); a miss
    gives ``missed_by_mhz`` (the clock it lacks) and ``missed_by_percent`` (of the clock
    required)."""
    required = speed.required_clock(interval)
    if fmax_mhz is None:  # no clock proxy for this target: met only when nothing is asked
        clock = speed.clock_mhz
        return {"interval": interval, "latency": latency, "latency_ns": clock and round(1000 * latency / clock, 2),
                "fmax_mhz": None, "clock_mhz": clock, "clock_source": None,
                "pixel_rate_mpx": clock and round(clock / interval, 2), "requirement_mpx": speed.mpx,
                "clock_required_mhz": required and round(required, 2), "met": True if required is None else None}
    clock = fmax_mhz if speed.clock_mhz is None else min(fmax_mhz, speed.clock_mhz)
    met = required is None or fmax_mhz >= required - 1e-9 and clock / interval >= (speed.mpx or 0) - 1e-9
    out = {"interval": interval, "latency": latency, "latency_ns": round(1000 * latency / clock, 2) if clock else None,
           "fmax_mhz": round(fmax_mhz, 2), "clock_mhz": round(clock, 2), "clock_source": source,
           "pixel_rate_mpx": round(clock / interval, 2), "requirement_mpx": speed.mpx,
           "clock_required_mhz": required and round(required, 2), "met": bool(met)}
    if not met:
        missed = required - clock
        out.update(missed_by_mhz=round(missed, 2), missed_by_percent=round(100 * missed / required, 1))
    return out


def price(method, params, analysis, architecture, speed, *, target="ecp5", device=None):
    """One architecture of ``method`` at ``params`` priced by the proxies: ``{"architecture",
    "config", "unit"`` (the area proxy's dict), ``"cost"`` (its compared number),
    ``"clock"`` (the clock proxy's dict) and the :func:`timing` figures``}``."""
    from phongfx.explore.synth.clock import proxy_clock
    from phongfx.explore.synth.proxy import proxy_estimate

    config = runs.build(method, params, analysis, architecture)
    block = get_block(runs.block_name(method), config=config)
    unit = proxy_estimate(block, target, device)
    try:
        clock = proxy_clock(block, target, device)
    except ValueError as error:  # a target the clock proxy is not calibrated for (iCE40)
        clock = {"fmax_mhz": None, "model": None, "error": None, "why": str(error)}
    figures = timing(clock["fmax_mhz"], getattr(config, "interval", 1), block.latency, speed, "proxy")
    return {"architecture": dict(architecture), "config": config, "unit": unit,
            "cost": unit[COST_UNITS[target][0]], "clock": clock, **figures}


def pick(priced):
    """``(chosen, fastest)`` of priced architectures: the cheapest that meets the speed
    (the faster of equal costs, then the shallower), else None; and the one of the highest
    pixel rate (the cheaper of equal rates), what the design reaches at best."""
    if not priced:
        return None, None
    def depth(p):  # of equal cost and rate, the shallower: fewer registers and cycles of latency
        return p["architecture"].get("pipeline", 0)

    fastest = min(priced, key=lambda p: (-(p["pixel_rate_mpx"] or 0), p["cost"], depth(p)))
    meeting = [p for p in priced if p["met"] and p.get("fits", True)]
    chosen = min(meeting, key=lambda p: (p["cost"], -(p["pixel_rate_mpx"] or 0), depth(p))) if meeting else None
    return chosen, fastest


def proposals(priced, speed, count=2):
    """The architectures worth synthesizing, at most ``count``: the cheapest that meets the
    speed by the proxies (whose clock is a promise: its calibrated margin taken off the
    fitted estimate), then the cheapest that meets it by the fitted estimate itself (it may
    well synthesize fast enough, and costs less); the fastest when none meets;
    :data:`DEFAULT` alone when nothing is asked."""
    fits = [p for p in priced if p.get("fits", True)] or priced
    chosen, fastest = pick(fits)
    if chosen is None:
        return [fastest]
    out = [chosen]
    hopeful = [p for p in fits if speed.asked and p["clock"].get("estimate_mhz") is not None
               and p["clock"]["estimate_mhz"] >= speed.required_clock(p["interval"])
               and p["cost"] < chosen["cost"]]
    if hopeful:
        out.append(min(hopeful, key=lambda p: (p["cost"], -p["pixel_rate_mpx"])))
    return out[:count]


def eligible(cost):
    """Whether a design of cost dict ``cost`` may be chosen: some architecture of it fits the
    part (not certainly over) and meets the speed by the proxies.  A synthesized design
    whose clock misses stays eligible (ranked after those that meet: :func:`rank_key`) and
    is flagged when chosen: the proxies proposed it as meeting."""
    fit = cost.get("fit") or {}
    return (cost.get("why_not") is None and fit.get("status") != "over"
            and not (cost.get("met") is False and cost.get("clock_source") == "proxy"))


def rank_key(cost):
    """Sort key of designs by cost dict: costed before uncosted, meeting the speed before
    missing it, then cheapest."""
    return cost.get("cost") is None, cost.get("met") is False, cost.get("cost") or 0


def refusal(compiled):
    """When nothing is chosen because no design that meets the error also meets the speed
    or fits the part: ``{"why": "speed" | "fit", "fastest": {method, params, architecture,
    pixel_rate_mpx, fmax_mhz, clock_source}, "fit": the cheapest design's fit, "text": [lines]}``;
    else None (something is chosen, or the error itself is what nothing meets)."""
    if compiled.chosen is not None:
        return None
    out = [r for r in compiled.results.values() if r["feasible"] and "cost" in r and not eligible(r["cost"])]
    if not out:
        return None

    def over(r):
        return r["cost"].get("why_not") == "fit" or (r["cost"].get("fit") or {}).get("status") == "over"

    timed = [r for r in out if r["cost"].get("pixel_rate_mpx") is not None]
    fastest = max((r for r in timed if not over(r)), default=None, key=lambda r: r["cost"]["pixel_rate_mpx"])
    reach = fastest and {"method": fastest["method"], "params": fastest["params"],
                         **{k: fastest["cost"][k] for k in ("architecture", "pixel_rate_mpx", "fmax_mhz",
                                                            "clock_source")}}
    if reach and reach["fmax_mhz"] is None:
        text = [f"no clock estimate for {compiled.cost_model.partition('-')[0]} without synthesis, so no design "
                f"is known to meet the speed asked: compile with --synth"]
        return {"why": "speed", "fastest": reach, "text": text}
    if reach:
        speed = compiled.speed
        asked = " and ".join(x for x in (speed.mpx and f"{speed.mpx:g} Mpixel/s",
                                         speed.clock_mhz and f"a {speed.clock_mhz:g} MHz clock") if x)
        text = [f"no design meets {asked}: the fastest, {reach['method']} at {reach['params']} "
                f"({describe(reach['architecture'])}), reaches {reach['fmax_mhz']:g} MHz by the "
                f"{reach['clock_source']}, {reach['pixel_rate_mpx']:g} Mpixel/s"]
        return {"why": "speed", "fastest": reach, "text": text}
    cheapest = min(out, key=lambda r: r["cost"].get("cost") or (r["cost"].get("proxy") or {}).get("cost") or 0)
    return {"why": "fit", "fit": cheapest["cost"].get("fit"), "method": cheapest["method"],
            "params": cheapest["params"], "architecture": cheapest["cost"].get("architecture"),
            "text": fit_text(cheapest)}


def fit_text(result):
    """The lines that refuse ``result``'s design for its part: the numbers and the smallest
    ``--device`` that holds it."""
    fit = result["cost"].get("fit") or {}
    names = {"lut4": "LUT4", "dsp": "DSP", "bram_bits": "block RAM bits"}
    counts = []
    for name in fit.get("over", []):
        r = fit["resources"][name]
        margin = f" (±{r['margin']:.0%} by the proxy: at least {r['low']:,})" if r.get("margin") else ""
        counts.append(f"{names[name]} {r['need']:,}{margin} of {r['available']:,}")
    device = fit.get("smallest_device")
    where = (f"the smallest part that holds it: --device {device}" if device
             else "no part of this target holds it")
    return [f"{result['method']} at {result['params']} ({describe(result['cost'].get('architecture'))}) does not "
            f"fit the {fit.get('part')}: {', '.join(counts) or fit.get('why', 'over')}; {where}"]


def config_of(result, analysis):
    """The shader config of a search result (``{"method", "params", "cost"}``) at the
    architecture its cost chose (:data:`DEFAULT` when it has none)."""
    architecture = (result.get("cost") or {}).get("architecture")
    return runs.build(result["method"], result["params"], analysis, architecture)


def design_block(result, analysis):
    """The registered block of a search result at :func:`config_of`'s config: the design the
    compiler ships, checks and proves."""
    return get_block(runs.block_name(result["method"]), config=config_of(result, analysis))


#: The keys of a cost dict that say how fast the design runs (the manifest's ``"timing"``).
TIMING_KEYS = ("architecture", "interval", "latency", "latency_ns", "fmax_mhz", "clock_mhz", "clock_source",
               "clock_model", "clock_error", "clock_margin", "clock_estimate_mhz", "pixel_rate_mpx", "requirement_mpx", "clock_required_mhz", "met",
               "missed_by_mhz", "missed_by_percent")


def timing_of(cost):
    """The manifest's ``"timing"`` of a chosen design's cost dict: its architecture, interval,
    latency (cycles, ns), clock (MHz, and its source: ``"proxy"`` or ``"synthesis"``), pixel
    rate, the requirement and whether it is ``met`` (by how much it is missed when not)."""
    return {k: cost[k] for k in TIMING_KEYS if k in cost}
