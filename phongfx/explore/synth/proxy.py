"""Tool-free cost estimates of a block, read from its RTLIL: LUT-equivalents for the FPGA
flow, and µm² of standard cells for the ASIC flow (:func:`proxy_area`).

When synthesis is not asked for (``phongfx compile`` without ``--synth``) the compiler
still has to rank designs.  :func:`proxy_cost` elaborates the block's Amaranth
component to RTLIL (no external tool) and prices each cell the way Yosys' ECP5 flow
maps it, in the unit of :mod:`phongfx.explore.tables.cost` (LUT-eq = LUT4 + 958·DSP):

* ``$mul`` with two variable operands: one MULT18 tile (958) per pair of 18-bit operand
  slices, a slice narrower than 2 bits left to logic as Yosys' ``mul2dsp`` does;
  by a constant: one adder of the other operand's width per extra set bit of the
  constant (a shift-and-add; a power of two is wiring);
* adders, subtracters, comparators: carry chains (ECP5 ``CCU2C``), which LUT-eq does not
  price: counted in ``carry_bits``, priced 0;
* multiplexers: one LUT per bit; shifts by a constant: wiring; by a variable amount:
  one mux per output bit per bit of the amount;
* bitwise logic: one per output bit; reductions one per 4 input bits;
* ROMs (``$memrd``): ``ceil(words/16)`` LUT4s per data bit (a LUT4 holds 16 bits);
* registers are counted (``ff_bits``) but priced 0, as LUT-eq prices them.

Checked against ECP5 synthesis (``phongfx tables clock``): the DSP counts match on every
datapath and shader at its defaults (Figure 7 39, the Blinn–Phong unit 20, two Blinn–Phong
copies 40, the spherical unit 4); LUTs run high (Yosys trims the unused bits of wide
intermediate results and folds much of the rounding and saturation logic), by the
margin of :data:`RESOURCE_MARGIN`.

On standard cells (:func:`proxy_area`) every bit costs area, so the estimate counts bits
by kind (:func:`rtlil_features`): a variable multiplier by the product of its operand
widths, adders, comparators, multiplexers and logic by their width, ROMs by words ×
bits, registers by their width; one coefficient per kind and library
(:data:`AREA_COEFFICIENTS`), fitted to the real flow over the registry's blocks
(``phongfx tables proxy``, which also states the error).

The design is read flattened (:func:`~phongfx.explore.synth.flatten.flatten`), and
identical cells (same type, parameters and drivers) count once, to a fixpoint, as
Yosys' ``flatten`` and ``opt_merge`` merge them: the expression trees Amaranth writes
out again for every use, and the logic of light copies that take the same shared
inputs (one N for every light) are priced once, as they are built.  It is a ranking
device, not a synthesis result: the manifest says
``"cost_model": "proxy"`` and the ``--synth`` result replaces it.
"""

import math
import re

from phongfx.explore.synth.flatten import flatten

__all__ = ["DSP_LUT_EQ", "LUT4_WEIGHTS", "RESOURCE_MARGIN", "FEATURES", "AREA_COEFFICIENTS", "proxy_cost", "proxy_area", "proxy_estimate", "price",
           "rtlil_cost", "rtlil_features", "rtlil_of"]

DSP_LUT_EQ = 958
#: LUT4 sites per counted bit (:func:`rtlil_cost`'s ``lut4``): the logic and carry bits of
#: the RTL over-count what Yosys keeps (it trims unused high bits and folds constants), so
#: these are fitted (``phongfx tables clock --refit``, non-negative least squares of the
#: relative error) to the LUT4 sites of the ECP5 calibration runs.
LUT4_WEIGHTS = {"lut": 0.396, "carry_bits": 0.745}
#: The largest relative error of :func:`rtlil_cost`'s ``lut4`` and ``dsp`` against ECP5
#: synthesis (``|synthesized / proxy - 1|``, the LUT4 sites as nextpnr counts them: LUT4
#: cells and two per CCU2C carry cell) over the calibration runs of ``phongfx tables
#: clock`` of 1,000 LUT4 sites or more: the margin a device fit keeps around the counts.  The
#: whole shaders set it (two Phong copies: 42 DSPs synthesized, 36 counted; Figure 7 holding
#: two lights at interval 2: 2,331 LUT4 sites against 1,801).
RESOURCE_MARGIN = {"lut4": 0.30, "dsp": 0.17}
#: The bit counts :func:`rtlil_features` returns, in the order of the coefficients.
FEATURES = ("mul_bits", "add_bits", "cmp_bits", "mux_bits", "logic_bits", "rom_bits", "ff_bits")
#: µm² per bit of each feature on each library, fitted by
#: :func:`phongfx.explore.tables.proxy.fit` to the standard-cell flow (``phongfx tables proxy``).
#: The fit puts the area on multipliers, registers and multiplexers (now that the copies
#: of an expression Amaranth writes out again count once, as Yosys merges them); adders
#: and comparators as the RTL writes them predict little, since Yosys trims the unused
#: bits of wide intermediate results, so the non-negative fit gives them 0.
AREA_COEFFICIENTS = {
    "osu018": {"mul_bits": 166.6, "add_bits": 0.0, "cmp_bits": 0.0, "mux_bits": 47.2, "logic_bits": 0.0,
               "rom_bits": 8.5, "ff_bits": 182.5},
}
# The OSU cells are drawn to scalable (lambda) rules, so every osu035 cell is 4 times its
# osu018 twin in area and the same design maps to 4.0 times the area (measured: fig7
# 6,463,444 against 1,615,889 µm², fig8 5,461,076 against 1,365,269).
AREA_COEFFICIENTS["osu035"] = {k: 4 * v for k, v in AREA_COEFFICIENTS["osu018"].items()}
# IHP SG13G2 (130 nm), typical corner, by the name inside its Liberty file: fitted on every
# registry block but the Figure 5 datapath and the whole shader (10 to 40 minutes each to
# synthesize), at their defaults, and fig7 and fig8 at vec_frac 7 (19 points; largest error
# 9.2% on the datapaths, 21.8% over all).  The slow and fast files give every cell the same
# area, so they take the same coefficients.
AREA_COEFFICIENTS["sg13g2_stdcell_typ_1p20V_25C"] = {
    "mul_bits": 46.3, "add_bits": 2.2, "cmp_bits": 0.0, "mux_bits": 18.0, "logic_bits": 158.4, "rom_bits": 2.4,
    "ff_bits": 73.2}
for _corner in ("slow_1p08V_125C", "fast_1p32V_m40C"):
    AREA_COEFFICIENTS[f"sg13g2_stdcell_{_corner}"] = AREA_COEFFICIENTS["sg13g2_stdcell_typ_1p20V_25C"]
_CONST = re.compile(r"^\d+'[01xz-]+$")
_ADD = {"$add", "$sub", "$neg", "$lt", "$le", "$gt", "$ge", "$eq", "$ne", "$alu"}
_LOGIC = {"$and", "$or", "$xor", "$xnor", "$not", "$logic_and", "$logic_or", "$logic_not"}
_SHIFT = {"$shl", "$shr", "$sshl", "$sshr", "$shift", "$shiftx"}


def _cells(text):
    """(type, parameters, connections) of every distinct cell of the flattened design
    (:func:`~phongfx.explore.synth.flatten.flatten`): cells of one type with the same
    parameters and the same drivers count once, to a fixpoint, as Yosys' ``flatten`` and
    ``opt_merge`` leave them; a connection is its constant text, or ``""`` when not constant."""
    netlist = flatten(text)
    for index in netlist.merged():
        node = netlist.nodes[index]
        if node.type.startswith("$") and node.type != "$process":
            yield node.type, node.params, {port: netlist.literal(bits) or "" for port, bits in node.inputs.items()}


def _int(params, name, default=0):
    value = params.get(name)
    return int(value) if value is not None and value.lstrip("-").isdigit() else default


def _ones(literal):
    return literal.split("'", 1)[1].count("1")


def _tiles(width):
    """18-bit slices of an operand that go to a DSP: Yosys' ``mul2dsp`` leaves a slice
    narrower than 2 bits (``DSP_A_MINWIDTH``) to logic."""
    return width // 18 + (width % 18 >= 2)


def _parts(text):
    """``(kind, amounts)`` of every distinct cell of RTLIL ``text``, in the terms both
    prices use: ``("mul", a, b)`` a variable multiplier; ``("add", bits)`` an adder (a
    constant multiply as its shift-and-add adders); ``("cmp", bits)``; ``("mux", bits)`` (a
    variable shift as its multiplexers); ``("logic", bits)``; ``("reduce", input bits)``;
    ``("rom", word bits, address bits)``; ``("ff", bits)``."""
    for kind, params, conns in _cells(text):
        a, b, y = _int(params, "A_WIDTH"), _int(params, "B_WIDTH"), _int(params, "Y_WIDTH")
        const_a, const_b = (bool(_CONST.match(conns.get(p, ""))) for p in ("A", "B"))
        if kind == "$mul":
            if const_a or const_b:
                literal, other = (conns["A"], b) if const_a else (conns["B"], a)
                yield "add", max(_ones(literal) - 1, 0) * other
            else:
                yield "mul", a, b
        elif kind in ("$add", "$sub", "$neg", "$alu"):
            yield "add", y
        elif kind in _ADD:
            yield "cmp", max(a, b, 1)
        elif kind in ("$mux", "$bmux"):
            yield "mux", _int(params, "WIDTH")
        elif kind == "$pmux":
            yield "mux", _int(params, "WIDTH") * _int(params, "S_WIDTH", 1)
        elif kind in _SHIFT:
            yield "mux", 0 if const_b else y * min(b, max(y, 2).bit_length())
        elif kind in _LOGIC:
            yield "logic", y
        elif kind.startswith("$reduce"):
            yield "reduce", a
        elif kind in ("$memrd_v2", "$memrd"):
            yield "rom", _int(params, "WIDTH"), _int(params, "ABITS")
        elif kind.endswith("dff") or kind.endswith("dffe"):
            yield "ff", _int(params, "WIDTH")


def rtlil_features(text):
    """Bit counts of RTLIL ``text`` by kind of hardware, what an area model prices:
    ``mul_bits`` (Σ a·b over variable×variable multipliers: their partial products),
    ``add_bits`` (adders, subtracters, shift-and-add constant multiplies), ``cmp_bits``
    (comparators), ``mux_bits`` (multiplexers, variable shifts), ``logic_bits``
    (bitwise logic and reductions), ``rom_bits`` (words × bits of every ROM) and
    ``ff_bits`` (registers)."""
    f = dict.fromkeys(FEATURES, 0)
    for kind, *n in _parts(text):
        if kind == "mul":
            f["mul_bits"] += n[0] * n[1]
        elif kind == "rom":
            f["rom_bits"] += n[0] * 2 ** n[1]
        else:
            f["logic_bits" if kind == "reduce" else f"{kind}_bits"] += n[0]
    return f


def rtlil_cost(text):
    """``{lut_eq, lut, dsp, carry_bits, ff_bits, lut4}`` of RTLIL ``text`` (module docstring);
    ``lut4`` estimates the LUT4 sites the design fills on ECP5, logic and carry alike (a
    CCU2C carry cell fills two sites for two bits), what a part's ``lut4`` capacity counts
    (:func:`~phongfx.explore.synth.fpga.device_resources`): the logic and carry bits
    weighted by :data:`LUT4_WEIGHTS`."""
    lut = dsp = carry = ff = 0
    for kind, *n in _parts(text):
        if kind == "mul":
            dsp += _tiles(n[0]) * _tiles(n[1])
        elif kind in ("add", "cmp"):
            carry += n[0]
        elif kind in ("mux", "logic"):
            lut += n[0]
        elif kind == "reduce":
            lut += math.ceil(n[0] / 4)
        elif kind == "rom":
            lut += n[0] * math.ceil(2 ** n[1] / 16)
        else:
            ff += n[0]
    return {"lut_eq": lut + DSP_LUT_EQ * dsp, "lut": lut, "dsp": dsp, "carry_bits": carry, "ff_bits": ff,
            "lut4": round(LUT4_WEIGHTS["lut"] * lut + LUT4_WEIGHTS["carry_bits"] * carry)}


def _coefficients(library):
    from phongfx.explore.synth.asic import is_liberty_path, library_name

    name = library_name(library) if is_liberty_path(library) else library
    if name not in AREA_COEFFICIENTS:
        where = "" if name == library else f" (Liberty file {library})"
        raise ValueError(f"library must be one of {', '.join(map(repr, AREA_COEFFICIENTS))}, not {name!r}"
                         + (f"{where}: fit its area proxy with `phongfx tables proxy --liberty FILE --refit`"
                            if where else ""))
    return AREA_COEFFICIENTS[name]


def price(features, library="osu018"):
    """µm² of :func:`rtlil_features` ``features`` on ``library`` (:data:`AREA_COEFFICIENTS`)."""
    coefficients = _coefficients(library)
    return float(sum(coefficients[k] * features[k] for k in FEATURES))


def proxy_area(block, library="osu018"):
    """Estimated standard-cell area (µm²) of ``block`` on ``library``: the
    :func:`rtlil_features` priced by :data:`AREA_COEFFICIENTS`, fitted to the real flow
    (:mod:`phongfx.explore.synth.asic`) over the registry's blocks."""
    _coefficients(library)  # a bad library is refused before the elaboration
    return price(rtlil_features(rtlil_of(block)), library)


def proxy_estimate(block, target, library=None):
    """The tool-free cost of ``block`` on ``target`` as the compiler and the sweeps record
    it: ``{"area_um2"}`` on ``"asic"`` (``library``, default ``osu018``), else
    :func:`proxy_cost`'s ``lut_eq`` with its parts; ``model`` says it is a proxy.  Kept per
    design identity (:func:`~phongfx.explore.synth.estimates.cached_estimate`), so a known
    design is priced without being elaborated."""
    from phongfx.explore.synth.estimates import cached_estimate

    if target == "asic":
        from phongfx.explore.synth.asic import is_liberty_path, library_name

        library = library_name(library) if is_liberty_path(library) else (library or "osu018")
        _coefficients(library)  # a bad library is refused before anything is cached
        return cached_estimate("area", block, target, library,
                               lambda: {"area_um2": proxy_area(block, library), "model": "asic-proxy"})
    return cached_estimate("area", block, target, None, lambda: {**proxy_cost(block), "model": f"{target}-proxy"})


def rtlil_of(block):
    """The RTLIL the flows synthesize for ``block`` (without the simulation-only overflow
    flags), as the proxies were fitted on: :func:`~phongfx.explore.synth.toolrun.design_rtlil`,
    which the clock proxy of a design without DSP mapping reads too."""
    from phongfx.explore.synth.toolrun import design_rtlil

    return design_rtlil(block, "top")


def proxy_cost(block):
    """:func:`rtlil_cost` of ``block``'s component (a :class:`~phongfx.core.registry.Block`)."""
    return rtlil_cost(rtlil_of(block))
