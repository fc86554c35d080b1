"""The documentation builds with warnings as errors and every cross-reference resolved."""

import importlib.util
import os
import re
import subprocess
import sys

import pytest

from tests.docs.pages import DOCS


@pytest.mark.skipif(importlib.util.find_spec("sphinx") is None,
                    reason="Sphinx is not installed (pip install -e '.[docs]', as make does)")
def test_docs_build_without_a_warning(tmp_path):
    run = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q", "-b", "html",
                          str(DOCS), str(tmp_path / "html")], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-5000:]
    assert (tmp_path / "html" / "tutorial.html").exists()


def test_importing_the_documented_packages_writes_nothing(tmp_path):
    """Autodoc imports them: that must leave no file behind, in the current folder or the cache."""
    code = ("import phongfx, phongfx.core, phongfx.core.format, phongfx.core.files, phongfx.core.registry, "
            "phongfx.config, phongfx.explore.compile as c, phongfx.explore.compile.emit, phongfx.compiler as d\n"
            "[getattr(phongfx, n) for n in phongfx.__all__]\n[getattr(m, n) for m in (c, d) for n in m.__all__]\n")
    cache = tmp_path / "cache"
    work = tmp_path / "work"
    work.mkdir()
    run = subprocess.run([sys.executable, "-c", code], cwd=work, capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PHONGFX_CACHE": str(cache)})
    assert run.returncode == 0, run.stderr
    assert list(work.iterdir()) == [] and not cache.exists()


@pytest.mark.skipif(importlib.util.find_spec("sphinx") is None, reason="Sphinx is not installed")
def test_a_reference_to_nothing_fails_the_build_and_one_to_a_real_object_does_not(tmp_path):
    """The build links what the API pages document, renders real objects elsewhere as code, and
    fails on a name that exists nowhere (a renamed function the pages still cite)."""
    docs = tmp_path / "docs"
    docs.mkdir()
    # the real configuration and extension, without the pictures (slow to draw, not under test)
    (docs / "conf.py").write_text(f"exec(open({str(DOCS / 'conf.py')!r}).read())\n"
                                  f"sys.path.insert(0, {str(DOCS / '_ext')!r})\nphongfx_pictures = []\n"
                                  "html_static_path = []\n", encoding="utf-8")
    (docs / "index.rst").write_text("Index\n=====\n", encoding="utf-8")
    page = docs / "probe.rst"
    page.write_text(":orphan:\n\nProbe\n=====\n\n:func:`phongfx.golden.lirp.lirp` is real.\n",
                    encoding="utf-8")
    command = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q", "-b", "html",
               str(docs), str(tmp_path / "html")]
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr[-3000:]
    page.write_text(":orphan:\n\nProbe\n=====\n\n:func:`phongfx.golden.lirp.no_such_function` is not.\n",
                    encoding="utf-8")
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert run.returncode != 0
    assert "probe.rst" in run.stderr and "no_such_function" in run.stderr, run.stderr[-3000:]


def test_the_api_page_documents_every_module_of_the_core():
    """``phongfx.core`` is documented module by module: a module added there needs its line."""
    api = (DOCS / "api.rst").read_text(encoding="utf-8")
    core = DOCS.parent / "phongfx" / "core"
    for module in sorted(p.stem for p in core.glob("*.py") if p.stem != "__init__"):
        assert f".. automodule:: phongfx.core.{module}\n" in api, f"docs/api.rst lacks phongfx.core.{module}"


def test_the_readme_links_only_to_files_that_exist_and_keeps_the_two_commands():
    readme = (DOCS.parent / "README.md").read_text(encoding="utf-8")
    links = re.findall(r"\]\(([^)#:]+)\)", readme)
    assert len(links) > 20
    assert [link for link in links if not (DOCS.parent / link).exists()] == []
    assert "make sim" in readme and "make test" in readme and len(readme.splitlines()) <= 300
