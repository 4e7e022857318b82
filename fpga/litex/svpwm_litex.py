# SPDX-License-Identifier: Apache-2.0
"""svpwm as a LiteX peripheral: rtl/svpwm_wb.sv (Wishbone B4 classic slave: svpwm_wb_if + svpwm_mmio =
the generated register block svpwm_regs + svpwm_core) behind a LiteX Wishbone interface.

    from svpwm_litex import SVPWM, SVPWM_BASE, add_svpwm
    add_svpwm(soc, platform.request("svpwm"), clk_hz=sys_clk_freq)     # slave "svpwm" at SVPWM_BASE
    add_svpwm(soc, pads, clk_hz=sys_clk_freq, config="foc")               # a smaller build of the core

Parameters (SVPWM):
  pads             - a record with hi (3), lo (3) gate outputs ({c, b, a}, 1 = transistor on), fault (1,
                     input) and, optionally, adc_trig, running, tripped (1, outputs) and adc_pt (2, outputs:
                     bit k pulses at the ADC trigger point ADC_PT<k>; 0 in a build without the feature adc)
  clk_hz           - the system clock in Hz (read back in the CLK_HZ register; the firmware converts units
                     with it)
  fault_active_low - the fault pad is active low (board pins with a pull-up); the core's fault_i is
                     active high
  gate_pol         - svpwm_core GatePol / CTRL.pol reset (2 bits: hi, lo sides inverted)
  config           - the build: a configuration name of model/svpwm_model/config.py CONFIGS (full, foc, vf,
                     minimal, tiny), a '+'-separated feature list or a mask (config.parse); passed as svpwm_wb's
                     Features (svpwm_core's and the register block's: registers of a feature not built read 0,
                     FEATURES.features tells the firmware). Default "full"
  min_period       - svpwm_core MinPeriod, default the build's (fixed.latencies(features)["MIN_PERIOD"], the same
                     as svpwm_pkg::min_period(Features), svpwm_wb's own default)
Bus: 32-bit data, word addressed (LiteX); the core sees byte addresses (bus.adr << 2), AddrWidth 8, so
the region is 256 bytes (the map, docs/registers.md, uses 0x00..0x8B; the rest reads 0). Classic cycles
(Pipelined = 0): LiteX masters hold STB until ACK; one access every two clocks, ACK the clock after.
Latency: a write is in its register (and at the core's input) from the clock its ACK is high.
Restrictions: the core and the bus share the system clock (sys); the fault pad is asynchronous (the core
synchronises it and also forces the gates off combinationally).
"""
from __future__ import annotations

import sys
from pathlib import Path

from migen import Cat, ClockSignal, Constant, Instance, ResetSignal, Signal

from litex.gen import LiteXModule
from litex.soc.interconnect import wishbone
from litex.soc.integration.soc import SoCRegion

REPO = Path(__file__).resolve().parents[2]
RTL = REPO / "rtl"
sys.path.insert(0, str(REPO / "model"))
from svpwm_model import config as svpwm_config  # noqa: E402
from svpwm_model.fixed import latencies  # noqa: E402

SVPWM_BASE = 0x9000_0000   # documented base address of the core's registers (LiteX IO region, uncached)
SVPWM_SIZE = 0x100         # AddrWidth 8


def rtl_sources() -> list[Path]:
    """The core's RTL, packages (*_pkg.sv) first (Yosys and Verilator read a package before its users)."""
    files = sorted(RTL.glob("*.sv"))
    return sorted(files, key=lambda f: not f.name.endswith("_pkg.sv"))


class SVPWM(LiteXModule):
    def __init__(self, platform, pads, clk_hz: int, fault_active_low: bool = False, gate_pol: int = 0,
                 config: str | int = "full", min_period: int | None = None):
        self.features = svpwm_config.parse(config)     # ValueError: names the configurations and features
        self.min_period = latencies(self.features)["MIN_PERIOD"] if min_period is None else int(min_period)
        self.bus = wishbone.Interface(data_width=32, address_width=32, addressing="word")
        self.fault = Signal()       # the core's fault_i (active high), after the pad's polarity
        self.hi = Signal(3)
        self.lo = Signal(3)
        self.adc_trig = Signal()
        self.adc_pt = Signal(2)     # adc_pt_o: trigger point k (0 in a build without adc)
        self.running = Signal()
        self.tripped = Signal()

        # # #

        addr_width = 8
        pole, valley, peak, update, sync_o = Signal(3), Signal(), Signal(), Signal(), Signal()
        stall = Signal()
        self.comb += self.fault.eq(~pads.fault if fault_active_low else pads.fault)
        self.specials += Instance("svpwm_wb",
            p_AddrWidth = addr_width,
            p_Pipelined = Constant(0, 1),
            p_GatePol   = Constant(gate_pol, 2),
            p_ClkHz     = int(clk_hz),
            p_Features  = Constant(self.features, 32),
            p_MinPeriod = self.min_period,
            i_clk_i     = ClockSignal("sys"),
            i_rst_ni    = ~ResetSignal("sys"),
            i_wb_cyc_i  = self.bus.cyc,
            i_wb_stb_i  = self.bus.stb,
            i_wb_we_i   = self.bus.we,
            i_wb_adr_i  = Cat(Constant(0, 2), self.bus.adr[:addr_width - 2]),
            i_wb_dat_i  = self.bus.dat_w,
            i_wb_sel_i  = self.bus.sel,
            o_wb_dat_o  = self.bus.dat_r,
            o_wb_ack_o  = self.bus.ack,
            o_wb_stall_o = stall,
            i_fault_i   = self.fault,
            i_sync_i    = Constant(0, 1),
            o_gate_hi_o = self.hi,
            o_gate_lo_o = self.lo,
            o_pole_o    = pole,
            o_valley_o  = valley,
            o_peak_o    = peak,
            o_update_o  = update,
            o_adc_trig_o = self.adc_trig,
            o_adc_pt_o  = self.adc_pt,
            o_sync_o    = sync_o,
            o_running_o = self.running,
            o_tripped_o = self.tripped,
        )
        self.comb += [pads.hi.eq(self.hi), pads.lo.eq(self.lo), self.bus.err.eq(0)]
        for name in ("adc_trig", "adc_pt", "running", "tripped"):
            if hasattr(pads, name):
                self.comb += getattr(pads, name).eq(getattr(self, name))
        for f in rtl_sources():
            platform.add_source(str(f), language="systemverilog")


def add_svpwm(soc, pads, clk_hz: int, origin: int = SVPWM_BASE, **kwargs) -> SVPWM:
    """Add the core to a LiteX SoC as the Wishbone slave "svpwm" at ``origin`` (SVPWM_BASE in the
    firmware's generated/mem.h); kwargs go to SVPWM (e.g. config="foc", the build)."""
    soc.svpwm = SVPWM(soc.platform, pads, clk_hz, **kwargs)
    soc.bus.add_slave("svpwm", soc.svpwm.bus, SoCRegion(origin=origin, size=SVPWM_SIZE, cached=False))
    return soc.svpwm
