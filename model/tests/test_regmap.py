# SPDX-License-Identifier: Apache-2.0
"""The generated register descriptions agree with each other: the C header (peakrdl-cheader) has the
Python description's offsets, masks and reset values (checked by the C compiler with static asserts),
and the Python description is self-consistent (no overlapping fields, 4-byte stride, PERIOD reset 1536).
The RTL is checked against the Python description by tb/cocotb/svpwm_bus on both simulators."""
from __future__ import annotations

import re
import shutil
import subprocess
from pathlib import Path

import pytest

from svpwm_model import config
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
    # FEATURES (map 2.2; 3.0: the feature mask and the board cut), appended after CLK_HZ; DTC (2.4) after it
    assert (R.FEATURES.addr, R.VERSION.reset) == (0x5C, 0x0003_0001)
    # map 2.4: the falling dead time and its enable in DT beside dt, feature dtf, reset 0 (= dt)
    fields = {f.name: (f.lsb, f.width, f.kind, f.reset, f.features) for f in R.DT.fields}
    assert fields == {"dt": (0, 10, "rw", 0, ()), "dtf": (16, 10, "rw", 0, ("dtf",)),
                      "dtf_en": (31, 1, "rw", 0, ("dtf",))}, fields
    assert R.DT.encode(dt=48, dtf=30, dtf_en=1) == 0x801E_0030
    assert (R.DTC.addr, R.DTC.encode(en=1, isign=5)) == (0x60, 0x51)
    # map 3.1 (feature adc): the trigger points, the minimum window and the window report after DTC
    assert [(r.name, r.addr) for r in R.REGISTERS if r.addr > R.DTC.addr] == [
        ("ADC_PT0", 0x64), ("ADC_PT1", 0x68), ("WIN_MIN", 0x6C), ("WIN_LO_A", 0x70), ("WIN_LO_B", 0x74),
        ("WIN_LO_C", 0x78), ("WIN_HI_A", 0x7C), ("WIN_HI_B", 0x80), ("WIN_HI_C", 0x84), ("WIN_STATUS", 0x88)]
    assert R.SIZE == 0x8C
    for r in (R.ADC_PT0, R.ADC_PT1):
        assert {f.name: (f.lsb, f.width, f.kind) for f in r.fields} == {
            "cnt": (0, 16, "rw"), "dn": (16, 1, "rw"), "en": (31, 1, "rw")}, r.name
    assert R.ADC_PT1.encode(cnt=0x300, dn=1, en=1) == 0x8001_0300
    assert [(f.name, f.lsb, f.width, f.kind) for f in R.WIN_MIN.fields] == [("win_min", 0, 17, "rw")]
    for r in (R.WIN_LO_A, R.WIN_LO_B, R.WIN_LO_C, R.WIN_HI_A, R.WIN_HI_B, R.WIN_HI_C):
        assert [(f.lsb, f.width, f.kind) for f in r.fields] == [(0, 17, "status")], r.name
    assert {f.name: (f.lsb, f.width, f.kind) for f in R.WIN_STATUS.fields} == {
        "ok": (0, 3, "status"), "recon": (4, 2, "status")}
    f, t = R.FEATURES.field("features"), R.FEATURES.field("trim")
    assert (f.kind, f.lsb, f.width, f.reset, f.rst_param) == ("const", 0, 16, config.FULL, R.FEATURE_PARAM)
    assert (t.kind, t.lsb, t.width, t.reset, t.rst_param) == ("const", 31, 1, 0, R.TRIM_PARAM)
    assert (R.FEATURE_PARAM, R.TRIM_PARAM, R.FEATURES.mask()) == ("Features", "Trim", 0x8000_FFFF)
    assert R.FEATURES.encode(features=config.CONFIGS["foc"], trim=1) == 0x8000_7F9C
    # CONFIG (map 2.3): each width is the wrapper's parameter of that name, default the map's field widths
    assert {f.name: (f.rst_param, f.reset) for f in R.CONFIG.fields} == {
        "dt_width": ("DtWidth", 10), "cnt_width": ("CntWidth", 16), "freq_width": ("FreqWidth", 24),
        "phase_width": ("PhaseWidth", 34)}
    assert (R.PERIOD.field("period").width, R.DT.field("dt").width, R.MP.field("mp").width,
            R.FREQ.field("freq").width) == (16, 10, 10, 24)


# the feature(s) each register / field belongs to (issue 28): typed here once more on purpose, the
# generator's input (rdl/svpwm.rdl) is checked against this
FEATURE_REGS = {"FREQ": ("freq", "vf"), "THETA": ("polar", "dq"), "V1": ("ab", "dq"), "V2": ("ab", "dq"),
                "VF_BOOST": ("vf",), "VF_SLOPE": ("vf",), "VF_MMAX": ("vf",), "PRESC": ("presc",), "DTC": ("dtc",),
                **{n: ("adc",) for n in ("ADC_PT0", "ADC_PT1", "WIN_MIN", "WIN_LO_A", "WIN_LO_B", "WIN_LO_C",
                                         "WIN_HI_A", "WIN_HI_B", "WIN_HI_C", "WIN_STATUS")}}
FEATURE_FIELDS = {("CTRL", "sync_en"): ("sync",), ("CTRL", "upd"): ("upd",), ("CTRL", "dpwm"): ("dpwm",),
                  ("CTRL", "om"): ("sixstep",), ("CTRL", "vsc_off"): ("carry",), ("DT", "dtf"): ("dtf",),
                  ("DT", "dtf_en"): ("dtf",)}
# the iCEstick's board cut (Trim = 1), whatever the features
TRIM_REGS = {"MP", "CARRIER", "PERIOD_ACT", "CMP_A", "CMP_B", "CMP_C"}
TRIM_FIELDS = {("CTRL", "mode"), ("CTRL", "adc_trig"), ("STATUS", "sector")}
# what the iCEstick (tiny, Trim = 1) has: the map of the compact variant before map 3.0
TINY_TRIM_REGS = ["ID", "VERSION", "CONFIG", "CTRL", "FREQ", "M", "PERIOD", "DT", "STATUS", "CLK_HZ", "FEATURES"]
TINY_TRIM_CTRL = ["en", "trip_cbc", "safe_lo", "pol", "lock", "fault_clear"]


def test_feature_tags():
    for r in R.REGISTERS:
        assert r.features == FEATURE_REGS.get(r.name, ()), r.name
        assert r.trimmed == (r.name in TRIM_REGS), r.name
        for f in r.fields:
            assert f.features == (r.features or FEATURE_FIELDS.get((r.name, f.name), ())), f"{r.name}.{f.name}"
            assert f.trimmed == (r.trimmed or (r.name, f.name) in TRIM_FIELDS), f"{r.name}.{f.name}"
            if f.features or f.trimmed:  # absent: its output is a constant there, so reset 0 without a parameter
                assert f.reset == 0 and f.rst_param is None, f"{r.name}.{f.name}"


def test_variants():
    assert R.variant() == R.variant(config.FULL, False) == R.REGISTERS
    v = R.variant(config.TINY, True)
    assert [r.name for r in v] == TINY_TRIM_REGS                     # map order
    assert [f.name for f in v[3].fields] == TINY_TRIM_CTRL and [f.name for f in v[7].fields] == ["dt"]
    for r in v:
        full = R.BY_NAME[r.name]
        assert r.addr == full.addr and r.fields == tuple(f for f in full.fields if R.built(f, config.TINY, True))
    # minimal (POLAR only): no FREQ, V1, V2, VF_*, PRESC, DTC, ADC_PT*, WIN_*; CTRL without sync_en, upd, dpwm,
    # om, vsc_off
    adc = {"ADC_PT0", "ADC_PT1", "WIN_MIN", "WIN_LO_A", "WIN_LO_B", "WIN_LO_C", "WIN_HI_A", "WIN_HI_B", "WIN_HI_C",
           "WIN_STATUS"}
    m = {r.name: r for r in R.variant(config.CONFIGS["minimal"])}
    assert set(R.BY_NAME) - set(m) == {"FREQ", "V1", "V2", "VF_BOOST", "VF_SLOPE", "VF_MMAX", "PRESC", "DTC"} | adc
    assert adc & {r.name for r in R.variant(config.CONFIGS["vf"])} == set()
    assert [f.name for f in m["CTRL"].fields] == ["en", "trip_cbc", "safe_lo", "pol", "lock", "fault_clear",
                                                  "mode", "adc_trig"]
    assert R.absent_mask(R.CTRL, config.CONFIGS["minimal"]) == 0x000F_3002
    assert R.absent_mask(R.THETA, config.CONFIGS["vf"]) == 0xFFFF and R.absent_mask(R.THETA) == 0
    # foc: every register but FREQ and VF_* (ADC_PT*, WIN_* included), CTRL without dpwm and om
    f = {r.name: r for r in R.variant(config.CONFIGS["foc"])}
    assert set(R.BY_NAME) - set(f) == {"FREQ", "VF_BOOST", "VF_SLOPE", "VF_MMAX"}
    assert R.absent_mask(R.CTRL, config.CONFIGS["foc"]) == 0x0007_0000


def test_docs_show_features():
    """docs/registers.md has the features and trim columns per register."""
    rows = {}
    for line in (REPO / "docs/registers.md").read_text().splitlines():
        cells = [c.strip() for c in re.split(r"(?<!\\)\|", line.strip("|"))]     # `\|`: a | in a cell
        if len(cells) == 7 and cells[1] in R.BY_NAME:
            rows[cells[1]] = (cells[4], cells[5])
    assert set(rows) == set(R.BY_NAME)
    assert rows["THETA"] == ("polar\\|dq", "—") and rows["MP"] == ("—", "cut")
    assert rows["CTRL"] == ("sync_en: sync; upd: upd; dpwm: dpwm; om: sixstep; vsc_off: carry", "mode, adc_trig")
    assert rows["STATUS"] == ("—", "sector") and rows["ID"] == ("—", "—")


def test_c_header_features(tmp_path):
    """sw/svpwm_regs.h names the feature bits and the configurations (config.py), checked by the compiler."""
    lines = ['#include "svpwm_regs.h"']
    lines += [f"_Static_assert(SVPWM_FEAT_{n.upper()} == 0x{1 << i:X}u, \"{n}\");" for i, n in enumerate(config.FEATURES)]
    lines += [f"_Static_assert(SVPWM_CFG_{n.upper()} == 0x{v:X}u, \"{n}\");" for n, v in config.CONFIGS.items()]
    src = tmp_path / "feat.c"
    src.write_text("\n".join(lines) + "\n")
    r = subprocess.run(["cc", "-std=c11", "-Wall", "-Werror", "-fsyntax-only", "-I", str(REPO / "sw"), str(src)],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr


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
