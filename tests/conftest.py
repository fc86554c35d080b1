"""The test tiers: every test is marked at collection with the external tools it needs, so
``-m`` filters on them (``make check`` runs those that need none).

* ``needs_verilator``: a Verilator back end (a ``backend`` parameter of ``"verilator"`` or
  ``"verilator-fast"``, or the mark set in the test file);
* ``needs_yosys`` (Yosys and nextpnr from PyPI: synthesis), ``needs_sta`` (OpenSTA and the
  OSU cells, through the :func:`asic_tools` fixture), ``needs_sby`` (SymbiYosys proofs),
  ``needs_iverilog`` (Icarus Verilog), ``needs_gappa`` (Gappa): set in the test files, or
  by a fixture that stands for the tool or needs it (:data:`FIXTURE_NEEDS`: :func:`asic_tools`,
  ``verilator_exe``; :func:`tiny_compiled`, whose compile runs the RTL check);
* the cocotb back end (``backend="verilator"``) checks the same Verilog as
  ``verilator-fast`` at about twice the cost, so it runs by default only in
  :data:`COCOTB_TESTS`, the proof that back end works; elsewhere a cocotb run whose
  ``verilator-fast`` twin (same test, same other parameters) runs is marked ``slow``
  (``make test-all`` runs it).

The marks are added before pytest's own ``-m`` deselection (``tryfirst``), so a filter
sees them; a mark added while a fixture runs would come too late.
"""

import contextlib
import io
import os
import shutil
from pathlib import Path
from types import SimpleNamespace

import pytest

from phongfx.explore.synth.asic import LIBRARIES
from phongfx.sim.harness import BACKENDS

#: Marks by what a test needs (registered in ``pyproject.toml``).
NEEDS = ("needs_verilator", "needs_yosys", "needs_sta", "needs_sby", "needs_iverilog", "needs_gappa")
#: Tests (node id prefixes) whose cocotb runs stay in the default run: ``test_harness.py``
#: tests the cocotb back end itself (stalls, resets, waveforms, build failures),
#: ``test_lirp.py`` runs the smallest block through it, with and without bubbles, and the
#: Figure 7 datapath is the widest design (a payload of hundreds of bits, which cocotb
#: drives as one big integer).
COCOTB_TESTS = ("tests/sim/test_harness.py::", "tests/hdl/test_lirp.py::",
                "tests/hdl/test_datapath.py::test_harness[verilator-fig7]")
VERILATOR_BACKENDS = ("verilator", "verilator-fast")
#: Fixtures that stand for a tool: a test that asks for one needs it.
FIXTURE_NEEDS = {"asic_tools": ("needs_yosys", "needs_sta"), "verilator_exe": ("needs_verilator",),
                 "tiny_compiled": ("needs_verilator",)}
BACKEND_PARAMETERS = ("backend", "stream_backend")


def _backend(item):
    """``(parameter name, back end)`` of a test parametrized by back end, else (None, None)."""
    params = getattr(getattr(item, "callspec", None), "params", {})
    return next(((name, params[name]) for name in BACKEND_PARAMETERS if name in params), (None, None))


def _twin_key(item, parameter, backend):
    params = item.callspec.params
    others = tuple(sorted((k, repr(v)) for k, v in params.items() if k != parameter))
    return item.path, item.originalname, others, backend


#: Seconds a test marked slow may run before it is failed as hung (pyproject's timeout is the
#: default tier's).
SLOW_TIMEOUT = 3600


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    fast = {_twin_key(item, *_backend(item)) for item in items if _backend(item)[1] == "verilator-fast"}
    for item in items:
        parameter, backend = _backend(item)
        if backend in VERILATOR_BACKENDS:
            item.add_marker(pytest.mark.needs_verilator)
        if (backend == "verilator" and not item.nodeid.startswith(COCOTB_TESTS)
                and _twin_key(item, parameter, "verilator-fast") in fast):
            item.add_marker(pytest.mark.slow)
        for fixture, marks in FIXTURE_NEEDS.items():
            if fixture in item.fixturenames:
                for mark in marks:
                    item.add_marker(getattr(pytest.mark, mark))
        if item.get_closest_marker("slow") and not item.get_closest_marker("timeout"):
            # the long sweeps run for up to an hour; the default tier's 15 minutes is for hangs
            item.add_marker(pytest.mark.timeout(SLOW_TIMEOUT))


def pytest_runtest_setup(item):
    """A test that needs Icarus Verilog or Gappa is skipped where it is missing (``make``
    installs them where apt-get works)."""
    if item.get_closest_marker("needs_iverilog") and not (shutil.which("iverilog") and shutil.which("vvp")):
        pytest.skip("Icarus Verilog (iverilog, vvp) is not installed; apt-get install iverilog")
    if item.get_closest_marker("needs_gappa") and not shutil.which("gappa"):
        pytest.skip("Gappa is not installed; apt-get install gappa")


@pytest.fixture(params=BACKENDS)
def backend(request):
    """Every harness test runs on each back end (the Verilator ones marked at collection)."""
    return request.param


@pytest.fixture(scope="session")
def asic_tools():
    """OpenSTA and the OSU Liberty files (Debian's ``opensta``, ``qflow-tech-osu018`` and
    ``qflow-tech-osu035``, which ``make`` installs where apt-get works).  Where they are
    absent the test is skipped, but only where they could not have been installed: as
    root with apt-get (CI) their absence fails the test."""
    missing = [name for name, lib in LIBRARIES.items() if not Path(lib.path).is_file()]
    missing += [] if shutil.which("sta") else ["opensta"]
    if missing:
        message = f"standard-cell tools missing: {', '.join(missing)}"
        if os.geteuid() == 0 and shutil.which("apt-get"):
            pytest.fail(f"{message}, though apt-get could install them (run make)")
        pytest.skip(f"{message}; apt-get install opensta qflow-tech-osu018 qflow-tech-osu035")


#: The IHP SG13G2 files the standard-cell tests use (never the project at run time).
SG13G2_FILES = ("sg13g2_stdcell_typ_1p20V_25C.lib", "sg13g2_stdcell_slow_1p08V_125C.lib",
                "sg13g2_stdcell_fast_1p32V_m40C.lib", "sg13g2_stdcell.v", "sg13g2_udp.v")


def _checkouts(root):
    """``root`` and, for a git worktree, the main checkout it was made from."""
    yield root
    marker = root / ".git"
    if marker.is_file() and marker.read_text().startswith("gitdir:"):
        gitdir = Path(marker.read_text().split(":", 1)[1].strip())
        if gitdir.parent.name == "worktrees":
            yield gitdir.parent.parent.parent


@pytest.fixture(scope="session")
def sg13g2():
    """The folder of IHP SG13G2's standard-cell Liberty files and Verilog models: env
    ``PHONGFX_SG13G2``, else ``../shared/pdk/ihp-sg13g2`` beside the checkout.  Absent, the
    test is skipped saying where to get them."""
    root = Path(__file__).resolve().parents[1]
    candidates = [Path(os.environ["PHONGFX_SG13G2"])] if os.environ.get("PHONGFX_SG13G2") else []
    candidates += [checkout.parent / "shared" / "pdk" / "ihp-sg13g2" for checkout in _checkouts(root)]
    for folder in candidates:
        if all((folder / name).is_file() for name in SG13G2_FILES):
            return folder
    pytest.skip(f"IHP SG13G2 standard cells not found (looked in {', '.join(map(str, candidates))}): get "
                f"{', '.join(SG13G2_FILES)} from github.com/IHP-GmbH/IHP-Open-PDK, "
                f"ihp-sg13g2/libs.ref/sg13g2_stdcell/{{lib,verilog}}/, and set PHONGFX_SG13G2 to their folder")


@pytest.fixture(scope="session")
def tiny_compiled(tmp_path_factory):
    """One ``phongfx compile`` of the tiny torus (``tests/compiler/test_compile.py``'s
    ``TORUS`` at 1 level against Phong; fig7 and blinn, ``--sampled``, with the RTL check),
    shared by the tests that read a compiled folder: a compile takes seconds to a minute, so
    the suite makes this one once.  ``.scene`` (the scene file), ``.out`` (the folder),
    ``.code`` (the exit code), ``.stdout``, ``.stderr``; the tests only read the folder."""
    from phongfx.cli import main
    from tests.compiler.test_compile import TORUS

    root = tmp_path_factory.mktemp("tiny-compiled")
    scene, out = root / "tiny.toml", root / "out"
    scene.write_text(TORUS.format(error=1.0, against="phong"))
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        code = main(["compile", str(scene), "-o", str(out), "--methods", "fig7,blinn", "--sampled", "--quiet"])
    return SimpleNamespace(scene=scene, out=out, code=code, stdout=stdout.getvalue(), stderr=stderr.getvalue())
