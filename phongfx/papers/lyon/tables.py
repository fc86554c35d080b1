"""``phongfx tables lyon``: Lyon's numeric claims (Apple TR #43, 1993), measured.

Every number the report's prose states about its shape functions, its length-error
sensitivity and its approximate normalizers is measured twice: in float (the formulas
themselves) and in fixed point (the golden models of the default Figure 7 formats,
through :func:`phongfx.core.registry.get_block`).  Each claim is printed as
``paper | measured float | measured fixed-point`` with the tolerance it is judged by
and a verdict; a claim that does not hold as measured says so.

Sections (their ids key the JSON and name the plots):

* ``figure3`` — shape functions f0, f1, f2 against cos^n α for n = 100 ("Phong
  Specularity Reformulation", Figure 3), with the low-n zero crossings of the text.
* ``figure4`` — vector length after g1 / g2 against input length 0.6…1.0
  ("Approximate Normalization", Figure 4) and the numbers of the text.
* ``sensitivity`` — the length error ε that costs 5 % at the specular peak for
  n = 1000, ``(R·L)^n`` against ``f_k`` ("Length Error Sensitivity").
* ``spans`` — peak specular error of the whole Figure 7 datapath against the span
  angle θ, g1 against g2, n = 10, 100, 1000, and the text's "factor of two".

Everything is deterministic (:data:`SEED`); plots are written atomically.
"""

import os

from phongfx.papers.claims import cell, escape, to_json

from .common import LEVELS, SEED, K
from .normalize import SPAN_ANGLES, SPAN_N, figure4, spans
from .shape import figure3, sensitivity

__all__ = ["TABLES", "SEED", "PLOTS", "lyon", "markdown", "to_json", "run_table"]

#: Tables ``phongfx tables`` knows.
TABLES = ("lyon",)

#: Plot file of each section, under the output folder.
PLOTS = {
    "figure3": "fig3_shapes.png",
    "figure4": "fig4_normalization.png",
    "sensitivity": "length_sensitivity.png",
    "spans": "span_error.png",
}


def write_plots(out_dir, plots):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from phongfx.core.files import atomic_write

    def save(fig, name):
        path = os.path.join(out_dir, name)
        atomic_write(path, lambda p: fig.savefig(p, dpi=100, format="png"))
        plt.close(fig)
        return path

    written = []
    p = plots["figure3"]
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.plot(p["alpha"], p["cosn"], "k-", lw=2, label=f"cos^n α (n = {p['n']})")
    for k, colour in zip(K, ("tab:red", "tab:green", "tab:blue")):
        ax.plot(p["alpha"], p["float"][k], "-", color=colour, label=f"f{k} float")
        ax.plot(p["alpha_fixed"], p["fixed"][k], ".", color=colour, ms=4, label=f"f{k} fixed point")
    ax.set(xlabel="α (radians)", ylabel="specular amount",
           title="Lyon Figure 3: shape functions vs cos^n α, n = 100")
    ax.grid(alpha=0.3)
    ax.legend()
    written.append(save(fig, PLOTS["figure3"]))

    p = plots["figure4"]
    fig, ax = plt.subplots(figsize=(8, 5))
    for o, colour in ((1, "tab:red"), (2, "tab:blue")):
        ax.plot(p["fine"], p["float"][o], "-", color=colour, label=f"g{o} float")
        ax.plot(p["s"], p["fixed"][o]["mean"], ".", color=colour, ms=3, label=f"g{o} fixed mean")
        ax.fill_between(p["s"], p["fixed"][o]["min"], p["fixed"][o]["max"], color=colour, alpha=0.2,
                        label=f"g{o} fixed min…max")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.axhspan(0.995, 1.005, color="grey", alpha=0.15, label="±0.5 %")
    ax.set(xlabel="input length |N'|", ylabel="length after normalization",
           title="Lyon Figure 4: approximate normalization")
    ax.grid(alpha=0.3)
    ax.legend()
    written.append(save(fig, PLOTS["figure4"]))

    p = plots["sensitivity"]
    fig, ax = plt.subplots(figsize=(8, 5))
    ax.loglog(p["eps"], p["phong"], "k-", lw=2, label="(R·L)^n = (1−ε)^n")
    for k in K:
        ax.loglog(p["eps"], p["shape"][k], "-", label=f"f{k}, x = (n/2)ε²")
    keep = p["fixed"] > 0
    ax.loglog(p["grid"][keep][::20], p["fixed"][keep][::20], ".", ms=2, label="f2 fixed point")
    ax.axhline(0.05, color="grey", ls="--", label="5 %")
    for e in (5e-5, 0.01):
        ax.axvline(e, color="grey", ls=":")
    ax.set(xlabel="length error ε", ylabel="peak error 1 − value", ylim=(1e-6, 1.5),
           title="Length error sensitivity, n = 1000 (dotted: the paper's 0.00005 and 0.01)")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    written.append(save(fig, PLOTS["sensitivity"]))

    p = plots["spans"]
    fig, axes = plt.subplots(1, len(SPAN_N), figsize=(15, 4.5), sharex=True)
    for ax, n in zip(axes, SPAN_N):
        for o, colour in ((1, "tab:red"), (2, "tab:blue")):
            ax.plot(SPAN_ANGLES, [p["errors"][(t, n, o)]["fixed"] for t in SPAN_ANGLES], "o-",
                    color=colour, label=f"g{o} fixed point")
            ax.plot(SPAN_ANGLES, [p["errors"][(t, n, o)]["float"] for t in SPAN_ANGLES], ":",
                    color=colour, label=f"g{o} float LIRP + g{o}")
        ax.set(xlabel="span angle θ (degrees)", title=f"n = {n}")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("peak specular error (8-bit levels)")
    axes[0].legend()
    fig.suptitle("Figure 7 datapath vs float lyon-k2 with exact normals, max over the span")
    fig.tight_layout()
    written.append(save(fig, PLOTS["spans"]))
    return written


def lyon(out_dir="build/lyon", plots=True):
    """Measure every claim; write the plots under ``out_dir`` (if ``plots``); return the result."""
    sections, data = [], {}
    for build in (figure3, figure4, sensitivity, spans):
        section, plot = build()
        sections.append(section)
        data[section["id"]] = plot
    written = write_plots(out_dir, data) if plots else []
    failed = [f"{s['id']}: {r['claim']}" for s in sections for r in s["rows"]
              if r["holds_float"] is False or r["holds_fixed"] is False]
    return {"table": "lyon", "source": "R. F. Lyon, Phong Shading Reformulation for Hardware "
                                       "Renderer Simplification, Apple TR #43, 1993",
            "seed": SEED, "sections": sections, "not_holding": failed, "plots": written}


def run_table(name, out_dir="build/lyon", plots=True):
    """The table called ``name`` (one of :data:`TABLES`)."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return lyon(out_dir=out_dir, plots=plots)


def markdown(result):
    """The result as Markdown: one claims table per section, then its measured extras."""
    lines = [f"# Lyon's numeric claims, measured ({result['source']})", "",
             "Each claim: paper value | measured float | measured fixed point (default formats).", ""]
    for section in result["sections"]:
        lines += [f"## {section['title']}", "", section["setup"], "",
                  "| claim | paper | float | fixed point | criterion | verdict | note |",
                  "|---|---|---|---|---|---|---|"]
        for r in section["rows"]:
            paper = r["paper_text"] if r["paper_text"] is not None else cell(r["paper"], r["fmt"])
            verdict = r["verdict"] if r["verdict"] in ("holds", "measured only") else f"**{r['verdict']}**"
            lines.append("| " + " | ".join(escape(c) for c in (
                r["claim"], paper, cell(r["float"], r["fmt"]), cell(r["fixed"], r["fmt"]),
                r["criterion"] or "—", verdict, r["note"])) + " |")
        lines.append("")
        if section["id"] == "figure3":
            lines += ["Shape statistics over α ∈ 0…0.4 rad (absolute error = relative to the peak):", "",
                      "| shape | max \\|f − cos^n\\| (float) | at α | mean \\|f − cos^n\\| | "
                      "max \\|fixed − f\\| | max \\|fixed − cos^n\\| | half-height α float | fixed | "
                      "÷ cos^n's |", "|---|---|---|---|---|---|---|---|---|"]
            for s in section["stats"]:
                if s["shape"] == "cos^n":
                    lines.append(f"| cos^n | — | — | — | — | — | {s['half_alpha_deg_float']:.3f}° | — | 1 |")
                    continue
                lines.append(
                    f"| {s['shape']} | {s['max_abs_error_vs_cos_n']:.4f} ({s['max_abs_error_vs_cos_n'] * LEVELS:.1f} "
                    f"levels) | {s['at_alpha_deg']:.2f}° | {s['mean_abs_error_vs_cos_n']:.4f} | "
                    f"{s['fixed_max_abs_error_vs_float_fk']:.5f} | {s['fixed_max_abs_error_vs_cos_n']:.4f} | "
                    f"{s['half_alpha_deg_float']:.3f}° | {cell(s['half_alpha_deg_fixed'], '{:.3f}°')} | "
                    f"{s['half_ratio_to_cos_n']:.3f} |")
            lines.append("")
        if section["id"] == "spans":
            head = " | ".join(f"n={n} g{o}" for n in SPAN_N for o in (1, 2))
            lines += ["Peak specular error in 8-bit levels, fixed point (float LIRP + float g_k):", "",
                      f"| θ | {head} |", "|---" * (1 + 2 * len(SPAN_N)) + "|"]
            for row in section["table"]:
                if row["theta_deg"] % 10:
                    continue
                lines.append(f"| {row['theta_deg']}° | " + " | ".join(
                    f"{row[f'n{n}_g{o}_fixed']:.1f} ({row[f'n{n}_g{o}_float']:.1f})"
                    for n in SPAN_N for o in (1, 2)) + " |")
            lines.append("")
    if result["not_holding"]:
        lines += ["## Claims that do NOT hold as measured", ""]
        lines += [f"* {escape(c)}" for c in result["not_holding"]]
        lines.append("")
    if result["plots"]:
        lines += ["Plots: " + ", ".join(result["plots"]), ""]
    return "\n".join(lines)
