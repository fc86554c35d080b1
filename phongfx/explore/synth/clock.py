"""A tool-free estimate of a block's clock (:func:`proxy_clock`): the longest
register-to-register path of its flattened RTLIL, priced per cell kind and width.

The compiler has to know, before any synthesis, whether a design at pipeline depth
``d`` meets a pixel rate; the area proxy (:mod:`.proxy`) says nothing about speed.  A
clocked design runs at the speed of its slowest stage, and the stages are what the RTL
says they are: the registers of :func:`~phongfx.hdl.fixed.stage` (and, on ECP5 from
:data:`~phongfx.hdl.dsp.DSP_MAPPING_DEPTH`, the MULT18X18D's own input and output
registers, :mod:`phongfx.hdl.dsp`) cut the datapath into combinational stages, and a
deeper ``pipeline`` moves them.  So the estimate reads the same design the flows
synthesize (:func:`~phongfx.explore.synth.toolrun.design_rtlil`, flattened by
:func:`~phongfx.explore.synth.flatten.flatten`), gives each combinational cell a delay
(:func:`cell_features` × :data:`COEFFICIENTS`), and takes the longest path from a
register or input to a register or output (:func:`critical_path`), plus a fixed
per-stage overhead (clock-to-Q, setup, the first and last route).

The delay of a cell is linear in a few amounts (:data:`FEATURES`): one per variable
multiplier (an ECP5 DSP, whatever its width up to 18 × 18 bits), the extra DSP tiles of a
wider product (summed in the fabric), the operand bits of a product (a standard-cell
array multiplier grows with them), one per carry chain (adders, subtracters,
comparators; a product by a constant is its shift-and-add tree of adders) with its width
and its log (ECP5's ripple ``CCU2C`` against the parallel-prefix adders of Yosys'
generic ``techmap`` on standard cells), and one per LUT level (multiplexers, logic, the
levels of a variable shift, of a ROM read, of a reduction).  The coefficients per target
were fitted by ``phongfx tables clock`` (:mod:`phongfx.explore.tables.clock`) to the
synthesized critical paths of every datapath at every depth, non-negative least squares
of the relative period error alternated with the choice of the critical path under the
coefficients of the round before; :data:`ERROR` is the largest relative Fmax error of
that calibration, the margin the compiler keeps.
"""

import math

from phongfx.explore.synth.flatten import flatten

__all__ = ["FEATURES", "COEFFICIENTS", "ERROR", "MARGIN", "TARGETS", "LIBRARY_COEFFICIENTS", "LIBRARY_ERROR",
           "LIBRARY_MARGIN", "promise_margin", "cell_features", "critical_path", "clock_rtlil",
           "clock_netlist", "proxy_clock", "estimate"]

#: The amounts a cell's delay is linear in (module docstring); ``stage`` is 1 per path.
FEATURES = ("stage", "mul", "mul_tiles", "mul_bits", "carry", "carry_bits", "carry_log", "lut", "fanout")

#: ns per unit of each feature, per target (``asic`` is osu018).  Fitted by
#: ``phongfx tables clock --refit`` (:func:`phongfx.explore.tables.clock.fit`): non-negative
#: least squares of the relative period error over the calibration points synthesized, the
#: critical path re-chosen under each round's coefficients until they settle.  ECP5 (nextpnr
#: seed 1 at 150 MHz on the LFE5U-45F): 32 points, every datapath at every depth and the
#: whole shaders of :data:`phongfx.explore.tables.clock.SHADERS` (Figure 7 holding two lights
#: at depths 0..4 and at interval 2, the two-light scene's blend, Phong and Blinn–Phong copies);
#: the time is on the DSP multiply, the carry chains, the LUT levels and the nets' fan-out
#: (0.05 ns per doubling of a net's loads: the route to every copy of a shared input, a
#: select steering a wide word).  osu018 (Yosys + ABC buffering and sizing, OpenSTA
#: pre-layout): 20 points, fig7 at 0..4, fig8 at 0, 2, 4, Lyon's Figure 5 at 0 and the
#: shaders (Figure 7 holding two lights at depths 0..4, at interval 2 and with the scene's
#: blend; two Phong copies); a fixed overhead, the multipliers and the adders, the fan-out
#: left to ABC's buffers (fitted 0).
COEFFICIENTS = {
    "ecp5": {"stage": 1.45, "mul": 5.553, "mul_tiles": 0.0, "mul_bits": 0.064,
             "carry": 0.0, "carry_bits": 0.063, "carry_log": 0.053, "lut": 0.385, "fanout": 0.052},
    "asic": {"stage": 3.322, "mul": 1.96, "mul_tiles": 0.756, "mul_bits": 0.003,
             "carry": 0.427, "carry_bits": 0.0, "carry_log": 0.0, "lut": 0.0, "fanout": 0.0},
}
#: The share of the fitted estimate the proxy gives up, per target, so that on no calibration
#: point does it state a clock above the synthesized one (:func:`promise_margin` of the fit's
#: errors): the clock it states is a promise the calibration holds, not a central estimate.
MARGIN = {"ecp5": 0.163, "asic": 0.051}
#: The largest relative Fmax error of the stated (promised) clock on the calibration
#: (``phongfx tables clock``), per target: how far below synthesis the promise may be.
ERROR = {"ecp5": 0.28, "asic": 0.13}
#: The targets :func:`proxy_clock` knows, and the device (library) each was calibrated on.
TARGETS = {"ecp5": "45k", "asic": "osu018"}
#: The standard-cell libraries the clock proxy is calibrated on (by the name
#: :func:`~phongfx.explore.synth.asic.library_name` gives a Liberty file): ns per unit of each
#: feature, the largest relative Fmax error of the promise and the margin.  osu018 is ``asic``.
#: IHP SG13G2 typical (its file's default wire-load model applied by OpenSTA; the flow buffers
#: and sizes as on osu018): fitted on fig7 at depths 0, 1, 2, 4 and fig8 at 0, 2, 4 (7 points;
#: the shaders, slow to synthesize, left out), median error 3.0%, largest 3.8%: the time is in
#: the array multipliers' operand bits and the adders' width.
LIBRARY_COEFFICIENTS = {
    "osu018": COEFFICIENTS["asic"],
    "sg13g2_stdcell_typ_1p20V_25C": {"stage": 0.0, "mul": 0.0, "mul_tiles": 0.026, "mul_bits": 0.195,
                                     "carry": 0.0, "carry_bits": 0.026, "carry_log": 0.0, "lut": 0.0, "fanout": 0.0},
}
LIBRARY_ERROR = {"osu018": ERROR["asic"], "sg13g2_stdcell_typ_1p20V_25C": 0.08}
LIBRARY_MARGIN = {"osu018": MARGIN["asic"], "sg13g2_stdcell_typ_1p20V_25C": 0.037}


def promise_margin(errors):
    """The share of an estimate to give up so that none of ``errors`` (estimate / measured − 1,
    one per calibration point) is above the measured value: the largest ``e / (1 + e)``, 0
    when the estimate is nowhere high."""
    return max((e / (1 + e) for e in errors if e > 0), default=0.0)

_CARRY = {"$add", "$sub", "$neg", "$alu", "$lt", "$le", "$gt", "$ge"}
_EQ = {"$eq", "$ne", "$eqx", "$nex", "$reduce_and", "$reduce_or", "$reduce_xor", "$reduce_xnor", "$reduce_bool",
       "$logic_not", "$logic_and", "$logic_or"}
_SHIFT = {"$shl", "$shr", "$sshl", "$sshr", "$shift", "$shiftx"}
_LOGIC = {"$and", "$or", "$xor", "$xnor"}
_WIRING = {"$not", "$pos", "$buf", "$concat", "$slice"}


def _int(params, name, default=0):
    value = str(params.get(name, "")).strip()
    return int(value) if value.lstrip("-").isdigit() else default


def _tiles(width):
    return width // 18 + (width % 18 >= 2)


def _carry(width):
    return {"carry": 1, "carry_bits": width, "carry_log": math.log2(max(width, 2))}


def _product(a, b):
    return {"mul": 1, "mul_tiles": max(_tiles(a) * _tiles(b) - 1, 0), "mul_bits": a + b}


def _reg(params, name):
    return str(params.get(name, "NONE")).strip().strip('"') not in ("NONE", "")


def cell_features(node, netlist):
    """The amounts (:data:`FEATURES`) of the delay through combinational ``node`` of
    ``netlist``; ``{}`` for wiring (a constant shift, a sign extension, an inversion)."""
    kind, params = node.type, node.params
    a, b, y = _int(params, "A_WIDTH"), _int(params, "B_WIDTH"), _int(params, "Y_WIDTH")
    if kind == "$mul":
        const = [netlist.literal(node.inputs.get(port, [])) for port in ("A", "B")]
        if const[0] is None and const[1] is None:
            return _product(a, b)
        ones = max((c or "'").split("'", 1)[1].count("1") for c in const)
        depth = math.ceil(math.log2(ones)) if ones > 1 else 0
        return {k: depth * v for k, v in _carry(y).items()}
    if kind == "MULT18X18D":
        return _product(18, 18)
    if kind in _CARRY:
        return _carry(max(a, b, y) if kind in ("$add", "$sub", "$neg", "$alu") else max(a, b))
    if kind in _EQ:
        return {"lut": max(1, math.ceil(math.log(max(a, b, 2), 4)))}
    if kind in ("$mux", "$process"):
        return {"lut": max(1, math.ceil(math.log2(max(_int(params, "CASES", 2), 2))))}
    if kind in ("$pmux", "$bmux"):
        return {"lut": max(1, math.ceil(math.log2(_int(params, "S_WIDTH", 1) + 1)))}
    if kind in _SHIFT:
        if netlist.literal(node.inputs.get("B", [])) is not None or b == 0:
            return {}
        return {"lut": min(b, max(y, 2).bit_length())}
    if kind in _LOGIC:
        return {"lut": 1}
    if kind.startswith("$memrd"):
        return {"lut": 1 + math.ceil(max(_int(params, "ABITS") - 4, 0) / 2)}
    return {}


def _ends(node):
    """(launch, capture) amounts of a register ``node``: a DSP with only one side
    registered still has the multiply on the other side of its registers."""
    if node.type != "MULT18X18D":
        return {}, {}
    inputs = _reg(node.params, "REG_INPUTA_CLK") or _reg(node.params, "REG_INPUTB_CLK")
    output = _reg(node.params, "REG_OUTPUT_CLK")
    multiply = _product(18, 18)
    return (multiply if inputs and not output else {}), (multiply if output and not inputs else {})


def _is_register(node):
    if node.type == "MULT18X18D":
        params = node.params
        return any(_reg(params, name) for name in ("REG_INPUTA_CLK", "REG_INPUTB_CLK", "REG_OUTPUT_CLK"))
    return node.register


def _price(amounts, coefficients):
    return sum(coefficients.get(k, 0.0) * v for k, v in amounts.items())


def _fanout(netlist, sink, src):
    """The amounts of the net from ``src`` into ``sink``: log2 of its fan-out (a buffer tree's
    depth, or an FPGA route's spread), nothing for a net of one load."""
    fan = netlist.fanins(sink).get(src, 1)
    return {"fanout": math.log2(fan)} if fan > 1 else {}


def critical_path(netlist, coefficients):
    """``(ns, amounts, names)`` of the slowest register-to-register stage of ``netlist``
    under ``coefficients`` (ns per feature): its delay with the ``stage`` overhead, the
    summed :data:`FEATURES` along it (the nets' fan-out among them), and the names of its
    cells from launch to capture."""
    nodes = netlist.nodes
    register = [_is_register(node) for node in nodes]
    own = [{} if register[i] else cell_features(node, netlist) for i, node in enumerate(nodes)]
    ends = [_ends(node) if register[i] else ({}, {}) for i, node in enumerate(nodes)]
    arrival, back = [0.0] * len(nodes), [None] * len(nodes)

    def launch(src):
        if src < 0:
            return 0.0
        return _price(ends[src][0], coefficients) if register[src] else arrival[src]

    def into(sink, src):
        return launch(src) + _price(_fanout(netlist, sink, src), coefficients)

    for index in netlist.order():
        if register[index]:
            continue
        best = max(netlist.sources(index), key=lambda src: into(index, src), default=-1)
        arrival[index] = into(index, best) + _price(own[index], coefficients)
        back[index] = best
    endpoints = [(i, netlist.sources(i)) for i in range(len(nodes)) if register[i]]
    endpoints.append((None, netlist.output_sources()))
    worst = (-1.0, None, -1)
    for sink, srcs in endpoints:
        capture = _price(ends[sink][1], coefficients) if sink is not None else 0.0
        for src in srcs:
            delay = (launch(src) if sink is None else into(sink, src)) + capture
            if delay > worst[0]:
                worst = (delay, sink, src)
    _, sink, src = worst
    path, amounts = [], dict.fromkeys(FEATURES, 0.0)
    amounts["stage"] = 1.0

    def add(part):
        for k, v in part.items():
            amounts[k] += v

    if sink is not None:
        path.append(nodes[sink].name)
        add(ends[sink][1])
    while src is not None:
        if sink is not None:
            add(_fanout(netlist, sink, src))
        if src < 0:
            break
        path.append(nodes[src].name)
        add(ends[src][0] if register[src] else own[src])
        sink, src = src, None if register[src] else back[src]
    path.reverse()
    return _price(amounts, coefficients), amounts, path


def clock_rtlil(block, target):
    """The RTLIL the flow of ``target`` synthesizes for ``block`` (on ECP5 deep enough, its
    products mapped onto MULT18X18D cells with their registers: :func:`~phongfx.hdl.dsp.dsp_mapping_of`)."""
    from phongfx.hdl.dsp import dsp_mapping_of

    from phongfx.explore.synth.toolrun import design_rtlil

    return design_rtlil(block, "top", dsp_mapping_of(block, target))


def clock_netlist(block, target):
    """:func:`clock_rtlil` of ``block`` on ``target``, flattened: what the estimate walks."""
    return flatten(clock_rtlil(block, target))


def _describe(amounts, path, ns):
    parts = [f"{int(amounts[k])} {label}" for k, label in
             (("mul", "multiplier"), ("carry", "carry chain"), ("lut", "LUT level")) if amounts[k]]
    if amounts.get("fanout", 0) >= 1:
        parts.append(f"nets of fan-out {2 ** amounts['fanout']:,.0f} (product)")
    ends = f"{path[0]} → {path[-1]}" if path else "input → output"
    return f"{ends}: {', '.join(parts) or 'wiring only'} ({len(path)} cells), {ns:.2f} ns"


def estimate(netlist, target, library=None):
    """:func:`proxy_clock`'s result for a flattened ``netlist`` on ``target`` (on ``"asic"``,
    on ``library``'s coefficients, a name of :data:`LIBRARY_COEFFICIENTS`; default osu018)."""
    if target == "asic" and library not in (None, TARGETS["asic"]):
        coefficients, margin, error = (LIBRARY_COEFFICIENTS[library], LIBRARY_MARGIN[library],
                                       LIBRARY_ERROR[library])
        model = f"asic-clock-proxy {library}"
    else:
        coefficients, margin, error = COEFFICIENTS[target], MARGIN[target], ERROR[target]
        model = f"{target}-clock-proxy"
    ns, amounts, path = critical_path(netlist, coefficients)
    promised = (1000.0 / ns) * (1 - margin)
    return {"fmax_mhz": promised, "period_ns": 1000.0 / promised, "estimate_mhz": 1000.0 / ns, "margin": margin,
            "model": model, "error": error, "path": _describe(amounts, path, ns)}


def proxy_clock(block, target="ecp5", device=None):
    """The estimated clock of ``block`` (a :class:`~phongfx.core.registry.Block`) on
    ``target``: ``{fmax_mhz, period_ns, model, error, path}``, ``error`` the calibration's
    largest relative Fmax error (:data:`ERROR`), ``path`` the slowest stage in words.

    ``device`` is accepted for the FPGA part (the ECP5 speed grade is the same on the
    25k, 45k and 85k: the estimate does not depend on it) or the standard-cell library
    (a name or Liberty file of a library in :data:`LIBRARY_COEFFICIENTS`).  Kept per design
    identity (:func:`~phongfx.explore.synth.estimates.cached_estimate`), so a known design is
    timed without being elaborated."""
    if target not in COEFFICIENTS:
        raise ValueError(f"target must be one of {', '.join(map(repr, COEFFICIENTS))}, not {target!r}")
    if target == "asic":
        from phongfx.explore.synth.asic import library_name

        name = library_name(device)
        if name not in LIBRARY_COEFFICIENTS:
            raise ValueError(f"device must be one of {', '.join(LIBRARY_COEFFICIENTS)} for the asic clock proxy, "
                             f"not {name!r}: fit it with `phongfx tables clock --liberty FILE --refit`")
    elif device is not None and device not in ("25k", "45k", "85k"):
        raise ValueError(f"device must be one of 25k, 45k, 85k for the {target} clock proxy, not {device!r}")
    else:
        name = None  # one speed grade: the part does not change the estimate
    from phongfx.explore.synth.estimates import cached_estimate

    # kept like the area proxy's: the clock's elaboration is as long as the area's
    return cached_estimate("clock", block, target, name, lambda: estimate(clock_netlist(block, target), target, name))
