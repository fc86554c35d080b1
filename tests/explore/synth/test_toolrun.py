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
