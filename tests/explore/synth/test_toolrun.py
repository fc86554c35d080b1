"""The cache of synthesis runs (phongfx.explore.synth.toolrun.cached_run): a failed flow
leaves no hidden or half folder, only its logs in ``failed/<key>``, which the error names."""

import pytest

from phongfx.explore.synth.toolrun import SynthError, cached_run


def _entries(root):
    return sorted(str(path.relative_to(root)) for path in root.rglob("*"))


def test_a_failed_synthesis_leaves_its_log_in_failed_and_nothing_hidden(tmp_path):
    def failing_flow(work):
        (work / "nextpnr.log").write_text("ERROR: Net 'in_shift[39]' is multiply driven\n")
        raise SynthError(f"nextpnr failed (exit code 1); log {work / 'nextpnr.log'}")

    with pytest.raises(SynthError) as error:
        cached_run(tmp_path, "0123abcd", failing_flow)
    log = tmp_path / "failed" / "0123abcd" / "nextpnr.log"
    assert str(error.value) == f"nextpnr failed (exit code 1); log {log}"
    assert _entries(tmp_path) == ["failed", "failed/0123abcd", "failed/0123abcd/nextpnr.log"]
    assert not [path for path in tmp_path.rglob(".*")]

    # the same key succeeding later: the entry, and the stale failure's logs gone
    result = cached_run(tmp_path, "0123abcd", lambda work: {"lut4": 3})
    assert result == {"lut4": 3, "cached": False, "directory": str(tmp_path / "0123abcd")}
    assert _entries(tmp_path) == ["0123abcd", "0123abcd/result.json", "failed"]


def test_a_design_is_elaborated_once_for_every_reader_of_its_text(monkeypatch):
    from amaranth.back import rtlil

    from phongfx.core.registry import get_block
    from phongfx.explore.synth import toolrun
    from phongfx.explore.synth.proxy import rtlil_of
    from phongfx.hdl.overflow import overflow_checks

    conversions = []
    convert = rtlil.convert
    monkeypatch.setattr(rtlil, "convert", lambda *a, **k: conversions.append(1) or convert(*a, **k))
    monkeypatch.setattr(toolrun, "_ELABORATED", {})
    lirp = get_block("lirp")
    text = toolrun.design_rtlil(lirp, "top")
    assert rtlil_of(lirp) is text and len(conversions) == 1
    # the text synthesis builds: no simulation-only overflow flag, no source location
    with overflow_checks(False):
        assert text == convert(lirp.component(), name="top", emit_src=False)
    assert toolrun.design_rtlil(lirp, "other") != text and len(conversions) == 2
    for name in ("shape", "difference", "normalize", "diffuse"):  # KEEP designs more: the first is forgotten
        toolrun.design_rtlil(get_block(name), "top")
    assert toolrun.KEEP == 4 and toolrun.design_rtlil(lirp, "top") == text and len(conversions) == 7

