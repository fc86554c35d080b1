"""Certificates kept in the cache: a second ask reads the first's back, a changed design or
refinement bounds again, and a probe, or a bound the clock cut, is never kept."""

import json

import phongfx.certify.remembered as remembered
from phongfx.cli.certify import per_pixel_scene
from phongfx.explore.compile.analysis import analyse
from phongfx.scene.domain import domain as scene_domain
from phongfx.scene.geometry import frames


def _scene():
    spec = per_pixel_scene(16)
    geometries = frames(spec)
    return spec, scene_domain(spec, geometries), analyse(spec, geometries)


def test_a_certificate_is_bounded_once_and_read_back_equal(tmp_path, monkeypatch):
    spec, domain, analysis = _scene()
    calls = []
    bound = remembered.certify

    def counting(*args, **options):
        calls.append((args[0], dict(args[1]), options["early"], options["max_boxes"]))
        return bound(*args, **options)
    monkeypatch.setattr(remembered, "certify", counting)
    certifier = remembered.remembering(tmp_path / "certificates")
    params = {"vec_frac": 9, "k": 4}
    first = certifier("fig7", params, spec, domain, analysis=analysis, max_boxes=2000)
    again = certifier("fig7", params, spec, domain, analysis=analysis, max_boxes=2000)
    assert len(calls) == 1 and first.bound_levels > 0 and again.as_dict() == json.loads(json.dumps(first.as_dict()))
    files = list((tmp_path / "certificates").iterdir())
    assert len(files) == 1 and json.loads(files[0].read_text())["bound_levels"] == first.bound_levels
    certifier("fig7", {**params, "vec_frac": 10}, spec, domain, analysis=analysis, max_boxes=2000)
    certifier("fig7", params, spec, domain, analysis=analysis, max_boxes=2000, early=True)
    certifier("fig7", params, spec, domain, analysis=analysis, max_boxes=0)  # a probe: not kept
    certifier("fig7", params, spec, domain, analysis=analysis, max_boxes=0)
    assert [c[1:] for c in calls[1:]] == [({"vec_frac": 10, "k": 4}, False, 2000), (params, True, 2000),
                                          (params, False, 0), (params, False, 0)]
    assert len(list((tmp_path / "certificates").iterdir())) == 3


def test_a_torn_file_is_bounded_again(tmp_path):
    spec, domain, analysis = _scene()
    certifier = remembered.remembering(tmp_path)
    first = certifier("fig7", {"vec_frac": 9}, spec, domain, analysis=analysis, max_boxes=2000)
    (path,) = tmp_path.iterdir()
    path.write_text('{"certified": tr')
    again = certifier("fig7", {"vec_frac": 9}, spec, domain, analysis=analysis, max_boxes=2000)
    assert again.bound_levels == first.bound_levels and json.loads(path.read_text())["certified"] == first.certified


def test_the_domain_sample_is_not_part_of_the_key_but_the_domain_is():
    import dataclasses

    spec, domain, analysis = _scene()
    shader = remembered.shader_config("fig7", {}, spec, analysis)
    key = remembered.certificate_key("fig7", shader, spec, domain, False, 2000)
    resampled = dataclasses.replace(domain, samples=7, final_samples=9, seed=5)
    assert remembered.certificate_key("fig7", shader, spec, resampled, False, 2000) == key
    narrower = dataclasses.replace(domain, view_cos_min=domain.view_cos_min + 0.1)
    assert remembered.certificate_key("fig7", shader, spec, narrower, False, 2000) != key


def test_coefficient_widths_of_the_same_values_share_a_certificate():
    """A wider ``coef_frac`` whose codes only gain trailing zeros gives the same outputs: one key;
    other coefficient values: another."""
    import dataclasses

    from phongfx.certify.outputs import fewest_coefficient_bits

    spec, domain, analysis = _scene()
    shader = remembered.shader_config("fig7", {}, spec, analysis)
    fewest = fewest_coefficient_bits(shader.blend)
    assert fewest.coef_frac <= shader.blend.coef_frac
    assert fewest_coefficient_bits(fewest) == fewest
    key = remembered.certificate_key("fig7", shader, spec, domain, False, 2000)
    for frac in (fewest.coef_frac, fewest.coef_frac + 3):
        same = dataclasses.replace(shader, blend=dataclasses.replace(shader.blend, coef_frac=frac))
        assert remembered.certificate_key("fig7", same, spec, domain, False, 2000) == key
    other = dataclasses.replace(shader, blend=dataclasses.replace(shader.blend, ambient=((0.1, 0.1, 0.1),)))
    assert remembered.certificate_key("fig7", other, spec, domain, False, 2000) != key



def test_a_certificate_the_clock_cut_is_not_kept(tmp_path, monkeypatch):
    """A bound cut by the branch and bound's hang guard is this machine's on this run: it is
    returned, not kept, so that a later run refines it to the budget's bound."""
    from phongfx.certify import branch

    spec, domain, analysis = _scene()
    monkeypatch.setattr(branch, "SECONDS", 0.0)
    certifier = remembered.remembering(tmp_path)
    cut = certifier("fig7", {"vec_frac": 9, "k": 4}, spec, domain, analysis=analysis, max_boxes=2000)
    assert cut.parts["timed_out"] and list(tmp_path.iterdir()) == []
    monkeypatch.setattr(branch, "SECONDS", 900.0)
    kept = certifier("fig7", {"vec_frac": 9, "k": 4}, spec, domain, analysis=analysis, max_boxes=2000)
    assert "timed_out" not in kept.parts and len(list(tmp_path.iterdir())) == 1
