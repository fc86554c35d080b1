"""Verilog for a datapath component, via Amaranth's Yosys back end.

The module keeps Amaranth's port names (``clk``, ``rst``, ``i__valid``,
``i__payload``, ``o__valid``, ``o__payload``) and the named wires it emits for
each payload field (``\\i__payload.n0[1]`` ...), so waveforms and lint messages
read in the block's own terms.
"""

import os
import tempfile
from pathlib import Path

from amaranth.back import verilog as _verilog

__all__ = ["verilog", "write_verilog"]


def verilog(component, name, *, emit_src=True):
    """Verilog text of ``component`` as a module called ``name``.

    Parameters
    ----------
    component : amaranth.lib.wiring.Component
        Usually a :class:`~phongfx.hdl.block.PipelinedBlock`.
    name : str
        Module name; must be a plain Verilog identifier.
    emit_src : bool
        Keep the ``(* src = "file:line" *)`` attributes.  They carry absolute
        paths and line numbers, so callers that hash the text (the Verilator
        build cache) turn them off to survive edits that change no logic.

    Returns
    -------
    str
    """
    if not name.isidentifier():
        raise ValueError(f"module name must be a Verilog identifier, not {name!r}")
    return _verilog.convert(component, name=name, emit_src=emit_src)


def write_verilog(component, name, path, *, emit_src=True):
    """Write :func:`verilog` to ``path`` atomically; returns ``path`` as a :class:`Path`.

    The text goes to a temporary file in the same directory, then replaces
    ``path`` in one step, so a reader (or a crash) never sees half a module.
    """
    path = Path(path)
    text = verilog(component, name, emit_src=emit_src)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, temp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w") as file:
            file.write(text)
        os.chmod(temp, 0o644)  # mkstemp makes it private; a Verilog file is not
        os.replace(temp, path)
    except BaseException:
        Path(temp).unlink(missing_ok=True)
        raise
    return path
