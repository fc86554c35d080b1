"""The wrapping rule of generated comments: no line may begin with a word a tool reads as
its pragma (:mod:`phongfx.hdl.comment`)."""

import pytest

from phongfx.hdl.comment import PRAGMA_WORDS, comment, starts_pragma, wrap


@pytest.mark.parametrize("text, expected", [
    ("Verilator (--binary)", True), ("  verilator lint_off", True), ("VERILATOR", True),
    ("verilator_top: the block", True), ("synopsys translate_off", True), ("Synthesis", True),
    ("pragma protect", True), ("translate_off", True), ("lint_off", True),
    ("(Verilator)", False), ("tb_verilator", False), ("`verilator_top`:", False), ("the Verilator run", False),
])
def test_starts_pragma(text, expected):
    assert starts_pragma(text) is expected


def test_a_pragma_word_at_a_break_stays_with_the_word_before():
    # greedy wrapping at 10 would start the second line with "Verilator"
    assert wrap("Icarus and Verilator (--binary) run", width=10, indent="") == [
        "Icarus", "and Verilator", "(--binary)", "run"]


def test_runs_of_pragma_words_move_together():
    assert wrap("one two synthesis pragma lint_off three", width=8, indent="  ") == [
        "one", "  two synthesis pragma lint_off", "  three"]


def test_a_text_that_begins_with_one_quotes_it():
    assert wrap("verilator_top: the phongfx block", width=96) == ["`verilator_top`: the phongfx block"]


def test_nowhere_to_break_runs_long():
    assert wrap("verilator synthesis", width=5, indent="") == ["`verilator` synthesis"]


def test_ordinary_text_wraps_greedily_with_indent():
    assert wrap("aa bb cc dd ee", width=5) == ["aa bb", "  cc", "  dd", "  ee"]
    assert wrap("", width=5) == [""]


@pytest.mark.parametrize("word", PRAGMA_WORDS)
def test_no_width_lets_a_pragma_word_start_a_line(word):
    text = f"a {word} b {word.upper()} cc {word.capitalize()}_x ddd {word} {word}"
    for width in range(1, 40):
        lines = wrap(text, width=width)
        assert not any(starts_pragma(line) for line in lines), (width, lines)
        assert " ".join(lines).split() == text.split()  # every word, in order, none changed



def test_comment_lines():
    text = comment("runs under Icarus and Verilator (--binary) unchanged", width=25)
    assert text == "// runs under Icarus\n// and Verilator (--binary)\n// unchanged\n"
