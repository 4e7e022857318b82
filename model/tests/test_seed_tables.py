# SPDX-License-Identifier: Apache-2.0
"""The ideal model (svpwm_model.ideal) against the seeds' tables, and the bit-exact model against both.

Tolerances: exact tables (fractions of E) are compared to 1e-12; Verma's printed magnitudes are rounded to
three decimals (0.999 for 1) and are compared to 1.1e-3; fixed point vs ideal uses the documented bound of
1.0 counts per compare value.
"""
from __future__ import annotations

import functools
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from svpwm_model import fixed, ideal
from svpwm_model.tables import (AVR495_TABLE_4_1, AVR495_TABLE_4_1_ERRATA, AVR495_TABLE_4_2,
                                AVR495_TABLE_4_3, MINAS_TABLE_I, VERMA_COLUMNS, VERMA_TABLE_1,
                                VERMA_TABLE_1_ERRATA)

REPO = Path(__file__).resolve().parents[2]
STATES = [(a, b, c) for a in (0, 1) for b in (0, 1) for c in (0, 1)]
A16 = np.arange(1 << 16, dtype=np.int64)
SECTORS = np.arange(6, dtype=np.int64)
P_DEFAULT = 1536
M_WORDS = (0, 1, 328, 3277, 16384, 32767, 32768)
EXACT = 1e-12


def code(state) -> int:
    a, b, c = state
    return 4 * a + 2 * b + c


def full_angle(sector, a16) -> np.ndarray:
    """theta = sector*60 deg + a16/65536*60 deg (rad)."""
    return (np.asarray(sector, dtype=np.float64) + np.asarray(a16, dtype=np.float64) / 65536.0) * (math.pi / 3)


# ---- AVR495 Table 4-1 / Verma Table 1: switching states -> voltages ------------------------------------

@pytest.mark.parametrize("state", STATES)
def test_state_voltages_avr495_table_4_1(state):
    row = dict(AVR495_TABLE_4_1[state])
    row.update(AVR495_TABLE_4_1_ERRATA.get(state, {}))
    v = ideal.state_voltages(*state)
    for key in ("Vab", "Vbc", "Vca", "Van", "Vbn", "Vcn", "alpha", "beta"):
        assert abs(float(v[key]) - row[key]) < EXACT, (state, key, float(v[key]), row[key])


def test_avr495_table_4_1_errata_are_errors():
    """The corrected entries follow from the seed's own formulas; the printed ones do not."""
    for state, fixes in AVR495_TABLE_4_1_ERRATA.items():
        printed = AVR495_TABLE_4_1[state]
        v = ideal.state_voltages(*state)
        assert abs(printed["Van"] + printed["Vbn"] + printed["Vcn"]) > 0.1       # printed: neutral not balanced
        # AVR495 sec. 4.1: V_bn = (V_bc - V_ab)/3, V_cn = (V_ca - V_bc)/3 from the row's own line voltages
        assert abs((printed["Vbc"] - printed["Vab"]) / 3 - fixes["Vbn"]) < EXACT
        assert abs((printed["Vca"] - printed["Vbc"]) / 3 - fixes["Vcn"]) < EXACT
        for key, val in fixes.items():
            assert abs(printed[key] - val) > 0.1
            assert abs(float(v[key]) - val) < EXACT


def test_avr495_vector_numbering():
    """Table 4-1's V_k lies at (k-1)*60 deg (the text's e^{j(k-1)2pi/3} would put V2 at 120 deg)."""
    for state, row in AVR495_TABLE_4_1.items():
        assert row["S"] == f"S{code(state)}"          # S_i: i = the state read as binary a b c
        k = int(row["V"][1:])
        if k in (0, 7):
            assert row["alpha"] == row["beta"] == 0.0
            continue
        assert abs(complex(row["alpha"], row["beta"]) - np.exp(1j * (k - 1) * math.pi / 3)) < EXACT


@pytest.mark.parametrize("state", STATES)
def test_state_voltages_verma_table_1(state):
    printed = dict(zip(VERMA_COLUMNS, VERMA_TABLE_1[state]))
    printed.update(VERMA_TABLE_1_ERRATA.get(state, {}))
    v = ideal.state_voltages(*state)
    got = dict(VRN=v["Van"], VYN=v["Vbn"], VBN=v["Vcn"], VRY=v["Vab"], VYB=v["Vbc"], VBR=v["Vca"])
    for key, val in got.items():
        assert abs(float(val) - printed[key]) < EXACT, (state, key)
    vec = complex(float(v["alpha"]), float(v["beta"]))
    # magnitudes are printed to three decimals, truncated (0.999 for exactly 1)
    assert abs(abs(vec) - printed["Mag"]) < 1.1e-3, (state, abs(vec))
    if abs(vec) > 0.5:   # angle of an active vector, compared modulo 360 deg (Verma prints -120 for 240)
        diff = (math.degrees(math.atan2(vec.imag, vec.real)) - printed["Ang"] + 180.0) % 360.0 - 180.0
        assert abs(diff) < 1e-9, (state, diff)
    else:
        assert printed["Ang"] == 0.0


def test_verma_table_1_errata_are_errors():
    for state, fixes in VERMA_TABLE_1_ERRATA.items():
        printed = dict(zip(VERMA_COLUMNS, VERMA_TABLE_1[state]))
        assert abs(printed["VRN"] + printed["VYN"] + printed["VBN"]) > 0.1
        for key, val in fixes.items():
            assert abs(printed[key] - val) > 0.1


def test_avr495_and_verma_tables_agree_except_errata():
    """Both seeds' state tables agree entry by entry except the listed misprints (one in each)."""
    pairs = (("Van", "VRN"), ("Vbn", "VYN"), ("Vcn", "VBN"), ("Vab", "VRY"), ("Vbc", "VYB"), ("Vca", "VBR"))
    disagree = set()
    for state in STATES:
        avr, ver = AVR495_TABLE_4_1[state], dict(zip(VERMA_COLUMNS, VERMA_TABLE_1[state]))
        for ka, kv in pairs:
            if abs(avr[ka] - ver[kv]) > EXACT:
                disagree.add((state, ka))
    expected = {(s, k) for s, f in AVR495_TABLE_4_1_ERRATA.items() for k in f}
    expected |= {(s, dict(VRN="Van", VYN="Vbn", VBN="Vcn")[k]) for s, f in VERMA_TABLE_1_ERRATA.items() for k in f}
    assert disagree == expected


# ---- AVR495 Table 4-2 / 4-3: duty cycles and compare values --------------------------------------------

@pytest.mark.parametrize("sector", range(6))
def test_ideal_compare_matches_avr495_table_4_2(sector):
    """Table 4-2's per-sector d_k, d_k+1 (functions of the full theta) == the unified d_a, d_b (sec. 4.2),
    and Table 4-3 fed with them gives ideal_compare."""
    theta = (sector + (np.arange(200) + 0.5) / 200.0) * (math.pi / 3)
    m = np.linspace(0.0, 1.0, 11)[:, None]
    (ok, sk), (ok1, sk1) = AVR495_TABLE_4_2[sector]
    dk, dk1 = m * np.sin(ok + sk * theta), m * np.sin(ok1 + sk1 * theta)
    sec, da, db = ideal.ideal_duties(theta, m)
    assert np.all(sec == sector)
    np.testing.assert_allclose(da, dk, rtol=0, atol=1e-12)
    np.testing.assert_allclose(db, dk1, rtol=0, atol=1e-12)
    for period in (32, P_DEFAULT, 65535):
        coef = np.asarray(AVR495_TABLE_4_3[sector], dtype=np.float64)        # (3 phases, 2)
        want = period / 2.0 * (1.0 + dk[..., None] * coef[:, 0] + dk1[..., None] * coef[:, 1])
        np.testing.assert_allclose(ideal.ideal_compare(theta, m, period), want, rtol=0, atol=1e-9 * period)


def test_split_angle():
    theta = np.linspace(-30.0, 30.0, 200001)
    sector, tp = ideal.split_angle(theta)
    assert sector.min() == 0 and sector.max() == 5
    assert np.all((tp >= 0) & (tp < math.pi / 3))
    back = np.exp(1j * (sector * math.pi / 3 + tp))
    np.testing.assert_allclose(back, np.exp(1j * theta), rtol=0, atol=1e-12)
    s, t = ideal.split_angle(np.array([-1e-300, -math.pi / 3 * 0.5, 2 * math.pi, 7 * math.pi / 6]))
    assert list(s) == [0, 5, 0, 3]   # -1e-300 rounds to 2pi mod 2pi: sector 0, theta' = 0
    np.testing.assert_allclose(t, [0.0, math.pi / 6, 0.0, math.pi / 6], atol=1e-12)


# ---- Minas Table I: switching state sequence ----------------------------------------------------------

def test_minas_table_i_is_centre_aligned_one_leg_per_step():
    for row in MINAS_TABLE_I:
        assert len(row) == 7 and row[0] == (0, 0, 0) and row[3] == (1, 1, 1)
        assert row[4:] == row[:3][::-1]
        assert all(sum(x != y for x, y in zip(p, q)) == 1 for p, q in zip(row, row[1:]))


@pytest.mark.parametrize("sector", range(6))
def test_ideal_state_sequence_is_minas_table_i(sector):
    """Strictly inside the sector (theta' grid of midpoints, never 30 deg) and m in (0, 1]: all four
    dwell times are non-zero and the sequence is Table I's first half."""
    want = list(MINAS_TABLE_I[sector][:4])
    tps = (np.arange(64) + 0.5) / 64.0
    for m in (0.001, 0.01, 0.1, 0.3, 0.5, 0.8, 0.95, 0.999, 1.0):
        cmp = ideal.ideal_compare(full_angle(sector, tps * 65536), m, P_DEFAULT)
        for row in cmp:
            assert ideal.state_sequence(row, P_DEFAULT) == want, (sector, m, row)


def test_state_sequence_ties_and_limits():
    p = 100
    assert ideal.state_sequence([20, 40, 60], p) == [(0, 0, 0), (1, 0, 0), (1, 1, 0), (1, 1, 1)]
    assert ideal.state_sequence([20, 20, 60], p) == [(0, 0, 0), (1, 1, 0), (1, 1, 1)]
    assert ideal.state_sequence([50, 50, 50], p) == [(0, 0, 0), (1, 1, 1)]
    assert ideal.state_sequence([0, 40, 100], p) == [(1, 0, 0), (1, 1, 0)]      # 000 and 111 have no dwell
    assert ideal.state_sequence([0, 40, 100]) == [(1, 0, 0), (1, 1, 0), (1, 1, 1)]  # no P: all turn on
    assert ideal.state_sequence([-5, 40, 130], p) == [(1, 0, 0), (1, 1, 0)]     # outside [0, P]: clipped
    assert ideal.state_sequence([100, 100, 100], p) == [(0, 0, 0)]
    # ideal model at a sector edge (theta' = 0: d_b = 0): b and c switch together in sector 0
    assert ideal.state_sequence(ideal.ideal_compare(0.0, 0.5, p), p) == [(0, 0, 0), (1, 0, 0), (1, 1, 1)]


def test_state_sequence_codes_match_scalar():
    rng = np.random.default_rng(1)
    cmp = rng.integers(0, 9, size=(2000, 3))
    codes = ideal.state_sequence_codes(cmp, 8)
    for row, cd in zip(cmp, codes):
        assert [code(s) for s in ideal.state_sequence(row, 8)] == [int(x) for x in cd if x >= 0]


@pytest.mark.parametrize("m_word", [32768, 16384, 328, 0])
def test_fixed_state_sequence_skips_never_reorders(m_word):
    """Bit-exact compare values, all 65536 a16 per sector: every sequence is a sub-sequence of Table I's
    first half (ties skip states), and it is the whole of it whenever the four dwells are non-zero."""
    skipped = 0
    for sector in range(6):
        cmp = fixed.compare_values_np(sector, A16, m_word, P_DEFAULT)
        codes = ideal.state_sequence_codes(cmp, P_DEFAULT)
        valid = codes >= 0
        pos = np.full(8, -1)
        pos[[code(s) for s in MINAS_TABLE_I[sector][:4]]] = np.arange(4)
        where = np.where(valid, pos[np.where(valid, codes, 0)], 99)
        assert np.all(where[valid] >= 0), "state outside Table I's row"
        step = np.diff(where, axis=-1)
        assert np.all((step > 0) | (~valid[..., 1:])), "states reordered"
        cs = np.sort(cmp, axis=-1)
        all_dwell = (cs[:, 0] > 0) & (cs[:, 2] < P_DEFAULT) & np.all(np.diff(cs, axis=-1) > 0, axis=-1)
        assert np.array_equal(valid.sum(-1) == 4, all_dwell)
        if m_word == 0:
            assert np.all(codes == [0, 7, -1, -1])
        skipped += int(np.count_nonzero(~all_dwell))
    print(f"\nm_word {m_word}, P {P_DEFAULT}: {skipped} of {6 << 16} periods skip a state")
    # m = 1.0 at theta' = 30 deg touches the hexagon: no zero vector; exact in fixed point
    c = fixed.compare_values_np(0, 32768, 32768, P_DEFAULT)
    assert list(c) == [0, P_DEFAULT // 2, P_DEFAULT]
    assert ideal.state_sequence(c, P_DEFAULT) == [(1, 0, 0), (1, 1, 0)]


# ---- cross-checks of the ideal model -------------------------------------------------------------------

def test_sector_formulation_equals_minmax_injection():
    theta = np.linspace(-2 * math.pi, 4 * math.pi, 60001)
    for m in np.linspace(0.0, 1.0, 21):
        err = np.abs(ideal.ideal_pole_duty(theta, m) - ideal.minmax_pole_duty(theta, m)).max()
        assert err < 1e-12, (m, err)


def test_average_vector_reproduces_reference():
    theta = np.linspace(0.0, 2 * math.pi, 6 * 1000 + 1)
    for m in np.linspace(0.0, 1.0, 11):
        got = ideal.average_vector(theta, m)
        np.testing.assert_allclose(got, m / math.sqrt(3) * np.exp(1j * theta), rtol=0, atol=1e-12)
    # the same from the switching states: sum of dwell * state vector (AVR495 Table 4-1 alpha/beta * 2/3)
    theta, m = 1.234, 0.77
    p = 1.0
    c = ideal.ideal_compare(theta, m, p)
    bounds = np.concatenate([[0.0], np.sort(c), [p]])
    acc = 0j
    for lo, hi in zip(bounds[:-1], bounds[1:]):
        st = tuple(int(lo >= cx) for cx in c)
        row = AVR495_TABLE_4_1[st]
        acc += (hi - lo) / p * complex(row["alpha"], row["beta"]) * 2.0 / 3.0
    assert abs(acc - m / math.sqrt(3) * np.exp(1j * theta)) < 1e-12


def test_pole_duty_range_and_line_voltage_peak():
    theta = np.linspace(0.0, 2 * math.pi, 36001)
    d = ideal.ideal_pole_duty(theta, 1.0)
    assert d.min() >= -1e-15 and d.max() <= 1 + 1e-15
    line = d[:, 0] - d[:, 1]   # average V_ab in units of Udc: peak m*Udc
    assert abs(np.abs(line).max() - 1.0) < 1e-6


# ---- fixed point vs ideal ------------------------------------------------------------------------------

@functools.lru_cache(maxsize=None)
def _ideal_unit(m_word: int) -> np.ndarray:
    """ideal_compare at P = 1 for all (sector, a16), shape (6, 65536, 3); C scales linearly with P."""
    theta = full_angle(SECTORS[:, None], A16[None, :])
    return ideal.ideal_compare(theta, m_word / 32768.0, 1.0)


@functools.lru_cache(maxsize=None)
def _max_error(period: int) -> float:
    """max |C_fixed - C_ideal| over sectors, all a16 and M_WORDS at half period P."""
    worst = 0.0
    for mw in M_WORDS:
        cf = fixed.compare_values_np(SECTORS[:, None], A16[None, :], mw, period)
        worst = max(worst, float(np.abs(cf - period * _ideal_unit(mw)).max()))
    return worst


@pytest.mark.parametrize("period", [32, 100, 1536, 4096, 16384])
def test_fixed_compare_within_one_count_of_ideal(period):
    err = _max_error(period)
    assert err <= 1.0, (period, err)


def test_fixed_compare_bound_largest_power_of_two():
    """Informative: the largest power-of-two P <= 65535 for which the 1-count bound holds."""
    ok = [p for p in (1 << k for k in range(5, 16)) if _max_error(p) <= 1.0]
    largest = max(ok)
    print(f"\nfixed vs ideal: max error <= 1 count up to P = {largest} (powers of two); "
          + ", ".join(f"P={p}: {_max_error(p):.4f}" for p in (16384, 32768, 65535)))
    assert largest >= 16384
    assert ok == [1 << k for k in range(5, largest.bit_length())]   # holds at every smaller power of two


def test_fixed_compare_bound_fails_at_max_period():
    """Informative: at P = 65535 the error exceeds 1 count (about 1.58 with m_word = 32767, 1.37 at
    m = 1.0).  If this fails, precision improved: update the documented bound."""
    err = _max_error(65535)
    assert err > 1.0, f"max error at P = 65535 is now {err:.4f} <= 1: update the docs"


def test_fixed_scalar_equals_vectorised():
    rng = np.random.default_rng(2024)
    n = 3000
    sec = rng.integers(0, 6, n)
    a16 = rng.integers(0, 1 << 16, n)
    m = rng.integers(0, fixed.M_ONE + 1, n)
    per = rng.integers(fixed.MIN_PERIOD, 1 << 16, n)
    vec = fixed.compare_values_np(sec, a16, m, per)
    for i in range(n):
        assert fixed.compare_values(int(sec[i]), int(a16[i]), int(m[i]), int(per[i])) == tuple(vec[i])


@pytest.mark.parametrize("period", [32, 1536, 65535])
def test_fixed_compare_in_range(period):
    for mw in M_WORDS + (8192, 24576, 32000, 32700):
        cf = fixed.compare_values_np(SECTORS[:, None], A16[None, :], mw, period)
        assert cf.min() >= 0 and cf.max() <= period, (period, mw, cf.min(), cf.max())


# ---- sine ROM ------------------------------------------------------------------------------------------

def test_sine_table():
    t = fixed.sine_table()
    assert len(t) == 257
    for i, v in enumerate(t):
        assert v == round(math.sin(math.radians(i * 60.0 / 256)) * 65536), i
    assert all(b > a for a, b in zip(t, t[1:]))
    assert t[0] == 0 and t[128] == 32768


def test_generated_tables_match_model():
    """rtl/sine_rom.sv and rtl/svpwm_sector_sel.sv are what scripts/gen_tables.py makes from the model."""
    r = subprocess.run([sys.executable, "scripts/gen_tables.py", "--check"], cwd=REPO,
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stdout + r.stderr
