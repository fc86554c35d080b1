import dataclasses

import pytest

from phongfx.config import (BlinnConfig, BlockConfig, DatapathConfig, DifferenceConfig, DiffuseConfig,
                            EulerConfig, GouraudConfig, HalfwayConfig, LirpConfig, NormalizeConfig,
                            ReflectConfig, RootConfig, SchlickConfig, ShapeConfig, SphericalConfig)
from phongfx.config.base import (MAX_PIPELINE, MAX_VEC_FRAC, check_format, check_fraction_format, check_int,
                                 check_integer_format, check_step_formats)
from phongfx.core.format import Format

BLOCKS = (LirpConfig, NormalizeConfig, ReflectConfig, DifferenceConfig, ShapeConfig, DiffuseConfig,
          RootConfig, HalfwayConfig, SchlickConfig, SphericalConfig, EulerConfig, GouraudConfig,
          BlinnConfig)
FIELD_NAMES = {cls: {f.name for f in dataclasses.fields(cls)} for cls in BLOCKS + (DatapathConfig,)}


@pytest.mark.parametrize("value", [-1, 4, True, 1.0, "2", None])
def test_check_int_refuses(value):
    with pytest.raises(ValueError, match=rf"^depth must be an integer in 0\.\.3, not {value!r}$"):
        check_int("depth", value, 0, 3)


def test_check_int_takes_the_bounds():
    assert check_int("depth", 0, 0, 3) == 0 and check_int("depth", 3, 0, 3) == 3


@pytest.mark.parametrize("value, kwargs, message", [
    ("S1.x", {}, "^vec: format must look like 'n.m' \\(unsigned\\) or 'Sn.m' \\(signed\\), not 'S1.x'$"),
    (12, {}, "^vec: format must be a string like 'S1.10' or a Format, not 12$"),
    ("1.10", {"signed": True}, r"^vec must be a signed format \(Sn\.m\), not 1\.10$"),
    ("S1.10", {"signed": False}, r"^vec must be an unsigned format \(n\.m\), not S1\.10$"),
    ("0.10", {"holds_one": True}, r"^vec must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.10$"),
])
def test_check_format_messages(value, kwargs, message):
    with pytest.raises(ValueError, match=message):
        check_format("vec", value, **kwargs)


def test_check_format_returns_the_format():
    assert check_format("vec", "S1.10", signed=True) == Format(1, 10, True)
    assert check_format("a", Format(1, 10), signed=False, holds_one=True) == Format(1, 10)


def test_integer_and_fraction_formats():
    assert check_integer_format("n", "13.0") == Format(13, 0)
    assert check_fraction_format("m", "0.18") == Format(0, 18)
    with pytest.raises(ValueError, match=r"^n must be an integer format \(m = 0\), not 13\.1$"):
        check_integer_format("n", "13.1")
    with pytest.raises(ValueError, match=r"^n must be an unsigned format \(n\.m\), not S13\.0$"):
        check_integer_format("n", "S13.0")
    with pytest.raises(ValueError, match=r"^m must be a fraction-only format \(0\.m\), not 1\.18$"):
        check_fraction_format("m", "1.18")


def test_step_formats():
    check_step_formats(EulerConfig(), ("ds", "t", "p"))
    with pytest.raises(ValueError, match=r"^t \(S3\.31\) may not have more fraction bits than p "
                                         r"\(S1\.30\): t is added into p exactly$"):
        EulerConfig(t="S3.31")
    with pytest.raises(ValueError, match=r"^dp must be a signed format \(Sn\.m\), not 3\.30$"):
        GouraudConfig(dp="3.30")


@pytest.mark.parametrize("cls", [cls for cls in BLOCKS if "rounding" in FIELD_NAMES[cls]])
def test_rounding_checked_for_every_block_that_has_it(cls):
    with pytest.raises(ValueError, match=r"^rounding must be one of truncate, round_half_up, "
                                         r"round_half_even, not 'nearest'$"):
        cls(rounding="nearest")


@pytest.mark.parametrize("cls", [cls for cls in BLOCKS + (DatapathConfig,)
                                 if "pipeline" in FIELD_NAMES[cls]])
@pytest.mark.parametrize("depth", [-1, MAX_PIPELINE + 1, True])
def test_pipeline_checked_for_every_block_that_has_it(cls, depth):
    with pytest.raises(ValueError, match=rf"^pipeline must be an integer in 0\.\.{MAX_PIPELINE}, not {depth!r}$"):
        cls(pipeline=depth)


def test_the_nine_pipelined_blocks():
    assert sorted(cls.__name__ for cls in BLOCKS + (DatapathConfig,)
                  if "pipeline" in FIELD_NAMES[cls]) == sorted(
        ["LirpConfig", "NormalizeConfig", "ReflectConfig", "DifferenceConfig", "ShapeConfig",
         "DiffuseConfig", "RootConfig", "HalfwayConfig", "DatapathConfig"])


def test_rounding_is_checked_before_the_pipeline():
    with pytest.raises(ValueError, match="^rounding must be"):
        LirpConfig(rounding="x", pipeline=9)


def test_pipeline_raises_sub_configs_but_keeps_deeper_ones():
    unit = HalfwayConfig(pipeline=2)
    assert unit.normalize.pipeline == 2
    deeper = HalfwayConfig(pipeline=1, normalize=HalfwayConfig().normalize.replace(pipeline=3))
    assert deeper.normalize.pipeline == 3
    datapath = DatapathConfig(pipeline=2)
    assert {getattr(datapath, name).pipeline for name in DatapathConfig.PIPELINED} == {2}


def test_class_declarations_are_not_fields():
    for cls in BLOCKS + (DatapathConfig,):
        assert not FIELD_NAMES[cls] & {"INPUTS", "OUTPUTS", "PIPELINED", "VECTOR_FIELDS", "UNITS",
                                       "DERIVED_SETTINGS", "vec_frac"}


@pytest.mark.parametrize("cls", BLOCKS)
def test_declared_ports_resolve_to_formats(cls):
    config = cls()
    for declared, resolved in ((cls.INPUTS, config.inputs), (cls.OUTPUTS, config.outputs)):
        assert list(resolved) == list(declared)
        for name, (field, lanes) in declared.items():
            fmt = field if isinstance(field, Format) else config.fmt(field)
            assert resolved[name] == (fmt, lanes)


def test_ports_follow_the_fields():
    config = LirpConfig(vec="S1.12", a="1.12", out="S2.9")
    assert config.inputs == {"n0": (Format(1, 12, True), 3), "n1": (Format(1, 12, True), 3),
                             "a": (Format(1, 12), 1)}
    assert config.outputs == {"n": (Format(2, 9, True), 3)}
    assert SphericalConfig().inputs["init"] == (Format(1, 0), 1)


def test_a_config_without_ports_says_so():
    @dataclasses.dataclass(frozen=True)
    class Bare(BlockConfig):
        x: str = "1.0"

    with pytest.raises(NotImplementedError):
        Bare().inputs
    with pytest.raises(NotImplementedError):
        Bare().outputs


def test_replace_as_dict_fmt():
    config = NormalizeConfig().replace(order=1)
    assert config == NormalizeConfig(order=1)
    assert list(config.as_dict()) == [f.name for f in dataclasses.fields(NormalizeConfig)]
    assert config.fmt("z") == Format(1, 12)


def test_block_with_vec_frac():
    assert NormalizeConfig().with_vec_frac(12) == NormalizeConfig(
        vec="S1.12", z="1.14", y2="1.14", g="1.14", out="S1.12")
    assert DifferenceConfig(vec="S2.10").with_vec_frac(6) == DifferenceConfig(
        vec="S2.6", d="S1.6", dd="2.12")  # integer bits kept
    assert ReflectConfig().with_vec_frac(10) == ReflectConfig()
    shape = ShapeConfig()
    assert shape.with_vec_frac(12) is shape  # no direction vector in it


@pytest.mark.parametrize("frac", [0, MAX_VEC_FRAC + 1, True, 12.0, "12"])
def test_block_with_vec_frac_refuses(frac):
    with pytest.raises(ValueError, match=rf"^vec_frac must be an integer in 1\.\.23, not {frac!r}$"):
        LirpConfig().with_vec_frac(frac)
