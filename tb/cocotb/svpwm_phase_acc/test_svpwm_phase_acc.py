# SPDX-License-Identifier: Apache-2.0
"""svpwm_phase_acc against the golden model fixed.angle_step (exact integers, compared with ==).

Four builds: the core's default widths (PhaseWidth 34, FreqWidth 24) and a small one (10 / 8) in which
every step wraps a sector within a few clocks, each with the split adder svpwm_core uses (Split 1) and with the
one-chain adder (Split 0). fixed.angle_step works on the model's PHASE_WIDTH (34)
bits; a W-bit accumulator is the same arithmetic with the angle and the step scaled by 2^(34-W), which
is exact (every value is a multiple of 2^(34-W)), so the small build is compared to angle_step too.

Covered: reset (also asynchronous, mid-run) to sector 0 / angle 0; forward wrap across 60 deg (sector
0->1 ... 5->0) and backward (0->5 ...), landing exactly on 60 deg and on 0; steps +max, the most
negative step, 0 (standing) and run_i low (hold, whatever the step); seeded random steps checked after
every clock; the full-revolution sector sequence in both directions, event-driven (each sector change
is awaited and its clock index checked against the model).
"""
from __future__ import annotations

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, Timer, with_timeout
from clocks import clock_cycles

from simrun import REPO, run_sim
from svpwm_model import fixed

CLK_NS = 10
SEED = 0x5A11


class AccTB:
    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.angle_o)
        self.F = len(dut.step_i)
        assert self.W <= fixed.PHASE_WIDTH
        self.sh = fixed.PHASE_WIDTH - self.W
        self.max = (1 << (self.F - 1)) - 1
        self.min = -(1 << (self.F - 1))          # the most negative step
        self.state = (0, 0)

    def model(self, state, step, clocks):
        """fixed.angle_step on this build's width (see the module docstring)."""
        sec, ang = fixed.angle_step(state[0], state[1] << self.sh, step << self.sh, clocks)
        assert ang & ((1 << self.sh) - 1) == 0
        return sec, ang >> self.sh

    def outputs(self):
        return int(self.dut.sector_o.value), int(self.dut.angle_o.value)

    def drive(self, run, step):
        assert self.min <= step <= self.max
        self.dut.run_i.value = run
        self.dut.step_i.value = step & ((1 << self.F) - 1)

    async def reset(self):
        self.drive(0, 0)
        self.dut.rst_ni.value = 0
        await FallingEdge(self.dut.clk)
        await FallingEdge(self.dut.clk)
        self.dut.rst_ni.value = 1
        self.state = (0, 0)
        assert self.outputs() == (0, 0), f"after reset: {self.outputs()}"

    async def per_clock(self, seq, what=""):
        """Drive (run, step) per clock from a falling edge; check sector/angle after every clock."""
        for i, (run, step) in enumerate(seq):
            self.drive(run, step)
            await FallingEdge(self.dut.clk)
            if run:
                self.state = self.model(self.state, step, 1)
            got = self.outputs()
            assert got == self.state, (f"{what} clock {i}: run={run} step={step}: RTL (sector, angle) = {got}, "
                                       f"model {self.state}")

    async def fast_forward(self, step, clocks):
        """Constant step for `clocks` clocks without per-clock checks; check the state at the end."""
        self.drive(1, step)
        await clock_cycles(self.dut.clk, clocks, rising=False)
        self.state = self.model(self.state, step, clocks)
        assert self.outputs() == self.state, f"after {clocks} x {step}: {self.outputs()} != {self.state}"

    def clocks_to_next_sector(self, state, step):
        a = state[1]
        if step > 0:
            return -(-((1 << self.W) - a) // step)
        return a // -step + 1

    async def revolution(self, step, changes):
        """Run a constant step, await `changes` sector changes; each must occur on the model's clock."""
        dut = self.dut
        self.drive(1, step)
        s0, cyc0, k = self.state, int(dut.cyc_o.value), 0
        seq = []
        for _ in range(changes):
            n = self.clocks_to_next_sector(self.model(s0, step, k), step)
            k += n
            await with_timeout(dut.sector_o.value_change, (n + 3) * CLK_NS, "ns")
            await ReadOnly()
            exp = self.model(s0, step, k)
            got, clk = self.outputs(), int(dut.cyc_o.value) - cyc0
            assert (clk, got) == (k, exp), f"step {step}: sector change at clock {clk} to {got}, model: {k} {exp}"
            seq.append(got[0])
        await FallingEdge(dut.clk)
        self.state = self.model(s0, step, int(dut.cyc_o.value) - cyc0)
        assert self.outputs() == self.state
        return seq


@cocotb.test()
async def reset_to_zero(dut):
    """Reset gives sector 0 / angle 0; an asynchronous reset mid-run clears at once and holds."""
    tb = AccTB(dut)
    await tb.reset()
    await tb.per_clock([(1, tb.max)] * 7 + [(1, tb.min)] * 3 + [(1, 5)] * 2, "pre-reset")
    assert tb.state != (0, 0)
    await Timer(2, "ns")                         # between clock edges
    dut.rst_ni.value = 0
    await Timer(1, "ns")
    await ReadOnly()
    assert tb.outputs() == (0, 0), f"asynchronous reset: {tb.outputs()}"
    await FallingEdge(dut.clk)
    await FallingEdge(dut.clk)
    assert tb.outputs() == (0, 0)
    dut.rst_ni.value = 1
    tb.state = (0, 0)
    await tb.per_clock([(1, 3), (0, tb.max), (1, -1)], "post-reset")


@cocotb.test()
async def directed_edges(dut):
    """Wrap 0->5 and 5->0 by one LSB, the most negative and the largest step, landing exactly on
    60 deg and on 0, standing still (step 0) and run_i low (hold with a nonzero step)."""
    tb = AccTB(dut)
    W, F = tb.W, tb.F
    await tb.reset()
    await tb.per_clock([(1, -1)], "0->5 by -1")
    assert tb.state == (5, (1 << W) - 1)
    await tb.per_clock([(1, 1)], "5->0 by +1")
    assert tb.state == (0, 0)
    await tb.per_clock([(1, tb.min)], "most negative from 0")
    assert tb.state == (5, (1 << W) + tb.min)
    await tb.per_clock([(1, tb.max), (1, 1)], "+max then +1 back to 0")
    assert tb.state == (0, 0)
    await tb.per_clock([(1, 0)] * 4 + [(0, tb.max)] * 3 + [(0, tb.min)] * 3 + [(1, tb.max)] + [(1, 0)] * 3
                       + [(0, tb.max)] * 2, "standing / run_i low")
    assert tb.state == (0, tb.max)
    await tb.reset()
    q = 1 << (F - 2)                                 # divides 2^W: lands exactly on the boundaries
    n = 1 << (W - F + 2)
    if n > 2:
        await tb.fast_forward(q, n - 2)
    await tb.per_clock([(1, q), (1, q)], "exactly 60 deg")
    assert tb.state == (1, 0)
    await tb.per_clock([(1, -q)], "1->0 from angle 0")
    assert tb.state == (0, (1 << W) - q)
    await tb.per_clock([(1, q), (1, q), (1, -q)], "exactly 60 deg again, then back to exactly 0")
    assert tb.state == (1, 0)
    await tb.per_clock([(1, -1), (1, 1), (1, 0)], "1->0->1 by one LSB")
    assert tb.state == (1, 0)
    # 5 -> 0 by an exact landing: go to sector 5 angle 2^W - q, then +q
    await tb.reset()
    await tb.per_clock([(1, -q), (1, q), (1, -q)], "0->5->0->5")
    assert tb.state == (5, (1 << W) - q)
    await tb.per_clock([(1, q)], "5->0 exactly")
    assert tb.state == (0, 0)


def random_steps(tb: AccTB, rng: random.Random, n: int):
    seq = []
    for _ in range(n):
        r = rng.random()
        if r < 0.15:
            step = tb.max
        elif r < 0.30:
            step = tb.min
        elif r < 0.40:
            step = 0
        elif r < 0.55:
            step = rng.choice((-1, 1)) * rng.randint(1, 3)
        else:
            step = rng.randint(tb.min, tb.max)
        seq.append((int(rng.random() >= 0.1), step))
    return seq


@cocotb.test()
async def random_per_clock(dut):
    """Seeded random steps (incl. +max, most negative, 0, +-1..3, run_i low) checked after every clock,
    started at 0 (backward wraps), near 60 deg and near 0 of other sectors (wraps both ways)."""
    tb = AccTB(dut)
    rng = random.Random(SEED + tb.W)
    await tb.reset()
    await tb.per_clock(random_steps(tb, rng, 150), "random from 0")
    for _ in range(3):
        # up to just below the next 60 deg boundary, random walk across it
        await tb.fast_forward(tb.max, max(((1 << tb.W) - 1 - tb.state[1]) // tb.max, 1))
        await tb.per_clock(random_steps(tb, rng, 100), "random near 60 deg")
        # down to just above 0 of the sector, random walk across it
        await tb.fast_forward(tb.min, max(tb.state[1] // -tb.min, 1))
        await tb.per_clock(random_steps(tb, rng, 100), "random near 0")


@cocotb.test()
async def full_revolution(dut):
    """Sector sequence over a full revolution forward (+max: 1,2,3,4,5,0) and backward (most negative:
    5,4,3,2,1,0), every sector change on the model's clock; run twice around forward."""
    tb = AccTB(dut)
    await tb.reset()
    fwd = await tb.revolution(tb.max, 12)
    assert fwd == [1, 2, 3, 4, 5, 0] * 2, fwd
    await tb.reset()
    bwd = await tb.revolution(tb.min, 6)
    assert bwd == [5, 4, 3, 2, 1, 0], bwd
    # a slow step from a random phase: one revolution backward and forward
    rng = random.Random(SEED)
    await tb.per_clock([(1, rng.randint(tb.min, tb.max)) for _ in range(5)], "random start")
    s = (tb.max // 3) | 1
    fwd = await tb.revolution(s, 6)
    assert fwd == [(tb.state[0] + 1 + i) % 6 for i in range(-6, 0)], fwd
    bwd = await tb.revolution(-s, 6)
    assert bwd == [(tb.state[0] - 1 - i) % 6 for i in range(-6, 0)], bwd


# Split 0: the one-chain adder (svpwm_core uses the split one but in its tiny build), checked against the same model
BUILDS = {"w34_f24": {"PhaseWidth": 34, "FreqWidth": 24}, "w10_f8": {"PhaseWidth": 10, "FreqWidth": 8},
          "w34_f24_chain": {"PhaseWidth": 34, "FreqWidth": 24, "Split": 0},
          "w10_f8_chain": {"PhaseWidth": 10, "FreqWidth": 8, "Split": 0}}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_phase_acc(sim, build):
    run_sim(sim, toplevel="tb_svpwm_phase_acc",
            sources=[REPO / "rtl/svpwm_phase_acc.sv", Path(__file__).parent / "tb_svpwm_phase_acc.sv"],
            test_module="test_svpwm_phase_acc", test_dir=Path(__file__).parent,
            parameters=BUILDS[build], build_name=build)
