"""Reading a compiled folder's manifest back: every registered block's config survives the
trip through JSON, and a folder or manifest that gives no design is refused naming the file
and the field."""

import dataclasses
import json
import re

import pytest

from phongfx.config import ShaderConfig
from phongfx.core.registry import REGISTRY
from phongfx.deliver.component import load_core
from phongfx.deliver.manifest import MANIFEST_VERSION, ManifestError, config_from_dict, design_of, read_manifest

from tests.deliver.streams import TWO_LIGHTS


def _through_json(config):
    return json.loads(json.dumps(dataclasses.asdict(config)))


@pytest.mark.parametrize("name", list(REGISTRY))
def test_every_blocks_default_config_comes_back_equal_from_its_json(name):
    config = REGISTRY[name].default_config()
    again = config_from_dict(REGISTRY[name].default_config(), _through_json(config))
    assert again == config and hash(again) == hash(config)


def test_a_shader_of_datapaths_with_one_local_light_and_interval_comes_back_equal():
    datapath = REGISTRY["fig7"].default_config().replace(local_lights=(True, False))
    shader = ShaderConfig(unit="fig7", units=(datapath,), blend=ShaderConfig().blend)
    again = config_from_dict(ShaderConfig(), _through_json(shader))
    assert again == shader and again.units[0].local_lights == (True, False)
    two = design_of(TWO_LIGHTS)[2]
    assert config_from_dict(ShaderConfig(), _through_json(two)) == two
    assert two.interval == 2 and two.units[0].outputs == two.units[1].outputs


def _folder(tmp_path, manifest, name="out"):
    folder = tmp_path / name
    folder.mkdir()
    if manifest is not None:
        text = manifest if isinstance(manifest, str) else json.dumps(manifest)
        (folder / "manifest.json").write_text(text)
    return folder


def _changed(**changes):
    data = json.loads(json.dumps(TWO_LIGHTS))
    for path, value in changes.items():
        *parents, last = path.split("__")
        target = data
        for key in parents:
            target = target[int(key)] if isinstance(target, list) else target[key]
        if value is KeyError:
            del target[last]
        else:
            target[last] = value
    return data


BAD = {
    "no manifest": (None, r"out/manifest\.json: no manifest\.json: not the output folder of "
                          r"'phongfx compile -o FOLDER'$"),
    "not JSON": ("{", r"out/manifest\.json: not a readable JSON manifest: Expecting property name"),
    "a list": ("[]", r"out/manifest\.json: a manifest is a JSON object, not list$"),
    "no version": (_changed(manifest_version=KeyError),
                   r"out/manifest\.json: field 'manifest_version' is absent \(written by a phongfx before "
                   rf"manifests had versions\); this phongfx reads version {MANIFEST_VERSION}: compile the scene again$"),
    "another version": (_changed(manifest_version=MANIFEST_VERSION + 1),
                        rf"out/manifest\.json: field 'manifest_version' is {MANIFEST_VERSION + 1}; this phongfx reads "
                        rf"version {MANIFEST_VERSION}"),
    "a failed compile": ({"manifest_version": MANIFEST_VERSION, "scene": "tiny", "chosen": None, "refused": None,
                          "methods": {"fig7": {"feasible": False}}},
                         r"out/manifest\.json: field 'config' is absent: the compile of scene 'tiny' found no "
                         r"design \(no method met the error requirement; 'chosen' is None\), so there is no core$"),
    "a compile refused for speed": ({"manifest_version": MANIFEST_VERSION, "scene": "tiny", "chosen": None,
                                     "refused": {"why": "speed", "text": ["no design meets 90 Mpixel/s: ..."]}},
                                    r"found no design \(no design meets 90 Mpixel/s: \.\.\.; 'chosen' is None\)"),
    "an unknown block": (_changed(block="pixel"),
                         r"out/manifest\.json: field 'block' must be a registered block \(lirp, .*shader\), "
                         r"not 'pixel'$"),
    "a bad module": (_changed(module="two lights"),
                     r"out/manifest\.json: field 'module' must be a Verilog identifier, not 'two lights'$"),
    "a missing config field": (_changed(config__blend__bits=KeyError),
                               r"out/manifest\.json: field 'config\.blend' \(BlendConfig\) lacks bits$"),
    "an unknown config field": (_changed(config__units__1__speed=3),
                                r"out/manifest\.json: field 'config\.units\[1\]' \(ConventionalConfig\) has "
                                r"unknown speed$"),
    "a bad config value": (_changed(config__units__0__vec="S1.x"),
                           r"out/manifest\.json: field 'config\.units\[0\]': vec: .*'S1\.x'"),
    "a bad interval": (_changed(config__interval=3),
                       r"out/manifest\.json: field 'config': interval \(2 lights\) must be an integer in 1\.\.2, "
                       r"not 3$"),
}


@pytest.mark.parametrize("case", list(BAD))
def test_a_folder_that_gives_no_design_is_refused_naming_the_file_and_field(tmp_path, case):
    manifest, message = BAD[case]
    folder = _folder(tmp_path, manifest)
    with pytest.raises(ManifestError) as error:
        load_core(folder)
    assert re.search(message, str(error.value)), str(error.value)
    assert str(error.value).startswith(str(folder / "manifest.json"))
    assert list(folder.iterdir()) == ([folder / "manifest.json"] if manifest is not None else [])


def test_a_missing_folder_is_named_and_a_manifest_error_is_a_value_error(tmp_path):
    with pytest.raises(ValueError, match=r"nowhere/manifest\.json: no such folder: give the output folder of "
                                         r"'phongfx compile -o FOLDER'$"):
        read_manifest(tmp_path / "nowhere")
    with pytest.raises(ManifestError, match=r"^manifest: field 'manifest_version' is '1'; "):
        load_core({**TWO_LIGHTS, "manifest_version": "1"})


def test_the_folder_of_a_real_compile_that_chose_nothing_is_refused(tmp_path):
    from phongfx.compiler.compile import compile_scene
    from phongfx.compiler.request import CompileRequest
    from phongfx.explore.compile.emit import emit
    from phongfx.scene.file import parse_scene
    from tests.compiler.test_compile import TORUS

    compiled = compile_scene(CompileRequest(parse_scene(TORUS.format(error=0.001, against="phong"), name="tiny"), methods=["fig7"]))
    data = emit(compiled, tmp_path / "out", check=False)
    assert data["manifest_version"] == MANIFEST_VERSION and data["chosen"] is None
    with pytest.raises(ManifestError, match=r"out/manifest\.json: field 'config' is absent: the compile of scene "
                                            r"'tiny' found no design \(no method met the error requirement; "
                                            r"'chosen' is None\), so there is no core$"):
        load_core(tmp_path / "out")
