"""Explicit operand widths in the Verilog Yosys writes, so that lint has nothing to say.

Yosys' ``write_verilog`` prints each cell as one ``assign`` whose operands keep their own
widths (``assign \\$6 = \\$5 + 15'h4000;`` with a 33-bit ``\\$5``) and leaves the rest to
Verilog's rules (IEEE 1364-2005 §5.4, §5.5): the operands of an arithmetic, bitwise or
conditional operator are extended to the widest of them and the assignment's target,
those of a comparison to the wider of the two, the shifted operand of a shift to its
target's width, by sign bits if every such operand is signed and by zeros otherwise.  The
result is right and Verilator warns on every one of them (``WIDTHEXPAND``).

:func:`explicit_widths` writes those extensions out: a constant at the width it is used
at (``33'h000004000``), a signed operand as ``$signed({ {k{msb}}, x })``, an unsigned
one as ``{ k'h0, x }``, and ``!`` of a vector as ``~|`` (the same bit; Verilator reads
``!`` of a vector as a truncation).  Each expression computes the same bits as before:
only what the rules above did implicitly is now in the text (a Yosys equivalence check
of every block's top, ``tests/hdl/test_lint_verilog.py``, proves it).  A line it cannot
read whole is left as it was.
"""

import re

__all__ = ["explicit_widths"]

_ATTRIBUTE = r"\(\*(?:[^*]|\*(?!\)))*\*\)"
_TOKEN = re.compile(r"""\s*(?:
    (?P<attr>""" + _ATTRIBUTE + r""")
  | (?P<signed>\$signed\()
  | (?P<const>\d+'s?[bhdo][0-9a-fA-FxXzZ?_]+)
  | (?P<name>(?:\\\S+\ |[A-Za-z_][\w$]*)(?:\ ?\[\d+(?::\d+)?\])?)
  | (?P<concat>\{[^{}]*\})
  | (?P<op>===|!==|<<<|>>>|<<|>>|<=|>=|==|!=|&&|\|\||~&|~\||~\^|\^~|[-+*/%&|^~!<>?:)])
)""", re.X)
_NAME = re.compile(r"(\\\S+ |[A-Za-z_][\w$]*)(?:\[(\d+)(?::(\d+))?\])?\s*$")
_DECLARATION = re.compile(r"^\s*(?:" + _ATTRIBUTE + r"\s*)*(?:input|output|inout|wire|reg)\s+(?:signed\s+)?"
                          r"(?:\[(\d+):(\d+)\]\s*)?(\\\S+ |[A-Za-z_][\w$]*)\s*(\[|;|=)")
_ASSIGN = re.compile(r"^(\s*assign )(.+?) = (.*);$")
_DIGITS = {"b": 1, "o": 3, "h": 4}

#: Operators whose operands are extended to the widest of them and the target.
_ARITHMETIC = ("+", "-", "*", "/", "%", "&", "|", "^", "~^", "^~")
#: Operators whose operands are extended to the wider of the two; the result is one bit.
_COMPARISON = ("<", "<=", ">", ">=", "==", "!=", "===", "!==")
_SHIFT = ("<<", ">>", "<<<", ">>>")


class _Unreadable(Exception):
    """A line outside the forms Yosys writes for a cell: left as it is."""


def _tokens(text):
    tokens, position = [], 0
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None:
            if text[position:].strip():
                raise _Unreadable(text)
            break
        kind = match.lastgroup
        tokens.append((kind, match.group(kind), match.start(kind), match.end()))
        position = match.end()
    return tokens


def _bits(constant):
    """The bits of a sized constant, MSB first, as a string of 0, 1, x, z."""
    size, _, rest = constant.partition("'")
    size = int(size)
    base, digits = rest.lstrip("s")[0].lower(), rest.lstrip("s")[1:].replace("_", "").lower()
    if base == "d":
        if not digits.isdigit():
            raise _Unreadable(constant)
        bits = format(int(digits), "b")
    else:
        step = _DIGITS[base]
        bits = "".join(d * step if d in "xz?" else format(int(d, 16), f"0{step}b") for d in digits)
    bits = bits.replace("?", "z")
    return (bits[0] * size + bits)[-size:] if bits[0] in "xz" else bits.rjust(size, "0")[-size:]


class _Operand:
    """One operand of a cell's expression: its text span, signal, width, signedness."""

    def __init__(self, tokens, widths, msbs):
        self.start, self.end = tokens[0][2], tokens[-1][3]
        self.signed = tokens[0][0] == "signed"
        signal = tokens[1] if self.signed else tokens[0]
        if self.signed and (len(tokens) != 3 or tokens[2][1] != ")"):
            raise _Unreadable(tokens)
        if not self.signed and len(tokens) != 1:
            raise _Unreadable(tokens)
        self.kind, self.text = signal[0], signal[1]
        if self.kind not in ("const", "name", "concat"):
            raise _Unreadable(tokens)
        self.width, self.msb = self._shape(self.kind, self.text, widths, msbs)

    @staticmethod
    def _shape(kind, text, widths, msbs):
        if kind == "const":
            return int(text.partition("'")[0]), None
        if kind == "name":
            # an escaped name ends at white space: written with one, whatever follows
            match = _NAME.match(text + " " if text.startswith("\\") else text)
            if match is None:
                raise _Unreadable(text)
            base, high, low = match.groups()
            if high is not None:
                return (1 if low is None else int(high) - int(low) + 1), f"{base}[{high}]"
            if base not in widths:
                raise _Unreadable(text)
            return widths[base], msbs[base]
        parts = [part.strip() for part in text[1:-1].split(",")]
        shapes = [_Operand._shape("const" if re.match(r"\d+'", part) else "name", part, widths, msbs)
                  for part in parts]
        first = parts[0]
        msb = shapes[0][1]
        if msb is None:  # a constant first: its top bit
            msb = f"1'b{_bits(first)[0]}"
        return sum(width for width, _ in shapes), msb

    def extended(self, width, signed):
        """The operand's text at ``width`` bits, in an expression that is ``signed`` or not."""
        extra = width - self.width
        if extra <= 0:
            return None
        sign = signed and self.signed
        if self.kind == "const":
            bits = _bits(self.text)
            bits = (bits[0] if sign else "0") * extra + bits
            if set(bits) <= {"0", "1"}:
                text = f"{width}'h{int(bits, 2):0{(width + 3) // 4}x}"
            else:
                text = f"{width}'b{bits}"
            return f"$signed({text})" if sign else text
        if sign:
            pad = self.msb if extra == 1 else f"{{{extra}{{{self.msb}}}}}"
            return f"$signed({{ {pad}, {self.text.rstrip()} }})"
        return f"{{ {extra}'h0, {self.text.rstrip()} }}"


def _split(tokens):
    """Tokens as ``[operand tokens | operator token | attribute token]``."""
    items, k = [], 0
    while k < len(tokens):
        kind = tokens[k][0]
        if kind == "signed":
            items.append(("operand", tokens[k:k + 3]))
            k += 3
        elif kind in ("const", "name", "concat"):
            items.append(("operand", tokens[k:k + 1]))
            k += 1
        else:
            items.append((kind, tokens[k]))
            k += 1
    return [item for item in items if item[0] != "attr"]


def _rewrite(target, expression, widths, msbs):
    """``expression`` (an assignment's right-hand side to ``target``) with explicit widths."""
    items = _split(_tokens(expression))
    shape = tuple(kind if kind == "operand" else token[1] for kind, token in items)
    operand = [(_Operand(token, widths, msbs) if kind == "operand" else None) for kind, token in items]
    target_width = _Operand(_split(_tokens(target))[0][1], widths, msbs).width
    edits = []  # (start, end, new text) in expression

    def extend(operands, width):
        signed = all(o.signed for o in operands)
        for o in operands:
            text = o.extended(width, signed)
            if text is not None:
                edits.append((o.start, o.end, text))

    if len(shape) == 3 and shape[0] == shape[2] == "operand":
        a, b, op = operand[0], operand[2], shape[1]
        if op in _ARITHMETIC:
            extend([a, b], max(a.width, b.width, target_width))
        elif op in _COMPARISON:
            extend([a, b], max(a.width, b.width))
        elif op in _SHIFT:
            extend([a], max(a.width, target_width))
    elif len(shape) == 2 and shape[1] == "operand":
        a, op = operand[1], shape[0]
        if op in ("-", "~", "+"):
            extend([a], max(a.width, target_width))
        elif op == "!" and a.width > 1:
            token = items[0][1]
            edits.append((token[2], token[2] + 1, "~|"))
    elif shape == ("operand", "?", "operand", ":", "operand"):
        b, c = operand[2], operand[4]
        extend([b, c], max(b.width, c.width, target_width))
    for start, end, text in sorted(edits, reverse=True):
        expression = expression[:start] + text + expression[end:]
    return expression


def _module_shapes(lines):
    """``({name: width}, {name: text of its MSB})`` of the signals declared in ``lines``."""
    widths, msbs = {}, {}
    for line in lines:
        match = _DECLARATION.match(line)
        if match is None:
            continue
        high, low, name, after = match.groups()
        if after == "[":  # a memory: its words are read by index, which is left alone
            continue
        if high is None:
            widths[name], msbs[name] = 1, name.rstrip() + (" " if name.startswith("\\") else "")
        else:
            widths[name] = abs(int(high) - int(low)) + 1
            msbs[name] = f"{name}[{high}]"
    # an escaped name is written with its trailing space; a plain one without
    return widths, msbs


def explicit_widths(text):
    """``text`` (Yosys ``write_verilog`` output) with every operand extension written out
    (see the module docstring); a line outside the forms Yosys writes is left as it is."""
    out, module = [], []

    def flush():
        widths, msbs = _module_shapes(module)
        for line in module:
            body = line.rstrip("\n")
            match = _ASSIGN.match(body)
            if match is not None:
                head, target, expression = match.groups()
                try:
                    line = f"{head}{target} = {_rewrite(target, expression, widths, msbs)};" + line[len(body):]
                except _Unreadable:
                    pass
            out.append(line)
        module.clear()

    for line in text.splitlines(keepends=True):
        module.append(line)
        if line.startswith("endmodule"):
            flush()
    flush()
    return "".join(out)
