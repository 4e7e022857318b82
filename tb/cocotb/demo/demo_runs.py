# SPDX-License-Identifier: Apache-2.0
"""cocotb module for scripts/demo.py and scripts/bench.py: one cocotb test per operating point.

Not a pytest file (pytest.ini collects test_*.py only): it is run through simrun.run_sim by the scripts.

Environment (set by the scripts):

* ``SVPWM_DEMO_POINTS``: JSON list of operating points, each a dict with
  ``name`` (a Python identifier; becomes the cocotb test name), ``f_hz``, ``m`` (project normalisation:
  m = 1 is the inscribed circle, line fundamental peak = m * Udc), ``period`` (P, half carrier period in
  clocks), ``dt`` (dead time, clocks) and optionally ``n_periods`` (default: one full revolution + 2
  periods), ``vcd`` (bool, default true), ``title`` (free text); and for the volt-second carry and
  overmodulation runs (issue 15 item 5(b), (c)): ``m_word`` (the UQ1.15 word itself, for m > 1), ``mp``
  (minimum pulse, clocks), ``vsc`` (vsc_en_i), ``om`` (om_i), ``spectra`` (line-voltage figures over the
  ``revs`` revolutions in the result, as the report's sweep: spectrum.figures), ``fund_ref`` (the expected
  line fundamental, default m), ``fund_check`` (false: the fundamental is reported, not checked).
* ``SVPWM_DEMO_OUT``: directory for ``<name>.json`` (results) and ``<name>.vcd`` (gate waveforms).

A point with ``kind`` "speed_loop" is the closed speed loop (run_speed_loop); ``kind`` "dtc" a dead-time run
with the motor model in the loop driving isign_i (run_dtc_point: ``dt``, ``dtc``, ``t_load``, ``revs``,
``warmup_revs``); ``kind`` "foc" the closed FOC current loop with a PMSM (run_foc_point, tb/cocotb/foc_loop.py:
its keys are run_foc's); any other point the constant-input run below.

Per point the core runs on tb_svpwm_core.sv with constant inputs; the test asserts RTL == model on every
edge (CoreTB.compare) and the in-RTL safety checker, and measures: the line-voltage (a - b) fundamental
from the RTL's pole edges against the command, the worst per-period |C - C_ideal| (ideal SVPWM at the exact
sampled accumulator angle and the quantised m), Minas Table I sequences, leg safety from the gate edges,
edge counts, simulated clock cycles and wall time. Results are written before any assertion fails.

Throughput: ``sim_wall_s`` runs from the first clock edge after the model has computed its expectation
(CoreTB.run computes the model first, synchronously) to the end of CoreTB.run, so it covers the simulator
plus cocotb's Python edge handling (one callback per output-word change and per valley), not the model
or the analysis. ``cycles_per_s`` = simulated core clocks / ``sim_wall_s``; ``cycles_per_cpu_s`` the same per
CPU second of the simulator process (simulator + embedded Python), which a shared machine does not inflate.

VCD: 1 ns time units; an edge at core clock cycle c (cycle 0 = first clock with en_i = 1) is written at
round(c * 1e9 / 48e6) ns, i.e. the waveform is shown at the core's 48 MHz clock (20.833 ns per cycle),
not at the harness' 10 ns simulation clock. Edges only (no clock), 1-bit wires gate_hi_a/b/c,
gate_lo_a/b/c, pole_a/b/c.

``save_edges``: ``<name>_edges.npz`` with the RTL's pole and gate edges, valleys, and per modulated period
(index i = period i + 1, as CoreTB's RtlRun) its compare values, sector and P, and the model's exact
full-accumulator angle (``theta``) and magnitude word (``m_used``) they were computed from (-1: none); the
RTL's values equal the model's (asserted), so scripts/demo.py can set them beside the seeds' tables.
"""
from __future__ import annotations

import json
import math
import os
import time
from pathlib import Path

import cocotb
import cocotb.utils
import numpy as np
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge

from clocks import clock_cycles
from svpwm_model import fixed
from svpwm_model.analysis import check_table_i, duty_error, line_fundamental
from svpwm_model.core import Inputs
from svpwm_tb import CLK_NS, CoreTB, compare_into, pin_checks

F_CLK = fixed.F_CLK_DEFAULT
VCD_NS_PER_CYCLE = 1e9 / F_CLK            # 20.833 ns at 48 MHz


def default_periods(f_hz: float, period: int, revs: float = 1) -> int:
    """Carrier periods covering at least ``revs`` revolutions (+2 for the pipeline start)."""
    if f_hz == 0:
        return 40
    return math.ceil(revs * F_CLK / (2 * period) / abs(f_hz)) + 2


def write_vcd(path: Path, pole_edges, gate_edges, end_cycle: int, comment: str) -> None:
    """Hand-written VCD of the 9 gate/pole bits from edge lists [(cycle, word)]; 1 ns units at 48 MHz."""
    names = [f"gate_hi_{x}" for x in "abc"] + [f"gate_lo_{x}" for x in "abc"] + [f"pole_{x}" for x in "abc"]
    ids = [chr(33 + i) for i in range(len(names))]
    changes: dict[int, dict[int, int]] = {}
    for c, w in gate_edges:                    # gate word {lo[2:0], hi[2:0]}: bits 0..5 = names 0..5
        for b in range(6):
            changes.setdefault(c, {})[b] = (w >> b) & 1
    for c, w in pole_edges:                    # pole word {c, b, a}
        for b in range(3):
            changes.setdefault(c, {})[6 + b] = (w >> b) & 1
    cur = [0] * len(names)
    lines = [
        f"$date {time.strftime('%Y-%m-%d %H:%M:%S')} $end",
        "$version svpwm demo_runs.py (hand-written VCD writer) $end",
        f"$comment {comment} $end",
        "$comment time unit 1 ns; core clock 48 MHz: cycle c at round(c * 20.833) ns; "
        "cycle 0 = first clock with en_i = 1; edges only, no clock $end",
        "$timescale 1ns $end",
        "$scope module svpwm_core $end",
    ]
    lines += [f"$var wire 1 {i} {n} $end" for i, n in zip(ids, names)]
    lines += ["$upscope $end", "$enddefinitions $end", "#0", "$dumpvars"]
    lines += [f"0{i}" for i in ids]
    lines.append("$end")
    last_t = 0
    for c in sorted(changes):
        out = []
        for b, v in sorted(changes[c].items()):
            if cur[b] != v:
                cur[b] = v
                out.append(f"{v}{ids[b]}")
        if not out:
            continue
        t = int(round(c * VCD_NS_PER_CYCLE))
        if t != last_t or t == 0:
            if t != 0:
                lines.append(f"#{t}")
            last_t = t
        lines += out
    t_end = int(round(end_cycle * VCD_NS_PER_CYCLE))
    if t_end > last_t:
        lines.append(f"#{t_end}")
    path.write_text("\n".join(lines) + "\n")


async def run_point(dut, pt: dict) -> None:
    t_test = time.perf_counter()
    out_dir = Path(os.environ.get("SVPWM_DEMO_OUT", "."))
    out_dir.mkdir(parents=True, exist_ok=True)
    tb = CoreTB(dut)
    fw = fixed.freq_word(pt["f_hz"])
    mw = int(pt["m_word"]) if pt.get("m_word") is not None else fixed.m_word(pt["m"])
    om, vsc = int(bool(pt.get("om"))), int(bool(pt.get("vsc")))
    u = Inputs(freq=fw, m=mw, period=int(pt["period"]), dt=int(pt["dt"]), mp=int(pt.get("mp", 0)), om=om, vsc=vsc)
    n = int(pt.get("n_periods") or default_periods(pt["f_hz"], u.period, pt.get("revs", 1)))
    res: dict = dict(point=pt, sim=getattr(cocotb, "SIM_NAME", "?"), freq_word=fw, m_word=mw,
                     f_out_hz_exact=fw * fixed.freq_lsb_hz(), f_sw_hz=F_CLK / (2 * u.period),
                     n_periods=n, failures=[])
    fails = res["failures"]
    await tb.reset(u)

    t_sim = {}

    async def mark_start():
        await RisingEdge(dut.clk)          # first edge after CoreTB.run() has run the model
        t_sim["start"] = time.perf_counter()
        t_sim["cpu_start"] = time.process_time()

    cocotb.start_soon(mark_start())
    rtl, exp = await tb.run(u, lambda k: u, n)
    t_sim["end"] = time.perf_counter()
    t_sim["cpu_end"] = time.process_time()
    cycles = exp.valley[-1]
    res.update(cycles=cycles, sim_wall_s=t_sim["end"] - t_sim["start"],
               cycles_per_s=cycles / (t_sim["end"] - t_sim["start"]),
               sim_cpu_s=t_sim["cpu_end"] - t_sim["cpu_start"],
               cycles_per_cpu_s=cycles / max(t_sim["cpu_end"] - t_sim["cpu_start"], 1e-9),
               gate_edges=len(rtl.gate_edges), pole_edges=len(rtl.pole_edges),
               modulated_periods=len(rtl.cmp))

    # ---- RTL == model, in-RTL checker, leg safety from the edges -----------------------------------
    compare_into(tb, rtl, exp, res, fails)
    pin_checks(tb, rtl, exp, res, fails)

    # ---- Table I -----------------------------------------------------------------------------------
    # with the volt-second carry and a minimum-pulse threshold two phases within thr of each other may swap
    # order (docs/design.md, "Volt-second carry"): Table I is then reported, not checked
    seq = check_table_i(rtl.pole_edges, rtl.valley, [None] + rtl.sector)
    ti_checked = not (vsc and u.dt + u.mp > 0)
    res["table_i"] = dict(periods=seq.periods, with_skipped_states=seq.with_skips,
                          failures=len(seq.failures), first_failures=seq.failures[:5], checked=ti_checked)
    if not seq.ok and (ti_checked or seq.periods == 0):
        fails.append("Table I: " + ("; ".join(seq.failures[:3]) or "no period checked"))

    # ---- duty error vs the ideal SVPWM -------------------------------------------------------------
    # the six-step law (om_i) stretches the clamp's rounding by its gain g (up to 217): the <= 1 count bound
    # is a calculator bound where g = 1 (om = 0, or m <= 2/sqrt3); above it the error is reported
    worst, at = duty_error(exp, om=om)
    bound = not (om and mw > fixed.M_VERTEX)
    res["worst_abs_c_minus_ideal_counts"] = worst
    res["worst_at_period"] = at
    res["duty_error_checked"] = bound
    if bound and worst > 1.0:
        fails.append(f"worst |C - C_ideal| = {worst:.3f} counts > 1")

    # ---- line fundamental over one revolution ------------------------------------------------------
    ref = float(pt.get("fund_ref", pt["m"]))
    res["line_fundamental_commanded"] = ref                   # m * Udc, Udc = 1 (or the law's map above m = 1)
    res["line_fundamental_commanded_quantised"] = mw / fixed.M_ONE
    t0 = rtl.valley[1] + 1
    if fw != 0 and t0 + 6 * (1 << fixed.PHASE_WIDTH) / abs(fw) <= rtl.valley[-1]:
        amp = line_fundamental(rtl.pole_edges, fw, t0, revolutions=1)
        rel = amp / ref - 1 if ref else None
        res.update(line_fundamental_measured=amp, line_fundamental_rel_err=rel)
        if rel is not None and abs(rel) > 1e-3 and pt.get("fund_check", True):
            fails.append(f"line fundamental {amp:.6f} vs commanded {ref}: {100 * rel:+.4f} % (> 0.1 %)")
    else:
        res.update(line_fundamental_measured=None, line_fundamental_rel_err=None,
                   line_fundamental_note="run shorter than one revolution: not measured")

    # ---- line-voltage figures over ``revs`` revolutions (pole states: ideal switches) ---------------------
    if pt.get("spectra") and fw != 0:
        from svpwm_model import spectrum as S
        n_fund = int(pt.get("revs", 1))
        T = n_fund / (abs(fw) / (6 * (1 << fixed.PHASE_WIDTH)))
        if t0 + T <= rtl.valley[-1] + 1:
            f_sw = F_CLK / (2 * u.period)
            sp = S.spectra_from_edges(rtl.pole_edges, t0, T, n_fund, int(3 * f_sw * T / F_CLK), F_CLK)
            L = S.figures(sp.line[0], n_fund, T, F_CLK, f_sw).as_dict()
            res["line"] = L
            amp = np.abs(sp.line[0])
            j = np.arange(amp.size)
            low1k = (j >= 1) & (j != n_fund) & (j / T * F_CLK < 1000.0)      # up to the 19th harmonic at 50 Hz
            res["line_low_order_max_below_1khz_dbc"] = float(20 * np.log10(amp[low1k].max() / amp[n_fund]))
            res["line_window"] = dict(t0=t0, T=T, n_fund=n_fund, leakage_bins=S.leakage(n_fund, T, f_sw / F_CLK))
            res["line_fundamental_rel_err_window"] = L["fundamental"] / ref - 1 if ref else None

    # ---- waveforms and results ---------------------------------------------------------------------
    if pt.get("vcd", True):
        vcd = out_dir / f"{pt['name']}.vcd"
        write_vcd(vcd, rtl.pole_edges, rtl.gate_edges, exp.end,
                  f"{pt.get('title', pt['name'])}: f = {pt['f_hz']} Hz (word {fw}), m = {pt['m']} (word {mw}), "
                  f"P = {u.period}, dt = {u.dt} clocks, {n} carrier periods, sim {res['sim']}")
        res["vcd"] = str(vcd)
    if pt.get("save_edges"):
        npz = out_dir / f"{pt['name']}_edges.npz"
        np.savez_compressed(npz, pole_edges=np.asarray(rtl.pole_edges, dtype=np.int64).reshape(-1, 2),
                            gate_edges=np.asarray(rtl.gate_edges, dtype=np.int64).reshape(-1, 2),
                            valley=np.asarray(rtl.valley, dtype=np.int64),
                            cmp=np.asarray(rtl.cmp, dtype=np.int64), sector=np.asarray(rtl.sector, dtype=np.int64),
                            period=np.asarray(rtl.period, dtype=np.int64), freq_word=fw, m_word=mw, dt=u.dt,
                            mp=u.mp, vsc=u.vsc, om=u.om, end=exp.end,
                            theta=np.asarray([-1 if x is None else x for x in exp.theta[1:]], dtype=np.int64),
                            m_used=np.asarray([-1 if x is None else x for x in exp.m[1:]], dtype=np.int64))
        res["edges_npz"] = str(npz)
    res["test_wall_s"] = time.perf_counter() - t_test
    res["ok"] = not fails
    (out_dir / f"{pt['name']}.json").write_text(json.dumps(res, indent=2) + "\n")
    dut._log.info("%s: %d cycles in %.2f s (%.0f cycles/s), %d gate edges, worst |C - ideal| %.3f, %s",
                  pt["name"], cycles, res["sim_wall_s"], res["cycles_per_s"], len(rtl.gate_edges), worst,
                  "ok" if not fails else "FAILED")
    assert not fails, "\n".join(fails)


async def run_speed_loop(dut, pt: dict) -> None:
    """Closed loop with the RTL in it: motor (svpwm_model.motor, driven by the RTL's gate edges with dead
    time resolved by the current sign) + speed controller (``ctrl``: "slip" = SlipPISpeed, the
    slip-regulated loop, default; "avr495" = PISpeed; ``ctrl_args``: its parameters), evaluated at every
    carrier valley from the edges the RTL has produced so far; the result sets the frequency input sampled
    at the next peak.  The core runs in V/f mode (mode_i = 1): it computes m from the frequency word with
    the law's boost / slope / m_max words (motor.vf_words, set once before the start).
    Afterwards the golden model replays the recorded inputs and must equal the RTL on every edge."""
    import sys

    from tqdm import tqdm

    from svpwm_model import motor as M
    from svpwm_tb import RtlRun, _squash

    t_test = time.perf_counter()
    out_dir = Path(os.environ.get("SVPWM_DEMO_OUT", "."))
    out_dir.mkdir(parents=True, exist_ok=True)
    P, dt = int(pt["period"]), int(pt["dt"])
    n_per = int(round(pt["t_end_s"] * F_CLK / (2 * P)))
    d = dut
    tb = CoreTB(dut)
    mot = M.InverterMotor(gates=dt > 0, trace=True, trace_every=int(pt.get("trace_every", 4)))
    loop = M.SpeedLoop(ctrl=M.make_speed_ctrl(pt.get("ctrl", "slip"), **pt.get("ctrl_args", {})),
                       every=int(pt.get("every", 1)))
    vf_in = loop.core_inputs()             # VF mode (mode_i = 1) + the law's words, constant for the run
    fw = loop.update(0, mot)
    idle = Inputs(freq=fw, period=P, dt=dt, **vf_in)
    inputs = [idle]
    await tb.reset(idle)
    tb.model.idle(tb.idle_cycles)
    tb.set_inputs(idle)
    await RisingEdge(d.clk)
    d.en_i.value = 1
    tb.t0 = cocotb.utils.get_sim_time("ns")
    mon: list = []
    task = cocotb.start_soon(tb._monitor(mon))
    upd_cycles: list = []
    task_upd = cocotb.start_soon(tb._updates(upd_cycles))
    await FallingEdge(d.clk)
    rtl = RtlRun(valley=[fixed.START_DELAY])     # the first valley: the core's first running clock
    k_mon = 0
    t_sim0 = time.perf_counter()
    bar = tqdm(total=n_per, desc="speed loop (RTL in the loop, Verilator)", unit="period", file=sys.stderr,
               mininterval=2.0, dynamic_ncols=False, ncols=100)
    for n in range(1, n_per + 1):
        await RisingEdge(d.peak_o)               # peak of period n - 1 (CoreTB.run records the same values)
        await ReadOnly()
        rtl.cmp_peak.append(tb._read_cmp() if int(d.running_o.value) else None)
        await RisingEdge(d.valley_o)
        await ReadOnly()
        c = tb._cycle()
        rtl.valley.append(c)
        new = mon[k_mon:]
        k_mon = len(mon)
        mot.push([(cy, w & 0x3F) if dt > 0 else (cy, w >> 6) for cy, w in new])
        mot.advance_to(c)
        bar.update(1)
        if n == n_per:
            break
        rtl.cmp.append(tb._read_cmp())
        rtl.sector.append(int(d.sector_o.value))
        rtl.period.append(int(d.period_o.value))
        rtl.running.append(int(d.running_o.value))
        rtl.sat.append(bool(int(d.sat_o.value)))
        fw = loop.update(c, mot)
        u = Inputs(freq=fw, period=P, dt=dt, **vf_in)
        inputs.append(u)
        await FallingEdge(d.clk)
        tb.set_inputs(u)
    bar.close()
    await FallingEdge(d.clk)
    t_sim = time.perf_counter() - t_sim0
    task.cancel()
    task_upd.cancel()
    exp = tb.model.run(idle, inputs, n_per)
    rtl.updates = [cy for cy in upd_cycles if cy < exp.end]
    words = [(cy, w) for cy, w in mon if cy < exp.end]
    rtl.pole_edges = _squash([(cy, w >> 6) for cy, w in words])
    rtl.gate_edges = _squash([(cy, w & 0x3F) for cy, w in words])
    fails = []
    try:
        tb.compare(rtl, exp)
        eq = True
    except AssertionError as e:
        eq = False
        fails.append(f"RTL != model: {e}")
    try:
        tb.check_harness()
    except AssertionError as e:
        fails.append(str(e))
    lg = loop.log.as_arrays()
    tt, ii, ww = mot.trace.arrays()
    npz = out_dir / f"{pt['name']}.npz"
    np.savez_compressed(npz, trace_t=tt, trace_i=ii, trace_wm=ww, **{f"log_{k}": v for k, v in lg.items()})
    res = dict(point=pt, sim=getattr(cocotb, "SIM_NAME", "?"), n_periods=n_per, cycles=exp.end,
               sim_wall_s=t_sim, cycles_per_s=exp.end / t_sim, rtl_equals_model=eq,
               gate_edges=len(rtl.gate_edges), pole_edges=len(rtl.pole_edges), npz=str(npz), failures=fails,
               inverter="gate edges, dead time resolved by current sign" if dt > 0 else "pole edges (ideal)",
               final_speed_rpm=mot.speed_rpm(), core_mode="vf (mode_i = 1): m computed by the core",
               vf_words=dict(boost=vf_in["vf_boost"], slope=vf_in["vf_slope"], m_max=vf_in["vf_mmax"]),
               test_wall_s=time.perf_counter() - t_test, ok=not fails)
    (out_dir / f"{pt['name']}.json").write_text(json.dumps(res, indent=2) + "\n")
    dut._log.info("%s: %d periods, %d cycles in %.1f s, RTL == model: %s", pt["name"], n_per, exp.end, t_sim, eq)
    assert not fails, "\n".join(fails)


def dtc_start(pt: dict, fw: int, lead: int) -> dict:
    """Operating point and start state of a dead-time run (run_dtc_point): motor.dtc_start for the point."""
    from svpwm_model import motor as M
    return M.dtc_start(fw, pt["m"], int(pt["period"]), int(pt["dt"]), bool(pt.get("dtc")), pt["t_load"], lead,
                       F_CLK)


def isign_of(currents) -> int:
    """isign_i word {c, b, a} of the phase currents: bit k = 1 for a negative current (into the leg)."""
    return sum(1 << k for k, i in enumerate(currents) if i < 0)


async def run_dtc_point(dut, pt: dict) -> None:
    """Dead-time run with the motor model in the loop (issue 15 item 5(a)).

    The core runs at (f_hz, m, P) with dead time ``dt`` and compensation ``dtc`` (dtc_en_i); the motor
    (svpwm_model.motor.InverterMotor, gates=True: the pole of a leg whose gates are both off is set by its
    current's sign, fixed speed) follows the RTL's gate edges as the run goes: at every update's sample point
    (upd_i = valley: once per carrier period, at S - 1 = t_{n+1} - lead - 1) the test wakes at the falling
    clock edge of S - 2, advances the motor over the gate edges the RTL has produced so far to the start of
    S - 1, and drives the three current signs onto isign_i, where the core samples them at the end of S - 1.
    The same value goes into that update's model inputs (Inputs.isign), so the golden model, replaying the
    recorded inputs afterwards, must equal the RTL on every edge (asserted; isign_i is driven in the runs
    without compensation too, where the core ignores it).  The run lasts ``warmup_revs`` revolutions
    (the motor's start transient; see dtc_start) plus the analysed window of ``revs`` revolutions."""
    from dataclasses import replace

    from svpwm_model import motor as M
    from svpwm_model import spectrum as S
    from svpwm_tb import parse_record

    t_test = time.perf_counter()
    out_dir = Path(os.environ.get("SVPWM_DEMO_OUT", "."))
    out_dir.mkdir(parents=True, exist_ok=True)
    d = dut
    P, dt, dtc = int(pt["period"]), int(pt["dt"]), int(bool(pt.get("dtc")))
    fw, mw = fixed.freq_word(pt["f_hz"]), fixed.m_word(pt["m"])
    lead = fixed.SAMPLE_LEAD
    f1 = fw / (6 * (1 << fixed.PHASE_WIDTH))
    n_fund = int(pt.get("revs", 1))
    T = n_fund / abs(f1)
    k0 = 1 + int(math.ceil(pt.get("warmup_revs", 1) / abs(f1) / (2 * P)))   # first valley of the window
    t0 = fixed.START_DELAY + 2 * P * k0 + 1
    n_per = int(math.ceil((t0 + T - fixed.START_DELAY) / (2 * P))) + 2
    st = dtc_start(pt, fw, lead)
    mot = M.InverterMotor(st["mp"], gates=True, fixed_speed=True, h_max=10e-6, trace=True)
    mot.set_state(st["ps"], st["pr"], st["wm"])
    mot.t = st["t_start"]
    base = Inputs(freq=fw, m=mw, period=P, dt=dt, dtc=dtc)
    tb = CoreTB(dut)
    await tb.reset(base)
    tb.model.idle(tb.idle_cycles)
    tb.set_inputs(base)
    await clock_cycles(d.clk, 2)
    d.en_i.value = 1
    tb.t0 = cocotb.utils.get_sim_time("ns")
    await FallingEdge(d.clk)
    lines: list = []
    inputs: list[Inputs] = []
    t_sim0, cpu0 = time.perf_counter(), time.process_time()
    t_val = fixed.START_DELAY
    for n in range(n_per):
        c = t_val + 2 * P - lead - 2                  # sample clock S - 1 = c + 1 of the update at t_{n+1}
        await tb._to_cycle(c)
        await FallingEdge(d.clk)
        new = tb._rec_lines()
        lines += new
        mot.push([(cy, int(r[2], 16) & 0x3F) for r in new if r[0] == "M"
                  for cy in (int(round(int(r[1]) - tb.t0)) // CLK_NS,) if cy >= 0])
        if c + 1 > mot.t:
            mot.advance_to(c + 1)
        u = replace(base, isign=isign_of(mot.phase_currents()))
        inputs.append(u)
        if u != base or n == 0:
            d.isign_i.value = u.isign
        t_val += 2 * P
    await tb._to_cycle(t_val)
    await FallingEdge(d.clk)
    t_sim, cpu = time.perf_counter() - t_sim0, time.process_time() - cpu0
    lines += tb._rec_lines()
    tb.rec.close()
    exp = tb.model.run(base, inputs, n_per)
    rtl = parse_record(lines, tb.t0, tb.cmp_width, n_per, exp.end)
    mot.push([(cy, w) for cy, w in rtl.gate_edges if cy >= mot.t])   # the edges after the last wake-up
    mot.advance_to(exp.end)
    fails: list[str] = []
    res: dict = dict(point=pt, sim=getattr(cocotb, "SIM_NAME", "?"), freq_word=fw, m_word=mw,
                     f_out_hz_exact=f1 * F_CLK, f_sw_hz=F_CLK / (2 * P), n_periods=n_per, cycles=exp.end,
                     sim_wall_s=t_sim, sim_cpu_s=cpu, cycles_per_s=exp.end / t_sim, sample_lead=lead,
                     isign_at="sample clock S - 1 of every update (once per carrier period, upd_i = valley)",
                     motor=dict(slip=st["slip"], speed_rpm=st["speed_rpm"], t_load_nm=pt["t_load"],
                                start_cycle=st["t_start"], dead_time_loss_v=st["v_loss_v"],
                                start_v_eff_over_cmd=st["v_eff_over_cmd"]),
                     window=dict(t0=t0, T=T, n_fund=n_fund, warmup_periods=k0 - 1,
                                 warmup_s=(t0 - 1 - fixed.START_DELAY) / F_CLK),
                     isign_changes=sum(1 for a, b in zip(inputs, inputs[1:]) if a.isign != b.isign),
                     gate_edges=len(rtl.gate_edges), pole_edges=len(rtl.pole_edges), failures=fails)
    compare_into(tb, rtl, exp, res, fails)
    pin_checks(tb, rtl, exp, res, fails)
    # Table I on the core's pole words: with the compensation two phases within a dead time of each other
    # and with opposite currents may cross (fixed.dtc_shift), so it is reported, and checked only without
    seq = check_table_i(rtl.pole_edges, rtl.valley, [None] + rtl.sector)
    res["table_i"] = dict(periods=seq.periods, with_skipped_states=seq.with_skips, failures=len(seq.failures),
                          first_failures=seq.failures[:5], checked=not dtc)
    if not dtc and not seq.ok:
        fails.append("Table I: " + ("; ".join(seq.failures[:3]) or "no period checked"))
    if dtc:          # the poles the motor sees (resolved by the current sign): reported
        sr = check_table_i(mot.effective, rtl.valley, [None] + rtl.sector)
        res["table_i_resolved"] = dict(periods=sr.periods, with_skipped_states=sr.with_skips,
                                       failures=len(sr.failures), first_failures=sr.failures[:5])
    hd = fixed.dtc_amounts(dt, dt, bool(dtc))[0]
    worst, at = duty_error(exp, isign=[None] + [u.isign for u in inputs], hd=hd)
    res["worst_abs_c_minus_ideal_counts"] = worst
    res["worst_at_period"] = at
    if worst > 1.0:
        fails.append(f"worst |C - C_ideal (+- hd)| = {worst:.3f} counts > 1")

    # ---- voltage seen by the motor (poles resolved by the current sign) and phase current ------------
    f_sw = F_CLK / (2 * P)
    jmax = int(3 * f_sw * T / F_CLK)
    eff = S.spectra_from_edges(mot.effective, t0, T, n_fund, jmax, F_CLK)
    core = S.spectra_from_edges(rtl.pole_edges, t0, T, n_fund, jmax, F_CLK)
    fig_line = S.figures(eff.line[0], n_fund, T, F_CLK, f_sw).as_dict()
    tt, ii, _ = mot.trace.arrays()
    ci = S.current_spectrum(tt, ii.real, t0, T, n_fund)
    res.update(line=fig_line, pole=S.figures(eff.pole[0], n_fund, T, F_CLK, f_sw).as_dict(),
               core_pole_word_line=S.figures(core.line[0], n_fund, T, F_CLK, f_sw).as_dict(),
               line_fundamental_commanded=pt["m"],
               line_fundamental_rel_err=fig_line["fundamental"] / pt["m"] - 1,
               i1_rms=float(abs(ci[n_fund]) / math.sqrt(2)), i_thd=S.current_thd(ci, n_fund))
    # ---- edges, resolved poles, current trace for the report's plots -----------------------------------
    npz = out_dir / f"{pt['name']}.npz"
    keep = tt >= t0 - 2 * P
    np.savez_compressed(npz, effective=np.asarray(mot.effective, dtype=np.int64).reshape(-1, 2),
                        pole_edges=np.asarray(rtl.pole_edges, dtype=np.int64).reshape(-1, 2),
                        valley=np.asarray(rtl.valley, dtype=np.int64),
                        isign=np.asarray([u.isign for u in inputs], dtype=np.int64),
                        trace_t=tt[keep], trace_i=ii[keep], t0=t0, T=T, n_fund=n_fund, freq_word=fw, dt=dt,
                        dtc=dtc, period=P)
    res["npz"] = str(npz)
    res["test_wall_s"] = time.perf_counter() - t_test
    res["ok"] = not fails
    (out_dir / f"{pt['name']}.json").write_text(json.dumps(res, indent=2, default=float) + "\n")
    dut._log.info("%s: %d periods in %.1f s, line low-order max %.1f dBc, WTHD %.4f %%, i THD %.2f %%, "
                  "RTL == model: %s", pt["name"], n_per, t_sim, fig_line["low_order_max_dbc"],
                  100 * fig_line["wthd"], 100 * res["i_thd"], res["rtl_equals_model"])
    assert not fails, "\n".join(fails)


async def run_foc_point(dut, pt: dict) -> None:
    """Closed FOC current loop with the RTL in it (issue 30 item 3): foc_loop.run_foc (the PMSM of
    svpwm_model.pmsm on the RTL's gate edges, a 12-bit ADC at the core's trigger, a dq PI, theta / v_d / v_q /
    isign_i written before the core's sample clock; RTL == model on every edge, the pin checker, the leg
    check, the ADC trigger instant), then foc_loop.analyse: step responses, dq ripple, phase-current THD, the
    low-side window at the valley. Writes <name>.json and <name>.npz (the per-period log and the motor's
    current trace for the report's plots)."""
    from foc_loop import analyse, run_foc

    out_dir = Path(os.environ.get("SVPWM_DEMO_OUT", "."))
    out_dir.mkdir(parents=True, exist_ok=True)
    res, a = await run_foc(dut, pt)
    res["metrics"] = analyse(res, a, pt)
    npz = out_dir / f"{pt['name']}.npz"
    np.savez_compressed(npz, **a)
    res["npz"] = str(npz)
    res["ok"] = not res["failures"]
    (out_dir / f"{pt['name']}.json").write_text(json.dumps(res, indent=2, default=float) + "\n")
    st = res["metrics"].get("steady") or {}
    dut._log.info("%s: %d periods in %.1f s, RTL == model: %s, i THD %s %%", pt["name"], res["n_periods"],
                  res["sim_wall_s"], res["rtl_equals_model"],
                  f"{100 * st['i_thd']:.2f}" if st else "-")
    assert not res["failures"], "\n".join(res["failures"])


def _make_test(pt: dict):
    async def point_test(dut):
        if pt.get("kind") == "foc":
            await run_foc_point(dut, pt)
        elif pt.get("kind") == "speed_loop":
            await run_speed_loop(dut, pt)
        elif pt.get("kind") == "dtc":
            await run_dtc_point(dut, pt)
        else:
            await run_point(dut, pt)

    point_test.__name__ = point_test.__qualname__ = pt["name"]
    point_test.__doc__ = pt.get("title") or pt["name"]
    return cocotb.test(point_test)


for _pt in json.loads(os.environ.get("SVPWM_DEMO_POINTS", "[]")):
    if not str(_pt["name"]).isidentifier():
        raise ValueError(f"operating point name {_pt['name']!r} is not a Python identifier")
    if _pt["name"] in globals():
        raise ValueError(f"operating point name {_pt['name']!r} clashes with a name in demo_runs.py")
    globals()[_pt["name"]] = _make_test(_pt)
