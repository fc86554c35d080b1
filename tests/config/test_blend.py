"""BlendConfig: its checks and their messages, the tables normalised, the ports, the coefficient codes."""

import pytest

from phongfx.config import BlendConfig
from phongfx.core.format import Format

GREY = ((0.5, 0.5, 0.5), (0.5, 0.5, 0.5))


@pytest.mark.parametrize("changes, message", [
    (dict(lights=0), r"lights must be an integer in 1\.\.8, not 0"),
    (dict(lights=9), r"lights must be an integer in 1\.\.8, not 9"),
    (dict(lights=True), r"lights must be an integer in 1\.\.8, not True"),
    (dict(diff="S1.10"), r"diff must be an unsigned format \(n\.m\), not S1\.10"),
    (dict(diff="0.10"), r"diff must hold exactly 1\.0 \(at least 1 integer bit\), not 0\.10"),
    (dict(diff="x"), r"diff: format must look like 'n\.m' \(unsigned\) or 'Sn\.m' \(signed\), not 'x'"),
    (dict(spec="S1.15"), r"spec must be an unsigned format \(n\.m\), not S1\.15"),
    (dict(coef_frac=25), r"coef_frac must be an integer in 0\.\.24, not 25"),
    (dict(coef_frac=-1), r"coef_frac must be an integer in 0\.\.24, not -1"),
    (dict(bits=0), r"bits must be an integer in 1\.\.16, not 0"),
    (dict(bits=17), r"bits must be an integer in 1\.\.16, not 17"),
    (dict(gate=1), r"gate must be True or False, not 1"),
    (dict(rounding="nearest"),
     r"rounding must be one of truncate, round_half_up, round_half_even, not 'nearest'"),
    (dict(pipeline=5), r"pipeline must be an integer in 0\.\.4, not 5"),
    (dict(ambient="x"), r"ambient must be a tuple with one entry per material, not 'x'"),
    (dict(ambient=()), r"ambient must have 1\.\.16 materials, not 0"),
    (dict(ambient=((0, 0, 0),) * 17), r"ambient must have 1\.\.16 materials, not 17"),
    (dict(ambient=(0.5,)), r"ambient\[0\] must be a tuple of values \(r, g, b\), not 0\.5"),
    (dict(ambient=((0, 0),)), r"ambient\[0\] must have 3 values \(r, g, b\), not 2"),
    (dict(ambient=((0, 0, 0), (0, 0, -0.5)), diffuse=(GREY,) * 2, specular=(GREY,) * 2),
     r"ambient\[1\]\[2\] must be a real number in 0\.\.16, not -0\.5"),
    (dict(ambient=((0, 0, 16.5),)), r"ambient\[0\]\[2\] must be a real number in 0\.\.16, not 16\.5"),
    (dict(ambient=((0, float("nan"), 0),)), r"ambient\[0\]\[1\] must be a real number in 0\.\.16, not nan"),
    (dict(ambient=((0, "1", 0),)), r"ambient\[0\]\[1\] must be a real number in 0\.\.16, not '1'"),
    (dict(ambient=((0, True, 0),)), r"ambient\[0\]\[1\] must be a real number in 0\.\.16, not True"),
    (dict(diffuse=((GREY[0], (0.5, 0.5)),)), r"diffuse\[0\]\[1\] must have 3 values \(r, g, b\), not 2"),
    (dict(diffuse=((GREY[0],),)), r"diffuse\[0\] must have 2 lights \(one \(r, g, b\) per light\), not 1"),
    (dict(lights=3), r"diffuse\[0\] must have 3 lights \(one \(r, g, b\) per light\), not 2"),
    (dict(diffuse=(GREY, GREY)), r"diffuse must have 1 material\(s\), as ambient has, not 2"),
    (dict(specular=3), r"specular must be a tuple with one entry per material, not 3"),
    (dict(specular=((GREY[0], (0.5, 0.5, 20)),)),
     r"specular\[0\]\[1\]\[2\] must be a real number in 0\.\.16, not 20"),
    (dict(diff=""),
     r"diff is '' \(no diffuse input\): diffuse must be all 0, not diffuse\[0\]\[0\]\[0\] = 0\.5"),
    (dict(diff="", diffuse=(((0, 0, 0), (0, 0, 0)),)),
     r"diff is '' \(no diffuse input\): gate must be False, the backside test reads diff"),
    # 8 lights of value 16 at 16 bits and 24 coefficient fraction bits: past int64
    (dict(lights=8, coef_frac=24, bits=16, ambient=((16, 16, 16),), diffuse=(((1, 1, 1),) * 8,),
          specular=(((1, 1, 1),) * 8,)),
     r"the exact sum of 8 light\(s\) at coef_frac=24 \(coefficients 20\.24\) does not fit: format 25\.39 is "
     r"64 bits wide; .*"),
])
def test_errors_name_field_value_and_range(changes, message):
    with pytest.raises(ValueError, match=rf"^{message}$"):
        BlendConfig(**changes)


def test_defaults():
    config = BlendConfig()
    assert (config.lights, config.diff, config.spec) == (2, "1.10", "1.15")
    assert (config.coef_frac, config.bits) == (10, 8)
    assert config.ambient == ((0.0, 0.0, 0.0),) and config.diffuse == config.specular == (GREY,)
    assert config.gate is True and config.rounding == "round_half_up" and config.pipeline == 0
    assert config.materials == 1 and config.material_format is None
    # 0.5 · 255 · 2^10 = 130560: 127.5 levels, 17 bits
    assert config.coefficients(0) == ((0, 0, 0), ((130560,) * 3,) * 2, ((130560,) * 3,) * 2)
    assert config.coef_format == Format(7, 10)


def test_lists_become_tuples_of_floats_hashable_and_repr_stable():
    given = BlendConfig(ambient=[[0, 1, 0.25]], diffuse=[[[1, 1, 1], [0, 0, 0]]],
                        specular=[[[0, 0, 0], [1, 1, 1]]])
    same = BlendConfig(ambient=((0.0, 1.0, 0.25),), diffuse=(((1.0, 1.0, 1.0), (0.0, 0.0, 0.0)),),
                       specular=(((0.0, 0.0, 0.0), (1.0, 1.0, 1.0)),))
    assert given == same and hash(given) == hash(same) and repr(given) == repr(same)
    assert type(given.ambient) is tuple and type(given.ambient[0][0]) is float
    assert {given: 1}[same] == 1
    assert eval(repr(given), {"BlendConfig": BlendConfig}) == given
    assert given.replace(bits=10).ambient == given.ambient


def test_ports():
    config = BlendConfig(lights=3, diffuse=((GREY[0],) * 3,) * 3, specular=((GREY[0],) * 3,) * 3,
                         ambient=((0, 0, 0),) * 3, bits=10)
    assert config.inputs == {"diff0": (Format(1, 10), 1), "spec0": (Format(1, 15), 1),
                             "diff1": (Format(1, 10), 1), "spec1": (Format(1, 15), 1),
                             "diff2": (Format(1, 10), 1), "spec2": (Format(1, 15), 1),
                             "material": (Format(2, 0), 1)}
    assert config.outputs == {name: (Format(10, 0), 1) for name in "rgb"}
    assert config.material_format == Format(2, 0)
    sixteen = BlendConfig(ambient=((0, 0, 0),) * 16, diffuse=(GREY,) * 16, specular=(GREY,) * 16)
    assert sixteen.material_format == Format(4, 0)
    no_diff = BlendConfig(diff="", gate=False, diffuse=(((0, 0, 0),) * 2,))
    assert no_diff.inputs == {"spec0": (Format(1, 15), 1), "spec1": (Format(1, 15), 1)}


def test_raw_code_is_exact_round_half_up_of_the_scaled_value():
    config = BlendConfig(bits=1, coef_frac=0)  # scale 1: the code is floor(v + 1/2)
    assert [config.raw_code(v) for v in (0, 0.25, 0.5, 1.5, 2.4999999999999996, 16)] == [0, 0, 1, 2, 2, 16]
    eight = BlendConfig(coef_frac=0)  # 255 levels: 0.001 · 255 = 0.255 rounds to 0
    assert eight.raw_code(0.001) == 0 and eight.raw_code(1 / 255) == 1 and eight.raw_code(1.0) == 255
    # 0.1 is a binary fraction a little above 1/10: exactly floor(0.1 · 255 · 1024 + 1/2)
    assert BlendConfig().raw_code(0.1) == 26112
    assert BlendConfig(bits=16, coef_frac=24).raw_code(16) == 16 * 65535 << 24


def test_coefficient_format_follows_the_largest_code():
    assert BlendConfig(ambient=((1, 0, 0),)).coef_format == Format(8, 10)  # 255 · 2^10 needs 18 bits
    zeros = BlendConfig(coef_frac=0, diffuse=(((0, 0, 0),) * 2,), specular=(((0, 0, 0),) * 2,))
    assert zeros.coef_format == Format(1, 0)
    assert zeros.replace(coef_frac=3).coef_format == Format(0, 3)


def test_coefficients_name_the_material():
    config = BlendConfig(ambient=((0.1, 0.2, 0.3), (0, 0, 0)), diffuse=(GREY,) * 2, specular=(GREY,) * 2)
    assert config.coefficients(0)[0] == tuple(config.raw_code(v) for v in (0.1, 0.2, 0.3))
    with pytest.raises(ValueError, match=r"^material must be an integer in 0\.\.1, not 2$"):
        config.coefficients(2)
