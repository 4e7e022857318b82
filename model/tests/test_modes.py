# SPDX-License-Identifier: Apache-2.0
"""Input modes of the golden model (fixed.modulate) checked against geometry, not against itself.

(a) alpha-beta vs polar, dq vs alpha-beta: the same vector gives the same compare values within one counter
    step (P <= 4095) and the same dwell-time vector within quantisation (any P);
(b) the three compare values, back through duty -> Clarke (zero sequence removed), give the commanded vector
    within the derived quantisation bound, every sector, every DPWM setting;
(c) overmodulation up to and beyond six-step: every C in [0, P] (T0 >= 0), sat exactly when the reference is
    outside the hexagon (up to the quantisation band), the clamped vector on the hexagon with the commanded angle;
(d) DPWM: line voltages identical to continuous SVPWM, DPWMMIN / DPWMMAX clamp a phase at P / 0, DPWM1 clamps
    each phase 120 deg per revolution in two 60 deg blocks;
(e) V/f law: boost at f = 0, linear, clamped at mmax, symmetric in the sign of f.

Units: "m units" = the modulation-index scale, 1.0 = the inscribed circle (M_ONE in UQ1.15, V_ONE in Q2.14);
the hexagon vertices are at 2/sqrt3. A phase is high for 2 (P - C) of 2P clocks, so its pole voltage about the
DC midpoint is u = 1/2 - C/P (in Udc) and the vector is v = sqrt3 * Clarke(u) in m units:
v_alpha = sqrt3 * 2/3 (u_a - (u_b + u_c)/2), v_beta = u_b - u_c (phase a at 0 deg, b at 120 deg, c at 240 deg);
a common shift of the three C (the zero sequence, i.e. the DPWM placement) cancels in both.
"""
from __future__ import annotations

import math
import random

import pytest

from svpwm_model import fixed as F

S3 = math.sqrt(3.0)
LSB = 2.0 ** -16                      # dwell-time LSB
ANGLE_LSB = 2 * math.pi / 65536       # one LSB of the 16-bit theta input, rad
M_VERTEX = int(round(2 / S3 * F.M_ONE))
TWO_PI = 2 * math.pi

# ---- error budget (derivation) ------------------------------------------------------------------------------
# Dwell times, polar path: the interpolated sine has |error| <= 0.5 (ROM rounding) + 0.5 (interpolation
# rounding) + (60 deg/256 in rad)^2 / 8 * 2^16 = 0.14 (linear-interpolation curvature) = 1.14 LSB; times
# m <= 2/sqrt3 and the product's rounding (0.5): |dT| <= 1.14 * 1.155 + 0.5 = 1.82 LSB per dwell time.
# alpha-beta path: sqrt3/2 is rounded (0.2 LSB per unit of |v_alpha| <= 2) and the product is rounded
# (0.5): <= 0.9 LSB per projection, so the polar bound covers it.
# A dwell time multiplies an active vector of length 2/sqrt3 (m units), so the dwell-time vector is off by
# at most 2/sqrt3 * (1.82 + 1.82) LSB = 4.2 LSB:
E_DWELL = 2 / S3 * 2 * 1.82 * LSB
# Compare values: A = floor(T1 P / 256) (and B) lose < 1/256 count each, C = floor(((P+1) 256 +- A +- B) / 512)
# = floor(P/2 (1 + k) + 1/2 - e) with 0 <= e < 2/512, so C - P/2 (1 + k) is in [-1/2 - 2/512, 1/2]:
# |e_k| <= 0.504 counts per phase, 0.504 / P in u. In m units |v|^2 = 2 sum (e_k - mean)^2 <= 2 * 3 e^2, so
E_CMP = math.sqrt(6) * (0.5 + 2 / 512)   # / P: the vector error of the compare-value rounding


def recon(c, p):
    """(v_alpha, v_beta) in m units from three compare values (zero sequence removed by Clarke)."""
    ua, ub, uc = (0.5 - x / p for x in c)
    return S3 * 2 / 3 * (ua - (ub + uc) / 2), ub - uc


def dwell_vector(sector, t1, t2):
    """The vector T1 V_s + T2 V_{s+1} in m units (|V| = 2/sqrt3, V_s at s * 60 deg)."""
    a0, a1 = math.radians(60 * sector), math.radians(60 * (sector + 1))
    r = 2 / S3 / F.D_ONE
    return r * (t1 * math.cos(a0) + t2 * math.cos(a1)), r * (t1 * math.sin(a0) + t2 * math.sin(a1))


def polar_dwell(m, theta):
    s, a16 = F.theta_split(theta)
    return (s, *F.duties(a16, m))


def modulate(mode, p, dpwm=F.DPWM_OFF, **kw):
    return F.modulate(mode, kw.pop("sector", 0), kw.pop("a16", 0), p, dpwm=dpwm, **kw)


def q214(x):
    """A float in m units as a Q2.14 word (saturating)."""
    return max(-32768, min(32767, round(x * F.V_ONE)))


def angdiff(a, b):
    return abs((a - b + math.pi) % TWO_PI - math.pi)


THETAS = list(range(0, 1 << 16, 97)) + [round(k * 65536 / 12) + d & 0xFFFF for k in range(12) for d in (-1, 0, 1)]
MS_IN = (0, 1, 0x1000, 0x4000, 0x6000, 0x7FFF, 0x8000, 0x8800, M_VERTEX)


# ---- (a) the paths agree -------------------------------------------------------------------------------------

@pytest.mark.parametrize("p", (48, 1000, 4095))
def test_ab_matches_polar_compare(p):
    """v_alpha = m/2 cos theta, v_beta = m/2 sin theta (integer words: UQ1.15 -> Q2.14 halves the word) gives
    the polar compare values within one count. Derivation: the two dwell-time sets differ by the Q2.14 input
    rounding (<= 0.5 * 2^-14 = 2 LSB per component) plus both paths' quantisation (<= 1.82 LSB each), i.e.
    k = +-T1 +-T2 differs by < 2 * (2 * 1.82 + 2 * 2) LSB = 16 LSB; P/2 * 16 LSB < 1/2 count for P <= 4095, and
    the floors of two numbers less than 1 apart differ by at most 1."""
    worst = 0
    for theta in THETAS:
        ph = theta * ANGLE_LSB
        for m in MS_IN:
            _, cp, satp, _ = modulate(F.MODE_POLAR, p, m=m, theta=theta)
            _, ca, sata, _ = modulate(F.MODE_AB, p, v1=round(m / 2 * math.cos(ph)), v2=round(m / 2 * math.sin(ph)))
            d = max(abs(x - y) for x, y in zip(cp, ca))
            worst = max(worst, d)
            assert d <= 1, f"theta {theta} m {m:#x} P {p}: polar {cp} vs alpha-beta {ca}"
    assert worst == 1          # the bound is tight: not a vacuous comparison


def test_ab_matches_polar_dwell():
    """The same at the dwell-time level, any P: the dwell-time vectors (sector independent, so a vector on a
    sector line may land in either neighbour) agree within 2 * E_DWELL + the input rounding (2/sqrt3 * 4 LSB)."""
    bound = 2 * E_DWELL + 2 / S3 * 4 * LSB
    worst = 0.0
    for theta in THETAS:
        ph = theta * ANGLE_LSB
        for m in MS_IN:
            vp = dwell_vector(*polar_dwell(m, theta))
            va = dwell_vector(*F.ab_dwell(round(m / 2 * math.cos(ph)), round(m / 2 * math.sin(ph))))
            err = math.dist(vp, va)
            worst = max(worst, err)
            assert err <= bound, f"theta {theta} m {m:#x}: polar {vp} vs alpha-beta {va}"
    assert worst > bound / 20


@pytest.mark.parametrize("p", (48, 1000, 4095))
def test_dq_matches_rotated_ab(p):
    """dq (v_d, v_q) at theta == alpha-beta of (v_d + j v_q) e^(j theta) rounded to Q2.14, within one count
    (the dq path's products are rounded once more than the alpha-beta path's: the same 16 LSB budget holds)."""
    rng = random.Random(3)
    worst = 0
    for theta in THETAS[::3]:
        ph = theta * ANGLE_LSB
        for _ in range(4):
            r, phi = rng.uniform(0, 1 / S3 * 2) / 2, rng.uniform(-math.pi, math.pi)   # |v| <= 2/sqrt3 (m units)
            vd, vq = round(r * math.cos(phi) * F.V_ONE * 2) // 2, round(r * math.sin(phi) * F.V_ONE * 2) // 2
            va = vd * math.cos(ph) - vq * math.sin(ph)
            vb = vd * math.sin(ph) + vq * math.cos(ph)
            _, cd, _, _ = modulate(F.MODE_DQ, p, theta=theta, v1=vd, v2=vq)
            _, ca, _, _ = modulate(F.MODE_AB, p, v1=round(va), v2=round(vb))
            d = max(abs(x - y) for x, y in zip(cd, ca))
            worst = max(worst, d)
            assert d <= 1, f"theta {theta} (v_d, v_q) ({vd}, {vq}) P {p}: dq {cd} vs alpha-beta {ca}"
    assert worst == 1


# ---- (b) compare values -> the commanded vector ----------------------------------------------------------------

@pytest.mark.parametrize("p", (48, 1000, 65535))
def test_reconstruct_polar_and_freq(p):
    """Polar (theta) and FREQ (sector + theta'), m up to the hexagon, every sector and DPWM setting: the vector
    from the compare values is m e^(j theta) within E_DWELL + E_CMP / P (module-level derivation)."""
    bound = E_DWELL + E_CMP / p
    worst, sectors = 0.0, set()
    for i, theta in enumerate(THETAS):
        for m in MS_IN:
            s, c, sat, _ = modulate(F.MODE_POLAR, p, dpwm=i % 4, m=m, theta=theta)
            if sat:
                continue
            sectors.add(s)
            ph = theta * ANGLE_LSB
            want = (m / F.M_ONE * math.cos(ph), m / F.M_ONE * math.sin(ph))
            err = math.dist(recon(c, p), want)
            worst = max(worst, err)
            assert err <= bound, f"polar theta {theta} m {m:#x} P {p} dpwm {i % 4}: {recon(c, p)} vs {want}"
    rng = random.Random(p)
    for _ in range(3000):
        sec, a16, m, dp = rng.randrange(6), rng.randrange(1 << 16), rng.randint(0, M_VERTEX), rng.randrange(4)
        _, c, sat, _ = modulate(F.MODE_FREQ, p, dpwm=dp, sector=sec, a16=a16, m=m)
        if sat:
            continue
        ph = math.radians(60 * (sec + a16 / 65536))
        err = math.dist(recon(c, p), (m / F.M_ONE * math.cos(ph), m / F.M_ONE * math.sin(ph)))
        worst = max(worst, err)
        assert err <= bound, f"freq sector {sec} a16 {a16} m {m:#x} P {p}"
    assert sectors == set(range(6))
    assert worst > bound / 10, f"worst {worst} vs bound {bound}: the bound is loose or the test is vacuous"


@pytest.mark.parametrize("p", (48, 1000, 65535))
def test_reconstruct_ab_and_dq(p):
    """alpha-beta and dq inputs inside the hexagon: the vector from the compare values is the commanded one
    (v1 + j v2 resp. (v_d + j v_q) e^(j theta), exact input words) within E_DWELL + E_CMP / P."""
    bound = E_DWELL + E_CMP / p
    rng = random.Random(p + 1)
    sectors = set()
    n = 0
    while n < 4000:
        mag, phi = rng.uniform(0, 2 / S3), rng.uniform(-math.pi, math.pi)
        v1, v2 = q214(mag * math.cos(phi)), q214(mag * math.sin(phi))
        dp = rng.randrange(4)
        if n % 2:
            theta = rng.randrange(1 << 16)
            s, c, sat, _ = modulate(F.MODE_DQ, p, dpwm=dp, theta=theta, v1=v1, v2=v2)
            ph = theta * ANGLE_LSB
            want = ((v1 * math.cos(ph) - v2 * math.sin(ph)) / F.V_ONE, (v1 * math.sin(ph) + v2 * math.cos(ph)) / F.V_ONE)
        else:
            s, c, sat, _ = modulate(F.MODE_AB, p, dpwm=dp, v1=v1, v2=v2)
            want = (v1 / F.V_ONE, v2 / F.V_ONE)
        if sat:
            continue
        n += 1
        sectors.add(s)
        err = math.dist(recon(c, p), want)
        assert err <= bound, f"mode {'dq' if n % 2 == 0 else 'ab'} v ({v1}, {v2}) P {p}: {recon(c, p)} vs {want}"
    assert sectors == set(range(6))
    # the zero vector: 50 % everywhere (continuous), sector 0
    assert modulate(F.MODE_AB, p) == (0, ((p + 1) // 2,) * 3, False, False)


# ---- (c) overmodulation ------------------------------------------------------------------------------------------

def _over_cases():
    """Polar m from 1.0 to 0xFFFF (beyond six-step and the vertex) and alpha-beta |v| up to 1.99, all angles."""
    out = []
    for theta in THETAS[::2]:
        for m in (0x8000, 0x8D00, 0x9000, M_VERTEX - 1, M_VERTEX, M_VERTEX + 1, 0xA000, 0xC000, 0xFFFF):
            ideal = m / F.M_ONE * math.cos(math.radians((6 * theta / 65536 % 1) * 60 - 30))
            out.append(("polar", dict(m=m, theta=theta), theta * ANGLE_LSB, ideal, polar_dwell(m, theta)))
    rng = random.Random(7)
    for _ in range(4000):
        mag, phi = rng.uniform(0.95, 1.99), rng.uniform(-math.pi, math.pi)
        v1, v2 = q214(mag * math.cos(phi)), q214(mag * math.sin(phi))
        ang = math.atan2(v2, v1)
        r = math.hypot(v1, v2) / F.V_ONE
        ideal = r * math.cos((math.degrees(ang) % 60 - 30) * math.pi / 180)
        out.append(("ab", dict(v1=v1, v2=v2), ang, ideal, F.ab_dwell(v1, v2)))
    for v1, v2 in ((-32768, -32768), (-32768, 32767), (32767, -32768), (32767, 32767), (-32768, 0), (0, -32768)):
        ang = math.atan2(v2, v1)
        ideal = math.hypot(v1, v2) / F.V_ONE * math.cos((math.degrees(ang) % 60 - 30) * math.pi / 180)
        out.append(("ab", dict(v1=v1, v2=v2), ang, ideal, F.ab_dwell(v1, v2)))
    return out


OVER = _over_cases()


@pytest.mark.parametrize("p", (48, 4095, 65535))
def test_overmodulation_compare_range(p):
    """T0 = 1 - T1 - T2 >= 0: every compare value in [0, P] in every DPWM setting; saturated vectors use the whole
    period (max C - min C >= P - 1, the -1 from the two floors / the 1 - 2^-16 cap)."""
    nsat = 0
    for i, (kind, kw, _, _, _) in enumerate(OVER):
        mode = F.MODE_POLAR if kind == "polar" else F.MODE_AB
        for dp in range(4):
            _, c, sat, _ = modulate(mode, p, dpwm=dp, **kw)
            assert all(0 <= x <= p for x in c), f"{kind} {kw} P {p} dpwm {dp}: {c}"
            if sat:
                nsat += dp == 0
                assert max(c) - min(c) >= p - 1, f"{kind} {kw} P {p}: saturated but T0 = {p - max(c) + min(c)} counts"
    assert nsat > len(OVER) // 2


def test_overmodulation_sat_and_boundary():
    """sat exactly when the reference is outside the hexagon: |v| cos(theta' - 30 deg) > 1 (float geometry),
    except within the dwell quantisation band (|ideal - 1| <= 2 * 1.82 LSB + the Q2.14 rounding for alpha-beta);
    the clamped dwell times lie on the boundary (T1 + T2 = 1, or 1 - 2^-16 when one of them hits the 16-bit cap),
    and keep the commanded angle within one theta LSB. Derivation of the angle bound: on the boundary |v| >= 1,
    q = floor(min 2^16 / (T1 + T2)) moves the vector along the edge by <= 2/sqrt3 LSB (<= 0.19 theta LSB of
    angle) and the unclamped dwell error (<= 4.2 LSB of vector, E_DWELL) turns it by <= 4.2 LSB / |v| rad
    = 0.67 theta LSB: 0.86 < 1 theta LSB (= 2 pi 2^-16 = 6.28 LSB rad)."""
    band_hits = worst = 0
    for kind, kw, ang, ideal, (s, t1, t2) in OVER:
        band = (2 * 1.82 + (4 if kind == "ab" else 0)) * LSB
        t1c, t2c, sat = F.hex_clamp(t1, t2)
        _, _, msat, _ = modulate(F.MODE_POLAR if kind == "polar" else F.MODE_AB, 1000, **kw)
        assert msat == sat
        if abs(ideal - 1) > band:
            assert sat == (ideal > 1), f"{kind} {kw}: sat {sat}, |v| cos(theta' - 30) = {ideal}"
        else:
            band_hits += 1
        if not sat:
            continue
        assert t1c + t2c in (F.D_ONE, F.D_ONE - 1), f"{kind} {kw}: clamped T1 + T2 = {t1c + t2c}"
        vx, vy = dwell_vector(s, t1c, t2c)
        d = angdiff(math.atan2(vy, vx), ang)
        worst = max(worst, d)
        assert d <= ANGLE_LSB, f"{kind} {kw}: clamped angle off by {d / ANGLE_LSB:.2f} theta LSB"
    assert band_hits < len(OVER) // 50
    assert worst > ANGLE_LSB / 20


# ---- (d) DPWM ------------------------------------------------------------------------------------------------------

def _dpwm_cases():
    rng = random.Random(11)
    out = []
    for _ in range(1500):
        p = rng.choice((48, 49, 1000, 4095, 65535, rng.randint(48, 65535)))
        if rng.random() < 0.5:
            out.append((F.MODE_POLAR, p, dict(m=rng.randint(0, 0xFFFF), theta=rng.randrange(1 << 16))))
        else:
            out.append((F.MODE_AB, p, dict(v1=rng.randint(-32768, 32767), v2=rng.randint(-32768, 32767))))
    return out


def test_dpwm_line_voltages_and_rails():
    """Line voltages (C differences) of DPWM 1..3 equal continuous SVPWM's exactly (a common integer shift; the
    rounding happened before it), C in [0, P]; DPWMMIN: the highest C is P (that phase stays low), DPWMMAX: the
    lowest is 0 (stays high), DPWM1: one of the two."""
    for mode, p, kw in _dpwm_cases():
        s0, c0, sat0, _ = modulate(mode, p, dpwm=F.DPWM_OFF, **kw)
        for dp in (F.DPWM_MIN, F.DPWM_MAX, F.DPWM_60):
            s, c, sat, _ = modulate(mode, p, dpwm=dp, **kw)
            assert (s, sat) == (s0, sat0)
            assert (c[0] - c[1], c[1] - c[2]) == (c0[0] - c0[1], c0[1] - c0[2]), f"{mode} {kw} P {p} dpwm {dp}"
            where = f"{mode} {kw} P {p} dpwm {dp}: {c}"
            assert all(0 <= x <= p for x in c), where
            if dp == F.DPWM_MIN:
                assert max(c) == p, where
            elif dp == F.DPWM_MAX:
                assert min(c) == 0, where
            else:
                assert max(c) == p or min(c) == 0, where


def clamp_runs(p, dpwm, m=0x6000, step=16):
    """Per phase, over one revolution of theta: the circular runs of (state, length in samples), state +1 =
    clamped high (C = 0), -1 = clamped low (C = P), 0 = switching; and the sample count."""
    n = (1 << 16) // step
    states = [[], [], []]
    for i in range(n):
        _, c, _, _ = modulate(F.MODE_POLAR, p, dpwm=dpwm, m=m, theta=i * step)
        for k in range(3):
            states[k].append(1 if c[k] == 0 else -1 if c[k] == p else 0)
    runs = []
    for st in states:
        j = next(i for i in range(n) if st[i] != st[i - 1])     # start at a state change
        rot = st[j:] + st[:j]
        r = []
        for x in rot:
            if r and r[-1][0] == x:
                r[-1][1] += 1
            else:
                r.append([x, 1])
        runs.append((r, rot, j))
    return runs, n


def test_dpwm_min_max_clamp_blocks():
    """DPWMMIN / DPWMMAX: each phase is clamped (low / high) for 120 deg per revolution in one block."""
    for dp, rail in ((F.DPWM_MIN, -1), (F.DPWM_MAX, 1)):
        runs, n = clamp_runs(1000, dp)
        for r, _, _ in runs:
            clamped = [ln for st, ln in r if st != 0]
            assert [st for st, _ in r if st != 0] == [rail]
            assert abs(clamped[0] - n / 3) <= 2, f"dpwm {dp}: clamped {clamped[0]} of {n} samples"


def test_dpwm1_clamps_60_deg_blocks():
    """DPWM1 (DPWM_60): each phase is clamped for 120 deg per revolution in two 60 deg blocks, high (C = 0) around
    its positive peak and low (C = P) around its negative peak (phase k peaks at k * 120 deg): the phase with the
    largest |reference| is clamped to its rail."""
    runs, n = clamp_runs(1000, F.DPWM_60)
    for k, (r, rot, j) in enumerate(runs):
        blocks = [(st, ln) for st, ln in r if st != 0]
        assert sorted(st for st, _ in blocks) == [-1, 1], f"phase {k}: clamp blocks {blocks}"
        for st, ln in blocks:
            assert abs(ln - n / 6) <= 2, f"phase {k}: {'high' if st > 0 else 'low'} block {ln} of {n} samples"
        hi = [(i + j) % n for i, x in enumerate(rot) if x == 1]
        centre = math.atan2(sum(math.sin(i * TWO_PI / n) for i in hi), sum(math.cos(i * TWO_PI / n) for i in hi))
        assert angdiff(centre, math.radians(120 * k)) < math.radians(2), f"phase {k}: high block not at its peak"


def test_dpwm1_example():
    """At theta = 0 phase a is at its positive peak (the largest |reference|): DPWM1 clamps it high (C_a = 0),
    the DPWMMAX result; a third of a sector later phase c's negative peak dominates: DPWMMIN. (A former model
    chose by min(C) + max(C) < P, which centred SVPWM never satisfies: DPWM1 was always DPWMMIN.)"""
    _, c_min, _, _ = modulate(F.MODE_POLAR, 1000, dpwm=F.DPWM_MIN, m=0x6000, theta=0)
    _, c_60, _, _ = modulate(F.MODE_POLAR, 1000, dpwm=F.DPWM_60, m=0x6000, theta=0)
    _, c_max, _, _ = modulate(F.MODE_POLAR, 1000, dpwm=F.DPWM_MAX, m=0x6000, theta=0)
    assert c_max[0] == 0 and c_60 == c_max != c_min
    _, c_min, _, _ = modulate(F.MODE_POLAR, 1000, dpwm=F.DPWM_MIN, m=0x6000, theta=65536 // 6)   # 60 deg
    _, c_60, _, _ = modulate(F.MODE_POLAR, 1000, dpwm=F.DPWM_60, m=0x6000, theta=65536 // 6)
    assert c_60 == c_min and c_min[2] == 1000


# ---- (e) V/f --------------------------------------------------------------------------------------------------------

LAWS = ((0x0800, 0x0100, 0x8000), (0x0800, 0x0181, M_VERTEX), (0x1000, 0x0100, 0x8000), (0, 0x0001, 0xFFFF),
        (0x0123, 0xFFFF, 0xFFFF), (0x4000, 0x0055, 0x6000), (0, 0, 0x8000))
SH = F.FREQ_WIDTH - 17


@pytest.mark.parametrize("law", LAWS)
def test_vf_law(law):
    """m = boost at f = 0; m = boost + fa * slope / 256 rounded (|error| <= 1/2 LSB) while below mmax, mmax above
    (clamp); the same for -f; non-decreasing in |f|; the low FREQ_WIDTH - 17 bits of |f| do not matter."""
    boost, slope, mmax = law
    assert F.vf_m(0, boost, slope, mmax) == min(boost, mmax)
    rng = random.Random(boost ^ slope)
    fas = sorted({0, 1, 2, 255, 256, 0xFFFF} | {rng.randrange(1 << 16) for _ in range(400)})
    prev = -1
    for fa in fas:
        lin = boost + fa * slope / 256
        for f in (fa << SH, (fa << SH) + (1 << SH) - 1):
            f = min(f, F.FREQ_MAX)
            m, mn = F.vf_m(f, boost, slope, mmax), F.vf_m(-f, boost, slope, mmax)
            assert m == mn, f"f {f}: m {m} vs m(-f) {mn}"
            if lin <= mmax - 0.5:
                assert abs(m - lin) <= 0.5, f"law {law} fa {fa}: m {m} vs linear {lin}"
            elif lin >= mmax + 0.5:
                assert m == mmax, f"law {law} fa {fa}: m {m} not clamped to {mmax}"
            assert m <= mmax and m >= prev
            prev = m
    assert F.vf_m(F.FREQ_MAX, boost, slope, mmax) == F.vf_m(-F.FREQ_MAX, boost, slope, mmax)


def test_vf_drives_modulator():
    """MODE_VF is MODE_FREQ with m from the law (the accumulator's angle, |f| only)."""
    rng = random.Random(17)
    for _ in range(500):
        sec, a16, p, dp = rng.randrange(6), rng.randrange(1 << 16), rng.randint(48, 65535), rng.randrange(4)
        f = rng.randint(-F.FREQ_MAX, F.FREQ_MAX)
        b, s, mx = rng.randrange(0x4000), rng.randrange(1 << 16) >> rng.randrange(16), rng.randrange(1 << 16)
        got = F.modulate(F.MODE_VF, sec, a16, p, freq=f, vf_boost=b, vf_slope=s, vf_mmax=mx, dpwm=dp)
        assert got == F.modulate(F.MODE_FREQ, sec, a16, p, m=F.vf_m(f, b, s, mx), dpwm=dp)
        assert got == F.modulate(F.MODE_VF, sec, a16, p, freq=-f, vf_boost=b, vf_slope=s, vf_mmax=mx, dpwm=dp)
