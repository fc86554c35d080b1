"""``phongfx tables extremes``: every block at the extremes of its inputs, for stability.

A cheap fixed-point datapath must stay stable where its inputs are extreme (exact ±1.0,
zero-length vectors, grazing light, the largest and smallest shininess, end codes): one
row per (block, extreme input class), each block's rows coming from its stimulus module
(``get_block(name).extremes()``, :class:`phongfx.sim.stimulus.extreme.Extreme`).  Per row

* the raw inputs, built from the block's config (:attr:`~phongfx.sim.stimulus.extreme.Extreme.build`);
* the golden outputs against the documented behaviour (``expected``, checked by ``holds``
  from exact constants and closed forms, not from the model);
* golden = RTL: :func:`phongfx.sim.harness.check`, cycle by cycle, one run per block
  with every row's vectors back to back (stateful blocks: every row starts with
  ``init``), mismatches attributed to rows by vector index.
"""

import json
import time

import numpy as np

from phongfx.core.registry import REGISTRY, block_names, get_block
from phongfx.sim.stimulus import concat

__all__ = ["TABLES", "all_rows", "rows_for", "run_block", "run_table", "markdown", "to_json"]

#: Tables this module knows.
TABLES = ("extremes",)


def all_rows():
    """Every row of the table, in order: each registered block's rows, in registry order."""
    return tuple(row for block in block_names() for row in rows_for(block))


def rows_for(block):
    """The :class:`~phongfx.sim.stimulus.extreme.Extreme` rows of ``block`` (none for a name
    the registry does not have)."""
    return tuple(get_block(block).extremes()) if block in REGISTRY else ()


def run_block(block_name, backend="amaranth", **options):
    """Rows of one block: golden against ``expected`` per row, then one harness run of all
    rows' vectors back to back, mismatching cycles attributed to rows by vector index."""
    from phongfx.sim.harness import check
    block = get_block(block_name)
    extremes = block.extremes()
    inputs, results, start = [], [], 0
    for extreme in extremes:
        raw = {k: np.asarray(v, dtype=np.int64) for k, v in extreme.build(block.config).items()}
        count = len(next(iter(raw.values())))
        try:
            holds = np.asarray(extreme.holds(block.config, raw, block.golden(raw)), dtype=bool)
            golden = "pass" if holds.all() else f"FAIL ({int((~holds).sum())}/{count})"
        except Exception as error:  # a row's verdict, not the table's end: noted in the row
            golden = f"FAIL ({type(error).__name__}: {error})"
        results.append({"block": block_name, "class": extreme.name, "expected": extreme.expected,
                        "vectors": count, "golden": golden, "first": start})
        inputs.append(raw)
        start += count
    t0 = time.perf_counter()
    result = check(block, concat(*inputs), backend=backend, bubbles=0, max_report=start + 1, **options)
    seconds = time.perf_counter() - t0
    bad = np.array([m.index for m in result.mismatches if m.index >= 0], dtype=np.int64)
    stray = sum(m.index < 0 for m in result.mismatches)
    for row in results:
        first = row.pop("first")
        count = int(np.count_nonzero((bad >= first) & (bad < first + row["vectors"])))
        row["rtl"] = "pass" if not count and not stray else f"FAIL ({count + stray} cycles)"
        row["backend"] = backend
    return results, seconds


def run_table(name, out_dir=None, backend="amaranth"):
    """The table called ``name`` (one of :data:`TABLES`); nothing is written to ``out_dir``."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    rows, seconds = [], {}
    for block in block_names():  # every registered block has extreme rows
        block_rows, seconds[block] = run_block(block, backend)
        rows += block_rows
    return {"source": "stability: every block at the extreme classes of its inputs", "backend": backend,
            "rows": rows, "seconds": seconds}


def markdown(result):
    """One line per (block, class): expected behaviour, golden verdict, RTL verdict."""
    lines = [f"# Extremes: golden against the documented behaviour, RTL against golden "
             f"({result['backend']})", "",
             "| block | extreme class | vectors | expected | golden | RTL |", "|---|---|---|---|---|---|"]
    for r in result["rows"]:
        cells = (r["block"], r["class"], r["vectors"], r["expected"], r["golden"], r["rtl"])
        lines.append("| " + " | ".join(str(cell).replace("|", "\\|") for cell in cells) + " |")
    failed = sum(r["golden"] != "pass" or r["rtl"] != "pass" for r in result["rows"])
    lines += ["", f"{len(result['rows'])} rows over {len(result['seconds'])} blocks; "
                  f"{failed} failing.", ""]
    return "\n".join(lines)


def to_json(result):
    # the run times differ between runs; the table itself is deterministic
    stable = {k: v for k, v in result.items() if k != "seconds"}
    return json.dumps(stable, indent=2, ensure_ascii=False)
