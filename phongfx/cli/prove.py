"""``phongfx prove``: formal proofs of a block's ``overflow="error"`` claims.

Kept in its own module: the proof's report (each claim, its status and time, the
assumptions it rests on) and the DSP-mapping proofs are their own command's business.
"""

import json
import sys

from .settings import configured_block

__all__ = ["add_arguments", "cmd_prove", "report"]


def add_arguments(p):
    """``phongfx prove``'s arguments, on its subparser ``p``."""
    from phongfx.core.registry import block_names
    from phongfx.sim.prove import SOLVERS

    p.add_argument("name", nargs="?", choices=block_names(), help="block name")
    p.add_argument("--dsp", action="store_true",
                   help="instead: prove the ECP5 DSP mapping of every product the registry maps equal to the "
                        "behavioural multiply (phongfx.sim.dsp_equivalence)")
    p.add_argument("--set", action="append", metavar="FIELD=VALUE", help="change a config field")
    p.add_argument("--json", action="store_true", help="the result as JSON on stdout")
    p.add_argument("--timeout", type=float, default=600, metavar="S",
                   help="seconds per claim before it is reported unknown (default 600)")
    p.add_argument("--solver", choices=tuple(SOLVERS), default="yices", help="smtbmc's solver (default yices)")
    p.add_argument("--quiet", action="store_true", help="no progress")


def report(proof, out=None):
    """The text report of a :class:`~phongfx.sim.prove.Proof` (on ``out``, default stdout)."""
    out = out or sys.stdout
    print(f"{proof.block}: {len(proof.claims)} overflow=\"error\" quantize(s); proven {proof.counts['proven']}, "
          f"by width {proof.counts['static']}, counterexample {proof.counts['counterexample']}, "
          f"unknown {proof.counts['unknown']} ({proof.seconds:.1f} s, k-induction depth {proof.depth}, "
          f"{proof.solver})", file=out)
    print("assuming, on every valid input: " + "; ".join(proof.assumptions), file=out)
    for claim in proof.claims:
        line = f"  {claim.status:14s} {claim.block}: {claim.claim}"
        if claim.seconds:
            line += f" ({claim.seconds:.1f} s)"
        print(line, file=out)
        if claim.inputs is not None:
            print(f"  {'':14s} inputs {claim.inputs}", file=out)
        if claim.why:
            print(f"  {'':14s} {claim.why}", file=out)


def cmd_prove(args):
    from phongfx.sim.prove import prove

    timeout = args.timeout
    if not timeout > 0:
        raise ValueError(f"--timeout must be a positive number of seconds, not {timeout:g}")
    if args.dsp == (args.name is not None):
        raise ValueError("give a block NAME or --dsp, not both or neither")
    if args.dsp:
        return _dsp(args, timeout)
    block = configured_block(args.name, args.set)

    def progress(text):
        if not args.quiet:
            print(f"prove {args.name}: {text}", file=sys.stderr, flush=True)
    proof = prove(block, solver=args.solver, timeout=timeout, progress=progress)
    if args.json:
        print(json.dumps(proof.as_dict(), indent=2))
    else:
        report(proof)
    return proof.exit_code


def _dsp(args, timeout):
    from phongfx.sim.dsp_equivalence import markdown, prove_dsp_mapping

    proofs = prove_dsp_mapping(timeout=timeout)
    counts = {status: sum(p.status == status for p in proofs) for status in ("proven", "counterexample", "unknown")}
    if args.json:
        print(json.dumps({**counts, "cases": [{"case": p.case.label, "status": p.status, "seconds": p.seconds,
                                               "dsps": p.dsps, "operands": p.operands} for p in proofs]},
                         indent=2))
    else:
        print(markdown(proofs))
    return 1 if counts["counterexample"] else 3 if counts["unknown"] else 0
