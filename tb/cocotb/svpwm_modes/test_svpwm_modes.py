# SPDX-License-Identifier: Apache-2.0
"""svpwm_core input modes, overmodulation, zero-vector placement and update timing against the golden model.

Every run is bit-exact (==) with svpwm_model.core over every pole and gate edge, the compare values at
every valley and peak, the sectors, sat_o and the cycle of every update_o pulse; the in-RTL pin checker
and the edge-list leg check run on each. Cases (each over at least one revolution of the vector):
  V/f law through a reversal (boost at zero frequency, m_max beyond the hexagon); polar angle (an
  encoder-like angle with steps); alpha-beta and dq + theta rotating vectors; an overmodulation sweep
  to m = 1.99 (beyond six-step) in polar and alpha-beta; DPWMMIN/MAX/DPWM1; update at the peak, at
  both (double update, different references in the two halves), prescaler, changes of update mode
  while running and the invalid codes (cfg_err_o). Verilator runs P = 1536 (15.6 kHz at 48 MHz), Icarus
  P = MinPeriod + 21 (240) with the same number of carrier periods per revolution scaled down.
"""
from __future__ import annotations

import math
import os
from pathlib import Path

import cocotb
import pytest

from simrun import cocotb_tests, sims_to_run
from svpwm_model import config, fixed
from svpwm_model.core import Inputs
from svpwm_tb import CoreTB, core_items, run_core_sim

ICARUS = os.environ.get("SVPWM_SIM_NAME", "") == "icarus"
P = fixed.MIN_PERIOD + 21 if ICARUS else 1536   # half period (Icarus: just above the core's MinPeriod)
K = 96 if ICARUS else 192                  # carrier periods per revolution (>= 64 at P = 96: |freq| < 2^23)
DT = 3 if ICARUS else 48                   # dead time (1 us at 48 MHz for P = 1536)
F_REV = (6 << fixed.PHASE_WIDTH) // (2 * P * K)          # frequency word: one revolution in K periods
assert F_REV <= fixed.FREQ_MAX, "one revolution in K periods needs a frequency word beyond the port range"
MW = fixed.m_word
V_ONE = fixed.V_ONE


def base(**kw) -> Inputs:
    return Inputs(**{**dict(freq=F_REV, m=MW(0.8), period=P, dt=DT), **kw})


def theta16(n: int, turns: float = 1.0) -> int:
    return int(round(65536 * turns * n / K)) & 0xFFFF


def vq(x: float) -> int:
    """A voltage component as Q2.14."""
    return max(-32768, min(32767, int(round(x * V_ONE))))


async def check(tb: CoreTB, idle: Inputs, inputs, n: int, *, peak_inputs=None, table_i: bool = True,
                stop=None):
    rtl, exp = await tb.run(idle, inputs, n, stop, peak_inputs)
    tb.compare(rtl, exp)
    tb.check_edges(rtl, exp, stop, table_i=table_i)
    assert exp.updates, "no update"
    tb.dut._log.info("%d periods, %d updates, %d gate edges, sat in %d", n, len(exp.updates),
                     len(rtl.gate_edges), sum(u.sat for u in exp.updates))
    return rtl, exp


@cocotb.test()
async def vf_law_reversal(dut):
    """V/f (AVR495): m = min(m_max, boost + slope |f|); the frequency ramps +f -> -f through zero: at zero
    the vector stands at m = boost, the angle never jumps; at the ends m_max (beyond 1.0) clamps."""
    tb = CoreTB(dut)
    n = 3 * K
    f_hi = min(3 * F_REV, fixed.FREQ_MAX)
    fa_hi = abs(f_hi) >> (fixed.FREQ_WIDTH - 17)
    boost, mmax = MW(0.05), 0x9000                     # m_max 1.125: the hexagon clamps near the vertices
    slope = max(1, int((1.2 * fixed.M_ONE - boost) * 256 / max(fa_hi, 1)))
    vf = dict(mode=fixed.MODE_VF, vf_boost=boost, vf_slope=slope, vf_mmax=mmax)
    f_of = lambda k: int(round(f_hi * (1 - 2 * k / (n - 1))))
    idle = base(freq=f_hi, **vf)
    await tb.reset(idle)
    rtl, exp = await check(tb, idle, lambda k: idle if k == 0 else base(freq=f_of(k), **vf), n)
    ms = [u.m for u in exp.updates]
    assert boost <= min(ms) < MW(0.1), "the ramp passes near zero frequency: m near the boost"
    assert max(ms) == mmax and any(u.sat for u in exp.updates)
    for u in exp.updates:          # the law, from the frequency word each update used
        assert u.m == fixed.vf_m(fixed.clamp_freq(f_of_sample(exp, u, f_hi, f_of))[0], boost, slope, mmax)


def f_of_sample(exp, u, f0, f_of):
    """The frequency word an update sampled: idle before valley 1's sample, then inputs(n) for period n."""
    k = next(i for i, t in enumerate(exp.valley) if t > u.sample) - 1     # the period of the sample
    return f0 if k == 0 else f_of(k)


@cocotb.test()
async def polar_angle(dut):
    """Polar mode: an external angle (encoder-like: advancing, with a jump back) and a magnitude."""
    tb = CoreTB(dut)
    n = K + 10
    th = lambda k: theta16(k) if k < K // 2 else (theta16(k) - 3000) & 0xFFFF
    mk = lambda k: MW(0.3 + 0.6 * k / n)
    sched = lambda k: base(mode=fixed.MODE_POLAR, theta=th(k), m=mk(k), freq=0)
    idle = sched(0)
    await tb.reset(idle)
    await check(tb, idle, sched, n)


@cocotb.test()
async def alphabeta_rotating(dut):
    """alpha-beta mode: a rotating stator-frame vector of magnitude 0.95, one revolution, reversed half."""
    tb = CoreTB(dut)
    n = K + 4

    def sched(k):
        a = 2 * math.pi * k / K * (1 if k < n // 2 else -1)
        return base(mode=fixed.MODE_AB, v1=vq(0.95 * math.cos(a)), v2=vq(0.95 * math.sin(a)), freq=0)
    idle = sched(0)
    await tb.reset(idle)
    await check(tb, idle, sched, n)


@cocotb.test()
async def dq_rotating(dut):
    """dq + theta mode: v_d = 0.6, v_q = -0.55 (|v| = 0.81) in a frame turning one revolution."""
    tb = CoreTB(dut)
    n = K + 4
    sched = lambda k: base(mode=fixed.MODE_DQ, v1=vq(0.6), v2=vq(-0.55), theta=theta16(k), freq=0)
    idle = sched(0)
    await tb.reset(idle)
    await check(tb, idle, sched, n)


@cocotb.test()
async def overmodulation_sweep(dut):
    """m from 0.9 to 1.99 (six-step is 1.10) in polar, then |v| from 0.9 to 1.99 in alpha-beta (a build
    without AB: polar again, a second revolution): the vector is clamped to the hexagon keeping its angle
    (sat_o), T0 never negative."""
    tb = CoreTB(dut)
    n = 2 * K

    def sched(k):
        if k < K or not tb.has("ab"):
            k %= K
            return base(mode=fixed.MODE_POLAR, theta=theta16(k), m=min(0xFFFF, MW(0.9) + k * 0x8000 // K), freq=0)
        a, mag = 2 * math.pi * k / K, 0.9 + 1.09 * (k - K) / K
        return base(mode=fixed.MODE_AB, v1=vq(mag * math.cos(a)), v2=vq(mag * math.sin(a)), freq=0)
    idle = sched(0)
    await tb.reset(idle)
    rtl, exp = await check(tb, idle, sched, n)
    sats = [u.sat for u in exp.updates]
    assert any(sats) and not all(sats)
    for u in exp.updates:
        assert all(0 <= c <= u.period for c in u.cmp)


@cocotb.test()
async def overmodulation_six_step(dut):
    """The six-step law (om_i = 1): m from just below the vertex magnitude 0x93CD to 0xFFFF in FREQ mode (the
    vector turning), then POLAR and V/f (m from the law, up to vf_mmax = 0xFFFF) and AB (where the law does not
    apply: the angle-keeping clamp); == model. The vector holds at the vertices more and more: the number of
    compare-value sets with every phase at 0 or P (a vertex) grows with m, every update at m = 0xFFFF
    (six-step); a run with om_i = 0 at m = 0xFFFF keeps the clamp (a vertex only at its own angle)."""
    tb = CoreTB(dut)
    steps = (fixed.M_VERTEX - 1, fixed.M_VERTEX + 64, 0xA000, 0xC000, 0xFFFF)
    at_vertex = []
    for m in steps:
        u = base(m=m, om=1)
        await tb.reset(u)
        rtl, exp = await check(tb, u, lambda k: u, K + 2)
        at_vertex.append(sum(1 for x in exp.updates if sum(c in (0, x.period) for c in x.cmp) == 3))
    tb.dut._log.info("updates at a vertex per m step: %s of %d", at_vertex, K + 2)
    # (below the vertex magnitude only the samples at a sector's own vertex angle sit at a vertex)
    assert at_vertex[0] <= K // 16 < at_vertex[1] and at_vertex == sorted(at_vertex), at_vertex
    assert at_vertex[-1] == K + 2, f"m = 0xFFFF: six-step, every update at a vertex ({at_vertex})"
    u = base(m=0xFFFF, om=0)
    await tb.reset(u)
    rtl, exp = await check(tb, u, lambda k: u, K // 4)
    n_v = sum(1 for x in exp.updates if sum(c in (0, x.period) for c in x.cmp) == 3)
    assert 8 * n_v <= len(exp.updates), f"om = 0: the clamp, {n_v} of {len(exp.updates)} updates at a vertex"

    def sched(k):
        m = fixed.M_VERTEX + k * (0x10000 - fixed.M_VERTEX) // K if k < K else 0xFFFF
        if k < K // 2:
            return base(mode=fixed.MODE_POLAR, theta=theta16(3 * k), m=min(m, 0xFFFF), om=1, freq=0)
        if k < K:
            return base(mode=fixed.MODE_VF, vf_boost=min(m, 0xFFFF), vf_slope=0, vf_mmax=0xFFFF, om=1)
        a = 2 * math.pi * k / K
        return base(mode=fixed.MODE_AB, v1=vq(1.9 * math.cos(a)), v2=vq(1.9 * math.sin(a)), om=1, freq=0)
    idle = sched(0)
    await tb.reset(idle)
    await check(tb, idle, sched, K + K // 4)


@cocotb.test()
async def dpwm_modes(dut):
    """DPWMMIN, DPWMMAX and DPWM1 (60 deg bus clamping), one revolution each at m = 0.85."""
    tb = CoreTB(dut)
    for dp in (fixed.DPWM_MIN, fixed.DPWM_MAX, fixed.DPWM_60):
        u = base(m=MW(0.85), dpwm=dp)
        await tb.reset(u)
        rtl, exp = await check(tb, u, lambda k: u, K + 2, table_i=False)
        clamped = sum(1 for u_ in exp.updates if any(c in (0, u_.period) for c in u_.cmp))
        assert clamped == len(exp.updates), "every period has a clamped leg"


@cocotb.test()
async def update_modes(dut):
    """Update at the peak; at both (different references in the two halves of each period); prescaler 3;
    update mode, prescaler and the invalid code 3 changed while running."""
    tb = CoreTB(dut)
    n = K // 2
    u = base(upd=fixed.UPD_PEAK)
    await tb.reset(u)
    await check(tb, u, lambda k: u, n, table_i=False)
    # double update: the up half carries m 0.5 / freq +F, the down half m 0.9 / freq -F/2
    up = base(upd=fixed.UPD_BOTH, m=MW(0.5))
    dn = base(upd=fixed.UPD_BOTH, m=MW(0.9), freq=-F_REV // 2)
    await tb.reset(up)
    rtl, exp = await check(tb, up, lambda k: dn, n, peak_inputs=lambda k: up, table_i=False)
    assert len(exp.updates) >= 2 * (n - 1)
    # latency (update_o cycles == model loads, checked above): every update SampleLead clocks after its
    # sample, one every half period, so a reference waits at most P clocks for a sample: <= P + SampleLead - 1
    assert all(u.load - u.sample == tb.model.lead for u in exp.updates)
    assert {b.load - a.load for a, b in zip(exp.updates, exp.updates[1:])} == {P}
    assert {u.at_peak for u in exp.updates} == {True, False}
    tb.dut._log.info("double update: reference -> update_o <= P + %d = %d clocks, + 1 to the poles",
                     tb.model.lead, P + tb.model.lead)
    # prescaler: new values every 4th valley; a period change forces an update
    u = base(presc=3)
    sched = lambda k: u if k < n // 2 else base(presc=3, period=P + 8)
    await tb.reset(u)
    rtl, exp = await check(tb, u, sched, n)
    gaps = {b.load - a.load for a, b in zip(exp.updates, exp.updates[1:])}
    assert 8 * P in gaps
    # changing mode / prescaler while running, and the invalid code 3 (= valley + cfg_err_o)
    modes = [fixed.UPD_VALLEY, fixed.UPD_BOTH, fixed.UPD_PEAK, 3, fixed.UPD_BOTH]
    sched = lambda k: base(upd=modes[(k // 6) % len(modes)], presc=(k // 10) % 3, m=MW(0.4 + 0.02 * (k % 20)))
    idle = sched(0)
    await tb.reset(idle)
    await check(tb, idle, sched, 30, table_i=False)
    u = base(upd=3)
    await tb.reset(u)
    await check(tb, u, lambda k: u, 4)
    assert int(dut.cfg_err_o.value) == 1


@cocotb.test()
async def invalid_mode(dut):
    """Mode codes 5..7 and those of the modes the build lacks: the zero vector (all phases 50 %) and
    cfg_err_o; a valid mode clears it."""
    tb = CoreTB(dut)
    lacking = [m for m in range(5) if not config.mode_built(tb.features, m)]
    for bad in [5, 6, 7] + lacking:
        u = base(mode=bad)
        await tb.reset(u)
        rtl, exp = await check(tb, u, lambda k: u, 4)
        assert all(u_.err for u_ in exp.updates) and int(dut.cfg_err_o.value) == 1
        assert len(set(rtl.cmp[0])) == 1, "zero vector: three equal compare values"
    # a valid mode: FREQ, else POLAR (the builds without FREQ)
    u = base() if tb.has("freq") else base(mode=fixed.MODE_POLAR, theta=0x1234, freq=0)
    await tb.reset(u)
    await check(tb, u, lambda k: u, 4)
    assert int(dut.cfg_err_o.value) == 0


# one pytest item per cocotb test and build that has what it drives (svpwm_tb.core_items); the builds are
# shared with tb/cocotb/svpwm_core
NEEDS = {"vf_law_reversal": ("vf",), "polar_angle": ("polar",), "alphabeta_rotating": ("ab",),
         "dq_rotating": ("dq",), "overmodulation_sweep": ("polar",),
         "overmodulation_six_step": ("polar", "vf", "ab", "sixstep"), "dpwm_modes": ("freq", "dpwm"),
         "update_modes": ("freq", "upd", "presc"), "invalid_mode": ()}
assert set(NEEDS) == set(cocotb_tests(__file__)), "every test states what it needs"
# Icarus runs every test on the full build; on the foc, vf and minimal builds (the same RTL with fewer
# program steps) invalid_mode (the modes each lacks) and one test of its own input modes; their other items
# run on Verilator
ICARUS_BUILD_CASES = {"foc": ("invalid_mode", "dq_rotating"), "vf": ("invalid_mode", "vf_law_reversal"),
                      "minimal": ("invalid_mode", "polar_angle")}
ITEMS = [(m, b, c) for m in sims_to_run() for b, c in core_items(NEEDS, ("default", "foc", "vf", "minimal"))
         if m != "icarus" or b == "default" or c in ICARUS_BUILD_CASES[b]]


@pytest.mark.parametrize("simulator,build,case", ITEMS, ids=[f"{m}-{b}-{c}" for m, b, c in ITEMS])
def test_svpwm_modes(simulator, build, case):
    run_core_sim(simulator, "test_svpwm_modes", Path(__file__).parent, build, case,
                 extra_env={"SVPWM_SIM_NAME": simulator})
