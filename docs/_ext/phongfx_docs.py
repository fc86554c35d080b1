"""Sphinx helpers of the phongfx pages.

* ``.. phongfx-help:: sim`` prints ``phongfx sim --help`` as the tool's own parser writes it,
  so a command page's option list cannot drift from the code (``.. phongfx-help::`` alone:
  the top-level help; ``render mesh`` for a nested subcommand).
* The pictures of the methods page are drawn by the tool itself when the docs are built
  (``phongfx_pictures`` in ``conf.py``: a file name under ``_generated/`` and the ``phongfx``
  arguments that draw it), so they always show what the code does now.
* A Python cross-reference that Sphinx cannot link is looked up in the code: if it names a
  real object (a golden model, an HDL component, a module outside the API pages), it renders
  as code without a link; if it names nothing, the nitpicky build reports it and fails.
"""

import argparse
import importlib
import shutil
import tempfile
from contextlib import redirect_stderr, redirect_stdout
from io import StringIO
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive

__all__ = ["setup", "subparser", "resolves", "draw_pictures"]


def subparser(words):
    """The :class:`argparse.ArgumentParser` of ``phongfx WORDS...`` (the tool's own parser)."""
    from phongfx.cli.parser import build_parser

    parser = build_parser()
    for word in words:
        actions = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        if not actions or word not in actions[0].choices:
            raise KeyError(f"phongfx has no subcommand {' '.join(words)!r}")
        parser = actions[0].choices[word]
    return parser


class HelpDirective(Directive):
    optional_arguments = 2
    has_content = False

    def run(self):
        parser = subparser(self.arguments)
        text = parser.format_help()
        block = nodes.literal_block(text, text)
        block["language"] = "text"
        return [block]


def resolves(target, module=None, klass=None):
    """Whether ``target`` (as written in a reference, maybe relative) names a real object."""
    target = target.lstrip("~.")
    candidates = [target]
    if module:
        if klass:
            candidates.append(f"{module}.{klass}.{target}")
        candidates.append(f"{module}.{target}")
        parent = module.rpartition(".")[0]
        while parent:
            candidates.append(f"{parent}.{target}")
            parent = parent.rpartition(".")[0]
    return any(_exists(name) for name in candidates)


def _exists(dotted):
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        try:
            for attr in parts[cut:]:
                obj = getattr(obj, attr)
        except AttributeError:
            # a dataclass field or an attribute set in __init__ is documented on its class
            return cut == len(parts) - 1 and _is_field(obj, parts[-1])
        return True
    return False


def _is_field(owner, name):
    fields = getattr(owner, "__dataclass_fields__", {})
    return name in fields or name in getattr(owner, "__annotations__", {})


def _missing_reference(app, env, node, contnode):
    if node.get("refdomain") != "py":
        return None
    if resolves(node["reftarget"], node.get("py:module"), node.get("py:class")):
        return contnode
    return None


def draw_pictures(pictures, folder):
    """Run ``phongfx ARGS --out TMP`` for each ``(name, args, pattern)`` and keep the PNG that
    matches ``pattern`` as ``folder/name``; a picture already there is kept (delete
    ``_generated/`` to redraw)."""
    from phongfx.cli import main

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    for name, args, pattern in pictures:
        if (folder / name).exists():
            continue
        with tempfile.TemporaryDirectory() as tmp:
            argv = [a.replace("{out}", tmp) for a in args]
            log = StringIO()
            with redirect_stdout(log), redirect_stderr(log):
                code = main(argv)
            found = sorted(Path(tmp).glob(pattern))
            if code != 0 or len(found) != 1:
                raise RuntimeError(f"phongfx {' '.join(argv)} gave exit {code} and {found}: {log.getvalue()}")
            shutil.copyfile(found[0], folder / name)


def _builder_inited(app):
    draw_pictures(app.config.phongfx_pictures, Path(app.srcdir) / "_generated")


def setup(app):
    app.add_config_value("phongfx_pictures", [], "env")
    app.connect("builder-inited", _builder_inited)
    app.add_directive("phongfx-help", HelpDirective)
    app.connect("missing-reference", _missing_reference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
