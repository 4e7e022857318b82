# SPDX-License-Identifier: Apache-2.0
"""A closed FOC current loop around the RTL core (tb_svpwm_core.sv), as a third party would build it.

Used by tb/cocotb/demo/demo_runs.py (run_foc_point, `make report`) and tb/cocotb/svpwm_foc/test_svpwm_foc.py
(`make test`).  Per carrier period n:

1. the ADC samples the three phase currents of the PMSM (svpwm_model.pmsm, driven by the RTL's gate edges,
   dead time through the diodes) at the sample instant ``sample_cycle`` (default: the valley t_n, where the
   core's ``adc_trig_o`` pulses with ``adc_trig_i`` = 2'b01; checked against the pin every period);
2. the dq PI (svpwm_model.foc.DqPi) computes (v_d, v_q) from the sampled currents, Park-transformed at the
   rotor angle of the sample instant;
3. theta_i (the angle advanced to the centre of the pulses the update produces), v1_i = v_d, v2_i = v_q
   (Q2.14) and isign_i (the measured currents' signs through a hysteresis band) are written at the falling
   clock edge before the core's sample clock T - L - 1 of the update they feed (T: the next update point
   after the sample; for a valley sample and a peak update, P - L - 1 clocks after the trigger: the README's
   deadline, met at its last clock).

The written words are recorded with the cycle they reach the ports; afterwards the golden model replays them
(inputs / peak_inputs: the port values in the clocks the core samples) and must equal the RTL on every edge.

The sample instant is one function of the carrier (``sample_cycle``: a count and a direction): programmable
ADC trigger points only change that and the ``adc_trig_i`` word.
"""
from __future__ import annotations

import bisect
import math
import time
from dataclasses import asdict, replace

import cocotb
import cocotb.utils
import numpy as np
from cocotb.triggers import FallingEdge, RisingEdge

from clocks import clock_cycles
from svpwm_model import adc as ADC
from svpwm_model import fixed, foc
from svpwm_model import pmsm as PM
from svpwm_model.core import Inputs
from svpwm_tb import CLK_NS, CoreTB, compare_into, parse_record, pin_checks

F_CLK = fixed.F_CLK_DEFAULT


def sample_cycle(t_n: int, period: int, count: int = 0, up: bool = True) -> int:
    """The clock of carrier period n (valley t_n, half period P) at which the carrier is at ``count``
    counting up (from t_n) or down (towards t_n + 2P): the ADC sample instant.  Valley: (0, up); peak: (P, up)."""
    if not 0 <= count <= period:
        raise ValueError(f"sample count {count} outside 0 .. {period}")
    return t_n + count if up else t_n + 2 * period - count


def next_update(s: int, t_n: int, period: int, lead: int, upd: int) -> int:
    """The first update point T after a sample at cycle s whose input sample clock T - L - 1 is not before s
    (so the sample is complete when the inputs are taken): a peak t + P (upd_i = peak / both) or a valley
    (valley / both), constant P."""
    pts = []
    for k in range(3):
        t = t_n + 2 * period * k
        if upd in (fixed.UPD_VALLEY, fixed.UPD_BOTH) and k:
            pts.append(t)
        if upd in (fixed.UPD_PEAK, fixed.UPD_BOTH):
            pts.append(t + period)
    return min(T for T in pts if T - lead - 1 >= s)


def ref_at(steps, t: float) -> float:
    """Piecewise-constant profile [[t0, x0], [t1, x1], ...] at time t (x0 before t0)."""
    x = steps[0][1]
    for ts, v in steps:
        if t >= ts:
            x = v
    return x


def lowside_windows(gate_edges, valleys, ph: int) -> list[int]:
    """For each valley the length (clocks) of phase ph's low-side on-interval containing it (0: off)."""
    bit = 1 << (ph + 3)
    t = [c for c, _ in gate_edges]
    out = []
    for v in valleys:
        k = bisect.bisect_right(t, v) - 1
        if k < 0 or not gate_edges[k][1] & bit:
            out.append(0)
            continue
        a = k
        while a > 0 and gate_edges[a - 1][1] & bit:
            a -= 1
        b = k + 1
        while b < len(gate_edges) and gate_edges[b][1] & bit:
            b += 1
        if b >= len(gate_edges):
            out.append(-1)                     # runs past the end: not measured
            continue
        out.append(gate_edges[b][0] - gate_edges[a][0])
    return out


async def run_foc(dut, pt: dict) -> tuple[dict, dict]:
    """Run one closed-loop point; returns (results, arrays). ``pt`` keys (defaults in brackets):
    period [1536], dt [0] (clocks), dtc [0] (dtc_en_i), speed_rpm, fixed_speed [True], load [[[0, 0]]]
    (N m profile, free speed), iq_steps ([[t_s, iq / rated], ...]), id_ref [0] (/ rated), t_end_s,
    hyst [0] (isign band / rated current), isign_from ["sample": the sampled currents; "advanced": the sampled
    current vector turned to the pulses' centre], sample [[0, True]] (count, up), upd ["peak"|"valley"],
    adc ({Adc12 fields}), delay_periods [1.5] (PI tuning), decouple [True], pi_sign [1], theta_dir [1]
    (-1: the angle written mirrored: a broken convention, for the check that the tests can fail),
    shunts [None] (low-side shunts, feature adc: {"win_min": clocks}: the ADC starts at trigger point 0, set
    to the sample's count and direction, one clock after the carrier is there (adc_pt_o); a phase whose
    low-side window the core reports shorter than win_min (win_ok_o) reads no current, the phase the core
    names (win_recon_o) is taken as minus the other two when they are readable, and with two phases
    unreadable the last measured currents are kept)."""
    t_test = time.perf_counter()
    d = dut
    P, dt, dtc = int(pt.get("period", 1536)), int(pt.get("dt", 0)), int(bool(pt.get("dtc")))
    upd = {"peak": fixed.UPD_PEAK, "valley": fixed.UPD_VALLEY}[pt.get("upd", "peak")]
    count, up = pt.get("sample", [0, True])
    tb = CoreTB(dut)
    lead = tb.model.lead
    mp = PM.PmsmParams(**pt.get("motor", {}))
    ts = 2 * P / F_CLK
    n_per = int(round(pt["t_end_s"] / ts))
    gains = foc.technical_optimum(mp.R, mp.Ld, mp.Lq, ts, float(pt.get("delay_periods", 1.5)))
    v_max = mp.udc / math.sqrt(3)
    pi = foc.DqPi(gains, ts, v_max, decouple=bool(pt.get("decouple", True)), R=mp.R, Ld=mp.Ld, Lq=mp.Lq,
                  psi_m=mp.psi_m, sign=float(pt.get("pi_sign", 1)))
    adc = foc.Adc12(**pt.get("adc", {}))
    sd = foc.SignDetector(float(pt.get("hyst", 0.0)) * mp.i_rated)
    theta_dir = int(pt.get("theta_dir", 1))
    w_m0 = float(pt["speed_rpm"]) * 2 * math.pi / 60
    fixed_speed = bool(pt.get("fixed_speed", True))
    load = pt.get("load", [[0.0, 0.0]])
    iq_steps = [[t, x * mp.i_rated] for t, x in pt["iq_steps"]]
    id_ref = float(pt.get("id_ref", 0.0)) * mp.i_rated
    shunts = pt.get("shunts")
    trig_word = 0 if shunts else 1 if (count, up) == (0, True) else 2 if count == P else 0
    # with shunts the sample is the point's pulse, one clock after the carrier is at (count, up)
    s_off = 1 if shunts else 0

    base = Inputs(mode=fixed.MODE_DQ, period=P, dt=dt, dtc=dtc, upd=upd, vsc=1)
    if shunts:
        base = replace(base, adc_pt=(ADC.Point(True, not up, count), ADC.Point()),
                       win_min=int(shunts["win_min"]))
    await tb.reset(base)
    tb.model.idle(tb.idle_cycles)
    tb.set_inputs(base)
    d.adc_trig_i.value = trig_word
    await clock_cycles(d.clk, 2)
    d.en_i.value = 1
    tb.t0 = cocotb.utils.get_sim_time("ns")
    trig: list[int] = []

    async def watch_trig():
        while True:
            await RisingEdge(d.adc_trig_o)
            trig.append(tb._cycle())
            if shunts:
                assert int(d.adc_pt_o.value) == 1, f"adc_trig_o without point 0 at cycle {tb._cycle()}"

    task_trig = cocotb.start_soon(watch_trig())
    await FallingEdge(d.clk)

    # the motor starts at the first update (the gates switch from the clock after it); before, all gates
    # are off and the model has no open-phase state (pmsm.py): no current flows at these speeds
    t_first = next_update(sample_cycle(fixed.START_DELAY, P, count, up) + s_off, fixed.START_DELAY, P, lead,
                          upd)
    mot = PM.InverterPmsm(mp, gates=True, fixed_speed=fixed_speed, t_load=ref_at(load, 0.0),
                          h_max=float(pt.get("h_max", 5e-6)))
    th0 = math.radians(float(pt.get("theta0_deg", 0.0)))
    mot.set_state(0.0, 0.0, th0 + mp.p * w_m0 * t_first / F_CLK, w_m0)
    mot.t = t_first

    lines: list = []
    pushed = -1                                   # the last edge cycle given to the motor
    writes: list[tuple[int, Inputs]] = []         # (first cycle on the ports, inputs)
    keys = ("t", "iq_ref", "id_ref", "id", "iq", "id_meas", "iq_meas", "vd", "vq", "v_pu", "pi_sat", "isign",
            "rpm", "theta", "t_load", "win_ok", "win_recon", "i_source")
    i_prev = (0.0, 0.0, 0.0)
    log: dict[str, list] = {k: [] for k in keys}
    t_sim0, cpu0 = time.perf_counter(), time.process_time()
    t_n = fixed.START_DELAY
    t_end = fixed.START_DELAY + 2 * P * n_per
    for n in range(n_per):
        s = sample_cycle(t_n, P, count, up) + s_off
        T = next_update(s, t_n, P, lead, upd)
        w = T - lead - 2                           # written at this clock's falling edge: on the port at T - L - 1
        if w + 1 >= t_end:                         # feeds an update after the run
            break
        await tb._to_cycle(w)
        await FallingEdge(d.clk)
        new = tb._rec_lines()
        lines += new
        ev = [(cy, int(r[2], 16) & 0x3F) for r in new if r[0] == "M"
              for cy in (int(round(int(r[1]) - tb.t0)) // CLK_NS,) if cy >= mot.t]
        mot.push(ev)
        pushed = ev[-1][0] if ev else pushed
        t_s = s / F_CLK
        if s > mot.t:
            mot.advance_to(s)
        th_s = mot.th - mot.w_e() * (mot.t - s) / F_CLK        # (before the motor starts: extrapolated)
        i_true = complex(mot.i_d, mot.i_q) if s >= mot.t else 0j     # the motor is at s (or not started)
        i_abc = mot.phase_currents() if s >= mot.t else (0.0, 0.0, 0.0)
        i_m = adc.amps(adc.convert(i_abc))
        w_ok, w_rc, src = 7, 0, 0                  # src: 0 all read, 1 one reconstructed, 2 held
        if shunts:
            # the report of the values active at s (no update between s and w: T - L - 2 >= s)
            w_ok, w_rc = int(d.win_ok_o.value), int(d.win_recon_o.value)
            others = [ph for ph in range(3) if ph != w_rc]
            if pt.get("no_recon"):                 # (broken on purpose: unreadable phases read 0 A)
                i_m, src = tuple(x if w_ok >> ph & 1 else 0.0 for ph, x in enumerate(i_m)), 0
            elif all(w_ok >> ph & 1 for ph in others):
                i_m = ADC.reconstruct(tuple(x if w_ok >> ph & 1 else 0.0 for ph, x in enumerate(i_m)),
                                      ADC.Window((0, 0, 0), (0, 0, 0), w_ok, w_rc))
                src = int(not w_ok >> w_rc & 1)
            else:
                i_m, src = i_prev, 2
        i_prev = i_m
        i_dq = foc.park(foc.clarke(i_m[0], i_m[1]), th_s)
        w_e = mot.w_e()
        iq_r = ref_at(iq_steps, t_s)
        vd, vq = pi.step(id_ref, iq_r, i_dq.real, i_dq.imag, w_e)
        th_c = th_s + w_e * (T + P - s) / F_CLK                 # the pulses' centre: P after the update point
        if pt.get("isign_from", "sample") == "advanced":
            i_c = i_dq * complex(math.cos(th_c), math.sin(th_c))
            i_sgn = (i_c.real, (i_c * PM.A.conjugate()).real, (i_c * PM.A).real)
        else:
            i_sgn = i_m
        u = replace(base, theta=foc.theta_word(theta_dir * th_c), v1=foc.v_word(vd, mp.udc),
                    v2=foc.v_word(vq, mp.udc), isign=sd.update(i_sgn))
        d.theta_i.value = u.theta
        d.v1_i.value = u.v1 & 0xFFFF
        d.v2_i.value = u.v2 & 0xFFFF
        d.isign_i.value = u.isign
        writes.append((w + 1, u))
        if not fixed_speed:
            mot.t_load = ref_at(load, t_s)
        for k, v in (("t", t_s), ("iq_ref", iq_r), ("id_ref", id_ref), ("id", i_true.real), ("iq", i_true.imag),
                     ("id_meas", i_dq.real), ("iq_meas", i_dq.imag), ("vd", vd), ("vq", vq),
                     ("v_pu", math.hypot(vd, vq) / v_max), ("pi_sat", pi.sat), ("isign", u.isign),
                     ("rpm", mot.speed_rpm()), ("theta", u.theta), ("t_load", mot.t_load), ("win_ok", w_ok),
                     ("win_recon", w_rc), ("i_source", src)):
            log[k].append(v)
        t_n += 2 * P
    await tb._to_cycle(t_end)
    await FallingEdge(d.clk)
    t_sim, cpu = time.perf_counter() - t_sim0, time.process_time() - cpu0
    task_trig.cancel()
    lines += tb._rec_lines()
    tb.rec.close()

    # ---- the golden model replays the port values in the clocks the core samples --------------------
    w_cyc = [c for c, _ in writes]

    def port_at(c: int) -> Inputs:
        k = bisect.bisect_right(w_cyc, c) - 1
        return base if k < 0 else writes[k][1]

    vals = [fixed.START_DELAY + 2 * P * n for n in range(n_per + 1)]
    inputs = [port_at(vals[n + 1] - lead - 1) for n in range(n_per)]
    peak_inputs = [port_at(vals[n] + P - lead - 1) for n in range(n_per)]
    exp = tb.model.run(base, inputs, n_per, peak_inputs=peak_inputs)
    rtl = parse_record(lines, tb.t0, tb.cmp_width, n_per, exp.end)
    mot.push([(cy, w) for cy, w in rtl.gate_edges if cy > max(pushed, mot.t - 1)])
    mot.advance_to(exp.end)

    fails: list[str] = []
    res: dict = dict(point=pt, sim=getattr(cocotb, "SIM_NAME", "?"), n_periods=n_per, cycles=exp.end,
                     period=P, f_sw_hz=F_CLK / (2 * P), sample_lead=lead, sim_wall_s=t_sim, sim_cpu_s=cpu,
                     cycles_per_s=exp.end / t_sim, motor=asdict(mp),
                     gains=dict(kp_d=gains.kp_d, ki_d=gains.ki_d, kp_q=gains.kp_q, ki_q=gains.ki_q,
                                sigma_s=gains.sigma),
                     adc=dict(lsb_a=adc.lsb, i_fs=adc.i_fs, bits=adc.bits), hyst_a=sd.band,
                     isign_changes=sum(1 for a, b in zip(inputs, inputs[1:]) if a.isign != b.isign),
                     gate_edges=len(rtl.gate_edges), failures=fails)
    compare_into(tb, rtl, exp, res, fails)
    pin_checks(tb, rtl, exp, res, fails)
    # the ADC sample instant is the core's trigger (checked where the core has one there: valley / peak, or
    # trigger point 0 with shunts)
    if trig_word or shunts:
        tset = set(trig)
        # (a trigger point fires from the first update on: the samples before it are not checked)
        first = exp.updates[0].load if (shunts and exp.updates) else 0
        smp = [sample_cycle(vals[n], P, count, up) + s_off for n in range(n_per)]
        smp = [c for c in smp if c >= first]
        miss = [c for c in smp if c not in tset]
        res["adc_trig_checked"] = len(smp) - len(miss)
        res["adc_trig_before_first_update"] = n_per - len(smp)
        if miss:
            fails.append(f"ADC sample not at adc_trig_o: cycles {miss[:5]} (adc_trig_o at {trig[:5]} ...)")
    res["sat_periods"] = int(sum(exp.sat))
    if shunts:       # per phase: periods unreadable; periods with one phase reconstructed, with all held
        ok = log["win_ok"]
        res["shunts"] = dict(win_min=int(shunts["win_min"]),
                             unreadable=[sum(1 for x in ok if not x >> ph & 1) for ph in range(3)],
                             reconstructed=sum(1 for x in log["i_source"] if x == 1),
                             held=sum(1 for x in log["i_source"] if x == 2), periods=len(ok))
    res["writes_on_port_cycle_after_trigger"] = sorted({c - sample_cycle(vals[n], P, count, up)
                                                         for n, (c, _) in enumerate(writes)})
    arrays = {k: np.asarray(v) for k, v in log.items()}
    tt, ii, th, wm = mot.trace.arrays()
    arrays.update(trace_t=tt, trace_i=ii, trace_th=th, trace_wm=wm, valley=np.asarray(rtl.valley),
                  gate_edges=np.asarray(rtl.gate_edges, dtype=np.int64).reshape(-1, 2))
    res["test_wall_s"] = time.perf_counter() - t_test
    return res, arrays


def analyse(res: dict, a: dict, pt: dict) -> dict:
    """Step responses (true i_q at the sample instants), dq ripple and phase-current THD over the steady
    window, the low-side window around the valley (the shunts' sampling window) and the modulation depth."""
    from svpwm_model import spectrum as S

    i_r = res["motor"]["i_rated"]
    t = a["t"]
    out: dict = {"steps": []}
    steps = [[ts, x * i_r] for ts, x in pt["iq_steps"]]
    t_end = float(t[-1])
    for k in range(1, len(steps)):
        t_a = steps[k][0]
        t_b = steps[k + 1][0] if k + 1 < len(steps) else t_end
        sr = foc.step_response(t, a["iq"], t_a, steps[k - 1][1], steps[k][1], t_b)
        sr.update(at_s=t_a, iq_from=steps[k - 1][1], iq_to=steps[k][1])
        out["steps"].append(sr)
    win = pt.get("steady")                      # [t_start_s, electrical revolutions]
    if win:
        w_e = res["motor"]["p"] * float(pt["speed_rpm"]) * 2 * math.pi / 60
        n_fund = int(win[1])
        t0 = float(win[0]) * F_CLK
        T = n_fund * 2 * math.pi / abs(w_e) * F_CLK
        tt, ii, th = a["trace_t"], a["trace_i"], a["trace_th"]
        grid = t0 + np.arange(1 << 15) / (1 << 15) * T
        ia = np.interp(grid, tt, ii.real)
        dq = np.interp(grid, tt, (ii * np.exp(-1j * th)).real) + 1j * np.interp(grid, tt, (ii * np.exp(-1j * th)).imag)
        c = S.spectrum_of_samples(ia, n_fund)
        sel = (t >= t0 / F_CLK) & (t < (t0 + T) / F_CLK)
        val = a["valley"]
        vsel = [int(v) for v in val if t0 <= v < t0 + T]
        ge = [(int(c), int(x)) for c, x in a["gate_edges"]]
        wins = [lowside_windows(ge, vsel, ph) for ph in range(3)]
        per = [min(x) for x in zip(*wins)] if vsel else []
        out["steady"] = dict(t0_s=t0 / F_CLK, T_s=T / F_CLK, n_fund=n_fund, f_e_hz=abs(w_e) / (2 * math.pi),
                             i_thd=S.current_thd(c, n_fund), i1_peak=float(abs(c[n_fund])),
                             id_mean=float(dq.real.mean()), iq_mean=float(dq.imag.mean()),
                             id_ripple_rms=float(dq.real.std()), iq_ripple_rms=float(dq.imag.std()),
                             v_pu_max=float(a["v_pu"][sel].max()), v_pu_mean=float(a["v_pu"][sel].mean()),
                             pi_limited_periods=int(a["pi_sat"][sel].sum()), periods=int(sel.sum()),
                             lowside_window_min_clocks=int(min(per)) if per else None,
                             lowside_window_mean_min_clocks=float(np.mean(per)) if per else None)
    out["v_pu_max"] = float(a["v_pu"].max())
    out["pi_sat_periods"] = int(a["pi_sat"].sum())
    return out
