# SPDX-License-Identifier: Apache-2.0
"""cocotb driver/monitor for tb_svpwm_core, event driven: no Python await per clock.

CoreTB.run() enables the core, applies the per-period inputs at each valley, records every edge of
{pole, gate_lo, gate_hi} and the active compare values at each valley, and returns them in the
model's time base (cycle 0 = first clock with en_i = 1) for comparison with svpwm_model.core.
"""
from __future__ import annotations

import bisect
import os
from dataclasses import dataclass, field
from typing import Callable, NamedTuple, Sequence

import cocotb
from cocotb.triggers import FallingEdge, RisingEdge, Timer
from cocotb.utils import get_sim_time
from clocks import clock_cycles

from pathlib import Path

from simrun import rtl_sources, run_sim
from svpwm_model import config, fixed
from svpwm_model.analysis import check_legs, check_table_i
from svpwm_model.core import CoreModel, Inputs, Run

CLK_NS = 10


@dataclass
class RtlRun:
    pole_edges: list[tuple[int, int]] = field(default_factory=list)
    gate_edges: list[tuple[int, int]] = field(default_factory=list)
    valley: list[int] = field(default_factory=list)
    cmp: list[tuple[int, int, int]] = field(default_factory=list)
    cmp_peak: list[tuple[int, int, int]] = field(default_factory=list)
    sector: list[int] = field(default_factory=list)
    period: list[int] = field(default_factory=list)
    running: list[int] = field(default_factory=list)
    sat: list[bool] = field(default_factory=list)
    updates: list[int] = field(default_factory=list)     # cycles update_o was high
    adc_fires: list[tuple[int, int]] = field(default_factory=list)   # (cycle, adc_pt_o) while nonzero
    adc_at: list[tuple[int, int]] = field(default_factory=list)      # (carrier_o, carrier_up_o) at those
    windows: list[tuple[int, tuple]] = field(default_factory=list)   # (cycle, (lo, hi, ok, recon))


class Clock(NamedTuple):
    """One clock of the harness' per-clock trace (CoreTB.per_clock)."""
    valley: int
    peak: int
    period: int
    adc: int
    carrier: int
    tripped: int
    fault: int
    hi: int              # gate_hi_o {c, b, a} (1 = on, whatever the pin polarity)
    lo: int              # gate_lo_o
    pclamp: int          # period_clamp_o
    carry: int           # the core's volt-second carry register (u_core.calc_carry_in, {c, b, a} packed)


def _diff(name: str, got: list, exp: list) -> str:
    for i, (g, e) in enumerate(zip(got, exp)):
        if g != e:
            lo = max(0, i - 3)
            return (f"{name}: first difference at index {i}: rtl {g} != model {e}\n"
                    f"  rtl   {got[lo:i + 4]}\n  model {exp[lo:i + 4]}")
    return f"{name}: lengths differ: rtl {len(got)} != model {len(exp)}"


class CoreTB:
    def __init__(self, dut):
        self.dut = dut
        # the build of the harness (svpwm_core Features, config.py; run_core_sim sets SVPWM_FEATURES)
        self.features = int(os.environ.get("SVPWM_FEATURES", str(config.FULL)))
        self.compact = self.features == config.TINY
        self.model = CoreModel(features=self.features)
        self.cmp_width = len(dut.period_o)
        self.rec = None                     # the harness' record file (see run())
        # what the ports get instead of the model's inputs (None: the same); e.g. another dead time on
        # dt_i while lock_i holds the locked one (the model keeps the locked value)
        self.port_inputs: Callable[[Inputs], Inputs] | None = None
        self.t0 = 0

    def has(self, name: str) -> bool:
        """The harness's build has feature ``name`` (config.FEATURES)."""
        return config.has(self.features, name)

    def set_inputs(self, u: Inputs) -> None:
        d = self.dut
        if self.port_inputs is not None:
            u = self.port_inputs(u)
        d.freq_i.value = u.freq
        d.m_i.value = u.m
        d.period_i.value = u.period
        d.dt_i.value = u.dt
        # the falling dead time: dtf_en_i = 0 with a value on dtf_i that must be ignored, or dtf_en_i = 1
        d.dtf_en_i.value = int(u.dtf is not None)
        d.dtf_i.value = u.dtf if u.dtf is not None else (u.dt ^ 0x155) & ((1 << len(d.dtf_i)) - 1)
        d.mp_i.value = u.mp
        d.mode_i.value = u.mode
        d.theta_i.value = u.theta & 0xFFFF
        d.v1_i.value = u.v1
        d.v2_i.value = u.v2
        d.vf_boost_i.value = u.vf_boost
        d.vf_slope_i.value = u.vf_slope
        d.vf_mmax_i.value = u.vf_mmax
        d.dpwm_i.value = u.dpwm
        d.upd_i.value = u.upd
        d.presc_i.value = u.presc
        d.dtc_en_i.value = u.dtc
        d.om_i.value = u.om
        d.vsc_en_i.value = u.vsc
        d.isign_i.value = u.isign & 7
        w = len(d.period_i)
        d.adc_pt_en_i.value = sum(int(p.en) << k for k, p in enumerate(u.adc_pt))
        d.adc_pt_dn_i.value = sum(int(p.dn) << k for k, p in enumerate(u.adc_pt))
        d.adc_pt_cnt_i.value = sum((p.cnt & ((1 << w) - 1)) << (k * w) for k, p in enumerate(u.adc_pt))
        d.win_min_i.value = u.win_min

    def set_safety(self, fault=0, fault_clear=0, cbc=0, safe_lo=0, pol=0, lock=0) -> None:
        d = self.dut
        d.fault_i.value = fault
        d.fault_clear_i.value = fault_clear
        d.trip_cbc_i.value = cbc
        d.safe_lo_i.value = safe_lo
        d.pol_i.value = pol
        d.lock_i.value = lock
        d.adc_trig_i.value = 0
        d.sync_en_i.value = 0
        d.sync_i.value = 0

    async def reset(self, idle: Inputs = Inputs()) -> None:
        d = self.dut
        d.en_i.value = 0
        d.trace_i.value = 0
        self.set_inputs(idle)
        self.set_safety()
        d.rst_ni.value = 0
        await clock_cycles(d.clk, 3)
        d.rst_ni.value = 1
        await clock_cycles(d.clk, fixed.ARM_CLOCKS)   # the core runs ARM_CLOCKS after the reset release at the earliest
        self.model = CoreModel(features=self.features)
        self.idle_cycles = fixed.ARM_CLOCKS + 2       # clocks from reset release to cycle 0 of run() (en_i low)
        self.t_idle = get_sim_time("ns")              # ... if run() is called now (later: more idle clocks)

    def _idle_now(self) -> int:
        """Clocks from the reset release (or the stop) to cycle 0 of a run() starting now: the model's dead-time
        counters and the reset hold (2^DtWidth - 1 clocks) need them exactly."""
        return self.idle_cycles + int(get_sim_time("ns") - self.t_idle) // CLK_NS

    def _cycle(self) -> int:
        return int(round(get_sim_time("ns") - self.t0)) // CLK_NS

    async def _monitor(self, out: list) -> None:
        while True:
            await self.dut.mon.value_change
            out.append((self._cycle(), int(self.dut.mon.value)))

    async def _updates(self, out: list) -> None:
        while True:
            await RisingEdge(self.dut.update_o)
            out.append(self._cycle())

    async def per_clock(self, n: int) -> list[Clock]:
        """The outputs 1 ns after each of the next n rising clock edges, from the harness' record (C lines,
        written while trace_i is high): Python wakes once for the whole window, not at every clock."""
        d = self.dut
        t_start = get_sim_time("ns")
        d.trace_i.value = 1
        await Timer(n * CLK_NS + 2, "ns")
        d.trace_i.value = 0
        rows = [Clock(*(int(x, 16) for x in r[2:13])) for r in self._rec_lines()
                if r[0] == "C" and int(r[1]) - 1 > t_start]
        assert len(rows) >= n, f"per_clock: {len(rows)} clocks recorded, {n} expected (trace_i, +svpwm_rec?)"
        return rows[:n]

    def _read_cmp(self) -> tuple[int, int, int]:
        w = self.cmp_width
        c = int(self.dut.cmp_o.value)
        return tuple((c >> (w * ph)) & ((1 << w) - 1) for ph in range(3))

    async def run(self, idle: Inputs, inputs: Sequence[Inputs] | Callable[[int], Inputs], n_periods: int,
                  stop: int | None = None,
                  peak_inputs: Sequence[Inputs] | Callable[[int], Inputs] | None = None) -> tuple[RtlRun, Run]:
        """Run the RTL and the model the same way; returns (rtl, model) results.

        inputs(n) are on the ports from valley n (from peak n if peak_inputs is given, which then holds
        the inputs from valley n to peak n); see svpwm_model.core.

        The harness records the edges and the per-period values (tb_svpwm_core.sv, +svpwm_rec); Python
        wakes only at the falling clock edges where an input changes (after the valley / peak the model
        puts it at; the valley and peak cycles themselves are compared with the RTL's) and at the end."""
        d = self.dut
        get = inputs if callable(inputs) else (lambda n: inputs[n])
        pget = None if peak_inputs is None else (peak_inputs if callable(peak_inputs) else (lambda n: peak_inputs[n]))
        if pget is None:
            assert get(0) == idle, "inputs(0) must equal the idle inputs (period 0 samples them)"
        else:
            assert pget(0) == idle, "peak_inputs(0) must equal the idle inputs"
        self.model.idle(self._idle_now())
        exp = self.model.run(idle, inputs, n_periods, stop, peak_inputs)
        # where the inputs change: (cycle of the valley / peak, inputs set at the falling edge of that cycle)
        changes: list[tuple[int, Inputs]] = []
        cur = idle
        for n in range(n_periods):
            seq = []
            if pget is not None:
                seq.append((exp.valley[n] + exp.period[n], get(n)))          # after peak n
            if n + 1 < n_periods:
                seq.append((exp.valley[n + 1], get(n + 1) if pget is None else pget(n + 1)))   # after valley n+1
            for c, u in seq:
                if u != cur:
                    changes.append((c, u))
                    cur = u
        self.set_inputs(idle)
        await clock_cycles(d.clk, 2)                # period_i on the port 2 clocks before en_i (README, Timing)
        d.en_i.value = 1
        self.t0 = get_sim_time("ns")
        await FallingEdge(d.clk)                    # (the first valley_o is cycle START_DELAY)
        for c, u in changes:
            await self._to_cycle(c)
            await FallingEdge(d.clk)
            self.set_inputs(u)
        t_n = exp.valley[n_periods]
        await self._to_cycle(t_n)                   # the rising clock edge of cycle t_N
        if stop is not None:
            if stop == 0:
                await FallingEdge(d.clk)            # still in cycle t_N
            else:
                await RisingEdge(d.clk)             # edge starting cycle t_N + 1
                if stop > 1:
                    await clock_cycles(d.clk, stop - 1)
            d.en_i.value = 0
            await clock_cycles(d.clk, 4)
            self.idle_cycles = 4                    # cycles stop+1 .. stop+4 idle before the next run
            self.t_idle = get_sim_time("ns")
        else:
            await FallingEdge(d.clk)                # the core runs on
        return self._recorded(n_periods, exp.end), exp

    async def _to_cycle(self, c: int) -> None:
        """Wait for the rising clock edge that starts cycle c (in the future)."""
        target = self.t0 + c * CLK_NS
        now = get_sim_time("ns")
        assert target > now, f"cycle {c} ({target} ns) is not after now ({now} ns)"
        if target - now > CLK_NS:
            await Timer(target - now - CLK_NS / 4, "ns")
        await RisingEdge(self.dut.clk)
        assert get_sim_time("ns") == target, f"rising edge at {get_sim_time('ns')} ns, expected {target} ns"

    def _rec_lines(self) -> list[list[str]]:
        """The harness' record lines written since the last call."""
        if self.rec is None:
            path = os.environ.get("SVPWM_REC")
            assert path, "SVPWM_REC not set: run through simrun.run_sim (it passes +svpwm_rec=<file>)"
            self.rec = open(path)
        return [ln.split() for ln in self.rec.read().splitlines()]

    def _recorded(self, n_periods: int, end: int) -> RtlRun:
        """RtlRun from the record: the first n_periods peaks and valleys after cycle 0, edges before end."""
        return parse_record(self._rec_lines(), self.t0, self.cmp_width, n_periods, end)

    @staticmethod
    def compare(rtl: RtlRun, exp: Run) -> None:
        """Assert the RTL equals the model: valleys, compare values, sectors, periods, every edge."""
        assert len(rtl.cmp) == len(exp.cmp) - 1 > 0, "no modulated period recorded"
        assert rtl.valley == exp.valley, _diff("valley cycles", rtl.valley, exp.valley)
        assert rtl.period == exp.period[1:], _diff("active period", rtl.period, exp.period[1:])
        assert rtl.cmp == exp.cmp[1:], _diff("compare values", rtl.cmp, exp.cmp[1:])
        assert rtl.cmp_peak == exp.cmp_peak, _diff("compare values at the peaks", rtl.cmp_peak, exp.cmp_peak)
        assert rtl.sector == exp.sector[1:], _diff("sector", rtl.sector, exp.sector[1:])
        assert rtl.sat == exp.sat[1:], _diff("sat_o", rtl.sat, exp.sat[1:])
        loads = [u.load for u in exp.updates if u.load < exp.end]
        assert rtl.updates == loads, _diff("update_o cycles", rtl.updates, loads)
        assert all(rtl.running), "running_o low in a modulated period"
        assert rtl.pole_edges == exp.pole_edges, _diff("pole edges", rtl.pole_edges, exp.pole_edges)
        assert rtl.gate_edges == exp.gate_edges, _diff("gate edges", rtl.gate_edges, exp.gate_edges)

    def check_edges(self, rtl: RtlRun, exp: Run, stop=None, table_i: bool = True, dt_of=None):
        """The in-RTL pin checker, then check_edges() of the module on the RTL's edges. Returns the Table I
        result (or None)."""
        self.check_harness()
        return check_edges(rtl, exp, stop, table_i, dt_of)

    def check_harness(self) -> None:
        d = self.dut
        assert int(d.shoot_through_count.value) == 0, "in-RTL checker: both gates of a leg on"
        assert int(d.dead_time_violations.value) == 0, "in-RTL checker: dead time violated"
        assert int(d.short_pulse_count.value) == 0, "in-RTL checker: gate pulse shorter than max(dt, mp)"
        assert int(d.off_violations.value) == 0, "in-RTL checker: a gate on in reset or while disabled"


def compare_into(tb: "CoreTB", rtl: RtlRun, exp: Run, res: dict, fails: list) -> None:
    """For the long runs that collect their failures (demo_runs, foc_loop): RTL == model on every edge
    (CoreTB.compare), recorded in res["rtl_equals_model"] and, if not, in fails."""
    try:
        tb.compare(rtl, exp)
        res["rtl_equals_model"] = True
    except AssertionError as e:
        res["rtl_equals_model"] = False
        fails.append(f"RTL != model: {e}")


def pin_checks(tb: "CoreTB", rtl: RtlRun, exp: Run, res: dict, fails: list) -> None:
    """For the long runs that collect their failures (demo_runs, foc_loop): the harness's pin-checker counters
    into res["harness"] and the leg check of the RTL's gate edges into res["legs"]; a failure of either is
    appended to ``fails``."""
    d = tb.dut
    res["harness"] = dict(shoot_through_clocks=int(d.shoot_through_count.value),
                          dead_time_violations=int(d.dead_time_violations.value),
                          short_pulses=int(d.short_pulse_count.value))
    try:
        tb.check_harness()
    except AssertionError as e:
        fails.append(str(e))
    legs = check_legs(rtl.gate_edges, dead_time_at(rtl.valley, exp.dt))
    res["legs"] = dict(shoot_through=len(legs.shoot_through), dead_time=len(legs.dead_time),
                       short_pulse=len(legs.short_pulse))
    if not legs.ok:
        fails.append("leg check: " + "; ".join((legs.shoot_through + legs.dead_time + legs.short_pulse)[:3]))


def check_edges(rtl: RtlRun, exp: Run, stop=None, table_i: bool = True, dt_of=None):
    """The checks beyond bit-exactness, from the RTL's own edges: every period against Table I
    (single-update SVPWM only: one symmetric seven-segment pattern per period) and the legs for
    shoot-through, dead time and short pulses (a stop at the end: the last clock forces the gates off).
    Returns the Table I result (or None)."""
    seq = None
    if table_i:
        seq = check_table_i(rtl.pole_edges, rtl.valley, [None] + rtl.sector)
        assert seq.ok, "; ".join(seq.failures[:5])
    legs = check_legs(rtl.gate_edges, dt_of or dead_time_at(rtl.valley, exp.dt, exp.dtf),
                      forced_off=[exp.end - 1] if stop is not None else [])
    assert legs.ok, (legs.shoot_through + legs.dead_time + legs.short_pulse)[:5]
    return seq


def parse_record(lines: list[list[str]], t0: float, cmp_width: int, n_periods: int, end: int) -> RtlRun:
    """RtlRun from the record lines of tb_svpwm_core.sv (split into fields), in the model's time base
    (cycle 0 = the clock that starts at t0 ns, the rising edge that set en_i): the first n_periods peaks
    and valleys after cycle 0, the edges before cycle `end`."""
    w = cmp_width
    cyc = lambda t: int(round(int(t) - t0)) // CLK_NS       # noqa: E731
    split = lambda c: tuple((c >> (w * ph)) & ((1 << w) - 1) for ph in range(3))   # noqa: E731
    rtl = RtlRun(valley=[fixed.START_DELAY])       # the first valley: the core's first running clock
    mon, upd, n_v, n_p = [], [], 0, 0
    for rec in lines:
        if int(rec[1]) < t0:
            continue
        c = cyc(rec[1])
        if rec[0] == "M":
            mon.append((c, int(rec[2], 16)))
        elif rec[0] == "U":
            upd.append(c)
        elif rec[0] == "A":
            rtl.adc_fires.append((c, int(rec[2], 16)))
            rtl.adc_at.append((int(rec[3], 16), int(rec[4], 16)))
        elif rec[0] == "W":
            ww = w + 1
            sp = lambda x: tuple((x >> (ww * ph)) & ((1 << ww) - 1) for ph in range(3))   # noqa: E731
            rtl.windows.append((c, (sp(int(rec[2], 16)), sp(int(rec[3], 16)), int(rec[4], 16), int(rec[5], 16))))
        elif rec[0] == "P" and c >= 1 and n_p < n_periods:
            n_p += 1
            rtl.cmp_peak.append(split(int(rec[2], 16)) if int(rec[3], 16) else None)
        elif rec[0] == "V" and c > fixed.START_DELAY and n_v < n_periods:
            n_v += 1
            rtl.valley.append(c)
            if n_v < n_periods:
                cmp, sector, period, running, sat = (int(x, 16) for x in rec[2:7])
                rtl.cmp.append(split(cmp))
                rtl.sector.append(sector)
                rtl.period.append(period)
                rtl.running.append(running)
                rtl.sat.append(bool(sat))
    rtl.updates = [c for c in upd if c < end]
    words = [(c, x) for c, x in mon if c < end]
    rtl.pole_edges = _squash([(c, x >> 6) for c, x in words])
    rtl.gate_edges = _squash([(c, x & 0x3F) for c, x in words])
    return rtl


def dead_time_at(valleys: list[int], dts: list[int], dtfs: list[int] | None = None) -> Callable:
    """The dead time in force at a cycle: the one of the carrier period containing it; with the falling
    dead times ``dtfs`` the pair (dt, dtf) (analysis.check_legs takes either)."""
    def at(c: int):
        k = bisect.bisect_right(valleys, c) - 1
        k = min(max(k, 0), len(dts) - 1)
        return dts[k] if dtfs is None else (dts[k], dtfs[k])
    return at


def _squash(ev: list[tuple[int, int]], initial: int = 0) -> list[tuple[int, int]]:
    """Changes of a stream that starts at ``initial``: same-cycle updates merged, repeats dropped."""
    out: list[tuple[int, int]] = [(-1, initial)]
    for c, w in ev:
        if out[-1][0] == c:
            out[-1] = (c, w)
        elif out[-1][1] != w:
            out.append((c, w))
        if len(out) >= 2 and out[-1][1] == out[-2][1]:
            out.pop()
    return out[1:]


# ---- the builds of tb_svpwm_core (tb/cocotb/svpwm_core/tb_svpwm_core.sv) that the core, safety, modes and
# stress tests share: one simulator model per build name (simrun.run_sim makes each once per simulator)
CORE_HARNESS = Path(__file__).parent / "svpwm_core" / "tb_svpwm_core.sv"
# (default: the full core; compact: the tiny configuration; foc, vf, minimal: the named configurations)
CORE_BUILDS: dict[str, dict] = {
    "default": {},
    "compact": {"features": config.TINY},
    "freq16": {"parameters": {"FreqWidth": 16, "PhaseWidth": 26}},   # the narrow frequency word
    **{n: {"features": config.CONFIGS[n]} for n in ("foc", "vf", "minimal")},
}


def build_features(build: str) -> int:
    return CORE_BUILDS[build].get("features", config.FULL)


def core_items(needs: dict[str, tuple[str, ...]], builds: Sequence[str]) -> list[tuple[str, str]]:
    """(build, case) for every cocotb case and every build of ``builds`` that has the features the case
    needs (needs[case]: config.FEATURES names): each test runs on the builds that have what it tests."""
    return [(b, c) for b in builds for c, need in needs.items()
            if all(config.has(build_features(b), n) for n in need)]


def run_core_sim(sim: str, test_module: str, test_dir: Path, build: str = "default", testcase=None,
                 record: bool = True, extra_env: dict | None = None) -> None:
    """Run cocotb tests of ``test_module`` on tb_svpwm_core built as ``build`` (CORE_BUILDS)."""
    cfg = CORE_BUILDS[build]
    feats = build_features(build)
    params = dict(cfg.get("parameters", {}))
    if feats != config.FULL:
        params["Features"] = feats
    run_sim(sim, toplevel="tb_svpwm_core", sources=rtl_sources() + [CORE_HARNESS], test_module=test_module,
            test_dir=test_dir, build_name=build, parameters=params,
            extra_env={"SVPWM_FEATURES": str(feats), **(extra_env or {})}, testcase=testcase, record=record,
            vpi_top_only=True)
