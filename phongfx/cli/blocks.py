"""``phongfx blocks``: the registered blocks, one short entry each, wrapped to the terminal.

A datapath's config nests every unit's config (fig7's repr is 1,300 characters, the shader's
1,600), so the list gives each block's own fields and names a nested config by its class;
``--long`` lists every field by the dotted name ``--set`` takes (``normalize.vec=S1.10``),
``--json`` the whole configs as data.
"""

import dataclasses
import json
import shutil
import sys
import textwrap

from phongfx.core.registry import block_names, get_block

__all__ = ["MAX_WIDTH", "summary", "fields", "cmd_blocks"]

#: The widest line printed, whatever the terminal's width.
MAX_WIDTH = 100
_NAME = 16  # the name column
_SHORT = 24  # a value longer than this (a blend's colour table) is cut in the summary


def _short(value):
    if dataclasses.is_dataclass(value):
        return f"{type(value).__name__}(…)"
    if isinstance(value, tuple) and value and all(dataclasses.is_dataclass(v) for v in value):
        return f"({len(value)} × {type(value[0]).__name__})"
    text = str(value).replace(", ", ",")  # one word: a line breaks between fields only
    return text if len(text) <= _SHORT else text[:_SHORT - 1] + "…"


def summary(config):
    """``field=value`` of ``config``'s fields, a nested config by its class name only."""
    return " ".join(f"{f.name}={_short(getattr(config, f.name))}" for f in dataclasses.fields(config))


def fields(config, prefix=""):
    """``[(dotted name, value)]`` of every leaf field of ``config``, nested configs walked (a
    tuple of configs by index)."""
    rows = []
    for f in dataclasses.fields(config):
        value, name = getattr(config, f.name), f"{prefix}{f.name}"
        if dataclasses.is_dataclass(value):
            rows += fields(value, f"{name}.")
        elif isinstance(value, tuple) and value and all(dataclasses.is_dataclass(v) for v in value):
            for index, item in enumerate(value):
                rows += fields(item, f"{name}.{index}.")
        else:
            rows.append((name, value))
    return rows


def _width():
    # A pipe or a file gets the full width whatever COLUMNS says (a test runner or CI sets
    # it), so the text a page shows is the text a script reads; a terminal gets its own.
    if not sys.stdout.isatty():
        return MAX_WIDTH
    return max(60, min(MAX_WIDTH, shutil.get_terminal_size((MAX_WIDTH, 24)).columns))


def cmd_blocks(args):
    blocks = [get_block(name) for name in block_names()]
    if args.json:
        print(json.dumps([{"name": b.name, "latency": b.latency, "config_class": type(b.config).__name__,
                           "config": dataclasses.asdict(b.config)} for b in blocks], indent=1))
        return 0
    width = _width()
    for block in blocks:
        head = f"{block.name:{_NAME}s} latency {block.latency:3d}  "
        if args.long:
            print(f"{head}{type(block.config).__name__}")
            for name, value in fields(block.config):
                print(textwrap.fill(f"{name}={value}", width, initial_indent="    ", subsequent_indent="      "))
        else:
            print(textwrap.fill(summary(block.config), width, initial_indent=head,
                                subsequent_indent=" " * len(head), break_long_words=True))
    if not args.long:
        print("(--long: every field by its --set name; --json: the configs as data)")
    return 0
