"""The documentation builds with warnings as errors and every cross-reference resolved."""

import importlib.util
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
