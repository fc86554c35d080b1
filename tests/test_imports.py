"""Honest imports: no import cycle (not even through imports inside functions), no private
name used outside its module, no relative import in ``golden/``, ``hdl/``, ``sim/`` that
leaves its folder, no import of a higher layer or of a higher room of ``phongfx.explore``
(not even inside a function).

The checks read the source with :mod:`ast` (nothing is imported), module names taken from
``pyproject.toml``'s package list and ``package-dir`` mapping, so ``sim/harness.py`` is
``phongfx.sim.harness`` as Python sees it once installed.

* A cycle of module-level imports makes the outcome depend on which module is imported
  first: one of them runs against a half-initialized other.  Imports under a module-level
  ``try`` or ``if`` (and in class bodies) run at import and count.  Importing ``a.b.c`` runs
  ``a/__init__`` and ``a/b/__init__`` first, so each parent package is an edge too, except
  the importer's own ancestors, which are already being imported.  An import inside a
  function runs later and breaks nothing at import, but a cycle through it is still two
  modules that need each other: the tree has none either.
* A private name (``_name``) is its module's own business: what another module needs is
  made public or moved.  Test and benchmark files are held to the same rule.
* ``golden/``, ``hdl/`` and ``sim/`` are installed under ``phongfx.`` by the package-dir
  mapping, so ``from ..config import X`` there works only because of it and points, on
  disk, at a file that does not exist; they use ``from phongfx.config import X``.

* The layers of :data:`LAYERS` (``phongfx/__init__.py`` lists them) import only themselves
  and the layers before them, inside functions too: an import deferred into a function
  is still a dependency on the layer above, only hidden from the reader.  The registry in
  ``phongfx.core`` loads the faces of a block by name when a block is asked for.
* Inside ``phongfx.explore`` the rooms of :data:`EXPLORE_LAYERS` (its ``__init__.py`` lists
  them) keep the same rule; rooms that share a step are peers and import none of each other.

Each check is also run on a tiny fake tree that breaks it, to show it can fail
(``tests/test_imports_can_fail.py``).
"""

import ast
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
#: Folders installed under another name by the package-dir mapping.
MAPPED_FOLDERS = ("golden", "hdl", "sim")
#: Folders of files that are not part of the package but are held to the private-name rule.
OTHER_FOLDERS = ("bench", "tests")
#: The layers of phongfx, lowest first: each may import only itself and those before it.
LAYERS = ("phongfx.core", "phongfx.config", "phongfx.golden", "phongfx.hdl", "phongfx.sim", "phongfx.scene",
          "phongfx.render", "phongfx.deliver", "phongfx.papers", "phongfx.explore", "phongfx.certify",
          "phongfx.compiler", "phongfx.cli")
#: The rooms of phongfx.explore, lowest first, as LAYERS; a tuple is a step of peers.  The shared
#: pieces import no other room; synthesis runs its jobs on the cluster; one method at one point
#: is evaluated on a scene by the synthesis or the proxies; a sweep evaluates many points; the
#: tables evaluate and synthesize and read the sweep's fronts; the report runs the tables and
#: reads the sweeps; the compile room prices designs by synthesis and may write any of them.
EXPLORE_LAYERS = (("phongfx.explore.progress", "phongfx.explore.cluster", "phongfx.explore.methods",
                   "phongfx.explore.scene_files"),
                  "phongfx.explore.synth", "phongfx.explore.evaluate", "phongfx.explore.sweep",
                  "phongfx.explore.tables", "phongfx.explore.report", "phongfx.explore.compile")


# ---------------------------------------------------------------- reading the tree

def layout(root):
    """``(packages, package_dir)`` of the ``pyproject.toml`` in ``root``."""
    setuptools = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    return setuptools["packages"], setuptools.get("package-dir", {})


def package_modules(root, packages, package_dir):
    """``{module name: (path, is_package)}`` of every module of ``packages``, each package's
    folder found through the longest matching ``package_dir`` entry."""
    modules = {}
    for package in packages:
        parts = package.split(".")
        for cut in range(len(parts), -1, -1):
            base = ".".join(parts[:cut])
            if base in package_dir or cut == 0:
                folder = root.joinpath(package_dir.get(base, ""), *parts[cut:])
                break
        for path in sorted(folder.glob("*.py")):
            if path.stem == "__init__":
                modules[package] = (path, True)
            else:
                modules[f"{package}.{path.stem}"] = (path, False)
    return modules


def other_modules(root, folders=OTHER_FOLDERS):
    """``{dotted name: (path, is_package)}`` of the ``.py`` files under ``folders``."""
    modules = {}
    for top in folders:
        for path in sorted((root / top).rglob("*.py")):
            parts = path.relative_to(root).with_suffix("").parts
            is_package = parts[-1] == "__init__"
            modules[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return modules


def absolute(name, is_package, node):
    """The module an ``ImportFrom`` in module ``name`` imports from, relative levels resolved."""
    if not node.level:
        return node.module
    package = name.split(".") if is_package else name.split(".")[:-1]
    base = package[:len(package) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def module_level_imports(tree):
    """The ``Import`` / ``ImportFrom`` nodes run when the module is imported: everywhere but
    inside function bodies (module-level ``try``, ``if``, ``with`` and class bodies count)."""
    found = []

    def visit(node):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
                continue
            if isinstance(child, (ast.Import, ast.ImportFrom)):
                found.append(child)
            visit(child)

    visit(tree)
    return found


def every_import(tree):
    """Every ``Import`` / ``ImportFrom`` node of ``tree``, those inside functions included."""
    return [node for node in ast.walk(tree) if isinstance(node, (ast.Import, ast.ImportFrom))]


def imported(name, is_package, node, known):
    """Dotted names of the modules an import node loads (as far as ``known`` holds them)."""
    if isinstance(node, ast.Import):
        return [alias.name for alias in node.names]
    source = absolute(name, is_package, node)
    return [source] + [f"{source}.{alias.name}" for alias in node.names
                       if f"{source}.{alias.name}" in known]


def _shown(path):
    """``path`` relative to the repository when it lies inside, for shorter messages."""
    return path.relative_to(ROOT) if path.is_relative_to(ROOT) else path


# ---------------------------------------------------------------- cycles

def import_graph(modules, inside_functions=False):
    """``{module: {imported module: line}}`` of the module-level imports among ``modules``
    (and of those inside functions too with ``inside_functions``)."""
    found = every_import if inside_functions else module_level_imports
    graph = {}
    for name, (path, is_package) in modules.items():
        edges = graph.setdefault(name, {})
        for node in found(ast.parse(path.read_text(), str(path))):
            for target in imported(name, is_package, node, modules):
                parts = target.split(".")
                for depth in range(1, len(parts) + 1):
                    step = ".".join(parts[:depth])
                    # the importer's own ancestors are already being imported when it runs
                    if step in modules and not (name == step or name.startswith(step + ".")):
                        edges.setdefault(step, node.lineno)
    return graph


def strongly_connected(graph):
    """The components of ``graph`` with more than one module (Tarjan), each sorted."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

    def strong(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                strong(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            strong(v)
    return found


def one_cycle(graph, component):
    """A shortest cycle through the first module of ``component``, as a list of modules."""
    start, members = component[0], set(component)
    paths = {start: [start]}
    frontier = [start]
    while frontier:
        following = []
        for v in frontier:
            for w in sorted(graph[v]):
                if w == start:
                    return paths[v] + [start]
                if w in members and w not in paths:
                    paths[w] = paths[v] + [w]
                    following.append(w)
        frontier = following
    raise AssertionError(f"no cycle through {start}")  # a component always has one


def assert_no_cycles(modules, inside_functions=False):
    """Fail naming one cycle per strongly connected set of modules, of module-level imports (and
    of those inside functions too with ``inside_functions``)."""
    graph = import_graph(modules, inside_functions)
    problems = []
    for component in strongly_connected(graph):
        cycle = one_cycle(graph, component)
        steps = "; ".join(f"{_shown(modules[a][0])}:{graph[a][b]} imports {b}"
                          for a, b in zip(cycle, cycle[1:]))
        problems.append(f"{' -> '.join(cycle)} ({steps})")
    what = "import cycle(s), imports inside functions included" if inside_functions else "module-level import cycle(s)"
    assert not problems, f"{what}:\n" + "\n".join(problems)


# ---------------------------------------------------------------- private names

def private(name):
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def dotted(node):
    """``a.b.c`` of a chain of attribute accesses on a name, else None."""
    names = []
    while isinstance(node, ast.Attribute):
        names.append(node.attr)
        node = node.value
    return ".".join([node.id, *reversed(names)]) if isinstance(node, ast.Name) else None


def private_uses(importers, targets):
    """``path:line: what`` of each use in ``importers`` of a private name of another module
    of ``targets``: ``from m import _x``, or ``m._x`` where ``m`` names an imported module
    (imports anywhere in the file, functions included)."""
    found = []
    for name, (path, is_package) in importers.items():
        tree = ast.parse(path.read_text(), str(path))
        aliases = {}  # local name -> module of targets
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    # `import a.b.c` binds `a`, and a use is spelt `a.b.c._x`
                    aliases[alias.asname or alias.name] = alias.name
            elif isinstance(node, ast.ImportFrom):
                source = absolute(name, is_package, node)
                for alias in node.names:
                    full = f"{source}.{alias.name}"
                    if full in targets:
                        aliases[alias.asname or alias.name] = full
                    elif source in targets and source != name and private(alias.name):
                        found.append(f"{_shown(path)}:{node.lineno}: imports {alias.name} from {source}")
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and private(node.attr):
                module = aliases.get(dotted(node.value))
                if module in targets and module != name:
                    found.append(f"{_shown(path)}:{node.lineno}: uses {node.attr} of {module}")
    return found


def assert_no_private_uses(importers, targets):
    found = private_uses(importers, targets)
    assert not found, "private names used outside their module:\n" + "\n".join(found)


# ---------------------------------------------------------------- relative imports

def escaping_relative_imports(root, folders=MAPPED_FOLDERS):
    """``path:line: from ...`` of each relative import under ``folders`` that leaves the
    importing file's own folder (two dots or more)."""
    found = []
    for top in folders:
        for path in sorted((root / top).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text(), str(path))):
                if isinstance(node, ast.ImportFrom) and node.level >= 2:
                    names = ", ".join(alias.name for alias in node.names)
                    found.append(f"{_shown(path)}:{node.lineno}: "
                                 f"from {'.' * node.level}{node.module or ''} import {names}")
    return found


def assert_no_escaping_relative_imports(root, folders=MAPPED_FOLDERS):
    found = escaping_relative_imports(root, folders)
    assert not found, ("relative imports that leave their folder (write `from phongfx.X import`):\n"
                       + "\n".join(found))


def room_of(module, layers):
    """``(index, room)``: the step of ``layers`` (each a package or a tuple of peer packages)
    ``module`` belongs to and which package of it, or ``(None, None)``."""
    for index, step in enumerate(layers):
        for room in (step,) if isinstance(step, str) else step:
            if module == room or module.startswith(room + "."):
                return index, room
    return None, None


def layer_of(module, layers):
    """Index in ``layers`` of the layer ``module`` belongs to, or None."""
    return room_of(module, layers)[0]


def assert_layered(modules, layers=LAYERS):
    """Fail naming every import of a later layer than the importer's, or of a peer of the
    importer's step (another room of the same tuple), inside functions too."""
    found = []
    for name, edges in sorted(import_graph(modules, inside_functions=True).items()):
        low, own = room_of(name, layers)
        for target, line in sorted(edges.items()):
            high, room = room_of(target, layers)
            if low is not None and high is not None and (high > low or high == low and room != own):
                found.append(f"{_shown(modules[name][0])}:{line}: {name} ({own}) imports {target} "
                             f"({room}{', a peer' if high == low else ''})")
    if found:
        pytest.fail("imports of a higher layer:\n" + "\n".join(found))


# ---------------------------------------------------------------- the real tree

def _package():
    return package_modules(ROOT, *layout(ROOT))


def test_every_package_folder_is_read():
    modules = _package()
    assert {"phongfx", "phongfx.golden.fixed", "phongfx.hdl.block", "phongfx.sim.harness",
            "phongfx.cli"} <= set(modules)
    assert modules["phongfx.sim.harness"][0] == ROOT / "sim" / "harness.py"


def test_no_module_level_import_cycle():
    assert_no_cycles(_package())


def test_no_import_cycle_even_through_imports_inside_functions():
    assert_no_cycles(_package(), inside_functions=True)


def test_no_private_name_used_outside_its_module():
    modules = _package()
    assert_no_private_uses(modules, modules)


def test_tests_and_benchmarks_use_no_private_name_of_the_package():
    assert_no_private_uses(other_modules(ROOT), _package())


def test_no_relative_import_leaves_a_mapped_folder():
    assert_no_escaping_relative_imports(ROOT)


def test_every_layer_imports_only_the_layers_before_it():
    modules = _package()
    assert {layer_of(name, LAYERS) for name in modules} == set(range(len(LAYERS))) | {None}
    assert [name for name in modules if layer_of(name, LAYERS) is None] == ["phongfx"]
    assert_layered(modules)


def test_every_room_of_explore_imports_only_the_rooms_before_it():
    modules = {name: where for name, where in _package().items() if layer_of(name, ("phongfx.explore",)) == 0}
    rooms = {room_of(name, EXPLORE_LAYERS)[1] for name in modules}
    assert rooms == {room for step in EXPLORE_LAYERS for room in ((step,) if isinstance(step, str) else step)} | {None}
    assert [name for name in modules if layer_of(name, EXPLORE_LAYERS) is None] == ["phongfx.explore"]
    assert_layered(modules, EXPLORE_LAYERS)
