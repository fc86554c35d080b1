"""Amounts in words: a count with its noun in the right number ("1 level", "2 levels").

The error of a datapath is counted in 8-bit display levels everywhere a person reads it (the
command line, the pictures' titles, the manifest's notes), and is often exactly one.
"""

__all__ = ["plural", "levels"]


def plural(value, noun, fmt="g"):
    """``value`` formatted by ``fmt`` and ``noun``, with an ``s`` unless it reads "1":
    ``plural(1, "level") == "1 level"``, ``plural(1.5, "level") == "1.5 levels"``,
    ``plural(1, "level", ".3f") == "1.000 levels"``."""
    text = f"{value:{fmt}}"
    return f"{text} {noun}" if text == "1" else f"{text} {noun}s"


def levels(value, fmt="g"):
    """``value`` 8-bit display levels in words: ``levels(1) == "1 level"``."""
    return plural(value, "level", fmt)
