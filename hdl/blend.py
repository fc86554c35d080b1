"""Colour blend: ``out_c = clip(round(A_c + Σ_i D_ic·diff_i + S_ic·gate_i·spec_i))`` per channel,
every coefficient a constant multiplied by shifts and adds."""

from functools import cached_property

from amaranth.hdl import Signal

from phongfx.config import BlendConfig
from phongfx.config.blend import CHANNELS
from phongfx.core.format import Format

from .block import PipelinedBlock
from .constant import signed_digits
from .fixed import FixedValue, cut, quantize_cut, stage

__all__ = ["Blend", "shift_add", "adder_tree"]


def _wire(m, x, name):
    """:class:`FixedValue` ``x`` through a named combinational signal: each use of it then
    reads one net rather than a copy of its expression (RTLIL and Verilog build a cell per
    use of an expression), and the net has a name in the Verilog and in waveforms."""
    signal = Signal(x.fmt.shape(), name=name)
    m.d.comb += signal.eq(x.value)
    return FixedValue(signal, x.fmt, x.cycle, x.module, name)


def adder_tree(values):
    """The exact sum of :class:`FixedValue` ``values`` (at least one) as a balanced tree of
    two-input adders: ``ceil(log2 n)`` adders deep rather than ``n − 1``."""
    values = list(values)
    if not values:
        raise ValueError("adder_tree needs at least one value")
    while len(values) > 1:
        pairs = [a + b for a, b in zip(values[0::2], values[1::2])]
        values = pairs + values[len(pairs) * 2:]
    return values[0]


def shift_add(value, code, frac=0):
    """``value × code·2^−frac`` exactly, for an integer ``code >= 0``, as a sum and difference of
    shifted copies of ``value``: the canonical signed digits of ``code``
    (:func:`~phongfx.hdl.constant.signed_digits`, the fewest non-zero digits, so
    ``k`` digits cost ``k − 1`` adders and a power of two is wiring), positive digits summed,
    negative ones summed and subtracted, each by :func:`adder_tree`.

    Written as ``*`` by a constant, the product is a ``$mul`` cell that Yosys may map to a DSP
    (``synth_ecp5`` maps a constant multiply that is not a power of two to MULT18X18D); a
    constant product needs adders only.  The result has ``value``'s fraction bits plus
    ``frac`` and the smallest range that holds ``value``'s times ``code``; None for ``code`` 0
    (nothing to add).
    """
    if not isinstance(code, int) or isinstance(code, bool) or code < 0:
        raise ValueError(f"shift_add: code must be an integer >= 0, not {code!r}")
    if code == 0:
        return None
    digits = signed_digits(code)
    plus = adder_tree(value.shift(shift - frac) for sign, shift in digits if sign > 0)
    minus = [value.shift(shift - frac) for sign, shift in digits if sign < 0]
    total = plus - adder_tree(minus) if minus else plus
    fmt = Format.covering(value.fmt.min_raw * code, value.fmt.max_raw * code, value.fmt.frac_bits + frac)
    # the exact value lies in fmt, which has at least the sum's fraction bits: no bit is lost
    return total.quantize(fmt, "truncate", "wrap")


class Blend(PipelinedBlock):
    """The final colour blend of a shader (:class:`~phongfx.config.BlendConfig`): per channel
    the ambient constant plus each light's diffuse and specular amounts times the material's
    coefficients, rounded once to an integer code and clamped to ``2^bits − 1``.

    This is the sum Phong's model takes over the lights (Phong 1975; Lyon 1993,
    "Background"): ``ambient + Σ_lights intensity·(kd·diffuse + ks·specular)``, with ``ka``,
    ``kd``, ``ks``, the material colour and the light RGB multiplied into one constant per
    term by the scene compiler.  The display scale ``2^bits − 1`` is folded into those
    constants too (:meth:`~phongfx.config.BlendConfig.raw_code`), so the sum is in output
    levels already: one rounding to an integer, no multiplier by 255 behind it.

    **Backside test.**  With ``gate`` the specular amount of light ``i`` is multiplexed to 0
    where ``diff_i = 0``, the diffuse unit's clamp of ``N·L <= 0``: a light behind the
    surface gives no highlight (one OR of ``diff_i``'s bits and a multiplexer on the narrow
    input, before the input register from depth 1, so that the products' stage does not
    start with it).

    **Constant multiplies by shift-and-add.**  Every coefficient is a constant, so every
    product is :func:`shift_add` (canonical signed digits): adders only, no ``$mul`` cell for
    Yosys to map onto a DSP.  A zero coefficient adds nothing; equal products are built once
    (light ``i``'s diffuse times the same code in two channels is one product); channels
    and materials with the same coefficients share one adder tree (a grey scene computes
    ``r`` once and wires it to ``g`` and ``b``), and channels with the same coefficients in
    every material share the rounding, the clamp and the output register too.

    **Materials.**  With several materials each material's sum is built and ``material``
    selects one by a balanced multiplexer tree on its bits; a code ``>= materials``
    selects the last material, ``materials − 1`` (the golden model refuses such codes and
    the harness never sends them).

    Latency: ``1 + pipeline`` (depth 0: everything in one clock, the output registered;
    1 also registers the inputs; 2 also the sum before its rounding; 3 also the rounding
    before its clamp; 4 also every product, before the adder tree, and clamps by bit
    tests).

    Ports: ``i.payload`` = ``diff{i}`` (``config.diff``, unless ``""``), ``spec{i}``
    (``config.spec``) for each light, ``material`` (``config.material_format``) when there
    are several materials; ``o.payload`` = ``r``, ``g``, ``b`` (``config.out_format``).
    """

    config_class = BlendConfig

    @cached_property
    def latency(self):
        return 1 + self.config.pipeline

    def datapath(self, m, i):
        cfg, depth = self.config, self.config.pipeline
        i = dict(i)
        for k in range(cfg.lights) if cfg.gate else ():
            # gated before the input register when there is one: the OR of diff's bits and the
            # select into every bit of spec then end a short stage of their own instead of
            # leading the products' adders (on ECP5 the two-light shader's slowest path at depth 4)
            d, s = i[f"diff{k}"], i[f"spec{k}"]
            lit = d.flag(d.value.any(), f"lit{k}")
            i[f"spec{k}"] = _wire(m, s.where(lit, FixedValue.const(0, s.fmt)), f"spec{k}_lit")
        inputs = {name: cut(m, value, depth >= 1, f"{name}_in") for name, value in i.items()}
        sources = {name: inputs[name] for name in inputs if name.startswith(("diff", "spec"))}
        products = {}

        def product(port, code):
            """``sources[port]`` × coefficient ``code``, built once (None for 0)."""
            if (port, code) not in products:
                p, name = shift_add(sources[port], code, cfg.coef_frac), f"{port}_p{len(products)}"
                if p is not None:
                    p = stage(m, p, name) if depth >= 4 else _wire(m, p, name)
                products[port, code] = p
            return products[port, code]

        sums = {}

        def total(key):
            """The exact sum of the coefficient set ``key`` = (A, ((port, code), ...)), built once,
            in the smallest format that holds its largest value."""
            if key not in sums:
                a, terms = key
                frac = cfg.coef_frac + max((sources[port].fmt.frac_bits for port, _ in terms), default=0)
                hi = a << (frac - cfg.coef_frac)
                for port, code in terms:
                    source = sources[port].fmt
                    hi += code * source.max_raw << (frac - cfg.coef_frac - source.frac_bits)
                fmt = Format.covering(0, hi, frac)
                values = [product(port, code) for port, code in terms]
                if a or not values:
                    values.append(FixedValue(a, Format.covering(0, a, cfg.coef_frac)))
                sums[key] = _wire(m, adder_tree(values).quantize(fmt, "truncate", "wrap"), f"sum{len(sums)}")
            return sums[key]

        def key_of(material, channel):
            a, d, s = cfg.coefficients(material)
            terms = []
            for k in range(cfg.lights):
                if cfg.diff:
                    terms.append((f"diff{k}", d[k][channel]))
                terms.append((f"spec{k}", s[k][channel]))
            return a[channel], tuple((port, code) for port, code in terms if code)

        keys = {name: tuple(key_of(material, c) for material in range(cfg.materials))
                for c, name in enumerate(CHANNELS)}
        groups = {}
        for name in CHANNELS:
            groups.setdefault(keys[name], []).append(name)

        select = self._selector(m, inputs, total)
        sum_cycle = (depth >= 1) + (depth >= 4)
        out = {}
        for key, names in groups.items():
            label = "".join(names)
            acc = _wire(m, select(key), f"{label}_acc") if cfg.materials > 1 else select(key)
            # a constant is valid at any cycle: tagged, so that its output's is known; a sum
            # without products (only the material chose it) waits for those that have them
            acc = acc.tagged(sum_cycle, m) if acc.cycle is None else acc.at(sum_cycle)
            acc = cut(m, acc, depth >= 2, f"{label}_sum")
            code = quantize_cut(m, acc, cfg.out_format, cfg.rounding, "saturate", depth >= 3,
                                f"{label}_round", depth >= 4)
            value = stage(m, code, label)
            out.update({name: value for name in names})
        return out

    def _selector(self, m, inputs, total):
        """``select(keys)``: the sum of the pixel's material, of the per-material coefficient
        sets ``keys`` (one material: its sum)."""
        cfg = self.config
        if cfg.materials == 1:
            return lambda keys: total(keys[0])
        material = inputs["material"]
        flags = [material.flag(material.value[j], f"material_b{j}") for j in range(cfg.material_format.width)]
        widened = {}

        def common(key, fmt):
            if (key, fmt) not in widened:
                value = total(key).quantize(fmt, "truncate", "wrap")  # exact: fmt holds it
                # a constant sum is tagged (valid from cycle 0 on): a multiplexer of two untagged
                # values takes no cycle from its select, and this one selects by the material
                widened[key, fmt] = value if value.cycle is not None else value.tagged(0, m)
            return widened[key, fmt]

        def select(keys):
            formats = [total(key).fmt for key in keys]
            frac = max(f.frac_bits for f in formats)
            fmt = Format.covering(0, max(f.max_raw << (frac - f.frac_bits) for f in formats), frac)
            # codes >= materials select the last material: the padding of the multiplexer tree
            level = list(keys) + [keys[-1]] * ((1 << len(flags)) - len(keys))
            values = {key: common(key, fmt) for key in dict.fromkeys(keys)}
            level = [(key, values[key]) for key in level]
            for flag in flags:  # bit 0 first: neighbours differ in the lowest bit left
                level = [low if low[0] == high[0] else ((low[0], high[0]), high[1].where(flag, low[1]))
                         for low, high in zip(level[0::2], level[1::2])]
            return level[0][1]
        return select
