"""Formal proofs of the overflow="error" claims: proven on the small blocks, a narrowed
config's counterexample confirmed by the golden model, the domain shown to matter."""

import json

import pytest

from phongfx.cli import main
from phongfx.core.registry import get_block
from phongfx.sim import prove as proofs
from phongfx.sim.prove import assumptions, prove


@pytest.mark.needs_sby
@pytest.mark.parametrize("name, claims, static", [("lirp", 4, 0), ("shape", 3, 0), ("root", 5, 3),
                                                  ("normalize", 1, 0)])
def test_the_default_blocks_are_proven(name, claims, static):
    proof = prove(get_block(name))
    assert len(proof.claims) == claims and proof.counts["static"] == static
    assert proof.counts["proven"] == claims - static and proof.exit_code == 0
    assert all(c.seconds > 0 for c in proof.claims if c.status == "proven")
    # the verdicts are kept in the per-user cache: a rerun proves nothing again
    again = prove(get_block(name))
    assert [(c.status, c.seconds) for c in again.claims] == [(c.status, c.seconds) for c in proof.claims]
    assert all(c.cached for c in again.claims if c.status == "proven")


def test_blocks_without_error_quantizes_have_nothing_to_prove(tmp_path):
    # reflect and difference saturate where they could overflow: no claim is made, no tool runs
    for name in ("reflect", "difference"):
        proof = prove(get_block(name), workdir=tmp_path)
        assert not tmp_path.exists() or list(tmp_path.iterdir()) == []
        assert proof.claims == [] and proof.exit_code == 0


def test_the_domain_is_the_golden_models():
    assert [text for *_, text in assumptions(get_block("lirp").config)] == [
        "0 <= a <= 1 (a: the position along the span)"]
    assert assumptions(get_block("lirp").config)[0][:3] == ("a", 0, 1024)
    assert [text for *_, text in assumptions(get_block("fig7").config)] == [
        "0 <= a <= 1 (a: the position along the span)", "1 <= n <= n_max = 8000 (n: the shininess exponent)"]
    assert [text for *_, text in assumptions(get_block("root").config)] == [
        "1 <= m <= m_max = 63 (m: the root unit's m = √n)"]
    assert assumptions(get_block("normalize").config) == []  # its n is a vector, not a shininess


def test_a_copys_own_input_is_named_by_its_port_and_copy():
    from phongfx.config import BlendConfig, SchlickConfig, ShaderConfig

    dark = ((0, 0, 0),) * 2
    config = ShaderConfig(unit="schlick", units=(SchlickConfig(n_max=32),) * 2, interval=2, share=False,
                          blend=BlendConfig(diff="", gate=False, diffuse=(dark,), specular=(((0.5, 0.5, 0.5),) * 2,)))
    # it printed "c0_1 <= n <= n_max = 32"
    assert [text for *_, text in assumptions(config)] == [
        "0 <= c0_t <= 1 (c0_t: the cosine t of copy 0)",
        "1 <= c0_n <= n_max = 32 (c0_n: the shininess exponent of copy 0)",
        "0 <= c1_t <= 1 (c1_t: the cosine t of copy 1)",
        "1 <= c1_n <= n_max = 32 (c1_n: the shininess exponent of copy 1)"]


@pytest.mark.needs_sby
def test_a_narrowed_output_has_a_counterexample_the_golden_model_confirms():
    proof = prove(get_block("lirp", out="S0.10"))
    assert proof.exit_code == 1 and proof.counts == {"proven": 1, "static": 0, "counterexample": 3, "unknown": 0}
    for claim in proof.claims[1:]:
        assert claim.confirmed is True and "the golden model refuses them too" in claim.why
        # the replayed codes: an end vector's lane at -2.0, which S0.10 cannot hold
        lanes = claim.inputs["n0"] + claim.inputs["n1"]
        assert any(abs(code) >= 1024 for code in lanes)


@pytest.mark.needs_sby
def test_without_its_domain_the_proof_fails_so_it_is_not_vacuous(monkeypatch):
    # a > 1 makes 1 - a negative: the first claim breaks, and the golden model refuses that a
    monkeypatch.setattr(proofs, "assumptions", lambda config: [])
    proof = prove(get_block("lirp"))
    first = proof.claims[0]
    assert first.status == "counterexample" and first.inputs["a"] > 1024
    assert first.confirmed is False and "outside the domain the golden model accepts" in first.why


@pytest.mark.needs_sby
def test_cli_exit_codes_and_json(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["prove", "shape", "--json", "--quiet"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["proven"] == 3 and data["unknown"] == 0 and data["assumptions"] == ["none: every input code"]
    assert main(["prove", "lirp", "--timeout", "0.01", "--quiet"]) == 3
    out = capsys.readouterr().out
    assert "unknown 4" in out and "time-out after 0.01 s" in out and "assuming, on every valid input: 0 <= a <= 1" in out
    assert main(["prove"]) == 2 and "give a block NAME or --dsp" in capsys.readouterr().err
    # a narrowed config is refused before any proof: the golden model's dry run overflows
    assert main(["prove", "lirp", "--set", "out=S0.10"]) == 2
    assert "overflow format S0.10" in capsys.readouterr().err


@pytest.mark.slow
@pytest.mark.needs_sby
@pytest.mark.parametrize("name", ["fig7", "fig8", "halfway_datapath", "halfway", "schlick"])
def test_the_datapaths_are_proven(name):
    # about 100-160 s each for the three datapaths (blinn's and conventional's table lookups time out)
    proof = prove(get_block(name))
    assert proof.counts["counterexample"] == 0 and proof.counts["unknown"] == 0


@pytest.mark.needs_sby
def test_a_shader_whose_lights_take_turns_is_proven(tmp_path):
    # two lights on one Schlick unit: the second light's t comes from the holding register
    from phongfx.config import BlendConfig, SchlickConfig, ShaderConfig

    dark = ((0, 0, 0),) * 2
    config = ShaderConfig(unit="schlick", units=(SchlickConfig(),) * 2, interval=2, blend=BlendConfig(
        diff="", gate=False, diffuse=(dark,), specular=(((0.5, 0.5, 0.5),) * 2,)))
    assert [port for port, *_ in assumptions(config)] == ["c0_t", "n", "c1_t"]  # n shared: bounded once
    proof = prove(get_block("shader", config=config), workdir=tmp_path)
    assert proof.counts == {"proven": 2, "static": 1, "counterexample": 0, "unknown": 0}
    assert proof.depth == get_block("shader", config=config.replace(interval=1)).latency + 1 + 2
