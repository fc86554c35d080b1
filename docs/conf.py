"""Sphinx configuration of the phongfx documentation (``make docs``: warnings are errors).

The API pages import the package (``phongfx``, ``phongfx.core``, ``phongfx.config``,
``phongfx.explore.compile``); importing them writes nothing.  A cross-reference that names
nothing in the code fails the build; one that names a real object outside the API pages
(a golden model, an HDL component) renders as code without a link (``_ext/phongfx_docs.py``).
"""

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
# phongfx itself comes from its install (``pip install -e '.[docs]'``, as make does): its
# golden/, hdl/ and sim/ folders are packages of phongfx only through that install.
sys.path.insert(0, str(HERE / "_ext"))

project = "phongfx"
author = "the phongfx authors"
copyright = "2026, the phongfx authors"

extensions = [
    "sphinx.ext.autodoc",
    "phongfx_docs",
]

root_doc = "index"
exclude_patterns = ["_build"]
nitpicky = True
# Names of other projects (no intersphinx: the build runs offline) and Python's own.
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|amaranth|argparse|pathlib|os|concurrent|tomllib|dataclasses)(\..*)?"),
    (r"py:.*", r"(int|float|str|bool|dict|list|tuple|set|bytes|object|None|callable|iterable|"
               r"Path|Fraction|Exception|ValueError|TypeError|KeyError|OSError|TextIO)"),
]

autodoc_member_order = "bysource"
autodoc_default_options = {"members": True, "show-inheritance": False}
autodoc_typehints = "none"

# Pictures the methods page shows, drawn by phongfx at build time: (file under _generated/,
# phongfx arguments with {out} for a temporary folder, the glob of the PNG to keep).
phongfx_pictures = [
    (f"{method}.png", ["render", "--out", "{out}", "mesh", "--method", method, "--size", "128",
                       "--n", "20"], "*-f0.png")
    for method in ("phong", "gouraud-float", "corrected-euler", "spherical", "blinn", "conventional")
] + [
    ("figure14.png", ["render", "--out", "{out}", "mesh", "--figure", "14"], "figure14.png"),
    ("figure15.png", ["render", "--out", "{out}", "mesh", "--figure", "15"], "figure15.png"),
    ("corrected-euler-error.png", ["render", "--out", "{out}", "mesh", "--method", "corrected-euler",
                                   "--polygons", "288", "--size", "128"], "*_error.png"),
    ("schlick-figure1.png", ["tables", "schlick", "--out", "{out}"], "figure1.png"),
    ("lyon-span-error.png", ["tables", "lyon", "--out", "{out}"], "span_error.png"),
]

html_theme = "furo"
html_title = "phongfx"
html_static_path = ["_static"]
