"""The report page's HTML pieces: escaping, numbers and costs in words, tables, PNG data URIs."""

import base64

import pytest

from phongfx.deliver.markup import Html, cost_text, esc, levels, number, pairs, png_data_uri, table


def test_text_is_escaped_unless_it_is_html():
    assert esc('<a href="x">&') == "&lt;a href=&quot;x&quot;&gt;&amp;"
    assert esc(Html("<b>x</b>")) == "<b>x</b>" and esc(None) == ""


@pytest.mark.parametrize("value, text", [(1.0, "1"), (28595, "28,595"), (1.4963, "1.5"), ("inf", "inf"),
                                         (None, "—"), (True, "True")])
def test_numbers_read_as_a_person_writes_them(value, text):
    assert number(value) == text


def test_levels_and_costs_in_words():
    assert (levels(1.0), levels(2), levels(None)) == ("1 level", "2 levels", "—")
    assert cost_text({"cost": 28595.0, "unit": "LUT-eq"}) == "LUT-eq 28,595"
    assert cost_text({"cost": 56789.4, "unit": "µm²"}) == "area 56,789 µm²"
    assert cost_text({"cost": None, "why": "Yosys did not finish"}) == "unknown (Yosys did not finish)"
    assert cost_text(None) == "unknown (not costed)"


def test_tables_escape_their_cells_and_pairs_leave_out_missing_values():
    assert table([["<x>", 1]], ["a", "b"], ["chosen"]) == (
        "<table>\n<tr><th>a</th><th>b</th></tr>\n<tr class=\"chosen\"><td>&lt;x&gt;</td><td>1</td></tr>\n</table>")
    assert pairs([("kept", 0), ("none", None), ("false", False)]).count("<tr>") == 1


def test_a_png_becomes_a_data_uri_and_anything_else_is_refused(tmp_path):
    path = tmp_path / "a.png"
    path.write_bytes(b"\x89PNG\r\n\x1a\nrest")
    assert png_data_uri(path) == "data:image/png;base64," + base64.b64encode(b"\x89PNG\r\n\x1a\nrest").decode()
    path.write_bytes(b"GIF89a")
    with pytest.raises(ValueError, match=r"a\.png: not a PNG \(its first bytes are b'GIF89a'\)"):
        png_data_uri(path)
