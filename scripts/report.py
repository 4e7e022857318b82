#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Analysis, plots and report of `make demo` / `make report` (called by scripts/demo.py after the RTL runs).

Inputs, in the run's output directory (build/demo/ for `make demo`, build/report/ for `make report`):
<point>.json + <point>_edges.npz (RTL pole/gate edges from tb/cocotb/demo/demo_runs.py), speed_loop_vf.npz
(the closed loop with the RTL in it) and dtc_<point>_<run>.npz (the dead-time compensation runs: RTL with the
motor model in the loop); a figure whose runs are not there is left out.  Outputs in the same directory:
fig_*.png, metrics.json, report.md.  Can be re-run alone: `.venv/bin/python scripts/report.py [DIR]`
(PYTHONPATH=model; DIR default build/report).
"""
from __future__ import annotations

import json
import math
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "model"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from tqdm import tqdm  # noqa: E402

from svpwm_model import fixed  # noqa: E402
from svpwm_model import motor as M  # noqa: E402
from svpwm_model import spectrum as S  # noqa: E402

F_CLK = fixed.F_CLK_DEFAULT
STATE_NAME = {w: f"{w & 1}{(w >> 1) & 1}{(w >> 2) & 1}" for w in range(8)}     # word {c,b,a} -> "abc"
T_LOAD = 2.5          # N m at the Minas points (half rated torque)


def f1_of(fw: int) -> float:
    return fw / (6 * (1 << fixed.PHASE_WIDTH))          # cycles^-1


def n_fund_for(f_hz: float) -> int:
    return 2 if f_hz >= 20 else 1


def load_point(out: Path, name: str):
    r = json.loads((out / f"{name}.json").read_text())
    z = np.load(out / f"{name}_edges.npz")
    return r, z


def edges_list(arr) -> list[tuple[int, int]]:
    return [(int(c), int(w)) for c, w in arr]


# ---- voltage analysis --------------------------------------------------------------------------------
def analyse_voltage(r: dict, z, h_mult: float = 3.0) -> dict:
    """RTL (pole states = dead time off), ideal exact and ideal rounded spectra over N revolutions."""
    pt = r["point"]
    P = int(pt["period"])
    fw = int(z["freq_word"])
    f1 = f1_of(fw)
    f_sw = F_CLK / (2 * P)
    n = n_fund_for(abs(pt["f_hz"]))
    T = n / abs(f1)
    t0 = float(z["valley"][1] + 1)
    if t0 + T > z["valley"][-1] + 1:
        raise RuntimeError(f"{pt['name']}: run shorter than {n} revolution(s)")
    jmax = int(h_mult * f_sw * T / F_CLK)
    rtl = S.spectra_from_edges(edges_list(z["pole_edges"]), t0, T, n, jmax, F_CLK)
    ide = S.ideal_spectra(f1, pt["m"], P, t0, n, jmax, F_CLK)
    rnd = S.ideal_spectra(f1, pt["m"], P, t0, n, jmax, F_CLK, rounding="nearest")
    figs = {}
    for key, sp in (("rtl", rtl), ("ideal", ide), ("ideal_rounded", rnd)):
        figs[key] = dict(line=S.figures(sp.line[0], n, T, F_CLK, f_sw).as_dict(),
                         pole=S.figures(sp.pole[0], n, T, F_CLK, f_sw).as_dict())
    return dict(spectra=dict(rtl=rtl, ideal=ide, ideal_rounded=rnd), figures=figs, t0=t0, T=T, n_fund=n,
                f1_hz=f1 * F_CLK, f_sw=f_sw, jmax=jmax, leakage_bins=S.leakage(n, T, f_sw / F_CLK))


# ---- motor at a fixed operating point ----------------------------------------------------------------
def motor_point(r: dict, z, va: dict, gates: bool) -> dict:
    """Motor at the speed of the equivalent-circuit steady state for T_LOAD (speed held), driven by the RTL's
    pole edges (gates=False: ideal inverter) or gate edges (gates=True: dead time, current-sign diodes)."""
    pt = r["point"]
    mp = M.MotorParams()
    f_hz = va["f1_hz"]
    m = pt["m"]
    v_rms = m * M.UDC / math.sqrt(6)
    slip = M.slip_for_torque(mp, abs(f_hz), v_rms, T_LOAD)
    t0, T = va["t0"], va["T"]
    c = va["spectra"]["rtl"].phase[0, va["n_fund"]]           # v_an fundamental, phase at t0
    v0 = abs(c) * M.UDC * np.exp(1j * np.angle(c))
    if f_hz < 0:
        v0 = np.conj(v0)
    ps, pr = M.steady_state_fluxes(mp, abs(f_hz), v0, slip)
    if f_hz < 0:
        ps, pr = np.conj(ps), np.conj(pr)
    mot = M.InverterMotor(mp, gates=gates, fixed_speed=True, h_max=10e-6)
    mot.set_state(complex(ps), complex(pr), math.copysign((1 - slip) * 2 * math.pi * abs(f_hz) / mp.p, f_hz))
    t_start = int(math.floor(t0))
    ed = z["gate_edges"] if gates else z["pole_edges"]
    mask = 0x3F if gates else 0x7
    from svpwm_model.analysis import word_at
    el = edges_list(ed)
    t_end = int(math.ceil(t0 + T)) + 2
    w0 = word_at(el, t_start) & mask
    win = [(cy, w & mask) for cy, w in el if t_start < cy < t_end]
    # periodic steady state: the window is a whole number of revolutions, so it is replayed PASSES times
    # from the end state of the previous pass (the dead-time voltage error makes the start state inexact)
    passes = 3
    for k in tqdm(range(passes), desc=f"motor {pt['name']} ({'dead time' if gates else 'poles'})",
                  unit="pass", mininterval=1.0, leave=False):
        mot.t, mot.word, mot._eff = t_start, w0, -1
        mot.effective = []
        mot.trace = M.Trace()
        mot.push(win)
        mot.advance_to(t_end)
    tt, ii, _ = mot.trace.arrays()
    ngrid = 1 << 16
    grid = t0 + np.arange(ngrid) / ngrid * T
    ia = np.interp(grid, tt, ii.real)
    ci = S.spectrum_of_samples(ia, va["n_fund"])
    eff = S.spectra_from_edges(mot.effective, t0, T, va["n_fund"], va["jmax"], F_CLK)
    n = va["n_fund"]
    ec = M.equivalent_circuit(mp, abs(f_hz), v_rms, slip)
    return dict(slip=slip, speed_rpm=(1 - slip) * 60 * abs(f_hz) / mp.p, t_load=T_LOAD, grid=grid, ia=ia,
                ci=ci, i1_rms=abs(ci[n]) / math.sqrt(2), i_rms=float(np.sqrt(np.mean(ia ** 2))),
                i_thd=S.figures(ci[: 200 * n + 1], n, T, F_CLK, va["f_sw"]).thd,
                ec_i_rms=ec["i_s_rms"], eff_spectra=eff,
                eff_line=S.figures(eff.line[0], n, T, F_CLK, va["f_sw"]).as_dict(),
                eff_pole=S.figures(eff.pole[0], n, T, F_CLK, va["f_sw"]).as_dict())


# ---- plots -------------------------------------------------------------------------------------------
def db(x, ref):
    return 20 * np.log10(np.maximum(np.abs(x), 1e-12) / ref)


def plot_carrier_period(r, z, path: Path):
    P = int(r["point"]["period"])
    sec, cmp, val = z["sector"], z["cmp"], z["valley"]
    # a period in sector 1 (index 0) with all dwell times non-zero, nearest to theta' = 30 deg
    cands = [i for i in range(len(sec)) if sec[i] == 0 and len(set(cmp[i])) == 3 and min(cmp[i]) > 0]
    ca = np.array([cmp[i] for i in cands])
    i = cands[int(np.argmin(np.abs((ca[:, 1] - ca[:, 0]) - (ca[:, 2] - ca[:, 1]))))]
    n = i + 1
    tn = int(val[n])
    us = 1e6 / F_CLK
    fig, ax = plt.subplots(4, 1, figsize=(10, 7.5), sharex=True, gridspec_kw=dict(height_ratios=[2, 1, 1, 1]))
    tc = np.array([tn, tn + P, tn + 2 * P])
    ax[0].plot((tc - tn) * us, [0, P, 0], "k-", lw=1.2, label="carrier 0 → P → 0")
    for ph, col in zip(range(3), ("C0", "C1", "C2")):
        ax[0].axhline(cmp[i][ph], color=col, ls="--", lw=1, label=f"C_{'abc'[ph]} = {cmp[i][ph]}")
    ax[0].set_ylabel("counter")
    ax[0].legend(loc="center", fontsize=8, ncol=2, bbox_to_anchor=(0.5, 0.45))
    from svpwm_model.analysis import word_at
    el = edges_list(z["pole_edges"])
    xs = np.arange(tn, tn + 2 * P + 2)
    words = np.array([word_at(el, int(x)) for x in xs[:: 4]])
    for ph in range(3):
        ax[ph + 1].step((xs[::4] - tn) * us, (words >> ph) & 1, where="post", color=f"C{ph}")
        ax[ph + 1].set_ylabel(f"pole {'abc'[ph]}")
        ax[ph + 1].set_ylim(-0.2, 1.5)
        ax[ph + 1].set_yticks([0, 1])
    # segments
    bounds = [tn + 1] + sorted({c for c, _ in el if tn + 1 < c < tn + 2 * P + 1}) + [tn + 2 * P + 1]
    dur = {}
    for k, (a, b) in enumerate(zip(bounds, bounds[1:])):
        w = word_at(el, a)
        st = STATE_NAME[w]
        for axx in ax:
            axx.axvline((a - tn) * us, color="0.7", lw=0.6)
        ax[0].text((a + b) / 2 * us - tn * us, P * 1.04, st, ha="center", fontsize=9, fontweight="bold")
        ax[3].text((a + b) / 2 * us - tn * us, 1.25, f"{(b - a)} clk", ha="center", fontsize=7)
        dur.setdefault(st, 0)
        dur[st] += b - a
    ax[0].set_ylim(-P * 0.05, P * 1.15)
    sa = fixed.SECTOR_SEL
    d0 = (dur.get("000", 0) + dur.get("111", 0)) / (2 * P)
    ax[0].set_title(f"One carrier period from the RTL (Fig. 10 point, period {n}, sector 1): seven segments "
                    f"000→100→110→111→110→100→000\n(Minas Fig. 4 / Table I); d_z = {d0:.3f}, "
                    f"d_x = {dur.get('100', 0) / (2 * P):.3f} (100), d_y = {dur.get('110', 0) / (2 * P):.3f} (110); "
                    f"P = {P} clocks, f_sw = 15.625 kHz", fontsize=9)
    ax[-1].set_xlabel("time in the carrier period (µs)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return dict(period=n, cmp=[int(x) for x in cmp[i]], durations_clocks=dur)


def plot_hexagon(points, path: Path):
    fig, ax = plt.subplots(figsize=(7, 7))
    a = 2 / 3
    vert = [a * np.exp(1j * k * np.pi / 3) for k in range(6)]
    names = ["100", "110", "010", "011", "001", "101"]
    hx = np.array(vert + vert[:1])
    ax.plot(hx.real, hx.imag, "k-", lw=1.5)
    for k, v in enumerate(vert):
        ax.plot([0, v.real], [0, v.imag], color="0.6", lw=0.8, ls="--")
        ax.annotate(f"V{k + 1} ({names[k]})", (v.real * 1.08, v.imag * 1.08), ha="center", va="center", fontsize=9)
        mid = 0.45 * np.exp(1j * (k + 0.5) * np.pi / 3)
        ax.text(mid.real, mid.imag, f"sector {k + 1}", ha="center", va="center", fontsize=8, color="0.4")
    th = np.linspace(0, 2 * np.pi, 400)
    ax.plot(np.cos(th) / np.sqrt(3), np.sin(th) / np.sqrt(3), color="0.5", lw=0.8, label="m = 1 (inscribed circle)")
    for (name, r, z), col in zip(points, ("C3", "C0")):
        P = int(r["point"]["period"])
        d = (P - z["cmp"]) / P
        v = 2 / 3 * (d[:, 0] + np.exp(2j * np.pi / 3) * d[:, 1] + np.exp(-2j * np.pi / 3) * d[:, 2])
        ax.plot(v.real, v.imag, ".", ms=1.5, color=col, label=f"{name}: per-period mean vector (RTL)")
    ax.set_aspect("equal")
    ax.set_xlim(-0.85, 0.85)
    ax.set_ylim(-0.8, 0.8)
    ax.set_xlabel("α (units of Udc, amplitude-invariant)")
    ax.set_ylabel("β")
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title("Voltage hexagon, sectors and the reference trajectory\n(per-period average of the RTL's switching pattern)", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_voltage(name, title, va, mo, z, path: Path):
    sp = va["spectra"]
    n = va["n_fund"]
    f = sp["rtl"].freqs / 1e3
    fig, ax = plt.subplots(3, 1, figsize=(11, 10))
    # waveform: pole-to-midpoint over 2 ms (Minas Fig. 9a/10a) with dead time (effective) and ideal
    t0 = va["t0"]
    from svpwm_model.analysis import word_at
    el = edges_list(z["pole_edges"])
    span = min(va["T"], 0.02 * F_CLK)
    xs = t0 + np.linspace(0, span, 6000)
    pa = np.array([word_at(el, int(x)) & 1 for x in xs]) - 0.5
    ax[0].plot((xs - t0) / F_CLK * 1e3, pa * M.UDC, lw=0.5, color="C0", label="v_a0 (pole to DC midpoint, RTL)")
    c1 = sp["rtl"].pole[0, n]
    fund = np.abs(c1) * np.cos(2 * np.pi * (xs - t0) / va["T"] * n + np.angle(c1))
    ax[0].plot((xs - t0) / F_CLK * 1e3, fund * M.UDC, color="k", lw=1.5, label="fundamental")
    ax[0].set_ylabel("V (Udc = 360 V)")
    ax[0].set_xlabel("ms")
    ax[0].legend(loc="upper right", fontsize=8)
    ax[0].set_title(title, fontsize=10)
    for k, (key, lab) in enumerate((("pole", "pole to DC midpoint v_a0"), ("line", "line-to-line v_ab"))):
        a = ax[k + 1]
        ref = abs(getattr(sp["rtl"], key)[0, n])
        a.vlines(f[1:], -140, db(getattr(sp["rtl"], key)[0, 1:], ref), color="C0", lw=0.6,
                 label="RTL, dead time off (pole states)")
        eff = getattr(mo["eff_spectra"], key)[0, 1:]
        a.plot(f[1:], db(eff, ref), ".", ms=1.5, color="C3", label="RTL, dead time 1 µs (gates + current sign)")
        a.plot(f[1:], db(getattr(sp["ideal"], key)[0, 1:], ref), "_", ms=3, color="k", alpha=0.6,
               label="ideal SVPWM, exact edges")
        a.set_ylim(-110, 5)
        a.set_xlim(0, f[-1])
        a.axvline(va["f_sw"] / 2e3, color="0.5", ls=":", lw=1)
        a.set_ylabel("dBc")
        a.set_title(f"{lab}: spectrum over {n} revolution(s), lines at k·f1/{n}", fontsize=9)
        a.legend(loc="upper right", fontsize=7)
    ax[2].set_xlabel("frequency (kHz); dotted: f_sw/2")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_current(name, title, va, mo_on, mo_off, path: Path):
    n = va["n_fund"]
    fig, ax = plt.subplots(2, 1, figsize=(11, 7.5))
    g = (mo_on["grid"] - va["t0"]) / F_CLK * 1e3
    ax[0].plot(g, mo_off["ia"], lw=0.6, color="C0", label="dead time off (pole states)")
    ax[0].plot(g, mo_on["ia"], lw=0.6, color="C3", label="dead time 1 µs")
    ax[0].set_xlabel("ms")
    ax[0].set_ylabel("i_a (A)")
    ax[0].legend(loc="upper right", fontsize=8)
    ax[0].set_title(title, fontsize=10)
    ci_off, ci_on = mo_off["ci"], mo_on["ci"]
    fk = np.arange(len(ci_on)) / va["T"] * F_CLK / 1e3
    kmax = int(3 * va["f_sw"] * va["T"] / F_CLK)
    ref = abs(ci_off[n])
    ax[1].vlines(fk[1:kmax], -140, db(ci_off[1:kmax], ref), color="C0", lw=0.6, label="dead time off")
    ax[1].plot(fk[1:kmax], db(ci_on[1:kmax], ref), ".", ms=1.5, color="C3", label="dead time 1 µs")
    ax[1].set_ylim(-110, 5)
    ax[1].set_xlim(0, fk[kmax])
    ax[1].set_ylabel("dBc")
    ax[1].set_xlabel("frequency (kHz)")
    ax[1].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_speed(npz, r, path: Path):
    lg = {k[4:]: npz[k] for k in npz.files if k.startswith("log_")}
    tt, ii, ww = npz["trace_t"] / F_CLK, npz["trace_i"], npz["trace_wm"]
    fig, ax = plt.subplots(4, 1, figsize=(10, 10), sharex=True)
    ax[0].plot(lg["t"], lg["n_ref"], "k--", lw=1, label="reference")
    ax[0].plot(tt, ww * 60 / (2 * np.pi), color="C0", lw=1.2, label="motor speed")
    ax[0].set_ylabel("rpm")
    ax[0].legend(loc="upper right", fontsize=8)
    ax[0].set_title("Speed steps +700 → −700 rpm (AVR495 Fig. 6-1): slip-regulated PI speed loop writing the RTL's "
                    "frequency input every carrier period;\nV/f law with boost computed by the core (mode 1) "
                    "(Verilator, 0.75 kW 4-pole motor model, dead time 1 µs)",
                    fontsize=9)
    ax[1].plot(lg["t"], lg["f"], color="C1", lw=1, label="stator frequency command f = p·n/60 + f_slip")
    ax[1].plot(lg["t"], np.asarray(lg["f"]) - M.MotorParams.p * np.asarray(lg["n"]) / 60, color="C4", lw=1,
               label="slip command f_slip (PI, limited)")
    ax[1].set_ylabel("Hz")
    ax[1].legend(loc="upper right", fontsize=8)
    ax[2].plot(lg["t"], np.asarray(lg["m"]) * M.UDC / np.sqrt(3), color="C2", lw=1,
               label="phase voltage fundamental peak m·Udc/√3 (m from the core's V/f mode, boost + slope·|f|)")
    ax[2].set_ylabel("V")
    ax[2].legend(loc="center right", fontsize=8)
    ax[3].plot(tt, ii.real, lw=0.3, color="C3", label="i_a")
    ax[3].set_ylabel("A")
    ax[3].set_xlabel("time (s)")
    ax[3].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def speed_summary(npz) -> dict:
    """Per step (motor.step_metrics): settling into +-2 % (settle_2pct_s), overshoot, peak-to-peak ripple and
    mean error over the last 0.2 s of the step, time to first reach the band (reach_2pct_s)."""
    lg = {k[4:]: np.asarray(npz[k]) for k in npz.files if k.startswith("log_")}
    out = {}
    for m in M.step_metrics(lg["t"], lg["n"], lg["n_ref"]):
        lab = ("start_to_" if m["step_at_s"] == 0 else "reversal_to_") + f"{m['n_ref_rpm']:+.0f}"
        out[lab] = dict(step_at_s=m["step_at_s"], n_ref_rpm=m["n_ref_rpm"], settle_2pct_s=m["settle_s"],
                        reach_2pct_s=m["reach_s"], overshoot_rpm=m["overshoot_rpm"],
                        ripple_pp_last_0p2s_rpm=m["ripple_pp_rpm"], mean_error_last_0p2s_rpm=m["mean_error_rpm"],
                        speed_at_end_rpm=m["speed_at_end_rpm"])
    out["i_peak_max_A"] = float(np.max(lg["i_peak"]))
    return out


def plot_sweep(rows, path: Path):
    m = np.array([x["m"] for x in rows])
    fig, ax = plt.subplots(3, 1, figsize=(8, 9), sharex=True)
    ax[0].plot(m, [100 * x["fund_err_rtl"] for x in rows], "o-", label="RTL")
    ax[0].plot(m, [100 * x["fund_err_rounded"] for x in rows], "s--", label="ideal, clock-rounded edges")
    ax[0].axhspan(-0.1, 0.1, color="g", alpha=0.1, label="±0.1 % target")
    ax[0].set_ylabel("line fundamental error (%)")
    ax[0].legend(fontsize=8)
    ax[0].set_title("m sweep at 50 Hz, P = 1536 (f_sw = 15.625 kHz), dead time off (dt = 0), 2 revolutions", fontsize=9)
    ax[1].plot(m, [x["low_rtl_dbc"] for x in rows], "o-", label="RTL: largest line below f_sw/2")
    ax[1].plot(m, [x["low_rounded_dbc"] for x in rows], "s--", label="bound: ideal with clock-rounded edges")
    ax[1].plot(m, [x["low_ideal_dbc"] for x in rows], "^:", label="ideal, exact edges")
    ax[1].set_ylabel("dBc")
    ax[1].legend(fontsize=8)
    ax[2].plot(m, [100 * (x["wthd_rtl"] / x["wthd_ideal"] - 1) for x in rows], "o-", label="RTL vs ideal")
    ax[2].plot(m, [100 * (x["wthd_rounded"] / x["wthd_ideal"] - 1) for x in rows], "s--", label="rounded vs ideal")
    ax[2].axhspan(-0.5, 0.5, color="g", alpha=0.1, label="±0.5 % target")
    ax[2].set_ylabel("WTHD difference (%)")
    ax[2].set_xlabel("m")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- dead-time compensation (issue 15 item 5(a)) -------------------------------------------------------
DTC_TARGET_DB = 6.0       # compensated low-order maximum at Fig. 9 within 6 dB of the dead-time-free run
DTC_LABEL = {"dt0": "dead time 0", "dt1us": "dead time 1 µs", "dt1us_dtc": "dead time 1 µs + compensation"}
DTC_COLOR = {"dt0": "C0", "dt1us": "C3", "dt1us_dtc": "C2"}


def dtc_summary(runs: list[dict], target_db: float = DTC_TARGET_DB) -> dict:
    """Per point (Fig. 9, Fig. 10) the three runs of demo_runs.run_dtc_point (their JSON results) and the
    target: the compensated run's largest line-voltage line below f_sw/2 (dBc, the measure of the Fig. 9/10
    spectra: S.figures) within ``target_db`` of the dead-time-free run's (a stated target, not a check)."""
    pts: dict = {}
    for r in runs:
        if r.get("missing"):
            continue
        pt = r["point"]
        g = pts.setdefault(pt["group"], dict(f_hz=pt["f_hz"], m=pt["m"], period=pt["period"],
                                             f_out_hz_exact=r["f_out_hz_exact"], t_load_nm=pt["t_load"],
                                             window=r["window"], motor=r["motor"], runs={}))
        L = r["line"]
        g["runs"][pt["case"]] = dict(
            name=pt["name"], dt=pt["dt"], dtc=pt["dtc"], line_fundamental=L["fundamental"],
            line_fundamental_commanded=pt["m"], line_fundamental_rel_err=r["line_fundamental_rel_err"],
            low_order_max_dbc=L["low_order_max_dbc"], low_order_max_at_hz=L["low_order_max_at_hz"],
            low_order_rss_dbc=L["low_order_rss_dbc"], wthd=L["wthd"], thd=L["thd"], h_max=L["h_max"],
            i_thd=r["i_thd"], i1_rms=r["i1_rms"], rtl_equals_model=r["rtl_equals_model"],
            isign_changes=r["isign_changes"], table_i_failures=r["table_i"]["failures"],
            table_i_resolved=r.get("table_i_resolved"), n_periods=r["n_periods"], sim_wall_s=r["sim_wall_s"])
    for tag, g in pts.items():
        rr = g["runs"]
        if "dt0" in rr and "dt1us_dtc" in rr:
            gap = rr["dt1us_dtc"]["low_order_max_dbc"] - rr["dt0"]["low_order_max_dbc"]
            g["compensated_vs_dt0_db"] = gap
            g["target_met"] = gap <= target_db
        if "dt0" in rr and "dt1us" in rr:
            g["dead_time_vs_dt0_db"] = rr["dt1us"]["low_order_max_dbc"] - rr["dt0"]["low_order_max_dbc"]
    fig9 = pts.get("fig9", {})
    return dict(target=f"Fig. 9 (5.1 Hz): with compensation the largest line-voltage line below f_sw/2 within "
                       f"{target_db:g} dB of the dead-time-free run", target_db=target_db,
                target_met=fig9.get("target_met"), gap_db=fig9.get("compensated_vs_dt0_db"), points=pts)


def dtc_table(summary: dict) -> list[str]:
    rows = ["| point | run | line fund. / command (error) | low-order max < f_sw/2 (at) | low-order rss | WTHD | "
            "phase-current THD | i1 rms | RTL == model |",
            "|---|---|---|---|---|---|---|---|---|"]
    for tag, g in summary["points"].items():
        for case in ("dt0", "dt1us", "dt1us_dtc"):
            x = g["runs"].get(case)
            if x is None:
                continue
            rows.append(f"| {tag} ({g['f_hz']:g} Hz, m = {g['m']:g}) | {DTC_LABEL[case]} | "
                        f"{x['line_fundamental']:.5f} / {x['line_fundamental_commanded']:g} Udc "
                        f"({100 * x['line_fundamental_rel_err']:+.2f} %) | {x['low_order_max_dbc']:.1f} dBc "
                        f"({x['low_order_max_at_hz']:.1f} Hz) | {x['low_order_rss_dbc']:.1f} dBc | "
                        f"{100 * x['wthd']:.4f} % | {100 * x['i_thd']:.2f} % | {x['i1_rms']:.3f} A | "
                        f"{'yes' if x['rtl_equals_model'] else 'NO'} |")
    return rows


def dtc_verdict(summary: dict) -> list[str]:
    out = []
    for tag, g in summary["points"].items():
        if "compensated_vs_dt0_db" not in g:
            continue
        rr = g["runs"]
        line = (f"{tag}: low-order max dead time 0 {rr['dt0']['low_order_max_dbc']:.1f} dBc, "
                + (f"1 µs {rr['dt1us']['low_order_max_dbc']:.1f} dBc ({g['dead_time_vs_dt0_db']:+.1f} dB), "
                   if "dt1us" in rr else "")
                + f"compensated {rr['dt1us_dtc']['low_order_max_dbc']:.1f} dBc ({g['compensated_vs_dt0_db']:+.1f} dB)")
        if tag == "fig9":
            gap = g["compensated_vs_dt0_db"]
            line += (f": target <= {summary['target_db']:g} dB MET (margin {summary['target_db'] - gap:.1f} dB)"
                     if g["target_met"] else
                     f": target <= {summary['target_db']:g} dB NOT MET (missed by {gap - summary['target_db']:.1f} dB)")
        else:
            line += " (no target at this point)"
        out.append(line)
    return out


def plot_dtc(tag: str, g: dict, out: Path, path: Path) -> None:
    """Line-voltage spectrum below f_sw/2 and the phase current of the three runs of one point."""
    fig, ax = plt.subplots(2, 1, figsize=(11, 8.5))
    n = g["window"]["n_fund"]
    f_sw = F_CLK / (2 * g["period"])
    for case in ("dt0", "dt1us", "dt1us_dtc"):
        x = g["runs"].get(case)
        if x is None:
            continue
        z = np.load(out / f"{x['name']}.npz")
        t0, T = float(z["t0"]), float(z["T"])
        jmax = int(f_sw / 2 * T / F_CLK)
        sp = S.spectra_from_edges(edges_list(z["effective"]), t0, T, n, jmax, F_CLK)
        c = sp.line[0]
        fk = np.arange(1, jmax + 1) / T * F_CLK
        lab = (f"{DTC_LABEL[case]}: max {x['low_order_max_dbc']:.1f} dBc, WTHD {100 * x['wthd']:.3f} %")
        ax[0].plot(fk, db(c[1:], abs(c[n])), ".-" if case != "dt0" else "o", ms=2.5, lw=0.5,
                   color=DTC_COLOR[case], label=lab, alpha=0.85)
        tt, ii = z["trace_t"], z["trace_i"].real
        sel = (tt >= t0) & (tt <= t0 + T / n)
        ax[1].plot((tt[sel] - t0) / F_CLK * 1e3, ii[sel], lw=0.6, color=DTC_COLOR[case],
                   label=f"{DTC_LABEL[case]}: THD {100 * x['i_thd']:.2f} %, i1 {x['i1_rms']:.3f} A rms")
    ax[0].set_xscale("log")
    ax[0].set_xlim(g["f_out_hz_exact"] / n * 0.8, f_sw / 2)
    ax[0].set_ylim(-110, 5)
    ax[0].axhline(g["runs"]["dt0"]["low_order_max_dbc"] + DTC_TARGET_DB if "dt0" in g["runs"] else -1e9,
                  color="0.4", ls=":", lw=1, label=f"dead time 0 max + {DTC_TARGET_DB:g} dB"
                  + (" (target)" if tag == "fig9" else ""))
    ax[0].set_ylabel("dBc")
    ax[0].set_xlabel(f"frequency (Hz), lines at k·f1/{n}, up to f_sw/2")
    ax[0].legend(loc="upper right", fontsize=8)
    ax[0].set_title(f"Minas Fig. {9 if tag == 'fig9' else 10} point, {g['f_hz']:g} Hz, m = {g['m']:g}: line voltage "
                    f"v_ab seen by the motor (poles resolved by the current sign during the dead time), "
                    f"{n} revolution(s)\nRTL (Verilator) with the motor model in the loop; isign_i = the model's "
                    f"current signs at every update's sample point", fontsize=9)
    ax[1].set_xlabel("ms")
    ax[1].set_ylabel("i_a (A)")
    ax[1].legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- volt-second carry of the minimum-pulse rule (issue 15 item 5(b)) ----------------------------------------
VSC_TARGET_DB = 2.0         # with the carry: low-order max within 2 dB of the dead-time-0 run
VSC_TARGET_WTHD = 0.01      # WTHD within 1 % (relative: wthd / wthd_dt0 - 1; also given in percentage points)
VSC_TARGET_FUND = 2e-4      # line fundamental within 0.02 % of the command m
VSC_LABEL = {"dt0": "dead time 0", "off": "1 µs, carry off", "on": "1 µs, carry on"}
VSC_COLOR = {"dt0": "C0", "off": "C3", "on": "C2"}


def _run_of(by_name: dict, name: str, alias: dict):
    r = by_name.get(alias.get(name, name))
    return None if r is None or r.get("missing") or not r.get("line") else r


def vsc_summary(by_name: dict, grid: list[dict], alias: dict | None = None) -> dict:
    """The volt-second carry study from the runs' JSON (demo_runs.run_point with ``spectra``): per m the runs
    dead time 0 / 1 µs carry off / 1 µs carry on (``grid``: scripts/demo.VSC; ``alias``: a grid run answered by
    an equal run of another part of the demo) and the three targets, with the carry, for every m: low-order max
    (largest line below f_sw/2, dBc) within VSC_TARGET_DB of dead time 0; WTHD within 1 % (relative, and in
    percentage points); line fundamental within 0.02 % of m. Stated, not checked."""
    alias = alias or {}
    rows: dict = {}
    for pt in grid:
        r = _run_of(by_name, pt["name"], alias)
        if r is None:
            continue
        L = r["line"]
        rows.setdefault(pt["m"], dict(m=pt["m"], runs={}))["runs"][pt["case"]] = dict(
            name=r["point"]["name"], dt=r["point"]["dt"], vsc=int(bool(r["point"].get("vsc"))), m_word=r["m_word"],
            fundamental=L["fundamental"], fund_err=L["fundamental"] / pt["m"] - 1,
            low_order_max_dbc=L["low_order_max_dbc"], low_order_max_at_hz=L["low_order_max_at_hz"],
            low_order_rss_dbc=L["low_order_rss_dbc"], wthd=L["wthd"], thd=L["thd"], h_max=L["h_max"],
            low_order_floor_dbc=S.low_order_floor_dbc(L["low_order_rss_dbc"], r["line_window"]["n_fund"],
                                                      r["line_window"]["T"], F_CLK, r["f_sw_hz"]),
            low_order_max_below_1khz_dbc=r.get("line_low_order_max_below_1khz_dbc"),
            rtl_equals_model=r["rtl_equals_model"], table_i_failures=r["table_i"]["failures"],
            n_periods=r["n_periods"], sim_wall_s=r["sim_wall_s"])
    out_rows = [rows[m] for m in sorted(rows)]
    per_case: dict = {}
    for row in out_rows:
        rr = row["runs"]
        if "dt0" not in rr:
            continue
        ref = rr["dt0"]
        for case in ("off", "on"):
            x = rr.get(case)
            if x is None:
                continue
            x["low_vs_dt0_db"] = x["low_order_max_dbc"] - ref["low_order_max_dbc"]
            x["floor_vs_dt0_db"] = x["low_order_floor_dbc"] - ref["low_order_max_dbc"]
            x["wthd_vs_dt0_rel"] = x["wthd"] / ref["wthd"] - 1
            x["wthd_vs_dt0_pp"] = 100 * (x["wthd"] - ref["wthd"])
            c = per_case.setdefault(case, dict(n=0, low=[], floor=[], wrel=[], wpp=[], fund=[]))
            c["n"] += 1
            c["low"].append((x["low_vs_dt0_db"], row["m"]))
            c["floor"].append((x["floor_vs_dt0_db"], row["m"]))
            c["wrel"].append((x["wthd_vs_dt0_rel"], row["m"]))
            c["wpp"].append((x["wthd_vs_dt0_pp"], row["m"]))
            c["fund"].append((abs(x["fund_err"]), row["m"]))
    verdict = {}
    for case, c in per_case.items():
        lo, wr, wp, fu = max(c["low"]), max(c["wrel"]), max(c["wpp"]), max(c["fund"])
        verdict[case] = dict(
            points=c["n"],
            low_order=dict(worst_db=lo[0], at_m=lo[1], met=lo[0] <= VSC_TARGET_DB,
                           points_met=sum(v <= VSC_TARGET_DB for v, _ in c["low"]),
                           floor_worst_db=max(c["floor"])[0], floor_at_m=max(c["floor"])[1],
                           floor_points_over=sum(v > VSC_TARGET_DB for v, _ in c["floor"])),
            wthd_relative=dict(worst=wr[0], at_m=wr[1], met=wr[0] <= VSC_TARGET_WTHD,
                               points_met=sum(v <= VSC_TARGET_WTHD for v, _ in c["wrel"])),
            wthd_pp=dict(worst_pp=wp[0], at_m=wp[1], met=wp[0] <= 100 * VSC_TARGET_WTHD,
                         points_met=sum(v <= 100 * VSC_TARGET_WTHD for v, _ in c["wpp"])),
            fundamental=dict(worst_abs_rel=fu[0], at_m=fu[1], met=fu[0] <= VSC_TARGET_FUND,
                             points_met=sum(v <= VSC_TARGET_FUND for v, _ in c["fund"])))
    return dict(target=(f"with the carry, for every m in [0.9, 1.0]: largest line below f_sw/2 within "
                        f"{VSC_TARGET_DB:g} dB of the dead-time-0 run; WTHD within {100 * VSC_TARGET_WTHD:g} % of it "
                        f"(read as relative, WTHD / WTHD_dt0 - 1; in percentage points also given); line fundamental "
                        f"within {100 * VSC_TARGET_FUND:g} % of m"),
                target_db=VSC_TARGET_DB, target_wthd_rel=VSC_TARGET_WTHD, target_fund_rel=VSC_TARGET_FUND,
                conditions=dict(f_hz=50.0, period=1536, f_sw_hz=F_CLK / (2 * 1536), dt_clocks=48, mp_clocks=0,
                                thr_clocks=48, revolutions=2,
                                measured_on="pole states (line a - b, ideal switches): the dead time acts only "
                                            "through the minimum-pulse rule"),
                rows=out_rows, verdict=verdict, reused=alias)


def vsc_table(sm: dict) -> list[str]:
    rows = ["| m | low-order max (dBc): dead time 0 / carry off / carry on (on − dt0) | WTHD %: dead time 0 / off / on "
            "(on vs dt0: relative, pp) | fundamental error vs m: dead time 0 / off / on |",
            "|---|---|---|---|"]
    for row in sm["rows"]:
        rr = row["runs"]

        def g(case, key, fmt, scale=1.0):
            x = rr.get(case)
            return "–" if x is None else format(scale * x[key], fmt)
        on = rr.get("on", {})
        rows.append(f"| {row['m']:.2f} | {g('dt0', 'low_order_max_dbc', '.1f')} / {g('off', 'low_order_max_dbc', '.1f')} / "
                    f"{g('on', 'low_order_max_dbc', '.1f')} ({on.get('low_vs_dt0_db', float('nan')):+.1f} dB) | "
                    f"{g('dt0', 'wthd', '.4f', 100)} / {g('off', 'wthd', '.4f', 100)} / {g('on', 'wthd', '.4f', 100)} "
                    f"({100 * on.get('wthd_vs_dt0_rel', float('nan')):+.2f} %, {on.get('wthd_vs_dt0_pp', float('nan')):+.4f} pp) | "
                    f"{g('dt0', 'fund_err', '+.4f', 100)} / {g('off', 'fund_err', '+.4f', 100)} / "
                    f"{g('on', 'fund_err', '+.4f', 100)} % |")
    return rows


def vsc_verdict(sm: dict) -> list[str]:
    out = []
    for case in ("on", "off"):
        v = sm["verdict"].get(case)
        if v is None:
            continue
        lab = "carry on" if case == "on" else "carry off"
        lo, wr, wp, fu = v["low_order"], v["wthd_relative"], v["wthd_pp"], v["fundamental"]

        def mt(ok):
            return "MET" if ok else "NOT MET"
        out.append(f"{lab}: low-order max within {sm['target_db']:g} dB of dead time 0: {mt(lo['met'])} "
                   f"({lo['points_met']}/{v['points']} points; worst {lo['worst_db']:+.1f} dB at m = {lo['at_m']:.2f}"
                   + ("" if lo["met"] else f", {lo['worst_db'] - sm['target_db']:.1f} dB over the target") + ")")
        if case == "on" and lo["floor_points_over"]:
            out.append(f"{lab}: at {lo['floor_points_over']}/{v['points']} points the low-order energy alone misses "
                       f"it: its rss spread evenly over every line below f_sw/2 (spectrum.low_order_floor_dbc) would "
                       f"still be up to {lo['floor_worst_db']:+.1f} dB from dead time 0 (m = {lo['floor_at_m']:.2f}); "
                       f"an error feedback on per-period values only moves energy inside that band")
        out.append(f"{lab}: WTHD within {100 * sm['target_wthd_rel']:g} % (relative): {mt(wr['met'])} "
                   f"({wr['points_met']}/{v['points']}; worst {100 * wr['worst']:+.2f} % at m = {wr['at_m']:.2f}); "
                   f"read as percentage points: {mt(wp['met'])} (worst {wp['worst_pp']:+.4f} pp)")
        out.append(f"{lab}: fundamental within {100 * sm['target_fund_rel']:g} % of m: {mt(fu['met'])} "
                   f"({fu['points_met']}/{v['points']}; worst |error| {100 * fu['worst_abs_rel']:.4f} % at "
                   f"m = {fu['at_m']:.2f})")
    return out


def plot_vsc(sm: dict, out: Path, path: Path) -> None:
    """Three measures vs m for the three cases, and the line spectra below f_sw/2 at the m where the carry-on
    run is furthest from the dead-time-0 run."""
    rows = sm["rows"]
    fig, ax = plt.subplots(4, 1, figsize=(10, 13))
    for case in ("dt0", "off", "on"):
        xs = [(r["m"], r["runs"][case]) for r in rows if case in r["runs"]]
        if not xs:
            continue
        m = [a for a, _ in xs]
        ax[0].plot(m, [x["low_order_max_dbc"] for _, x in xs], "o-", color=VSC_COLOR[case], label=VSC_LABEL[case])
        ax[1].plot(m, [100 * x["wthd"] for _, x in xs], "o-", color=VSC_COLOR[case], label=VSC_LABEL[case])
        ax[2].plot(m, [100 * x["fund_err"] for _, x in xs], "o-", color=VSC_COLOR[case], label=VSC_LABEL[case])
    ref = [(r["m"], r["runs"]["dt0"]) for r in rows if "dt0" in r["runs"]]
    if ref:
        ax[0].plot([a for a, _ in ref], [x["low_order_max_dbc"] + sm["target_db"] for _, x in ref], ":", color="0.4",
                   label=f"dead time 0 + {sm['target_db']:g} dB (target for carry on)")
        ax[1].plot([a for a, _ in ref], [100 * x["wthd"] * (1 + sm["target_wthd_rel"]) for _, x in ref], ":",
                   color="0.4", label=f"dead time 0 × {1 + sm['target_wthd_rel']:g} (target, relative)")
    ax[2].axhspan(-100 * sm["target_fund_rel"], 100 * sm["target_fund_rel"], color="g", alpha=0.12,
                  label=f"±{100 * sm['target_fund_rel']:g} % (target)")
    ax[0].set_ylabel("largest line < f_sw/2 (dBc)")
    ax[0].set_title("Volt-second carry of the minimum-pulse rule: 50 Hz, P = 1536 (f_sw = 15.625 kHz), dead time 1 µs "
                    "(thr = 48 clocks), minimum pulse 0;\nline a − b of the RTL's pole states over 2 revolutions "
                    "(the dead time acts here only through the minimum-pulse rule)", fontsize=9)
    ax[1].set_ylabel("WTHD (%)")
    ax[2].set_ylabel("fundamental error vs m (%)")
    ax[2].set_xlabel("m")
    for a in ax[:3]:
        a.legend(fontsize=8)
    # spectra at the worst carry-on point
    cand = [r for r in rows if "on" in r["runs"] and "low_vs_dt0_db" in r["runs"]["on"]]
    if cand:
        row = max(cand, key=lambda r: r["runs"]["on"]["low_vs_dt0_db"])
        for case in ("dt0", "off", "on"):
            x = row["runs"].get(case)
            f = out / f"{x['name']}_edges.npz" if x else None
            if f is None or not f.is_file():
                continue
            z = np.load(f)
            fw = int(z["freq_word"])
            f1 = f1_of(fw)
            T = 2 / abs(f1)
            t0 = float(z["valley"][1] + 1)
            f_sw = F_CLK / (2 * int(z["period"][0]))
            jmax = int(f_sw / 2 * T / F_CLK)
            sp = S.spectra_from_edges(edges_list(z["pole_edges"]), t0, T, 2, jmax, F_CLK)
            c = sp.line[0]
            fk = np.arange(1, jmax + 1) / T * F_CLK
            ax[3].plot(fk, db(c[1:], abs(c[2])), "o" if case == "dt0" else ".-", ms=2.5, lw=0.5,
                       color=VSC_COLOR[case], alpha=0.85,
                       label=f"{VSC_LABEL[case]}: max {x['low_order_max_dbc']:.1f} dBc at {x['low_order_max_at_hz']:.0f} Hz")
        ax[3].set_xscale("log")
        ax[3].set_xlim(40, F_CLK / (2 * 1536) / 2)
        ax[3].set_ylim(-110, 5)
        ax[3].set_xlabel("frequency (Hz), lines at k·f1/2, up to f_sw/2")
        ax[3].set_ylabel("dBc")
        ax[3].set_title(f"line a − b below f_sw/2 at m = {row['m']:.2f} (the carry-on run furthest from dead time 0)",
                        fontsize=9)
        ax[3].legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- six-step overmodulation law (issue 15 item 5(c)) --------------------------------------------------------
OM_TARGET_REL = 0.01        # RTL line fundamental within 1 % of ideal.overmod_fundamental at every point
OM_MONO_TOL = 1e-4          # Udc: "monotonic within" reading (the fixed-point law's bound against the map,
#                             model/tests/test_overmod.py; near six-step the map rises ~1e-5 Udc from 0xA000 to 0xFFFF,
#                             while the regularly sampled near-six-step waveform moves ~1e-4 Udc with f and window)


def om_summary(by_name: dict, grid: list[dict], alias: dict | None = None) -> dict:
    """The overmodulation study from the runs' JSON: per run (om, m word) the line fundamental of the pole
    states over 2 revolutions against the documented map ideal.overmod_fundamental(m, six_step=om) (the run's
    fund_ref); targets: monotonic in m (per law) and within 1 % of the map at every point."""
    from svpwm_model import ideal
    alias = alias or {}
    rows = []
    for pt in grid:
        r = _run_of(by_name, pt["name"], alias)
        if r is None:
            continue
        L = r["line"]
        ref = float(pt["fund_ref"])
        rows.append(dict(name=r["point"]["name"], om=int(pt["om"]), m_word=int(pt["m_word"]), m=pt["m"],
                         fundamental=L["fundamental"], map=ref, err_rel=L["fundamental"] / ref - 1,
                         low_order_max_dbc=L["low_order_max_dbc"], low_order_max_at_hz=L["low_order_max_at_hz"],
                         wthd=L["wthd"], worst_abs_c_minus_ideal_counts=r["worst_abs_c_minus_ideal_counts"],
                         rtl_equals_model=r["rtl_equals_model"], table_i_failures=r["table_i"]["failures"],
                         sim_wall_s=r["sim_wall_s"]))
    laws = {}
    for om in (1, 0):
        xs = sorted((x for x in rows if x["om"] == om), key=lambda x: x["m_word"])
        if not xs:
            continue
        steps = [b["fundamental"] - a["fundamental"] for a, b in zip(xs, xs[1:])]
        worst = max(xs, key=lambda x: abs(x["err_rel"]))
        # strictly: every step >= 0 (the clamp, om = 0, is flat above 2/sqrt3: steps of ~1e-7 Udc either way are
        # its rounding, so it is read with 1e-6 Udc); and within OM_MONO_TOL
        tol = 0.0 if om else 1e-6
        mono = all(d >= -tol for d in steps)
        laws[f"om{om}"] = dict(points=len(xs), monotonic=mono, monotonic_within_tol=all(d >= -OM_MONO_TOL for d in steps),
                               mono_tol_udc=OM_MONO_TOL, min_step_udc=min(steps) if steps else None,
                               min_step_at=(xs[int(np.argmin(steps))]["m_word"], xs[int(np.argmin(steps)) + 1]["m_word"])
                               if steps else None,
                               worst_err_rel=worst["err_rel"], worst_at_word=worst["m_word"],
                               within_target=all(abs(x["err_rel"]) <= OM_TARGET_REL for x in xs))
    return dict(target=f"line fundamental monotonic in m and within {100 * OM_TARGET_REL:g} % of "
                       f"ideal.overmod_fundamental at every point",
                target_rel=OM_TARGET_REL, six_step_udc=ideal.SIX_STEP, vertex_m=ideal.M_VERTEX_F,
                conditions=dict(f_hz=50.0, period=1536, dt_clocks=0, revolutions=2,
                                measured_on="pole states (line a - b)"),
                rows=sorted(rows, key=lambda x: (-x["om"], x["m_word"])), laws=laws, reused=alias)


def om_table(sm: dict) -> list[str]:
    rows = ["| om | m (word) | RTL line fundamental (Udc) | map (Udc) | error | largest line < f_sw/2 | "
            "worst abs(C − C_ideal) (counts) |",
            "|---|---|---|---|---|---|---|"]
    for x in sm["rows"]:
        rows.append(f"| {x['om']} | {x['m']:.5f} ({x['m_word']:#06x}) | {x['fundamental']:.5f} | {x['map']:.5f} | "
                    f"{100 * x['err_rel']:+.4f} % | {x['low_order_max_dbc']:.1f} dBc ({x['low_order_max_at_hz']:.0f} Hz) | "
                    f"{x['worst_abs_c_minus_ideal_counts']:.2f} |")
    return rows


def om_verdict(sm: dict) -> list[str]:
    out = []
    for key, v in sm["laws"].items():
        lab = "six-step law (om 1)" if key == "om1" else "angle-keeping clamp (om 0)"
        a, b = v["min_step_at"] or (0, 0)
        out.append(f"{lab}: {v['points']} points, monotonic: {'MET' if v['monotonic'] else 'NOT MET'} "
                   + (f"(smallest step {v['min_step_udc']:+.5f} Udc, {a:#06x} -> {b:#06x}; within "
                      f"{v['mono_tol_udc']:g} Udc: {'MET' if v['monotonic_within_tol'] else 'NOT MET'})"
                      if v["min_step_udc"] is not None else "(one point)")
                   + f"; within {100 * sm['target_rel']:g} % of the map: "
                   f"{'MET' if v['within_target'] else 'NOT MET'} (worst {100 * v['worst_err_rel']:+.4f} % at "
                   f"{v['worst_at_word']:#06x})")
    return out


def plot_om(sm: dict, path: Path) -> None:
    from svpwm_model import ideal
    fig, ax = plt.subplots(1, 2, figsize=(13, 5.5), gridspec_kw=dict(width_ratios=[3, 2]))
    mm = np.concatenate([np.linspace(1.0, 1.15, 31), np.linspace(1.1547, 1.2, 181), np.linspace(1.2, 2.0, 81)[1:]])
    for a, lo, hi in ((ax[0], 1.0, 2.0), (ax[1], 1.14, 1.20)):
        sel = (mm >= lo) & (mm <= hi)
        a.plot(mm[sel], [ideal.overmod_fundamental(x, six_step=True) for x in mm[sel]], "-", color="C0", lw=1.2,
               label="map, six-step law (ideal.overmod_fundamental)")
        a.plot(mm[sel], [ideal.overmod_fundamental(x, six_step=False) for x in mm[sel]], "--", color="C1", lw=1.2,
               label="map, angle-keeping clamp")
        for om, mk, col in ((1, "o", "C0"), (0, "s", "C1")):
            xs = [x for x in sm["rows"] if x["om"] == om and lo <= x["m"] <= hi]
            a.plot([x["m"] for x in xs], [x["fundamental"] for x in xs], mk, color=col, mfc="none", ms=8, mew=1.5,
                   label=f"RTL, om_i = {om}")
        a.axhline(sm["six_step_udc"], color="k", ls=":", lw=1)
        a.text(lo + 0.01 * (hi - lo), sm["six_step_udc"] + 0.002, f"six-step {sm['six_step_udc']:.4f} Udc", fontsize=8)
        a.axvline(sm["vertex_m"], color="0.5", ls=":", lw=1)
        a.set_xlim(lo, hi)
        a.set_xlabel("m (UQ1.15 word / 0x8000)")
    ax[0].text(sm["vertex_m"] + 0.01, 1.005, "2/√3 (0x93CD)", fontsize=8, color="0.4")
    top = [x for x in sm["rows"] if x["om"] == 1 and x["m_word"] == 0xFFFF]
    if top:
        ax[0].annotate(f"0xFFFF: six-step, {top[0]['fundamental']:.5f} Udc", (top[0]["m"], top[0]["fundamental"]),
                       textcoords="offset points", xytext=(-150, -30), fontsize=8, arrowprops=dict(arrowstyle="->"))
    ax[0].set_ylim(0.99, 1.115)
    ax[1].set_ylim(1.04, 1.11)
    ax[0].set_ylabel("line fundamental (Udc)")
    ax[0].legend(fontsize=8, loc="lower right")
    ax[0].set_title("Overmodulation: line fundamental of the RTL's pole states vs m (50 Hz, P = 1536, 2 revolutions)",
                    fontsize=9)
    ax[1].set_title("zoom: 1.14 … 1.20 (the law's steep part)", fontsize=9)
    for x in sm["rows"]:
        if x["om"] == 1 and 1.14 <= x["m"] <= 1.2:
            ax[1].annotate(f"{100 * x['err_rel']:+.3f} %", (x["m"], x["fundamental"]), textcoords="offset points",
                           xytext=(6, -12), fontsize=7, color="C0")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


# ---- main --------------------------------------------------------------------------------------------
def sweep_row(r, va) -> dict:
    fr = va["figures"]
    m = r["point"]["m"]
    return dict(m=m, fund_rtl=fr["rtl"]["line"]["fundamental"],
                fund_err_rtl=fr["rtl"]["line"]["fundamental"] / m - 1,
                fund_err_ideal=fr["ideal"]["line"]["fundamental"] / m - 1,
                fund_err_rounded=fr["ideal_rounded"]["line"]["fundamental"] / m - 1,
                low_rtl_dbc=fr["rtl"]["line"]["low_order_max_dbc"],
                low_rounded_dbc=fr["ideal_rounded"]["line"]["low_order_max_dbc"],
                low_ideal_dbc=fr["ideal"]["line"]["low_order_max_dbc"],
                low_rss_rtl_dbc=fr["rtl"]["line"]["low_order_rss_dbc"],
                low_rss_rounded_dbc=fr["ideal_rounded"]["line"]["low_order_rss_dbc"],
                thd_rtl=fr["rtl"]["line"]["thd"], thd_ideal=fr["ideal"]["line"]["thd"],
                wthd_rtl=fr["rtl"]["line"]["wthd"], wthd_ideal=fr["ideal"]["line"]["wthd"],
                wthd_rounded=fr["ideal_rounded"]["line"]["wthd"], h_max=fr["rtl"]["line"]["h_max"])


def build(out: Path, minas: list[str], sweep: list[str], speed: str | None, dtc: list[str] = (),
          vsc: dict | None = None, om: dict | None = None, made_by: str = "make report") -> dict:
    """``vsc`` / ``om``: the summaries of the volt-second carry and overmodulation runs (vsc_summary,
    om_summary, made by scripts/demo.py from the runs' JSON; in demo.json). ``made_by``: the make target, named
    in report.md ("make demo": the quick subset, the rest is pointed to `make report`)."""
    t_start = time.perf_counter()
    metrics: dict = dict(date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), made_by=made_by, udc_v=M.UDC,
                         motor=M.MotorParams().__dict__,
                         definitions=S.__doc__.split("Figures of merit")[1].split("The ideal references")[0].strip(),
                         points={}, sweep_50hz=[], speed_loop=None)
    figs: list[tuple[str, str, str]] = []
    data = {}
    for name in tqdm(minas, desc="spectra + motor at Minas' points", unit="point"):
        r, z = load_point(out, name)
        va = analyse_voltage(r, z)
        mo_on = motor_point(r, z, va, gates=True)
        mo_off = motor_point(r, z, va, gates=False)
        data[name] = (r, z, va, mo_on, mo_off)
        metrics["points"][name] = dict(
            f_hz=r["point"]["f_hz"], f1_hz_exact=va["f1_hz"], m=r["point"]["m"], window_revolutions=va["n_fund"],
            carrier_leakage_bins=va["leakage_bins"], h_max=va["jmax"] / va["n_fund"],
            voltage=va["figures"], sweep=sweep_row(r, va),
            dead_time_on=dict(line=mo_on["eff_line"], pole=mo_on["eff_pole"]),
            motor=dict(t_load_nm=T_LOAD, slip=mo_on["slip"], speed_rpm=mo_on["speed_rpm"],
                       i1_rms_dead_time_off=mo_off["i1_rms"], i1_rms_dead_time_on=mo_on["i1_rms"],
                       i1_rms_equivalent_circuit=mo_off["ec_i_rms"],
                       i_thd_dead_time_off=mo_off["i_thd"], i_thd_dead_time_on=mo_on["i_thd"],
                       i_rms_dead_time_off=mo_off["i_rms"]))
    for name in tqdm(sweep, desc="m sweep spectra", unit="point"):
        r, z = load_point(out, name)
        va = analyse_voltage(r, z)
        metrics["sweep_50hz"].append(sweep_row(r, va))
    fig10 = [n for n in minas if "50hz" in n]
    if fig10 and sweep:                          # Fig. 10 is the sweep's m = 0.9 (no sweep in `make demo`)
        metrics["sweep_50hz"].append(metrics["points"][fig10[0]]["sweep"])
    metrics["sweep_50hz"].sort(key=lambda x: x["m"])

    if fig10:
        r, z = data[fig10[0]][:2]
        p = out / "fig_carrier_period.png"
        metrics["carrier_period"] = plot_carrier_period(r, z, p)
        figs.append((p.name, "One carrier period (Minas Fig. 4)",
                     "Carrier (up/down counter), the three compare values and the pole states of one RTL period in "
                     "sector 1 at the 50 Hz point; the seven segments 000→100→110→111→110→100→000 of Minas Table I "
                     "are labelled with their lengths in clocks (V0 split at both ends, V7 in the middle, one leg "
                     "switching per transition)."))
    if data:
        p = out / "fig_hexagon.png"
        plot_hexagon([(n.replace("minas_", ""), data[n][0], data[n][1]) for n in minas], p)
        figs.append((p.name, "Hexagon and reference trajectory",
                     "The six active vectors (states abc), sector boundaries, the m = 1 inscribed circle and the "
                     "per-carrier-period mean voltage vector of the RTL's switching pattern at both Minas points "
                     "(circles of radius m/√3 in units of Udc)."))
    for name, (r, z, va, mo_on, mo_off) in data.items():
        fr = va["figures"]
        tag = name.replace("minas_", "")
        p = out / f"fig_voltage_{tag}.png"
        title = (f"{r['point'].get('title', name)}: f1 = {va['f1_hz']:.4f} Hz, f_sw = 15.625 kHz, Udc = {M.UDC:.0f} V")
        plot_voltage(name, title, va, mo_on, z, p)
        lr, li, lq = fr["rtl"]["line"], fr["ideal"]["line"], fr["ideal_rounded"]["line"]
        figs.append((p.name, f"Voltage waveform and spectra, {tag} (Minas Fig. {9 if '5p1' in tag else 10}a/b)",
                     f"Pole-to-DC-midpoint voltage (±Udc/2) and its spectrum, and the line voltage spectrum, exact over "
                     f"{va['n_fund']} revolution(s) from the RTL's edges (dBc re the fundamental). Sidebands cluster at "
                     f"f_sw and its multiples as in Minas. Line fundamental {lr['fundamental']:.6f} Udc "
                     f"(command {r['point']['m']}, error {100 * (lr['fundamental'] / r['point']['m'] - 1):+.4f} %); "
                     f"THD {100 * lr['thd']:.2f} % (ideal {100 * li['thd']:.2f} %), WTHD {100 * lr['wthd']:.4f} % "
                     f"(ideal {100 * li['wthd']:.4f} %); largest line below f_sw/2: RTL {lr['low_order_max_dbc']:.1f} dBc, "
                     f"clock-rounded ideal {lq['low_order_max_dbc']:.1f} dBc, exact ideal {li['low_order_max_dbc']:.1f} dBc. "
                     f"Dead time 1 µs (red): line fundamental {mo_on['eff_line']['fundamental']:.5f} Udc "
                     f"({100 * (mo_on['eff_line']['fundamental'] / lr['fundamental'] - 1):+.2f} %), largest low-order line "
                     f"{mo_on['eff_line']['low_order_max_dbc']:.1f} dBc at {mo_on['eff_line']['low_order_max_at_hz']:.1f} Hz."
                     + (f" Note: {va['leakage_bins']:.2f}-bin carrier leakage (one revolution is not a whole number of "
                        f"carrier periods) sets the exact ideal's floor." if va["leakage_bins"] > 0.01 else "")))
        p = out / f"fig_current_{tag}.png"
        plot_current(name, f"Phase current, {tag}: motor at {mo_on['speed_rpm']:.0f} rpm (slip {mo_on['slip']:.3f}, "
                     f"load {T_LOAD} N m, speed held), driven by the RTL's switched voltages", va, mo_on, mo_off, p)
        figs.append((p.name, f"Phase current and spectrum, {tag} (Minas Fig. {9 if '5p1' in tag else 10}c/d)",
                     f"Fundamental {mo_off['i1_rms']:.3f} A rms without dead time (equivalent circuit at the same "
                     f"voltage and slip: {mo_off['ec_i_rms']:.3f} A), {mo_on['i1_rms']:.3f} A with 1 µs dead time; current "
                     f"THD (to 200th) {100 * mo_off['i_thd']:.2f} % / {100 * mo_on['i_thd']:.2f} %. The dead time adds "
                     f"5th/7th-order distortion, strongest at low frequency where the voltage is small."))
    if metrics["sweep_50hz"]:
        p = out / "fig_m_sweep.png"
        plot_sweep(metrics["sweep_50hz"], p)
        figs.append((p.name, "Fidelity over m (50 Hz, dead time off)",
                     "Line fundamental error, largest low-order line (below f_sw/2) vs the clock-rounded ideal bound, "
                     "and WTHD vs the exact ideal SVPWM, from RTL runs of 2 revolutions each."))
    if speed:
        npz = np.load(out / f"{speed}.npz")
        r = json.loads((out / f"{speed}.json").read_text())
        p = out / "fig_speed.png"
        plot_speed(npz, r, p)
        ss = speed_summary(npz)
        ctrl = M.make_speed_ctrl(r["point"].get("ctrl", "slip"), **r["point"].get("ctrl_args", {}))
        vfl = M.VfLaw()
        vfw = r.get("vf_words") or M.vf_words(vfl).__dict__
        metrics["speed_loop"] = dict(summary=ss, rtl_equals_model=r.get("rtl_equals_model"), cycles=r.get("cycles"),
                                     sim_wall_s=r.get("sim_wall_s"), inverter=r.get("inverter"),
                                     controller=dict(kind=type(ctrl).__name__, **{k: v for k, v in ctrl.__dict__.items()
                                                                                  if k not in ("integ", "f_slip")}),
                                     core_mode=r.get("core_mode"),
                                     vf=dict(vfl.__dict__, words=vfw))
        st0 = next(v for k, v in ss.items() if k.startswith("start_to_"))
        st = next(v for k, v in ss.items() if k.startswith("reversal_to_"))

        def fmt(x):
            return "not settled" if x is None else f"{x:.2f} s"
        figs.append((p.name, "Speed response +700 → −700 rpm (AVR495 Fig. 6-1)",
                     f"RTL in the loop (Verilator): every carrier period the motor model is advanced over the RTL's "
                     f"gate edges (1 µs dead time) and the speed controller computes the stator frequency, whose word is the "
                     f"only input written for the next period; the V/f law is computed by the core (mode 1, VF): "
                     f"m = min(m_max, boost + slope·|f|) from its registers boost = {vfw['boost']} "
                     f"({vfl.boost}), slope = {vfw['slope']} (UQ8.8 m-LSBs per {M.vf_unit_hz() * 1e3:.1f} mHz = {vfl.slope:.4f}/Hz), "
                     f"m_max = {vfw['m_max']} ({vfl.m_max}), converted once by motor.vf_words "
                     f"({r.get('cycles', 0):,} clocks; afterwards "
                     f"the golden model replayed the same inputs: RTL == model on every edge: "
                     f"{r.get('rtl_equals_model')}). Loop: slip-regulated V/f (f = p·n/60 + PI slip command limited to "
                     f"±{getattr(ctrl, 'f_slip_max', float('nan'))} Hz, kp = {ctrl.kp} Hz/rpm, ki = {ctrl.ki} Hz/(rpm·s), "
                     f"conditional-integration anti-windup; model/svpwm_model/motor.py SlipPISpeed) — AVR495's "
                     f"PI-to-frequency loop leaves the open-loop V/f machine's light-load mode (13.7 Hz, ζ = 0.08 at "
                     f"700 rpm; 14.6 Hz, ζ = 0.03 with its PI) in the loop, which oscillated at ~13 Hz here. "
                     f"Measured: start 0 → +700 rpm: within ±2 % after {fmt(st0['settle_2pct_s'])}, overshoot "
                     f"{st0['overshoot_rpm']:.1f} rpm, ripple over the last 0.2 s {st0['ripple_pp_last_0p2s_rpm']:.1f} rpm "
                     f"p-p; reversal +700 → −700 rpm: first within ±2 % after {fmt(st['reach_2pct_s'])}, settled "
                     f"(stays within ±14 rpm) after {fmt(st['settle_2pct_s'])}, overshoot {st['overshoot_rpm']:.1f} rpm, "
                     f"ripple {st['ripple_pp_last_0p2s_rpm']:.1f} rpm p-p, mean error "
                     f"{st['mean_error_last_0p2s_rpm']:+.1f} rpm (AVR495: ~1.2 s transient); peak stator current "
                     f"{ss['i_peak_max_A']:.2f} A. Near f = 0 the voltage is the boost voltage, as in AVR495."))
    if dtc:
        sm = dtc_summary([json.loads((out / f"{n}.json").read_text()) for n in dtc])
        metrics["dead_time_compensation"] = sm
        for tag, g in sm["points"].items():
            p = out / f"fig_dtc_{tag}.png"
            plot_dtc(tag, g, out, p)
            rr = g["runs"]
            txt = (f"The line voltage the motor sees and its phase current in three RTL runs at the Minas Fig. "
                   f"{9 if tag == 'fig9' else 10} point (P = {g['period']}, f_sw = 15.625 kHz, motor speed held at "
                   f"{g['motor']['speed_rpm']:.0f} rpm, slip {g['motor']['slip']:.3f}): dead time 0, 1 µs (48 clocks) "
                   f"without and with the core's compensation (dtc_en_i = 1). The motor model follows the RTL's "
                   f"gate edges as the run goes (the pole of a leg with both gates off set by the current sign) "
                   f"and its three current signs are written to isign_i at every update's sample point; the "
                   f"window is {g['window']['n_fund']} revolution(s) after {g['window']['warmup_s'] * 1e3:.0f} ms "
                   f"of warm-up. " + " ".join(dtc_verdict(dict(sm, points={tag: g}))) + ".")
            figs.append((p.name, f"Dead-time compensation, {tag} (issue 15 item 5(a))", txt))
    if vsc and vsc.get("rows"):
        metrics["volt_second_carry"] = vsc
        p = out / "fig_vsc_sweep.png"
        plot_vsc(vsc, out, p)
        figs.append((p.name, "Volt-second carry of the minimum-pulse rule (issue 15 item 5(b))",
                     "Largest line below f_sw/2, WTHD and the fundamental error of the line voltage a − b from the "
                     "RTL's pole states at m = 0.90 … 1.00 (50 Hz, f_sw = 15.625 kHz, 2 revolutions): dead time 0, "
                     "and dead time 1 µs (minimum pulse 0: thr = 48 clocks) with the carry off and on; the bottom "
                     "panel is the spectrum at the m where the carry-on run is furthest from dead time 0. "
                     + "; ".join(vsc_verdict(vsc)) + "."))
    if om and om.get("rows"):
        metrics["overmodulation"] = om
        p = out / "fig_overmod.png"
        plot_om(om, p)
        figs.append((p.name, "Six-step overmodulation law (issue 15 item 5(c))",
                     "Line fundamental of the RTL's pole states (50 Hz, P = 1536, dead time 0, 2 revolutions) vs m "
                     "with om_i = 1 (the six-step law) and om_i = 0 (the angle-keeping clamp), on the documented map "
                     "ideal.overmod_fundamental; dotted: six-step (2√3/π Udc) and the vertex magnitude 2/√3. "
                     + "; ".join(om_verdict(om)) + "."))
    metrics["report_wall_s"] = time.perf_counter() - t_start
    (out / "metrics.json").write_text(json.dumps(metrics, indent=2, default=float) + "\n")
    write_md(out, metrics, figs)
    return metrics


def fidelity_table(metrics) -> list[str]:
    rows = ["| point | m | line fund. error | THD RTL / ideal | WTHD RTL / rounded / ideal (RTL, rounded vs ideal) | "
            "low-order max RTL / rounded bound / exact ideal (dBc) |",
            "|---|---|---|---|---|---|"]
    items = [(k, v["sweep"]) for k, v in metrics["points"].items()] + [("50 Hz sweep", x) for x in metrics["sweep_50hz"]]
    for k, x in items:
        rows.append(f"| {k} | {x['m']:.3g} | {100 * x['fund_err_rtl']:+.4f} % | {100 * x['thd_rtl']:.2f} / "
                    f"{100 * x['thd_ideal']:.2f} % | {100 * x['wthd_rtl']:.4f} / {100 * x['wthd_rounded']:.4f} / "
                    f"{100 * x['wthd_ideal']:.4f} % ({100 * (x['wthd_rtl'] / x['wthd_ideal'] - 1):+.2f} %, "
                    f"{100 * (x['wthd_rounded'] / x['wthd_ideal'] - 1):+.2f} %) | {x['low_rtl_dbc']:.1f} / "
                    f"{x['low_rounded_dbc']:.1f} / {x['low_ideal_dbc']:.1f} |")
    return rows


def write_md(out: Path, metrics: dict, figs):
    made_by = metrics.get("made_by", "make report")
    quick = (["`make demo` runs Minas' two points and the dead-time compensation runs only: the m sweep, the "
              "volt-second carry and overmodulation studies and the AVR495 speed loop are in `make report` "
              "(build/report/report.md).", ""] if made_by == "make demo" else [])
    lines = ["# svpwm demo report", ""] + quick + [
             f"Generated {metrics['date']} by `{made_by}` (scripts/demo.py → scripts/report.py). All voltages come from "
             "the RTL (rtl/*.sv on Verilator through cocotb); spectra are exact integrals over the RTL's edge times. "
             f"Udc = {metrics['udc_v']:.0f} V (m = 0.9 at 50 Hz = 230 V line rms). m: m = 1 is the inscribed circle, "
             "line fundamental peak = m·Udc. Dead time off = the core's pole states (ideal inverter; the m sweep runs with "
             "dt = 0, so no minimum-pulse rule acts either); dead time on = "
             "the gate edges (1 µs) with the pole set by the phase-current sign while both gates are off.", "",
             "## Fidelity (line voltage, dead time off)", "",
             "Targets: line fundamental within 0.1 % of the command; largest low-order line ≤ 1 dB above the "
             "clock-rounded ideal; WTHD within 0.5 % of the ideal. 'rounded' is ideal SVPWM with every edge on the "
             "nearest clock: the floor any modulator at this clock and carrier reaches; where it is itself more than "
             "0.5 % above the ideal, the WTHD target is below the clock's quantisation.", ""]
    lines += fidelity_table(metrics)
    lines += ["", "Definitions: " + metrics["definitions"].replace("\n", " "), ""]
    sm = metrics.get("dead_time_compensation")
    if sm:
        lines += ["## Dead-time compensation (1 µs, motor model in the loop)", "",
                  "Target: " + sm["target"] + " (stated, not a check: the demo passes on RTL == model and "
                  "the safety checks).", ""]
        lines += dtc_table(sm)
        lines += [""] + [f"- {x}" for x in dtc_verdict(sm)] + [""]
    sm = metrics.get("volt_second_carry")
    if sm:
        lines += ["## Volt-second carry of the minimum-pulse rule (50 Hz, dead time 1 µs, pole states)", "",
                  "Target: " + sm["target"] + " (stated, not a check).", ""]
        lines += vsc_table(sm)
        lines += [""] + [f"- {x}" for x in vsc_verdict(sm)] + [""]
    sm = metrics.get("overmodulation")
    if sm:
        lines += ["## Overmodulation: line fundamental vs m (50 Hz, dead time 0, pole states)", "",
                  "Target: " + sm["target"] + " (stated, not a check).", ""]
        lines += om_table(sm)
        lines += [""] + [f"- {x}" for x in om_verdict(sm)] + [""]
    for fn, title, text in figs:
        lines += [f"## {title}", "", f"![{title}]({fn})", "", text, ""]
    mp = metrics["motor"]
    lines += ["## Motor model", "",
              "Standard dq model in the stationary frame (model/svpwm_model/motor.py), 0.75 kW 4-pole 50 Hz, "
              "star-equivalent at 230 V: " + ", ".join(f"{k} = {v}" for k, v in mp.items()) +
              ". Parameters derived from typical catalogue data (see the MotorParams docstring).", ""]
    (out / "report.md").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    out = Path(sys.argv[1]).resolve() if len(sys.argv) > 1 else REPO / "build" / "report"
    d = json.loads((out / "demo.json").read_text())
    names = [r["point"]["name"] for r in d["results"] if not r.get("missing")]
    kinds = {r["point"]["name"]: r["point"].get("kind", "point") for r in d["results"]}
    minas = [n for n in names if n.startswith("minas_")]
    sweep = [n for n in names if n.startswith("sweep_")]
    speed = next((n for n in names if kinds[n] == "speed_loop"), None)
    dtc = [n for n in names if kinds[n] == "dtc"]
    build(out, minas, sweep, speed, dtc, vsc=d.get("volt_second_carry"), om=d.get("overmodulation"),
          made_by="make demo" if str(d.get("mode", "")).startswith("quick") else "make report")
    print(f"report: {out / 'report.md'}")
