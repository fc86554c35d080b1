"""``phongfx certify``: every exit code, on a method and on a compiled folder, and its errors."""

import json
import math

import pytest

from phongfx.cli import main
from phongfx.cli.certify import PER_PIXEL
from phongfx.deliver.manifest import MANIFEST_VERSION
from phongfx.explore.compile.witness import search
from phongfx.scene.domain import domain
from phongfx.scene.file import load_scene

#: Figure 7 at 7 fraction bits and k = 4 on the per-pixel domain of n = 16: every one of its
#: 154,917 normal codes is within 4.53 levels of Phong, the worst displays 5 levels off.
SMALL = ["certify", "fig7", "--set", "vec_frac=7", "--set", "k=4", "--quiet"]


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_bound_meets(capsys):
    code, out, _ = run(capsys, *SMALL, "--max-error", "5", "--json")
    result = json.loads(out)
    assert code == 0 and result["exit"] == 0
    cert = result["certificate"]
    assert cert["method"] == "exhaustive" and cert["certified"]
    assert 4.5 < cert["bound_levels"] < 4.6 and cert["parts"]["codes"] == 154_917
    assert result["witness"]["error_levels"] == 5
    assert result["domain"]["view_cos_min"] == pytest.approx(0, abs=1e-12)


def test_witness_fails(capsys):
    code, out, _ = run(capsys, *SMALL, "--max-error", "3")
    assert code == 1
    assert "witness: 5 levels" in out and "bound: 4.528 levels (exhaustive" in out
    assert "not certified: some input code misses the requirement" in out


def test_only_the_bound_misses(capsys):
    # spans cannot be enumerated: no bound, while the witness search meets a loose requirement
    code, out, err = run(capsys, "certify", "fig7", "--scene", "scenes/torus.toml", "--bound", "exhaustive",
                         "--samples", "3000", "--max-error", "30")
    assert code == 3
    assert "bound: none (exhaustive" in out and "the domain has spans" in out
    assert "certify: witness fig7: 3,000 of 3,000 domain points" in err


def test_interval(capsys):
    # the interval bound counts the host's rounding of the float normal too: it is loose here,
    # but never under the witness, which is measured against the exact normal
    code, out, _ = run(capsys, *SMALL, "--max-error", "5", "--bound", "interval", "--samples", "2000", "--json")
    result = json.loads(out)
    assert code == 3
    cert, witness = result["certificate"], result["witness"]
    assert cert["method"] == "interval" and not cert["certified"]
    assert witness["error_levels"] <= 5 < math.floor(cert["bound_levels"] + 0.5)
    assert cert["bound_levels"] >= witness["unrounded"]
    assert "(2,000 fresh domain points" in witness["found_by"]


@pytest.mark.parametrize("argv, message", [
    (["fig7", "--set", "vec_frac=99"], "--set vec_frac must be an integer in 4..16, not '99'"),
    (["fig7", "--set", "n=4"], "--set n: fig7 has no width 'n'; widths: vec_frac"),
    (["fig7", "--set", "vec_frac"], "--set wants width=value, not 'vec_frac'"),
    (["fig9", "--n", "4"], "METHOD|DIR must be a method (fig7"),
    (["fig7", "--n", "0"], "--n must be an integer in 1..8000, not 0"),
    (["fig7", "--light", "1,2"], "--light must be three numbers X,Y,Z, not '1,2'"),
    (["fig7", "--light", "0,0,0"], "lights[0].direction"),
    (["fig7", "--samples", "0"], "--samples must be a positive integer, not 0"),
    (["fig7", "--max-error", "-1"], "--max-error must be a positive number of display levels, not -1"),
    (["fig7", "--replay"], "--replay re-evaluates a compiled folder's witness"),
    (["fig7", "--scene", "scenes/torus.toml", "--n", "4"], "--n sets up the per-pixel domain"),
    (["fig7", "--scene", "no/such.toml"], "no/such.toml"),
])
def test_bad_input(capsys, argv, message):
    code, _, err = run(capsys, "certify", *argv)
    assert code == 2
    assert err.startswith("phongfx: error:") and message in err and err.count("\n") == 1


@pytest.fixture
def compiled(tmp_path):
    """A compiled folder as ``phongfx compile`` leaves it: the scene file (relative to the
    folder), the chosen design, its widths and its witness (from a small search)."""
    scene = tmp_path / "ball.toml"
    scene.write_text(PER_PIXEL.format(n=16, light="1.0, 1.0, 1.0").replace("max_error_levels = 1.0",
                                                                            "max_error_levels = 5.0"))
    spec = load_scene(str(scene))
    widths = {"vec_frac": 7, "k": 4}
    witness = search("fig7", widths, spec, domain(spec), samples=2000, seed=3)
    folder = tmp_path / "out"
    folder.mkdir()
    manifest = {"manifest_version": MANIFEST_VERSION, "scene": spec.name, "path": "../ball.toml", "chosen": "fig7",
                "widths": widths, "witness": witness}
    (folder / "manifest.json").write_text(json.dumps(manifest, default=float))
    return folder


def test_compiled_folder(capsys, compiled):
    code, out, _ = run(capsys, "certify", str(compiled), "--quiet", "--json")
    result = json.loads(out)
    assert code == 0 and result["method"] == "fig7" and result["params"] == {"vec_frac": 7, "k": 4}
    assert result["certificate"]["certified"] and result["certificate"]["method"] == "exhaustive"
    code, _, err = run(capsys, "certify", str(compiled), "--set", "k=2")
    assert code == 2 and "--set applies to a METHOD target" in err


def test_a_compiled_folder_certifies_from_any_working_directory(capsys, compiled, tmp_path, monkeypatch):
    elsewhere = tmp_path / "elsewhere" / "deeper"
    elsewhere.mkdir(parents=True)
    monkeypatch.chdir(elsewhere)
    code, out, _ = run(capsys, "certify", "../../out", "--quiet", "--json")
    assert code == 0 and json.loads(out)["scene"] == "../../ball.toml"  # the manifest's path, from here
    assert run(capsys, "certify", "../../out", "--replay")[0] == 0
    # or named by its manifest, from its own folder too
    code, out, _ = run(capsys, "certify", "../../out/manifest.json", "--quiet", "--json")
    assert code == 0 and json.loads(out)["scene"] == "../../ball.toml"
    monkeypatch.chdir(compiled)
    code, out, _ = run(capsys, "certify", "manifest.json", "--quiet", "--json")
    assert code == 0 and json.loads(out)["scene"] == "../ball.toml" and json.loads(out)["method"] == "fig7"


def test_a_manifest_of_another_version_or_without_its_scene_file_is_refused(capsys, compiled, tmp_path):
    data = json.loads((compiled / "manifest.json").read_text())
    (compiled / "manifest.json").write_text(json.dumps({**data, "manifest_version": 1}))
    code, _, err = run(capsys, "certify", str(compiled))
    assert code == 2 and err == (f"phongfx: error: {compiled / 'manifest.json'}: field 'manifest_version' is 1; "
                                 f"this phongfx reads version {MANIFEST_VERSION}: compile the scene again\n")
    (compiled / "manifest.json").write_text(json.dumps(data))
    (tmp_path / "ball.toml").rename(tmp_path / "moved.toml")
    code, _, err = run(capsys, "certify", str(compiled))
    assert code == 2 and err == (f"phongfx: error: {compiled / 'manifest.json'}: field 'path' is '../ball.toml' "
                                 f"(relative to the manifest's folder): the scene file {tmp_path / 'ball.toml'} "
                                 f"is not there any more\n")


def test_replay(capsys, compiled):
    code, out, _ = run(capsys, "certify", str(compiled), "--replay")
    assert code == 0 and "reproduced" in out and "NOT" not in out
    manifest = json.loads((compiled / "manifest.json").read_text())
    manifest["witness"]["outputs"]["r"] += 1  # a witness that the design does not give
    (compiled / "manifest.json").write_text(json.dumps(manifest))
    code, out, err = run(capsys, "certify", str(compiled), "--replay")
    assert code == 1 and "NOT reproduced" in out and "does not reproduce" in err


def test_not_a_compiled_folder(capsys, tmp_path):
    code, _, err = run(capsys, "certify", str(tmp_path))
    assert code == 2 and "manifest.json: no manifest.json: not the output folder of 'phongfx compile -o FOLDER'" in err


@pytest.mark.needs_gappa
def test_gappa(capsys, tmp_path):
    proof = tmp_path / "chain.v"
    code, out, _ = run(capsys, *SMALL, "--max-error", "5", "--gappa", "--coq", str(proof), "--json")
    gappa = json.loads(out)["gappa"]
    assert code == 0 and gappa["n"] == [16, 16]
    # the chain's rounding is a small part of the 4.53 levels: Lyon's shape against cos^n is the rest
    assert 0 < gappa["levels"] < 0.05 and 0 < gappa["amount"] < 2 ** -11
    assert "rndNU" in proof.read_text()


@pytest.mark.parametrize("argv, message", [
    (["fig7", "--coq", "x.v"], "--coq writes Gappa's proof: add --gappa"),
    (["conventional", "--gappa"], "--gappa proves Figure 7's chain (fig7), not conventional's"),
])
def test_gappa_refused(capsys, argv, message):
    code, _, err = run(capsys, "certify", *argv)
    assert code == 2 and message in err


def test_gappa_missing(capsys, monkeypatch):
    import phongfx.certify.gappa as gappa

    monkeypatch.setattr(gappa.shutil, "which", lambda name: None)
    code, _, err = run(capsys, *SMALL, "--gappa")
    assert code == 2 and "--gappa: gappa is not installed; as root: apt-get install gappa" in err
