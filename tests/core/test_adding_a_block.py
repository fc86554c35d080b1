"""Adding a block is four source modules named after it, their tests, and one registry line.

This test adds a block ``toy`` (an exact dot product ``N·L``, one register) the way the
README's "Adding a block" says, without touching any other file: its config, golden,
hdl and stimulus modules are made from source text under the names the registry's
naming rule gives them (``phongfx.config.toy``, ``phongfx.golden.toy``,
``phongfx.hdl.toy``, ``phongfx.sim.stimulus.toy``), and one :class:`Entry` goes into
``REGISTRY``.  Then the command line lists, emits and checks it, and the extremes table
runs its rows, golden against RTL, like any other block's.
"""

import re
import sys
import textwrap
import types

import pytest

from phongfx.cli import main
from phongfx.core.registry import REGISTRY, Entry, get_block
from phongfx.explore.tables.extremes import run_block
from phongfx.sim.harness import check

SOURCES = {
    "phongfx.config.toy": '''
        from dataclasses import dataclass

        from phongfx.config.base import BlockConfig, check_format

        @dataclass(frozen=True)
        class ToyConfig(BlockConfig):
            vec: str = "S1.10"

            INPUTS = {"n": ("vec", 3), "l": ("vec", 3)}
            OUTPUTS = {"dot": ("out", 1)}

            @property
            def out(self):
                """The exact format of three products summed (the adder tree grows)."""
                product = self.fmt("vec").mul(self.fmt("vec"))
                return str(product.add(product).add(product))

            def validate(self):
                check_format("vec", self.vec, signed=True)
        ''',
    "phongfx.golden.toy": '''
        def toy(config, n, l):
            return {"dot": n.dot(l)}
        ''',
    "phongfx.hdl.toy": '''
        from phongfx.config.toy import ToyConfig
        from phongfx.hdl.block import PipelinedBlock
        from phongfx.hdl.fixed import stage

        class Toy(PipelinedBlock):
            """Latency: 1 (the sum is registered)."""

            config_class = ToyConfig
            latency = 1

            def datapath(self, m, i):
                return {"dot": stage(m, i["n"].dot(i["l"]), "dot")}
        ''',
    "phongfx.sim.stimulus.toy": '''
        import numpy as np

        from phongfx.sim.stimulus import AXES, codes, random_codes, rng
        from phongfx.sim.stimulus.extreme import Extreme, exactly

        def stimulus(config, count=1000, seed=0):
            vec, g = config.fmt("vec"), rng(seed)
            return {"n": random_codes(vec, (count, 3), g), "l": random_codes(vec, (count, 3), g)}

        def extremes(block_name):
            return (Extreme(block_name, "N = L on the axes", "1.0 exactly",
                            lambda c: {"n": codes(AXES, c.vec), "l": codes(AXES, c.vec)},
                            exactly("dot", 1.0)),)
        ''',
}


@pytest.fixture
def toy(monkeypatch):
    for name, source in SOURCES.items():  # dependencies first: the order of SOURCES
        module = types.ModuleType(name)
        monkeypatch.setitem(sys.modules, name, module)
        exec(compile(textwrap.dedent(source), f"<{name}>", "exec"), module.__dict__)
    monkeypatch.setitem(REGISTRY, "toy", Entry.of("toy", "ToyConfig", "Toy"))  # the one line
    return get_block("toy")


def test_a_new_block_is_a_block_like_any_other(toy, capsys, tmp_path):
    assert toy.latency == 1 and str(toy.config.fmt("out")) == "S5.20"
    raw = toy.stimulus(count=100, seed=3)
    assert (toy.golden(raw)["dot"] == (raw["n"] * raw["l"]).sum(axis=-1)).all()
    assert check(toy, raw, backend="amaranth").ok

    assert main(["blocks"]) == 0
    assert re.search(r"^toy +latency +1 ", capsys.readouterr().out, re.M)
    assert main(["verilog", "toy", "-o", str(tmp_path / "toy.v")]) == 0
    assert "module toy(" in (tmp_path / "toy.v").read_text()
    assert main(["sim", "toy", "--backend", "amaranth", "--vectors", "20"]) == 0
    assert "0 mismatching cycle(s)" in capsys.readouterr().out

    (row,), _ = run_block("toy")
    assert (row["block"], row["golden"], row["rtl"]) == ("toy", "pass", "pass")
