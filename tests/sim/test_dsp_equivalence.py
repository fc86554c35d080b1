"""The ECP5 DSP mapping proven equal to ``*``: the cases the registry uses, their proofs,
and broken DSP models that must fail with a real counterexample (the proof is not vacuous)."""

import pytest
from amaranth.back import rtlil

from phongfx.core.format import Format
from phongfx.core.registry import get_block
from phongfx.hdl.dsp import MODEL, dsp_mapping, recording_products
from phongfx.sim.dsp_equivalence import DspCase, DspProof, dsp_cases, markdown, prove_case, prove_dsp_mapping

#: (function, a, b) of the datapaths' mapped products at depths 3 and 4 (raw formats)
DATAPATH_PRODUCTS = {
    ("product", "9.0", "9.0"), ("product", "11.0", "6.0"), ("product", "S11.0", "11.0"),
    ("product", "S11.0", "S11.0"), ("product", "S11.0", "13.0"), ("product", "S11.0", "S13.0"),
    ("product", "S11.0", "S14.0"), ("product", "S13.0", "S11.0"), ("product", "S13.0", "13.0"),
    ("product", "S13.0", "S13.0"), ("product", "16.0", "16.0"),
    ("split_product", "13.0", "22.0"), ("split_product", "15.0", "22.0"),
}


@pytest.fixture(scope="module")
def cases():
    return dsp_cases()


def _triples(cases):
    return {(case.function, str(case.a), str(case.b)) for case in cases}


def test_recording_changes_nothing_and_lists_each_call_once():
    block = get_block("lirp", pipeline=4)
    with dsp_mapping("ecp5"):
        plain = rtlil.convert(block.component(), name="b", emit_src=False)
        with recording_products() as calls:
            recorded = rtlil.convert(block.component(), name="b", emit_src=False)
    assert recorded == plain
    # two vector products of three elements; isolate's inner product call is not listed again
    assert [call.name for call in calls] == ["p0"] * 3 + ["p1"] * 3
    assert all(call.isolate and call.a_registered and call.b_registered for call in calls)


def test_cases_cover_the_datapaths_at_the_mapping_depth(cases):
    datapaths = dsp_cases(["fig7", "fig8", "halfway_datapath"])
    assert _triples(datapaths) == DATAPATH_PRODUCTS
    # both mapped depths, with and without the isolating registers of depth 4
    for triple in DATAPATH_PRODUCTS:
        found = [case for case in datapaths if (case.function, str(case.a), str(case.b)) == triple]
        assert sorted(case.isolate for case in found) == [False, True]
        assert {use.partition("@")[2][0] for case in found for use in case.used_by} == {"3", "4"}
    assert {use.partition("@")[0] for case in datapaths for use in case.used_by} == {
        "fig7", "fig8", "halfway_datapath"}
    # the datapaths use every width the blocks use; widths are 6 to 22 bits, split above 18
    assert _triples(cases) == DATAPATH_PRODUCTS and len(cases) == 26
    assert all(case.function == "split_product" for case in cases if max(case.a.width, case.b.width) > 18)
    # below the mapping depth the flow leaves the products to Yosys: nothing to prove
    assert dsp_cases(["fig7"], depths=[2]) == []


def _representative(cases):
    # depth 3's cases, and depth 4's (isolated) only for the split products
    return [case for case in cases if not case.isolate or case.function == "split_product"]


def _check_proven(proofs):
    assert proofs and all(proof.status == "proven" for proof in proofs), markdown(proofs)
    assert all(proof.dsps >= 1 for proof in proofs)  # the gate really maps onto MULT18X18D


@pytest.mark.needs_yosys
def test_registry_cases_are_proven(cases):
    _check_proven(prove_dsp_mapping(timeout=120, cases=_representative(cases)))


@pytest.mark.slow
@pytest.mark.needs_yosys
def test_every_registry_case_is_proven(cases):
    proofs = prove_dsp_mapping(timeout=300, cases=cases)
    _check_proven(proofs)
    assert [proof.case for proof in proofs] == cases


def _broken_model(tmp_path, old, new):
    text = MODEL.read_text()
    assert old in text
    path = tmp_path / "broken.v"
    path.write_text(text.replace(old, new))
    return path


A_BITS = "wire [17:0] a = {A17, A16, A15, A14, A13, A12, A11, A10, A9, A8, A7, A6, A5, A4, A3, A2, A1, A0};"


@pytest.mark.needs_yosys
@pytest.mark.parametrize("case", [
    DspCase("product", Format.parse("16.0"), Format.parse("16.0"), True, True),
    DspCase("product", Format.parse("S11.0"), Format.parse("S13.0"), True, True, isolate=True),
    DspCase("split_product", Format.parse("13.0"), Format.parse("22.0"), True, True, on=True),
], ids=lambda case: case.label)
def test_a_dropped_operand_bit_is_a_counterexample(tmp_path, case):
    # bit 0 of the DSP's A operand read as 0: the product of an odd A and a non-zero B is wrong
    model = _broken_model(tmp_path, A_BITS, A_BITS.replace("A1, A0}", "A1, 1'b0}"))
    proof = prove_case(case, timeout=120, model=model, work=tmp_path / "proof")
    assert proof.status == "counterexample", proof
    a, b = proof.operands["a"], proof.operands["b"]
    assert case.a.min_raw <= a <= case.a.max_raw and case.b.min_raw <= b <= case.b.max_raw
    assert a % 2 == 1 and a * b != (a & ~1) * b
    assert prove_case(case, timeout=120).status == "proven"  # the same case with the true model


@pytest.mark.needs_yosys
def test_an_unsigned_operand_b_is_a_counterexample(tmp_path):
    # SIGNEDB ignored: a negative B operand is read as a large positive one
    model = _broken_model(tmp_path, "wire signed [18:0] b_value = {b_in[18] & b_in[17], b_in[17:0]};",
                          "wire signed [18:0] b_value = {1'b0, b_in[17:0]};")
    case = DspCase("product", Format.parse("S11.0"), Format.parse("S11.0"), True, True)
    proof = prove_case(case, timeout=120, model=model)
    assert proof.status == "counterexample" and proof.operands["b"] < 0 and proof.operands["a"] != 0, proof


@pytest.mark.needs_yosys
def test_a_proof_past_its_time_out_is_unknown():
    case = DspCase("product", Format.parse("9.0"), Format.parse("9.0"), False, False)
    proof = prove_case(case, timeout=0.01)
    assert proof.status == "unknown" and proof.operands is None and "0.01 s" in proof.detail


def test_markdown_lists_each_proof_and_the_counts():
    case = DspCase("product", Format.parse("S11.0"), Format.parse("13.0"), True, True, used_by=("fig7@3:ng",))
    proofs = [DspProof(case, "proven", 1.25, 1, 2),
              DspProof(case, "counterexample", 2.0, 1, 2, {"a": -3, "b": 5}, "outputs differ"),
              DspProof(case, "unknown", 60.0, 1, 2, detail="no answer in 60 s")]
    text = markdown(proofs)
    assert text.splitlines()[0].startswith("| product | a | b | registers |")
    assert ("| product | S11.0 (12 bits) | 13.0 (13 bits) | in, out | 1 | 2 | proven | 1.2 "
            "| fig7@3:ng |") in text
    assert "counterexample a=-3 b=5 (outputs differ)" in text
    assert text.rstrip().endswith("3 cases: 1 proven, 1 counterexample, 1 unknown; 63.2 s")
