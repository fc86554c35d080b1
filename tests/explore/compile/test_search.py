"""The width search's order of questions: a binary search per width, but one under the lowest
value passed first where the test's margins say the edge is there; the same widths either way."""

from types import SimpleNamespace

from phongfx.explore.compile.search import search_widths


class Rounding:
    """A test whose bound is ``1.4 + sum(weight · 2^-width)`` (each width's rounding halves per
    bit), passing under 1.5 and giving its margin to it, or no margins (``margins=False``)."""

    def __init__(self, weights, margins=True):
        self.weights, self.asked = weights, []
        if not margins:
            self.margin = None

    def bound(self, params):
        return 1.4 + sum(weight * 2.0 ** -params[name] for name, weight in self.weights.items())

    def __call__(self, params):
        self.asked.append(dict(params))
        return self.bound(params) < 1.5

    def margin(self, params):
        return 1.5 - self.bound(params) if self.bound(params) < 1.5 else None

    def failure(self, params):
        return {"bound_levels": self.bound(params)}


SCENE = SimpleNamespace(spec=SimpleNamespace(requirement=SimpleNamespace(against="self")), measured=lambda m, p: {})


def _search(weights, margins):
    test = Rounding(weights, margins)
    result = search_widths(SCENE, "conventional", passes=test)
    table = [p["table_addr"] for p in test.asked if p["table_addr"] < 8 and p["coef"] == 8]
    return result["params"], table, test.asked


def test_one_under_a_point_that_passed_at_the_edge_is_asked_next():
    # table_addr from 8 passes at 4 by 0.01 of 1.5, having spent 0.084 from 8: 3 next, not 2
    found, table, asked = _search({"table_addr": 1.44}, margins=True)
    binary, table_binary, asked_binary = _search({"table_addr": 1.44}, margins=False)
    assert found == binary == {"vec_frac": 6, "rsqrt_addr": 2, "table_addr": 4, "coef": 0}
    assert table == [4, 3] and table_binary == [4, 2, 3]
    assert len(asked) == len(asked_binary) - 1


def test_far_from_the_edge_the_questions_are_the_binary_searchs():
    # table_addr passes at 4 with 0.097 of its margin left, having spent 0.003: 2 next
    found, table, asked = _search({"table_addr": 0.05}, margins=True)
    binary, _, asked_binary = _search({"table_addr": 0.05}, margins=False)
    assert found == binary and found["table_addr"] == 1
    assert table == [4, 2, 1] and asked == asked_binary
