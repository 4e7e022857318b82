# SPDX-License-Identifier: Apache-2.0
"""The generated register descriptions agree with each other: the C header (peakrdl-cheader) has the
Python description's offsets, masks and reset values (checked by the C compiler with static asserts),
and the Python description is self-consistent (no overlapping fields, 4-byte stride, PERIOD reset 1536).
The RTL is checked against the Python description by tb/cocotb/svpwm_bus on both simulators."""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

from svpwm_model import regmap as R

REPO = Path(__file__).resolve().parents[2]


def test_regmap_consistent():
    assert [r.addr for r in R.REGISTERS] == list(range(0, 4 * len(R.REGISTERS), 4))
    assert R.SIZE == 4 * len(R.REGISTERS)
    for r in R.REGISTERS:
        used = 0
        for f in r.fields:
            assert f.mask & used == 0, f"{r.name}.{f.name} overlaps"
            assert f.mask >> 32 == 0 and f.reset < (1 << f.width)
            used |= f.mask
    assert R.ID.reset == 0x53565057 and R.PERIOD.reset == 1536 and R.DT.reset == 0
    assert R.FREQ.field("freq").signed and R.FREQ.decode(0xFFFFFF)["freq"] == -1
    assert R.CTRL.encode(mode=7, en=1) == 0x701
    # CLK_HZ: appended at the next free offset (nothing moved), its value is the wrappers' ClkHz parameter
    assert (R.CMP_C.addr, R.CLK_HZ.addr, R.VERSION.reset) == (0x54, 0x58, 0x0002_0001)
    f = R.CLK_HZ.field("clk_hz")
    assert (f.kind, f.lsb, f.width, f.reset, f.rst_param) == ("const", 0, 32, 0, "ClkHz")


def _c_checks() -> str:
    lines = ['#include <stddef.h>', '#include "svpwm_regs.h"']
    for r in R.REGISTERS:
        lines.append(f"_Static_assert(offsetof(svpwm_t, {r.name}) == 0x{r.addr:X}, \"{r.name} offset\");")
        for f in r.fields:
            p = f"SVPWM__{r.name}__{f.name.upper()}"
            lines += [f"_Static_assert({p}_bm == 0x{f.mask:X}u, \"{p} mask\");",
                      f"_Static_assert({p}_bp == {f.lsb}, \"{p} lsb\");",
                      f"_Static_assert({p}_bw == {f.width}, \"{p} width\");",
                      f"_Static_assert({p}_reset == 0x{f.reset:X}u, \"{p} reset\");"]
    lines.append(f"_Static_assert(sizeof(svpwm_t) == 0x{R.SIZE:X}, \"size\");")
    return "\n".join(lines) + "\n"


def test_c_header_matches_regmap(tmp_path):
    assert shutil.which("cc"), "no C compiler (cc); the Makefile needs g++ / gcc anyway"
    src = tmp_path / "check.c"
    src.write_text(_c_checks())
    r = subprocess.run(["cc", "-std=c11", "-Wall", "-Werror", "-fsyntax-only", "-I", str(REPO / "sw"), str(src)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
