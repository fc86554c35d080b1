"""Scene files: every example parses, every bad field gets one line naming it."""

import copy
import math
import os
import re

import pytest

from phongfx.scene.file import SceneError, load_scene, parse_scene

SCENES = os.path.join(os.path.dirname(__file__), "..", "..", "scenes")

BASE = {
    "camera": {"at": "infinity"},
    "lights": [{"direction": [1, 1, 1]}],
    "materials": {"m": {"kd": 0.5, "ks": 0.5, "n": 16}},
    "objects": [{"type": "torus", "material": "m", "polygons": 32}],
    "output": {"width": 16, "height": 16},
}


def _parse(change=None, **kw):
    data = copy.deepcopy(BASE)
    if change:
        change(data)
    return parse_scene(data, name="t", **kw)


def test_defaults_and_properties():
    spec = _parse()
    assert spec.name == "t" and spec.camera.kind == "infinity" and spec.camera.vector == (0, 0, 1)
    assert spec.lights[0].kind == "directional" and spec.lights[0].intensity == 1.0
    assert spec.lights[0].vector == pytest.approx((3 ** -0.5,) * 3)
    assert (spec.frames.count, spec.output.bits, spec.requirement.against) == (1, 8, "phong")
    assert spec.shininess == (16,) and not spec.local_lights and not spec.local_viewer
    assert spec.objects[0].params["mesh"].polygons == 32


def test_local_light_colour_range_and_camera():
    def change(d):
        d["camera"] = {"position": [0, 0, 5]}
        d["lights"].append({"position": [1, 2, 3], "colour": [0.2, 0.4, 0.9]})
        d["materials"]["m"]["n"] = [4, 64]
    spec = _parse(change)
    assert spec.local_lights and spec.local_viewer and spec.camera.vector == (0, 0, 5)
    assert spec.lights[1].vector == (1, 2, 3) and spec.lights[1].rgb == (0.2, 0.4, 0.9)
    assert spec.lights[1].intensity == pytest.approx(0.5)
    assert (spec.materials["m"].n_lo, spec.materials["m"].n_hi) == (4, 64)
    assert spec.shininess == (4, 64)


def test_light_and_material_colours():
    def change(d):
        d["lights"][0].update(intensity=2.0, colour=[1.0, 0.5, 0.25])
        d["materials"]["m"].update(ka=0.1, colour=[0.8, 0.6, 0.4])
    spec = _parse(change)
    assert spec.lights[0].rgb == (2.0, 1.0, 0.5)
    assert spec.materials["m"].ka == 0.1 and spec.materials["m"].colour == (0.8, 0.6, 0.4)
    assert _parse().materials["m"].colour == (1.0, 1.0, 1.0) and _parse().materials["m"].ka == 0.0


@pytest.mark.parametrize("name", ["lyon-balls", "torus", "local-mesh"])
def test_example_scenes_round_trip(name):
    spec = load_scene(os.path.join(SCENES, f"{name}.toml"))
    assert spec.name == name and spec.path.endswith(f"{name}.toml")
    with open(spec.path) as file:
        again = parse_scene(file.read(), name=name, base_dir=SCENES)
    assert again.camera == spec.camera and again.lights == spec.lights
    assert again.materials == spec.materials and again.frames == spec.frames
    assert again.output == spec.output and again.requirement == spec.requirement
    assert [o.kind for o in again.objects] == [o.kind for o in spec.objects]


def test_example_scene_contents():
    lyon = load_scene(os.path.join(SCENES, "lyon-balls.toml"))
    assert lyon.shininess == (1, 4, 16, 64, 256) and (lyon.output.width, lyon.output.height) == (193, 65)
    assert [light.vector for light in lyon.lights] == [
        pytest.approx(tuple(x / math.sqrt(3) for x in v)) for v in ((1, 1, -1), (1, -1, 1))]
    local = load_scene(os.path.join(SCENES, "local-mesh.toml"))
    assert local.local_lights and local.local_viewer and local.shininess == (16, 32)
    assert 300 <= local.objects[0].params["mesh"].polygons <= 800


def _set(path, value):
    def change(d):
        *head, last = path
        target = d
        for key in head:
            target = target[key]
        target[last] = value
    return change


def _drop(path):
    def change(d):
        *head, last = path
        target = d
        for key in head:
            target = target[key]
        del target[last]
    return change


BAD = [
    (_set(("colour",), 1), r"^t: scene: unknown key 'colour'; allowed: name, camera, lights, "
                           r"materials, objects, frames, output, requirement, domain$"),
    (_drop(("lights",)), r"^t: scene\.lights is missing$"),
    (_set(("lights",), []), r"^t: lights must be an array of 1\.\.8 tables \(\[\[lights\]\]\), not \[\]$"),
    (_set(("lights", 0, "position"), [1, 2]),
     r"^t: lights\[0\] must have exactly one of direction \(at infinity\) or position \(local\), "
     r"not \['direction', 'position'\]$"),
    (_set(("lights", 0), {}), r"^t: lights\[0\] must have exactly one of direction .* not neither$"),
    (_set(("lights", 0), {"position": [1, 2]}), r"^t: lights\[0\]\.position must be 3 numbers, not \[1, 2\]$"),
    (_set(("lights", 0, "direction"), [0, 0, 0]),
     r"^t: lights\[0\]\.direction must be a nonzero vector \(a direction\), not \[0, 0, 0\]$"),
    (_set(("lights", 0, "intensity"), -1), r"^t: lights\[0\]\.intensity must be a number in \[0, 16\], not -1$"),
    (_set(("lights", 0, "spot"), 1), r"^t: lights\[0\]: unknown key 'spot'; allowed: direction, position, "
                                     r"intensity, colour, color$"),
    (_set(("camera",), {"at": "infinity", "position": [0, 0, 1]}),
     r"^t: camera must have either position \(local\) or at/direction \(at infinity\), not both: "
     r"\['at', 'position'\]$"),
    (_set(("camera", "at"), "home"), r"^t: camera\.at must be \"infinity\" \(or give camera\.position\), not 'home'$"),
    (_set(("materials", "m", "n"), 0), r"^t: materials\.m\.n must be an integer in 1\.\.8000, not 0$"),
    (_set(("materials", "m", "n"), 9000), r"^t: materials\.m\.n must be an integer in 1\.\.8000, not 9000$"),
    (_set(("materials", "m", "n"), [64, 8]), r"^t: materials\.m\.n must be a range \[lo, hi\] with lo <= hi, "
                                             r"not \[64, 8\]$"),
    (_set(("materials", "m", "n"), 2.5), r"^t: materials\.m\.n must be an integer in 1\.\.8000, not 2\.5$"),
    (_set(("materials", "m", "kd"), "high"), r"^t: materials\.m\.kd must be a number in \[0, 1\], not 'high'$"),
    (_drop(("materials", "m", "ks")), r"^t: materials\.m\.ks is missing$"),
    (_drop(("materials", "m", "n")), r"^t: materials\.m\.n is missing \(needed by objects\[0\], type 'torus'\)$"),
    (_set(("objects", 0, "type"), "cube"),
     r"^t: objects\[0\]\.type must be one of lyon_spheres, sphere, torus, mesh, not 'cube'$"),
    (_set(("objects", 0, "material"), "gold"),
     r"^t: objects\[0\]\.material must name a \[materials\] table \(m\), not 'gold'$"),
    (_set(("objects", 0, "polygons"), 300),
     r"^t: objects\[0\]\.polygons must be 2·k² for an integer k >= 3 .*, not 300$"),
    (_set(("objects", 0, "stacks"), 4), r"^t: objects\[0\]: unknown key 'stacks'; allowed: type, material, "
                                        r"scale, offset, polygons, major, minor$"),
    (_set(("objects", 0), {"type": "mesh", "material": "m", "file": "nothing.obj"}),
     r"^t: objects\[0\]\.file: no such file 'nothing\.obj' \(looked in .*\)$"),
    (_set(("objects", 0), {"type": "mesh", "material": "m"}), r"^t: objects\[0\]\.file is missing$"),
    (_set(("objects", 0), {"type": "sphere", "material": "m", "slices": 2}),
     r"^t: objects\[0\]\.slices must be an integer in 3\.\.1024, not 2$"),
    (_set(("name",), 7), r"^t: name must be a non-empty string, not 7$"),
    (_set(("lights",), [1]), r"^t: lights\[0\] must be a table, not 1$"),
    (_set(("lights", 0, "colour"), [1, 1]), r"^t: lights\[0\]\.colour must be a number or \[r, g, b\], "
                                            r"not \[1, 1\]$"),
    (_set(("lights", 0), {"direction": [1, 0, 0], "colour": 1, "color": [1, 1, 1]}),
     r"^t: lights\[0\] must have at most one of colour, color, not both$"),
    (_set(("lights", 0), {"direction": [1, 0, 0], "intensity": 4, "colour": [1, 8, 1]}),
     r"^t: lights\[0\]: intensity × colour must be at most 16 in each channel, not \[4.0, 32.0, 4.0\]$"),
    (_set(("materials", "m", "ka"), 1.5), r"^t: materials\.m\.ka must be a number in \[0, 1\], not 1\.5$"),
    (_set(("materials", "m", "colour"), [1, 0.5, 2]),
     r"^t: materials\.m\.colour\[2\] must be a number in \[0, 1\], not 2$"),
    (_set(("objects",), []), r"^t: objects must be an array of 1\.\.64 tables \(\[\[objects\]\]\), not \[\]$"),
    (_set(("objects", 0, "scale"), 0), r"^t: objects\[0\]\.scale must be a number in \(0, 1000000\.0\], not 0$"),
    (_set(("objects", 0, "minor"), 2), r"^t: objects\[0\]\.radii must satisfy 0 < minor < major, "
                                       r"not minor=2\.0, major=1\.0$"),
    (_set(("objects", 0), {"type": "mesh", "material": "m", "file": 3}),
     r"^t: objects\[0\]\.file must be the path of an OBJ file, not 3$"),
    (_set(("objects", 0), {"type": "lyon_spheres", "material": "m", "shininess": [1, 0]}),
     r"^t: objects\[0\]\.shininess must be an integer in 1\.\.8000, not 0$"),
    (_set(("frames",), {"count": 0}), r"^t: frames\.count must be an integer in 1\.\.1000, not 0$"),
    (_set(("frames",), {"axis": [0, 0, 0]}), r"^t: frames\.axis must be a nonzero vector \(a direction\), "
                                             r"not \[0, 0, 0\]$"),
    (_set(("output", "width"), 4), r"^t: output\.width must be an integer in 8\.\.4096, not 4$"),
    (_set(("output", "height"), 5000), r"^t: output\.height must be an integer in 8\.\.4096, not 5000$"),
    (_set(("output", "bits"), 17), r"^t: output\.bits must be an integer in 1\.\.16, not 17$"),
    (_set(("requirement",), {"against": "fig7"}),
     r"^t: requirement\.against must be \"phong\" or \"self\", not 'fig7'$"),
    (_set(("requirement",), {"max_error_levels": 0}),
     r"^t: requirement\.max_error_levels must be a number in \(0, 65535\], not 0$"),
    (_set(("requirement",), {"mpixels_per_second": 0}),
     r"^t: requirement\.mpixels_per_second must be a number in \(0, 100000\], not 0$"),
    (_set(("requirement",), {"mpixels_per_second": 2e6}),
     r"^t: requirement\.mpixels_per_second must be a number in \(0, 100000\], not 2000000\.0$"),
    (_set(("requirement",), {"mpixels_per_second": 40, "fps": 60}),
     r"^t: requirement must give the pixel rate either as mpixels_per_second or as the display's width, "
     r"height and fps, not both: \['mpixels_per_second', 'fps'\]$"),
    (_set(("requirement",), {"width": 640, "height": 480}),
     r"^t: requirement\.fps is missing: width, height and fps together give the pixel rate of the display "
     r"driven \(given: width, height\)$"),
    (_set(("requirement",), {"width": 0, "height": 480, "fps": 60}),
     r"^t: requirement\.width must be an integer in 1\.\.16384, not 0$"),
    (_set(("requirement",), {"width": 640, "height": 480, "fps": 0}),
     r"^t: requirement\.fps must be a number in \(0, 1000\], not 0$"),
    (_set(("requirement",), {"pixels": 3}),
     r"^t: requirement: unknown key 'pixels'; allowed: max_error_levels, against, mpixels_per_second, width, "
     r"height, fps$"),
]


@pytest.mark.parametrize("change, message", BAD)
def test_bad_fields(change, message):
    with pytest.raises(SceneError, match=message):
        _parse(change)


def test_lyon_spheres_rules():
    def lyon(d):
        d["objects"] = [{"type": "lyon_spheres", "material": "m", "radius": 8}]
        del d["output"]
    spec = _parse(lyon)
    assert (spec.output.width, spec.output.height) == (8 * 6 + 1, 17)
    with pytest.raises(SceneError, match=r"^t: objects: lyon_spheres must be the only object "
                                         r"\(it has its own image\), not one of 2$"):
        _parse(lambda d: (lyon(d), d["objects"].append(BASE["objects"][0])))
    with pytest.raises(SceneError, match=r"^t: output\.width must be 49 \(Lyon's image for radius 8 "
                                         r"and 5 spheres\) or left out, not 64$"):
        _parse(lambda d: (lyon(d), d.update(output={"width": 64})))


def test_files(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text("[camera]\nat = \n")
    with pytest.raises(SceneError, match=rf"^{re.escape(str(bad))}: invalid TOML: "
                                         rf".*\(at line 2, column \d+\)$"):
        load_scene(bad)
    none = re.escape(str(tmp_path / "none.toml"))
    with pytest.raises(SceneError, match=rf"^{none}: cannot read: No such file or directory$"):
        load_scene(tmp_path / "none.toml")
    (tmp_path / "two.obj").write_text("v 0 0 0\nv 1 0 0\nf 1 2 3\n")
    scene = tmp_path / "s.toml"
    scene.write_text('[[lights]]\ndirection = [0, 0, 1]\n[materials.m]\nkd = 1\nks = 0\nn = 1\n'
                     '[[objects]]\ntype = "mesh"\nmaterial = "m"\nfile = "two.obj"\n')
    with pytest.raises(SceneError, match=rf"^{re.escape(str(scene))}: objects\[0\]\.file: two\.obj:3: face index 3 "
                                         rf"out of range 1\.\.2$"):
        load_scene(scene)


def test_the_scene_page_shows_the_example_scenes_whole():
    # the page includes the files themselves, whole (no :lines: or :start-after:), so the
    # reference a user reads is the scene that is shipped
    with open(os.path.join(SCENES, "..", "docs", "scenes.rst"), encoding="utf-8") as file:
        page = file.read()
    for name in ("lyon-balls", "local-mesh"):
        include = f".. literalinclude:: ../scenes/{name}.toml\n"
        assert include in page
        options = page.split(include, 1)[1].split("\n\n", 1)[0]
        assert all(option.strip().split(":")[1] in ("language", "caption")
                   for option in options.splitlines() if option.strip()), options


def test_the_pixel_rate_is_given_or_the_display_s():
    assert _parse(lambda d: None).requirement.mpixels_per_second is None
    rate = _parse(_set(("requirement",), {"mpixels_per_second": 40})).requirement
    assert rate.mpixels_per_second == 40.0 and rate.display is None
    assert rate.as_dict() == {"max_error_levels": 1.0, "against": "phong", "mpixels_per_second": 40.0}
    vga = _parse(_set(("requirement",), {"width": 640, "height": 480, "fps": 60})).requirement
    assert vga.mpixels_per_second == pytest.approx(18.432) and vga.display == (640, 480, 60.0)
    assert vga.as_dict()["display"] == {"width": 640, "height": 480, "fps": 60.0}


def test_the_command_line_s_throughput_replaces_the_file_s():
    from phongfx.scene.file import with_throughput
    vga = _parse(_set(("requirement",), {"width": 640, "height": 480, "fps": 60}))
    faster = with_throughput(vga, 150)
    assert faster.requirement.mpixels_per_second == 150.0 and faster.requirement.display is None
    assert faster.requirement.max_error_levels == vga.requirement.max_error_levels
    with pytest.raises(SceneError, match=r"^--throughput: throughput must be a number in \(0, 100000\], not -1$"):
        with_throughput(vga, -1)
