"""Each check of :mod:`tests.test_imports` run on a tiny fake tree that breaks it, to show it can fail."""

import pytest

from tests.test_imports import (assert_layered, assert_no_cycles, assert_no_escaping_relative_imports,
                                assert_no_private_uses, escaping_relative_imports, layout, package_modules,
                                private_uses)

def _tree(tmp_path, files, packages=("fake", "fake.low"), package_dir=None):
    """A fake project: ``files`` ``{path: source}`` and a pyproject naming ``packages``."""
    package_dir = package_dir or {"fake": "fake", "fake.low": "low"}
    mapping = "".join(f'"{k}" = "{v}"\n' for k, v in package_dir.items())
    (tmp_path / "pyproject.toml").write_text(
        f"[tool.setuptools]\npackages = {list(packages)!r}\n[tool.setuptools.package-dir]\n{mapping}")
    for relative, source in files.items():
        (tmp_path / relative).parent.mkdir(parents=True, exist_ok=True)
        (tmp_path / relative).write_text(source)
    return package_modules(tmp_path, *layout(tmp_path))


def test_a_cycle_fails(tmp_path):
    modules = _tree(tmp_path, {
        "fake/__init__.py": "",
        "fake/a.py": "from fake.low import b\n",
        # a relative import resolved through the mapping: low/ is fake.low
        "low/__init__.py": "",
        "low/b.py": "try:\n    from fake import c\nexcept ImportError:\n    pass\n",
        "fake/c.py": "if True:\n    import fake.a\n",
    })
    with pytest.raises(AssertionError, match=r"fake\.a -> fake\.low\.b -> fake\.c -> fake\.a \("):
        assert_no_cycles(modules)


def test_a_parent_package_closes_a_cycle(tmp_path):
    modules = _tree(tmp_path, {
        "fake/__init__.py": "",
        "low/__init__.py": "from .b import B\n",  # importing fake.low runs this
        "low/b.py": "from fake.x import X\nB = 1\n",
        "fake/x.py": "from fake.low.c import C\nX = 1\n",  # runs low/__init__ first
        "low/c.py": "C = 1\n",
    })
    with pytest.raises(AssertionError, match=r"fake\.low -> fake\.low\.b -> fake\.x -> fake\.low"):
        assert_no_cycles(modules)


def test_imports_inside_functions_and_own_ancestors_make_no_cycle(tmp_path):
    modules = _tree(tmp_path, {
        "fake/__init__.py": "from fake.low import b\n",
        "low/__init__.py": "",
        "low/b.py": "import fake.low\n\ndef f():\n    from fake import a\n",
        "fake/a.py": "from fake.low import b\n",
    })
    assert_no_cycles(modules)


def test_a_cycle_through_an_import_inside_a_function_fails(tmp_path):
    modules = _tree(tmp_path, {
        "fake/__init__.py": "",
        "low/__init__.py": "",
        "low/b.py": "def f():\n    from fake import a\n",
        "fake/a.py": "from fake.low import b\n",
    })
    assert_no_cycles(modules)  # no cycle at import
    with pytest.raises(AssertionError, match=r"imports inside functions included:\n  fake\.a -> fake\.low\.b -> "
                                             r"fake\.a \(.*fake/a\.py:1 imports fake\.low\.b; .*low/b\.py:2 imports "
                                             r"fake\.a\)"):
        assert_no_cycles(modules, inside_functions=True)


def test_a_private_use_fails(tmp_path):
    modules = _tree(tmp_path, {
        "fake/__init__.py": "",
        "fake/a.py": "_hidden = 1\n__version__ = '1'\nok = _hidden\n",
        "low/__init__.py": "",
        "low/b.py": "from fake.a import __version__\n\ndef f():\n    from fake.a import _hidden\n",
        "low/c.py": "from fake import a as alias\nimport fake.a\nx = alias._hidden + fake.a._hidden\n",
        "low/d.py": "from .. import a\ny = a.ok\n",
    })
    found = private_uses(modules, modules)
    assert [line.split(": ", 1)[1] for line in found] == [
        "imports _hidden from fake.a", "uses _hidden of fake.a", "uses _hidden of fake.a"]
    with pytest.raises(AssertionError, match=r"low/b\.py:4: imports _hidden from fake\.a"):
        assert_no_private_uses(modules, modules)


def test_an_escaping_relative_import_fails(tmp_path):
    _tree(tmp_path, {
        "fake/__init__.py": "",
        "fake/config.py": "X = 1\n",
        "low/__init__.py": "from . import ok\n",
        "low/ok.py": "from .sub import y\n",
        "low/sub.py": "y = 1\n",
        "low/bad.py": "def f():\n    from ..config import X\n",
    })
    assert escaping_relative_imports(tmp_path, ("low",)) == [
        f"{tmp_path / 'low' / 'bad.py'}:2: from ..config import X"]
    with pytest.raises(AssertionError, match=r"bad\.py:2: from \.\.config import X"):
        assert_no_escaping_relative_imports(tmp_path, ("low",))


def test_an_import_of_a_higher_layer_fails(tmp_path):
    _tree(tmp_path, {"fake/__init__.py": "", "low/__init__.py": "",
                     "low/base.py": "from fake.top import X\n",
                     "fake/top.py": "X = 1\n"})
    modules = package_modules(tmp_path, *layout(tmp_path))
    assert_layered(modules, ("fake.top", "fake.low"))  # top is the lower layer here: allowed
    with pytest.raises(pytest.fail.Exception, match=r"fake\.low\.base \(fake\.low\) imports fake\.top "):
        assert_layered(modules, ("fake.low", "fake.top"))


def test_an_import_of_a_higher_layer_inside_a_function_fails(tmp_path):
    _tree(tmp_path, {"fake/__init__.py": "", "low/__init__.py": "",
                     "low/base.py": "def f():\n    if True:\n        from fake.top import X\n    return X\n",
                     "fake/top.py": "X = 1\n"})
    modules = package_modules(tmp_path, *layout(tmp_path))
    assert_no_cycles(modules)  # a deferred import closes no cycle, but it is still upward
    with pytest.raises(pytest.fail.Exception, match=r"low/base\.py:3: fake\.low\.base \(fake\.low\) imports fake\.top "):
        assert_layered(modules, ("fake.low", "fake.top"))


def test_an_import_of_a_higher_or_a_peer_room_fails(tmp_path):
    _tree(tmp_path, {"fake/__init__.py": "", "low/__init__.py": "",
                     "fake/base.py": "", "fake/side.py": "from fake import base\n",
                     "fake/top.py": "def f():\n    from fake import side\n",
                     "low/a.py": "from fake import top\n", "low/b.py": "from fake.low import a\n"})
    modules = package_modules(tmp_path, *layout(tmp_path))
    assert_layered(modules, ("fake.base", "fake.side", "fake.top", "fake.low"))  # low.b imports its own room
    with pytest.raises(pytest.fail.Exception, match=r"low/a\.py:1: fake\.low\.a \(fake\.low\) imports fake\.top "
                                                     r"\(fake\.top\)\n.*top\.py:2: fake\.top \(fake\.top\) imports "
                                                     r"fake\.side \(fake\.side, a peer\)$"):
        assert_layered(modules, ("fake.low", "fake.base", ("fake.side", "fake.top")))
