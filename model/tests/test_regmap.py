# SPDX-License-Identifier: Apache-2.0
"""The generated register descriptions agree with each other: the C header (peakrdl-cheader) has the
Python description's offsets, masks and reset values (checked by the C compiler with static asserts),
and the Python description is self-consistent (no overlapping fields, 4-byte stride, PERIOD reset 1536).
The RTL is checked against the Python description by tb/cocotb/svpwm_bus on both simulators."""
from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

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
    assert (R.CMP_C.addr, R.CLK_HZ.addr) == (0x54, 0x58)
    f = R.CLK_HZ.field("clk_hz")
    assert (f.kind, f.lsb, f.width, f.reset, f.rst_param) == ("const", 0, 32, 0, "ClkHz")
    # FEATURES (map 2.2): appended after CLK_HZ, bit 0 = the Compact parameter; maps 2.3, 2.4: the same offsets
    assert (R.FEATURES.addr, R.VERSION.reset) == (0x5C, 0x0002_0004)
    # map 2.4: the falling dead time and its enable in DT beside dt, full variant only, reset 0 (= dt)
    fields = {f.name: (f.lsb, f.width, f.kind, f.reset, f.compact) for f in R.DT.fields}
    assert fields == {"dt": (0, 10, "rw", 0, True), "dtf": (16, 10, "rw", 0, False),
                      "dtf_en": (31, 1, "rw", 0, False)}, fields
    assert R.DT.encode(dt=48, dtf=30, dtf_en=1) == 0x801E_0030
    # map 2.4: DTC appended after FEATURES, the full variant only
    assert (R.DTC.addr, R.SIZE, R.DTC.encode(en=1, isign=5)) == (0x60, 0x64, 0x51)
    assert not R.DTC.compact
    f = R.FEATURES.field("compact")
    assert (f.kind, f.lsb, f.width, f.reset, f.rst_param, f.compact) == ("const", 0, 1, 0, R.VARIANT_PARAM, True)
    assert R.VARIANT_PARAM == "Compact" and R.FEATURES.mask() == 1
    # CONFIG (map 2.3): each width is the wrapper's parameter of that name, default the map's field widths
    assert {f.name: (f.rst_param, f.reset) for f in R.CONFIG.fields} == {
        "dt_width": ("DtWidth", 10), "cnt_width": ("CntWidth", 16), "freq_width": ("FreqWidth", 24),
        "phase_width": ("PhaseWidth", 34)}
    assert (R.PERIOD.field("period").width, R.DT.field("dt").width, R.MP.field("mp").width,
            R.FREQ.field("freq").width) == (16, 10, 10, 24)


# what the compact core uses (FREQ mode, continuous SVPWM, valley updates, no sync start; map 2.3: no MP,
# the core runs with a minimum pulse of 0 -- what fits the iCEstick's HX1K)
COMPACT_REGS = {"ID", "VERSION", "CONFIG", "CTRL", "FREQ", "M", "PERIOD", "DT", "STATUS", "CLK_HZ", "FEATURES"}
COMPACT_CTRL = ["en", "trip_cbc", "safe_lo", "pol", "lock", "fault_clear"]
COMPACT_DT = ["dt"]            # map 2.4: the compact core has one dead time (no dtf, dtf_en)
PARTIAL = {"CTRL": COMPACT_CTRL, "DT": COMPACT_DT}     # registers only some of whose fields are compact


def test_compact_variant():
    assert {r.name for r in R.REGISTERS if r.compact} == COMPACT_REGS
    for name, compact in PARTIAL.items():
        assert [f.name for f in R.BY_NAME[name].fields if f.compact] == compact
    for r in R.REGISTERS:
        for f in r.fields:
            if r.name not in PARTIAL:
                assert f.compact == r.compact, f"{r.name}.{f.name}"
            if not f.compact:        # absent: its output is a constant there, so reset 0 without a parameter
                assert f.reset == 0 and f.rst_param is None, f"{r.name}.{f.name}"
    assert R.variant(False) == R.REGISTERS
    v = R.variant(True)
    assert [r.name for r in v] == [r.name for r in R.REGISTERS if r.name in COMPACT_REGS]   # map order
    for r in v:
        full = R.BY_NAME[r.name]
        assert r.addr == full.addr and r.fields == tuple(f for f in full.fields if f.compact)
    assert {f.name for f in [r for r in v if r.name == "CTRL"][0].fields} == set(COMPACT_CTRL)


def test_docs_show_compact():
    """docs/registers.md has the compact column: yes / the present fields / a dash, per register."""
    rows = {}
    for line in (REPO / "docs/registers.md").read_text().splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 6 and cells[1] in R.BY_NAME:
            rows[cells[1]] = cells[4]
    assert set(rows) == set(R.BY_NAME)
    for r in R.REGISTERS:
        present = [f.name for f in r.fields if f.compact]
        exp = "yes" if len(present) == len(r.fields) else ", ".join(present) if present else "—"
        assert rows[r.name] == exp, f"{r.name}: docs say {rows[r.name]!r}, regmap {exp!r}"


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


@pytest.mark.parametrize("std", ["c99", "c11"])
def test_c_header_std(tmp_path, std):
    """sw/svpwm_regs.h compiles as C99 and as C11 (gcc -Wall -Werror); its named CTRL.mode values are the
    model's mode codes (fixed.MODE_*), checked by the compiler in a C99-compatible way."""
    from svpwm_model import fixed

    assert shutil.which("gcc"), "gcc not found: run scripts/install-deps.sh"
    names = {"FREQ": fixed.MODE_FREQ, "VF": fixed.MODE_VF, "POLAR": fixed.MODE_POLAR,
             "ALPHABETA": fixed.MODE_AB, "DQ": fixed.MODE_DQ}
    lines = ['#include "svpwm_regs.h"']
    lines += [f"typedef char mode_{n}[SVPWM__CTRL__MODE__{n} == {v} ? 1 : -1];" for n, v in names.items()]
    lines += ["uint32_t ctrl_dq(void) {",
              "  return (uint32_t)SVPWM__CTRL__MODE__DQ << SVPWM__CTRL__MODE_bp & SVPWM__CTRL__MODE_bm;", "}"]
    src = tmp_path / "std.c"
    src.write_text("\n".join(lines) + "\n")
    r = subprocess.run(["gcc", f"-std={std}", "-Wall", "-Werror", "-Wno-unused-local-typedefs", "-c", "-o",
                        str(tmp_path / "std.o"), "-I", str(REPO / "sw"), str(src)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
