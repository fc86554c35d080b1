"""Vectors as the back ends see them: packed payload words, and the cycle each is driven.

A block's ports (``{name: (format, lanes)}``) are laid out in one payload word, field after
field (:func:`payload_fields`); :func:`pack` and :func:`unpack` convert raw codes to such words
and back, :func:`schedule` places the vectors on cycles with seeded ``valid`` bubbles.  Every
back end (:mod:`phongfx.sim.harness`, :mod:`phongfx.sim.fast_backend`) and the Verilog
testbench share them.
"""

import numpy as np

__all__ = ["payload_fields", "columns", "pack", "unpack", "row_of", "schedule"]


def payload_fields(ports):
    """(name, lane, offset, width, signed) for each payload field, in layout order."""
    offset = 0
    out = []
    for name, (fmt, lanes) in ports.items():
        for lane in range(lanes):
            out.append((name, lane if lanes > 1 else None, offset, fmt.width, fmt.signed))
            offset += fmt.width
    return out, offset


def columns(ports, raw):
    """``(column, offset, width)`` of each payload field, ``column`` the int64 codes of
    that field (one lane of a vector port); all columns must have the same length."""
    fields_, _ = payload_fields(ports)
    count = None
    for name, lane, offset, width, _ in fields_:
        column = np.asarray(raw[name], dtype=np.int64)
        column = column[:, lane] if lane is not None else column
        count = len(column) if count is None else count
        if len(column) != count:
            raise ValueError(f"input {name} has {len(column)} vectors, others have {count}")
        yield column, offset, width


def pack(ports, raw):
    """Pack raw codes ``{name: array (count,) or (count, lanes)}`` into payload integers."""
    packed = None
    for column, offset, width in columns(ports, raw):
        mask = (1 << width) - 1
        bits = [(int(v) & mask) << offset for v in column.tolist()]
        packed = bits if packed is None else [p | b for p, b in zip(packed, bits)]
    return packed


def unpack(ports, packed):
    """Inverse of :func:`pack`: payload integers to raw codes (int64 arrays)."""
    fields_, _ = payload_fields(ports)
    out = {}
    for name, (fmt, lanes) in ports.items():
        out[name] = np.zeros((len(packed), lanes) if lanes > 1 else len(packed), dtype=np.int64)
    for name, lane, offset, width, signed in fields_:
        mask = (1 << width) - 1
        values = [(p >> offset) & mask for p in packed]
        if signed:
            values = [v - (1 << width) if v >> (width - 1) else v for v in values]
        column = np.array(values, dtype=np.int64)
        if lane is None:
            out[name][:] = column
        else:
            out[name][:, lane] = column
    return out


def row_of(ports, raw, index):
    """``{name: code or [codes]}`` of vector ``index`` of ``raw``: one row of a mismatch report."""
    row = {}
    for name, (fmt, lanes) in ports.items():
        value = raw[name][index]
        row[name] = value.tolist() if lanes > 1 else int(value)
    return row


def schedule(count, bubbles, seed, interval=1):
    """Per-cycle index of the vector driven, ``-1`` for a bubble (``valid`` low).

    ``bubbles`` is the probability of a bubble before each vector (0: back to back);
    ``interval`` − 1 bubbles follow each vector, for a block that takes one every
    ``interval`` cycles (:attr:`~phongfx.hdl.block.PipelinedBlock.interval`).  Before that
    spacing, each cycle is one draw of ``numpy.random.default_rng(seed)``: below ``bubbles`` a bubble, else
    the next vector, so a vector follows a geometric number of bubbles.  The draws are made
    a block at a time (a million vectors in 20 ms rather than a second, one draw per Python
    loop); the generator's stream is the same whether its numbers are drawn one by one or in
    blocks, so the schedule of a seed is the one-by-one loop's, cycle for cycle.
    """
    if not 0 <= bubbles < 1:
        raise ValueError(f"bubbles must be a probability in 0..1 (excluding 1), not {bubbles}")
    slots = _drawn(count, bubbles, seed)
    if interval > 1:
        vector = slots >= 0
        spaced = np.full(len(slots) + (interval - 1) * count, -1, dtype=np.int64)
        spaced[np.arange(len(slots)) + (interval - 1) * (np.cumsum(vector) - vector)] = slots
        slots = spaced
    return slots


def _drawn(count, bubbles, seed):
    """:func:`schedule` at interval 1."""
    if not bubbles or not count:
        return np.arange(count, dtype=np.int64)
    rng = np.random.default_rng(seed)
    parts, placed = [], 0
    while placed < count:
        left = count - placed
        # enough draws for the vectors left, most of the time, with a margin of 6 sigma
        size = int(left / (1 - bubbles) + 6 * np.sqrt(left * bubbles) / (1 - bubbles)) + 16
        vector = rng.random(size) >= bubbles
        # the draws up to the one that places the last vector (the rest go unused)
        ends = np.flatnonzero(vector)
        if len(ends) >= left:
            vector = vector[:ends[left - 1] + 1]
        slots = np.where(vector, placed + np.cumsum(vector) - 1, -1)
        parts.append(slots)
        placed += int(np.count_nonzero(vector))
    return np.concatenate(parts).astype(np.int64)
