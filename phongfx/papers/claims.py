"""Claim rows of the paper tables: a paper value beside measured float and fixed-point values.

A row (:func:`row`) carries the claim, the paper's value, the measured values, the
criterion it is judged by and a verdict; :func:`cell`, :func:`escape` render it in
Markdown and :func:`to_json` writes a result with NaN and infinities as null.
"""

import json
import math

import numpy as np

__all__ = ["first", "within", "row", "verdict", "cell", "escape", "plain", "to_json"]


def first(grid, mask):
    """First grid value where ``mask`` holds, or None."""
    index = np.flatnonzero(mask)
    return float(grid[index[0]]) if index.size else None


def within(value, target, tol):
    return None if value is None else bool(abs(value - target) <= tol)


def row(claim, paper, flt, fixed, *, fmt="{:.4f}", paper_text=None, criterion="",
         holds_float=None, holds_fixed=None, note=""):
    # numpy booleans are not ``False``: make every verdict a plain bool (or None)
    holds_float, holds_fixed = (None if h is None else bool(h) for h in (holds_float, holds_fixed))
    return {"claim": claim, "paper": paper, "paper_text": paper_text, "float": flt, "fixed": fixed,
            "fmt": fmt, "criterion": criterion, "holds_float": holds_float,
            "holds_fixed": holds_fixed, "verdict": verdict(holds_float, holds_fixed), "note": note}


def verdict(hf, hx):
    if hf is None and hx is None:
        return "measured only"
    if hf is not False and hx is not False:
        return "holds"
    if hf is False and hx is False:
        return "does NOT hold"
    if hf is False:
        return "does NOT hold in float" + ("; holds in fixed point" if hx else "")
    return ("holds in float; " if hf else "") + "does NOT hold in fixed point"


def cell(value, fmt):
    if value is None:
        return "—"
    if isinstance(value, str):
        return value
    return fmt.format(value)


def escape(text):
    return str(text).replace("|", "\\|")


def plain(value):
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, (np.floating, float)):
        return None if not math.isfinite(value) else float(value)
    if isinstance(value, (np.integer,)):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def to_json(result):
    """The result as JSON (NaN and infinities as null)."""
    return json.dumps(plain(result), indent=2, ensure_ascii=False)
