"""Yosys' LUT mapping on the FPGAs, and what to do where ABC9 gets it wrong.

``synth_ecp5`` / ``synth_ice40`` map logic to LUTs with ABC9.  Yosys 0.70's ABC9 fails in
two ways on our designs, and each has a fallback that maps the same design correctly:

* it stops on an assertion while reintegrating ABC's result (:data:`ABC9_ASSERT`; met on
  fig8 with local lights and on fig7 at depth 2 with its DSPs mapped): the classic
  ``abc -lut 4`` mapping is run instead;
* it finishes, but its netlist has nets with two drivers (:data:`CONFLICT`, the warning
  of the ``check`` pass that ends the script): on ECP5 the ``difference`` block in its
  timing harness came out with two flip-flops of the input shift register driving one
  net, and nextpnr stopped with "Net 'in_shift[39]' is multiply driven".  The cause is
  ABC9's default exchange format since 0.69 (``write_xaiger2``; Yosys issue #6237, with
  the same workaround); Yosys' switch back to the former one (:data:`XAIGER1`) maps
  it correctly, still with ABC9, and the classic mapping is the last resort.

A netlist that still has a net with two drivers is a :class:`SynthError` naming the net,
rather than a result (nextpnr would refuse it, and a simulator would read it wrongly).
"""

import re

from phongfx.sim.tools import SynthError, run_yosys, tail

__all__ = ["ABC9_ASSERT", "CONFLICT", "XAIGER1", "conflicts", "run_yosys_abc9_fallback"]

#: What Yosys' log says when ABC9 fails its reintegration assertion.
ABC9_ASSERT = "Assert `GetSize(conn.first) == GetSize(conn.second)' failed"
#: What Yosys' ``check`` pass says of a net with more than one driver.
CONFLICT = "multiple conflicting drivers for"
#: The Yosys command, put before the script, that makes ABC9 exchange its design with ABC in
#: the format it used up to 0.68 (``write_xaiger``) rather than ``write_xaiger2``.
XAIGER1 = "scratchpad -set abc9.xaiger 1"

_CONFLICT_NET = re.compile(re.escape(CONFLICT) + r" (\S+(?: \[\d+\])?)")


def conflicts(log):
    """The nets Yosys' ``check`` reported with conflicting drivers in ``log`` (a path; none
    if it is missing)."""
    try:
        text = log.read_text(errors="replace")
    except OSError:
        return []
    return _CONFLICT_NET.findall(text)


def run_yosys_abc9_fallback(work, script, make_script, outputs=()):
    """Run the Yosys script ``make_script(True)`` as ``script`` in ``work``, falling back as
    the module docstring says: on ABC9's assertion, ``make_script(False)`` (the classic
    ABC mapping); on nets with two drivers, the script after :data:`XAIGER1`, then the
    classic mapping.  The logs of the runs replaced stay beside (``yosys-abc9.log``,
    ``yosys-xaiger2.log``, ``yosys-xaiger1.log``).  Returns (seconds, which ABC flow
    mapped it); a netlist still with conflicting drivers is a :class:`SynthError`."""
    log = work / "yosys.log"
    (work / script).write_text(make_script(True))
    try:
        seconds, abc = run_yosys(work, script, outputs), "abc9"
    except SynthError:
        if ABC9_ASSERT not in log.read_text(errors="replace"):
            raise
        log.rename(work / "yosys-abc9.log")
        (work / script).write_text(make_script(False))
        seconds, abc = run_yosys(work, script, outputs), "abc (ABC9 failed an assertion: yosys-abc9.log)"
    if not conflicts(log):
        return seconds, abc
    if abc == "abc9":
        log.rename(work / "yosys-xaiger2.log")
        (work / script).write_text(f"{XAIGER1}\n{make_script(True)}")
        seconds = run_yosys(work, script, outputs)
        abc = "abc9 with xaiger1 (xaiger2 gave nets two drivers: yosys-xaiger2.log)"
        if not conflicts(log):
            return seconds, abc
        log.rename(work / "yosys-xaiger1.log")
        (work / script).write_text(make_script(False))
        seconds = run_yosys(work, script, outputs)
        abc = "abc (ABC9 gave nets two drivers: yosys-xaiger2.log, yosys-xaiger1.log)"
        if not conflicts(log):
            return seconds, abc
    nets = conflicts(log)
    raise SynthError(f"Yosys' netlist has {len(nets)} net(s) with conflicting drivers ({', '.join(nets[:3])}); "
                     f"log {log}:\n{tail(log)}")
