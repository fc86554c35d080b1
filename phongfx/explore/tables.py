"""The paper and cost tables ``phongfx tables NAME`` and the report know, by name.

Each is a module with ``run_table(name, out_dir)``, ``markdown(result)`` and
``to_json(result)``; :func:`table_module` imports it on first use.
"""

from importlib import import_module

__all__ = ["TABLES", "table_module"]

#: table name -> module
TABLES = {
    "lyon": "phongfx.papers.lyon.tables",            # Lyon 1993: shape, normalizer, span claims
    "szirmay": "phongfx.papers.szirmay",             # Szirmay-Kalos et al. 2000: Table 1, Figure 11
    "schlick": "phongfx.papers.schlick",             # Schlick 1994: Figure 1
    "hast": "phongfx.papers.hast",                   # Hast, Barrera, Bengtsson: Tables 1-2 on tori
    "cost": "phongfx.explore.cost_table",            # synthesis: Figure 7 vs Figure 8 vs blinn
    "proxy": "phongfx.explore.proxy_table",          # the area proxy against standard-cell synthesis
    "pipeline": "phongfx.explore.pipeline_table",    # synthesis: Fmax against pipeline depth
    "extremes": "phongfx.explore.extremes",          # stability: every block at its extreme inputs
}


def table_module(name):
    """The module of table ``name``; ValueError naming the valid tables otherwise."""
    if name not in TABLES:
        raise ValueError(f"unknown table {name!r}; valid tables: {', '.join(TABLES)}")
    return import_module(TABLES[name])
