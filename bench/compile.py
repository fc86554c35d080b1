"""Compile time from an empty cache: each example scene, and ``make sim``'s two steps.

Run ``python -m bench.compile`` (``--help`` for options).  Each of the example scenes
(:data:`SCENES`) is compiled by ``phongfx compile scenes/<name>.toml -o DIR --quiet``, as a
user runs it (``--no-check``: without the cycle-by-cycle RTL check), in a fresh process
whose per-user cache is a new empty folder (``PHONGFX_CACHE``): every width point measured,
every design elaborated and priced, the RTL check's simulator built, nothing remembered.
Then ``make sim``'s steps the same way, as the Makefile runs them: ``phongfx compile
scenes/lyon-balls.toml --testbench``, then its Icarus testbench (when ``iverilog`` is
installed) beside ``phongfx render --backend verilator-fast``.  Each time is printed against its target, :data:`TARGET`
seconds per scene (:data:`GOAL` the aim) and :data:`SIM_TARGET` for ``make sim``, with the
design each scene chose (method, widths, cost, certified), the processor time of the
compile and its workers, and the machine's load (a shared machine's times are longer than
its processor times).  Not a test: nothing fails on a slow run.  The numbers go to
``build/bench/compile.json`` (atomically).
"""

import argparse
import json
import os
import platform
import resource
import shutil
import subprocess
import sys
import tempfile
import threading
import time

from phongfx.core.files import atomic_write
from phongfx.deliver.manifest import manifest_path, read_manifest

__all__ = ["SCENES", "TARGET", "GOAL", "SIM_TARGET", "timed", "chosen_design", "compile_scene", "make_sim", "run",
           "table", "main"]

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
#: The example scenes (``scenes/<name>.toml``).
SCENES = ("torus", "local-mesh", "lyon-balls", "two-lights")
#: Seconds a cold compile of an example scene may take on 2 cores, and the aim.
TARGET, GOAL = 60.0, 30.0
#: Seconds ``make sim`` may take from a fresh clone (its two steps, from an empty cache).
SIM_TARGET = 90.0


def _phongfx():
    """The ``phongfx`` command of this interpreter's environment."""
    here = os.path.join(os.path.dirname(sys.executable), "phongfx")
    return [here] if os.path.exists(here) else [sys.executable, "-m", "phongfx.cli"]


def timed(command, cache, log):
    """Run ``command`` with the per-user cache ``cache``; ``{"seconds", "cpu_seconds",
    "load", "returncode"}`` (processor time of the command and its children, the
    1-minute load average before it), its output appended to ``log``."""
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    with open(log, "a") as out:
        done = subprocess.run(command, cwd=ROOT, stdout=out, stderr=subprocess.STDOUT,
                              env={**os.environ, "PHONGFX_CACHE": str(cache)})
    seconds = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"seconds": seconds, "cpu_seconds": cpu, "load": load, "returncode": done.returncode}


def chosen_design(folder):
    """What a compiled ``folder``'s manifest says was chosen."""
    if not os.path.exists(manifest_path(folder)):
        return None
    data = read_manifest(folder)  # its version checked: a manifest of another layout is refused
    certificate = data.get("certificate") or {}
    return {"chosen": data.get("chosen"), "widths": data.get("widths"), "cost": (data.get("cost") or {}).get("cost"),
            "max_error": (data.get("error") or {}).get("max"), "certified": certificate.get("certified"),
            "bound_levels": certificate.get("bound_levels")}


def compile_scene(name, out_dir, check=True, workers=None):
    """:func:`timed` cold compile of ``scenes/<name>.toml`` into ``out_dir/<name>``, with the
    chosen design (module docstring)."""
    folder = os.path.join(out_dir, name)
    shutil.rmtree(folder, ignore_errors=True)
    command = [*_phongfx(), "compile", os.path.join("scenes", f"{name}.toml"), "-o", folder, "--quiet"]
    command += [] if check else ["--no-check"]
    command += [] if workers is None else ["--workers", str(workers)]
    with tempfile.TemporaryDirectory(prefix="phongfx-bench-cache-") as cache:
        found = timed(command, cache, os.path.join(out_dir, f"{name}.log"))
    return {"scene": name, "check": check, **found, "design": chosen_design(folder)}


def make_sim(out_dir):
    """``make sim``'s steps (module docstring) from one empty cache, as the Makefile runs them:
    the compile, then the testbench beside the render; each :func:`timed`, and the whole."""
    folder = os.path.join(out_dir, "sim")
    shutil.rmtree(folder, ignore_errors=True)
    log = os.path.join(out_dir, "sim.log")
    render = [*_phongfx(), "render", "--backend", "verilator-fast", "--out", folder]
    compile_ = [*_phongfx(), "compile", os.path.join("scenes", "lyon-balls.toml"), "-o",
                os.path.join(folder, "lyon-balls"), "--testbench", "--quiet"]
    out = {}
    start, before = time.perf_counter(), resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory(prefix="phongfx-bench-cache-") as cache:
        out["compile"] = timed(compile_, cache, log)
        beside = threading.Thread(target=lambda: out.update(render=timed(render, cache, log + ".render")))
        beside.start()
        if shutil.which("iverilog"):
            out["testbench"] = timed(["sh", os.path.join(folder, "lyon-balls", "testbench", "run.sh"), "icarus"],
                                     cache, log)
        beside.join()
    seconds, after = time.perf_counter() - start, resource.getrusage(resource.RUSAGE_CHILDREN)
    # the steps side by side share the children's counters: the whole's processor time only
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return {"steps": out, "seconds": seconds, "cpu_seconds": cpu,
            "returncode": max(s["returncode"] for s in out.values())}


def run(scenes=SCENES, out_dir="build/bench/compile", check=True, sim=True, workers=None):
    """Every scene's cold compile and ``make sim``; the result dict (also written to
    ``<out_dir>/../compile.json``)."""
    os.makedirs(out_dir, exist_ok=True)
    rows = [compile_scene(name, out_dir, check, workers) for name in scenes]
    result = {"rows": rows, "sim": make_sim(out_dir) if sim else None, "target_seconds": TARGET,
              "goal_seconds": GOAL, "sim_target_seconds": SIM_TARGET, "cores": os.cpu_count(),
              "python": platform.python_version(), "machine": platform.machine()}
    path = os.path.join(os.path.dirname(os.path.normpath(out_dir)), "compile.json")
    atomic_write(path, lambda tmp: open(tmp, "w").write(json.dumps(result, indent=2)))
    result["path"] = path
    return result


def _verdict(seconds, target, goal=None):
    if goal is not None and seconds <= goal:
        return "goal met"
    return "within target" if seconds <= target else f"over by {seconds - target:.0f} s"


def table(result):
    """Markdown table of :func:`run`'s result."""
    lines = [f"| scene | RTL check | seconds | cpu s | load | vs {TARGET:.0f} s | chosen | cost | max | certified |",
             "|---" * 10 + "|"]
    for row in result["rows"]:
        d = row["design"] or {}
        status = _verdict(row["seconds"], TARGET, GOAL) if row["returncode"] == 0 else f"exit {row['returncode']}"
        lines.append(f"| {row['scene']} | {'yes' if row['check'] else 'no'} | {row['seconds']:.1f} | "
                     f"{row['cpu_seconds']:.1f} | {row['load']:.1f} | {status} | {d.get('chosen')} {d.get('widths')} | "
                     f"{d.get('cost')} | {d.get('max_error')} | {d.get('certified')} |")
    sim = result.get("sim")
    if sim:
        steps = ", ".join(f"{name} {s['seconds']:.1f} s" for name, s in sim["steps"].items())
        status = _verdict(sim["seconds"], SIM_TARGET) if sim["returncode"] == 0 else f"exit {sim['returncode']}"
        lines.append(f"make sim (from an empty cache): {sim['seconds']:.1f} s ({steps}; cpu {sim['cpu_seconds']:.1f} s), "
                     f"{status} of {SIM_TARGET:.0f} s")
    lines.append(f"targets: {TARGET:.0f} s per scene (goal {GOAL:.0f} s) on 2 cores, this machine has "
                 f"{result['cores']}; load: the 1-minute load average when each started")
    return "\n".join(lines)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python -m bench.compile", description=__doc__.split("\n\n")[0])
    parser.add_argument("--scenes", nargs="*", default=list(SCENES), choices=SCENES, metavar="NAME",
                        help=f"example scenes to compile (default all: {', '.join(SCENES)})")
    parser.add_argument("--no-check", action="store_true", help="compile without the cycle-by-cycle RTL check")
    parser.add_argument("--no-sim", action="store_true", help="skip make sim's steps")
    parser.add_argument("--workers", type=int, help="phongfx compile --workers (default: every core)")
    parser.add_argument("--out", default="build/bench/compile", help="folder for the compiled scenes and logs")
    args = parser.parse_args(argv)
    if args.workers is not None and args.workers < 1:
        parser.error(f"--workers must be a positive integer, not {args.workers}")
    result = run(args.scenes, args.out, not args.no_check, not args.no_sim, args.workers)
    print(table(result))
    print(f"wrote {result['path']}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
