"""The certificate split by region: the largest of the regions' bounds, each sound on what its
region presents, the worst region named; tighter than the whole domain's where a region's limits
are what decide it."""

import dataclasses

import numpy as np
import pytest

from phongfx.certify import certify, figures
from phongfx.certify.bound import shader_config
from phongfx.certify.branch import Resume
from phongfx.certify.bounding import bounding
from phongfx.explore.compile.measure import SceneEval
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene
from tests.certify.test_bound import LYON

SPEC = load_scene("scenes/lyon-balls.toml")


def _measured(spec, shader, params, geometries=None, method="fig7"):
    """``method``'s largest ``|out - 255·I_ref|`` over the frames (None) or ``geometries``."""
    scene = SceneEval(spec, geometries)
    renders = (scene.render(method, shader, params, i)[:2] for i in range(len(scene.renders)))
    return max(float(np.max(np.abs(codes - 255 * ref), initial=0.0)) for codes, ref in renders)


def test_the_bound_by_region_holds_on_frames_and_region_samples_smoke():
    d = domain(SPEC)
    shader = shader_config("fig7", LYON, SPEC)
    got = certify("fig7", LYON, SPEC, d, shader=shader, max_boxes=20_000)
    bounds = [r["bound_levels"] for r in got.parts["regions"]]
    # the whole domain's bound misses the requirement: the regions are bounded too, the smaller kept
    assert len(bounds) == 20 and got.parts["whole_bound"] > 1.5
    assert got.bound_levels == min(got.parts["whole_bound"], max(bounds))
    worst = got.parts["regions"][int(np.argmax(bounds))]
    assert got.parts["region"] == worst["name"] and f"by region, largest in {worst['name']}" in got.why
    assert worst["where"]["n"] == int(worst["name"].split("n = ")[1].split(")")[0])  # its sphere's own n
    measured = max(_measured(SPEC, shader, LYON), _measured(SPEC, shader, LYON, [d.sample(20_000, 3)]))
    assert 1.0 < measured <= got.bound_levels
    # each region's bound holds on that region's own samples (two: the worst, and a narrow one)
    for index in (int(np.argmax(bounds)), int(np.argmin(bounds))):
        sub = d.region(index)
        assert _measured(SPEC, shader, LYON, [sub.sample(5_000, index)]) <= bounds[index]
    # the whole-domain path is unchanged: one bound, no regions
    whole = certify("fig7", LYON, SPEC, dataclasses.replace(d, regions=()), shader=shader, max_boxes=20_000)
    assert "regions" not in whole.parts and whole.bound_levels == got.parts["whole_bound"]


def test_a_probe_without_budget_bounds_the_whole_domain_only():
    """``max_boxes=0`` asks whether the domain can be bounded at all (the compiler's coverage
    probe): the regions could only refine a finite whole, so they are not bounded."""
    d = domain(SPEC)
    probe = certify("fig7", LYON, SPEC, d, max_boxes=0, early=True)
    whole = certify("fig7", LYON, SPEC, dataclasses.replace(d, regions=()), max_boxes=0, early=True)
    assert "regions" not in probe.parts and np.isfinite(probe.bound_levels) and probe.bound_levels > 1.5
    assert probe.bound_levels == whole.bound_levels and probe.parts["boxes"] == whole.parts["boxes"]


def test_early_stops_at_the_first_region_that_fails():
    """Every region on its first share, then the highest first: the first that stays over the
    requirement ends the certificate, the others over it are named unbounded."""
    d = domain(SPEC)
    got = certify("fig7", LYON, SPEC, d, max_boxes=20_000, early=True)
    regions = {r["name"]: r["bound_levels"] for r in got.parts["regions"]}
    assert len(regions) == len(d.regions) and not got.certified and regions[got.parts["region"]] >= 1.5
    over = [name for name, bound in regions.items() if bound >= 1.5 and name != got.parts["region"]]
    assert over and got.parts["unbounded_regions"] == over
    assert got.bound_levels == got.parts["whole_bound"]  # not the failing region's: no bound over the rest
    assert f"(which stays over it: {len(over)} regions not bounded)" in got.why


def test_regions_first_skips_the_whole_domain_and_bounds_by_the_largest_region():
    """A width search whose wider certificate needed the regions asks for them first: the same
    answer without the whole domain's branch and bound, the bound the largest over the regions
    (sound: they cover the domain), the failing region's own bound named in why."""
    d = domain(SPEC)
    whole_first, regions_first = (certify("fig7", LYON, SPEC, d, max_boxes=20_000, early=True, regions_first=first)
                                  for first in (False, True))
    assert not regions_first.certified and regions_first.parts["whole_bound"] is None
    assert regions_first.parts["region"] == whole_first.parts["region"]
    listed = [r["bound_levels"] for r in regions_first.parts["regions"]]
    assert regions_first.bound_levels == max(listed) and len(listed) == len(d.regions)
    assert regions_first.parts["boxes"] < whole_first.parts["boxes"]
    alone = regions_first.parts["region_bound"]
    assert alone == whole_first.parts["region_bound"] <= regions_first.bound_levels
    # named apart where another region's first share is higher than the one that stayed over
    assert (f"at {alone:.3f} levels there" in regions_first.why) == (alone < regions_first.bound_levels)
    # a domain whose whole meets the requirement is still bounded whole when its regions are asked
    # for on one without regions
    torus = load_scene("scenes/torus.toml")
    wide = {"vec_frac": 14, "x2_frac": 14, "shape_t_frac": 18, "coef": 8, "order": 2, "k": 4}
    plain = dataclasses.replace(domain(torus), regions=())
    assert certify("fig7", wide, torus, plain, early=True, regions_first=True).certified


def test_a_whole_domain_that_meets_the_requirement_needs_no_regions():
    spec = load_scene("scenes/torus.toml")
    wide = {"vec_frac": 14, "x2_frac": 14, "shape_t_frac": 18, "coef": 8, "order": 2, "k": 4}
    got = certify("fig7", wide, spec, domain(spec), early=True)
    assert got.certified and "regions" not in got.parts and got.bound_levels < 1.5


@pytest.mark.slow
def test_regions_tighten_the_bound_where_the_span_angle_decides_it():
    """Figure 7 with a first-order normalizer: its error grows with the span angle, 39° at the
    limb but 16° near the centre, so the centre bands' bounds fall and the largest with them."""
    d = domain(SPEC)
    params = {**LYON, "vec_frac": 12, "order": 1}
    shader = shader_config("fig7", params, SPEC)
    split = certify("fig7", params, SPEC, d, shader=shader)
    assert split.bound_levels < 0.8 * split.parts["whole_bound"]
    measured = max(_measured(SPEC, shader, params), _measured(SPEC, shader, params, [d.sample(100_000, 5)]))
    assert measured <= split.bound_levels


@pytest.mark.slow
def test_the_regions_certify_lyons_halfway_unit_where_the_whole_domain_cannot():
    """The halfway unit the compiler chooses for Lyon's spheres: over the whole domain (39° spans
    at every sphere's centre) its bound misses 1 level; by region it meets it, early stop or not."""
    params = {"vec_frac": 15, "x2_frac": 5, "shape_t_frac": 13, "coef": 2, "order": 2}
    shader = shader_config("halfway", params, SPEC)
    d = domain(SPEC)
    final, early = (certify("halfway", params, SPEC, d, shader=shader, early=e) for e in (False, True))
    assert final.parts["whole_bound"] > 1.5 and final.certified and early.certified
    assert final.bound_levels == max(r["bound_levels"] for r in final.parts["regions"]) < 1.5
    measured = max(_measured(SPEC, shader, params, None, "halfway"),
                   _measured(SPEC, shader, params, [d.sample(100_000, 8)], "halfway"))
    assert measured <= final.bound_levels


def test_a_branch_and_bound_resumed_on_a_larger_budget_ends_where_a_fresh_one_does(monkeypatch):
    """A region refined on four times its budget goes on from where it stopped
    (:class:`~phongfx.certify.branch.Resume`): the same bound, worst box and box count as a
    fresh branch and bound on that budget, for the boxes of the second run only."""
    bounded, errors = [], figures.box_errors

    def counted(shader, unit_bound, against, boxes, *args):
        bounded.append(len(boxes))
        return errors(shader, unit_bound, against, boxes, *args)

    monkeypatch.setattr(figures, "box_errors", counted)
    region = domain(SPEC).region(19)  # sphere 4, n = 256: the worst region, refined the longest
    shader, how = shader_config("fig7", LYON, SPEC), bounding("fig7")
    fresh = how.bound(shader, SPEC, region, max_boxes=8_000)
    resume = Resume()
    first = how.bound(shader, SPEC, region, max_boxes=2_000, resume=resume)
    del bounded[:]
    resumed = how.bound(shader, SPEC, region, max_boxes=8_000, resume=resume)
    assert first[1]["boxes"] < fresh[1]["boxes"] and resumed[0] < first[0]
    assert resumed == fresh
    assert sum(bounded) == fresh[1]["boxes"] - first[1]["boxes"]


def test_regions_with_the_whole_domain_s_limits_are_not_bounded_and_change_no_result(monkeypatch):
    """On the torus one patch reaches every N·V of the whole: no region can then beat the whole
    domain's bound, so a failing width point's certificate bounds the whole alone; bounding the
    regions anyway gives the same bound and verdict."""
    from phongfx.certify import regions

    spec = load_scene("scenes/torus.toml")
    whole, how = domain(spec), bounding("fig7")
    assert regions.like_whole(how, whole) == [1]
    assert regions.like_whole(how, domain(SPEC)) == []  # Lyon's rings of θ: each its own N·V, span angle and n
    # about a local viewer's cone the table units cover the cone's normals whatever a patch's N·V:
    # the local mesh's patches with the whole's span angle are the whole to them, not to Figure 7
    mesh = domain(load_scene("scenes/local-mesh.toml"))
    assert regions.like_whole(bounding("conventional"), mesh) == [0, 2] and regions.like_whole(how, mesh) == []
    params = {"vec_frac": 12, "x2_frac": 20, "shape_t_frac": 24, "coef": 16, "order": 2, "k": 4}
    calls, bound = [], figures.LyonDatapaths.bound

    def counted(self, *args, **options):
        calls.append(args[2].region_name)
        return bound(self, *args, **options)

    monkeypatch.setattr(figures.LyonDatapaths, "bound", counted)
    skipped = certify("fig7", params, spec, whole, early=True)
    assert calls == [""] and skipped.parts["like_whole"] == whole.regions[1].name
    del calls[:]
    monkeypatch.setattr(regions, "like_whole", lambda *_: [])
    bounded = certify("fig7", params, spec, whole, early=True)
    assert len(calls) > len(whole.regions) and "regions" in bounded.parts
    assert not skipped.certified and (skipped.certified, skipped.bound_levels) == (bounded.certified,
                                                                                   bounded.bound_levels)
