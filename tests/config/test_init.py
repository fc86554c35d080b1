import ast
from pathlib import Path

import phongfx.config
from phongfx.core.registry import REGISTRY

HERE = Path(__file__).resolve().parent
PACKAGE = Path(phongfx.config.__file__).resolve().parent

#: The public names of phongfx.config when it was one module, every one still importable,
#: and the configs of the blocks added since (ConventionalConfig, BlendConfig, ShaderConfig).
#: UNIT_TERMS, the table of what each shading unit's outputs are to the blend, became each
#: unit config's TERMS, read by phongfx.config.shader.unit_terms.
PUBLIC = ["BlockConfig", "LirpConfig", "NormalizeConfig", "ReflectConfig", "DifferenceConfig",
          "ShapeConfig", "DiffuseConfig", "RootConfig", "SchlickConfig", "SphericalConfig",
          "HalfwayConfig", "HALFWAY_VARIANTS", "EulerConfig", "GouraudConfig", "BlinnConfig",
          "DatapathConfig", "SPECULAR_UNITS", "fig7_config", "fig8_config", "halfway_config",
          "MAX_PIPELINE", "ConventionalConfig", "BlendConfig", "ShaderConfig"]


def test_public_names_kept():
    assert sorted(phongfx.config.__all__) == sorted(PUBLIC)
    for name in PUBLIC:
        assert getattr(phongfx.config, name) is not None


def test_one_module_per_block():
    modules = {path.stem for path in PACKAGE.glob("*.py")} - {"__init__", "base"}
    assert modules == {entry.module for entry in REGISTRY.values()}
    for entry in REGISTRY.values():
        assert entry.config.startswith(f"phongfx.config.{entry.module}:")


def test_registry_defaults_unchanged():
    # repr() of every registry default, captured before the module was split
    lines = (HERE / "registry_defaults.txt").read_text().splitlines()
    assert [line.split("\t")[0] for line in lines] == list(REGISTRY)
    for line in lines:
        name, expected = line.split("\t")
        assert repr(REGISTRY[name].default_config()) == expected, name


def test_imports_only_core():
    # the configuration layer stands on the formats alone
    for path in PACKAGE.glob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 0:
                module = node.module
            elif isinstance(node, ast.Import):
                module = node.names[0].name
            else:
                continue
            if module.startswith("phongfx"):
                assert module.startswith("phongfx.core"), (path.name, module)
            else:
                assert module == "dataclasses", (path.name, module)


def test_modules_declare_all():
    for path in PACKAGE.glob("*.py"):
        tree = ast.parse(path.read_text())
        names = [t.id for node in tree.body if isinstance(node, ast.Assign) for t in node.targets
                 if isinstance(t, ast.Name)]
        assert "__all__" in names, path.name
        assert ast.get_docstring(tree), path.name
        assert len(path.read_text().splitlines()) <= 400, path.name
