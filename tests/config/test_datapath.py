import dataclasses
from pathlib import Path

import pytest

from phongfx.config import DatapathConfig, fig7_config, fig8_config, halfway_config
from phongfx.config.base import MAX_VEC_FRAC
from phongfx.core.format import Format
from phongfx.core.registry import REGISTRY
from phongfx.core.methods import METHODS
from phongfx.explore.sweep.spec import expand

FACTORIES = {"fig7": fig7_config, "fig8": fig8_config, "halfway": halfway_config}
DEFAULT_SWEEP = Path(__file__).resolve().parents[2] / "sweeps" / "default.toml"


# --- the vector-width derivation methods.py wrote by hand before DatapathConfig had
# vec_frac, copied as it was: the configs built through vec_frac must equal these -------

def _vec_formats(base, f, vec_int=1):
    vec, guard = f"S{vec_int}.{f}", f"1.{f + 2}"
    return dict(lirp=base.lirp.replace(vec=vec, a=f"1.{f}", out=vec),
                normalize=base.normalize.replace(vec=vec, out=vec, z=guard, y2=guard, g=guard),
                diffuse=base.diffuse.replace(vec=vec))


def _by_hand_fig7(p):
    base = REGISTRY["fig7"].default_config()
    f, vec, x2 = p["vec_frac"], f"S1.{p['vec_frac']}", f"13.{p['x2_frac']}"
    return base.replace(**_vec_formats(base, f), lights=p["lights"],
                        reflect=base.reflect.replace(vec=vec, dot=f"S1.{f + 2}", out=vec),
                        difference=base.difference.replace(vec=vec, d=vec, dd=f"2.{2 * f}", x2=x2),
                        shape=base.shape.replace(x2=x2, t=f"1.{p['shape_t_frac']}", k=p["k"]))


def _by_hand_fig8(p):
    base = REGISTRY["fig8"].default_config()
    f, vec = p["vec_frac"], f"S1.{p['vec_frac']}"
    return base.replace(**_vec_formats(base, f), lights=p["lights"],
                        reflect=base.reflect.replace(vec=vec, dot=f"S1.{f + 2}", out=vec),
                        root=base.root.replace(vec=vec, d=vec, frac=f"0.{p['root_frac']}",
                                               t=f"1.{p['t_frac']}", k=p["k"]))


def _by_hand_halfway(p):
    base = REGISTRY["halfway_datapath"].default_config()
    f, x2 = p["vec_frac"], f"13.{p['x2_frac']}"
    h, guard = f"S2.{f + 1}", f"1.{f + 2}"
    unit = base.halfway.replace(vec=f"S1.{f}", hvec=h, dot=f"S2.{f + 2}", out=f"S2.{f}",
                                normalize=base.halfway.normalize.replace(vec=h, out=h, z=guard,
                                                                         y2=guard, g=guard))
    return base.replace(**_vec_formats(base, f), lights=p["lights"], halfway=unit,
                        difference=base.difference.replace(vec=f"S2.{f}", d=f"S1.{f}",
                                                           dd=f"2.{2 * f}", x2=x2),
                        shape=base.shape.replace(x2=x2, t=f"1.{p['shape_t_frac']}", k=p["k"]))


BY_HAND = {"fig7": _by_hand_fig7, "fig8": _by_hand_fig8, "halfway": _by_hand_halfway}


@pytest.mark.parametrize("method", BY_HAND)
@pytest.mark.parametrize("frac", range(1, MAX_VEC_FRAC + 1))
def test_methods_build_what_was_built_by_hand(method, frac):
    spec = METHODS[method]
    # the builder directly: the sweeps' own range (4..16) is narrower than vec_frac's
    p = {**spec.params, "vec_frac": frac}
    assert spec.build(p) == BY_HAND[method](p)
    if spec.ranges["vec_frac"][0] <= frac <= spec.ranges["vec_frac"][1]:
        assert spec.config({"vec_frac": frac}) == BY_HAND[method](p)


@pytest.mark.parametrize("method", BY_HAND)
def test_methods_other_parameters_unchanged(method):
    spec = METHODS[method]
    for name, (lo, hi) in spec.ranges.items():
        for value in (lo, hi):
            p = spec.resolve({"vec_frac": 12, name: value} if name != "vec_frac" else {name: value})
            assert spec.build(p) == BY_HAND[method](p), (name, value)


def test_the_default_sweep_points():
    points = [point for point in expand(DEFAULT_SWEEP) if point["method"] in BY_HAND]
    assert len(points) > 20
    for point in points:
        p = point["params"]
        assert METHODS[point["method"]].config(p) == BY_HAND[point["method"]](p), point


def test_fig7_at_12_by_name():
    config = fig7_config().replace(vec_frac=12)
    assert (config.lirp.vec, config.lirp.a, config.lirp.out) == ("S1.12", "1.12", "S1.12")
    n = config.normalize
    assert (n.vec, n.z, n.y2, n.g, n.out) == ("S1.12", "1.14", "1.14", "1.14", "S1.12")
    assert (config.reflect.vec, config.reflect.dot, config.reflect.out) == ("S1.12", "S1.14", "S1.12")
    d = config.difference
    assert (d.vec, d.d, d.dd, d.x2) == ("S1.12", "S1.12", "2.24", "13.12")
    assert config.diffuse.vec == "S1.12" and config.diffuse.out == "1.10"


def test_halfway_at_8_by_name():
    config = halfway_config().replace(vec_frac=8)
    u = config.halfway
    assert (u.vec, u.hvec, u.dot, u.out) == ("S1.8", "S2.9", "S2.10", "S2.8")
    assert (u.normalize.vec, u.normalize.out, u.normalize.z, u.normalize.g) == ("S2.9", "S2.9", "1.10", "1.10")
    d = config.difference
    assert (d.vec, d.d, d.dd, d.n, d.n_max) == ("S2.8", "S1.8", "2.16", "15.0", 32000)


# --- connected formats agree at every width -----------------------------------------------

def _vectors(config):
    """Every format that carries a direction vector (or H, |D|) of the datapath in use."""
    names = ["lirp.vec", "lirp.out", "normalize.vec", "normalize.out", "diffuse.vec"]
    names += {"fig7": ["reflect.vec", "reflect.out", "difference.vec", "difference.d"],
              "fig8": ["reflect.vec", "reflect.out", "root.vec", "root.d"],
              "halfway": ["halfway.vec", "difference.d"]}[config.specular]
    if config.local_lights or config.local_viewer:
        names += ["direction_normalize.vec", "direction_normalize.out"]
    return {name: Format.parse(getattr(getattr(config, name.split(".")[0]), name.split(".")[1]))
            for name in names}


@pytest.mark.parametrize("specular", FACTORIES)
@pytest.mark.parametrize("local", [{}, {"local_lights": True}, {"local_viewer": True}])
@pytest.mark.parametrize("frac", [1, 4, 8, 12, 16, MAX_VEC_FRAC])
def test_vec_frac_sets_every_connected_format(specular, local, frac):
    config = FACTORIES[specular](**local).replace(vec_frac=frac)
    vectors = _vectors(config)
    assert set(vectors.values()) == {Format(1, frac, True)}, vectors
    assert config.vec_frac == frac
    guards = [config.normalize.fmt(name) for name in ("z", "y2", "g")]
    assert set(guards) == {Format(1, frac + 2)}
    if config.local_lights or config.local_viewer:
        assert config.direction_normalize == config.normalize
    if specular == "halfway":
        h = Format(2, frac + 1, True)
        assert config.halfway.fmt("hvec") == config.halfway.normalize.fmt("vec") == h
        assert config.halfway.fmt("out") == config.difference.fmt("vec") == Format(2, frac, True)
    else:
        assert config.reflect.fmt("dot") == Format(1, frac + 2, True)


@pytest.mark.parametrize("specular", FACTORIES)
def test_vec_frac_leaves_idle_sub_configs(specular):
    default = FACTORIES[specular]()
    config = default.replace(vec_frac=8)
    subs = {f.name for f in dataclasses.fields(DatapathConfig)
            if dataclasses.is_dataclass(getattr(default, f.name))}
    assert len(subs) == 9
    for name in subs - set(default.used):
        assert getattr(config, name) == getattr(default, name), name
    assert config.shape == default.shape  # it has no direction vector


def test_used_sub_configs():
    assert fig7_config().used == ("lirp", "normalize", "reflect", "difference", "shape", "diffuse")
    assert fig8_config().used == ("lirp", "normalize", "reflect", "root", "diffuse")
    assert halfway_config(local_viewer=True).used == (
        "lirp", "normalize", "halfway", "difference", "shape", "diffuse", "direction_normalize")


def test_vec_frac_is_derived_not_stored():
    assert DatapathConfig.DERIVED_SETTINGS == ("vec_frac",)
    config = fig7_config().replace(vec_frac=12)
    assert "vec_frac" not in {f.name for f in dataclasses.fields(config)}
    assert "vec_frac" not in repr(config) and "vec_frac" not in config.as_dict()
    assert fig7_config().replace(vec_frac=10) == fig7_config()
    assert config == fig7_config().with_vec_frac(12)


@pytest.mark.parametrize("frac", [0, -1, MAX_VEC_FRAC + 1, True, 12.0, "12", None])
def test_vec_frac_refuses(frac):
    with pytest.raises(ValueError, match=rf"^vec_frac must be an integer in 1\.\.23, not {frac!r}$"):
        fig7_config().replace(vec_frac=frac)


def test_vec_frac_after_the_fields():
    # the fields first, so that vec_frac also sets what a field change connects
    config = fig7_config().replace(vec_frac=12, local_viewer=True, pipeline=2, lights=1)
    assert config.direction_normalize.vec == "S1.12" and config.lights == 1
    assert config.lirp.pipeline == config.normalize.pipeline == 2
    assert fig7_config(pipeline=1).replace(vec_frac=8).reflect.pipeline == 1
    keep = fig7_config(normalize=fig7_config().normalize.replace(order=1)).replace(vec_frac=8)
    assert keep.normalize.order == 1


def test_vec_frac_read_back():
    for factory in FACTORIES.values():
        assert factory().vec_frac == 10
    wider_guard = fig7_config().replace(normalize=fig7_config().normalize.replace(g="1.13"))
    assert wider_guard.vec_frac is None
    assert METHODS["fig8"].config({"vec_frac": 13}).vec_frac == 13


def test_local_lights_per_light():
    config = DatapathConfig(lights=2, local_lights=[False, True])
    assert config.local_lights == (False, True) and hash(config)
    assert [config.local_light(i) for i in range(2)] == [False, True] and config.any_local
    assert not DatapathConfig(lights=2).any_local
    with pytest.raises(ValueError, match=r"local_lights must be True, False or 2 of them \(one per light\), "
                                         r"not \(True,\)"):
        DatapathConfig(lights=2, local_lights=(True,))
    with pytest.raises(ValueError, match="local_lights must be True or False, not 1"):
        DatapathConfig(local_lights=1)
