"""The documentation builds with warnings as errors and every cross-reference resolved."""

import importlib.util
import os
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
            "phongfx.config, phongfx.explore.compile as c, phongfx.explore.compile.emit\n"
            "[getattr(phongfx, n) for n in phongfx.__all__]\n[getattr(c, n) for n in c.__all__]\n")
    cache = tmp_path / "cache"
    work = tmp_path / "work"
    work.mkdir()
    run = subprocess.run([sys.executable, "-c", code], cwd=work, capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PHONGFX_CACHE": str(cache)})
    assert run.returncode == 0, run.stderr
    assert list(work.iterdir()) == [] and not cache.exists()
