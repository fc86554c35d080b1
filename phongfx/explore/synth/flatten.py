"""RTLIL text flattened into one word-level :class:`~phongfx.explore.synth.netgraph.Netlist`,
in Python, as Yosys' ``flatten`` would see it: what both tool-free proxies read.

Amaranth writes one RTLIL module per elaborated instance, joined by cells named after
the modules, and ``process`` blocks for its comb assignments and the register resets.
:func:`flatten` parses that text and

* splices every instance into its parent, joining wires bit by bit (a union-find over
  bits, so that slices, concatenations and ``connect`` statements all become aliases);
* turns each ``process`` into aliases where an output bit has one non-constant source
  (a register's synchronous reset, which Yosys folds into the flip-flop, is no logic)
  and into one ``$process`` multiplexer per output wire otherwise;
* keeps every other cell as a :class:`Node` whose inputs name the nodes that drive them.
"""

import re
from dataclasses import dataclass

from phongfx.explore.synth.netgraph import Netlist

__all__ = ["Node", "flatten", "REGISTERS"]

#: Cell types whose output is a register (the graph's sources and sinks).
REGISTERS = ("$dff", "$dffe", "$sdff", "$sdffe", "$adff", "$adffe", "$dffsr", "$dffsre", "$aldff", "$aldffe")
_OUTPUTS = {"Y", "Q", "X", "CO"}
_CONST = re.compile(r"^(\d+)'([01xzm-]*)$")
_SLICE = re.compile(r"^\[(\d+)(?::(\d+))?\]$")
_ZERO, _ONE, _UNDEF = 0, 1, 2  # the bit ids of the constants


@dataclass
class Node:
    """One cell of the flattened design: ``type`` (``$add``, ``MULT18X18D``, ``$process``
    ...), hierarchical ``name`` (the wire its output drives where that has a name, else
    the cell's), ``params``, and per port its bit ids (``inputs``,
    ``outputs``); ``register`` when its outputs come from a clock edge."""

    type: str
    name: str
    params: dict
    inputs: dict
    outputs: dict
    register: bool = False


class _Module:
    def __init__(self, name):
        self.name, self.wires, self.cells, self.connects, self.processes, self.ports = name, {}, [], [], [], []


def _parse(text):
    """``{name: _Module}`` of RTLIL ``text``; a process is kept as its lines."""
    modules, module, cell, process = {}, None, None, None
    for line in text.splitlines():
        words = line.split()
        if not words or words[0] == "attribute":
            continue
        head = words[0]
        if process is not None:
            if head == "end" and process[1] == 0:
                module.processes.append(process[0])
                process = None
            else:
                process[1] += {"switch": 1, "end": -1}.get(head, 0)
                process[0].append(words)
        elif cell is not None:
            if head == "parameter":
                cell[2][words[1].lstrip("\\")] = " ".join(words[2:])
            elif head == "connect":
                cell[3][words[1].lstrip("\\")] = words[2:]
            elif head == "end":
                module.cells.append(cell)
                cell = None
        elif head == "module":
            module = modules[words[1]] = _Module(words[1])
        elif head == "wire":
            width = int(words[words.index("width") + 1]) if "width" in words else 1
            module.wires[words[-1]] = width
            if "input" in words or "output" in words:
                module.ports.append((words[-1], "input" in words))
        elif head == "cell":
            cell = [words[1], words[2], {}, {}]
        elif head == "process":
            process = [[], 0]
        elif head == "connect":
            module.connects.append(words[1:])
    return modules


class _Flattener:
    def __init__(self, modules):
        self.modules, self.parent, self.nodes, self.aliases = modules, [0, 1, 2], [], []

    def find(self, bit):
        parent = self.parent
        while parent[bit] != bit:
            parent[bit] = parent[parent[bit]]
            bit = parent[bit]
        return bit

    def union(self, a, b):
        a, b = self.find(a), self.find(b)
        if a != b:
            if a < 3:  # a constant stays its set's root
                a, b = b, a
            self.parent[a] = b

    def wires(self, module):
        base = {}
        for name, width in module.wires.items():
            base[name] = len(self.parent)
            self.parent.extend(range(len(self.parent), len(self.parent) + width))
        return base

    def bits(self, words, base, widths):
        """Bit ids (LSB first) of a sigspec given as its words."""
        parts, i = [], 0
        while i < len(words):
            word = words[i]
            i += 1
            if word in ("{", "}"):
                continue
            match = _CONST.match(word)
            if match:
                parts.append([{"0": _ZERO, "1": _ONE}.get(c, _UNDEF) for c in reversed(match.group(2))])
                continue
            if word.lstrip("-").isdigit():  # a plain integer: 32 bits
                parts.append([(int(word) >> k) & 1 for k in range(32)])
                continue
            start, width = base[word], widths[word]
            bits = list(range(start, start + width))
            if i < len(words) and _SLICE.match(words[i]):
                hi, lo = _SLICE.match(words[i]).groups()
                lo = hi if lo is None else lo
                bits = bits[int(lo):int(hi) + 1]
                i += 1
            parts.append(bits)
        return [bit for part in reversed(parts) for bit in part]

    def instance(self, module, prefix):
        base = self.wires(module)
        sig = lambda words: self.bits(words, base, module.wires)  # noqa: E731
        for lhs, rhs in map(_split_assign, module.connects):
            for a, b in zip(sig(lhs), sig(rhs)):
                self.union(a, b)
        for kind, name, params, conns in module.cells:
            child = self.modules.get(kind)
            if child is not None:
                inner = self.instance(child, f"{prefix}{name.lstrip(chr(92))}.")
                for port, words in conns.items():
                    for a, b in zip(inner[port], sig(words)):
                        self.union(a, b)
                continue
            if kind.startswith("$mem") and not kind.startswith("$memrd"):
                params = {**params, "_node": "init"}  # a ROM's contents: read through its $memrd
            outputs = _output_ports(kind, params, conns)
            named = [w[0] for p, w in conns.items() if p in outputs and w and w[0].startswith("\\")]
            node = Node(kind, prefix + (named[0] if named else name).lstrip("\\$"), params,
                        {p: sig(w) for p, w in conns.items() if p not in outputs},
                        {p: sig(w) for p, w in conns.items() if p in outputs},
                        register=_is_register(kind, params))
            self.nodes.append(node)
        for lines in module.processes:
            self.process(lines, sig, prefix)
        return {name.lstrip("\\"): list(range(base[name], base[name] + module.wires[name]))
                for name, _ in module.ports}

    def process(self, lines, sig, prefix):
        """Aliases, or one ``$process`` mux node per output wire (module docstring)."""
        stack, sources, conds = [], {}, {}
        for words in lines:
            if words[0] == "switch":
                stack.append(words[1:])
            elif words[0] == "end" and stack:
                stack.pop()
            elif words[0] == "assign":
                split = _split_assign(words[1:])
                lhs, rhs = sig(split[0]), sig(split[1])
                reset = all(s == ["\\rst", "[0]"] for s in stack)
                for a, b in zip(lhs, rhs):
                    if reset and stack and b < 3:
                        continue
                    sources.setdefault(a, []).append(b)
                    for s in stack:
                        if s != ["\\rst", "[0]"]:
                            conds.setdefault(a, set()).update(sig(s))
        groups = {}
        for bit, srcs in sources.items():
            distinct = list(dict.fromkeys(s for s in srcs if s >= 3)) or srcs[-1:]
            if len(distinct) == 1 and not conds.get(bit):
                self.aliases.append((bit, distinct[0]))
            else:
                groups.setdefault(frozenset(conds.get(bit, ())), []).append((bit, distinct))
        for index, (cond, members) in enumerate(groups.items()):
            cases = max(len(d) for _, d in members)
            self.nodes.append(Node("$process", f"{prefix}process{len(self.nodes)}.{index}",
                                   {"WIDTH": str(len(members)), "CASES": str(cases)},
                                   {"S": sorted(cond), "D": [s for _, d in members for s in d]},
                                   {"Y": [bit for bit, _ in members]}))


def _split_assign(words):
    """The lhs and rhs words of an ``assign``/``connect`` (each a sigspec of one or more words)."""
    depth = 0
    for i, word in enumerate(words):
        depth += (word == "{") - (word == "}")
        if depth == 0 and not (i + 1 < len(words) and _SLICE.match(words[i + 1])):
            return words[:i + 1], words[i + 1:]
    raise ValueError(f"cannot split {' '.join(words)!r} into two sigspecs")


def _output_ports(kind, params, conns):
    if kind.startswith("$memrd"):
        return {"DATA"}
    if kind.startswith("$"):
        return _OUTPUTS & set(conns)
    # a vendor primitive: the ECP5 DSP's product and cascade outputs
    return {p for p in conns if re.match(r"^(P|RO|SRO|SIGNEDP)", p)}


def _is_register(kind, params):
    if kind in REGISTERS:
        return True
    if kind.startswith("$memrd"):
        return params.get("CLK_ENABLE", "0").strip() == "1"
    return False


def flatten(text, top=None):
    """The :class:`Netlist` of RTLIL ``text`` flattened from module ``top`` (default: the
    module no other instantiates)."""
    modules = _parse(text)
    if top is None:
        used = {cell[0] for module in modules.values() for cell in module.cells}
        tops = [name for name in modules if name not in used]
        if len(tops) != 1:
            raise ValueError(f"RTLIL must have one top module, not {len(tops)} ({', '.join(tops)})")
        top = tops[0]
    flat = _Flattener(modules)
    ports = flat.instance(modules[top], "")
    for a, b in flat.aliases:
        flat.union(a, b)
    root = [flat.find(bit) for bit in range(len(flat.parent))]
    driver = {}
    for index, node in enumerate(flat.nodes):
        for bits in node.outputs.values():
            for i, bit in enumerate(bits):
                if root[bit] >= 3:
                    driver[root[bit]] = (index, i)
    directions = {name.lstrip("\\"): is_input for name, is_input in modules[top].ports}
    inputs = [bit for name, bits in ports.items() if directions[name] for bit in bits]
    outputs = {name: bits for name, bits in ports.items() if not directions[name]}
    return Netlist(flat.nodes, driver, inputs, outputs, root)
