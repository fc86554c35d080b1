"""What the scene compiler says when a method, or every method, misses the requirement.

A bare "infeasible" leaves a user guessing: was the search too timid, is a cap in the way,
or can this method never get there?  :func:`summary` reports the best point the search
measured (not the last one tried: every width at its maximum can be worse than the
defaults), and why it could go no further, from measurements: the method's own float form
against true Phong (an error no width removes), the shape function's ``k`` scanned over its
whole range, and a cap reached.  :func:`hint`, when nothing is feasible, computes a way
forward: the requirement that is met (with the command; met by the best point's measurement
and by its witness, :func:`phongfx.explore.compile.witness.search`), and, for a shininess range that
no single ``k`` serves, the split of the range whose parts each meet it.
"""

import math

from phongfx.core import words

from . import witness as witnesses
from .measure import GUARD, met_at

__all__ = ["summary", "per_variant", "split", "complete", "hint"]


def _finite(error):
    return math.isfinite(error["max"])


def per_variant(scene, error):
    """Per shininess variant of ``scene``, the max error of ``error`` (a
    :meth:`SceneEval.error` dict) over that variant's renders."""
    count = max(scene.variant_of, default=0) + 1
    out = [0.0] * count
    for variant, value in zip(scene.variant_of, error.get("per_render", [])):
        out[variant] = max(out[variant], value)
    return out


def _best(scene, method):
    """The measured point of ``method`` with the lowest max (then mean) error, or None."""
    points = [(dict(key[1]), error) for key, error in scene.cache.items()
              if key[0] == method and _finite(error)]
    if not points:
        return None
    return min(points, key=lambda p: (p[1]["max"], p[1]["mean"]))


def _ordered(params, like):
    """``params`` in the order of ``like``'s keys (the cache holds them sorted)."""
    return {**{k: params[k] for k in like if k in params}, **params}


def _why(scene, method, best, widest_point, scan, requirement):
    """The sentences of :func:`summary`'s ``why``, each from a measurement."""
    params, error = best
    out = []
    widest_error = scene.error(method, widest_point)
    if widest_point != params and widest_error["max"] > error["max"]:
        out.append(f"every width at its range maximum gives {words.levels(widest_error['max'])}, more than the "
                   f"best point's {error['max']:g}: wider formats do not lower this error")
    if scene.spec.requirement.against == "phong":
        try:
            form = scene.form_error(method, params)
        except ValueError:
            form = None
        if form is not None and form > requirement:
            out.append(f"its own float form is itself {form:.2f} levels from true Phong at the best point "
                       f"(before any rounding): no width can bring it to {requirement:g}")
        elif form is not None:
            out.append(f"its own float form is {form:.2f} levels from true Phong at the best point: the rest "
                       f"is the fixed-point rounding, with the widths at their range maxima")
    unrounded = error.get("domain_unrounded")
    if error["max"] <= requirement and unrounded is not None and unrounded > requirement + 0.5 - GUARD:
        out.append(f"on the domain its continuous error reaches {unrounded:.3f} levels, past the "
                   f"{requirement + 0.5 - GUARD:g} the search allows (the requirement's {requirement + 0.5:g} "
                   f"less a guard of {GUARD:g}, so that a fresh witness search does not find a point past it)")
    if scan:
        lo, hi = min(scan), max(scan)
        k = min(scan, key=lambda v: (scan[v]["max"], scan[v]["mean"], v))
        near = ", ".join(f"k = {v}: {scan[v]['max']:g}" for v in (k - 1, k + 1) if v in scan)
        out.append(f"the shape function's k, scanned over {lo}..{hi} with every other width at its maximum, "
                   f"is best at k = {k} ({words.levels(scan[k]['max'])}{'; ' + near if near else ''})"
                   + (f"; {hi} is the cap (phongfx.config.shape.K_MAX, n = 2^k = {2 ** hi})"
                      if k == hi else ""))
    return out


def summary(scene, method, widest_point, scan):
    """The result keys of an infeasible ``method``: ``feasible`` False, ``params`` and the
    error of the best point measured, ``widest`` (the fallback start and its max error),
    ``why`` (sentences) and ``k_scan`` (per ``k``: max error, and per shininess variant).

    A point that misses on the frames is measured there only (``domain_max`` None), as the
    search measures it: its domain changes no verdict, and measuring it was the longest part of
    some compiles (Lyon's spherical unit on the two-light scene, whose domain is fed as
    rasterized poses: 11 s of the method's 13).  :func:`hint`, which quotes the numbers when no
    method is feasible, measures its candidates' domains then (:func:`complete`)."""
    requirement = scene.spec.requirement.max_error_levels
    for key in sorted(k for k in scene.failed if k[0] == method):  # measured until they failed: whole now,
        scene.error(method, dict(key[1]))                           # so that every point tried can be the best
    best = _best(scene, method) or (widest_point, scene.error(method, widest_point))
    out = {"feasible": False, "params": _ordered(best[0], widest_point), **scene.measured(method, best[0]),
           "widest": {"params": widest_point, "max": scene.error(method, widest_point)["max"]},
           "why": _why(scene, method, best, widest_point, scan, requirement)}
    if scan:
        out["k_scan"] = {k: {"max": e["max"], "per_variant": per_variant(scene, e)} for k, e in scan.items()}
    return out


def split(scene, k_scan, requirement):
    """The split of the shininess range into two parts, each met by its own ``k``, from a
    ``k_scan`` measured at the scene's shininess variants (n_lo, geometric mean, n_hi), or
    None: ``{"k": [k_low, k_high], "ranges": {material: [[lo, b - 1], [b, hi]]}, "at": ...}``.
    Only the sampled n are measured; the boundary is the geometric mean of the two samples
    either side."""
    variants = scene.shininess_variants
    if len(variants) < 2 or not k_scan:
        return None
    meets = {k: [e <= requirement for e in data["per_variant"]] for k, data in k_scan.items()}
    if any(all(m) for m in meets.values()):
        return None  # one k meets every sample: the widths, not k, are what is missing
    for cut in range(1, len(variants)):
        low = [k for k, m in meets.items() if all(m[:cut])]
        high = [k for k, m in meets.items() if all(m[cut:])]
        if low and high:
            k_low = min(low, key=lambda k: k_scan[k]["per_variant"][cut - 1])
            k_high = min(high, key=lambda k: k_scan[k]["per_variant"][cut])
            ranges = {}
            for name in variants[0]:
                lo, hi = variants[0][name], variants[-1][name]
                b = round(math.sqrt(variants[cut - 1][name] * variants[cut][name]))
                ranges[name] = [[lo, b - 1], [b, hi]]
            return {"k": [k_low, k_high], "ranges": ranges,
                    "at": [{"n": v, "k": min(k_scan, key=lambda k: k_scan[k]["per_variant"][i]),
                            "max": min(d["per_variant"][i] for d in k_scan.values())}
                           for i, v in enumerate(variants)]}
    return None


def _met(result):
    """The whole requirement a method's result meets: its measurement's (:func:`met_at`), or
    its witness's error when that is more (a design the witness search failed)."""
    return max(met_at(result), (result.get("witness") or {}).get("error_levels", 0))


def complete(scene, result):
    """``result`` (an infeasible method's, :func:`summary`) with its best point and its widest
    measured on the domain too where the frames missed, in place: the error a hint quotes."""
    if result["feasible"] or scene.points is None or not math.isfinite(result["max"]):
        return result
    if result.get("domain_max") is None:
        result.update(scene.measured(result["method"], result["params"], complete=True))
    result["widest"]["max"] = scene.error(result["method"], result["widest"]["params"], complete=True)["max"]
    return result


def hint(compiled):
    """When no method meets the requirement: ``{"best": {method, max, params}, "command",
    "split" (:func:`split` of the best method with a ``k_scan``, or None), "text"}``,
    or None when something is feasible or nothing was measured.  The infeasible methods'
    results are first measured on the domain where their frames missed (:func:`complete`)."""
    if compiled.chosen is not None:
        return None
    results = [complete(compiled.scene, r) for r in compiled.results.values()]
    results = [r for r in results if math.isfinite(r["max"])]
    if not results:
        return None
    spec = compiled.spec
    requirement = spec.requirement.max_error_levels
    best = min(results, key=lambda r: (_met(r), r["max"], r["mean"]))
    levels, witness = _met(best), None
    if compiled.domain is not None:  # what the requirement it quotes must hold: the witness search's worst
        witness = witnesses.search(best["method"], best["params"], spec, compiled.domain, analysis=compiled.analysis)
        levels = max(levels, witness["error_levels"])
    command = f"phongfx compile {spec.path or spec.name + '.toml'} -o DIR --max-error {levels}"
    text = [f"the best any method reaches is {words.levels(best['max'])} ({best['method']} at {best['params']}); "
            f"a requirement of {words.levels(levels)} is met: {command}"]
    found = None
    for r in sorted(results, key=lambda r: r["max"]):
        found = split(compiled.scene, r.get("k_scan"), requirement)
        if found:
            found["method"] = r["method"]
            break
    if found:
        parts = "; ".join(f"{name} n = {a[0]}..{a[1]} and {b[0]}..{b[1]}"
                          for name, (a, b) in found["ranges"].items())
        samples = ", ".join(f"n = {'/'.join(map(str, s['n'].values()))}: k = {s['k']} ({words.levels(s['max'])})"
                            for s in found["at"])
        text.append(f"no single k serves the whole shininess range, but each part does ({found['method']}, "
                    f"measured at {samples}): split it into two materials ({parts}) or two units, "
                    f"at k = {found['k'][0]} "
                    f"and k = {found['k'][1]}")
    return {"best": {"method": best["method"], "max": best["max"], "params": best["params"], "witness": witness},
            "command": command, "split": found, "text": text}
