"""The tables ``phongfx tables NAME`` and the report know, by name, and those measured here.

Each table is a module with ``run_table(name, out_dir)``, ``markdown(result)`` and
``to_json(result)``; :func:`table_module` imports it on first use (so naming the tables
costs no synthesis import).  The paper tables live with their papers
(:mod:`phongfx.papers`); this room holds the measured ones:

* :mod:`.cost`: Lyon's Figure 8 against Figure 7 (and Blinn) in LUTs, DSPs and MHz;
* :mod:`.pipeline`: Fmax, size and latency against pipeline depth;
* :mod:`.proxy`: the tool-free area proxy against standard-cell synthesis, and its fit;
* :mod:`.clock`: the tool-free clock proxy against synthesis at every depth, and its fit;
* :mod:`.extremes`: every block at the extremes of its inputs, for stability.

Their functions share names (``run_table``, ``markdown``, ...), so they are reached
through their module, not re-exported here.
"""

from importlib import import_module

__all__ = ["TABLES", "table_module"]

#: table name -> module
TABLES = {
    "lyon": "phongfx.papers.lyon.tables",            # Lyon 1993: shape, normalizer, span claims
    "szirmay": "phongfx.papers.szirmay",             # Szirmay-Kalos et al. 2000: Table 1, Figure 11
    "schlick": "phongfx.papers.schlick",             # Schlick 1994: Figure 1
    "hast": "phongfx.papers.hast",                   # Hast, Barrera, Bengtsson: Tables 1-2 on tori
    "cost": "phongfx.explore.tables.cost",           # synthesis: Figure 7 vs Figure 8 vs blinn
    "proxy": "phongfx.explore.tables.proxy",         # the area proxy against standard-cell synthesis
    "pipeline": "phongfx.explore.tables.pipeline",   # synthesis: Fmax against pipeline depth
    "clock": "phongfx.explore.tables.clock",         # the clock proxy against synthesis, every depth
    "extremes": "phongfx.explore.tables.extremes",   # stability: every block at its extreme inputs
}


def table_module(name):
    """The module of table ``name``; ValueError naming the valid tables otherwise."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return import_module(TABLES[name])
