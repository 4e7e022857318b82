# SPDX-License-Identifier: Apache-2.0
"""Feature adc (issue 30 items 1, 2): the ADC trigger points and the shunt-window report of svpwm_core
(rtl/svpwm_adc.sv) against the golden model (svpwm_model.core with svpwm_model.adc), on the builds that have
the feature (full = "default", foc), both simulators; the harness tb_svpwm_core.sv records every adc_pt_o
pulse with the carrier (A lines) and the report 9 clocks after every valley and peak (W lines: its latency bound).

* points_valley: POLAR at m = 1.1, 1.12 (near the hexagon: the largest phase's low-side window closes), 0.86
  and m = 0.5, the angle stepping through every sector, separate falling dead times, minimum pulses up to
  longer than both dead times (windows stretched by the minimum on-time) and none, valley updates; the points and the
  minimum window change at every update, at random: counts 0, 1, P - 1, P, P + 1, beyond P, random; both
  directions; on / off.
* points_double: the same with double updates (peak and valley): the points of the down half are those of
  the peak update.
* points_stop_restart: points and report while stopped (none, zero) and from the first update of a new run.

The ports of the points and the minimum window carry other values in the clocks where the compare values
are taken (before each valley and peak; port_junk), so a point taken from the port instead of the sample fails.
Checked exactly: every pulse's cycle and point bits == model (adc_fires), the carrier at each pulse the
point's count (or the valley / peak), every recorded report == adc.window of the model's values of that half
period; and all of CoreTB.compare (every edge == model) and the pin checker. Coverage is asserted (readable
and unreadable phases, every recon value, pulses on both halves, clamped counts), so no check passes empty.
"""
from __future__ import annotations

import random
from dataclasses import replace
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, RisingEdge

from clocks import clock_cycles
from simrun import cocotb_tests
from svpwm_model import adc, fixed
from svpwm_model.core import Inputs
from svpwm_tb import CoreTB, _diff, core_items, run_core_sim

P = 420
DT, DTF, MP = 24, 31, 4
# (m, dt, dtf, mp) per run: near the hexagon and inside it; a falling dead time and a minimum pulse longer than
# the rising one (so that a gate held on for H = max(dt, dtf, mp) stretches a window: adc.on_times); no minimum
# pulse with equal dead times (H = dt: a pulse snapped to the threshold ends where a held one would)
RUNS = ((1.1, DT, DTF, MP), (0.5, DT, DTF, MP), (0.86, 10, 40, 2), (1.12, 12, 20, 50), (1.12, 24, 24, 0))


def icarus() -> bool:
    return "icarus" in getattr(cocotb, "SIM_NAME", "").lower()


def n_periods(verilator: int, icarus_n: int) -> int:
    return icarus_n if icarus() else verilator


def rand_point(rng: random.Random, p: int) -> adc.Point:
    cnt = rng.choice([0, 1, p - 1, p, p + 1, p + 300, rng.randrange(0, p + 1), rng.randrange(0, p + 1),
                      (1 << 16) - 1])
    return adc.Point(en=rng.random() < 0.85, dn=rng.random() < 0.5, cnt=cnt)


def make_inputs(rng: random.Random, n: int, m: float, upd: int, dt: int = DT, dtf: int = DTF,
                mp: int = MP) -> list[Inputs]:
    base = Inputs(mode=fixed.MODE_POLAR, m=round(m * 0x8000), period=P, dt=dt, dtf=dtf, mp=mp, upd=upd)
    out = [base]
    for k in range(1, n):
        theta = (k * 5471 + rng.randrange(0, 800)) & 0xFFFF       # ~30 deg per period: every sector
        out.append(replace(base, theta=theta, adc_pt=(rand_point(rng, P), rand_point(rng, P)),
                           win_min=rng.choice([0, 1, 60, 200, 400, rng.randrange(0, 2 * P)])))
    return out


def check_adc(rtl, exp, cov: dict, h: int = 0) -> None:
    """The pulses and reports of the RTL == model; coverage counted into cov."""
    assert rtl.adc_fires == exp.adc_fires, _diff("ADC trigger pulses (cycle, {pt1, pt0})", rtl.adc_fires,
                                                 exp.adc_fires)
    halves = {h0: w for h0, w in exp.windows}
    starts = sorted(halves)
    n_win = 0
    for c, got in rtl.windows:
        h0 = c - 9
        if h0 not in halves or c >= exp.end:
            continue
        w = halves[h0]
        assert got == (w.lo, w.hi, w.ok, w.recon), (
            f"shunt-window report 9 clocks after the half period at cycle {h0}: RTL (lo, hi, ok, recon) {got} "
            f"!= model {w}")
        n_win += 1
        cov["ok0"] += w.ok != 0b111 and w.lo != (0, 0, 0)
        cov["ok1"] += w.ok != 0
        cov["recon"].add(w.recon)
        cov["hi_held"] += h in w.hi          # a high side held on for the minimum on-time H
    assert n_win >= len([h for h in starts if h + 9 < exp.end]) - 1, "report records missing"
    for (c, bits), (cnt, up) in zip(rtl.adc_fires, rtl.adc_at):
        cov["up"] += up
        cov["down"] += not up
        cov["pulses"] += 1


def new_cov() -> dict:
    return {"ok0": 0, "ok1": 0, "recon": set(), "up": 0, "down": 0, "pulses": 0, "hi_held": 0}


def assert_cov(cov: dict) -> None:
    assert cov["ok0"] and cov["ok1"], f"no readable / unreadable phase reported: {cov}"
    assert cov["recon"] == {0, 1, 2}, f"not every phase reconstructed: {cov}"
    assert cov["up"] and cov["down"], f"pulses not on both halves: {cov}"
    assert cov["hi_held"], f"no window stretched by the minimum on-time: {cov}"


PORTS = ("adc_pt_en_i", "adc_pt_dn_i", "adc_pt_cnt_i", "win_min_i")


async def port_junk(dut, rng: random.Random) -> None:
    """Other values on the points' and window's ports in the clocks around each update that are not sample
    clocks: the load clock before every valley and the one before every peak (where the compare values are
    taken) and the clock after; back to what they were after it (unless CoreTB wrote new inputs meanwhile).
    The RTL must take the values sampled with the reference, so the model does not see these."""
    async def junk_at_next_fall() -> dict:
        await FallingEdge(dut.clk)
        saved = {n: int(getattr(dut, n).value) for n in PORTS}
        junk = {n: rng.getrandbits(len(getattr(dut, n))) for n in PORTS}
        for n, v in junk.items():
            getattr(dut, n).value = v
        return {"saved": saved, "junk": junk}

    async def restore_at_fall(j: dict) -> None:
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        for n in PORTS:
            if int(getattr(dut, n).value) == j["junk"][n]:     # (CoreTB may have written new inputs)
                getattr(dut, n).value = j["saved"][n]

    await RisingEdge(dut.valley_o)                     # cycle v (P is constant in these runs)
    while True:
        await clock_cycles(dut.clk, P - 1)             # cycle v + P - 1: the load clock before the peak
        j = await junk_at_next_fall()
        await restore_at_fall(j)                       # falling edge of v + P
        await clock_cycles(dut.clk, P - 1)             # cycle v + 2P - 1: the one before the next valley
        j = await junk_at_next_fall()
        await restore_at_fall(j)                       # falling edge of v + 2P (= the next v)


async def run_case(dut, upd: int, seed: int) -> None:
    tb = CoreTB(dut)
    rng = random.Random(seed)
    cov = new_cov()
    for m, dt, dtf, mp in RUNS:
        await tb.reset(Inputs(mode=fixed.MODE_POLAR, period=P, dt=dt, dtf=dtf, mp=mp, upd=upd))
        ins = make_inputs(rng, n_periods(100, 24), m, upd, dt, dtf, mp)
        junk = cocotb.start_soon(port_junk(dut, random.Random(seed + 1)))
        rtl, exp = await tb.run(ins[0], ins, len(ins))
        junk.cancel()
        tb.compare(rtl, exp)
        tb.check_edges(rtl, exp, table_i=False)
        check_adc(rtl, exp, cov, max(dt, dtf, mp, 1))
    assert_cov(cov)


@cocotb.test()
async def points_valley(dut):
    """Points and windows with valley updates (RUNS: every sector)."""
    await run_case(dut, fixed.UPD_VALLEY, 0xADC0)


@cocotb.test()
async def points_double(dut):
    """Points and windows with double updates: the down half's points are the peak update's."""
    await run_case(dut, fixed.UPD_BOTH, 0xADC1)


@cocotb.test()
async def points_stop_restart(dut):
    """A stop in mid-period, idle, a new run: no pulse and a zero report while stopped and before the new
    run's first update, the points of the new run from its first update."""
    tb = CoreTB(dut)
    rng = random.Random(0xADC2)
    idle = Inputs(mode=fixed.MODE_POLAR, m=fixed.m_word(0.9), period=P, dt=DT, dtf=DTF, mp=MP,
                  adc_pt=(adc.Point(True, False, 0), adc.Point(True, True, 100)), win_min=50)
    await tb.reset(idle)
    for k in range(2):
        ins = [idle] + make_inputs(rng, 6, 0.9, fixed.UPD_VALLEY)[1:]
        rtl, exp = await tb.run(idle, ins, len(ins), stop=P // 2)
        tb.check_harness()
        assert rtl.adc_fires == exp.adc_fires, _diff(f"run {k}: ADC trigger pulses", rtl.adc_fires,
                                                     exp.adc_fires)
        first = exp.updates[0].load
        assert all(c >= first for c, _ in rtl.adc_fires), f"run {k}: a pulse before the first update"
        halves = dict(exp.windows)
        for c, got in rtl.windows:
            if c - 9 in halves and c < exp.end:
                w = halves[c - 9]
                assert got == (w.lo, w.hi, w.ok, w.recon), f"run {k}: report at {c}: {got} != {w}"
        await clock_cycles(dut.clk, 50)
        assert int(dut.adc_pt_o.value) == 0 and int(dut.win_lo_o.value) == 0 and int(dut.win_ok_o.value) == 0


# ---- pytest items: the builds with the feature (svpwm_tb.CORE_BUILDS: the models are shared) -------------
CASES = cocotb_tests(__file__)
ITEMS = core_items({c: ("adc",) for c in CASES}, ("default", "foc"))


@pytest.mark.parametrize("build,case", ITEMS, ids=[f"{b}-{c}" for b, c in ITEMS])
def test_svpwm_adc(sim, build, case):
    run_core_sim(sim, "test_svpwm_adc", Path(__file__).parent, build, case)
