# Register map targets (included from the top Makefile).
#   make regs        regenerate docs/registers.md, sw/svpwm_regs.h, model/svpwm_model/regmap.py and
#                    rtl/svpwm_regs.sv from rdl/svpwm.rdl
#   make regs-check  fail if a committed output differs from what rdl/svpwm.rdl generates
#   make lint-bus    lint the bus wrappers (second verilator invocation; `make lint` runs it too)

.PHONY: regs regs-check lint-bus

regs: $(STAMP)
	$(PY) scripts/gen_regs.py

regs-check: $(STAMP)
	$(PY) scripts/gen_regs.py --check

# The bus-side tops are linted on their own (the main lint top is svpwm_core); same sources and waivers.
BUS_LINT_TOPS ?= svpwm_axil svpwm_wb svpwm_mmio svpwm_regs svpwm_axil_if svpwm_wb_if
lint: lint-bus
lint-bus: $(STAMP)
	@for t in $(BUS_LINT_TOPS); do \
	  echo "verilator $(LINT_FLAGS) --top-module $$t"; \
	  verilator $(LINT_FLAGS) --top-module $$t $(LINT_WAIVER) $(LINT_SRCS) || exit 1; done
	@echo "lint-bus: clean ($(BUS_LINT_TOPS))"
