"""Exhaustive checks, golden against RTL on the fast back end, where the space is small.

At default widths no registry block has an input space of 2^20 codes or fewer (the
smallest, ``shape``, takes one 25-bit ``x2``: ``13.12``); the spaces below are the
largest whole ones we check:

* ``shape`` (Lyon Figure 7d), every one of the 2^25 codes of ``x2`` at the default
  k = 2 (about 11 s and 3.4 GB here), the other k in the slow run;
* the spherical unit's angle register and both ROMs: every one of the 2^12 codes of
  ``θ`` loaded by a one-pixel span (``s = 0``) with the largest ``C``, through the
  specular and diffuse channels at once;
* Schlick's unit, every ``t`` in 0..1 (2^15 + 1 codes of ``1.15``) at n = 1, 2, 16, 255
  and 8000: slices of its 2^29-code space, one per divisor range of the divider.
"""

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.sim.harness import check

pytestmark = pytest.mark.needs_verilator


def _every_x2(k):
    block = get_block("shape", k=k)
    raw = {"x2": np.arange(1 << block.config.fmt("x2").width, dtype=np.int64)}
    return block, raw


def test_shape_every_code_at_the_default_k():
    block, raw = _every_x2(2)
    result = check(block, raw, backend="verilator-fast", bubbles=0.0)
    assert result.vectors == 1 << 25
    result.raise_on_mismatch()


@pytest.mark.slow
@pytest.mark.parametrize("k", [0, 1, 3, 4])
def test_shape_every_code_at_every_k(k):
    block, raw = _every_x2(k)
    check(block, raw, backend="verilator-fast", bubbles=0.0).raise_on_mismatch()


def test_spherical_every_angle_code_through_both_roms():
    block = get_block("spherical")
    theta, c = block.config.fmt("theta"), block.config.fmt("c")
    codes = np.arange(theta.min_raw, theta.max_raw + 1, dtype=np.int64)
    count = len(codes)
    raw = {"init": np.ones(count, dtype=np.int64), "b": codes, "s": np.zeros(count, dtype=np.int64),
           "c": np.full(count, c.max_raw), "bd": codes[::-1].copy(), "sd": np.zeros(count, dtype=np.int64),
           "cd": np.full((count, 3), c.max_raw)}
    assert count == 1 << 12
    result = check(block, raw, backend="verilator-fast", bubbles=0.25, seed=3)
    result.raise_on_mismatch()
    spec = block.golden(raw)["spec"]
    # the lit half of the register (|θ| < π/2) reads nonzero words, the rest zeros
    quarter = 1 << (theta.width - 2)
    assert np.all(spec[np.abs(codes) >= quarter + (1 << (theta.width - block.config.addr_bits))] == 0)
    assert np.all(spec[np.abs(codes) < quarter - (1 << (theta.width - block.config.addr_bits))] > 0)


def test_schlick_every_t_at_several_n():
    block = get_block("schlick")
    one = block.config.fmt("t").exact_raw(1.0)
    shininess = (1, 2, 16, 255, block.config.n_max)
    t = np.tile(np.arange(one + 1, dtype=np.int64), len(shininess))
    n = np.repeat(np.array(shininess, dtype=np.int64), one + 1)
    result = check(block, {"t": t, "n": n}, backend="verilator-fast", bubbles=0.1, seed=2)
    assert result.vectors == len(shininess) * ((1 << 15) + 1)
    result.raise_on_mismatch()
    spec = block.golden({"t": t, "n": n})["spec"].reshape(len(shininess), one + 1)
    np.testing.assert_array_equal(spec[0], np.arange(one + 1))  # S_1(t) = t
    assert np.all(spec[:, -1] == one) and np.all(spec[:, 0] == 0)  # S_n(1) = 1, S_n(0) = 0
    assert np.all(np.diff(spec, axis=1) >= 0)  # monotonic in t for every n
