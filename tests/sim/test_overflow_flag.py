"""RTL overflow assertions, so that an overflow the golden model did not predict is never
silent: an ``overflow="error"`` quantize that meets a value out of its format raises the
block's ``overflow`` field, and the harness reports it on every back end, at the cycle of
the output it belongs to, never on an idle cycle."""

import dataclasses

import numpy as np
import pytest

from phongfx.config import LirpConfig
from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.hdl.block import OVERFLOW, checked_outputs
from phongfx.hdl.fixed import FixedValue
from phongfx.hdl.lirp import Lirp
from phongfx.hdl.overflow import overflow_checks
from phongfx.sim.harness import BACKENDS, check

LIRP = get_block("lirp")
#: holds only [0, 1): a negative ``N0·(1 - a)`` overflows it
UNSIGNED = Format(1, 20, signed=False)


class StrictLirp(Lirp):
    """The LIRP, plus a check the golden model does not make: ``N0_x·(1 - a)`` must be
    non-negative.  Its result is unused, so the payload stays the golden one; only the
    overflow field can differ."""

    def datapath(self, m, i):
        b = (FixedValue.const(1, self.config.a) - i["a"]).quantize(self.config.a, "truncate", "error")
        (i["n0"][0] * b).quantize(UNSIGNED, "truncate", "error")
        return super().datapath(m, i)


class UntaggedLirp(Lirp):
    """A block without cycle tags that quantizes with "error" without tagging the value."""

    cycle_tags = False


def _inputs(count=300, seed=11):
    """Seeded random unit-range end normals and positions ``a`` in 0..1."""
    rng = np.random.default_rng(seed)
    one = LirpConfig().fmt("vec").exact_raw(1.0)
    a_one = LirpConfig().fmt("a").exact_raw(1.0)
    return {"n0": rng.integers(-one, one + 1, (count, 3)), "n1": rng.integers(-one, one + 1, (count, 3)),
            "a": rng.integers(0, a_one + 1, count)}


def _negative(inputs):
    """Vectors whose ``N0_x·(1 - a)`` is below 0, by the golden formats."""
    one = 1 << LirpConfig().fmt("a").frac_bits
    return np.flatnonzero(inputs["n0"][:, 0] * (one - inputs["a"]) < 0)


def test_the_payload_gains_the_flag_last():
    ports = checked_outputs(LIRP.config)
    assert list(ports) == ["n", OVERFLOW] and ports[OVERFLOW] == (Format(1, 0), 1)


@pytest.mark.parametrize("backend", BACKENDS)
def test_an_unpredicted_overflow_is_reported_at_its_output_cycle(backend):
    inputs = _inputs()
    bad = _negative(inputs)
    assert 20 < len(bad) < len(inputs["a"]) - 20  # the sample has both kinds
    block = dataclasses.replace(LIRP, component_class=StrictLirp)
    result = check(block, inputs, backend=backend, bubbles=0.3, seed=5)
    # junk payloads on idle cycles overflow too: gated by valid, they never count
    assert result.mismatch_count == len(bad)
    assert [mm.index for mm in result.mismatches] == bad[:len(result.mismatches)].tolist()
    first = result.mismatches[0]
    assert first.what == "RTL overflow that the golden model did not predict"
    assert first.got == {**first.expected, OVERFLOW: 1} and first.expected[OVERFLOW] == 0


def test_the_flag_is_not_built_for_synthesis():
    block = dataclasses.replace(LIRP, component_class=StrictLirp)
    with overflow_checks(False):
        result = check(block, _inputs(), backend="amaranth", bubbles=0.3, seed=5)
    assert result.ok


def test_an_untagged_flag_is_refused():
    block = dataclasses.replace(LIRP, component_class=UntaggedLirp)
    message = (r'^UntaggedLirp: an overflow="error" quantize has no cycle tag, so its flag cannot '
               r'be aligned with valid$')
    with pytest.raises(ValueError, match=message):
        check(block, _inputs(count=10), backend="amaranth")


def test_an_output_may_not_be_named_overflow():
    @dataclasses.dataclass(frozen=True)
    class Clash(LirpConfig):
        @property
        def outputs(self):
            return {OVERFLOW: (self.fmt("out"), 1)}

    with pytest.raises(ValueError, match=r"^an output may not be named 'overflow': the overflow "
                                         r"flag uses it$"):
        checked_outputs(Clash())
