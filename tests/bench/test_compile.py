"""Smoke test of ``bench/compile.py`` (its compiles take minutes: ``make bench`` runs them): a
command timed with its processor time and an empty cache of its own, a compiled folder's
chosen design read back, the table against the targets."""

import json
import sys

import pytest

from bench.compile import GOAL, SIM_TARGET, TARGET, chosen_design, main, table, timed
from phongfx.deliver.manifest import MANIFEST_VERSION, ManifestError


def test_a_command_is_timed_with_its_own_empty_cache(tmp_path):
    cache = tmp_path / "cache"
    log = tmp_path / "log"
    busy = "import os, time\nt = time.process_time()\nwhile time.process_time() - t < 0.3: pass\n" \
           "print(os.environ['PHONGFX_CACHE'])"
    found = timed([sys.executable, "-c", busy], cache, log)
    assert found["returncode"] == 0 and found["seconds"] >= found["cpu_seconds"] * 0.5 >= 0.15
    assert log.read_text().strip() == str(cache)
    assert timed([sys.executable, "-c", "raise SystemExit(3)"], cache, log)["returncode"] == 3


def test_the_chosen_design_and_the_table(tmp_path):
    (tmp_path / "torus").mkdir()
    manifest = {"manifest_version": MANIFEST_VERSION, "chosen": "fig7", "widths": {"vec_frac": 11},
                "cost": {"cost": 28613}, "error": {"max": 1.0}, "certificate": {"certified": True, "bound_levels": 1.49}}
    (tmp_path / "torus" / "manifest.json").write_text(json.dumps(manifest))
    design = chosen_design(tmp_path / "torus")
    assert design == {"chosen": "fig7", "widths": {"vec_frac": 11}, "cost": 28613, "max_error": 1.0,
                      "certified": True, "bound_levels": 1.49}
    assert chosen_design(tmp_path / "none") is None
    # read by the one manifest reader: a manifest of another version is refused, not guessed at
    (tmp_path / "torus" / "manifest.json").write_text(json.dumps({**manifest, "manifest_version": 1}))
    with pytest.raises(ManifestError, match=r"field 'manifest_version' is 1"):
        chosen_design(tmp_path / "torus")
    rows = [{"scene": "torus", "check": False, "seconds": GOAL - 1, "cpu_seconds": 40.0, "load": 2.0,
             "returncode": 0, "design": design},
            {"scene": "lyon-balls", "check": True, "seconds": TARGET + 12, "cpu_seconds": 90.0, "load": 2.0,
             "returncode": 0, "design": None}]
    step = {"seconds": 50.0, "cpu_seconds": 60.0, "load": 1.0, "returncode": 0}
    text = table({"rows": rows, "cores": 2, "sim": {"steps": {"render": step, "compile": step}, "seconds": 100.0,
                                                     "cpu_seconds": 120.0, "returncode": 0}})
    assert "| torus | no | 29.0 | 40.0 | 2.0 | goal met | fig7 {'vec_frac': 11} | 28613 | 1.0 | True |" in text
    assert "| lyon-balls | yes | 72.0 | 90.0 | 2.0 | over by 12 s |" in text
    assert f"make sim (from an empty cache): 100.0 s (render 50.0 s, compile 50.0 s; cpu 120.0 s), over by 10 s " \
           f"of {SIM_TARGET:.0f} s" in text


def test_bad_options_are_refused(capsys):
    with pytest.raises(SystemExit):
        main(["--workers", "0", "--no-sim", "--scenes"])
    assert "--workers must be a positive integer, not 0" in capsys.readouterr().err
