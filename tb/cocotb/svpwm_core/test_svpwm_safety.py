# SPDX-License-Identifier: Apache-2.0
"""Issue 27 (safety): the findings of the independent random test, reproduced exactly, on the full and the
compact core (the same harness as test_svpwm_core.py, tb_svpwm_core.sv, and its builds).

Clock: 10 ns, rising edges at 10 k + 5 ns, falling edges at 10 k ns. "Edge j after a release" is the j-th
rising clock edge after rst_ni rose (edge 1 the first). CntMax = 2^DtWidth - 1 = 1023. The pins are sampled
1 ns after every rising edge (the harness' C record, trace_i), and every change of them is recorded as well
(M record), so that a gate on for less than a clock is seen too.

* f1_reset_with_fault (F1): a reset that turns a high side off and a fault raised with it and held across the
  release, with braking (safe_lo_i = 1): no gate on before the reset hold ends, the three low sides on at
  exactly edge CntMax + 1 after the release. Derivation: the synchroniser takes the held fault at edges 1 and
  2 after the release, so the dead-time FSMs see the trip (brake) from edge 2, with safe_lo_q (reloaded at edge
  1: the configuration is unlocked after a reset) set; the brake is in force long before the hold ends, so it
  adds no latency: the first turn-on is the hold's, edge CntMax + 1. Variants:
  (a) running, a 6 ns reset pulse between two clock edges; (b) the same with en_i lowered with it; (c) a reset
  over 3 clock edges, the core waiting for sync_i after it (never started); (d) locked (lock_i) with the largest
  falling dead time (1023; compact: its one dead time), a 6 ns pulse. Old RTL: the low sides on at edge 3.
* f2_clear_with_new_fault (F2): latched trip (trip_cbc_i = 0); a fault_clear_i pulse in the clock in which a
  new short fault_i pulse is high over the clock edge that takes the clear -- (a) 5 ns, (b) 2 ns around that
  edge: no gate on at any time after the clear, the trip latched again (tripped_o high through two valleys),
  fault_o the pulse through the synchroniser (high at edge 2 after the clear's clock only); a second clear
  without a fault releases it and the gates come back.
* f3_brake_before_start (F3): braking before the core has run since the reset (en_i low, or waiting for
  sync_i): a fault raised in clock k after the release turns the low sides on at edge max(CntMax + 1, k + 3)
  (2 synchroniser edges, the dead-time FSM's edge; the dead time in force is 0 before the first
  update), the gates are off otherwise; after the fault falls and a clear in clock c, the low sides stay on
  through edge c + 2 (the trip held one clock longer after the release) and are off from edge c + 3 on.
* f4_short_fault_no_gap (F4): latched, a fault_i pulse that spans one clock edge and falls before the next
  ((a) early, (b) late in the clock), (c) (a) with braking: from the fault's rise until the clear no gate on
  at any time (braking: no high side on), tripped_o high at every edge; (d) a 2 ns glitch between two edges,
  seen by no edge: every gate off while it lasts, nothing latched (tripped_o low at every edge after it, the
  gates back without a clear).
* reset_hold: every kind of reset (over clock edges, between two edges, over one edge) while running, with
  dt = 0 and 100: the first gate turn-on after it is at edge CntMax + 1 exactly (the model's reset hold).

Every test also asserts the harness' checker counters (the new ones included) 0 at its end. Each variant runs
from its own reset; a test collects the failures of all its variants and reports them together.
"""
from __future__ import annotations

from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, Timer
from cocotb.utils import get_sim_time

from clocks import clock_cycles
from simrun import cocotb_tests
from svpwm_model import fixed
from svpwm_model.core import Inputs
from svpwm_tb import CLK_NS, Clock, CoreTB, run_core_sim

FW = fixed.freq_word
MW = fixed.m_word
CNT_MAX = (1 << fixed.DT_WIDTH) - 1          # 1023: the reset hold ends at edge CNT_MAX + 1
HOLD_EDGE = CNT_MAX + 1
LOW_ALL = 0b111

COUNTERS = ("shoot_through_count", "dead_time_violations", "short_pulse_count", "off_violations",
            "trip_violations_o", "lock_violations_o", "reset_dt_violations_o", "reset_hold_violations_o",
            "trip_gap_violations_o")


def now() -> float:
    return get_sim_time("ns")


def next_edge(t: float) -> float:
    """The first rising clock edge after time t (rising edges at 10 k + 5 ns)."""
    return t + ((5 - int(t)) % CLK_NS or CLK_NS)


def counters(dut) -> dict[str, int]:
    return {k: int(getattr(dut, k).value) for k in COUNTERS}


class Trace:
    """The harness' record from start() to stop(): per-clock rows (edge time, Clock) and every change of mon
    (time, gates = mon & 0x3F: {lo[2:0], hi[2:0]})."""

    def __init__(self, tb: CoreTB):
        self.tb = tb
        self.rows: list[tuple[float, Clock]] = []
        self.gates: list[tuple[float, int]] = []

    def start(self) -> None:
        self.tb._rec_lines()                               # drop what came before
        self.t0 = now()
        self.tb.dut.trace_i.value = 1

    async def stop(self) -> None:
        await Timer(2, "ns")                               # the record of the last edge (1 ns after it)
        self.tb.dut.trace_i.value = 0
        for r in self.tb._rec_lines():
            t = int(r[1])
            if r[0] == "C" and t - 1 > self.t0:
                self.rows.append((t - 1, Clock(*(int(x, 16) for x in r[2:13]))))
            elif r[0] == "M" and t >= self.t0:
                if self.gates and self.gates[-1][0] == t:    # the last value of a time step (the record
                    self.gates.pop()                         # has every change within it)
                self.gates.append((t, int(r[2], 16) & 0x3F))

    def edge(self, t_edge: float, e1: float) -> int:
        """Index of a rising edge counted from e1 (the edge at e1 is 1)."""
        return int(round(t_edge - e1)) // CLK_NS + 1

    def first_gate_on(self, t_from: float) -> tuple[float, int] | None:
        return next(((t, g) for t, g in self.gates if t >= t_from and g), None)


def gates_of(k: Clock) -> tuple[int, int]:
    return k.hi, k.lo


async def wait_until(dut, cond, max_clocks: int, step: int = 7) -> None:
    """Poll cond() right after rising clock edges (ReadOnly), every `step` clocks; returns in ReadOnly."""
    for _ in range(max_clocks // step + 1):
        await clock_cycles(dut.clk, step)
        await ReadOnly()
        if cond():
            return
    raise AssertionError(f"condition not met within {max_clocks} clocks")


async def fresh(dut, u: Inputs, *, safe_lo=0, cbc=0, lock=0, en=1, run_clocks=0) -> CoreTB:
    """A reset (CoreTB: 3 clocks), the safety configuration, en_i, then run_clocks clocks (returns at a falling
    edge)."""
    tb = CoreTB(dut)
    await tb.reset(u)
    tb.set_safety(safe_lo=safe_lo, cbc=cbc, lock=lock)
    dut.en_i.value = en
    if run_clocks:
        await clock_cycles(dut.clk, run_clocks)
    await FallingEdge(dut.clk)
    return tb


def check_counters(dut, errs: list[str], what: str) -> None:
    c = counters(dut)
    if any(c.values()):
        errs.append(f"{what}: checker counters {c}")


def report(dut, errs: list[str]) -> None:
    for e in errs:
        dut._log.error(e)
    assert not errs, " | ".join(errs)


# ---- F1 ----------------------------------------------------------------------------------------------------
@cocotb.test()
async def f1_reset_with_fault(dut):
    """F1, four variants (module doc): the low sides on at exactly edge CntMax + 1 after the release."""
    compact = CoreTB(dut).compact
    errs: list[str] = []
    for variant in ("running", "disabled", "waiting_for_sync", "locked_dtf_max"):
        dt, dtf = 100, 100
        if variant == "locked_dtf_max":
            dt, dtf = (CNT_MAX, CNT_MAX) if compact else (100, CNT_MAX)
        u = Inputs(freq=FW(50.0), m=MW(0.8), period=1000, dt=dt, dtf=dtf)
        period = max(u.period, 2 * max(dt, dtf))                       # the clamp (mp = 0)
        tb = await fresh(dut, u, safe_lo=1, lock=int(variant == "locked_dtf_max"),
                         run_clocks=HOLD_EDGE + 6 * period)             # the dead times in force
        await wait_until(dut, lambda: int(dut.gate_hi_o.value) & 1, 8 * period)   # phase a's high side on
        await Timer(2, "ns")                                            # between the edges
        tr = Trace(tb)
        tr.start()
        t_rst = now()
        dut.rst_ni.value = 0
        dut.fault_i.value = 1
        if variant == "disabled":
            dut.en_i.value = 0
        if variant == "waiting_for_sync":
            dut.sync_en_i.value = 1
            dut.sync_i.value = 0
            await clock_cycles(dut.clk, 3)                              # a reset over 3 clock edges
            await FallingEdge(dut.clk)
        else:
            await Timer(1, "ns")
            pins = (int(dut.gate_hi_o.value), int(dut.gate_lo_o.value), int(dut.tripped_o.value))
            if pins != (0, 0, 1):
                errs.append(f"F1 {variant}: (hi, lo, tripped_o) 1 ns into the reset {pins}, expected (0, 0, 1)")
            await Timer(5, "ns")                                        # a 6 ns pulse, no edge in it
        dut.rst_ni.value = 1
        e1 = next_edge(now())                                           # edge 1 after the release
        await clock_cycles(dut.clk, HOLD_EDGE + 20)
        await tr.stop()
        dut.fault_i.value = 0
        first = tr.first_gate_on(t_rst)
        got = None if first is None else (tr.edge(first[0], e1), first[1])
        if got != (HOLD_EDGE, LOW_ALL << 3):
            errs.append(f"F1 {variant}: first gate turn-on after the reset at edge {got and got[0]} after the "
                        f"release with gates {got and bin(got[1])}, expected edge {HOLD_EDGE} with the three low "
                        f"sides (0b111000); checker {counters(dut)}")
        rows = [(tr.edge(t, e1), k) for t, k in tr.rows if t >= e1]
        bad = [(j, gates_of(k), k.tripped) for j, k in rows
               if (gates_of(k), k.tripped) != (((0, LOW_ALL) if j >= HOLD_EDGE else (0, 0)), 1)]
        if bad or len(rows) < HOLD_EDGE + 19:
            errs.append(f"F1 {variant}: per-clock (edge, (hi, lo), tripped) not as expected: {bad[:4]} "
                        f"({len(rows)} clocks)")
        check_counters(dut, errs, f"F1 {variant}")
        dut._log.info("F1 %s: the low sides on at edge %s after the release", variant, got)
    report(dut, errs)


# ---- F2 ----------------------------------------------------------------------------------------------------
@cocotb.test()
async def f2_clear_with_new_fault(dut):
    """F2: a clear in the clock of a new short fault pulse (over the clock edge / between two edges): no gate
    on after it, the trip latched again; a later clear releases it."""
    errs: list[str] = []
    P = 400
    u = Inputs(freq=FW(200.0), m=MW(0.5), period=P, dt=10, dtf=10)
    for variant, (t_on, t_off), fault_o_exp in (("over_edge", (2, 7), [0, 1, 0, 0, 0]),
                                                ("over_edge_2ns", (4, 6), [0, 1, 0, 0, 0])):
        tb = await fresh(dut, u, run_clocks=HOLD_EDGE + 4 * P)
        dut.fault_i.value = 1                                           # the trip, latched
        await clock_cycles(dut.clk, 2)
        await FallingEdge(dut.clk)
        dut.fault_i.value = 0
        await clock_cycles(dut.clk, 10)
        await FallingEdge(dut.clk)
        assert int(dut.tripped_o.value) == 1 and int(dut.gate_hi_o.value) == 0 == int(dut.gate_lo_o.value)
        tr = Trace(tb)
        tr.start()
        t_clr = now()                                                   # T: the clear's clock starts
        dut.fault_clear_i.value = 1
        await Timer(t_on, "ns")
        dut.fault_i.value = 1
        await Timer(t_off - t_on, "ns")
        dut.fault_i.value = 0
        await FallingEdge(dut.clk)
        dut.fault_clear_i.value = 0
        await clock_cycles(dut.clk, 4 * P)                              # two valleys and more
        await tr.stop()
        e1 = t_clr + 5                                                  # the edge that takes the clear
        on = tr.first_gate_on(t_clr)
        if on is not None:
            errs.append(f"F2 {variant}: a gate on after the clear: gates {bin(on[1])} at edge "
                        f"{tr.edge(on[0], e1)} (edge 1 takes the clear); checker {counters(dut)}")
        rows = [k for t, k in tr.rows if t >= e1]
        bad = [(j + 1, gates_of(k), k.tripped) for j, k in enumerate(rows) if gates_of(k) != (0, 0) or not k.tripped]
        if bad:
            errs.append(f"F2 {variant}: per clock after the clear (edge, (hi, lo), tripped_o): {bad[:4]}")
        if sum(k.valley for k in rows) < 2:
            errs.append(f"F2 {variant}: fewer than 2 valleys in the window")
        fo = [k.fault for k in rows[:5]]
        if fo != fault_o_exp:
            errs.append(f"F2 {variant}: fault_o at edges 1..5 {fo}, expected {fault_o_exp}")
        # a clear without a fault releases it: tripped_o low from the next edge, the gates back
        await FallingEdge(dut.clk)
        dut.fault_clear_i.value = 1
        await FallingEdge(dut.clk)
        dut.fault_clear_i.value = 0
        if int(dut.tripped_o.value):
            errs.append(f"F2 {variant}: a clear without a fault did not release the trip")
        try:
            await wait_until(dut, lambda: int(dut.gate_hi_o.value) or int(dut.gate_lo_o.value), 2 * P, step=3)
        except AssertionError:
            errs.append(f"F2 {variant}: no gate on within a period after the release")
        await FallingEdge(dut.clk)
        check_counters(dut, errs, f"F2 {variant}")
    report(dut, errs)


# ---- F3 ----------------------------------------------------------------------------------------------------
@cocotb.test()
async def f3_brake_before_start(dut):
    """F3: a trip brakes before the core has run since the reset (en_i low / waiting for sync_i): the low sides
    on at edge max(CntMax + 1, k + 3) for a fault raised in clock k, off otherwise; after a clear in clock c
    they are off from edge c + 3."""
    errs: list[str] = []
    u = Inputs(freq=FW(50.0), m=MW(0.8), period=1000, dt=100, dtf=100)
    for state in ("disabled", "waiting_for_sync"):
        for k in (10, 1500):
            tb = CoreTB(dut)
            dut.en_i.value = 0
            dut.trace_i.value = 0
            tb.set_inputs(u)
            tb.set_safety(safe_lo=1)
            if state == "waiting_for_sync":
                dut.en_i.value = 1
                dut.sync_en_i.value = 1
            await FallingEdge(dut.clk)
            dut.rst_ni.value = 0
            await clock_cycles(dut.clk, 3)
            await FallingEdge(dut.clk)
            tr = Trace(tb)
            tr.start()
            dut.rst_ni.value = 1
            e1 = now() + 5
            await clock_cycles(dut.clk, k)                              # edge k
            await FallingEdge(dut.clk)                                  # clock k
            dut.fault_i.value = 1
            on_exp = max(HOLD_EDGE, k + 3)
            await clock_cycles(dut.clk, on_exp - k + 20)
            await FallingEdge(dut.clk)
            dut.fault_i.value = 0
            await clock_cycles(dut.clk, 5)
            await FallingEdge(dut.clk)
            c = tr.edge(now() + 5, e1) - 1                              # the clear's clock
            dut.fault_clear_i.value = 1
            await FallingEdge(dut.clk)
            dut.fault_clear_i.value = 0
            await clock_cycles(dut.clk, 300)
            await tr.stop()
            what = f"F3 {state} fault in clock {k}"
            first = tr.first_gate_on(e1 - 5)
            got = None if first is None else (tr.edge(first[0], e1), first[1])
            if got != (on_exp, LOW_ALL << 3):
                errs.append(f"{what}: first gate turn-on at edge {got and got[0]} with gates {got and bin(got[1])}, "
                            f"expected edge {on_exp} with the three low sides; checker {counters(dut)}")
            rows = [(tr.edge(t, e1), kk) for t, kk in tr.rows if t >= e1]
            exp = lambda j: (0, LOW_ALL) if on_exp <= j <= c + 2 else (0, 0)     # noqa: E731
            bad = [(j, gates_of(kk)) for j, kk in rows if gates_of(kk) != exp(j)]
            if bad:
                errs.append(f"{what}: (edge, (hi, lo)) not as expected (low sides on at edges {on_exp} .. {c + 2}): "
                            f"{bad[:4]}")
            check_counters(dut, errs, what)
        dut.sync_en_i.value = 0
    report(dut, errs)


# ---- F4 ----------------------------------------------------------------------------------------------------
@cocotb.test()
async def f4_short_fault_no_gap(dut):
    """F4: latched, a short fault pulse (over one edge, early or late in the clock; between two edges; with
    braking): the pins safe at every time from the fault's rise until the clear."""
    errs: list[str] = []
    P = 400
    u = Inputs(freq=FW(200.0), m=MW(0.5), period=P, dt=10, dtf=10)
    for variant, (t_on, t_off), safe_lo in (("over_edge_early", (1, 9), 0), ("over_edge_late", (4, 14), 0),
                                            ("over_edge_braking", (1, 9), 1), ("glitch_between_edges", (1, 3), 0)):
        tb = await fresh(dut, u, safe_lo=safe_lo, run_clocks=HOLD_EDGE + 4 * P)
        await wait_until(dut, lambda: int(dut.gate_hi_o.value) != 0, 2 * P, step=1)   # a high side on
        await FallingEdge(dut.clk)
        tr = Trace(tb)
        tr.start()
        t0 = now()
        await Timer(t_on, "ns")
        t_f = now()
        dut.fault_i.value = 1
        await Timer(t_off - t_on, "ns")
        dut.fault_i.value = 0
        await clock_cycles(dut.clk, 40)
        await FallingEdge(dut.clk)
        t_clr = now()
        dut.fault_clear_i.value = 1
        await FallingEdge(dut.clk)
        dut.fault_clear_i.value = 0
        await clock_cycles(dut.clk, 2 * P)
        await tr.stop()
        e1 = t0 + 5                                                     # the first edge that sees the fault
        unsafe = (lambda g: g != 0) if not safe_lo else (lambda g: g & 0b111 != 0)   # noqa: E731
        if variant == "glitch_between_edges":       # seen by no edge: off while it lasts, nothing latched
            bad = [(t - t_f, bin(g)) for t, g in tr.gates if t_f <= t < t_f + (t_off - t_on) and unsafe(g)]
            if bad:
                errs.append(f"F4 {variant}: a gate on during the glitch: {bad[:4]}")
            rows = [k for t, k in tr.rows if t >= e1]
            if any(k.tripped or k.fault for k in rows) or not any(k.hi for k in rows[:2 * P]):
                errs.append(f"F4 {variant}: a glitch no edge sees latched, or the gates did not come back")
            check_counters(dut, errs, f"F4 {variant}")
            continue
        bad = [(t - t_f, bin(g)) for t, g in tr.gates if t_f <= t < t_clr + 5 and unsafe(g)]
        if bad:
            errs.append(f"F4 {variant}: pins not safe between the fault ({t_f} ns) and the clear: (ns after the "
                        f"fault, gates) {bad[:4]}; checker {counters(dut)}")
        rows = [(tr.edge(t, e1), k) for t, k in tr.rows if e1 <= t < t_clr + 5]
        badr = [(j, gates_of(k), k.tripped) for j, k in rows
                if k.hi or (k.lo and not safe_lo) or not k.tripped]
        if badr:
            errs.append(f"F4 {variant}: per clock from the first edge that sees the fault to the clear "
                        f"(edge, (hi, lo), tripped_o): {badr[:4]}")
        after = [k for t, k in tr.rows if t >= t_clr + 5]
        if any(k.tripped for k in after) or not any(k.hi for k in after):
            errs.append(f"F4 {variant}: not released by the clear (or no high side on after it)")
        check_counters(dut, errs, f"F4 {variant}")
    report(dut, errs)


# ---- the reset hold ----------------------------------------------------------------------------------------
@cocotb.test()
async def reset_hold(dut):
    """Every kind of reset while running (over 3 clock edges, a 6 ns pulse between two edges, a 6 ns pulse over
    one edge), dt = 0 and 100: the first gate turn-on after the release at edge CntMax + 1 exactly."""
    errs: list[str] = []
    P = 300
    for dt in (0, 100):
        u = Inputs(freq=FW(300.0), m=MW(0.6), period=P, dt=dt, dtf=dt)
        tb = await fresh(dut, u, run_clocks=HOLD_EDGE + 4 * P)
        for kind in ("over_edges", "between_edges", "over_one_edge"):
            await wait_until(dut, lambda: int(dut.gate_hi_o.value) != 0, 2 * P, step=1)
            await Timer(2 if kind != "over_one_edge" else 7, "ns")
            tr = Trace(tb)
            tr.start()
            t_rst = now()
            dut.rst_ni.value = 0
            if kind == "over_edges":
                await clock_cycles(dut.clk, 3)
                await FallingEdge(dut.clk)
            else:
                await Timer(6, "ns")
            dut.rst_ni.value = 1
            t_rel = now()
            e1 = next_edge(t_rel)
            await clock_cycles(dut.clk, HOLD_EDGE + 10)
            await tr.stop()
            first = tr.first_gate_on(t_rst)
            got = None if first is None else tr.edge(first[0], e1)
            if got != HOLD_EDGE:
                errs.append(f"reset hold, dt {dt}, {kind}: first turn-on at edge {got} after the release "
                            f"(release at {t_rel} ns, edge 1 at {e1} ns), expected {HOLD_EDGE}")
            await FallingEdge(dut.clk)
        check_counters(dut, errs, f"reset hold dt {dt}")
    report(dut, errs)


# ---- pytest items: one per cocotb test and build (the builds of test_svpwm_core.py: the same sources and
# parameters: svpwm_tb.CORE_BUILDS, so the simulator models are shared)
CASES = cocotb_tests(__file__)


@pytest.mark.parametrize("case", CASES)
def test_svpwm_safety(sim, case):
    run_core_sim(sim, "test_svpwm_safety", Path(__file__).parent, "default", case)


@pytest.mark.parametrize("case", CASES)
def test_svpwm_safety_compact(sim, case):
    run_core_sim(sim, "test_svpwm_safety", Path(__file__).parent, "compact", case)
