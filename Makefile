# phongfx: `make sim` shades Lyon's scene through the Figure 7 datapath (golden + RTL),
# `make test` runs the test suite.  Both create .venv and install everything from PyPI.

PYTHON ?= python3
VENV ?= .venv
BACKEND ?= verilator-fast
STAMP := $(VENV)/.installed-stamp

.PHONY: sim test test-all synth sweep report bench identity clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet -e '.[cluster,bench]'
	touch $(STAMP)

sim: $(STAMP)
	$(VENV)/bin/phongfx render --backend $(BACKEND) --out build/sim

test: $(STAMP)
	$(VENV)/bin/python -m pytest -q --durations=10

# everything, including tests marked slow (long sweeps)
test-all: $(STAMP)
	$(VENV)/bin/python -m pytest -q -m "" --durations=10

# synthesis, place and route of the Figure 7 and Figure 8 datapaths (ECP5, yowasp tools)
synth: $(STAMP)
	$(VENV)/bin/phongfx synth fig7 --quiet
	$(VENV)/bin/phongfx synth fig8 --quiet

# the small default sweep: error and cost per width point, resumable (build/sweep)
sweep: $(STAMP)
	$(VENV)/bin/phongfx sweep sweeps/default.toml --out build/sweep

# build/report/index.md: the papers' tables beside ours, the sweep's Pareto plots
report: $(STAMP)
	$(VENV)/bin/phongfx report --out build/report --sweep build/sweep

# benchmarks (not part of make test): RTL verification throughput, golden model throughput
bench: $(STAMP)
	$(VENV)/bin/python -m bench.rtl
	$(VENV)/bin/python -m bench.golden
	$(VENV)/bin/python -m bench.scaling

# the behaviour identity check: this checkout's outputs against revision REF's (bench/identity.py)
REF ?= 58cdcc7
identity: $(STAMP)
	$(VENV)/bin/python -m bench.identity check --ref $(REF) --out build/identity

clean:
	rm -rf build
