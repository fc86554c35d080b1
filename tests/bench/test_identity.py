"""The behaviour identity check compares what matters and only that."""

import contextlib
import io
import json

from bench.identity import compare, listed_blocks, normalize_json, normalize_verilog


def test_verilog_without_src_attributes():
    a = '(* src = "/a/hdl/lirp.py:10" *)\nwire \\$1 ;\n  (* src = "/a/x.py:3" *) assign x = y;\n'
    b = '(* src = "/b/elsewhere.py:99" *)\nwire \\$1 ;\n  (* src = "/b/y.py:4" *) assign x = y;\n'
    assert normalize_verilog(a) == normalize_verilog(b)
    assert normalize_verilog(a) != normalize_verilog(b.replace("assign x = y", "assign x = z"))


def test_json_without_timings_and_capture_paths():
    a = {"rows": [{"lut4": 10, "seconds": 1.5, "cached": False, "log": "/c1/build/synth/.ab12.xyz01/log"}],
         "cycles_per_second": {"verilator": 1e6}}
    b = {"rows": [{"lut4": 10, "seconds": 9.0, "cached": True, "log": "/c2/build/synth/.ab12.qq77/log"}],
         "cycles_per_second": {"verilator": 2e6}}
    assert normalize_json(a, "/c1") == normalize_json(b, "/c2")
    b["rows"][0]["lut4"] = 11
    assert normalize_json(a, "/c1") != normalize_json(b, "/c2")


def _capture(root, verilog, table, extra=None):
    (root / "verilog").mkdir(parents=True)
    (root / "tables").mkdir()
    (root / "verilog" / "lirp.v").write_text(verilog)
    (root / "tables" / "pipeline.json").write_text(json.dumps(table))
    if extra:
        (root / "verilog" / extra).write_text("module x; endmodule\n")
    return root


def test_compare_finds_each_kind_of_difference(tmp_path, capsys):
    v = '(* src = "/a.py:1" *)\nmodule lirp; endmodule\n'
    table = {"source": "old words", "rows": [1, 2]}
    a = _capture(tmp_path / "a", v, table)
    same = _capture(tmp_path / "same", v.replace("/a.py:1", "/b.py:7"), {**table, "source": "new words"})
    assert compare(str(a), str(same)) == (2, [])
    assert "intended: tables/pipeline.json source: 'old words' -> 'new words'" in capsys.readouterr().out

    other = _capture(tmp_path / "other", v.replace("lirp;", "lirp2;"), {**table, "rows": [1, 3]}, extra="b.v")
    count, differences = compare(str(a), str(other))
    assert count == 2
    assert differences == [f"only in {other}: verilog/b.v", "differs: tables/pipeline.json",
                           "differs: verilog/lirp.v"]
    assert compare(str(a), str(other), common_only=True)[1] == differences[1:]
    assert compare(str(a), str(other), ignore=("tables/",))[1] == [differences[0], differences[2]]


def test_a_compiled_folder_s_report_page_is_a_view_not_compared(tmp_path):
    """``report.html`` is made from the manifest and PNGs beside it, which are compared: a
    capture with it and one from before it (without) agree, and so do two pages that differ."""
    table = {"rows": [1]}
    a = _capture(tmp_path / "a", "module lirp; endmodule\n", table)
    b = _capture(tmp_path / "b", "module lirp; endmodule\n", table)
    for root in (a, b):
        (root / "work" / "compile" / "torus").mkdir(parents=True)
        (root / "work" / "compile" / "torus" / "manifest.json").write_text('{"chosen": "fig7"}')
    (b / "work" / "compile" / "torus" / "report.html").write_text("<p>certified in 5.6 s</p>")
    assert compare(str(a), str(b)) == (3, [])
    (a / "work" / "compile" / "torus" / "report.html").write_text("<p>certified in 9.1 s</p>")
    assert compare(str(a), str(b)) == (3, [])


def test_the_blocks_are_read_from_phongfx_blocks_with_wrapped_configs():
    from phongfx.cli import main
    from phongfx.core.registry import REGISTRY

    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        assert main(["blocks"]) == 0
    assert "\n  " in out.getvalue()  # some configs wrap onto a second line
    assert listed_blocks(out.getvalue()) == list(REGISTRY)


def test_the_compile_journal_s_source_key_is_not_a_difference():
    # the key hashes the package's source: every change of the code renames the file
    a = {"evaluation": {"journal": "/cap/a/work/build/compile/c3a40cb7ae698de9f5a4.jsonl"}}
    b = {"evaluation": {"journal": "/cap/b/work/build/compile/313c2688006ececf15af.jsonl"}}
    assert normalize_json(a, "/cap/a") == normalize_json(b, "/cap/b") == {
        "evaluation": {"journal": "<capture>/work/build/compile/<source key>.jsonl"}}
    assert normalize_json({"p": "/cap/a/x/compile/notes.jsonl"}, "/cap/a") == {"p": "<capture>/x/compile/notes.jsonl"}
