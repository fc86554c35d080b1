"""What the standard-cell flow needs to know of a Liberty file, read from the file itself.

Any foundry's library can be given (``--liberty FILE``): its name, its corner (the
``nom_process``, ``nom_voltage`` and ``nom_temperature`` every Liberty library states),
its time unit (OpenSTA reads and reports times in it), which cells are sequential (those
with an ``ff`` or ``latch`` group: no name convention is assumed), its smallest buffer (the
cell of one input whose output's ``function`` is that input; ABC sizes and buffers nets driven
as by it) and which cells the mapper must not use:

* the cells the file marks ``dont_use : true`` (IHP SG13G2 marks its fillers, decaps,
  antenna diode, clock gates, the scan flip-flop with set and reset and the bus keeper);
* by name, in any library, the cells a synthesis flow leaves to placement and clock-tree
  tools: fillers, decaps, antenna diodes, tie cells, clock gates, bus keepers and delay
  cells (:data:`DONT_USE_PATTERNS`, Yosys glob patterns; the same cells OpenROAD's flow
  scripts keep out of synthesis for SG13G2).

Reading is a scan of cell headers, not a full Liberty parser: a cell's text runs to the
next cell's header, which is all the facts above need.
"""

import functools
import re
from dataclasses import dataclass
from pathlib import Path

__all__ = ["Liberty", "DONT_USE_PATTERNS", "LibertyError", "read_liberty", "dont_use"]

#: Glob patterns (Yosys ``-dont_use``) of the cells no synthesis should map to.
DONT_USE_PATTERNS = ("*fill*", "*decap*", "*antenna*", "*tie*", "*lgcp*", "*icg*", "*clkgate*", "*sighold*",
                     "*dly*")

_UNITS_NS = {"1ps": 1e-3, "10ps": 1e-2, "100ps": 0.1, "1ns": 1.0, "10ns": 10.0, "1us": 1e3}
_CELL = re.compile(r"^\s*cell\s*\(\s*\"?([^\")\s]+)\"?\s*\)\s*\{", re.M)
_PIN = re.compile(r"^\s*pin\s*\(\s*\"?([^\")\s]+)\"?\s*\)\s*\{", re.M)


class LibertyError(ValueError):
    """A file given as a Liberty library cannot be used: it names the file and what is missing."""


@dataclass(frozen=True)
class Liberty:
    """The facts of one Liberty file the flow uses (module docstring)."""

    path: str
    name: str
    process: float
    voltage: float
    temperature: float
    time_unit_ns: float
    cells: tuple
    sequential: tuple
    dont_use: tuple
    buffer: tuple = None  # (cell, input capacitance in the file's unit) of the smallest buffer

    @property
    def corner(self):
        """``1.20 V, 25 °C, process 1``: the corner the file's timing holds at."""
        return f"{self.voltage:.2f} V, {self.temperature:g} °C, process {self.process:g}"


def _attribute(text, name, path):
    match = re.search(rf"^\s*{name}\s*:\s*\"?([^\";\s]+)\"?\s*;", text, re.M)
    if match is None:
        raise LibertyError(f"{path} gives no library-level {name} (a Liberty library states its corner "
                           f"as nom_process, nom_voltage and nom_temperature)")
    return match.group(1)


def _number(text, name, path):
    value = _attribute(text, name, path)
    try:
        return float(value)
    except ValueError:
        raise LibertyError(f"{path}: {name} must be a number, not {value!r}") from None


@functools.lru_cache(maxsize=8)
def _read(path, mtime_ns):
    try:
        text = Path(path).read_text(errors="replace")
    except OSError as error:
        raise LibertyError(f"cannot read the Liberty file {path}: {error.strerror or error}") from None
    header = re.search(r"^\s*library\s*\(\s*\"?([^\")\s]+)\"?\s*\)\s*\{", text[:20000], re.M)
    if header is None:
        raise LibertyError(f"{path} is not a Liberty file: no 'library (NAME) {{' group in its first 20,000 "
                           f"characters")
    heads = list(_CELL.finditer(text))
    if not heads:
        raise LibertyError(f"{path} is a Liberty library ({header.group(1)}) without any cell")
    head = text[header.end():heads[0].start()]
    unit = _attribute(head, "time_unit", path)
    if unit not in _UNITS_NS:
        raise LibertyError(f"{path}: time_unit must be one of {', '.join(_UNITS_NS)}, not {unit!r}")
    cells, sequential, marked, buffers = [], [], [], []
    for this, after in zip(heads, [*heads[1:], None]):
        body = text[this.end():after.start() if after else len(text)]
        name = this.group(1)
        cells.append(name)
        if re.search(r"^\s*(ff|latch)\s*\(", body, re.M):
            sequential.append(name)
        if re.search(r"^\s*dont_use\s*:\s*true\s*;", body, re.M):
            marked.append(name)
        found = _buffer(body)
        if found is not None and name not in marked and not _excluded(name):
            buffers.append((found[0], name, found[1]))
    usable_ff = [cell for cell in sequential if cell not in marked and not _excluded(cell)]
    if not usable_ff:
        raise LibertyError(f"{path} ({header.group(1)}) has no usable flip-flop cell: no cell with an 'ff' "
                           f"or 'latch' group outside the dont_use ones ({', '.join(marked) or 'none'})")
    return Liberty(str(path), header.group(1), _number(head, "nom_process", path),
                   _number(head, "nom_voltage", path), _number(head, "nom_temperature", path), _UNITS_NS[unit],
                   tuple(cells), tuple(sequential), tuple(marked), min(buffers)[1:] if buffers else None)


def _buffer(body):
    """``(area, input capacitance)`` of a cell whose text is ``body`` when it is a buffer (one
    input pin, one output pin whose ``function`` is that input), else None."""
    pins = list(_PIN.finditer(body))
    kinds = {}
    for this, after in zip(pins, [*pins[1:], None]):
        text = body[this.end():after.start() if after else len(body)]
        direction = re.search(r"\bdirection\s*:\s*\"?(\w+)\"?\s*;", text)
        if direction:
            kinds.setdefault(direction.group(1), []).append((this.group(1), text))
    if len(kinds.get("input", ())) != 1 or len(kinds.get("output", ())) != 1:
        return None
    (name, text), (_, out) = kinds["input"][0], kinds["output"][0]
    function = re.search(r"\bfunction\s*:\s*\"\s*\(?\s*(\w+)\s*\)?\s*\"\s*;", out)
    area = re.search(r"\barea\s*:\s*([0-9.eE+-]+)\s*;", body)
    cap = re.search(r"\bcapacitance\s*:\s*([0-9.eE+-]+)\s*;", text)
    if function is None or function.group(1) != name or area is None or cap is None:
        return None
    return float(area.group(1)), float(cap.group(1))


def _excluded(cell):
    from fnmatch import fnmatchcase

    return any(fnmatchcase(cell.lower(), pattern) for pattern in DONT_USE_PATTERNS)


def read_liberty(path):
    """The :class:`Liberty` facts of the file at ``path`` (read again only when it changes).

    Raises
    ------
    LibertyError
        If the file is missing or unreadable, is not a Liberty library, lacks its corner or
        time unit, or has no flip-flop cell the mapper may use.
    """
    path = Path(path).expanduser().resolve()
    if not path.is_file():
        raise LibertyError(f"Liberty file {path} does not exist" if not path.exists()
                           else f"Liberty file {path} is not a file")
    return _read(str(path), path.stat().st_mtime_ns)


def dont_use(liberty):
    """The cells of ``liberty`` the mapper must not use: marked ``dont_use`` or matching
    :data:`DONT_USE_PATTERNS`."""
    return tuple(cell for cell in liberty.cells if cell in liberty.dont_use or _excluded(cell))
