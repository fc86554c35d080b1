"""The per-cycle schedule and the stimulus, drawn with numpy a block at a time: for a given seed
the same cycles and the same codes as drawn one number at a time (the slow loops they replace)."""

import hashlib

import numpy as np
import pytest

from phongfx.core.registry import get_block
from phongfx.sim.stimulus import lengths, normalized, unit_vectors
from phongfx.sim.vectors import schedule


def one_by_one(count, bubbles, seed):
    """The schedule as it was made before: one draw per Python loop."""
    rng = np.random.default_rng(seed)
    slots = []
    for index in range(count):
        while bubbles and rng.random() < bubbles:
            slots.append(-1)
        slots.append(index)
    return np.array(slots, dtype=np.int64)


@pytest.mark.parametrize("count, bubbles", [(count, bubbles) for count in (0, 1, 2, 17, 1000, 12345)
                                            for bubbles in (0.0, 0.01, 0.25, 0.5, 0.9)]
                         + [(1, 0.999), (17, 0.999), (300, 0.999)])
def test_the_schedule_is_the_one_by_one_loops(count, bubbles):
    for seed in (0, 1, 7):
        fast = schedule(count, bubbles, seed)
        assert fast.dtype == np.int64 and np.array_equal(fast, one_by_one(count, bubbles, seed))


def test_the_schedule_of_seed_0():
    assert schedule(12, 0.25, 0).tolist() == [0, 1, -1, -1, 2, 3, 4, 5, 6, 7, 8, -1, 9, -1, 10, -1, 11]
    million = schedule(1_000_000, 0.25, 0)
    assert len(million) == 1_333_183 and int(np.count_nonzero(million < 0)) == 333_183
    assert np.array_equal(million[million >= 0], np.arange(1_000_000))
    assert schedule(5, 0.0, 3).tolist() == [0, 1, 2, 3, 4]
    with pytest.raises(ValueError, match=r"^bubbles must be a probability in 0..1 \(excluding 1\), not 1$"):
        schedule(5, 1, 0)


def test_lengths_and_normalized_are_numpys_norm_to_the_bit():
    v = np.random.default_rng(1).normal(size=(100_000, 3)) * np.array([1, 1e-3, 1e3])
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    assert np.array_equal(lengths(v), norm) and np.array_equal(normalized(v), v / norm)
    assert lengths([3.0, 4.0, 12.0]).tolist() == [13.0]
    unit = unit_vectors(1000, np.random.default_rng(2))
    assert np.allclose(lengths(unit), 1.0, rtol=0, atol=1e-15)


#: sha256 (first 16 hex digits) of each block's ``stimulus(count=20000, seed=3)``, ports in name
#: order, as drawn before the stimulus helpers were vectorised.
STIMULUS_DIGESTS = {"fig7": "9169c5bb1c65dea3", "fig8": "7e4fa3630495afba", "lirp": "18832f89f8d21abf",
                    "normalize": "d761c83f555de175", "euler": "036eff00bdcbb440",
                    "spherical": "0f3546d779756853", "blinn": "3980ff211f795a53",
                    "conventional": "eb3ae238c8a28b95", "root": "1964d0f040dbf20e", "shape": "9d0543d0ee28f49f"}


@pytest.mark.parametrize("name", STIMULUS_DIGESTS)
def test_the_stimulus_of_a_seed_is_unchanged(name):
    raw = get_block(name).stimulus(count=20000, seed=3)
    digest = hashlib.sha256()
    for port in sorted(raw):
        digest.update(port.encode())
        digest.update(np.ascontiguousarray(raw[port]).tobytes())
    assert digest.hexdigest()[:16] == STIMULUS_DIGESTS[name]


def test_an_interval_spaces_the_vectors():
    # interval 3: two bubbles after every vector, on top of the drawn ones
    assert schedule(4, 0.0, 0, interval=3).tolist() == [0, -1, -1, 1, -1, -1, 2, -1, -1, 3, -1, -1]
    drawn = schedule(12, 0.25, 0)
    spaced = schedule(12, 0.25, 0, interval=2)
    assert len(spaced) == len(drawn) + 12 and spaced[spaced >= 0].tolist() == list(range(12))
    assert spaced[:8].tolist() == [0, -1, 1, -1, -1, -1, 2, -1]
