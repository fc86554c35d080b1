import pytest

from phongfx.sim.harness import BACKENDS


@pytest.fixture(params=BACKENDS)
def backend(request):
    """Every harness test runs on each back end; Verilator runs are marked ``verilator``."""
    if request.param.startswith("verilator"):
        request.applymarker(pytest.mark.verilator)
    return request.param
