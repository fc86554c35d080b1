"""``phongfx tables szirmay``: Szirmay-Kalos et al. (2000) Table 1 and Figure 11, measured.

* ``table1`` — ``a(n)`` solving ``1/(n+1) = (2a²(1 - cos(π/2a)) - 1)/(4a² - 1)`` (§4) by
  :func:`phongfx.golden.spherical_setup.solve_a`, to four decimals beside the paper's
  Table 1 (:data:`PAPER_TABLE1`, transcribed from the paper), judged within ``1e-4``.
* ``figure11`` — the ``cos²`` ROM of :func:`phongfx.golden.spherical.rom_contents` against
  ``cos²θ`` (0 outside ``|θ| <= π/2``) for address bits 3…10 × data bits 3…10: max and
  mean absolute error over ``θ ∈ [-π/2, π/2)``, sampled at every code of a 16-bit
  angle register (:data:`SAMPLE_BITS`) as the hardware would address the ROM, beside
  the bound ``π/2^A + 2^-D`` of :mod:`phongfx.golden.spherical`.  The paper's figure is
  a plot; it claims 6 × 6 bits (384) suffice and 4 bits show halos (Figure 15).

Deterministic: no randomness.
"""

import json
import math

import numpy as np

from phongfx.core.format import Format
from phongfx.golden.spherical import rom_bound, rom_contents
from phongfx.golden.spherical_setup import solve_a

__all__ = ["TABLES", "PAPER_TABLE1", "BITS", "SAMPLE_BITS", "TOLERANCE", "table1", "figure11",
           "szirmay", "run_table", "markdown", "to_json"]

#: Tables this module knows.
TABLES = ("szirmay",)

#: Table 1 of the paper: n -> a, as printed (four decimals).
PAPER_TABLE1 = {2: 1.0000, 5: 1.4502, 10: 1.9845, 20: 2.7582, 50: 4.3143, 100: 6.0791, 500: 13.5535}

#: Tolerance of the Table 1 comparison: the paper prints four decimals.
TOLERANCE = 1e-4

#: Address and data bits of the Figure 11 grid.
BITS = tuple(range(3, 11))

#: Width of the angle register whose every code in ``[-π/2, π/2)`` samples the error.
SAMPLE_BITS = 16


def table1():
    """Rows ``{n, paper, measured, difference, holds}`` of Table 1."""
    rows = []
    for n, paper in PAPER_TABLE1.items():
        a = solve_a(n)
        rows.append({"n": n, "paper": paper, "measured": a, "difference": a - paper,
                     "holds": bool(abs(a - paper) <= TOLERANCE)})
    return rows


def _rom_error(addr_bits, data_bits):
    code = np.arange(-(1 << (SAMPLE_BITS - 2)), 1 << (SAMPLE_BITS - 2), dtype=np.int64)
    theta = code * math.pi / (1 << (SAMPLE_BITS - 1))
    address = (code >> (SAMPLE_BITS - addr_bits)) & ((1 << addr_bits) - 1)
    rom = Format(0, data_bits)
    word = rom_contents(addr_bits, rom, "cos2")[address] * rom.lsb
    error = np.abs(word - np.cos(theta) ** 2)
    return float(error.max()), float(error.mean()), rom_bound(addr_bits, rom)


def figure11():
    """Cells ``{addr_bits, data_bits, rom_bits, max, mean, bound}`` of the Figure 11 grid."""
    cells = []
    for addr_bits in BITS:
        for data_bits in BITS:
            worst, mean, bound = _rom_error(addr_bits, data_bits)
            cells.append({"addr_bits": addr_bits, "data_bits": data_bits,
                          "rom_bits": data_bits << addr_bits, "max": worst, "mean": mean, "bound": bound})
    return cells


def szirmay():
    return {"source": "Szirmay-Kalos et al. (2000), Phong shading hardware by spherical interpolation",
            "table1": table1(), "figure11": figure11()}


def run_table(name, out_dir=None):
    """The table called ``name`` (one of :data:`TABLES`); nothing is written to ``out_dir``."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return szirmay()


def markdown(result):
    """Table 1 beside the paper, then the Figure 11 grids of max and mean error."""
    lines = [f"# Table 1 and Figure 11, measured ({result['source']})", "",
             "## Table 1: a(n)", "",
             f"| n | paper | measured | difference | within {TOLERANCE:g} |", "|---|---|---|---|---|"]
    for r in result["table1"]:
        lines.append(f"| {r['n']} | {r['paper']:.4f} | {r['measured']:.4f} | {r['difference']:+.2e} | "
                     f"{'yes' if r['holds'] else '**no**'} |")
    cells = {(c["addr_bits"], c["data_bits"]): c for c in result["figure11"]}
    for key, title in (("max", "max"), ("mean", "mean")):
        lines += ["", f"## Figure 11: {title} |ROM − cos²θ| over θ ∈ [−π/2, π/2) "
                      f"(rows: address bits, columns: data bits)", "",
                  "| A \\ D | " + " | ".join(str(d) for d in BITS) + " |",
                  "|---" * (len(BITS) + 1) + "|"]
        for a in BITS:
            lines.append(f"| {a} | " + " | ".join(f"{cells[a, d][key]:.4f}" for d in BITS) + " |")
    paper = cells[6, 6]
    lines += ["", f"Paper's choice 6 × 6 = {paper['rom_bits']} bits: max {paper['max']:.4f}, "
                  f"mean {paper['mean']:.4f}; 4 × 4: max {cells[4, 4]['max']:.4f}, "
                  f"mean {cells[4, 4]['mean']:.4f}.  Bound π/2^A + 2^-D holds in every cell: "
                  f"{'yes' if all(c['max'] <= c['bound'] for c in result['figure11']) else 'NO'}.", ""]
    return "\n".join(lines)


def to_json(result):
    return json.dumps(result, indent=2, ensure_ascii=False)
