# SPDX-License-Identifier: Apache-2.0
"""svpwm_carrier against a per-clock reference written from the RTL header's spec (the golden model has
no carrier function; model/svpwm_model/core.py only uses its consequences: valleys 2P apart, peak at P).

Spec (rtl/svpwm_carrier.sv header): the count runs 0, 1, .., P-1 counting up (up_o = 1), then P, P-1,
.., 1 counting down, so f_sw = f_clk / (2P). valley_o: running, count 0 and up (first cycle of a
carrier period); peak_o: running, count P and down; load_o: the last cycle before a valley (down and
count 1) or any idle cycle -- period_i is taken in that cycle and active (period_o) from the next one,
so a period never changes mid-carrier. run_i low: hold at the valley (0, up) from the next clock on.
Reset: count 0, up, period 2. The reference below is that text as a generator, one tuple per clock.

Builds: CntWidth 16 (default) and 8 (the largest period, 255, is run too).
"""
from __future__ import annotations

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer, with_timeout
from cocotb.utils import get_sim_time

from simrun import REPO, run_sim

CLK_NS = 10


def carrier_ref(inputs, count=0, up=1, period=2):
    """Expected (count, up, period_o, valley, peak, load, pre_peak) of each clock for per-clock (run_i,
    period_i), starting from the reset state (count 0, counting up, period 2)."""
    for run, period_i in inputs:
        valley = int(run and up and count == 0)
        peak = int(run and not up and count == period)
        load = int(not run or (not up and count == 1))       # last clock of a carrier period, or idle
        pre_peak = int(run and up and count == period - 1)    # the next clock is the peak
        yield count, up, period, valley, peak, load, pre_peak
        if load:
            period = period_i                                   # active from the next clock (the valley)
        if not run:
            count, up = 0, 1                                    # hold at the valley
        elif up:
            count += 1                                          # 0 .. P-1 up; P is the first down clock
            up = int(count < period)
        else:
            count -= 1                                          # P .. 1 down, then 0 (up) again
            up = int(count == 0)


class CarrierTB:
    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.period_i)
        self.top = (1 << self.W) - 1

    def outputs(self):
        d = self.dut
        return (int(d.count_o.value), int(d.up_o.value), int(d.period_o.value), int(d.valley_o.value),
                int(d.peak_o.value), int(d.load_o.value), int(d.pre_peak_o.value))

    async def reset(self, period_i=1):
        d = self.dut
        d.run_i.value = 0
        d.period_i.value = period_i
        d.rst_ni.value = 0
        await FallingEdge(d.clk)
        await FallingEdge(d.clk)
        d.rst_ni.value = 1
        self.state = dict(count=0, up=1, period=2)

    async def per_clock(self, inputs, what=""):
        """Drive (run_i, period_i) per clock from a falling edge; compare every output in every clock.
        Returns the RTL trace. Must directly follow reset() (the reference starts from the reset state)."""
        d, trace = self.dut, []
        exp_iter = carrier_ref(inputs)
        for i, (run, period_i) in enumerate(inputs):
            d.run_i.value = run
            d.period_i.value = period_i
            await Timer(1, "ns")
            await ReadOnly()
            got, exp = self.outputs(), next(exp_iter)
            assert got == exp, (f"{what} clock {i} (run {run}, period_i {period_i}): RTL (count, up, period_o, "
                                f"valley, peak, load, pre_peak) = {got}, expected {exp}")
            trace.append(got)
            await FallingEdge(d.clk)
        return trace


def periods_of(trace):
    """Split a trace at the valleys: list of (start clock, counts of that carrier period)."""
    starts = [i for i, t in enumerate(trace) if t[3]]
    return [(a, [t[0] for t in trace[a:b]]) for a, b in zip(starts, starts[1:])]


@cocotb.test()
async def turnaround(dut):
    """P = 1, 2, 3, 100 (and the largest period for CntWidth 8): count sequence 0..P-1, P..1 exactly,
    valley at count 0, peak at count P, load in the last clock of the period, 2P clocks per period."""
    tb = CarrierTB(dut)
    for p in (1, 2, 3, 100) + ((tb.top,) if tb.top < 1000 else ()):
        await tb.reset(p)
        trace = await tb.per_clock([(0, p)] * 2 + [(1, p)] * (6 * p + 3), f"P={p}")
        run = trace[2:]
        per = periods_of(run)[:3]
        assert len(per) == 3
        for k, (start, counts) in enumerate(per):
            assert start == 2 * p * k
            assert counts == list(range(p)) + list(range(p, 0, -1)), f"P={p}: {counts}"
        for i, (count, up, period, valley, peak, load, pre_peak) in enumerate(run[:6 * p]):
            ph = i % (2 * p)
            assert up == int(ph < p) and period == p
            assert valley == int(ph == 0) and peak == int(ph == p) and load == int(ph == 2 * p - 1), (p, i)
            assert pre_peak == int(ph == p - 1), (p, i)


@cocotb.test()
async def period_change_at_valley(dut):
    """period_i changed mid-period (counting up and counting down, several times) takes effect only at
    the next valley: the running period completes with its old value; the value in the load clock wins."""
    tb = CarrierTB(dut)
    await tb.reset(10)
    sched = [(0, 10)] * 2 + [(1, 10)] * 3 + [(1, 4)] * 40            # 4 from the 4th clock of period 0
    sched[2 + 21: 2 + 26] = [(1, 7)] * 5            # 7 in period 1 (P=4, clocks 20..27) but not its load clock
    trace = await tb.per_clock(sched, "change")
    per = periods_of(trace[2:])
    assert [max(c) for _, c in per[:3]] == [10, 4, 4], [max(c) for _, c in per]
    # mid-down-count change, and a value that is there only in the load clock
    await tb.reset(6)
    sched = [(0, 6)] * 2 + [(1, 6)] * 8 + [(1, 9)] * 3 + [(1, 5)] + [(1, 3)] * 20
    # period 0: clocks 0..11 (P=6); clock 8 is count 4 down; clock 11 is the load clock (period_i = 5)
    trace = await tb.per_clock(sched, "load clock")
    per = periods_of(trace[2:])
    assert [max(c) for _, c in per[:3]] == [6, 5, 3], [max(c) for _, c in per]
    assert trace[2 + 11][5] == 1 and trace[2 + 12][2] == 5 and trace[2 + 11][2] == 6


@cocotb.test()
async def run_low_holds(dut):
    """run_i low: count 0 counting up, no valley/peak, load every clock, period_o follows period_i one
    clock later; run_i dropped mid-period returns to 0 on the next clock; resuming starts at a valley
    with the period loaded in the last idle clock."""
    tb = CarrierTB(dut)
    await tb.reset(5)
    idle = [(0, p) for p in (5, 9, 1, min(300, tb.top), 7, 7)]
    sched = idle + [(1, 7)] * 10 + [(0, 12)] * 3 + [(1, 2)] * 9 + [(0, 3)] + [(1, 3)] * 3
    trace = await tb.per_clock(sched, "run_i low")
    for i, (run, pi) in enumerate(sched):
        if not run:
            assert trace[i][5] == 1 and trace[i][3] == 0 and trace[i][4] == 0
            if i + 1 < len(sched):
                assert trace[i + 1][:3] == (0, 1, pi)                # held at the valley, period loaded
    assert [t[0] for t in trace[6:16]] == [0, 1, 2, 3, 4, 5, 6, 7, 6, 5]
    assert trace[16][0] == 4 and trace[17][0] == 0                # dropped at count 4 (down): 0 next clock


@cocotb.test()
async def switching_frequency(dut):
    """f_sw = f_clk / (2P), event-driven: successive valley_o rising edges are 2P clocks apart and the
    peak lies P clocks after the valley, for P = 1, 2, 3, 100, 1000 and the largest period."""
    tb = CarrierTB(dut)
    for p, n in [(p, n) for p, n in ((1, 8), (2, 8), (3, 8), (100, 5), (1000, 3)) if p < tb.top] + [(tb.top, 2)]:
        await tb.reset(p)
        dut.run_i.value = 1
        # valley_o is combinational in run_i: the first valley starts with the write of run_i, so
        # measure from the second valley on (all later ones start at a rising clock edge); run_i rises in
        # the first clock after reset, so that first period has the reset period (2)
        await with_timeout(RisingEdge(dut.valley_o), 2 * CLK_NS, "ns")
        await with_timeout(RisingEdge(dut.valley_o), (2 * max(p, 2) + 1) * CLK_NS, "ns")
        t_prev = get_sim_time("ns")
        for _ in range(n):
            if p > 1:
                await with_timeout(RisingEdge(dut.peak_o), (p + 1) * CLK_NS, "ns")
                assert get_sim_time("ns") - t_prev == p * CLK_NS, f"P={p}: peak not P clocks after valley"
            await with_timeout(RisingEdge(dut.valley_o), (2 * p + 1) * CLK_NS, "ns")
            t = get_sim_time("ns")
            assert t - t_prev == 2 * p * CLK_NS, f"P={p}: valley-to-valley {(t - t_prev) / CLK_NS} clocks"
            t_prev = t
        await FallingEdge(dut.clk)


@cocotb.test()
async def random_per_clock(dut):
    """Seeded random period_i changes (often, at any clock) and rare run_i drops, every clock checked."""
    tb = CarrierTB(dut)
    rng = random.Random(0xCA22 + tb.W)
    sched, p = [], 3
    for _ in range(1500):
        r = rng.random()
        if r < 0.15:
            p = rng.choice((1, 2, 3, rng.randint(1, 12), rng.randint(1, 40)))
        sched.append((int(rng.random() >= 0.02), p))
    await tb.reset(3)
    trace = await tb.per_clock(sched, "random")
    assert sum(t[3] for t in trace) > 50 and all(t[0] <= t[2] for t in trace)


BUILDS = {"cnt16": {"CntWidth": 16}, "cnt8": {"CntWidth": 8}}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_carrier(sim, build):
    run_sim(sim, toplevel="tb_svpwm_carrier",
            sources=[REPO / "rtl/svpwm_carrier.sv", Path(__file__).parent / "tb_svpwm_carrier.sv"],
            test_module="test_svpwm_carrier", test_dir=Path(__file__).parent,
            parameters=BUILDS[build], build_name=build)
