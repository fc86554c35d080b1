"""The branch and bound: a round's boxes bounded in halves, one by a twin of this process, give
the bounds of the whole round."""

import pytest

from phongfx.certify import branch
from phongfx.certify.bound import shader_config
from phongfx.certify.bounding import bounding
from phongfx.explore.compile import workers
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene
from tests.certify.test_bound import LYON
from tests.certify.test_table_units import LOCAL


@pytest.mark.parametrize("method, name, params, region", [
    ("fig7", "lyon-balls", LYON, 19),           # Lyon's datapaths: every box bounded alone
    ("conventional", "local-mesh", LOCAL, None),  # a table unit with a point light: its cells too
])
def test_a_round_bounded_in_halves_by_a_twin_gives_the_same_bound(monkeypatch, method, name, params, region):
    spec = load_scene(f"scenes/{name}.toml")
    where = domain(spec) if region is None else domain(spec).region(region)
    shader, how = shader_config(method, params, spec), bounding(method)
    whole = how.bound(shader, spec, where, max_boxes=20_000)
    twins = []

    class Counted(workers.Twin):
        def __init__(self, function):
            twins.append(self)
            super().__init__(function)

    monkeypatch.setattr(branch, "Twin", Counted)
    monkeypatch.setattr(branch, "spare_core", lambda: True)
    monkeypatch.setattr(branch, "TWIN_BOXES", 512)
    halved = how.bound(shader, spec, where, max_boxes=20_000)
    assert len(twins) == 1 and halved == whole


def test_a_unit_that_lists_codes_across_boxes_is_bounded_whole(monkeypatch):
    """The conventional unit with the light at infinity lists the normal codes of the boxes of
    largest bound, up to a count per round: a bound of the whole round, never halved."""
    spec = load_scene("scenes/torus.toml")
    monkeypatch.setattr(branch, "spare_core", lambda: True)
    monkeypatch.setattr(branch, "Twin", None)  # a twin would fail here
    how = bounding("conventional")
    bound, parts = how.bound(shader_config("conventional", {"vec_frac": 11, "rsqrt_addr": 8, "table_addr": 5,
                                                            "coef": 0}, spec), spec, domain(spec), max_boxes=5_000)
    assert parts["boxes"] > branch.TWIN_BOXES and bound < float("inf")


def test_the_clock_only_guards_against_a_hang_and_a_cut_certificate_says_so(monkeypatch):
    """The box budget decides where a branch and bound stops, so that a loaded machine ships the
    bound an idle one does; the clock stops only a hang, and a bound it cut is marked."""
    spec = load_scene("scenes/lyon-balls.toml")
    where = domain(spec).region(19)
    shader, how = shader_config("fig7", LYON, spec), bounding("fig7")
    assert branch.SECONDS >= 600
    bound, parts = how.bound(shader, spec, where, max_boxes=4_000)
    assert "timed_out" not in parts and parts["rounds"] > 1
    monkeypatch.setattr(branch, "SECONDS", 0.0)
    cut, cut_parts = how.bound(shader, spec, where, max_boxes=4_000)
    assert cut_parts["timed_out"] and cut_parts["rounds"] == 1 and cut >= bound
