"""Every registered block under back-pressure and a mid-stream reset.

A block passes the harness back to back; inside :class:`~phongfx.hdl.handshake.Handshake`
it must also hold a stalled output, move only when the pipeline does, and come back
clean from a reset, which every block's registers (sub-blocks, tables, scanline state)
must obey.  The parametrization is :func:`~phongfx.core.registry.block_names` at
collection time, so a newly registered block is covered without editing this file.  The
default runs are modest (the whole file takes about a minute on two cores once the
Verilator builds are cached); the ``slow`` ones run longer streams, heavier stalls and
bursts of them.
"""

import numpy as np
import pytest

from phongfx.core.registry import block_names, get_block
from phongfx.sim.harness import check

NAMES = block_names()


def _reset_at(vectors, stalls, bubbles):
    """A cycle in the middle of the run: half of what the vectors should take."""
    return int(vectors * (1 / (1 - stalls) + bubbles / (1 - bubbles)) / 2)


def _sample(block, count, seed):
    """A seeded sample of ``count`` of the block's test vectors, in stimulus order."""
    every = block.stimulus(count=count, seed=seed)
    total = len(next(iter(every.values())))
    if total <= count:
        return every
    pick = np.sort(np.random.default_rng(seed).choice(total, count, replace=False))
    return {name: value[pick] for name, value in every.items()}


def _vectors(inputs):
    return len(next(iter(inputs.values())))


def _check(name, backend, inputs, stalls, bubbles, seed):
    block = get_block(name)
    vectors = _vectors(inputs)
    reset_at = _reset_at(vectors, stalls if np.ndim(stalls) == 0 else np.mean(stalls), bubbles)
    result = check(block, inputs, backend=backend, stalls=stalls, bubbles=bubbles, seed=seed,
                   reset_at=reset_at)
    assert result.ok, result.describe()
    assert result.vectors == vectors and result.stall_cycles > 0 and result.resets == 1
    if not bubbles:
        # back to back the pipeline is full at the reset, so the re-send is exercised (with
        # bubbles it may by chance be empty: tests/sim/test_stream.py covers that case)
        assert result.resent > 0, result.describe()
    return result


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", NAMES)
def test_block_under_stalls_and_reset_fast(name):
    block = get_block(name)
    _check(name, "verilator-fast", block.stimulus(count=2000, seed=21), 0.3, 0.0, seed=21)


@pytest.mark.parametrize("name", NAMES)
def test_block_under_stalls_and_reset_amaranth(name):
    _check(name, "amaranth", _sample(get_block(name), 300, seed=22), 0.4, 0.2, seed=22)


@pytest.mark.slow
@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", NAMES)
@pytest.mark.parametrize("seed, stalls, bubbles", [
    (31, 0.7, 0.5),  # mostly stalled, mostly idle
    (32, 0.05, 0.0),  # rare stalls in a back-to-back stream
    (33, [False] * 5 + [True] * 9, 0.1),  # bursts of 9 stalled cycles
])
def test_block_long_stream_fast(name, seed, stalls, bubbles):
    block = get_block(name)
    _check(name, "verilator-fast", block.stimulus(count=100_000, seed=seed), stalls, bubbles, seed)


@pytest.mark.slow
@pytest.mark.parametrize("name", NAMES)
def test_block_long_stream_amaranth(name):
    _check(name, "amaranth", _sample(get_block(name), 3000, seed=34), 0.5, 0.3, seed=34)
