# SPDX-License-Identifier: Apache-2.0
"""Waiting for clock edges without waking Python on every one of them.

cocotb's ``ClockCycles(clk, n)`` awaits the edge trigger ``n`` times, i.e. one Python callback per clock.
The harnesses generate their clock in SystemVerilog (``always #5 clk = ~clk``, 10 ns), so a long wait
can be one timer instead: ``clock_cycles`` awaits the first edge, then a timer to a quarter period before
the n-th edge, then that edge -- three callbacks for any ``n`` -- and checks that it landed on the n-th
edge (a stopped or differently timed clock fails loudly instead of counting wrong). It returns in the
same simulation step as ``await ClockCycles(clk, n, rising=...)``.
"""
from __future__ import annotations

from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, Timer
from cocotb.utils import get_sim_time

CLK_PS = 10_000          # the harness clock period (10 ns), in the 1 ps simulation precision


async def clock_cycles(clk, n: int, rising: bool = True, period_ps: int = CLK_PS) -> None:
    """Like ``await ClockCycles(clk, n, rising=rising)`` for a free-running clock of ``period_ps``."""
    if n <= 4:
        await ClockCycles(clk, n, rising=rising)
        return
    edge = RisingEdge(clk) if rising else FallingEdge(clk)
    await edge
    t1 = get_sim_time("ps")
    await Timer((n - 1) * period_ps - period_ps // 4, "ps")
    await edge
    got = get_sim_time("ps") - t1
    if got != (n - 1) * period_ps:
        raise AssertionError(f"clock_cycles: {clk._path} edge {n} came {got} ps after edge 1, "
                             f"not {(n - 1) * period_ps} ps (clock period not {period_ps} ps?)")
