"""``phongfx tables hast``: Hast, Barrera & Bengtsson Tables 1 and 2, measured on tori.

The paper renders tori of 288, 512, 800 and 1152 polygons in 200 frames "rotated in the
x, y and z directions", about 4 million pixels per torus, diffuse ``N·L`` only.  Its
radii and light are not given; ours: :func:`phongfx.scene.mesh.torus` radii 1 and 0.4 (quads
``2k × k``), light :data:`LIGHT` (eye space, viewer at infinity along ``+z``), frames
of :data:`SIZE`² pixels (about 20k rasterized pixels a frame, 4M over 200 frames).
Every front-facing rasterized pixel counts (the shader runs before the z test).

Per pixel, intensities are truncated 8-bit levels ``trunc(255·I)``, ``I`` clamped to
``0..1`` (:func:`phongfx.golden.adaptive.levels`); Phong is Duff's exact ``p/√q``
(Hast equation 4) from the span's unit end normals.

* Table 2 — mean and max ``|level - level_Phong|`` for Gouraud (the span chord from
  ``p_a`` to ``p_b``, exact at the edges: what the adaptive scheme would run), Euler
  (uncorrected, ``s_0 = di_a``), corrected Euler (``t_0``); extra columns: classic
  Gouraud (vertex intensities interpolated over the triangle, screen barycentrics)
  and the fixed-point corrected Euler unit (:func:`phongfx.golden.euler.euler` at the
  default :class:`~phongfx.config.EulerConfig`, its ``p`` register then ``trunc(255·p)``).
* Table 1 — % of spans where the truncated chord equals truncated Phong at every pixel
  (the paper's §5 count) and where it equals truncated corrected Euler (its caption);
  beside them the rate at which Hast's test (equations 23–24) picks Gouraud, and its
  false positives / negatives against the corrected-Euler truth.
* Hammersley's highlight test rate over rasterized triangles, threshold
  ``(1/255)^(1/n)`` (the specular term reaches one level) for :data:`SHININESS`, beside
  the exact rate; and specular ``(N·H)^n`` through corrected Euler against Duff's for
  ``n`` in :data:`SHININESS` (:func:`phongfx.golden.adaptive.specular_euler`).

The paper's light is unknown and matters: the deviations scale with it (with the light
at the viewer, 288 polygons give Gouraud 0.91 / 9 and Table 1 51%; ours, 0.58 / 10 and
62%).  Our means come out a third to a half of the paper's, with the same trends and
maxima close to its; Hast's test passes 14–20% of spans whose truncated levels differ
(it bounds the float difference by a level, not the truncated one).

Deterministic: no randomness.
"""

import json
import os

import numpy as np

from phongfx.config import EulerConfig
from phongfx.golden.adaptive import adaptive_test, highlight_test, levels, specular_euler
from phongfx.golden.euler import euler
from phongfx.golden.euler_setup import curves_at, span_setups
from phongfx.golden.fixed import Fixed
from phongfx.scene.mesh import project, rasterize, rotation, torus

__all__ = ["TABLES", "POLYGONS", "PAPER_TABLE1", "PAPER_TABLE2", "LIGHT", "SIZE", "SHININESS",
           "measure", "hast", "run_table", "markdown", "to_json"]

TABLES = ("hast",)
POLYGONS = (288, 512, 800, 1152)
#: Table 1 of the paper: polygons -> % of scan lines Gouraud would have done.
PAPER_TABLE1 = {288: 54.9, 512: 69.3, 800: 80.9, 1152: 89.0}
#: Table 2 of the paper: polygons -> method -> (mean, max) deviation in 8-bit levels.
PAPER_TABLE2 = {288: {"gouraud": (1.08, 15), "euler": (0.75, 21), "corrected": (0.081, 3)},
                512: {"gouraud": (0.60, 9), "euler": (0.42, 10), "corrected": (0.033, 1)},
                800: {"gouraud": (0.38, 6), "euler": (0.28, 6), "corrected": (0.016, 1)},
                1152: {"gouraud": (0.26, 4), "euler": (0.21, 5), "corrected": (0.009, 1)}}
LIGHT = tuple(np.array([1.0, 1.0, 1.0]) / np.sqrt(3))
SIZE = 210
SHININESS = (1, 10, 50)
METHODS = ("gouraud", "euler", "corrected", "vertex", "fixed")
NAMES = {"gouraud": "Gouraud (span chord)", "euler": "Euler", "corrected": "corr. Euler",
         "vertex": "Gouraud (vertex)", "fixed": "fixed corr. Euler"}


def _vertex_gouraud(mesh, rot, spans, light):
    """Classic Gouraud: vertex ``N·L`` interpolated with screen barycentrics."""
    _, normals, screen = project(mesh, rot, spans.width, spans.height)
    tri = mesh.faces[spans.face[spans.pixel_span()]]
    xy = spans.pixel_xy() + 0.5
    v0, v1, v2 = (screen[tri[:, i], :2] for i in range(3))
    e1, e2, r = v1 - v0, v2 - v0, xy - v0
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]
    b1 = (r[:, 0] * e2[:, 1] - r[:, 1] * e2[:, 0]) / det
    b2 = (e1[:, 0] * r[:, 1] - e1[:, 1] * r[:, 0]) / det
    shade = normals @ np.asarray(light)
    return (1 - b1 - b2) * shade[tri[:, 0]] + b1 * shade[tri[:, 1]] + b2 * shade[tri[:, 2]]


def _fixed_corrected(setups, span, step, config):
    init = step == 0
    loads = [Fixed.from_float(np.where(init, setups[key][span], 0.0), config.fmt(fmt))
             for key, fmt in (("p_a", "p"), ("t0", "t"), ("ds", "ds"))]
    return euler(config, Fixed(init.astype(np.int64), "1.0"), *loads)["p"].to_float()


def _new_totals():
    return {"pixels": 0, "spans": 0, "triangles": 0,
            **{f"{m}_{s}": 0 for m in METHODS for s in ("sum", "max")},
            **{k: 0 for k in ("phong_equal", "euler_equal", "adaptive", "fp", "fn")},
            **{f"{k}_{n}": 0 for n in SHININESS
               for k in ("hl", "hl_vertex", "hl_exact", "spec_sum", "spec_max")}}


def _frame(mesh, rot, light, halfway, size, config, totals):
    spans = rasterize(mesh, rot, size, size)
    span, step = spans.pixel_span(), spans.pixel_step()
    setups = span_setups(spans.na, spans.nb, light, spans.length)
    curves = curves_at(setups, span, step)
    curves["vertex"] = _vertex_gouraud(mesh, rot, spans, light)
    if config is not None:
        curves["fixed"] = _fixed_corrected(setups, span, step, config)
    phong = levels(curves["phong"])
    for method in METHODS:
        if method in curves:
            dev = np.abs(levels(curves[method]) - phong)
            totals[f"{method}_sum"] += int(dev.sum())
            totals[f"{method}_max"] = max(totals[f"{method}_max"], int(dev.max(initial=0)))
    count = len(spans.length)

    def whole_span(equal):  # equal at every pixel of the span
        return np.bincount(span, weights=~equal, minlength=count) == 0

    chord = levels(curves["gouraud"])
    truth = whole_span(chord == levels(curves["corrected"]))
    decision = adaptive_test(setups)["gouraud"]
    totals["phong_equal"] += int(whole_span(chord == phong).sum())
    totals["euler_equal"] += int(truth.sum())
    totals["adaptive"] += int(decision.sum())
    totals["fp"] += int((decision & ~truth).sum())
    totals["fn"] += int((~decision & truth).sum())
    faces = np.unique(spans.face)
    vertex_normals = (mesh.normals @ rot.T)[mesh.faces[faces]]
    setups_h = span_setups(spans.na, spans.nb, halfway, spans.length)
    for n in SHININESS:
        test = highlight_test(vertex_normals, halfway, (1 / 255) ** (1 / n))
        totals[f"hl_{n}"] += int(test["highlight"].sum())
        totals[f"hl_exact_{n}"] += int(test["exact"].sum())
        totals[f"hl_vertex_{n}"] += int(test["vertex"].sum())
        ours, exact = specular_euler(setups_h, span, step, n)
        dev = np.abs(levels(ours) - levels(exact))
        totals[f"spec_sum_{n}"] += int(dev.sum())
        totals[f"spec_max_{n}"] = max(totals[f"spec_max_{n}"], int(dev.max(initial=0)))
    totals["pixels"] += len(span)
    totals["spans"] += count
    totals["triangles"] += len(faces)


def _unit_light(light):
    light = np.asarray(light, dtype=np.float64)
    if light.shape != (3,) or not np.isclose(np.linalg.norm(light), 1.0):
        raise ValueError(f"light must be a unit 3-vector, not {light.tolist()}")
    return light


def measure(polygons, frames=200, size=SIZE, light=LIGHT, fixed=True):
    """Row of the tables for one torus of ``polygons`` over ``frames`` frames."""
    if isinstance(frames, bool) or not isinstance(frames, int) or frames < 1:
        raise ValueError(f"frames must be a positive integer, not {frames!r}")
    light = _unit_light(light)
    halfway = light + [0.0, 0.0, 1.0]
    halfway /= np.linalg.norm(halfway)
    mesh, totals = torus(polygons), _new_totals()
    config = EulerConfig() if fixed else None
    for frame in range(frames):
        _frame(mesh, rotation(frame, frames), light, halfway, size, config, totals)
    pixels, spans = totals["pixels"], totals["spans"]
    row = {"polygons": polygons, "frames": frames, "pixels": pixels, "spans": spans}
    for method in METHODS:
        if fixed or method != "fixed":
            row[method] = {"mean": totals[f"{method}_sum"] / pixels, "max": totals[f"{method}_max"]}
    row["table1"] = {key: 100 * totals[key] / spans
                     for key in ("phong_equal", "euler_equal", "adaptive", "fp", "fn")}
    row["highlight"] = {str(n): {"test": 100 * totals[f"hl_{n}"] / totals["triangles"],
                                 "vertex": 100 * totals[f"hl_vertex_{n}"] / totals["triangles"],
                            "exact": 100 * totals[f"hl_exact_{n}"] / totals["triangles"]} for n in SHININESS}
    row["specular"] = {str(n): {"mean": totals[f"spec_sum_{n}"] / pixels, "max": totals[f"spec_max_{n}"]}
                       for n in SHININESS}
    return row


def hast(frames=200, size=SIZE, polygons=POLYGONS, light=LIGHT, fixed=True):
    """Rows of :func:`measure` for each torus, with the settings."""
    light = _unit_light(light)
    return {"source": "Hast, Barrera & Bengtsson, Approximated Phong shading by using the Euler method",
            "light": light.tolist(), "radii": [1.0, 0.4], "size": size, "frames": frames,
            "rows": [measure(p, frames, size, light, fixed) for p in polygons]}


def run_table(name, out_dir=None, frames=200, size=SIZE, light=LIGHT, fixed=True):
    """The table called ``name`` (one of :data:`TABLES`); writes ``hast.png`` (deviation
    against polygon count, ours and the paper's) into ``out_dir`` if given."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    result = hast(frames, size, light=light, fixed=fixed)
    if out_dir is not None:
        _plot(os.path.join(out_dir, "hast.png"), result)
    return result


def markdown(result):
    """Table 2 and Table 1 beside the paper's numbers, then the extra measurements."""
    rows = result["rows"]
    extra = [m for m in ("vertex", "fixed") if m in rows[0]]
    lines = [f"# Tables 1 and 2, measured ({result['source']})", "",
             f"Tori (radii {result['radii'][0]:g}, {result['radii'][1]:g}), {result['frames']} frames of "
             f"{result['size']}², light ({', '.join(f'{v:.3f}' for v in result['light'])}), diffuse N·L; "
             "levels trunc(255·I).", "",
             "## Table 2: mean / max deviation from Phong in 8-bit levels (paper | ours)", "",
             "| polygons | pixels | "
             + " | ".join(f"{NAMES[m]} paper | ours" for m in ("gouraud", "euler", "corrected"))
             + "".join(f" | {NAMES[m]}" for m in extra) + " |",
             "|---" * (2 + 6 + len(extra)) + "|"]
    for r in rows:
        paper = PAPER_TABLE2.get(r["polygons"], {})
        cells = []
        for m in ("gouraud", "euler", "corrected"):
            p = paper.get(m)
            places = 3 if m == "corrected" else 2  # as printed in the paper
            cells += [f"{p[0]:.{places}f} / {p[1]}" if p else "–", f"{r[m]['mean']:.3f} / {r[m]['max']}"]
        cells += [f"{r[m]['mean']:.3f} / {r[m]['max']}" for m in extra]
        lines.append(f"| {r['polygons']} | {r['pixels']} | " + " | ".join(cells) + " |")
    lines += ["", "## Table 1: % of spans Gouraud would have done", "",
              "| polygons | spans | paper | chord = Phong | chord = corr. Euler | test (eq. 23–24) | "
              "false pos. | false neg. |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        t = r["table1"]
        paper = PAPER_TABLE1.get(r["polygons"])
        lines.append(f"| {r['polygons']} | {r['spans']} | {paper if paper else '–'} | "
                     f"{t['phong_equal']:.1f} | {t['euler_equal']:.1f} | {t['adaptive']:.1f} | "
                     f"{t['fp']:.1f} | {t['fn']:.1f} |")
    shin = list(rows[0]["specular"])
    lines += ["", "## Highlights: Hammersley's test (% rasterized triangles; vertex condition alone, "
                  "exact in brackets) and specular (N·H)^n through corrected Euler vs Duff "
                  "(mean / max levels)", "",
              "| polygons | " + " | ".join(f"test n={n}" for n in shin) + " | "
              + " | ".join(f"spec n={n}" for n in shin) + " |", "|---" * (1 + 2 * len(shin)) + "|"]
    for r in rows:
        hl = [f"{h['test']:.1f} ({h['vertex']:.1f}, {h['exact']:.1f})"
              for h in (r["highlight"][n] for n in shin)]
        sp = [f"{r['specular'][n]['mean']:.4f} / {r['specular'][n]['max']}" for n in shin]
        lines.append(f"| {r['polygons']} | " + " | ".join(hl + sp) + " |")
    return "\n".join(lines) + "\n"


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)


def _plot(path, result):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from phongfx.core.files import atomic_write

    rows = result["rows"]
    x = [r["polygons"] for r in rows]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for m, colour in zip(("gouraud", "euler", "corrected"), ("C0", "C1", "C2")):
        axes[0].plot(x, [r[m]["mean"] for r in rows], "o-", color=colour, label=f"{NAMES[m]} ours")
        axes[1].plot(x, [r[m]["max"] for r in rows], "o-", color=colour, label=f"{NAMES[m]} ours")
        paper = [PAPER_TABLE2[p][m] for p in x if p in PAPER_TABLE2]
        if len(paper) == len(x):
            axes[0].plot(x, [p[0] for p in paper], "s--", color=colour, label=f"{NAMES[m]} paper")
            axes[1].plot(x, [p[1] for p in paper], "s--", color=colour, label=f"{NAMES[m]} paper")
    axes[2].plot(x, [r["table1"]["phong_equal"] for r in rows], "o-", label="chord = Phong")
    axes[2].plot(x, [r["table1"]["adaptive"] for r in rows], "o-", label="test eq. 23–24")
    axes[2].plot(x, [PAPER_TABLE1.get(p, np.nan) for p in x], "s--", label="paper")
    for ax, title in zip(axes, ("Table 2: mean deviation (levels)", "Table 2: max deviation",
                                "Table 1: % spans Gouraud")):
        ax.set_title(title)
        ax.set_xlabel("polygons")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_yscale("log")
    fig.tight_layout()
    atomic_write(path, lambda p: fig.savefig(p, dpi=100, format="png"))
    plt.close(fig)
