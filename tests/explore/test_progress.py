import pytest

from phongfx.explore.progress import Candidates, describe


def test_describe_names_block_and_widths():
    assert describe("fig7") == "fig7"
    assert describe("fig7", {"vec": 10, "t": 8}) == "fig7, vec=10 t=8"


def test_candidates_count_and_time():
    now = [0.0]
    lines = []
    steps = Candidates(3, lines.append, clock=lambda: now[0])
    steps.next("fig7", {"k": 4})
    now[0] = 61.4
    stage = steps.next("fig8")
    stage("nextpnr")
    assert lines == ["synthesizing candidate 1 of 3 (fig7, k=4) 0 s",
                     "synthesizing candidate 2 of 3 (fig8) 61 s",
                     "synthesizing candidate 2 of 3 (fig8): nextpnr 61 s"]


def test_total_must_be_a_count():
    with pytest.raises(ValueError, match=r"^total must be a non-negative integer, not -1$"):
        Candidates(-1, print)
