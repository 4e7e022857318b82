#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Mutation testing of the hand-written RTL (`make mutate`, `make mutate-smoke`).

A source-level mutator: every hand-written file of rtl/ (not the generated ones: their header says
GENERATED) is scanned for mutation points outside comments, `ifdef FORMAL blocks, declarations and
elaboration checks:

  rel    a relational operator replaced (== !=, < <=, > >=)
  arith  + <-> -
  logic  && <-> ||, binary & <-> |, ^ -> |
  const  a number +1 or -1 (1'b0 <-> 1'b1; bit indices included: a swapped bit)
  cond   an if condition inverted
  stuck  an if condition of a clocked block stuck at 1 or 0 (stuck enable / stuck reset branch)
  assign a continuous assignment stuck at '0

A seeded sample (--count, spread over the files in proportion to their mutation points, at least two
per file) is generated into build/mutate/m<id>/rtl (a copy of rtl/ with one file changed). A mutant that
iverilog does not compile is "stillborn" and not counted. Each other mutant runs the fast kill subset of
its file (tests/KILL below: the unit test of the module first, then the system tests that contain it, on
Icarus -- the simulator that builds in a second -- stopping at the first failure); a mutant no test fails
is rerun on the wider set (WIDE: every Icarus test that instantiates the file). A test that fails or
times out kills the mutant. Survivors are checked against scripts/mutate_equivalent.json (mutants shown
equivalent, with the reason); what remains is "survived".

Writes build/mutate/report.md (score, per file, every survivor and equivalent with its diff) and
build/mutate/results.json. The score is killed / (generated - stillborn - equivalent).
"""
from __future__ import annotations

import argparse
from collections import Counter
import hashlib
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
RTL = REPO / "rtl"
OUT = REPO / "build" / "mutate"
SMOKE_FILES = ["deadtime.sv", "svpwm_carrier.sv", "svpwm_phase_acc.sv", "svpwm_wb_if.sv"]   # unit-tested, killed in seconds
EQUIV = REPO / "scripts" / "mutate_equivalent.json"

# pytest selections (files / -k expressions), on Icarus; fastest and most specific first
CORE_FAST = "tb/cocotb/svpwm_core/test_svpwm_core.py::test_svpwm_core"
UNIT = {
    "deadtime.sv": ["tb/cocotb/deadtime"],
    "svpwm_carrier.sv": ["tb/cocotb/svpwm_carrier"],
    "svpwm_phase_acc.sv": ["tb/cocotb/svpwm_phase_acc"],
    "svpwm_calc.sv": ["tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-full_cnt16-directed]",
                      "tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-full_cnt16-handshake]"],
    "svpwm_mul.sv": ["tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-full_serial-serial]",
                     "tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-full_cnt16-directed]",
                     "tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-full_cnt16-handshake]"],
    "svpwm_duty_lite.sv": ["tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-compact_cnt16-directed]",
                           "tb/cocotb/svpwm_calc/test_svpwm_calc.py::test_svpwm_calc[icarus-compact_cnt16-handshake]"],
    "svpwm_config.sv": ["tb/cocotb/svpwm_sync/test_svpwm_sync.py::test_svpwm_sync[icarus]"],   # (+ the core items)
    "svpwm_reference.sv": ["tb/cocotb/svpwm_core/test_svpwm_core_yosys.py"],   # the frequency clamp, exactly
    "svpwm_adc.sv": ["tb/cocotb/svpwm_core/test_svpwm_adc.py::test_svpwm_adc[icarus-default-points_valley]",
                     "tb/cocotb/svpwm_core/test_svpwm_adc.py::test_svpwm_adc[icarus-default-points_double]",
                     "tb/cocotb/svpwm_core/test_svpwm_adc.py::test_svpwm_adc[icarus-default-points_stop_restart]"],
    "svpwm_axil_if.sv": ["tb/cocotb/svpwm_bus/test_svpwm_bus_regs.py"],
    "svpwm_wb_if.sv": ["tb/cocotb/svpwm_bus/test_svpwm_bus_regs.py"],
    "svpwm_axil.sv": ["tb/cocotb/svpwm_bus/test_svpwm_bus.py::test_svpwm_bus[icarus-axil]"],
    "svpwm_wb.sv": ["tb/cocotb/svpwm_bus/test_svpwm_bus.py::test_svpwm_bus[icarus-wb]",
                    "tb/cocotb/svpwm_bus/test_svpwm_bus.py::test_svpwm_bus[icarus-wbc]"],
    "svpwm_mmio.sv": ["tb/cocotb/svpwm_bus/test_svpwm_bus.py::test_svpwm_bus[icarus-axil]",
                      "tb/cocotb/svpwm_bus/test_svpwm_bus.py::test_svpwm_bus[icarus-axil_cnt12]"],
}
# (node ids: test_svpwm_core[<sim>-<build>-<case>], builds as svpwm_tb.CORE_BUILDS; a selection that names no
# test is a harness error, checked before any mutant runs: preflight)
CORE_ITEMS = [f"{CORE_FAST}[icarus-default-{c}]" for c in ("config_and_safety", "full_only_inputs",
                                                            "clamps_and_disable", "reset_mid_run")] \
    + [f"{CORE_FAST}_freq16[icarus]"]
COMPACT_ITEMS = [f"{CORE_FAST}[icarus-compact-{c}]" for c in ("full_only_inputs", "clamps_and_disable")]
# (a node id given together with its file runs in the file's order: pytest merges them)
SYSTEM = ["tb/cocotb/svpwm_modes", "tb/cocotb/svpwm_core/test_svpwm_core.py", "tb/cocotb/svpwm_sync",
          "tb/cocotb/svpwm_bus", "tb/cocotb/svpwm_stress", "tb/cocotb/ice40_uart/test_ice40_uart.py::test_ice40_uart"]


BUS_FILES = ("svpwm_axil_if.sv", "svpwm_wb_if.sv", "svpwm_axil.sv", "svpwm_wb.sv", "svpwm_mmio.sv")
BUS_TIMEOUT = 240.0


def kill_set(fname: str) -> list[str]:
    sel = list(UNIT.get(fname, []))
    if fname == "svpwm_duty_lite.sv":
        return sel + COMPACT_ITEMS
    if fname in ("svpwm_axil_if.sv", "svpwm_wb_if.sv", "svpwm_axil.sv", "svpwm_wb.sv", "svpwm_mmio.sv"):
        return sel
    return sel + CORE_ITEMS + COMPACT_ITEMS[:1]


def wide_set(fname: str) -> list[str]:
    if fname in ("svpwm_axil_if.sv", "svpwm_wb_if.sv", "svpwm_axil.sv", "svpwm_wb.sv", "svpwm_mmio.sv"):
        return ["tb/cocotb/svpwm_bus", "tb/cocotb/ice40_uart/test_ice40_uart.py::test_ice40_uart"]
    sel = list(dict.fromkeys(UNIT.get(fname, [])))
    if fname in ("svpwm_calc.sv", "svpwm_mul.sv", "svpwm_duty_lite.sv"):
        sel = ["tb/cocotb/svpwm_calc"]
    return sel + SYSTEM


# ---------------------------------------------------------------------------------------------- mutator
@dataclass
class Mutant:
    id: str
    file: str
    line: int            # 1-based
    op: str
    orig: str            # the original line
    new: str             # the mutated line
    status: str = ""     # stillborn | killed | survived | equivalent
    by: str = ""         # the test that killed it / the equivalence reason
    seconds: float = 0.0
    ctx: str = ""        # the next non-blank line, when the original line's text is not unique in its file

    @property
    def key(self) -> str:
        """Stable across line shifts: file, operator, original and mutated line text (and, for a line whose
        text occurs more than once in the file, e.g. `if (!rst_ni) begin`, the line after it)."""
        ctx = f"|{self.ctx.strip()}" if self.ctx else ""
        return hashlib.sha1(f"{self.file}|{self.op}|{self.orig.strip()}|{self.new.strip()}{ctx}"
                            .encode()).hexdigest()[:12]


def hand_written() -> list[Path]:
    return [f for f in sorted(RTL.glob("*.sv")) if "GENERATED" not in "".join(f.read_text().splitlines()[:8])]


SKIP_LINE = re.compile(r"^\s*(module|endmodule|parameter|localparam|input|output|inout|import|typedef|package|"
                       r"function|endfunction|`|generate|endgenerate|genvar)\b")
DECL = re.compile(r"^\s*(logic|wire|reg|bit|int|integer|longint)\b[^=]*;\s*$")
NUM = re.compile(r"(?<![\w$'.])(\d+)?'([sS]?[bdhBDH])([0-9a-fA-F_]+)|(?<![\w$'.\]])\b(\d+)\b(?!')")


def code_part(line: str) -> tuple[str, str]:
    i = line.find("//")
    return (line, "") if i < 0 else (line[:i], line[i:])


def points(path: Path) -> list[tuple[int, str, str, str]]:
    """(line index, op, original line, mutated line) for every mutation point of a file."""
    out = []
    lines = path.read_text().splitlines()
    in_block = False
    skip_depth = 0          # `ifdef FORMAL nesting
    in_clocked = False
    for i, line in enumerate(lines):
        s = line.strip()
        if in_block:
            if "*/" in s:
                in_block = False
            continue
        if s.startswith("/*"):
            in_block = "*/" not in s
            continue
        if re.match(r"`if(n)?def\s+FORMAL", s) or (skip_depth and re.match(r"`if(n)?def", s)):
            skip_depth += 1
            continue
        if skip_depth:
            if s.startswith("`endif"):
                skip_depth -= 1
            continue
        if s.startswith("always_ff") or s.startswith("always @(posedge"):
            in_clocked = True
        elif s.startswith("always_comb") or s.startswith("assign") or s.startswith("always_latch"):
            in_clocked = False
        code, comment = code_part(line)
        cs = code.strip()
        if not cs or SKIP_LINE.match(cs) or DECL.match(cs) or "$fatal" in cs or "$error" in cs \
                or "$display" in cs or cs.startswith("case") or "gen_bad" in cs:
            continue
        # the assignment operator of a nonblocking assignment is not a relational operator
        m_nba = re.match(r"^(\s*[\w\[\]:.' +\-*{},]+?)\s*<=", code)
        protect = m_nba.end() if m_nba else 0
        if cs.startswith(("if", "else if", "end else if")) and "<=" in code:
            protect = 0
        if (cs.startswith("assign") or re.match(r"^\s*[\w\[\]:.]+\s*=[^=]", code)) and not protect:
            m_eq = re.match(r"^(.*?[^=!<>])=(?!=)", code)
            protect = m_eq.end() if m_eq else 0

        def add(op, start, end, repl):
            if start < protect:
                return
            new = code[:start] + repl + code[end:]
            if new != code:
                out.append((i, op, line, new + comment))

        for m in re.finditer(r"==|!=|<=|>=|(?<![<>=!])<(?![<=])|(?<![<>=\-])>(?![>=])", code):
            t = m.group(0)
            add("rel", m.start(), m.end(), {"==": "!=", "!=": "==", "<=": "<", ">=": ">", "<": "<=", ">": ">="}[t])
        for m in re.finditer(r"(?<=[\w\)\]'])\s*([+\-])\s*(?=[\w\(\{'])", code):
            if code[m.start(1) - 1:m.start(1)] in "+-" or code[m.end(1):m.end(1) + 1] in "+-:":
                continue
            if re.search(r"\[[^\]]*$", code[:m.start(1)]):          # inside a part-select / index: "const" does it
                continue
            add("arith", m.start(1), m.end(1), "-" if m.group(1) == "+" else "+")
        for m in re.finditer(r"&&|\|\|", code):
            add("logic", m.start(), m.end(), "||" if m.group(0) == "&&" else "&&")
        for m in re.finditer(r"(?<=[\w\)\]'}])\s*([&|^])(?![&|^=~])\s*(?=[\w\(\{~!'])", code):
            t = m.group(1)
            add("logic", m.start(1), m.end(1), {"&": "|", "|": "&", "^": "|"}[t])
        for m in NUM.finditer(code):
            if m.group(4) is not None:                       # plain decimal
                v = int(m.group(4))
                if re.search(r"#\s*\(?\s*$", code[:m.start()]):   # a delay
                    continue
                for d in (1, -1):
                    if v + d >= 0:
                        add("const", m.start(), m.end(), str(v + d))
            else:
                width, base, digits = m.group(1), m.group(2), m.group(3).replace("_", "")
                radix = {"b": 2, "d": 10, "h": 16}[base[-1].lower()]
                try:
                    v = int(digits, radix)
                except ValueError:
                    continue
                for d in (1, -1):
                    nv = v + d
                    if nv < 0 or (width and nv >= 1 << int(width)):
                        continue
                    b = base[-1].lower()
                    digits_new = format(nv, {"b": "b", "d": "d", "h": "x"}[b])
                    add("const", m.start(), m.end(), f"{width or ''}'{base[:-1]}{b}{digits_new}")
        m = re.match(r"^(\s*(?:end\s+)?(?:else\s+)?if\s*)\((.*)\)(\s*(?:begin\b.*)?)$", code) or \
            re.match(r"^(\s*(?:end\s+)?(?:else\s+)?if\s*)\((.*?)\)(\s+\w.*;.*)$", code)
        if m and m.group(2).count("(") == m.group(2).count(")"):
            pre, cond, post = m.group(1), m.group(2), m.group(3)
            out.append((i, "cond", line, f"{pre}(!({cond})){post}{comment}"))
            if in_clocked:
                out.append((i, "stuck", line, f"{pre}(1'b1){post}{comment}"))
                out.append((i, "stuck", line, f"{pre}(1'b0){post}{comment}"))
        m = re.match(r"^(\s*assign\s+[\w\[\]:.{}, ]+?\s*=)(.*);(\s*)$", code)
        if m and not re.fullmatch(r"\s*(\d*'[bdhBDH]0+|'0|0)\s*", m.group(2)):
            out.append((i, "assign", line, f"{m.group(1)} '0;{m.group(3)}{comment}"))
    return out


def generate(count: int, seed: int, files: list[Path]) -> list[Mutant]:
    rng = random.Random(seed)
    per = {f: points(f) for f in files}
    total = sum(len(p) for p in per.values())
    quota = {f: max(2, round(count * len(p) / total)) if p else 0 for f, p in per.items()}
    while sum(quota.values()) > count:                     # trim the largest down to the count
        f = max(quota, key=lambda k: quota[k])
        quota[f] -= 1
    while sum(quota.values()) < count:
        f = max(per, key=lambda k: len(per[k]) - quota[k])
        quota[f] += 1
    muts = []
    for f in files:
        pick = rng.sample(per[f], min(quota[f], len(per[f])))
        lines = f.read_text().splitlines()
        count_of = Counter(x.strip() for x in lines)
        for (i, op, orig, new) in sorted(pick):
            ctx = ""
            if count_of[orig.strip()] > 1:
                ctx = next((x for x in lines[i + 1:] if x.strip()), "")
            muts.append(Mutant(id="", file=f.name, line=i + 1, op=op, orig=orig, new=new, ctx=ctx))
    for k, m in enumerate(muts):
        m.id = f"m{k:03d}"
    return muts


# ------------------------------------------------------------------------------------------------ runner
def make_dir(m: Mutant) -> Path:
    d = OUT / m.id
    if d.exists():
        shutil.rmtree(d)
    (d / "rtl").mkdir(parents=True)
    for f in RTL.glob("*.sv"):
        shutil.copy2(f, d / "rtl" / f.name)
    lines = (RTL / m.file).read_text().splitlines(keepends=True)
    assert lines[m.line - 1].rstrip("\n") == m.orig, f"{m.id}: {m.file}:{m.line} changed"
    lines[m.line - 1] = m.new + "\n"
    (d / "rtl" / m.file).write_text("".join(lines))
    return d


def compiles(d: Path) -> bool:
    files = sorted((d / "rtl").glob("*.sv"))
    srcs = [f for f in files if f.name.endswith("_pkg.sv")] + [f for f in files if not f.name.endswith("_pkg.sv")]
    r = subprocess.run(["iverilog", "-g2012", "-o", str(d / "check.vvp")] + [str(s) for s in srcs],
                       capture_output=True, text=True)
    return r.returncode == 0


class HarnessError(RuntimeError):
    """pytest could not run the selection (not a failing test): the run stops instead of counting a kill."""


def preflight(files: list[Path], wide: bool) -> None:
    """Every pytest selection the mutants of these files will run collects at least one test on the unmutated
    RTL (a renamed test would otherwise make every mutant 'killed' by a usage error)."""
    sels = sorted({t for f in files for t in kill_set(f.name) + (wide_set(f.name) if wide else [])})
    cmd = [sys.executable, "-m", "pytest", "--collect-only", "-q", "-p", "no:cacheprovider", "-p", "no:xdist",
           "-o", "addopts=", *sels]
    env = dict(os.environ, SVPWM_SIMS="icarus", PYTHONPATH=f"{REPO / 'model'}:{REPO / 'tb/cocotb'}")
    r = subprocess.run(cmd, cwd=REPO, env=env, capture_output=True, text=True)
    missing = re.findall(r"ERROR: not found: (\S+)", r.stdout + r.stderr)
    if r.returncode != 0 or missing:
        raise HarnessError(f"the kill / wide selections do not all collect (exit {r.returncode}): "
                           f"{missing or (r.stdout + r.stderr)[-2000:]}")


def run_tests(d: Path, sel: list[str], timeout: float, log: Path) -> tuple[bool, str]:
    # a timeout counts as a kill (a mutant that hangs the design); the report says "timeout"
    """Run the pytest selection on the mutant; returns (all passed, the first failing test or '')."""
    # (CALC_DIRECTED_STRIDE=1: test_svpwm_calc's directed sets in full on Icarus as well, as `make sim` runs
    # them on Verilator; make sim runs a complete subset of the largest on Icarus)
    env = dict(os.environ, SVPWM_SIMS="icarus", SVPWM_RTL_DIR=str(d / "rtl"), SVPWM_SIM_BUILD=str(d / "sim"),
               PYTHONPATH=f"{REPO / 'model'}:{REPO / 'tb/cocotb'}", CALC_DIRECTED_STRIDE="1")
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", "-p", "no:xdist",
           "--durations=0", "-o", "addopts=", *sel]
    # own process group: on a timeout the simulator under pytest is ended with it (no orphan left running)
    p = subprocess.Popen(cmd, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        log.write_text(out or "")
        return False, f"timeout after {timeout:.0f} s"
    r = subprocess.CompletedProcess(cmd, p.returncode, out, "")
    log.write_text(r.stdout)
    if r.returncode == 0:
        return True, ""
    if r.returncode != 1:              # 1: tests failed; anything else (2 interrupted, 3 internal error, 4 usage:
        # a selection that names no test, 5 none collected) is the harness's fault, never a kill
        raise HarnessError(f"pytest exit {r.returncode} (not a test failure), log {log}")
    failed = re.findall(r"^FAILED (\S+)", r.stdout, re.M)
    return False, failed[0] if failed else "a test failed"


def evaluate(m: Mutant, timeout: float, equiv: dict, wide: bool, wide_cap: float = 3600.0,
             survived_kill: bool = False) -> Mutant:
    t = time.monotonic()
    if m.key in equiv:                  # shown equivalent (the reason is in the file): nothing can kill it
        m.status, m.by = "equivalent", equiv[m.key]["why"]
        return m
    d = make_dir(m)
    if not compiles(d):
        m.status, m.by = "stillborn", "iverilog does not compile it"
    else:
        # the bus interface tests wait for a handshake without a time limit of their own: a mutant that
        # breaks the handshake hangs them, so they get a shorter limit (they pass in < 70 s under load)
        limit = min(timeout, BUS_TIMEOUT) if m.file in BUS_FILES else timeout
        ok, by = (True, "") if survived_kill else run_tests(d, kill_set(m.file), limit, d / "kill.log")
        undecided = ""
        if ok and wide:
            ok, by = run_tests(d, wide_set(m.file), wide_cap, d / "wide.log")
            if by.startswith("timeout"):       # the wide set did not finish in the cap: not a kill
                ok, undecided, by = True, f"wide set not finished in {wide_cap:.0f} s", ""
            by = by and f"{by} (wide set)"
        m.status, m.by = ("killed", by) if not ok else ("survived", undecided)
    m.seconds = round(time.monotonic() - t, 1)
    if m.status in ("killed", "stillborn"):
        shutil.rmtree(d / "sim", ignore_errors=True)
    return m


def diff(m: Mutant) -> str:
    return f"-{m.orig.strip()}\n+{m.new.strip()}"


def report(muts: list[Mutant], args, wall: float) -> str:
    by = {s: [m for m in muts if m.status == s] for s in ("killed", "survived", "equivalent", "stillborn")}
    valid = len(muts) - len(by["stillborn"])
    nonequiv = valid - len(by["equivalent"])
    score = 100.0 * len(by["killed"]) / nonequiv if nonequiv else 0.0
    L = ["# Mutation testing report", "",
         f"`{' '.join(['scripts/mutate.py'] + sys.argv[1:])}` -- seed {args.seed}, {len(muts)} mutants of "
         f"{len({m.file for m in muts})} hand-written RTL files, kill subset on Icarus"
         f"{', wider set for survivors' if args.wide else ''}; wall time {wall / 60:.1f} min.", "",
         "| generated | stillborn (do not compile) | killed | survived | equivalent | score (killed / non-equivalent) |",
         "|---:|---:|---:|---:|---:|---:|",
         f"| {len(muts)} | {len(by['stillborn'])} | {len(by['killed'])} | {len(by['survived'])} | "
         f"{len(by['equivalent'])} | {score:.1f} % |", "",
         "## Per file", "", "| file | mutants | stillborn | killed | survived | equivalent |", "|---|---:|---:|---:|---:|---:|"]
    for f in sorted({m.file for m in muts}):
        ms = [m for m in muts if m.file == f]
        c = {s: sum(m.status == s for m in ms) for s in by}
        L.append(f"| {f} | {len(ms)} | {c['stillborn']} | {c['killed']} | {c['survived']} | {c['equivalent']} |")
    L += ["", "## Per operator", "", "| operator | mutants | killed | survived | equivalent |", "|---|---:|---:|---:|---:|"]
    for op in sorted({m.op for m in muts}):
        ms = [m for m in muts if m.op == op and m.status != "stillborn"]
        L.append(f"| {op} | {len(ms)} | {sum(m.status == 'killed' for m in ms)} | "
                 f"{sum(m.status == 'survived' for m in ms)} | {sum(m.status == 'equivalent' for m in ms)} |")
    for title, s in (("Survivors (no test fails: a missing test, or an equivalent mutant not yet shown)", "survived"),
                     ("Equivalent (scripts/mutate_equivalent.json)", "equivalent")):
        L += ["", f"## {title}", ""]
        if not by[s]:
            L.append("none")
        for m in by[s]:
            L += [f"- `{m.id}` key `{m.key}` {m.file}:{m.line} ({m.op}){': ' + m.by if m.by else ''}",
                  "  ```diff", *("  " + x for x in diff(m).splitlines()), "  ```"]
    L += ["", "## Killed: by which test", ""]
    kills: dict[str, int] = {}
    for m in by["killed"]:
        k = re.sub(r"\[.*", "", m.by.split("::")[-1]) if "::" in m.by else m.by
        kills[k] = kills.get(k, 0) + 1
    for k, n in sorted(kills.items(), key=lambda x: -x[1]):
        L.append(f"- {n} x {k}")
    return "\n".join(L) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=220, help="mutants to generate (default 220)")
    ap.add_argument("--seed", type=int, default=16)
    ap.add_argument("--files", nargs="*", help="only these rtl/ file names")
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--timeout", type=float, default=300, help="seconds per kill-subset run (exceeded: killed)")
    ap.add_argument("--no-wide", dest="wide", action="store_false", help="survivors: no rerun on the wider set")
    ap.add_argument("--wide-cap", type=float, default=3600.0,
                    help="seconds for the wider set; not finished in time: the mutant stays a survivor")
    ap.add_argument("--list", action="store_true", help="print the mutants and exit")
    ap.add_argument("--only", nargs="*", help="run only these mutant ids (e.g. the survivors of a --no-wide run); "
                                             "the report then merges them into the previous results.json")
    ap.add_argument("--min-score", type=float, default=None, help="exit 1 below this score (percent)")
    ap.add_argument("--expect-killed", action="store_true", help="exit 1 unless every valid mutant is killed")
    ap.add_argument("--out", type=Path, default=None, help="output directory (default build/mutate)")
    ap.add_argument("--smoke", action="store_true",
                    help="`make test`'s smoke run: 10 mutants of the unit-tested modules (seed 1), no wide set, "
                         "every one killed or listed equivalent; in build/mutate-smoke")
    args = ap.parse_args(argv)
    global OUT
    if args.smoke:
        args.count, args.seed, args.files, args.wide, args.expect_killed = 10, 1, SMOKE_FILES, False, True
        OUT = REPO / "build" / "mutate-smoke"
    if args.out:
        OUT = args.out.resolve()

    files = hand_written()
    if args.files:
        files = [f for f in files if f.name in args.files]
    muts = generate(args.count, args.seed, files)
    if args.list:
        for m in muts:
            print(f"{m.id} {m.key} {m.file}:{m.line} {m.op}\n  {diff(m)}")
        return 0
    OUT.mkdir(parents=True, exist_ok=True)
    try:
        preflight(files, args.wide)
    except HarnessError as e:
        print(f"mutate: ERROR -- {e}", file=sys.stderr)
        return 2
    equiv = json.loads(EQUIV.read_text()) if EQUIV.is_file() else {}
    previous = {}
    if args.only:
        prev_file = OUT / "results.json"
        previous = {r["id"]: r for r in json.loads(prev_file.read_text())} if prev_file.is_file() else {}
        keep = muts
        muts = [m for m in keep if m.id in args.only]
    t0 = time.monotonic()
    done = 0
    try:
        with ThreadPoolExecutor(args.jobs) as ex:
            # --only: a mutant that survived the kill subset before goes straight to the wider set
            for m in ex.map(lambda m: evaluate(m, args.timeout, equiv, args.wide, args.wide_cap,
                                               previous.get(m.id, {}).get("status") == "survived" and args.wide),
                            muts):
                done += 1
                print(f"[{done}/{len(muts)}] {m.id} {m.file}:{m.line} {m.op:6s} {m.status:10s} {m.seconds:6.1f} s"
                      f"  {m.by}", flush=True)
    except HarnessError as e:
        print(f"mutate: ERROR -- {e}", file=sys.stderr)
        return 2
    wall = time.monotonic() - t0
    if args.only:                        # merge: the rerun mutants replace their previous results
        ran = {m.id: m for m in muts}
        muts = [ran.get(m.id) or Mutant(**{k: v for k, v in previous[m.id].items() if k != "key"})
                if m.id in ran or m.id in previous else m for m in keep]
        muts = [m for m in muts if m.status]
    for m in muts:                       # a survivor shown equivalent since it ran
        if m.status == "survived" and m.key in equiv:
            m.status, m.by = "equivalent", equiv[m.key]["why"]
    if args.smoke:
        shutil.rmtree(OUT, ignore_errors=True)
        OUT.mkdir(parents=True)
    (OUT / "results.json").write_text(json.dumps([asdict(m) | {"key": m.key} for m in muts], indent=1))
    rep = report(muts, args, wall)
    (OUT / "report.md").write_text(rep)
    print(rep.split("## Per file")[0])
    print(f"report: {OUT / 'report.md'}")
    valid = [m for m in muts if m.status != "stillborn"]
    nonequiv = [m for m in valid if m.status != "equivalent"]
    score = 100.0 * sum(m.status == "killed" for m in muts) / len(nonequiv) if nonequiv else 0.0
    if args.expect_killed and any(m.status == "survived" for m in muts):
        print("mutate: FAILED -- a mutant survived (see the report)", file=sys.stderr)
        return 1
    if args.min_score is not None and score < args.min_score:
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
