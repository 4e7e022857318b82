# SPDX-License-Identifier: Apache-2.0
"""svpwm_duty against the golden model fixed.compare_values (exact, ==) and its handshake.

Handshake (RTL header, fixed.DUTY_LATENCY): start_i high in cycle c is accepted when idle; busy_o is
high in cycles c+1 .. c+10, done_o is a one-cycle pulse in cycle c+11 = c + DUTY_LATENCY, together with
the new cmp_o / sector_o, which then hold until the next done_o; start_i is ignored while busy_o.
`protocol` checks every output on every clock against a small reference of exactly that handshake;
`edge_vectors` / `random_vectors` run many vectors event-driven (await done_o, check its time).

Vectors: all six sectors at the sector edges (angle16 = 0, 1, 0x7FFF, 0x8000, 0xFFFE, 0xFFFF) x
m = 0, 1, 0x4000, 0x7FFF, 0x8000 x periods 16, 32, 1536, 2^CntWidth - 1 (65535 / 4095) on both
simulators, plus seeded random vectors (300 on Verilator, 100 on Icarus).

Builds: CntWidth 16 (default) and 12. compare_values has no width: for P < 2^CntWidth its results lie
in [0, P] and the RTL of any width must equal them -- the CntWidth = 12 build checks that claim.
"""
from __future__ import annotations

import itertools
import random
from dataclasses import dataclass
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, with_timeout
from cocotb.utils import get_sim_time

from simrun import REPO, run_sim
from svpwm_model import fixed

CLK_NS = 10
ANGLES = (0, 1, 0x7FFF, 0x8000, 0xFFFE, 0xFFFF)
MS = (0, 1, 0x4000, 0x7FFF, 0x8000)


@dataclass(frozen=True)
class Vec:
    sector: int
    angle: int
    m: int
    period: int


class DutyTB:
    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.period_i)
        self.top = (1 << self.W) - 1

    def expect(self, v: Vec) -> tuple[int, int, int, int]:
        """(sector, C_a, C_b, C_c) by the model; the model is width-free: check the result fits."""
        c = fixed.compare_values(v.sector, v.angle, v.m, v.period)
        assert all(0 <= x <= v.period <= self.top for x in c), (v, c)
        return (v.sector, *c)

    def outputs(self):
        d, W = self.dut, self.W
        cmp = int(d.cmp_o.value)
        return (int(d.busy_o.value), int(d.done_o.value), int(d.sector_o.value),
                cmp & self.top, (cmp >> W) & self.top, (cmp >> 2 * W) & self.top)

    def drive(self, start: int, v: Vec):
        d = self.dut
        d.start_i.value = start
        d.sector_i.value = v.sector
        d.angle_i.value = v.angle
        d.m_i.value = v.m
        d.period_i.value = v.period

    def rand_vec(self, rng: random.Random) -> Vec:
        return Vec(rng.randrange(6), rng.randrange(1 << 16), rng.randint(0, fixed.M_ONE),
                   rng.randint(16, self.top))

    async def reset(self):
        self.drive(0, Vec(0, 0, 0, 16))
        self.dut.rst_ni.value = 0
        await FallingEdge(self.dut.clk)
        await FallingEdge(self.dut.clk)
        self.dut.rst_ni.value = 1
        assert self.outputs() == (0, 0, 0, 0, 0, 0)

    async def run_vectors(self, vecs, rng: random.Random):
        """Event-driven: start each vector right in the done cycle of the previous one (back to back),
        scramble the inputs after the start, await done_o and check its time and the results."""
        dut = self.dut
        prev = None
        for i, v in enumerate(vecs):
            self.drive(1, v)
            await FallingEdge(dut.clk)
            t_start = get_sim_time("ns") - CLK_NS // 2         # the rising edge that sampled v
            if prev is not None:                                # the previous results still hold
                assert self.outputs()[1:] == (0, *prev), f"vector {i}: outputs changed before done_o"
            self.drive(0, self.rand_vec(rng))                   # inputs are sampled only at the start
            await with_timeout(RisingEdge(dut.done_o), (fixed.DUTY_LATENCY + 2) * CLK_NS, "ns")
            await ReadOnly()
            dt = get_sim_time("ns") - t_start
            assert dt == (fixed.DUTY_LATENCY - 1) * CLK_NS, f"vector {i}: done_o {dt} ns after the start edge"
            exp = self.expect(v)
            got = self.outputs()
            assert got == (0, 1, *exp), (f"vector {i} {v}: RTL (busy, done, sector, Ca, Cb, Cc) = {got}, "
                                        f"model {exp}")
            prev = exp
            await FallingEdge(dut.clk)


@cocotb.test()
async def edge_vectors(dut):
    """6 sectors x sector-edge angles x m = 0, 1, 0x4000, 0x7FFF, 0x8000 x periods 16, 32, 1536, max."""
    tb = DutyTB(dut)
    await tb.reset()
    periods = sorted({16, 32, 1536 if tb.top > 1536 else tb.top - 1, tb.top})
    vecs = [Vec(*x) for x in itertools.product(range(6), ANGLES, MS, periods)]
    await tb.run_vectors(vecs, random.Random(1))
    dut._log.info("%d edge vectors", len(vecs))


@cocotb.test()
async def random_vectors(dut):
    """Seeded random (sector, angle16, m <= 0x8000, period in [16, 2^CntWidth - 1])."""
    tb = DutyTB(dut)
    n = 100 if cocotb.SIM_NAME.lower().startswith("icarus") else 300
    rng = random.Random(0xD07 + tb.W)
    await tb.reset()
    await tb.run_vectors([tb.rand_vec(rng) for _ in range(n)], rng)


class Ref:
    """Per-clock reference of the handshake (module docstring), results from fixed.compare_values."""

    def __init__(self, tb: DutyTB):
        self.tb, self.st, self.latch, self.done, self.res = tb, 0, None, 0, (0, 0, 0, 0)
        self.starts, self.dones = [], []

    def outputs(self):
        return (int(self.st != 0), self.done, *self.res)

    def clock(self, cycle: int, start: int, v: Vec):
        self.done = 0
        if self.st == fixed.DUTY_LATENCY - 1:
            self.st, self.done, self.res = 0, 1, self.tb.expect(self.latch)
            self.dones.append(cycle + 1)
        elif self.st:
            self.st += 1
        elif start:
            self.st, self.latch = 1, v
            self.starts.append(cycle)


@cocotb.test()
async def protocol(dut):
    """Every output on every clock: single starts with gaps, start_i held high with inputs changing
    every clock (ignored while busy, back-to-back restarts), random start pulses."""
    tb = DutyTB(dut)
    rng = random.Random(0xB05 + tb.W)
    await tb.reset()
    sched = []
    for gap in (0, 1, 2, 15):                                 # single start pulses
        sched += [(1, tb.rand_vec(rng))] + [(0, tb.rand_vec(rng))] * (fixed.DUTY_LATENCY - 1 + gap)
    sched += [(1, tb.rand_vec(rng)) for _ in range(5 * fixed.DUTY_LATENCY + 3)]   # start held high
    sched += [(int(rng.random() < 0.3), tb.rand_vec(rng)) for _ in range(150)]    # random pulses
    sched += [(0, tb.rand_vec(rng))] * 14
    ref = Ref(tb)
    trace = []
    for cyc, (start, v) in enumerate(sched):
        got = tb.outputs()
        assert got == ref.outputs(), f"cycle {cyc}: RTL (busy, done, sector, Ca, Cb, Cc) = {got}, ref {ref.outputs()}"
        trace.append(got)
        tb.drive(start, v)
        ref.clock(cyc, start, v)
        await FallingEdge(dut.clk)
    # the handshake, stated directly on the RTL trace
    assert len(ref.starts) >= 15
    for c in ref.starts:
        if c + fixed.DUTY_LATENCY < len(trace):
            assert trace[c + fixed.DUTY_LATENCY][1] == 1, f"no done_o {fixed.DUTY_LATENCY} clocks after start at {c}"
            assert all(trace[k][0] == 1 and trace[k][1] == 0 for k in range(c + 1, c + fixed.DUTY_LATENCY))
    dones = [k for k, t in enumerate(trace) if t[1]]
    assert dones == [c + fixed.DUTY_LATENCY for c in ref.starts if c + fixed.DUTY_LATENCY < len(trace)]
    for a, b in zip(trace, trace[1:]):
        if not b[1]:
            assert b[2:] == a[2:], "outputs changed without done_o"


BUILDS = {"cnt16": {"CntWidth": 16}, "cnt12": {"CntWidth": 12}}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_duty(sim, build):
    run_sim(sim, toplevel="tb_svpwm_duty",
            sources=[REPO / "rtl/sine_rom.sv", REPO / "rtl/svpwm_duty.sv", Path(__file__).parent / "tb_svpwm_duty.sv"],
            test_module="test_svpwm_duty", test_dir=Path(__file__).parent,
            parameters=BUILDS[build], build_name=build)
