#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Hysteresis of the current-sign detection for the dead-time compensation (isign_i): phase-current THD
against the hysteresis band, model only (no RTL simulation).

At Minas' two operating points (Fig. 9: 5.1 Hz, m = 0.102; Fig. 10: 50 Hz, m = 0.9; P = 1536 = 15.625 kHz
at 48 MHz, the points of `make demo`) the full core's golden-model arithmetic (fixed.modulate with the
compensation, fixed.snap_min_pulse, the dead-time FSM deadtime.simulate_events, valley updates, sample lead
fixed.SAMPLE_LEAD) drives the induction-motor model (motor.InverterMotor, gates = True: while both gates of a
leg are off its pole follows the current's sign; speed held at the equivalent-circuit point for 2.5 N m,
as `make demo`) period by period, in a closed loop:

* the controller measures the three phase currents at the valley (``--sample valley``: adc_trig_o with
  adc_trig_i = valley, the ripple-free V0 centre) or, as `make demo` does, in the sample clock S - 1 of the
  next update (``--sample lead``), optionally with Gaussian noise (``--noise``, % of the rated current);
* a comparator with hysteresis turns each current into its sign bit: negative (isign bit 1) below -band,
  positive above +band, else the last sign is kept;
* the core takes the three bits with the reference of the next valley update (isign_i, 1 = negative).

Printed: the phase-current THD to the 200th order (spectrum.current_thd over the window `make demo`
analyses), a row per run (dead time 0 and 1 us uncompensated as references, then 1 us compensated with each
band), a column per point and condition (where the currents are measured, noise). Band and noise are in %
of the motor model's rated current (3.07 A rms: motor.MotorParams at 230 V, 50 Hz, slip 0.064). --detail
adds a line per run: the fundamental, how often the applied 3-bit word changed over the run, and the
phase-periods whose applied sign differs from the current's at the middle of the period (the peak, where
the pulse is centred). With the currents taken in S - 1 and no band the motor gets the same gate edges and
segment boundaries (the harness' monitor word holds the poles too) as in make demo's RTL runs, so the
figures equal docs/demo.md's.

``--check`` replays the inputs the loop applied through CoreModel.run (the golden model of the core) and
asserts its gate edges equal the loop's on every clock, so the incremental loop is the core's timeline.

    python scripts/isign_hysteresis.py                  # both points, bands 0 1 2 5 10 %, noise 0 1 3 % (~35 s)
    python scripts/isign_hysteresis.py --noise 2 --sample valley --detail   # 2 % rms noise, one line per run
    python scripts/isign_hysteresis.py --points fig10 --bands 0,5 --check
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[1]
if str(REPO / "model") not in sys.path:
    sys.path.insert(0, str(REPO / "model"))

from svpwm_model import config, fixed  # noqa: E402
from svpwm_model import motor as M  # noqa: E402
from svpwm_model import spectrum as S  # noqa: E402
from svpwm_model.core import CoreModel, Inputs  # noqa: E402
from svpwm_model.deadtime import HI, LO, OFF, LegState, simulate_events  # noqa: E402

F_CLK = 48e6
P_DEMO = 1536            # 15.625 kHz at 48 MHz (scripts/demo.py P_VERMA)
DT_1US = 48
T_LOAD = 2.5             # N m, as scripts/demo.py DTC_T_LOAD
# name: (f_hz, m, analysed revolutions, warm-up revolutions), as scripts/demo.py DTC
POINTS = {"fig9": (5.1, 0.102, 1, 1), "fig10": (50.0, 0.9, 2, 4)}
BANDS = (0.0, 1.0, 2.0, 5.0, 10.0)
SAT = (1 << fixed.DT_WIDTH) - 1


def rated_current_rms(mp: M.MotorParams = M.MotorParams()) -> float:
    """The motor model's rated current (equivalent circuit at 230 V, 50 Hz, slip 0.064: 3.1 A rms)."""
    return M.equivalent_circuit(mp, mp.f_rated, mp.V_rated_line_rms / math.sqrt(3), 0.064)["i_s_rms"]


class SignDetector:
    """Three comparators with hysteresis: bit k = 1 (negative) below -band, 0 above +band, else kept."""

    def __init__(self, band: float, currents):
        self.band = band
        self.bits = sum(1 << k for k, i in enumerate(currents) if i < 0)

    def __call__(self, currents) -> int:
        for k, i in enumerate(currents):
            if i > self.band:
                self.bits &= ~(1 << k)
            elif i < -self.band:
                self.bits |= 1 << k
        return self.bits


def _period_targets(t: int, period: int, c: int | None) -> list[tuple[int, int]]:
    """(cycle, target) of one leg over the cycles [t + 1, t + 2P + 1) of the carrier period from valley t
    with compare value c (None: no values yet, gates off): the pole is high in [t + c + 1, t + 2P - c + 1)
    (core.py), the dead-time leg follows it."""
    if c is None:
        return [(t + 1, OFF)]
    if c >= period:
        return [(t + 1, LO)]
    if c == 0:
        return [(t + 1, HI)]
    return [(t + 1, LO), (t + c + 1, HI), (t + 2 * period - c + 1, LO)]


def run(f_hz: float, m: float, *, dt: int, dtc: bool, band_pct: float = 0.0, noise_pct: float = 0.0,
        sample: str = "valley", revs: int = 1, warmup_revs: int = 1, period: int = P_DEMO, seed: int = 1,
        n_periods: int | None = None, check: bool = False) -> dict:
    """One closed-loop run; returns its figures (and, with ``check``, asserts the golden model agrees)."""
    if sample not in ("valley", "lead"):
        raise ValueError("sample must be 'valley' or 'lead'")
    i_rated = rated_current_rms()
    band, sigma = band_pct / 100 * i_rated, noise_pct / 100 * i_rated
    rng = np.random.default_rng(seed)
    fw, mw = fixed.freq_word(f_hz), fixed.m_word(m)
    lead = fixed.latencies(config.FULL)["SAMPLE_LEAD"]
    f1 = fw / (6 * (1 << fixed.PHASE_WIDTH))               # cycles^-1
    P = period
    T = revs / abs(f1)
    k0 = 1 + int(math.ceil(warmup_revs / abs(f1) / (2 * P)))
    t0 = fixed.START_DELAY + 2 * P * k0 + 1                 # the analysed window [t0, t0 + T)
    n_per = n_periods or int(math.ceil((t0 + T - fixed.START_DELAY) / (2 * P))) + 2
    st = M.dtc_start(fw, m, P, dt, dtc, T_LOAD, lead, F_CLK)   # make demo's start state
    mot = M.InverterMotor(st["mp"], gates=True, fixed_speed=True, h_max=10e-6, trace=True)
    mot.set_state(st["ps"], st["pr"], st["wm"])
    mot.t = st["t_start"]
    det = SignDetector(band, mot.phase_currents())
    hdr, hdf = fixed.dtc_amounts(dt, dt, dtc)
    full = 6 << fixed.PHASE_WIDTH
    legs = [LegState(0, 0, SAT, True) for _ in range(3)]    # after a reset and a long idle
    leg_start = 0                                           # the legs are simulated up to this cycle
    cmp: tuple[int, int, int] | None = None                 # values active in the current period
    applied: list[int] = []                                 # isign of the update at t_{n+1}
    gate_words: list[tuple[int, int]] = []
    word = 0
    for n in range(n_per):
        t = fixed.START_DELAY + 2 * P * n
        # ---- the gates of period n (its values were computed at the update at t) ----
        ev: dict[int, dict[int, int]] = {}
        for ph in range(3):
            tg = _period_targets(t, P, None if cmp is None else cmp[ph])
            if leg_start < tg[0][0]:
                tg = [(leg_start, OFF)] + tg
            out, legs[ph] = simulate_events([(c, g, dt) for c, g in tg], t + 2 * P + 1, SAT, legs[ph],
                                            start=leg_start)
            for c, hi, lo in out:
                ev.setdefault(c, {})[ph] = hi | lo << 3
        leg_start = t + 2 * P + 1
        # the motor gets the gate words and, as in `make demo` (the harness' monitor word holds the poles
        # too), a segment boundary at every pole edge: the pole of a leg in its dead time is resolved by the
        # current's sign at the start of each segment
        poles = set() if cmp is None else {c for x in cmp if 0 < x < P for c in (t + x + 1, t + 2 * P - x + 1)}
        for c in sorted(set(ev) | poles):
            for ph, v in ev.get(c, {}).items():
                word = (word & ~(9 << ph)) | (v << ph)
            if c in ev and (not gate_words or gate_words[-1][1] != word):
                gate_words.append((c, word))
                mot.pending.append((c, -1, word))
            else:
                mot.pending.append((c, 0, 0))
        # ---- the controller: currents at the valley t (or at S - 1), signs with hysteresis ----
        s = t + 2 * P - lead                                # sample point S of the update at t + 2P
        t_meas = t if sample == "valley" else s - 1
        if t_meas > mot.t:
            mot.advance_to(t_meas)
        i = mot.phase_currents()
        if sigma:
            i = tuple(x + sigma * float(rng.standard_normal()) for x in i)
        isign = det(i)
        applied.append(isign)
        # ---- the update at t + 2P: the reference and isign sampled in S - 1 (fixed.modulate) ----
        th = (fw * (s - fixed.START_DELAY)) % full
        a16 = (th & ((1 << fixed.PHASE_WIDTH) - 1)) >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS)
        _, c_new, _, _ = fixed.modulate(fixed.MODE_FREQ, th >> fixed.PHASE_WIDTH, a16, P, m=mw, isign=isign,
                                        hdr=hdr, hdf=hdf)
        cmp = tuple(fixed.snap_min_pulse(c, P, dt) for c in c_new)
    end = fixed.START_DELAY + 2 * P * n_per
    mot.advance_to(end)
    res = dict(f_hz=f_hz, m=m, dt=dt, dtc=dtc, band_pct=band_pct, band_a=band, noise_pct=noise_pct,
               sample=sample, n_periods=n_per, lead=lead)
    if check:
        base = Inputs(freq=fw, m=mw, period=P, dt=dt, dtc=int(dtc))
        model = CoreModel(features=config.FULL)
        model.idle(SAT)
        r = model.run(base, [Inputs(freq=fw, m=mw, period=P, dt=dt, dtc=int(dtc), isign=x) for x in applied], n_per)
        mine = [(c, w) for c, w in gate_words if c < r.end]
        assert mine == r.gate_edges, "the loop's gate edges differ from CoreModel.run's"
        res["checked_edges"] = len(mine)
    tt, ii, _ = mot.trace.arrays()
    if n_periods is None:
        ci = S.current_spectrum(tt, ii.real, t0, T, revs)
        res.update(i_thd=S.current_thd(ci, revs), i1_rms=float(abs(ci[revs]) / math.sqrt(2)))
    # applied sign vs the current's sign at the middle (peak) of the period it acts in
    mids = np.asarray([fixed.START_DELAY + 2 * P * (n + 1) + P for n in range(n_per - 1)], dtype=np.float64)
    keep = (mids >= t0) & (mids < t0 + T) if n_periods is None else mids < end
    a = np.asarray(applied[:-1], dtype=np.int64)[keep]
    mid_i = np.interp(mids[keep], tt, ii.real), np.interp(mids[keep], tt, (ii * M.A.conjugate()).real), \
        np.interp(mids[keep], tt, (ii * M.A).real)
    wrong = sum(int(np.sum(((a >> k) & 1) != (mid_i[k] < 0))) for k in range(3))
    res.update(sign_changes=int(np.sum(np.diff(np.asarray(applied)) != 0)), wrong_sign_phase_periods=wrong,
               phase_periods=int(3 * np.sum(keep)))
    return res


def detail(rows: list[dict]) -> list[str]:
    """One line per run."""
    out = ["| point | currents | noise | run | band | phase-current THD | i1 rms | isign changes | wrong-sign |",
           "|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        out.append(f"| {r['point']} | {r['sample']} | {r['noise_pct']:g} % | {_run_name(r)} | {_band(r)} | "
                   f"{100 * r['i_thd']:.2f} % | {r['i1_rms']:.3f} A | {r['sign_changes']} | "
                   f"{r['wrong_sign_phase_periods']} / {r['phase_periods']} |")
    return out


def _run_name(r: dict) -> str:
    if r["dt"] == 0:
        return "dead time 0"
    return f"{r['dt']} clk " + ("+ compensation" if r["dtc"] else "uncompensated")


def _band(r: dict) -> str:
    return f"{r['band_pct']:g} %" if r["dtc"] and r["dt"] else "—"


def pivot(rows: list[dict], conds: list[tuple[str, float]], pts: list[str]) -> list[str]:
    """Phase-current THD in %: a row per run (the references once: they do not read isign), a column per point and
    condition (where the currents are measured, noise)."""
    lab = {"valley": "valley", "lead": "S−1"}
    head = "| run | band | " + " | ".join(f"{p}: {lab[s]}, noise {n:g}" for p in pts for s, n in conds) + " |"
    out = [head, "|---|---|" + "---|" * (len(pts) * len(conds))]
    keys = []
    for r in rows:
        k = (r["dt"], r["dtc"], r["band_pct"] if r["dtc"] and r["dt"] else None)
        if k not in keys:
            keys.append(k)
    for k in keys:
        cells = []
        for p in pts:
            for s, n in conds:
                hit = [r for r in rows if r["point"] == p and (r["dt"], r["dtc"]) == k[:2]
                       and (k[2] is None or (r["band_pct"] == k[2] and r["sample"] == s and r["noise_pct"] == n))]
                cells.append(f"{100 * hit[0]['i_thd']:.2f}" if hit else "")
        r0 = next(r for r in rows if (r["dt"], r["dtc"]) == k[:2])
        out.append(f"| {_run_name(r0)} | {'—' if k[2] is None else f'{k[2]:g}'} | " + " | ".join(cells) + " |")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", default="fig9,fig10", help="comma-separated: " + ", ".join(POINTS))
    ap.add_argument("--bands", default=",".join(f"{b:g}" for b in BANDS), help="hysteresis bands, %% of rated")
    ap.add_argument("--noise", default="0,1,3", help="rms noise on the measured currents, %% of rated (list)")
    ap.add_argument("--sample", default="valley,lead",
                    help="where the currents are measured: valley (adc_trig_o) and / or lead (the core's sample "
                         "clock S - 1: sign comparators wired to isign_i); with lead, only the first noise level")
    ap.add_argument("--dt", type=int, default=DT_1US, help="dead time, clocks (48 = 1 us)")
    ap.add_argument("--check", action="store_true", help="assert CoreModel.run gives the same gate edges")
    ap.add_argument("--detail", action="store_true", help="also print one line per run")
    ap.add_argument("--json", type=Path, help="write the rows here")
    a = ap.parse_args(argv)
    pts = [p.strip() for p in a.points.split(",") if p.strip()]
    bands = [float(x) for x in a.bands.split(",") if x.strip()]
    noises = [float(x) for x in a.noise.split(",") if x.strip()]
    samples = [x.strip() for x in a.sample.split(",") if x.strip()]
    conds = [(s, n) for s in samples for n in (noises if s == "valley" else noises[:1])]
    i_rated = rated_current_rms()
    rows = []
    t_start = time.perf_counter()
    for p in pts:
        f_hz, m, revs, wu = POINTS[p]
        cases = [(0, False, 0.0, conds[0]), (a.dt, False, 0.0, conds[0])]
        cases += [(a.dt, True, b, c) for c in conds for b in bands]
        for dt, dtc, b, (smp, nz) in cases:
            t1 = time.perf_counter()
            r = run(f_hz, m, dt=dt, dtc=dtc, band_pct=b, noise_pct=nz, sample=smp, revs=revs,
                    warmup_revs=wu, check=a.check)
            r["point"] = p
            rows.append(r)
            print(f"  {p}: dt {dt}, dtc {int(dtc)}, band {b:g} %, {smp}, noise {nz:g} %: i THD "
                  f"{100 * r['i_thd']:.2f} % ({time.perf_counter() - t1:.1f} s)", file=sys.stderr)
    print(f"isign hysteresis (scripts/isign_hysteresis.py, model only): phase-current THD (%) to the 200th order; "
          f"P = {P_DEMO} (15.625 kHz), sample lead {rows[0]['lead']} clocks, valley updates; band and noise "
          f"(rms) in % of the rated current {i_rated:.2f} A rms; currents measured at the valley "
          f"(adc_trig_o) or in the core's sample clock S−1 (comparators on isign_i)"
          f"{'; every edge == CoreModel.run' if a.check else ''} ({time.perf_counter() - t_start:.0f} s)")
    for line in pivot(rows, conds, pts):
        print(line)
    if a.detail:
        print()
        for line in detail(rows):
            print(line)
    if a.json:
        a.json.write_text(json.dumps(rows, indent=2) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
