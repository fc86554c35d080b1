"""The sweep's Pareto plots: error against cost and against speed, every method in one picture.

A plot has to explain itself to someone who has not read the spec: the points on the
front carry their parameters ("vec=10 t=8": the widths that were swept, not the ones held
fixed), and a sweep run without synthesis (error only) is still drawn against a cost:
the tool-free proxy (:func:`phongfx.explore.synth.proxy.proxy_estimate`) of each point's
design, which the axis label names, instead of an empty picture.  How records are
costed and ranked is :mod:`phongfx.explore.sweep.front`.
"""

import functools

from phongfx.explore.sweep.front import (DSP_LUT_WEIGHT, INVISIBLE, MAXIMIZE, cost_key, is_proxy, pareto,
                                         target_label, usable, value)

__all__ = ["COST_LABEL", "pareto_plot", "swept", "short_params", "with_proxy_cost"]

#: Axis label of each cost key.
COST_LABEL = {"lut_eq": f"cost (LUT4 + {DSP_LUT_WEIGHT}·DSP LUT-equivalents)",
              "area_um2": "area (µm², standard cells)",
              "mpixels_per_s": "Mpixel/s (Fmax at 1 pixel/clock)"}

_MARKERS = "osD^v<>pPX*h"


def _style(methods):
    import matplotlib

    colours = matplotlib.colormaps["tab10"].colors
    return {m: (colours[i % len(colours)], _MARKERS[i % len(_MARKERS)]) for i, m in enumerate(methods)}


def swept(records):
    """``method -> parameter names`` whose values differ among that method's records: the
    axes of the sweep, the only parameters worth printing beside a point."""
    values = {}
    for r in records:
        for k, v in (r.get("params") or {}).items():
            values.setdefault(r["method"], {}).setdefault(k, set()).add(repr(v))
    return {m: [k for k, seen in params.items() if len(seen) > 1] for m, params in values.items()}


def _short(name):
    # vec_frac -> vec, shape_t_frac -> t: the label sits beside a point, it must be short
    return name.removesuffix("_frac").removeprefix("shape_")


def short_params(record, names, method=False):
    """``"vec=10 t=8"`` of ``record``'s parameters ``names`` (``"fig7 vec=10"`` with
    ``method``); the method's name when ``names`` is empty."""
    params = record.get("params") or {}
    text = " ".join(f"{_short(k)}={params[k]}" for k in names if k in params)
    return f"{record['method']} {text}".strip() if method or not text else text


@functools.lru_cache(maxsize=None)
def _proxy(method, params, target):
    from phongfx.core.registry import get_block

    from phongfx.explore.synth.proxy import proxy_estimate
    from phongfx.core.methods import METHODS

    spec = METHODS[method]
    estimate = proxy_estimate(get_block(spec.block, spec.config(dict(params))), target)
    return {k: estimate[k] for k in ("area_um2", "lut_eq", "dsp", "model") if k in estimate}


def with_proxy_cost(records, target="ecp5"):
    """``records`` with every ``ok`` record that has no cost priced by the tool-free proxy
    on ``target`` (``model`` ``"<target>-proxy"``), when none of them was synthesized;
    otherwise ``records`` unchanged (a proxy beside synthesis results would rank
    estimates against measurements).  A record whose design cannot be built (an unknown
    method, a parameter out of range) stays without cost.  About 1.6 s per Figure 7 point
    (the design is elaborated), cached per design."""
    if any(r.get("status") == "ok" and r.get("cost") and not is_proxy(r) for r in records):
        return list(records)
    out = []
    for r in records:
        if r.get("status") == "ok" and not r.get("cost"):
            try:
                r = {**r, "cost": _proxy(r["method"], tuple(sorted((r.get("params") or {}).items())), target)}
            except (KeyError, TypeError, ValueError):
                pass
        out.append(r)
    return out


def _proxy_target(records):
    model = next((str(r["cost"]["model"]) for r in records if is_proxy(r)), "ecp5-proxy")
    return model.removesuffix("-proxy")


def _xlabel(key, points):
    better = "→ faster (better)" if key in MAXIMIZE else "← cheaper (better)"
    if points and all(is_proxy(r) for r in points):
        model = (points[0].get("cost") or {}).get("model")
        return f"{COST_LABEL[key]}  {better}\nestimated by the tool-free proxy ({model}): no point synthesized"
    return f"{COST_LABEL[key]}  {better}"


def _draw_front(ax, front, key, ys, labels, dsp_weight):
    xs = [value(r, key, dsp_weight) for r in front]
    order = sorted(range(len(xs)), key=xs.__getitem__)
    ax.step([xs[i] for i in order], [ys[i] for i in order], "k-", lw=1.2, alpha=0.7,
            where="pre" if key in MAXIMIZE else "post", label="Pareto front")
    ax.scatter(xs, ys, s=130, facecolors="none", edgecolors="k", linewidths=1.5)
    for rank, i in enumerate(order):  # alternate above and below, so neighbours do not collide
        right = rank >= len(order) / 2  # the right half's labels to the left, inside the axes
        ax.annotate(labels[i], (xs[i], ys[i]), textcoords="offset points", xytext=(-6 if right else 6,
                    7 if rank % 2 else -11), ha="right" if right else "left", fontsize=7, alpha=0.9)


def pareto_plot(records, path, error_key="torus.phong.max", *, dsp_weight=DSP_LUT_WEIGHT):
    """Write a two-panel PNG: ``error_key`` against cost (LUT-equivalents on an FPGA, µm² on
    standard cells: :func:`~phongfx.explore.sweep.front.cost_key`) and against Mpixel/s.

    Every method in one picture (one colour and marker each), the Pareto front over all
    of them drawn as a staircase with its points ringed and labelled by their swept
    parameters (:func:`short_params`), and a dashed line at :data:`INVISIBLE` level.  Costs
    estimated by a proxy are hollow; a sweep without synthesis is priced by the proxy
    (:func:`with_proxy_cost`) and says so on the axis.  The error axis (and the cost axis)
    is logarithmic when its values span more than a factor of 20 (zero errors are drawn at
    a floor of 0.01 level).  Written atomically (:func:`phongfx.core.files.atomic_write`).

    Returns
    -------
    dict
        ``{<cost key>: front, "mpixels_per_s": front, "plotted": int, "skipped": int,
        "labels": {key: [text per front record]}, "xlabel": {key: text}}``: each front as
        :func:`~phongfx.explore.sweep.front.pareto` gives it; ``plotted`` counts the ``ok``
        records drawn against cost, ``skipped`` those without cost (failed records are
        never plotted).
    """
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from phongfx.core.files import atomic_write

    ok = [r for r in records if r.get("status") == "ok" and value(r, error_key) is not None]
    ok = with_proxy_cost(ok, _proxy_target(ok))
    methods = sorted({r["method"] for r in ok})
    style, axes_of = _style(methods), swept(ok)
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.5))
    result = {"plotted": 0, "skipped": 0, "labels": {}, "xlabel": {}}
    errors = [value(r, error_key) for r in ok]
    positive = [e for e in errors if e > 0]
    log = bool(positive) and max(positive) / min(positive + [INVISIBLE]) > 20
    floor = 0.01

    def y(r):
        return max(value(r, error_key), floor) if log else value(r, error_key)

    for ax, key in zip(axes, (cost_key(ok), "mpixels_per_s")):
        points = usable(ok, error_key, key, dsp_weight)
        if key not in MAXIMIZE:  # counted by cost: a speed needs synthesis, a cost does not
            result["plotted"], result["skipped"] = len(points), len(ok) - len(points)
        for method in methods:
            for proxy in (False, True):  # proxy-costed points hollow: estimates, not synthesis
                pts = [r for r in points if r["method"] == method and is_proxy(r) == proxy]
                if pts:
                    colour, marker = style[method]
                    ax.scatter([value(r, key, dsp_weight) for r in pts], [y(r) for r in pts],
                               marker=marker, s=30, alpha=0.75, label=f"{method}{' (proxy cost)' if proxy else ''}",
                               **({"facecolors": "none", "edgecolors": colour} if proxy else {"color": colour}))
        # the front over synthesized points where there are any: proxies only estimate
        synthesized = [r for r in points if not is_proxy(r)]
        front = pareto(synthesized or points, error_key, key, dsp_weight=dsp_weight)
        result[key] = front
        several = len({r["method"] for r in points}) > 1
        result["labels"][key] = [short_params(r, axes_of.get(r["method"], []), several) for r in front]
        if front:
            _draw_front(ax, front, key, [y(r) for r in front], result["labels"][key], dsp_weight)
        elif key in MAXIMIZE:
            ax.text(0.5, 0.5, "no point synthesized: speed needs a [synth] table in the spec",
                    transform=ax.transAxes, ha="center", va="center", color="0.4")
        ax.axhline(INVISIBLE, color="tab:red", ls="--", lw=1, label=f"{INVISIBLE:g} level")
        if log:
            ax.set_yscale("log")
        xs = [value(r, key, dsp_weight) for r in points]
        if key not in MAXIMIZE and xs and min(xs) > 0 and max(xs) / min(xs) > 20:
            ax.set_xscale("log")
        result["xlabel"][key] = _xlabel(key, points)
        ax.set(xlabel=result["xlabel"][key], ylabel=f"{error_key} (8-bit levels)",
               title=f"error vs {'speed' if key in MAXIMIZE else 'cost'} ({len(points)} points)")
        ax.grid(alpha=0.3, which="both")
    handles = {}
    for ax in axes:  # one legend for both panels, below them, so it hides no point
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(label, handle)
    fig.legend(list(handles.values()), list(handles), loc="lower center", ncol=min(len(handles), 10), fontsize=9)
    skipped = f"; {result['skipped']} points without cost not drawn" if result["skipped"] else ""
    fig.suptitle(f"Sweep: {error_key} against hardware cost, {target_label(ok)}{skipped}")
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    atomic_write(str(path), lambda p: fig.savefig(p, dpi=100, format="png"))
    plt.close(fig)
    return result
