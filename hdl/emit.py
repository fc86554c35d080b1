"""Verilog for a datapath component, via Amaranth's Yosys back end.

The module keeps Amaranth's port names (``clk``, ``rst``, ``i__valid``,
``i__payload``, ``o__valid``, ``o__payload``) and the named wires it emits for
each payload field (``\\i__payload.n0[1]`` ...), so waveforms and lint messages
read in the block's own terms.
"""

from pathlib import Path

from amaranth.back import verilog as _verilog

__all__ = ["verilog", "write_verilog", "payload_widths"]


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
    from phongfx.core.files import atomic_write

    path = Path(path)
    text = verilog(component, name, emit_src=emit_src)
    atomic_write(path, lambda temp: Path(temp).write_text(text))
    return path


def payload_widths(component):
    """Bit widths ``(in, out)`` of a block's ``i.payload`` and ``o.payload``: what every
    wrapper around the emitted module (simulation tops, the synthesis harness) needs."""
    return len(component.i.payload.as_value()), len(component.o.payload.as_value())
