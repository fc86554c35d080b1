"""Running the synthesis tools: one private folder per run, logs read back, results cached.

Both flows (:mod:`.fpga` for the FPGAs, :mod:`.asic` for standard cells) run external
programs the way :mod:`phongfx.sim.tools` does (its names are re-exported here), and a
report is trusted only when the files the log names parse (:func:`read_json`).

A result is cached in ``<workdir>/<key>/result.json`` (:func:`cached_run`), ``<workdir>``
being the per-user cache's ``synth/`` or ``sta/`` folder (:mod:`phongfx.core.cache`)
unless given: the run works in a private folder beside it and is renamed into place only
when complete, so a folder with a ``result.json`` is a finished run, an interrupted one
leaves nothing and a failed one leaves its logs in ``failed/<key>``.
"""

import json
from pathlib import Path

from phongfx.core.cache import folder, make_entry, remembered_key
from phongfx.sim.tools import SynthError, run, run_yosys, tail, tool

__all__ = ["SynthError", "RESULT", "KEEP", "tool", "run", "run_yosys", "tail", "read_json", "harness", "design_rtlil",
           "flow_key", "cached_run"]

#: The file written last in a run folder: its presence means a complete run.
RESULT = "result.json"


def read_json(path, what, log):
    """JSON file ``path``, or a :class:`SynthError` naming ``what`` and the end of ``log``."""
    try:
        return json.loads(Path(path).read_text())
    except (OSError, ValueError) as error:
        raise SynthError(f"{what} missing or incomplete ({error}); log {log}:\n{tail(log)}") from None


def harness(module, in_width, out_width):
    """Verilog of ``<module>_synth``: block ``module`` between two shift registers.

    Ports ``clk``, ``rst``, ``si`` (serial in), ``load`` and ``so`` (serial out).  Each
    clock shifts ``si`` into the ``{i.payload, i.valid}`` register; ``load`` captures
    ``{o.payload, o.valid}`` into the output register, which otherwise shifts out
    through ``so``.  Nothing is constant, so Yosys can remove none of the block.
    """
    wi, wo = in_width + 1, out_width + 1
    return f"""
module {module}_synth(clk, rst, si, load, so);
  input clk, rst, si, load;
  output so;
  reg [{wi - 1}:0] in_shift = 0;
  reg [{wo - 1}:0] out_shift = 0;
  wire o_valid;
  wire [{out_width - 1}:0] o_payload;
  {module} dut (
    .clk(clk), .rst(rst),
    .i__valid(in_shift[0]), .i__payload(in_shift[{wi - 1}:1]),
    .o__valid(o_valid), .o__payload(o_payload)
  );
  assign so = out_shift[{wo - 1}];
  always @(posedge clk) begin
    in_shift <= {{in_shift[{wi - 2}:0], si}};
    out_shift <= load ? {{o_payload, o_valid}} : {{out_shift[{wo - 2}:0], 1'b0}};
  end
endmodule
"""


#: How many elaborated designs :func:`design_rtlil` keeps: a design's area and clock proxies,
#: and its flows' cache keys, read the same text (Amaranth's netlist takes 0.5 to 1.5 s a shader).
KEEP = 4
_ELABORATED = {}  # identity -> RTLIL, oldest first


def design_rtlil(block, module, dsp=None):
    """RTLIL of ``block`` (a :class:`~phongfx.core.registry.Block`) emitted as ``module``, as
    the flows' cache keys hash it: without source locations, and without the
    simulation-only overflow flags (they cost nothing in a netlist, and the flows
    synthesize without them); its products mapped onto ``dsp``'s DSPs
    (:func:`~phongfx.hdl.dsp.dsp_mapping`) when given.  The last :data:`KEEP` designs with
    an identity (:func:`~phongfx.hdl.identity.design_identity`) are elaborated once."""
    from amaranth.back import rtlil

    from phongfx.hdl.dsp import dsp_mapping
    from phongfx.hdl.identity import design_identity
    from phongfx.hdl.overflow import overflow_checks

    with overflow_checks(False), dsp_mapping(dsp):
        identity = design_identity(block.component_class, block.config, module)
        if identity is not None and identity in _ELABORATED:
            return _ELABORATED[identity]
        text = rtlil.convert(block.component(), name=module, emit_src=False)
    if identity is not None:
        _ELABORATED[identity] = text
        while len(_ELABORATED) > KEEP:
            del _ELABORATED[next(iter(_ELABORATED))]
    return text


def flow_key(block, module, dsp, head, tail):
    """The cache key of a flow's run of ``block``: the digest of the strings ``head``, the
    design's :func:`design_rtlil` and ``tail``, remembered per design identity
    (:func:`phongfx.core.cache.remembered_key`) so that a known design is not elaborated to
    find its run."""
    from phongfx.hdl.dsp import dsp_mapping
    from phongfx.hdl.identity import design_identity
    from phongfx.hdl.overflow import overflow_checks
    from phongfx.sim.build_cache import digest

    with overflow_checks(False), dsp_mapping(dsp):
        identity = design_identity(block.component_class, block.config, module)
    parts = None if identity is None else [*head, identity, *tail]
    return remembered_key(parts, lambda: digest([*head, design_rtlil(block, module, dsp), *tail]))


def cached_run(workdir, key, flow, cache="synth"):
    """The result in ``<workdir>/<key>``, else ``flow(work)`` run in a fresh private folder
    renamed there when it returns (:func:`phongfx.core.cache.make_entry`).  ``workdir``
    None is the per-user cache's folder ``cache``.  Adds ``cached`` and ``directory``
    to the result."""
    def make(work):
        result = flow(work)
        (work / RESULT).write_text(json.dumps(result, indent=1) + "\n")
        return result

    final, result = make_entry(folder(cache) if workdir is None else workdir, key, RESULT, make)
    if result is None:
        result = json.loads((final / RESULT).read_text())
        return {**result, "cached": True, "directory": str(final)}
    return {**result, "cached": False, "directory": str(final)}
