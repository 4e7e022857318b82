# SPDX-License-Identifier: Apache-2.0
"""svpwm_core against the golden model: every gate and pole edge, every period's compare values.

Operating points (each over at least one full revolution of the output vector, except where the
frequency is zero): Minas Fig. 9 and 10 (5.1 Hz and 50 Hz at f_sw = 15.625 kHz), m = 0, a small m,
0.5 and 1, negative and zero frequency, a reversal through zero, a period and a dead-time change while
running, and a disable mid-period. Besides bit-exactness: Table I sequences, leg safety from the edges,
an in-RTL per-clock safety checker, and the duty error against the floating-point ideal.

Icarus (~100x slower than Verilator) runs every operating point over a complete but shorter window:
the same revolutions / transitions with fewer clocks (Fig. 10: P = 256 at 6x the frequency, the same
315 periods per revolution; other points: a higher frequency, i.e. fewer carrier periods per revolution,
or fewer periods per step), bit-exact like every run; Verilator runs them in full (ICARUS below).

Builds (svpwm_core Features, model/svpwm_model/config.py): the full core, vf, and the tiny one (the compact
variant: the iCEstick's HX1K, FREQ mode, SVPWM, valley updates, one serial calculator with a longer lead) run
every test against the golden model (CoreModel(features=...)); foc and minimal (no FREQ mode) run
`full_only_inputs`, which checks that a build ignores what it does not have (their modes:
tb/cocotb/svpwm_modes).
"""
from __future__ import annotations

import math
import random
from dataclasses import replace
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer
from cocotb.utils import get_sim_time

from simrun import cocotb_tests, sims_to_run
from svpwm_model import fixed
from svpwm_model.analysis import duty_error, line_fundamental
from svpwm_model.core import CoreModel, Inputs
from svpwm_tb import CLK_NS, CoreTB, core_items, run_core_sim
from clocks import clock_cycles

F_CLK = fixed.F_CLK_DEFAULT
P_VERMA = 1536                        # 48 MHz / (2 * 1536) = 15.625 kHz (Verma; Minas: ~15.6 kHz)
DT_1US = 48                           # 1 us dead time at 48 MHz
FW = fixed.freq_word
MW = fixed.m_word


ICARUS = (getattr(cocotb, "SIM_NAME", None) or "").lower().startswith("icarus")
F_SCALE = 6 if ICARUS else 1          # Icarus: frequencies x6 (a revolution in 1/6 of the periods)


def periods_per_rev(f_hz: float, period: int = P_VERMA) -> int:
    """Carrier periods covering at least one revolution (+2 for the pipeline start)."""
    return math.ceil(F_CLK / (2 * period) / abs(f_hz)) + 2


def const(u: Inputs):
    return lambda n: u


async def check_run(tb: CoreTB, idle: Inputs, inputs, n: int, stop=None, dt_of=None):
    rtl, exp = await tb.run(idle, inputs, n, stop)
    tb.compare(rtl, exp)
    seq = tb.check_edges(rtl, exp, stop, dt_of=dt_of)
    err, _ = duty_error(exp)
    assert err <= 1.0, f"duty error {err:.3f} counts > 1 count vs the ideal SVPWM"
    tb.dut._log.info("%d periods, %d edges, Table I ok (%d with skipped states), worst |C - ideal| = %.3f",
                     len(rtl.cmp), len(rtl.gate_edges), seq.with_skips, err)
    return rtl, exp


@cocotb.test()
async def minas_fig10_50hz(dut):
    """Minas Fig. 10: 50 Hz at 15.6 kHz, m = 0.9, 1 us dead time; fundamental within 0.1 %."""
    tb = CoreTB(dut)
    # Icarus: P / 6 at 6 x 50 Hz, the same 315 periods per revolution (the fundamental is within 0.015 %)
    u = Inputs(freq=FW(50.0 * F_SCALE), m=MW(0.9), period=P_VERMA // F_SCALE, dt=DT_1US // F_SCALE)
    await tb.reset(u)
    n = periods_per_rev(50.0 * F_SCALE, u.period)
    rtl, exp = await check_run(tb, u, const(u), n)
    amp = line_fundamental(rtl.pole_edges, u.freq, rtl.valley[1] + 1, 1)
    assert abs(amp / 0.9 - 1) < 1e-3, f"line fundamental {amp:.5f} vs command 0.9"


@cocotb.test()
async def minas_fig9_5hz(dut):
    """Minas Fig. 9: 5.1 Hz at 15.6 kHz, V/f-like m = 0.102 (5.1/50 * 1.0), 1 us dead time.

    One revolution is 3063 carrier periods = 9.4 M clocks. Icarus runs one revolution of the same m at
    P = 256 (above MinPeriod) and 36 x 5.1 Hz: 513 periods, 1/36 of the clocks, bit-exact against the
    model like every run; the 0.1 % fundamental requirement is specified at P = 1536 and is asserted
    on the Verilator run of Fig. 9 itself (at P = 256 and m = 0.1 rounding the edges to the clock alone
    moves the fundamental by ~0.2 %)."""
    tb = CoreTB(dut)
    scale = 6 if ICARUS else 1
    f = 5.1 * scale * scale
    u = Inputs(freq=FW(f), m=MW(0.102), period=P_VERMA // scale, dt=DT_1US // scale)
    await tb.reset(u)
    rtl, exp = await check_run(tb, u, const(u), periods_per_rev(f, u.period))
    amp = line_fundamental(rtl.pole_edges, u.freq, rtl.valley[1] + 1, 1)
    dut._log.info("line fundamental %.6f vs command 0.102 (%+.4f %%), P = %d", amp, (amp / 0.102 - 1) * 100,
                  u.period)
    if scale == 1:
        assert abs(amp / 0.102 - 1) < 1e-3, f"line fundamental {amp:.5f} vs command 0.102"


@cocotb.test()
async def modulation_sweep(dut):
    """m = 0, 0.02, 0.5, 1.0 at 200 Hz (Icarus 1200 Hz), one revolution each, no dead time then 5 us."""
    tb = CoreTB(dut)
    for i, (m, dt) in enumerate(((0.0, 0), (0.02, 0), (0.5, 240), (1.0, 240))):
        u = Inputs(freq=FW(200.0 * F_SCALE), m=MW(m), period=P_VERMA, dt=dt)
        await tb.reset(u)
        await check_run(tb, u, const(u), periods_per_rev(200.0 * F_SCALE))


@cocotb.test()
async def reverse_and_zero_frequency(dut):
    """-150 Hz (Icarus -900 Hz; reverse rotation, all six sectors backwards) and 0 Hz (standing vector)."""
    tb = CoreTB(dut)
    u = Inputs(freq=FW(-150.0 * F_SCALE), m=MW(0.75), period=P_VERMA, dt=DT_1US)
    await tb.reset(u)
    rtl, _ = await check_run(tb, u, const(u), periods_per_rev(150.0 * F_SCALE), stop=100)
    assert sorted(set(rtl.sector)) == [0, 1, 2, 3, 4, 5]
    u0 = Inputs(freq=0, m=MW(0.6), period=P_VERMA, dt=DT_1US)
    tb.set_inputs(u0)
    rtl0, _ = await check_run(tb, u0, const(u0), 40 // F_SCALE)
    assert len(set(rtl0.cmp)) == 1, "a standing vector must give the same compare values every period"


@cocotb.test()
async def reversal_through_zero(dut):
    """The frequency ramps +200 Hz -> -200 Hz (Icarus +-1200 Hz) through zero; the vector turns, stops and
    turns back."""
    tb = CoreTB(dut)
    f0 = 200.0 * F_SCALE
    n = 2 * periods_per_rev(f0)
    f_of = lambda k: f0 - 2 * f0 * k / (n - 1)
    idle = Inputs(freq=FW(f0), m=MW(0.8), period=P_VERMA, dt=DT_1US)
    await tb.reset(idle)
    rtl, exp = await check_run(tb, idle, lambda k: Inputs(FW(f_of(k)), MW(0.8), P_VERMA, DT_1US), n)
    assert min(exp.theta[1:]) != max(exp.theta[1:])


@cocotb.test()
async def period_and_dead_time_change(dut):
    """Period 1536 -> 1000 -> 2400 -> 64 and dead time 48 -> 0 -> 240 -> 5 while running at 100 Hz, 40 periods
    each (Icarus: 8)."""
    tb = CoreTB(dut)
    steps = ((1536, 48), (1000, 0), (2400, 240), (64, 5), (1536, 48))
    n_each = 8 if ICARUS else 40
    sched = [Inputs(FW(100.0), MW(0.85), p, d) for p, d in steps for _ in range(n_each)]
    await tb.reset(sched[0])
    await check_run(tb, sched[0], sched, len(sched))


@cocotb.test()
async def dead_time_change_at_valley(dut):
    """m = 1 (compare values snapped to dt + mp near each phase's minimum, so gate decisions fall on the
    valley clock) with the dead time and minimum pulse changing at every valley: a new dead time reaches
    the legs one clock after the valley. Two revolutions at 400 Hz, P = 600 (Icarus: one)."""
    tb = CoreTB(dut)
    steps = ((600, 6, 0), (600, 23, 0), (600, 9, 4), (600, 31, 0), (600, 17, 2))
    n = periods_per_rev(400.0, 600) * (1 if ICARUS else 2)
    sched = [Inputs(FW(400.0), MW(1.0), *steps[k % len(steps)]) for k in range(n)]
    await tb.reset(sched[0])
    await check_run(tb, sched[0], sched, len(sched))


@cocotb.test()
async def asymmetric_dead_time(dut):
    """Separate rising (dt_i) and falling (dtf_i, dtf_en_i = 1) dead times, changing at valleys: each
    larger in turn, a zero on one edge (a swap there), dtf_en_i = 0 with another value on dtf_i (ignored),
    a minimum pulse, a period too short for the larger dead time (raised to 2 (max(dt, dtf) + mp)), and
    changes of dtf alone that force an update (the prescaler skips 3 of 4 valleys otherwise). Every gate
    and pole edge and every period == model; the compact core ignores dtf (its model: one dead time).
    Not vacuous: the model with dtf removed gives other gate edges (the full core), the same (compact)."""
    tb = CoreTB(dut)
    P = 600
    steps = [dict(dt=6, dtf=20), dict(dt=20, dtf=6), dict(dt=0, dtf=9, mp=2), dict(dt=11, dtf=0),
             dict(dt=9), dict(dt=5, dtf=31, mp=4), dict(dt=5, dtf=12, mp=4), dict(dt=5, dtf=12, mp=4),
             dict(dt=10, dtf=150, period=280), dict(dt=10, dtf=40, period=280), dict(dt=40, dtf=10)]
    n_each = 3 if ICARUS else 9
    sched = [Inputs(FW(400.0), MW(0.9), **(dict(period=P, presc=3) | st)) for st in steps for _ in range(n_each)]
    await tb.reset(sched[0])
    rtl, exp = await check_run(tb, sched[0], sched, len(sched))
    if tb.has("dtf"):
        assert sum(a != b for a, b in zip(exp.dt, exp.dtf)) > len(sched) // 2, "dt != dtf in too few periods"
        k = next(i for i, u in enumerate(sched) if u.dtf == 150)
        assert exp.period[k + 1] == 2 * (150 + 0), f"period {exp.period[k + 1]}: not raised for dtf 150"
        # a change of dtf alone (dt, mp, period unchanged) forces an update at its valley
        for i in range(1, len(sched)):
            a, b = sched[i - 1], sched[i]
            if (a.dt, a.mp, a.period) == (b.dt, b.mp, b.period) and a.dtf != b.dtf:
                assert exp.valley[i + 1] in {u.load for u in exp.updates}, f"no forced update at valley {i + 1}"
    else:
        assert exp.dtf == exp.dt, "a build without DTF: one dead time"
    sym = CoreModel(features=tb.features)
    sym.idle(fixed.ARM_CLOCKS + 2)
    ref = sym.run(replace(sched[0], dtf=None), [replace(u, dtf=None) for u in sched], len(sched))
    if not tb.has("dtf"):
        assert ref.gate_edges == exp.gate_edges, "no DTF: dtf changed the gates"
    else:
        assert ref.gate_edges != exp.gate_edges, "asymmetric dead times gave the symmetric gates"


@cocotb.test()
async def clamps_and_disable(dut):
    """m far beyond the hexagon and a period below the minimum are clamped and flagged; disabling mid-pulse turns
    every gate off on the next clock; the core restarts cleanly; a clamped period forces no update."""
    tb = CoreTB(dut)
    u = Inputs(FW(300.0), 0xFFFF, 20, 3)
    await tb.reset(u)
    rtl, exp = await check_run(tb, u, const(u), 30, stop=17)
    assert int(dut.sat_o.value) == 1 and int(dut.period_clamp_o.value) == 1
    assert all(p == tb.model.min_period for p in rtl.period)
    assert int(dut.gate_hi_o.value) == 0 and int(dut.gate_lo_o.value) == 0
    u2 = Inputs(FW(300.0), MW(0.5), 700, 30)
    tb.set_inputs(u2)
    await check_run(tb, u2, const(u2), 60)
    assert int(dut.sat_o.value) == 0 and int(dut.period_clamp_o.value) == 0
    # peak updates with the period clamped: the clamped period equals the active one, so no valley is a
    # forced update (a forced update compared with the port's value instead would update every valley)
    u3 = Inputs(FW(300.0), MW(0.5), 20, 3, upd=fixed.UPD_PEAK)
    await tb.reset(u3)
    rtl, exp = await tb.run(u3, const(u3), 12)
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp, table_i=False)              # peak updates: no one pattern per period


@cocotb.test()
async def reset_mid_run(dut):
    """rst_ni asserted between two clock edges while a pole is high: every pole and gate is off in that same
    time step (asynchronous reset, no clock needed), the in-RTL checker stays clean, and after the release
    the core runs exactly like after the first reset."""
    tb = CoreTB(dut)
    u = Inputs(freq=FW(400.0), m=MW(0.8), period=P_VERMA // 2, dt=24)
    await tb.reset(u)
    await check_run(tb, u, const(u), 6)
    for _ in range(2 * u.period):                        # a clock with a pole and a gate on
        await RisingEdge(dut.clk)
        await ReadOnly()
        if int(dut.pole_o.value) and int(dut.gate_hi_o.value):
            break
    assert int(dut.pole_o.value) and int(dut.gate_hi_o.value), "no pole / gate on within a carrier period"
    await Timer(3, "ns")                                 # between the rising and the falling edge
    dut.rst_ni.value = 0
    await ReadOnly()
    got = (int(dut.pole_o.value), int(dut.gate_hi_o.value), int(dut.gate_lo_o.value))
    assert got == (0, 0, 0), f"rst_ni low: pole_o, gate_hi_o, gate_lo_o = {got}, not all off at once"
    await FallingEdge(dut.clk)
    await tb.reset(u)
    await check_run(tb, u, const(u), 6)


@cocotb.test()
async def full_only_inputs(dut):
    """POLAR mode, DPWM1, double update, prescaler 1: a build follows those it has and ignores the others
    (SVPWM, an update at every valley; POLAR not built: the zero vector and cfg_err_o; the tiny core: FREQ
    mode); exact against the model in every build."""
    tb = CoreTB(dut)
    u = Inputs(freq=FW(400.0), m=MW(0.7), period=P_VERMA // 2, dt=24, mode=fixed.MODE_POLAR, theta=0x2345,
               dpwm=fixed.DPWM_60, upd=fixed.UPD_BOTH, presc=1)
    await tb.reset(u)
    rtl, exp = await tb.run(u, const(u), 40)
    tb.compare(rtl, exp)
    # Table I: single-update SVPWM only
    tb.check_edges(rtl, exp, table_i=not tb.has("upd") and not tb.has("dpwm"))
    peak_updates = sum(x.at_peak for x in exp.updates)
    if tb.has("upd"):
        assert peak_updates > 0, "UPD: peak updates"
    else:
        assert peak_updates == 0 and len(exp.updates) == 40, "no UPD: one update per valley, none at a peak"
    if tb.compact:
        assert len(set(rtl.sector[1:])) > 1, "tiny: the phase accumulator turns the vector (FREQ mode)"
    elif tb.has("polar"):
        assert len(set(rtl.sector[1:])) == 1 and not any(exp.err), "POLAR at a fixed angle"
    else:
        assert all(exp.err[1:]) and int(dut.cfg_err_o.value) == 1, "POLAR not built: cfg_err_o"
        assert all(len(set(c)) == 1 for c in rtl.cmp[1:]), "POLAR not built: the zero vector"


# the outputs that are 0 in reset (a valid configuration, en_i high): every status output and the gates
RESET_ZERO_OUTPUTS = ("running_o", "update_o", "sat_o", "cfg_err_o", "period_clamp_o", "freq_clamp_o", "fault_o",
                      "tripped_o", "locked_o", "gate_hi_o", "gate_lo_o")


@cocotb.test()
async def config_and_safety(dut):
    """The inputs the long tests leave at one value, each in a short exact check (the full core; the compact
    core ignores V/f and the prescaler and runs the same steps in FREQ mode):
    * in reset every status output and every gate is 0 (valid configuration, en_i high; and clocked with the
      frequency word, period and mode out of range), period_clamp_o stays 0 after the release;
    * the core runs exactly ARM_CLOCKS clocks after the reset release when en_i is already high; period_o
      is MinPeriod (the reset value of the registered clamped period) in the first clock, then period_i;
    * V/f at a reverse frequency (m from |f|) with updates at both points and prescaler 2, == model;
    * adc_trig_o == (valley_o & adc_trig_i[0]) | (peak_o & adc_trig_i[1]) on every clock, each code; carrier_o
      0 at the valleys, P at the peaks, steps of one;
    * period_i and dt_i changed between a valley's sample and the valley are taken only at the next valley;
    * fault_o is fault_i through the 2-flop synchroniser: high from the second clock edge after fault_i
      rises, low from the second edge after it falls;
    * a latched trip holds through valleys until fault_clear_i (then releases in the next clock); a
      cycle-by-cycle trip holds until the first valley after the fault and releases in the clock after it;
    * braking (safe_lo_i = 1): a fault turns the high sides off at once and the low sides on after the
      falling dead time, counted from the trip the dead-time FSMs see (the fault through the synchroniser),
      held until fault_clear_i, then the modulator again;
    * a reset pulse between two clock edges: every output 0 at once, then the clocks of a long reset
      (period_o, the start, period_clamp_o), with no clamp of the configuration before it left over;
    * the pin polarity is taken while en_i is low; lock_i freezes polarity and dead time: locked_o, the
      pins, and a run == model with the locked dead time while dt_i / pol_i on the ports differ."""
    tb = CoreTB(dut)
    P = 300
    vf = Inputs(freq=-FW(1000.0), m=MW(0.6), period=P, dt=7, mode=fixed.MODE_VF, vf_boost=MW(0.1),
                vf_slope=0x0100, vf_mmax=0x9000, upd=fixed.UPD_BOTH, presc=2)
    # ---- run from the reset release with en_i high: cycle 0 (valley_o) is the ARM_CLOCKS-th clock
    tb.set_inputs(vf)
    tb.set_safety()
    dut.en_i.value = 1
    dut.rst_ni.value = 0
    await clock_cycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    # in reset (valid configuration, en_i high): every status output and every gate is at its reset value 0
    status = {n: int(getattr(dut, n).value) for n in RESET_ZERO_OUTPUTS}
    assert not any(status.values()), f"outputs in reset: {status}"
    # and with inputs out of range in reset (the one frequency word beyond the default FreqMax, a period
    # below the minimum, an invalid mode), clocked: still 0 (the clamp flags are registers held in reset)
    tb.set_inputs(replace(vf, freq=-(1 << (len(dut.freq_i) - 1)), period=3, mode=7))
    await clock_cycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    status = {n: int(getattr(dut, n).value) for n in RESET_ZERO_OUTPUTS}
    assert not any(status.values()), f"outputs in reset, inputs out of range: {status}"
    tb.set_inputs(vf)
    await FallingEdge(dut.clk)
    dut.rst_ni.value = 1
    got0 = await tb.per_clock(fixed.ARM_CLOCKS + 2)
    got = [(k.valley, k.period) for k in got0]
    valleys = [v for v, _ in got]
    # the idle carrier loads the clamped period_i through a register whose reset value is MinPeriod
    assert [p for _, p in got] == [tb.model.min_period] + [P] * (len(got) - 1), \
        f"period_o after the reset release: {[p for _, p in got]}, expected MinPeriod, then period_i"
    assert valleys.index(1) == fixed.ARM_CLOCKS - 1, \
        f"valley_o after the reset release (en_i high) at clocks {valleys}: not the clock ARM_CLOCKS = " \
        f"{fixed.ARM_CLOCKS} after it"
    assert not any(k.pclamp for k in got0), f"period_clamp_o after the reset release: {[k.pclamp for k in got0]}"
    # ---- V/f, reverse frequency, double update, prescaler 2: exact
    await tb.reset(vf)
    rtl, exp = await tb.run(vf, const(vf), 12)
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp, table_i=not tb.has("upd"))
    fa = abs(vf.freq) >> (fixed.FREQ_WIDTH - 17)
    if tb.has("vf"):
        m_vf = fixed.vf_m(vf.freq, vf.vf_boost, vf.vf_slope, vf.vf_mmax)
        assert m_vf == vf.vf_boost + fa < vf.vf_mmax and {u.m for u in exp.updates} == {m_vf}, \
            "the V/f point is on the linear part of the law"
    gaps = {b.load - a.load for a, b in zip(exp.updates, exp.updates[1:])}
    # prescaler 2 at both points: every third half period; without UPD / PRESC every valley (2 P)
    want = (3 if tb.has("presc") else 1) * (1 if tb.has("upd") else 2) * P
    assert gaps == {want}, f"prescaler 2, both points: an update every {want} clocks, gaps {gaps}"
    # ---- ADC triggers (the core runs on with the last inputs)
    for code in (1, 2, 3):
        dut.adc_trig_i.value = code
        got = [(k.adc, k.valley, k.peak, k.carrier) for k in await tb.per_clock(2 * P + 4)]
        bad = [k for k, (a, v, pk, _) in enumerate(got) if a != ((v & code) | (pk & code >> 1))]
        assert not bad, f"adc_trig_i = {code}: adc_trig_o wrong at clocks {bad[:5]} of {got[bad[0]]}"
        assert sum(a for a, _, _, _ in got) == bin(code).count("1"), f"adc_trig_i = {code}: pulses in a period"
        # carrier_o: 0 at the valley, P at the peak, one step per clock in between
        assert all(c == (0 if v else P) for _, v, pk, c in got if v or pk), "carrier_o at the valley / peak"
        assert all(abs(a[3] - b[3]) == 1 for a, b in zip(got, got[1:])), "carrier_o does not step by one"
    dut.adc_trig_i.value = 0
    # ---- latched trip: holds through two valleys, released by fault_clear_i in the next clock
    await FallingEdge(dut.clk)
    dut.fault_i.value = 1
    await Timer(1, "ns")
    assert int(dut.tripped_o.value) == 1 and int(dut.gate_hi_o.value) == 0 and int(dut.gate_lo_o.value) == 0
    # fault_o: fault_i through the 2-flop synchroniser, high from the second clock edge on
    got = [(k.fault, k.tripped) for k in await tb.per_clock(5)]
    assert got == [(0, 1)] + [(1, 1)] * 4, f"fault_o, tripped_o in the 5 clocks after fault_i rose: {got}"
    await FallingEdge(dut.clk)
    dut.fault_i.value = 0
    got = [(k.tripped, k.valley, k.fault) for k in await tb.per_clock(4 * P + 8)]
    assert [f for _, _, f in got[:3]] == [1, 0, 0], f"fault_o after fault_i fell: {[f for _, _, f in got[:3]]}"
    assert sum(v for _, v, _ in got) >= 2 and all(t for t, _, _ in got), \
        f"latched trip released without fault_clear_i (clock {[t for t, _, _ in got].index(0)} after the fault)"
    await FallingEdge(dut.clk)
    dut.fault_clear_i.value = 1
    await FallingEdge(dut.clk)
    dut.fault_clear_i.value = 0
    assert int(dut.tripped_o.value) == 0, "fault_clear_i: the latched trip is not released in the next clock"
    # ---- cycle-by-cycle trip: released in the clock after the first valley after the fault
    dut.trip_cbc_i.value = 1
    await clock_cycles(dut.clk, 2)
    await FallingEdge(dut.clk)
    dut.fault_i.value = 1
    await clock_cycles(dut.clk, 3)
    await FallingEdge(dut.clk)
    dut.fault_i.value = 0
    got = [(k.tripped, k.valley) for k in await tb.per_clock(2 * P + 8)]
    v = [k for k, (_, vl) in enumerate(got) if vl and k >= 2][0]      # fault synchronised low from clock 2 on
    assert all(t for t, _ in got[:v + 1]) and got[v + 1][0] == 0, \
        f"cycle-by-cycle trip: tripped_o {[t for t, _ in got[max(0, v - 2):v + 3]]} around the valley at clock {v}"
    tb.check_harness()
    assert int(dut.trip_violations_o.value) == 0, "in-RTL checker: a gate on while tripped"
    # ---- braking (safe_lo_i = 1), latched: a fault at a peak (all three high sides on) turns the high sides
    # off at once; the dead-time FSMs see the trip two edges later (trip_sync: the synchronised fault) and
    # turn every low side on after the falling dead time (the compact core: its one dead time), counted
    # from the clock after it (the high sides' turn-off there): low sides on from the (3 + dtf)-th edge
    # after the fault, held through valleys until fault_clear_i, and back to the modulator after it
    brk = Inputs(freq=FW(500.0), m=MW(0.3), period=P, dt=7, dtf=12)
    dtf = brk.dtf if tb.has("dtf") else brk.dt
    await tb.reset(brk)
    tb.set_safety(safe_lo=1)
    rtl, exp = await tb.run(brk, const(brk), 2)
    tb.compare(rtl, exp)
    await RisingEdge(dut.peak_o)
    await FallingEdge(dut.clk)
    assert (int(dut.gate_hi_o.value), int(dut.gate_lo_o.value)) == (7, 0), "m = 0.3: not V7 at the peak"
    dut.fault_i.value = 1
    await Timer(1, "ns")
    assert (int(dut.gate_hi_o.value), int(dut.gate_lo_o.value)) == (0, 0), "braking: high sides not off at once"
    got = [(k.hi, k.lo, k.tripped) for k in await tb.per_clock(2 * P + 8)]      # row k: edge k + 1 after it
    await FallingEdge(dut.clk)
    dut.fault_i.value = 0
    exp_brk = [(0, 0, 1)] * (2 + dtf) + [(0, 7, 1)] * (2 * P + 6 - dtf)
    assert got == exp_brk, \
        "braking: (gate_hi_o, gate_lo_o, tripped_o) per clock after the fault " + \
        f"{[(k, g) for k, g in enumerate(got) if g != exp_brk[k]][:4]}: low sides expected on from clock {2 + dtf}"
    await clock_cycles(dut.clk, 4)
    assert (int(dut.gate_hi_o.value), int(dut.gate_lo_o.value)) == (0, 7), "braking: released without fault_clear_i"
    await FallingEdge(dut.clk)
    dut.fault_clear_i.value = 1
    await FallingEdge(dut.clk)
    dut.fault_clear_i.value = 0
    got = [(k.hi, k.lo, k.tripped) for k in await tb.per_clock(2 * P)]
    assert all(not t for _, _, t in got) and any(h == 7 for h, _, _ in got), \
        "braking: fault_clear_i did not return the gates to the modulator (no V7 in the period after it)"
    tb.check_harness()
    assert int(dut.trip_violations_o.value) == 0, "in-RTL checker: a high side on while tripped"
    # ---- a reset pulse shorter than a clock (no clock edge while rst_ni is low) in a run whose period the
    # clamp raised (2 (dt + mp) > period_i): every output is 0 at once, and the clocks after the release are
    # those of a long reset: period_o MinPeriod then period_i (no clamp of the old configuration leaks into
    # the first period), the start ARM_CLOCKS clocks after the release, period_clamp_o 0 throughout
    big = Inputs(freq=FW(500.0), m=MW(0.3), period=P, dt=100, mp=60)
    await tb.reset(big)
    rtl, exp = await tb.run(big, const(big), 2)
    tb.compare(rtl, exp)
    assert exp.period[0] == 2 * (big.dt + big.mp) > P, f"the clamp: period {exp.period}"
    await FallingEdge(dut.clk)
    tb.set_inputs(brk)
    dut.rst_ni.value = 0
    await Timer(2, "ns")
    status = {n: int(getattr(dut, n).value) for n in RESET_ZERO_OUTPUTS}
    assert not any(status.values()), f"outputs 2 ns into a reset pulse without a clock edge: {status}"
    dut.rst_ni.value = 1
    got = await tb.per_clock(fixed.ARM_CLOCKS + 2)
    assert [k.period for k in got] == [tb.model.min_period] + [P] * (len(got) - 1), \
        f"period_o after a short reset: {[k.period for k in got]}, expected MinPeriod, then period_i"
    assert [k.valley for k in got].index(1) == fixed.ARM_CLOCKS - 1 and not any(k.pclamp for k in got), \
        f"valley_o / period_clamp_o after a short reset: {[(k.valley, k.pclamp) for k in got]}"
    # ---- period_i / dt_i changed after a valley's sample: taken at the next sample, i.e. the valley after
    # (as if changed at that valley: the model's inputs(6)); the RTL gets them about 40 clocks before valley 6
    u1, u2 = Inputs(freq=FW(500.0), m=MW(0.7), period=P, dt=7), Inputs(freq=FW(500.0), m=MW(0.7), period=P + 40, dt=11)
    await tb.reset(u1)

    async def early():
        for _ in range(6):                                   # valleys 1 .. 5 (valley 0 is the start)
            await RisingEdge(dut.valley_o)
        await RisingEdge(dut.peak_o)                         # peak of period 5, then down to count ~40
        await Timer((P - 40) * 10, "ns")
        await FallingEdge(dut.clk)
        assert 0 < int(dut.carrier_o.value) < fixed.SAMPLE_LEAD and not int(dut.carrier_up_o.value)
        dut.period_i.value, dut.dt_i.value = u2.period, u2.dt

    task = cocotb.start_soon(early())
    rtl, exp = await tb.run(u1, lambda n: u1 if n < 6 else u2, 10)
    assert task.done()
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp)
    assert exp.period[6:8] == [P, P + 40], "the change is taken at valley 7"
    # ---- polarity (taken while en_i is low) and lock
    base = Inputs(freq=FW(500.0), m=MW(0.7), period=P, dt=9, mp=3)
    await tb.reset(base)
    tb.set_safety(pol=3)
    await clock_cycles(dut.clk, 2)
    pins = (int(dut.gate_hi_pin.value), int(dut.gate_lo_pin.value))
    assert pins == (7, 7), f"pol_i = 3 while idle: pins {pins}, expected all off = active-low high (7, 7)"
    tb.set_safety(pol=3, lock=1)
    await clock_cycles(dut.clk, 1)
    tb.set_safety(pol=0, safe_lo=1, cbc=1)                     # locked: ignored until reset
    tb.port_inputs = lambda u: replace(u, dt=u.dt + 20, mp=1)
    tb.set_inputs(base)
    await clock_cycles(dut.clk, 3)
    pins = (int(dut.gate_hi_pin.value), int(dut.gate_lo_pin.value))
    assert int(dut.locked_o.value) == 1 and pins == (7, 7), f"locked_o {int(dut.locked_o.value)}, pins {pins}"
    rtl, exp = await tb.run(base, const(base), 6)
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp)
    assert int(dut.lock_violations_o.value) == 0, "in-RTL checker: a locked configuration register changed"


@cocotb.test()
async def narrow_freq_word(dut):
    """FreqWidth = 16, PhaseWidth = 26 (the freq16 build only): the same core as the 24 / 34 one driven
    with the frequency word shifted left by 8, so the model runs freq << 8 (exact: the accumulator holds
    the 34-bit one's upper 26 bits). V/f with a steep slope (one fabs_i LSB = ~256 m LSBs, so the
    FreqWidth < 17 branch of fabs_i, |f| shifted left, shows in the compare values) from +f through zero
    to -f, then FREQ mode turning the vector through every sector; == model."""
    assert len(dut.freq_i) == 16, "narrow_freq_word runs on the FreqWidth = 16 build only"
    tb = CoreTB(dut)
    tb.port_inputs = lambda u: replace(u, freq=u.freq >> 8)          # the port gets the 16-bit word
    vf = dict(period=400, dt=5, mode=fixed.MODE_VF, vf_boost=0x0400, vf_slope=0xFFFF, vf_mmax=0xFFFF)
    n_vf, n_fr = 24, 30
    f16 = lambda k: round(60 * (1 - 2 * k / (n_vf - 1)))             # noqa: E731  +60 .. -60, through 0
    sched = [Inputs(freq=f16(k) << 8, **vf) for k in range(n_vf)]
    sched += [Inputs(freq=20000 << 8, m=MW(0.8), period=400, dt=5)] * n_fr
    await tb.reset(sched[0])
    rtl, exp = await check_run(tb, sched[0], sched, len(sched))
    ms = {u.m for u in exp.updates[:n_vf]}
    assert len(ms) > 10, f"V/f: m took only {len(ms)} values"
    assert sorted(set(rtl.sector[n_vf:])) == [0, 1, 2, 3, 4, 5], "FREQ mode: not every sector"


@cocotb.test()
async def dtc_sign_changes(dut):
    """Dead-time compensation with the current signs changing at every point of a period: double update
    (valley and peak samples), isign_i changed on random clocks of every half period and on the clocks
    around each sample point (two before, one before = the sampled clock, the sample clock itself), dtc_en_i
    switched off and on again, rising dead time 24 and falling 36 (hdr 12, hdf 18) with a minimum pulse, m from
    0.05 to 1.0 so that the
    compensated values leave [0, P] and the minimum-pulse rule snaps them; == model (which takes isign as
    sampled in the clock before each sample point). The compact core has no compensation: its model ignores
    dtc and isign, and so must the RTL."""
    tb = CoreTB(dut)
    rng = random.Random(1126)
    P, lead = 600, tb.model.lead
    n = 48 if ICARUS else 160
    ms = [MW(0.05), MW(0.5), MW(0.98), MW(1.0)]
    base = lambda k, sgn: Inputs(freq=FW(700.0), m=ms[(k // 12) % 4], period=P, dt=24, dtf=36, mp=3,   # noqa: E731
                                 upd=fixed.UPD_BOTH, dtc=int(k % 40 < 32), isign=sgn)
    t = lambda k: fixed.START_DELAY + 2 * P * k                      # noqa: E731  (the period is constant)
    s_peak = lambda k: t(k) + P - lead                               # noqa: E731  sample points (S)
    s_valley = lambda k: t(k + 1) - lead                             # noqa: E731
    busy = {t(k) for k in range(n + 1)} | {t(k) + P for k in range(n + 1)}   # tb.run's input cycles
    changes = {}
    for k in range(n):
        for s in (s_peak(k), s_valley(k)):
            for off in (-2, -1, 0):
                if rng.random() < 0.6:
                    changes[s + off] = rng.randint(0, 7)
        for _ in range(2):
            changes[rng.randint(t(k), t(k + 1) - 1)] = rng.randint(0, 7)
    first = s_peak(0) - 1                                            # isign fixed up to the first sample
    cyc = sorted(c for c in changes if c > first and c not in busy)
    val0 = 5

    def val_at(c: int) -> int:                                       # isign_i during cycle c
        v = val0
        for x in cyc:
            if x > c:
                break
            v = changes[x]
        return v

    sched = [base(k, val_at(s_valley(k) - 1)) for k in range(n)]        # sampled before valley k + 1
    peaks = [base(k, val_at(s_peak(k) - 1)) for k in range(n)]          # sampled before peak k
    peaks[0] = base(0, val0)                                         # (the idle inputs: up to peak 0)
    cur = {"v": val0}
    tb.port_inputs = lambda u: replace(u, isign=cur["v"])            # isign_i: the schedule's, not the sample's

    async def drive():
        while tb.t0 == float("inf"):                                 # tb.run sets t0 as en_i rises
            await RisingEdge(dut.clk)
        for c in cyc:                                                # the falling edge in cycle c
            await Timer(tb.t0 + c * CLK_NS + CLK_NS // 2 - get_sim_time("ns"), "ns")
            cur["v"] = changes[c]
            dut.isign_i.value = cur["v"]

    await tb.reset(peaks[0])
    tb.t0 = float("inf")
    task = cocotb.start_soon(drive())
    rtl, exp = await tb.run(peaks[0], sched, n, peak_inputs=peaks)
    task.cancel()
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp, table_i=False)                          # (double update: no single pattern)
    if tb.has("dtc"):
        comp = [x for x in exp.updates if x.cmp != fixed.modulate(
            fixed.MODE_FREQ, x.theta >> fixed.PHASE_WIDTH,
            (x.theta & ((1 << fixed.PHASE_WIDTH) - 1)) >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS), x.period,
            m=x.m)[1]]
        assert len(comp) > n // 2, "the compensation changed too few updates"
    tb.dut._log.info("%d isign changes, %d updates, %d edges", len(cyc), len(exp.updates), len(rtl.gate_edges))


@cocotb.test()
async def volt_second_carry(dut):
    """The minimum-pulse rule's volt-second carry (vsc_en_i): pulses dropped and widened near duty 0 and 1 --
    m near 1 in SVPWM and m near 0 with DPWMMIN / DPWMMAX (two phases a few counts from a rail), dead time 24 +
    minimum pulse 6 (thr 30) -- a period change (no carry across it), the carry switched off and on, and a stop
    holding a carry, then a restart at the same period (no carry into it); == model on every edge; the model's carries chain from update to update (model/tests/test_carry.py: the average
    follows the command)."""
    tb = CoreTB(dut)
    n = 60 if ICARUS else 200
    P = 400

    def u(k):
        m, dp = ((MW(0.99), fixed.DPWM_OFF), (MW(0.02), fixed.DPWM_MIN), (MW(0.01), fixed.DPWM_MAX),
                 (MW(1.0), fixed.DPWM_OFF))[(k * 4) // n]
        per = P + 20 if (k * 8) // n == 5 else P                   # a period change and back
        return Inputs(freq=FW(900.0), m=m, period=per, dt=24, mp=6, dpwm=dp, vsc=int((k + 5) % 50 < 45))
    sched = [u(k) for k in range(n)]
    await tb.reset(sched[0])
    rtl, exp = await tb.run(sched[0], sched, n, stop=P // 2)       # stopped with a carry held ...
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp, P // 2, table_i=False)   # (the carry may reorder two phases within thr of each other)
    u2 = sched[-1]                                   # ... and restarted at the same period: no carry into it
    tb.set_inputs(u2)
    rtl2, exp2 = await tb.run(u2, const(u2), 12)
    tb.compare(rtl2, exp2)
    tb.check_edges(rtl2, exp2, table_i=False)
    if not tb.has("carry"):
        return
    assert any(exp.updates[-1].carry) and exp2.updates[0].period == exp.updates[-1].period, \
        "the stop held no carry to clear"
    assert not any(exp2.updates[0].carry_in) and any(x.carry_in for x in exp2.updates)
    carried = [x for x in exp.updates if any(x.carry_in)]
    assert len(carried) > n // 4, f"only {len(carried)} updates with a carry"
    for a, b, ub in zip(exp.updates, exp.updates[1:], sched[1:]):      # the carry chains, and stops where due
        want = a.carry if (b.period == a.period) else (0, 0, 0)
        assert b.carry_in == want or not any(b.carry_in) and not ub.vsc, (a, b)
    tb.dut._log.info("%d updates with a carry in of %d", len(carried), len(exp.updates))


@cocotb.test()
async def carry_cleared_by_trip(dut):
    """A trip clears the volt-second carry (the core's carry register, recorded per clock): with a carry held
    between two updates (m = 0.99, thr 30), a cycle-by-cycle trip clears it from the third edge after fault_i
    rises (the dead-time FSMs' trip, two edges after it, then the register), it stays 0 until the release
    (the first valley with the fault low), and a carry comes back after it. The compact core has no carry:
    its register stays 0."""
    tb = CoreTB(dut)
    P = 400
    u = Inputs(freq=FW(900.0), m=MW(0.99), period=P, dt=24, mp=6, vsc=1)
    await tb.reset(u)
    tb.set_safety(cbc=1)
    rtl, exp = await tb.run(u, const(u), 6)
    tb.compare(rtl, exp)
    got = []
    for _ in range(12):                                  # an update whose carry is not 0 (or none: compact)
        got = await tb.per_clock(P)
        if got[-1].carry:
            break
    if not tb.has("carry"):
        assert not any(k.carry for k in got), "a build without CARRY: a carry"
        return
    held = got[-1].carry
    assert held, "no update with a carry in 12 half periods"
    await FallingEdge(dut.clk)
    dut.fault_i.value = 1
    got = await tb.per_clock(3)
    await FallingEdge(dut.clk)
    dut.fault_i.value = 0
    assert [k.carry for k in got] == [held, held, 0], \
        f"carry in the 3 clocks after fault_i rose: {[hex(k.carry) for k in got]}, expected {hex(held)} twice, then 0"
    got = await tb.per_clock(6 * P)
    rel = [k.tripped for k in got].index(0)              # released after the first valley with the fault low
    assert all(k.carry == 0 for k in got[:rel]), f"carry while tripped: {sorted({hex(k.carry) for k in got[:rel]})}"
    assert any(k.carry for k in got[rel:]), "no carry after the release"
    assert int(dut.trip_violations_o.value) == 0

# ---- pytest items: one per cocotb test and build, so that both pytest-xdist workers stay busy; each build is
# made once per simulator and shared by its items (svpwm_tb.run_core_sim, CORE_BUILDS). A test runs on the
# builds that have what it drives (svpwm_tb.core_items): the operating points are FREQ-mode ones (full, vf and
# tiny, the compact core); full_only_inputs runs on every build (what a build lacks is ignored).
NARROW = "narrow_freq_word"                 # the freq16 build's own test
# The vf build's FREQ operating points (the same datapath as the full core's, at a shorter lead) are long
# runs: Verilator only (make test's time); on Icarus the vf build runs the tests of what it has and lacks
# (dead times, compensation, carry, V/f, ignored inputs, reset, clamps).
NEEDS = {c: (() if c == "full_only_inputs" else ("freq",)) for c in cocotb_tests(__file__) if c != NARROW}
VF_VERILATOR_ONLY = ("minas_fig9_5hz", "minas_fig10_50hz", "modulation_sweep", "reversal_through_zero",
                     "reverse_and_zero_frequency", "period_and_dead_time_change", "dead_time_change_at_valley")
assert set(VF_VERILATOR_ONLY) <= set(NEEDS)
# The compact (tiny) build on Icarus: its own serial datapath over both Minas points, the safety, reset,
# dead-time compensation / carry (ignored there), clamps and ignored-input tests; the sweeps and steps of
# the core around it (the same carrier, dead-time and update RTL as the full build's, which Icarus runs)
# run on Verilator
COMPACT_VERILATOR_ONLY = ("modulation_sweep", "dead_time_change_at_valley", "reverse_and_zero_frequency",
                          "period_and_dead_time_change", "reversal_through_zero", "asymmetric_dead_time")
assert set(COMPACT_VERILATOR_ONLY) <= set(NEEDS)
ITEMS = [(s, b, c) for s in sims_to_run() for b, c in core_items(NEEDS, ("default", "compact", "vf", "foc", "minimal"))
         if not (s == "icarus" and b == "vf" and c in VF_VERILATOR_ONLY)
         and not (s == "icarus" and b == "compact" and c in COMPACT_VERILATOR_ONLY)]


@pytest.mark.parametrize("simulator,build,case", ITEMS, ids=[f"{s}-{b}-{c}" for s, b, c in ITEMS])
def test_svpwm_core(simulator, build, case):
    run_core_sim(simulator, "test_svpwm_core", Path(__file__).parent, build, case)


def test_svpwm_core_freq16(sim):
    # FreqWidth = 16 / PhaseWidth = 26: the frequency-word width branch no other build has (narrow_freq_word)
    run_core_sim(sim, "test_svpwm_core", Path(__file__).parent, "freq16", NARROW)
