"""Wrapped ``//`` comments that no tool can read as one of its pragmas.

Verilog tools take some line comments as directives: Verilator any ``//`` comment whose
text begins ``verilator`` or ``Verilator`` (``// Verilator (--binary) ...`` is
``%Error-BADVLTPRAGMA``, ``// verilator lint_off ...`` switches a warning off), synthesis
tools ``// synopsys ...``, ``// synthesis ...``, ``// pragma ...``, ``// translate_off``
and their kin.  A comment wrapped to a width puts whatever word falls at a break at the
start of a line, so a header naming the simulators, or a module whose name begins with
such a word, can turn into a directive for some module-name lengths and not others.

:func:`wrap` never starts a line with such a word (:data:`PRAGMA_WORDS`, any case, also
as the start of a longer word such as ``verilator_top``): it breaks the line one word
earlier, so the word stays with the one before it, and a text that itself begins with
one gets it in backquotes (`` `verilator_top`: ...``).  :func:`comment` gives the
lines as ``// `` comments.
"""

import re

__all__ = ["PRAGMA_WORDS", "starts_pragma", "wrap", "comment"]

#: Words a tool reads as a directive at the start of a ``//`` comment (compared in any case,
#: as prefixes): Verilator's own, and those of synthesis and lint tools (Synopsys, Cadence
#: and Ambit, Altera, Xilinx, SpyGlass, the IEEE 1364.1 ``synthesis`` and ``pragma``).
PRAGMA_WORDS = ("verilator", "synopsys", "synthesis", "pragma", "translate_off", "translate_on", "lint_off",
                "lint_on", "cadence", "ambit", "rtl_synthesis", "altera", "xilinx", "spyglass", "coverage")

_PRAGMA = re.compile(r"\s*(?:" + "|".join(PRAGMA_WORDS) + ")", re.I)
_LEADING_NAME = re.compile(r"\w+")


def starts_pragma(text):
    """Whether a ``//`` comment whose text (after the ``//``) is ``text`` begins with one of
    :data:`PRAGMA_WORDS`, in any case and whatever follows it."""
    return _PRAGMA.match(text) is not None


def wrap(text, width=96, indent="  "):
    """``text`` as lines of at most ``width`` characters (the later ones after ``indent``),
    none beginning with one of :data:`PRAGMA_WORDS`.

    Words are split on white space.  A break that would put such a word first moves one
    word earlier (onto a word that is not one); a line may exceed ``width`` only where a
    single word does, or where no earlier break exists.  If ``text`` itself begins with
    such a word, its leading name is put in backquotes.
    """
    words = text.split()
    if not words:
        return [""]
    if starts_pragma(words[0]):
        words[0] = _LEADING_NAME.sub(lambda match: f"`{match.group()}`", words[0], count=1)
    lines, line = [], [words[0]]
    for word in words[1:]:
        if len(" ".join(line)) + 1 + len(word) <= width - (len(indent) if lines else 0):
            line.append(word)
            continue
        # break before the last word of the line from which the new line may start
        cut = len(line)
        if starts_pragma(word):
            cut = next((k for k in range(len(line) - 1, 0, -1) if not starts_pragma(line[k])), None)
        if cut is None:
            line.append(word)  # nowhere to break: the line runs long
            continue
        lines.append(line[:cut])
        line = line[cut:] + [word]
    lines.append(line)
    out = [(indent if k else "") + " ".join(words) for k, words in enumerate(lines)]
    assert not any(starts_pragma(line) for line in out), out
    return out


def comment(text, width=94, indent=""):
    """``text`` as ``// `` comment lines (:func:`wrap` ``(text, width, indent)``, each line
    after ``// ``), newline-terminated: the text of no line reads as a tool's pragma."""
    return "".join(f"// {line}".rstrip() + "\n" for line in wrap(text, width, indent))
