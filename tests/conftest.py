import pytest

from phongfx.sim.harness import BACKENDS


@pytest.fixture(params=BACKENDS)
def backend(request):
    """Every harness test runs on each back end; Verilator runs are marked ``verilator``."""
    if request.param.startswith("verilator"):
        request.applymarker(pytest.mark.verilator)
    return request.param


@pytest.fixture(scope="session")
def asic_tools():
    """OpenSTA and the OSU Liberty files (Debian's ``opensta``, ``qflow-tech-osu018`` and
    ``qflow-tech-osu035``, which ``make`` installs where apt-get works).  Where they are
    absent the test is skipped, but only where they could not have been installed: as
    root with apt-get (CI) their absence fails the test."""
    import os
    import shutil
    from pathlib import Path

    from phongfx.explore.synth.asic import LIBRARIES

    missing = [name for name, lib in LIBRARIES.items() if not Path(lib.path).is_file()]
    missing += [] if shutil.which("sta") else ["opensta"]
    if missing:
        message = f"standard-cell tools missing: {', '.join(missing)}"
        if os.geteuid() == 0 and shutil.which("apt-get"):
            pytest.fail(f"{message}, though apt-get could install them (run make)")
        pytest.skip(f"{message}; apt-get install opensta qflow-tech-osu018 qflow-tech-osu035")
