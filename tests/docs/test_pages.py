"""Every command line shown in the documentation runs, or at least parses.

The convention is ``docs/testing.rst``'s: console blocks run in page order in one folder
per page, ``PHONGFX_CACHE`` shared by the whole session; ``long`` blocks are parsed by the
tool's own argument parser; a command shown anywhere else fails, since nothing would check it.
"""

import os
import re
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from phongfx.cli.parser import build_parser

from tests.docs.pages import DOCS, blocks, matches, pages

ROOT = DOCS.parent
#: a shell command the pages may show: the tool, make, or a script of an output folder
_COMMAND = re.compile(r"^\s*(\$ )?(phongfx|make|sh|VERILATOR=\S+ sh) ")
_TOOLS = {"iverilog": "iverilog", "verilator": None, "yosys": None, "sta": "sta", "sby": None}


def _runnable():
    """One test per page: its blocks depend on each other (a compile, then its testbench), so they
    run in page order in one folder, whichever worker runs the page; the page carries every mark
    its blocks need, so ``-m "not needs_verilator"`` leaves out a page that builds a model."""
    for page in pages():
        runnable = [b for b in blocks(page) if b.language == "console" and not b.long]
        if runnable:
            needs = sorted({tool for block in runnable for tool in block.needs})
            marks = [getattr(pytest.mark, f"needs_{tool}") for tool in needs]
            yield pytest.param(page, runnable, id=page, marks=marks)


def _long():
    for page in pages():
        for block in blocks(page):
            if block.language == "console" and block.long:
                yield pytest.param(block, id=f"{page}:{block.lineno}")


@pytest.fixture(scope="session")
def cache(tmp_path_factory):
    """One cache for the session, unless the caller points ``PHONGFX_CACHE`` at one."""
    return os.environ.get("PHONGFX_CACHE") or str(tmp_path_factory.mktemp("phongfx-cache"))


@pytest.fixture(scope="session")
def folders(tmp_path_factory):
    """One working folder per page, with copies of scenes/ and sweeps/ and the page's files."""
    made = {}

    def folder(page):
        if page not in made:
            path = tmp_path_factory.mktemp(page.replace("/", "-").removesuffix(".rst"))
            for name in ("scenes", "sweeps"):
                shutil.copytree(ROOT / name, path / name)
            for block in blocks(page):
                if block.caption and block.language != "console":
                    (path / block.caption).write_text(block.text + "\n", encoding="utf-8")
            made[page] = path
        return made[page]
    return folder


@pytest.mark.parametrize(("page", "runnable"), list(_runnable()))
def test_commands_run_and_print_what_the_page_shows(page, runnable, folders, cache):
    env = dict(os.environ, PHONGFX_CACHE=cache,
               PATH=os.pathsep.join([str(Path(sys.executable).parent), os.environ.get("PATH", "")]))
    cwd = folders(page)
    missing_tools = set()
    for block in runnable:
        absent = [tool for tool in block.needs if _TOOLS.get(tool) and shutil.which(_TOOLS[tool]) is None]
        if absent:
            missing_tools.update(absent)
            continue
        for command in block.commands():
            run = subprocess.run(["bash", "-c", command.line], cwd=cwd, env=env, capture_output=True,
                                 text=True, timeout=600)
            output = run.stdout + run.stderr
            where = f"{page}:{block.lineno}: {command.line}"
            assert run.returncode == 0, f"{where}\n{output[-3000:]}"
            missing = [line for line in command.expected if not matches(line, output)]
            assert not missing, f"{where}\nmissing {missing}\nin\n{output[-3000:]}"
    if missing_tools:
        pytest.skip(f"blocks that need {', '.join(sorted(missing_tools))} were not run: not installed")


def _makefile_targets():
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    return set(re.findall(r"^([A-Za-z][\w-]*):", text, flags=re.M))


@pytest.mark.parametrize("block", list(_long()))
def test_long_commands_name_real_subcommands_options_and_targets(block):
    """A command too long to run still uses only what exists: argparse says so for phongfx."""
    assert block.commands(), f"{block.page}:{block.lineno}: a console block without a command"
    for command in block.commands():
        words = shlex.split(command.line, comments=True)
        while words and re.fullmatch(r"[A-Z_]+=\S*", words[0]):
            words.pop(0)
        if words[0] == "phongfx":
            try:
                build_parser().parse_args(words[1:])
            except SystemExit as exit:
                pytest.fail(f"{block.page}:{block.lineno}: {command.line}: refused ({exit.code})")
        elif words[0] == "make":
            assert set(words[1:]) <= _makefile_targets(), f"{block.page}:{block.lineno}: {command.line}"
        else:
            assert words[0] == "sh", f"{block.page}:{block.lineno}: {command.line}: not a command the test knows"


@pytest.mark.parametrize("page", pages())
def test_no_command_is_shown_outside_a_console_block(page):
    for block in blocks(page):
        if block.language != "console":
            shown = [line for line in block.text.splitlines() if line.startswith("$ ")
                     or (block.language in ("sh", "bash", "shell") and _COMMAND.match(line))]
            assert not shown, f"{page}:{block.lineno}: commands outside a console block: {shown}"


def test_the_page_reader_sees_the_pages_commands():
    """The reader itself: the tutorial's compile command, its expected lines, its scene file."""
    tutorial = blocks("tutorial.rst")
    scene = [b for b in tutorial if b.caption == "my-scene.toml"]
    assert len(scene) == 1 and 'name = "my-scene"' in scene[0].text
    compile_block = next(b for b in tutorial if b.language == "console")
    (command,) = compile_block.commands()
    assert command.line == (
        "phongfx compile my-scene.toml -o my-core --methods fig7 --samples 100000 --final-samples 1000000 "
        "--testbench --quiet")
    assert "cost model: ecp5-proxy; wrote my-core/manifest.json" in command.expected
    assert matches("RTL check frame 0: 1608 pixels, ... 0 mismatches, ...",
                   "RTL check frame 0: 1608 pixels, 2457 cycles (20% stalls), 0 mismatches, 1.87 s\n")
    assert not matches("PASS 1608 vectors", "FAIL vector 3\n")


def test_every_subcommand_has_its_page_with_its_options():
    """``phongfx --help`` lists the subcommands; each has ``docs/commands/NAME.rst`` printing its help."""
    parser = build_parser()
    (subcommands,) = [a.choices for a in parser._subparsers._group_actions]
    index = (DOCS / "commands" / "index.rst").read_text(encoding="utf-8")
    for name in subcommands:
        page = DOCS / "commands" / f"{name}.rst"
        assert page.exists(), f"no page for phongfx {name}"
        assert f".. phongfx-help:: {name}" in page.read_text(encoding="utf-8"), page
        assert f"\n   {name}\n" in index, f"commands/index.rst does not list {name}"
