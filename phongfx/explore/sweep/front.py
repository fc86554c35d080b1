"""Sweep records compared: the cost a record is ranked by, and the Pareto front in error
against cost.

The report (:mod:`phongfx.explore.report`) and the sweep's plots
(:mod:`phongfx.explore.sweep.plot`) both rank records this way, so it lives apart from
either.  Cost is counted in **LUT-equivalents**: ``lut4 + W·dsp`` with ``W`` =
:data:`DSP_LUT_WEIGHT`, the LUT4 count of an 18×18 signed multiplier (the size of one
ECP5 ``MULT18X18D``) built from logic, measured with Yosys 0.70 ``synth_ecp5 -nodsp``
after ``booth`` (958 LUT4 and 18 CCU2C; Yosys' default array mapping takes 1868 LUT4);
on standard cells in µm².  Speed is ``cost["mpixels_per_s"]`` (one pixel per clock),
where higher is better.
"""

import math

__all__ = ["DSP_LUT_WEIGHT", "MAXIMIZE", "INVISIBLE", "is_proxy", "cost_key", "target_label", "lut_equivalent",
           "value", "usable", "pareto"]

#: LUT4s one MULT18X18D stands for (Booth 18×18 signed soft multiplier, Yosys 0.70, ECP5).
DSP_LUT_WEIGHT = 958

#: Cost keys where a larger value is better (the others are minimized).
MAXIMIZE = frozenset({"mpixels_per_s", "fmax_mhz"})

#: Largest max error, in 8-bit levels, that a display cannot show.
INVISIBLE = 1.0

def is_proxy(record):
    """Whether a record's cost is a tool-free proxy's estimate, not a synthesis result."""
    return str((record.get("cost") or {}).get("model", "")).endswith("-proxy")


def cost_key(records):
    """The cost the records are compared by: ``"area_um2"`` when they were synthesized onto
    standard cells, else ``"lut_eq"``."""
    return "area_um2" if any((r.get("cost") or {}).get("area_um2") is not None for r in records) else "lut_eq"


def target_label(records):
    """``ecp5``, ``asic osu018``, ...: where the records were synthesized (ecp5 when nowhere)."""
    synth = next((r.get("synth") for r in records if r.get("synth")), None) or {}
    target = synth.get("target", "ecp5")
    device = synth.get("device") or ("osu018" if target == "asic" else None)
    return target + (f" {device}" if device else "")


def lut_equivalent(cost, dsp_weight=DSP_LUT_WEIGHT):
    """``lut4 + dsp_weight·dsp`` of a record's ``cost``, or ``None`` when not synthesized."""
    if cost and cost.get("lut4") is None and cost.get("lut_eq") is not None:
        return float(cost["lut_eq"])  # a proxy's estimate
    if not cost or cost.get("lut4") is None:
        return None
    return float(cost["lut4"]) + dsp_weight * float(cost.get("dsp") or 0)


def value(record, key, dsp_weight=DSP_LUT_WEIGHT):
    """``key`` of a record: ``"lut_eq"``, a metric (``"torus.phong.max"``) or a cost key; else ``None``."""
    if key == "lut_eq":
        result = lut_equivalent(record.get("cost"), dsp_weight)
    elif key in (record.get("metrics") or {}):
        result = record["metrics"][key]
    else:
        result = (record.get("cost") or {}).get(key)
    if result is None or isinstance(result, bool):
        return None
    result = float(result)
    return result if math.isfinite(result) else None


def usable(records, error_key, cost_key, dsp_weight=DSP_LUT_WEIGHT):
    """The ``ok`` records that have both ``error_key`` and ``cost_key``."""
    return [r for r in records if r.get("status") == "ok" and value(r, error_key) is not None
            and value(r, cost_key, dsp_weight) is not None]


def pareto(records, error_key, cost_key, *, maximize=None, dsp_weight=DSP_LUT_WEIGHT):
    """The non-dominated ``ok`` records in (error, cost), best cost first (so error falls along it).

    Error is always minimized; cost is minimized, unless ``maximize`` (default: ``cost_key``
    in :data:`MAXIMIZE`, e.g. ``"mpixels_per_s"``).  A record is dominated when another is
    no worse in both and strictly better in one, so records tied in both are all kept.
    Records that failed or lack either value are ignored.
    """
    if maximize is None:
        maximize = cost_key in MAXIMIZE
    sign = -1.0 if maximize else 1.0
    points = sorted(((sign * value(r, cost_key, dsp_weight), value(r, error_key), i, r)
                     for i, r in enumerate(usable(records, error_key, cost_key, dsp_weight))),
                    key=lambda p: p[:3])
    front, best_error, best_cost = [], math.inf, None
    for cost, error, _, record in points:  # each point sees every cheaper-or-equal one first
        if error < best_error:
            best_error, best_cost = error, cost
            front.append(record)
        elif error == best_error and cost == best_cost:
            front.append(record)
    return front
