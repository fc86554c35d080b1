"""Scene files as evaluation scenes (phongfx.explore.scene_files): frames and lights pooled."""

import os

from phongfx.explore.scene_files import file_views, is_scene_file, scene_label


def test_a_file_is_told_from_a_name_and_named_by_its_stem():
    assert is_scene_file("../scenes/my.toml") and not is_scene_file("torus")
    assert scene_label("../scenes/my.toml") == "my"


def test_the_example_torus_scene_pools_its_frames():
    from phongfx.core.methods import METHODS
    from phongfx.explore.evaluate import error_metrics, evaluate
    here = os.path.join(os.path.dirname(__file__), "..", "..", "scenes", "torus.toml")
    label, views = file_views(here)
    assert (label, [v.frame for v in views]) == ("torus", [0, 1, 2, 3])
    pooled = evaluate("schlick", {"t_frac": 8}, scenes=(here,))["metrics"]
    spec = METHODS["schlick"]
    p = spec.resolve({"t_frac": 8})
    each = []
    for view in views:
        fixed, floats, _ = spec.run(spec, spec.build(p), p, view)
        each.append(error_metrics(fixed, floats["phong"], view.data["visible"])["max"])
    assert pooled["torus.phong.max"] == max(each) > 0 and len(pooled) == 16
