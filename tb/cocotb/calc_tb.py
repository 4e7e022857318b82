# SPDX-License-Identifier: Apache-2.0
"""What the two duty-calculator testbenches share (tb/cocotb/svpwm_duty: svpwm_duty; tb/cocotb/svpwm_duty_lite:
the compact core's svpwm_duty_lite): output sampling, reset, the harness checker, an aborted start, the
event-driven vector runner and the per-clock reference of the handshake with the loop that compares every
clock against it. A testbench subclasses CalcTB with its inputs (drive, junk, IDLE), its model (expect), its
result flags (FLAGS) and its latency (LATENCY).

Handshake (both RTL headers): start_i high in cycle c (sampled by the rising edge that ends cycle c) is
accepted when idle; busy_o is high in cycles c+1 .. c+LATENCY-1, done_o is a one-cycle pulse in cycle
c+LATENCY with the new sector_o / cmp_o / flags, which then hold until the next done_o; start_i is ignored
while busy_o; the done cycle is idle, so a start there is accepted (back to back); abort_i returns to idle
at once (no done_o, the results held; with start_i the start is not taken).
"""
from __future__ import annotations

import random
import time
from typing import Any

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer, with_timeout
from cocotb.utils import get_sim_time

CLK_NS = 10                  # the harnesses' clock period


def icarus() -> bool:
    return cocotb.SIM_NAME.lower().startswith("icarus")


class CalcTB:
    LATENCY: int = 0                     # clocks from start_i to done_o
    FLAGS: tuple[str, ...] = ()          # 1-bit result outputs after cmp_o, e.g. ("sat_o", "err_o")
    IDLE: Any = None                     # the input vector driven while idle

    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.period_i)
        self.top = (1 << self.W) - 1
        self.names = "(busy, done, sector, Ca, Cb, Cc, " + ", ".join(f[:-2] for f in self.FLAGS) + ")"

    # ---- per testbench -----------------------------------------------------------------------------
    def expect(self, v) -> tuple[int, ...]:
        """(sector, C_a, C_b, C_c, flags...) of the golden model."""
        raise NotImplementedError

    def drive(self, start: int, v) -> None:
        raise NotImplementedError

    def junk(self, rng: random.Random):
        """Any input word at all (what start_i must ignore while busy)."""
        raise NotImplementedError

    # ---- shared ------------------------------------------------------------------------------------
    def outputs(self) -> tuple[int, ...]:
        d, W = self.dut, self.W
        cmp = int(d.cmp_o.value)
        return (int(d.busy_o.value), int(d.done_o.value), int(d.sector_o.value),
                cmp & self.top, (cmp >> W) & self.top, (cmp >> 2 * W) & self.top,
                *(int(getattr(d, f).value) for f in self.FLAGS))

    async def reset(self):
        self.drive(0, self.IDLE)
        self.dut.abort_i.value = 0
        self.dut.rst_ni.value = 0
        await FallingEdge(self.dut.clk)
        await FallingEdge(self.dut.clk)
        self.dut.rst_ni.value = 1
        assert self.outputs() == (0,) * (6 + len(self.FLAGS))

    def check_harness(self, what: str):
        chk = int(self.dut.chk_o.value)
        assert chk == 0, (f"{what}: harness handshake checker chk_o = {chk:03b} (bit 0: output changed without "
                          f"done_o, 1: done_o > 1 clock, 2: busy_o not {self.LATENCY - 1} clocks long or done_o "
                          f"while busy)")

    async def aborted_start(self, rng: random.Random, k: int):
        """Start junk, pulse abort_i k clocks after the start edge (k = 0: together with start_i, which then
        is not accepted; k = LATENCY - 2, - 1: in the last steps, so no done_o must follow). The previous
        results must hold (the harness checker flags any output change without done_o); busy_o must be low
        afterwards."""
        dut = self.dut
        self.drive(1, self.junk(rng))
        dut.abort_i.value = int(k == 0)
        await FallingEdge(dut.clk)
        if k:
            self.drive(int(rng.random() < 0.5), self.junk(rng))
            await Timer((k - 1) * CLK_NS + 2, "ns")            # 2 ns after falling edge k (before rising edge k)
            dut.abort_i.value = 1
            await FallingEdge(dut.clk)
        self.drive(0, self.junk(rng))
        dut.abort_i.value = 0
        got = self.outputs()
        assert got[:2] == (0, 0), f"abort {k} clocks after the start: busy_o, done_o = {got[:2]}, expected idle"
        await FallingEdge(dut.clk)                              # no done_o on its way
        assert self.outputs()[:2] == (0, 0), f"abort {k} clocks after the start: busy_o / done_o after the abort"
        self.check_harness(f"abort {k} clocks after the start")

    async def run_vectors(self, vecs, rng: random.Random, name: str):
        """Event-driven, back to back: each vector is started in the done cycle of the previous one; 3 % are
        preceded by an aborted junk computation; while busy, start_i stays high with scrambled inputs (25 %:
        scrambled again mid-computation)."""
        dut, lat = self.dut, self.LATENCY
        prev = None
        t0 = time.perf_counter()
        await FallingEdge(dut.clk)
        for i, v in enumerate(vecs):
            if rng.random() < 0.03:                             # a junk computation aborted after k clocks
                await self.aborted_start(rng, rng.randint(0, lat - 1))
            self.drive(1, v)
            await FallingEdge(dut.clk)
            t_start = get_sim_time("ns") - CLK_NS // 2         # the rising edge that sampled v
            got = self.outputs()
            if prev is not None:                                # busy; done pulse over; results held
                assert got == (1, 0, *prev), f"{name} {i}: one clock after the start {got}, expected busy + {prev}"
            else:
                assert got[:2] == (1, 0), f"{name} {i}: not busy one clock after the start"
            self.drive(1, self.junk(rng))                       # start_i held high: ignored while busy
            if rng.random() < 0.25:                             # scramble once more mid-computation
                await Timer(rng.randint(1, lat - 3) * CLK_NS + 2, "ns")
                self.drive(int(rng.random() < 0.5), self.junk(rng))
            await with_timeout(RisingEdge(dut.done_o), (lat + 2) * CLK_NS, "ns")
            await ReadOnly()
            dt = get_sim_time("ns") - t_start
            assert dt == (lat - 1) * CLK_NS, f"{name} {i}: done_o {dt} ns after the start edge"
            exp = self.expect(v)
            got = self.outputs()
            assert got == (0, 1, *exp), f"{name} {i} {v}: RTL {self.names} = {got}, model {exp}"
            prev = exp
            await FallingEdge(dut.clk)                          # middle of the done cycle
        self.drive(0, self.IDLE)
        await FallingEdge(dut.clk)
        await FallingEdge(dut.clk)
        self.check_harness(name)
        dut._log.info("%s: %d vectors == model in %.1f s", name, len(vecs), time.perf_counter() - t0)

    async def protocol(self, sched: list[tuple[int, int, Any]], min_starts: int) -> None:
        """Every output on every clock against HandshakeRef for the schedule of (start_i, abort_i, inputs) per
        clock, then the handshake stated directly on the RTL trace: done_o exactly LATENCY clocks after each
        start that no abort cut, busy_o between, no other done_o, outputs changing only with done_o."""
        dut, lat = self.dut, self.LATENCY
        ref = HandshakeRef(self)
        trace, aborts = [], []
        for cyc, (start, abort, v) in enumerate(sched):
            got = self.outputs()
            assert got == ref.outputs(), f"cycle {cyc}: RTL {self.names} = {got}, ref {ref.outputs()}"
            trace.append(got)
            self.drive(start, v)
            dut.abort_i.value = abort
            if abort:
                aborts.append(cyc)
            ref.clock(cyc, start, abort, v)
            await FallingEdge(dut.clk)
        assert len(ref.starts) >= min_starts
        done_starts = [c for c in ref.starts if not any(c <= a < c + lat for a in aborts)]
        for c in done_starts:
            if c + lat < len(trace):
                assert trace[c + lat][1] == 1, f"no done_o {lat} clocks after the start in cycle {c}"
                assert all(trace[k][0] == 1 and trace[k][1] == 0 for k in range(c + 1, c + lat))
        dones = [k for k, t in enumerate(trace) if t[1]]
        assert dones == [c + lat for c in done_starts if c + lat < len(trace)]
        for a, b in zip(trace, trace[1:]):
            if not b[1]:
                assert b[2:] == a[2:], "outputs changed without done_o"
        self.check_harness("protocol")
        dut._log.info("protocol: %d clocks, %d starts (%d aborted), latency %d clocks", len(sched),
                      len(ref.starts), len(ref.starts) - len(done_starts), lat)


class HandshakeRef:
    """Per-clock reference of the handshake (module docstring), results from the testbench's model."""

    def __init__(self, tb: CalcTB):
        self.tb, self.st, self.latch, self.done = tb, 0, None, 0
        self.res: tuple[int, ...] = (0,) * (4 + len(tb.FLAGS))
        self.starts: list[int] = []

    def outputs(self) -> tuple[int, ...]:
        return (int(self.st != 0), self.done, *self.res)

    def clock(self, cycle: int, start: int, abort: int, v) -> None:
        self.done = 0
        if abort:                               # back to idle, no done_o, results held, start_i not taken
            self.st = 0
        elif self.st == self.tb.LATENCY - 1:
            self.st, self.done, self.res = 0, 1, self.tb.expect(self.latch)
        elif self.st:
            self.st += 1
        elif start:                             # idle (incl. the done cycle): accept
            self.st, self.latch = 1, v
            self.starts.append(cycle)
