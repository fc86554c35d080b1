"""Sweeps (phongfx.explore.sweep.run): spec checks, the local pool and Dask, resume after a kill,
failed points.  Most tests run a stand-in catalog and ``evaluate`` (fast and
countable); two run the real :func:`phongfx.explore.evaluate.evaluate` on a tiny grid."""

import csv
import json
import os
import re
from dataclasses import dataclass

import pytest

from phongfx.explore.sweep import spec as sweep_spec
from phongfx.explore.sweep.run import SweepSpecError, load_records, load_spec, run_sweep


@dataclass(frozen=True)
class StubMethod:
    params: dict

    def config(self, params):
        if not 1 <= params.get("a", 1) <= 16:
            raise ValueError(f"a must be in [1, 16], not {params['a']}")
        return params


STUB_METHODS = {"alpha": StubMethod({"a": 4, "b": 2, "n": 20}), "beta": StubMethod({"c": 3, "n": 20})}
STUB_SCENES = ("torus", "sphere")


def stub_evaluate(method, params, *, scenes=("torus", "sphere"), synth=None, proxy=None):
    """Metrics that are simple functions of the params; a == 13 fails, a == 7 is a Ctrl-C."""
    count = os.environ.get("SWEEP_TEST_COUNT")
    if count:
        with open(count, "a") as file:
            file.write(f"{method} {sorted(params.items())}\n")
    if params.get("a") == 13:
        raise RuntimeError("boom\nsecond line of the message")
    if params.get("a") == 7:
        raise KeyboardInterrupt
    value = params.get("a", 0) + params.get("b", 0) / 10 + params.get("c", 0) * 100
    metrics = {f"{scene}.phong.max": value + i for i, scene in enumerate(scenes)}
    cost = None if synth is None else {"lut4": 10 * value, "fmax_mhz": float(synth["freq"])}
    if synth is None and proxy is not None:
        cost = {"lut_eq": 11 * value, "model": f"{proxy}-proxy"}
    return {"metrics": metrics, "cost": cost}


@pytest.fixture
def stub(monkeypatch, tmp_path):
    monkeypatch.setattr(sweep_spec, "_catalog", lambda: (STUB_METHODS, STUB_SCENES))
    monkeypatch.setenv("SWEEP_TEST_COUNT", str(tmp_path / "calls.txt"))
    return tmp_path


def calls(tmp_path):
    try:
        return (tmp_path / "calls.txt").read_text().splitlines()
    except FileNotFoundError:
        return []


def rows(out):
    with open(os.path.join(out, "points.csv"), newline="") as file:
        return list(csv.DictReader(file))


GRID = {"scenes": ["torus"], "grid": [{"method": "alpha", "a": [1, 2, 3], "b": [5, 6]}],
        "points": [{"method": "beta", "c": 4}]}


def test_expand_fills_defaults_and_dedupes(stub):
    spec = {"grid": [{"method": "alpha", "a": [3, 4]}], "points": [{"method": "alpha", "a": 4, "b": 2}]}
    points = load_spec(spec)["points"]
    assert [p["params"] for p in points] == [{"a": 3, "b": 2, "n": 20}, {"a": 4, "b": 2, "n": 20}]
    assert all(re.fullmatch(r"[0-9a-f]{16}", p["id"]) for p in points)
    assert points[0]["scenes"] == ["torus", "sphere"] and points[0]["synth"] is None
    other = load_spec({**spec, "scenes": ["sphere"]})["points"]
    synth = load_spec({**spec, "synth": {"target": "ecp5", "freq": 100}})["points"]
    assert len({p["id"] for p in points + other + synth}) == 6  # scenes and synth are in the id


def test_proxy_prices_the_points_not_synthesized(stub):
    spec = {"synth": {"target": "asic", "freq": 100}, "grid": [{"method": "alpha", "a": [1, 2], "synth": False},
                                                             {"method": "beta"}]}
    assert [p["proxy"] for p in load_spec(spec)["points"]] == ["asic", "asic", None]
    assert [p["proxy"] for p in load_spec({**spec, "proxy": False})["points"]] == [None, None, None]
    assert load_spec({"grid": [{"method": "beta"}]})["points"][0]["proxy"] == "ecp5"
    with pytest.raises(SweepSpecError, match=r"^sweep spec: proxy must be one of ecp5, ice40, asic or false, "
                                             r"not 'xc7'$"):
        load_spec({**spec, "proxy": "xc7"})
    # the proxy is not in a point's identity: its error does not depend on it
    assert [p["id"] for p in load_spec(spec)["points"]] == [p["id"] for p in load_spec({**spec, "proxy": False})["points"]]


def test_per_entry_synth_switch(stub):
    spec = {"synth": {"freq": 120}, "grid": [{"method": "alpha", "a": [1, 2], "synth": False},
                                            {"method": "beta"}]}
    synths = [p["synth"] for p in load_spec(spec)["points"]]
    assert synths == [None, None, {"target": "ecp5", "freq": 120}]


def test_synthesized_points_run_first(stub):
    spec = {"synth": {"freq": 120}, "grid": [{"method": "alpha", "a": [1, 2], "synth": False},
                                            {"method": "alpha", "a": [3, 4]}]}
    run_sweep(spec, out=stub / "out", workers=1, progress=False, evaluate=stub_evaluate)
    assert [line.split("('a', ")[1][0] for line in calls(stub)] == ["3", "4", "1", "2"]


def test_pool_run_and_csv(stub):
    out = stub / "out"
    summary = run_sweep({**GRID, "synth": {"freq": 90}}, out=out, workers=2, progress=False,
                        evaluate=stub_evaluate)
    assert (summary["total"], summary["ran"], summary["ok"], summary["failed"]) == (7, 7, 7, 0)
    table = rows(out)
    assert list(table[0]) == ["id", "method", "status", "error", "seconds", "param.a", "param.b",
                              "param.n", "param.c", "torus.phong.max", "cost.lut4", "cost.fmax_mhz"]
    by_params = {(r["param.a"], r["param.b"], r["param.c"]): r for r in table}
    assert float(by_params["3", "6", ""]["torus.phong.max"]) == pytest.approx(3.6)
    assert float(by_params["3", "6", ""]["cost.lut4"]) == pytest.approx(36)
    assert float(by_params["", "", "4"]["torus.phong.max"]) == pytest.approx(400)
    assert {r["status"] for r in table} == {"ok"} and {r["cost.fmax_mhz"] for r in table} == {"90.0"}


def test_resume_runs_nothing_twice(stub):
    out = stub / "out"
    run_sweep(GRID, out=out, workers=1, progress=False, evaluate=stub_evaluate)
    assert len(calls(stub)) == 7
    again = run_sweep(GRID, out=out, workers=1, progress=False, evaluate=stub_evaluate)
    assert len(calls(stub)) == 7 and (again["skipped"], again["ran"]) == (7, 0)
    assert len(rows(out)) == 7 and len(load_records(out / "points.jsonl")) == 7


def test_torn_last_line_is_rerun(stub):
    out = stub / "out"
    run_sweep(GRID, out=out, workers=1, progress=False, evaluate=stub_evaluate)
    path = out / "points.jsonl"
    data = path.read_bytes()
    path.write_bytes(data[:-40])  # killed while writing the last record
    again = run_sweep(GRID, out=out, workers=1, progress=False, evaluate=stub_evaluate)
    assert again["ran"] == 1 and len(calls(stub)) == 8
    lines = path.read_text().splitlines()
    assert len(lines) == 7 and all(json.loads(line)["status"] == "ok" for line in lines)


@pytest.mark.parametrize("workers", [1, 2])
def test_interrupted_run_keeps_finished_points(stub, workers):
    import threading
    out = stub / "out"
    spec = {"scenes": ["torus"], "grid": [{"method": "alpha", "a": [1, 2, 7, 3, 4, 5]}]}
    threads = set(threading.enumerate())
    with pytest.raises(KeyboardInterrupt):
        run_sweep(spec, out=out, workers=workers, progress=False, evaluate=stub_evaluate)
    # a pool thread still running at exit races Python's exit hook (an EBADF traceback)
    assert [t.name for t in set(threading.enumerate()) - threads if t.is_alive()] == []
    kept = load_records(out / "points.jsonl")
    assert kept and all(r["status"] == "ok" for r in kept) and len(rows(out)) == len(kept)
    if workers == 1:
        assert [r["params"]["a"] for r in kept] == [1, 2]
    spec["grid"][0]["a"] = [1, 2, 8, 3, 4, 5]  # the user's fix; finished points keep their ids
    os.remove(stub / "calls.txt")
    again = run_sweep(spec, out=out, workers=workers, progress=False, evaluate=stub_evaluate)
    assert again["ran"] == 6 - len(kept) == len(calls(stub)) and again["ok"] == again["ran"]
    assert sorted(int(r["param.a"]) for r in rows(out)) == [1, 2, 3, 4, 5, 8]


def test_failed_point_is_recorded_and_rerun(stub):
    out = stub / "out"
    spec = {"scenes": ["torus"], "grid": [{"method": "alpha", "a": [12, 13, 14]}]}
    summary = run_sweep(spec, out=out, workers=2, progress=False, evaluate=stub_evaluate)
    assert (summary["ok"], summary["failed"]) == (2, 1)
    failed = [r for r in rows(out) if r["status"] == "failed"]
    assert [(r["param.a"], r["error"], r["torus.phong.max"]) for r in failed] == \
        [("13", "RuntimeError: boom", "")]
    again = run_sweep(spec, out=out, workers=1, progress=False, evaluate=stub_evaluate)
    assert (again["ran"], again["failed"]) == (1, 1) and len(calls(stub)) == 4
    kept = run_sweep(spec, out=out, workers=1, progress=False, evaluate=stub_evaluate,
                     rerun_failed=False)
    assert kept["ran"] == 0 and len(rows(out)) == 3


def test_bad_workers(stub):
    with pytest.raises(ValueError, match=r"^workers must be a positive integer, not 0$"):
        run_sweep(GRID, out=stub / "out", workers=0, evaluate=stub_evaluate)


SPEC_ERRORS = [
    ({"grid": [{"method": "gamma"}]},
     r"^sweep spec: grid\[0\]\.method: unknown method 'gamma'; methods: alpha, beta$"),
    ({"grid": [{"a": [1]}]}, r"^sweep spec: grid\[0\]\.method is missing; methods: alpha, beta$"),
    ({"points": [{"method": "beta", "a": 1}]},
     r"^sweep spec: points\[0\] \(beta\): unknown parameter 'a'; parameters: c, n$"),
    ({"grid": [{"method": "alpha", "a": []}]}, r"^sweep spec: grid\[0\]\.a must be a non-empty list, not \[\]$"),
    ({"grid": [{"method": "alpha", "a": [1, "8"]}]},
     r"^sweep spec: grid\[0\]\.a\[1\] must be an integer, not '8'$"),
    ({"points": [{"method": "alpha", "b": 2.5}]}, r"^sweep spec: points\[0\]\.b must be an integer, not 2\.5$"),
    ({"points": [{"method": "alpha", "a": [1, 2]}]},
     r"^sweep spec: points\[0\]\.a must be an integer, not \[1, 2\]$"),
    ({"grid": [{"method": "alpha", "a": [4, 17]}]},
     r"^sweep spec: grid\[0\] \(alpha, a=17\): a must be in \[1, 16\], not 17$"),
    ({"scenes": ["cube"], "grid": [{"method": "beta"}]},
     r"^sweep spec: scenes: unknown scene 'cube'; scenes: torus, sphere, or a scene file \(\.toml\) relative to the sweep file$"),
    ({"scenes": [], "grid": [{"method": "beta"}]},
     r"^sweep spec: scenes must be a non-empty list of scene names, not \[\]; scenes: torus, sphere, or a scene file \(\.toml\) relative to the sweep file$"),
    ({"synth": {"freq": -1}, "grid": [{"method": "beta"}]},
     r"^sweep spec: synth\.freq must be a number of MHz in \(0, 1000\], not -1$"),
    ({"synth": {"target": "xc7"}, "grid": [{"method": "beta"}]},
     r"^sweep spec: synth\.target must be one of ecp5, ice40, asic, not 'xc7'$"),
    ({"synth": {"fmax": 1}, "grid": [{"method": "beta"}]},
     r"^sweep spec: synth: unknown key 'fmax'; keys: target, freq, device, seed$"),
    ({"synth": {"target": "ice40", "device": "45k"}, "grid": [{"method": "beta"}]},
     r"^sweep spec: synth\.device must be one of up5k, hx8k, hx1k for ice40, not '45k'$"),
    ({"synth": {"seed": -2}, "grid": [{"method": "beta"}]},
     r"^sweep spec: synth\.seed must be a non-negative integer, not -2$"),
    ({"points": [{"method": "beta", "synth": {"freq": 0}}]},
     r"^sweep spec: points\[0\]\.synth\.freq must be a number of MHz in \(0, 1000\], not 0$"),
    ({"points": [{"method": "beta", "scenes": ["torus", 3]}]},
     r"^sweep spec: points\[0\]\.scenes must be a non-empty list of scene names, not \['torus', 3\]; "
     r"scenes: torus, sphere, or a scene file \(\.toml\) relative to the sweep file$"),
    ({"grid": [{"method": "beta", "synth": True}]},
     r"^sweep spec: grid\[0\]\.synth = true needs a top-level \[synth\] table"),
    ({"grids": [{"method": "beta"}]}, r"^sweep spec: unknown key 'grids'; keys: scenes, synth, proxy, grid, points$"),
    ({"grid": {"method": "beta"}}, r"^sweep spec: grid must be an array of tables \(\[\[grid\]\]\), not "),
    ({"scenes": ["torus"]}, r"^sweep spec: no points; add a \[\[grid\]\] or \[\[points\]\] table$"),
]


@pytest.mark.parametrize("spec, message", SPEC_ERRORS)
def test_spec_errors(stub, spec, message):
    with pytest.raises(SweepSpecError, match=message):
        load_spec(spec)


def test_spec_file_errors(stub):
    with pytest.raises(SweepSpecError, match=r"^sweep spec \S+nope\.toml: no such file$"):
        load_spec(stub / "nope.toml")
    bad = stub / "bad.toml"
    bad.write_text('scenes = ["torus"]\n[[grid]]\nmethod = "alpha"\na = [1, 2]\nb = = 3\n')
    with pytest.raises(SweepSpecError,
                       match=r"^sweep spec \S+bad\.toml: invalid TOML: Invalid value \(at line 5, column 5\)$"):
        load_spec(bad)
    good = stub / "good.toml"
    good.write_text('scenes = ["torus"]\n[[grid]]\nmethod = "alpha"\na = [1, 2]\n')
    assert [p["params"]["a"] for p in load_spec(good)["points"]] == [1, 2]
    assert isinstance(SweepSpecError("x"), ValueError)


REAL = {"scenes": ["sphere"], "grid": [{"method": "spherical", "addr_bits": [4, 8]}],
        "points": [{"method": "schlick", "t_frac": 8}]}


def _real_columns():
    metrics = [f"sphere.{ref}.{stat}" for ref in ("phong", "pixel-phong", "self", "pixel-self")
               for stat in ("max", "mean", "psnr", "pct_over1")]
    return (["id", "method", "status", "error", "seconds", "param.addr_bits", "param.rom_bits",
             "param.theta_frac", "param.n", "param.t_frac", "param.out_frac"] + metrics
            + ["cost.lut_eq", "cost.dsp", "cost.model"])  # no synthesis asked: the ECP5 proxy


def _check_real(out):
    from phongfx.explore.evaluate import evaluate
    table = rows(out)
    assert list(table[0]) == _real_columns() and [r["status"] for r in table] == ["ok"] * 3
    by = {(r["method"], r["param.addr_bits"] or r["param.t_frac"]): r for r in table}
    # Szirmay-Kalos et al. 2000, Fig. 11: more ROM address bits, a smaller table error
    assert float(by["spherical", "8"]["sphere.self.max"]) < float(by["spherical", "4"]["sphere.self.max"])
    direct = evaluate("schlick", {"t_frac": 8}, scenes=("sphere",), proxy="ecp5")
    assert {k: float(by["schlick", "8"][k]) for k in direct["metrics"]} == pytest.approx(direct["metrics"])
    assert float(by["schlick", "8"]["cost.lut_eq"]) == direct["cost"]["lut_eq"] > 0
    assert by["schlick", "8"]["cost.model"] == "ecp5-proxy"


def test_real_sweep_on_the_local_pool(tmp_path):
    summary = run_sweep(REAL, out=tmp_path, workers=2, progress=False)
    assert (summary["ok"], summary["failed"]) == (3, 0)
    _check_real(tmp_path)


def test_real_sweep_on_a_dask_local_cluster(tmp_path):
    pytest.importorskip("distributed", reason="Dask is the optional extra phongfx[cluster]")
    summary = run_sweep(REAL, out=tmp_path, workers=2, scheduler="local", progress=False)
    assert (summary["ok"], summary["failed"]) == (3, 0)
    _check_real(tmp_path)
    again = run_sweep(REAL, out=tmp_path, workers=2, scheduler="local", progress=False)
    assert (again["skipped"], again["ran"]) == (3, 0)  # resumed: no cluster work at all


def test_dask_missing_is_a_clear_error(stub, monkeypatch):
    import builtins
    real_import = builtins.__import__

    def no_dask(name, *args, **kwargs):
        if name.split(".")[0] in ("dask", "distributed"):
            raise ImportError(f"No module named {name!r}")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_dask)
    with pytest.raises(ValueError, match=r"^scheduler 'local' needs Dask, which is not installed: "
                                         r"pip install phongfx\[cluster\]$"):
        run_sweep(GRID, out=stub / "out", scheduler="local", progress=False, evaluate=stub_evaluate)


# --- Ctrl-C: a real SIGINT to a child `phongfx sweep` on two workers --------------------------

_SLOW_CHILD = r'''
import os, subprocess, sys, time
import phongfx.explore.evaluate as ev
from phongfx.cli import main

def slow(method, params, *, scenes, synth=None, proxy=None):
    """addr_bits 4 finishes at once; every other point runs a tool for a minute."""
    if params["addr_bits"] != 4:
        script = "import os, sys, time; open(sys.argv[1], 'w').write(str(os.getpid())); time.sleep(60)"
        subprocess.run([sys.executable, "-c", script, os.path.join(sys.argv[1], f"tool{params['addr_bits']}.pid")])
    return {"metrics": {"sphere.phong.max": float(params["addr_bits"])}, "cost": None}

ev.evaluate = slow
sys.exit(main(["sweep", os.path.join(sys.argv[1], "spec.toml"), "--workers", "2", "--quiet",
               "--out", os.path.join(sys.argv[1], "out")]))
'''


def alive(pid):
    """Whether ``pid`` runs; a zombie (killed, its parent gone, not yet reaped by init) does not."""
    try:
        with open(f"/proc/{pid}/stat") as file:
            return file.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@pytest.mark.parametrize("to", ["group", "parent"])
def test_ctrl_c_stops_the_workers_at_once_and_a_rerun_resumes(tmp_path, to):
    # "group" is a terminal's Ctrl-C (every process of the group gets it), "parent" a kill -INT;
    # before, the parent waited for the running points: a minute here, minutes with synthesis
    import signal
    import subprocess
    import sys
    import time
    (tmp_path / "spec.toml").write_text('scenes = ["sphere"]\nproxy = false\n'
                                        '[[grid]]\nmethod = "spherical"\naddr_bits = [4, 5, 6, 7]\n')
    # SIGINT at its default and unblocked in the child, whatever this test worker inherited (an ignored SIGINT
    # passes on through exec, and Python then never raises KeyboardInterrupt)
    child = subprocess.Popen([sys.executable, "-c", _SLOW_CHILD, str(tmp_path)], stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True, start_new_session=True,
                             preexec_fn=lambda: (signal.signal(signal.SIGINT, signal.SIG_DFL),
                                                 signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})))
    jsonl, deadline = tmp_path / "out" / "points.jsonl", time.monotonic() + 60
    while not (jsonl.is_file() and any(tmp_path.glob("tool*.pid"))) and child.poll() is None \
            and time.monotonic() < deadline:
        time.sleep(0.05)
    time.sleep(0.3)  # the tool is running
    assert child.poll() is None, "the sweep ended before it could be interrupted"
    sent = time.monotonic()
    (os.killpg if to == "group" else os.kill)(child.pid, signal.SIGINT)
    try:
        _, err = child.communicate(timeout=20)
    finally:
        child.kill()
    seconds = time.monotonic() - sent
    assert child.returncode == 130 and seconds < 5, (child.returncode, seconds, err)
    assert len(err.strip().splitlines()) == 1 and err.startswith("phongfx: interrupted"), err
    time.sleep(0.3)
    tools = [int(p.read_text() or 0) for p in tmp_path.glob("tool*.pid")]
    assert not any(alive(pid) for pid in tools if pid), "a worker's tool outlived the sweep"
    kept = load_records(jsonl)
    assert [(r["params"]["addr_bits"], r["status"]) for r in kept] == [(4, "ok")]

    def quick(method, params, **options):
        return {"metrics": {"sphere.phong.max": 0.5}, "cost": None}
    again = run_sweep(tmp_path / "spec.toml", out=tmp_path / "out", workers=1, progress=False, evaluate=quick)
    assert (again["skipped"], again["ran"], again["ok"]) == (1, 3, 3)


# --- scene files -----------------------------------------------------------------------------

TINY_SCENE = """name = "tiny"
[camera]
at = "infinity"
[[lights]]
direction = [1, 1, 1]
[[lights]]
direction = [-1, 0.5, 1]
[materials.m]
kd = 0.6
ks = 0.4
n = 16
[[objects]]
type = "sphere"
material = "m"
[frames]
count = 2
axis = [0, 1, 0]
degrees = 30
[output]
width = 32
height = 32
"""


def test_a_scene_file_is_a_sweep_scene_resolved_from_the_sweep_file(tmp_path, monkeypatch):
    from phongfx.explore.evaluate import evaluate
    (tmp_path / "study").mkdir()
    (tmp_path / "scenes").mkdir()
    (tmp_path / "scenes" / "tiny.toml").write_text(TINY_SCENE)
    spec = tmp_path / "study" / "spec.toml"
    spec.write_text('scenes = ["../scenes/tiny.toml", "sphere"]\nproxy = false\n'
                    '[[grid]]\nmethod = "schlick"\nt_frac = [8, 12]\n')
    monkeypatch.chdir(tmp_path)  # not the sweep file's folder: the path is the spec's
    points = load_spec(spec)["points"]
    assert [p["scenes"] for p in points] == [["tiny", "sphere"]] * 2
    assert points[0]["scene_files"] == {"tiny": str(tmp_path / "scenes" / "tiny.toml")}
    summary = run_sweep(spec, out=tmp_path / "out", workers=1, progress=False)
    assert (summary["ok"], summary["failed"]) == (2, 0)
    record = load_records(tmp_path / "out" / "points.jsonl")[0]
    direct = evaluate("schlick", {"t_frac": 8}, scenes=(str(tmp_path / "scenes" / "tiny.toml"),))["metrics"]
    assert record["metrics"]["tiny.phong.max"] == direct["tiny.phong.max"] > 0
    assert "sphere.phong.max" in record["metrics"] and "tiny.pixel-self.mean" in record["metrics"]
    # an edited scene file is a new point; an unchanged one is skipped
    again = run_sweep(spec, out=tmp_path / "out", workers=1, progress=False)
    assert (again["skipped"], again["ran"]) == (2, 0)
    (tmp_path / "scenes" / "tiny.toml").write_text(TINY_SCENE.replace("degrees = 30", "degrees = 40"))
    assert {p["id"] for p in load_spec(spec)["points"]}.isdisjoint(p["id"] for p in points)


SCENE_ERRORS = [
    ('scenes = ["my.toml"]', "my.toml", None,
     r"^sweep spec \S+spec\.toml: scenes\[0\]: no scene file 'my\.toml' \(looked for \S+/my\.toml\); "
     r"scenes: torus, sphere, or a scene file \(\.toml\) relative to the sweep file$"),
    ('scenes = ["lit.toml"]', "lit.toml", TINY_SCENE.replace("direction = [1, 1, 1]", "position = [3, 3, 3]"),
     r"^sweep spec \S+: scenes\[0\] 'lit\.toml': lights\[0\] is a point light; sweeps take lights at infinity"),
    ('scenes = ["bad.toml"]', "bad.toml", TINY_SCENE.replace("kd = 0.6", "kd = 6"),
     r"^sweep spec \S+: scenes\[0\] 'bad\.toml': \S+bad\.toml: materials\.m\.kd must be"),
    ('scenes = ["sphere", "sphere.toml"]', "sphere.toml", TINY_SCENE,
     r"^sweep spec \S+: scenes\[1\]: 'sphere\.toml' names its metrics 'sphere' as an earlier scene does; "
     r"rename the file$"),
]


@pytest.mark.parametrize("top, name, text, message", SCENE_ERRORS)
def test_scene_file_errors_name_the_field_and_the_value(stub, top, name, text, message):
    if text is not None:
        (stub / name).write_text(text)
    spec = stub / "spec.toml"
    spec.write_text(f'{top}\n[[grid]]\nmethod = "alpha"\n')
    with pytest.raises(SweepSpecError, match=message):
        load_spec(spec)
