"""The ``verilator-fast`` simulator's build: its run-time objects compiled ahead (``warm``), and
a failed build's error."""

import pytest

from phongfx.core.registry import get_block
from phongfx.sim import build_cache, fast_build

pytestmark = pytest.mark.needs_verilator


def test_warm_compiles_the_run_time_objects_alone_and_a_build_then_only_its_design(tmp_path):
    """``warm`` (the compile's, beside its search) keeps the run-time objects of the flavour and
    compiles no design; the next build copies them in and compiles its design only."""
    lirp = get_block("lirp")
    assert fast_build.warm(lirp.component(), build_dir=tmp_path, optimize=False)
    runtime = list(tmp_path.glob("runtime-*"))
    assert len(runtime) == 1 and sorted(p.name for p in runtime[0].glob("*.o")) == ["verilated.o",
                                                                                  "verilated_threads.o"]
    assert list(tmp_path.glob("runtime-*.part-*")) == [] and list(tmp_path.glob("*/phongfx_sim")) == []
    assert not fast_build.warm(lirp.component(), build_dir=tmp_path, optimize=False)  # kept: nothing to do
    fast_build.build(get_block("shape").component(), build_dir=tmp_path, optimize=False)
    log = next(tmp_path.glob("*/build.log")).read_text()
    assert "Vtop__ALL.o" in log and "-o verilated.o" not in log and "-o verilated_threads.o" not in log


def test_build_failure_raises_with_log(monkeypatch, tmp_path):
    monkeypatch.setattr(build_cache, "verilog", lambda *args, **kwargs: "module broken(;\n")
    with pytest.raises(RuntimeError, match=r"^Verilator build of lirp failed .*log .*build\.log"):
        fast_build.build(get_block("lirp").component(), build_dir=tmp_path)
