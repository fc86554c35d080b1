"""The code blocks of the documentation pages (``docs/**/*.rst``), as the page tests read them.

A ``.. code-block:: console`` block holds command lines (``$ `` prompts) and the output
each must print; its ``:class:`` option says ``long`` (not run: parsed only) and the tools
it needs (``needs-iverilog`` ...).  A ``.. code-block:: toml`` with a ``:caption:`` is a file
the page's commands read.  ``docs/testing.rst`` states the convention for page writers.
"""

import re
from dataclasses import dataclass
from pathlib import Path

__all__ = ["DOCS", "Block", "Command", "blocks", "pages", "matches"]

DOCS = Path(__file__).resolve().parents[2] / "docs"

_DIRECTIVE = re.compile(r"^(?P<indent> *)\.\. (?:code-block|code|sourcecode):: *(?P<lang>\S*) *$")
_OPTION = re.compile(r"^ +:(?P<name>[a-z-]+):(?P<value>.*)$")


@dataclass(frozen=True)
class Command:
    line: str
    expected: tuple


@dataclass(frozen=True)
class Block:
    page: str
    lineno: int
    language: str
    classes: tuple
    caption: str
    text: str

    @property
    def long(self):
        return "long" in self.classes

    @property
    def needs(self):
        """The tools the block needs: ``needs-iverilog`` -> ``"iverilog"``."""
        return tuple(c.removeprefix("needs-") for c in self.classes if c.startswith("needs-"))

    def commands(self):
        """The block's command lines (a trailing backslash continues one) and their output."""
        out = []
        lines = self.text.splitlines()
        i = 0
        while i < len(lines):
            line = lines[i]
            i += 1
            if not line.startswith("$ "):
                if out:
                    out[-1][1].append(line)
                continue
            command = line[2:]
            while command.endswith("\\") and i < len(lines):
                command = command[:-1] + " " + lines[i].strip()
                i += 1
            out.append((command.strip(), []))
        return [Command(c, tuple(e for e in exp if e.strip() and e.strip() != "...")) for c, exp in out]


def pages():
    """Every page, as its path relative to ``docs/`` (``commands/sim.rst``)."""
    return sorted(str(p.relative_to(DOCS)) for p in DOCS.rglob("*.rst") if not p.name.startswith("_"))


def blocks(page):
    """The code blocks of ``page`` in page order, literal blocks (``::``) included as ``text``."""
    lines = (DOCS / page).read_text(encoding="utf-8").splitlines()
    found = []
    i = 0
    while i < len(lines):
        match = _DIRECTIVE.match(lines[i])
        literal = lines[i].rstrip().endswith("::") and not lines[i].lstrip().startswith("..")
        if not match and not literal:
            i += 1
            continue
        start, indent = i + 1, len(lines[i]) - len(lines[i].lstrip())
        language = match["lang"] if match else "text"
        i += 1
        options = {}
        while match and i < len(lines) and _OPTION.match(lines[i]):
            option = _OPTION.match(lines[i])
            options[option["name"]] = option["value"].strip()
            i += 1
        body = []
        while i < len(lines) and (not lines[i].strip() or len(lines[i]) - len(lines[i].lstrip()) > indent):
            body.append(lines[i])
            i += 1
        content = [b for b in body]
        while content and not content[-1].strip():
            content.pop()
        while content and not content[0].strip():
            content.pop(0)
        margin = min((len(b) - len(b.lstrip()) for b in content if b.strip()), default=0)
        text = "\n".join(b[margin:] for b in content)
        found.append(Block(page, start, language, tuple(options.get("class", "").split()),
                           options.get("caption", ""), text))
    return found


def _pattern(expected):
    parts = [re.escape(" ".join(part.split())) for part in expected.strip().split("...")]
    return re.compile(".*".join(parts))


def matches(expected, output):
    """Whether the output line ``expected`` (``...`` standing for any text) is a line of ``output``."""
    pattern = _pattern(expected)
    return any(pattern.fullmatch(" ".join(line.split())) for line in re.split(r"[\r\n]", output))
