"""A flattened design as one word-level graph of cells (:func:`~phongfx.explore.synth.flatten.flatten`
builds it from RTLIL), as Yosys' ``opt_merge`` would see it.

:meth:`Netlist.merged` hash-conses the nodes: two cells of one type with the same
parameters and the same (merged) drivers on every input are one cell (the operands of
a commutative cell in either order), repeated to a fixpoint, since a merge upstream makes
cells downstream identical: a shader whose light copies take the same inputs shares the
logic that depends on those inputs only, as the synthesized netlist does.

:meth:`Netlist.sources`, :meth:`Netlist.fanins` and the nodes' ``register`` flag give the
register-to-register graph the clock proxy (:mod:`.clock`) walks.
"""

from dataclasses import dataclass, field

__all__ = ["Netlist", "COMMUTATIVE"]

#: Cell types whose ``A`` and ``B`` operands commute (``opt_merge`` sorts them).
COMMUTATIVE = {"$add", "$mul", "$and", "$or", "$xor", "$xnor", "$eq", "$ne", "$logic_and", "$logic_or"}


@dataclass
class Netlist:
    """The flattened design: ``nodes``; ``driver``, per root bit id, the ``(node, bit)`` that
    drives it; the top's ``inputs`` (bit ids) and ``outputs`` (port -> bit ids); ``root``,
    per bit id, the bit it is joined to (0, 1, 2: the constants 0, 1, x).  A root no node
    drives is a primary input (or undriven)."""

    nodes: list
    driver: dict
    inputs: list
    outputs: dict
    root: list
    _sources: list = field(default=None, repr=False)
    _ordered: list = field(default=None, repr=False)
    _fanins: list = field(default=None, repr=False)

    def source_bits(self, node):
        """Per input port of ``node``, the tuple of its bits' drivers: ``(node index, bit)``,
        ``("c", 0/1/2)`` for a constant, ``("in", bit)`` for a primary input."""
        return {port: tuple(self._driver(bit) for bit in bits) for port, bits in node.inputs.items()}

    def _driver(self, bit):
        root = self.root[bit]
        if root < 3:
            return ("c", root)
        return self.driver.get(root, ("in", root))

    def literal(self, bits):
        """RTLIL constant text (``4'1010``) of ``bits`` when every one is a constant, else None."""
        roots = [self.root[bit] for bit in bits]
        if any(root >= 3 for root in roots):
            return None
        return f"{len(roots)}'" + "".join("01x"[root] for root in reversed(roots))

    def sources(self, index):
        """Indices of the nodes that drive node ``index``'s inputs (primary inputs: -1)."""
        if self._sources is None:
            self._sources = [self._find_sources(i) for i in range(len(self.nodes))]
        return self._sources[index]

    def _find_sources(self, index):
        return self._drivers_of(self.nodes[index].inputs.values())

    def _drivers_of(self, ports):
        found = set()
        for bits in ports:
            for bit in bits:
                d = self._driver(bit)
                if d[0] != "c":
                    found.add(-1 if d[0] == "in" else d[0])
        return found

    def fanins(self, index):
        """``{source: fan-out}`` of node ``index``: per node driving its inputs (-1 for the
        primary inputs), the largest number of loads that one bit it drives into ``index``
        reaches: a cell per cell reading it, or the output's width for a cell it steers (a
        multiplexer's select, a register's enable: a LUT or flip-flop per bit), the design's
        outputs counting as one.  A bit driving hundreds of cells
        (a turn counter's enable, an input fanned out to every light copy) is a slow net on
        an FPGA's routing and on unbuffered standard cells alike."""
        if self._fanins is None:
            loads = [_loads(node, self.root) for node in self.nodes]
            outputs = {self.root[bit]: 1 for bits in self.outputs.values() for bit in bits if self.root[bit] >= 3}
            readers = {}
            for counts in loads + [outputs]:
                for root, count in counts.items():
                    readers[root] = readers.get(root, 0) + count
            self._fanins = []
            for counts in loads:
                fan = {}
                for root in counts:
                    d = self._driver(root)[0]  # a root is its own root
                    d = -1 if d == "in" else d
                    fan[d] = max(fan.get(d, 0), readers[root])
                self._fanins.append(fan)
        return self._fanins[index]

    def output_sources(self):
        """Indices of the nodes that drive the design's outputs (-1 for a pass-through input)."""
        return self._drivers_of(self.outputs.values())

    def merged(self):
        """Indices of the distinct nodes after hash-consing to a fixpoint (module docstring)."""
        sources = [self.source_bits(node) for node in self.nodes]
        contents = self._contents()
        order = self.order()
        canon, classes = list(range(len(self.nodes))), None
        while True:
            seen = {}
            for index in order:
                canon[index] = seen.setdefault(self._key(index, sources[index], canon, contents), index)
            if len(seen) == classes:
                return sorted(set(canon))
            classes = len(seen)

    def _key(self, index, sources, canon, contents):
        node = self.nodes[index]
        if node.type.startswith("$mem") and not node.type.startswith("$memrd"):
            return ("init", index)
        ports = {port: tuple(s if s[0] in ("c", "in") else (canon[s[0]], s[1]) for s in srcs)
                 for port, srcs in sources.items()}
        params = dict(node.params)
        if node.type in COMMUTATIVE and "B" in ports:
            a = (ports.get("A"), params.get("A_SIGNED"), params.get("A_WIDTH"))
            b = (ports["B"], params.get("B_SIGNED"), params.get("B_WIDTH"))
            if repr(b) < repr(a):
                ports["A"], params["A_SIGNED"], params["A_WIDTH"] = b
                ports["B"], params["B_SIGNED"], params["B_WIDTH"] = a
        if node.type.startswith("$memrd"):
            params["MEMID"] = contents.get((_scope(node.name), params.get("MEMID")), params.get("MEMID"))
        if node.type == "$process":
            ports["D"] = tuple(sorted(ports["D"], key=repr))
        return node.type, tuple(sorted(params.items())), tuple(sorted(ports.items()))

    def _contents(self):
        """``{(scope, MEMID): contents}`` of the ROMs: two ROMs with the same words are one."""
        return {(_scope(node.name), node.params.get("MEMID")):
                (node.params.get("WIDTH"), node.params.get("WORDS"), tuple(self.root[b] for b in node.inputs.get("DATA", ())))
                for node in self.nodes if node.type.startswith("$meminit")}

    def order(self):
        """Node indices with every combinational node after its drivers; registers first."""
        if self._ordered is not None:
            return self._ordered
        order, state = [], {}
        regs = [i for i, n in enumerate(self.nodes) if n.register]
        order.extend(regs)
        for i in regs:
            state[i] = 2
        for start in range(len(self.nodes)):
            if start in state:
                continue
            stack = [(start, iter(self.sources(start)))]
            state[start] = 1
            while stack:
                index, it = stack[-1]
                for nxt in it:
                    if nxt >= 0 and nxt not in state:
                        state[nxt] = 1
                        stack.append((nxt, iter(self.sources(nxt))))
                        break
                else:
                    stack.pop()
                    state[index] = 2
                    order.append(index)
        self._ordered = order
        return order


#: Ports whose one bit steers every bit of the cell's output (a word-level cell is one LUT,
#: gate or flip-flop enable per output bit): the bit's loads are that many.
_STEERING = {"S": ("$mux",), "EN": ("$dffe", "$sdffe", "$adffe", "$aldffe", "$dffsre")}


def _loads(node, root):
    """``{root bit: loads}`` of the data bits ``node`` reads (its clocks and constants are not):
    one per bit, the output's width for a bit that steers every output bit (a multiplexer's
    select, a register's enable); bits joined to one root count as that root once."""
    width = max((len(bits) for bits in node.outputs.values()), default=1)
    loads = {}
    for port, bits in node.inputs.items():
        if port.startswith("CLK"):  # a clock travels on its own network, not the logic's routing
            continue
        count = width if node.type in _STEERING.get(port, ()) else 1
        for bit in bits:
            if root[bit] >= 3:
                loads[root[bit]] = max(loads.get(root[bit], 0), count)
    return loads


def _scope(name):
    return name.rsplit(".", 1)[0] if "." in name else ""
