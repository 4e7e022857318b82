# SPDX-License-Identifier: Apache-2.0
"""Floating-point ideal SVPWM, written from the seeds' equations (shared/seeds/*.txt); plain numpy.

An independent reference for the bit-exact model (``fixed.py``): nothing here is imported from it.

Normalisation (project-wide): m = 1 is the inscribed circle of the hexagon; phase fundamental peak
= m*Udc/sqrt3, line-to-line fundamental peak = m*Udc.  Seed conversions:

* Minas eq. (2): ma (0 < ma <= 100 %, U_max = inscribed circle)  ->  m = ma.
* AVR495 Table 4-2: 2/sqrt3 * V_s/E  ->  m (V_s in the seed's unscaled Concordia frame, |V_k| = E).
* Verma eqs. (29)-(30): m_i <= sqrt3/2  ->  m = 2/sqrt3 * m_i.

Sectors are 0..5 (= the seeds' 1..6), sector k covers [k*60 deg, (k+1)*60 deg).  Switching states are
tuples of bits (a, b, c), MSB first like Minas Table I ("100" = a on).  Compare values follow AVR495
Table 4-3: C_x = P/2 * (1 + k_x) for an up/down counter 0..P..0, phase x high while counter >= C_x, so
phase x is high for the fraction (P - C_x)/P = (1 - k_x)/2 of the carrier period.
"""
from __future__ import annotations

import math

import numpy as np

from .tables import AVR495_TABLE_4_3, State

SECTOR_RAD = math.pi / 3
_TWO_PI = 2.0 * math.pi
_SQRT3 = math.sqrt(3.0)

# AVR495 Table 4-3 as an array: [sector, phase, (coef of d_a, coef of d_b)]
_T43 = np.asarray(AVR495_TABLE_4_3, dtype=np.float64)


def split_angle(theta) -> tuple[np.ndarray, np.ndarray]:
    """Full angle (rad, any real) -> (sector 0..5, theta' in [0, pi/3)).

    AVR495 sec. 4.2: theta' = theta - (k - 1)*pi/3 with the seed's sector k = 1..6 (code sector = k - 1);
    sec. 4.3 keeps theta' in [0, pi/3) and counts the sector modulo 6.
    """
    t = np.mod(np.asarray(theta, dtype=np.float64), _TWO_PI)
    sector = np.floor(t / SECTOR_RAD).astype(np.int64)
    tp = t - sector * SECTOR_RAD
    # float rounding at the sector edges: move theta' back into [0, pi/3)
    low = tp < 0.0
    sector = np.where(low, sector - 1, sector)
    tp = np.where(low, tp + SECTOR_RAD, tp)
    high = tp >= SECTOR_RAD
    sector = np.where(high, sector + 1, sector)
    tp = np.where(high, tp - SECTOR_RAD, tp)
    sector = np.mod(sector, 6)                             # theta mod 2pi may round up to 2pi: sector 6 -> 0
    tp = np.clip(tp, 0.0, np.nextafter(SECTOR_RAD, 0.0))
    return sector, tp


def ideal_duties(theta, m) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(sector, d_a, d_b): dwell fractions of the two active vectors bounding the sector.

    d_a = m sin(pi/3 - theta'), d_b = m sin(theta')  -- Minas eq. (4) (d_x, d_y with ma = m),
    AVR495 sec. 4.2 (unified d_a, d_b), Verma eqs. (29)-(30) with t/T0 and m = 2/sqrt3 * m_i.
    d_a weights the vector at sector*60 deg, d_b the one at (sector+1)*60 deg; d_0 = 1 - d_a - d_b.
    Overmodulation: a vector outside the hexagon (d_a + d_b > 1, possible for m > 1) is scaled back onto
    its boundary keeping its angle, d_a, d_b -> d_a, d_b / (d_a + d_b), so d_0 = 0 (never negative).
    """
    sector, tp = split_angle(theta)
    m = np.asarray(m, dtype=np.float64)
    da, db = m * np.sin(SECTOR_RAD - tp), m * np.sin(tp)
    s = np.maximum(da + db, 1.0)
    return sector, da / s, db / s


def _k(theta, m) -> np.ndarray:
    """k_x = 4/Ts * C_x - 1 for the three phases, AVR495 Table 4-3; shape (..., 3)."""
    sector, da, db = ideal_duties(theta, m)
    sector, da, db = np.broadcast_arrays(sector, da, db)
    coef = _T43[sector]                                   # (..., 3, 2)
    return coef[..., 0] * da[..., None] + coef[..., 1] * db[..., None]


def ideal_compare(theta, m, period) -> np.ndarray:
    """Compare values (C_a, C_b, C_c), shape (..., 3): AVR495 Table 4-3, C = Ts/4 (1 + k) = P/2 (1 + k).

    ``period`` is P, the counter's top (half carrier period, in counts).
    """
    p = np.asarray(period, dtype=np.float64)[..., None]
    return p / 2.0 * (1.0 + _k(theta, m))


def ideal_pole_duty(theta, m) -> np.ndarray:
    """Fraction of the carrier period each phase is high, (..., 3): (P - C)/P = (1 - k)/2 (AVR495 Table 4-3)."""
    return (1.0 - _k(theta, m)) / 2.0


def minmax_pole_duty(theta, m) -> np.ndarray:
    """Pole duties as carrier-based PWM with min-max common-mode injection, (..., 3).

    Sinusoidal references v_x = m/sqrt3 cos(theta - x*2pi/3) (units of Udc, phase peak m*Udc/sqrt3), plus
    the common mode -(max v + min v)/2: duty_x = 1/2 + v_x - (max(v) + min(v))/2.  Equivalent to SVPWM with
    equal zero-vector halves (AVR495 sec. 4.1 "T_0 = T_7"; AVR495 ref. [5] Zhou & Wang; Minas sec. II:
    "SPWM with harmonic addition").
    """
    theta = np.asarray(theta, dtype=np.float64)
    m = np.asarray(m, dtype=np.float64)
    theta, m = np.broadcast_arrays(theta, m)
    shifts = np.array([0.0, 2.0 * math.pi / 3.0, -2.0 * math.pi / 3.0])
    v = (m / _SQRT3)[..., None] * np.cos(theta[..., None] - shifts)
    cm = (v.max(axis=-1) + v.min(axis=-1)) / 2.0
    return 0.5 + v - cm[..., None]


def state_voltages(a, b, c) -> dict[str, np.ndarray]:
    """Voltages of switching state (a, b, c) in units of Udc (AVR495 Table 4-1 with E = Udc; Verma eqs. 1-5).

    Keys: Vab, Vbc, Vca (line), Van, Vbn, Vcn (phase to the isolated neutral, AVR495 sec. 4.1
    V_n = (V_a + V_b + V_c)/3), alpha, beta (AVR495's Concordia matrix [[1, -1/2, -1/2], [0, sqrt3/2,
    -sqrt3/2]] on (V_an, V_bn, V_cn), unscaled: active vectors have length 1 = E, Verma "unity").
    """
    va, vb, vc = (np.asarray(x, dtype=np.float64) for x in (a, b, c))   # pole voltages vs. the - rail
    vn = (va + vb + vc) / 3.0
    van, vbn, vcn = va - vn, vb - vn, vc - vn
    return dict(Vab=va - vb, Vbc=vb - vc, Vca=vc - va, Van=van, Vbn=vbn, Vcn=vcn,
                alpha=van - vbn / 2.0 - vcn / 2.0, beta=_SQRT3 / 2.0 * (vbn - vcn))


def average_vector(theta, m) -> np.ndarray:
    """Average output voltage vector over a carrier period, complex alpha + j beta in units of Udc.

    Scaling: 2/3 of AVR495's Concordia (amplitude-invariant transform, v = 2/3 (v_an + a v_bn + a^2 v_cn),
    a = e^{j 2pi/3}), so a balanced set of phase voltages with peak A maps to A e^{j theta}: the ideal
    modulator gives m/sqrt3 * e^{j theta}.  (AVR495's unscaled frame would give 3/2 of that, sqrt3/2 m E, the
    seed's V_s; active vectors have length 2/3 here.)  Computed from the pole duties only, so it checks the
    whole chain duty -> compare value -> switching pattern against the reference.
    """
    d = ideal_pole_duty(theta, m)                         # average pole voltage = d * Udc
    v = d - d.mean(axis=-1, keepdims=True)                # average phase-to-neutral voltages
    a = np.exp(2j * math.pi / 3.0)
    return (2.0 / 3.0) * (v[..., 0] + a * v[..., 1] + a * a * v[..., 2])


def state_sequence_codes(compare_values, period=None) -> np.ndarray:
    """Vectorised :func:`state_sequence`: state codes 4a+2b+c in visiting order, padded with -1; (..., 4)."""
    c = np.asarray(compare_values, dtype=np.float64)
    top = np.inf if period is None else np.asarray(period, dtype=np.float64)[..., None]
    c = np.clip(c, 0.0, top)
    bounds = np.sort(np.concatenate([np.zeros(c.shape[:-1] + (1,)), c], axis=-1), axis=-1)   # (..., 4)
    valid = bounds < top
    valid[..., 1:] &= bounds[..., 1:] != bounds[..., :-1]          # equal C: one transition, state skipped
    bits = bounds[..., :, None] >= c[..., None, :]                  # (..., 4 boundaries, 3 phases)
    codes = bits[..., 0] * 4 + bits[..., 1] * 2 + bits[..., 2] * 1
    codes = np.where(valid, codes, -1)
    order = np.argsort(~valid, axis=-1, kind="stable")               # visited states first, order kept
    return np.take_along_axis(codes, order, axis=-1)


def state_sequence(compare_values, period=None) -> list[State]:
    """Switching states visited in the first half of a carrier period (counter 0 -> P), in order.

    A phase is high while counter >= C (AVR495 Table 4-3 register semantics), so the state on
    [b, next boundary) has the phases with C <= b high, b in sorted {0, C_a, C_b, C_c}.  Only states with a
    non-zero dwell are listed; the second half is the mirror image (Minas Table I).

    * Phases with equal C switch on the same clock: the state between them is skipped, never reordered.
    * The initial 000 is listed only if every C > 0; C <= 0 means "high for the whole period".
    * The final 111 is listed only if every C < P; C >= P means "never high" (the counter's top P is the
      last count of the up-ramp and the zero vector 111 would have zero dwell).  Without ``period`` every
      phase is assumed to turn on within the half period (P = infinity), so the list always ends in 111.

    Minas Table I's first half (e.g. 000, 100, 110, 111 in sector 0) is the result whenever all four
    dwell times are non-zero; the sequences for ties are sub-sequences of it.
    """
    codes = state_sequence_codes(compare_values, period)
    if codes.ndim != 1:
        raise ValueError("state_sequence takes one (C_a, C_b, C_c); use state_sequence_codes for arrays")
    return [((int(x) >> 2) & 1, (int(x) >> 1) & 1, int(x) & 1) for x in codes if x >= 0]


# ---- overmodulation: the line fundamental of the two laws (floating point, from the geometry) -------------
SIX_STEP = 2.0 * _SQRT3 / math.pi      # line fundamental of six-step operation, in Udc (1.1027)
M_VERTEX_F = 2.0 / _SQRT3              # m of the hexagon's vertices


def overmod_gain(m: float) -> float:
    """The six-step law's stretch g as a real number (fixed.om_gain / 256): 1 + 256 (m - 2/sqrt3), at least 1."""
    return 1.0 + 256.0 * max(0.0, m - M_VERTEX_F)


def overmod_fundamental(m: float, six_step: bool = False, n: int = 7200) -> float:
    """Line-to-line fundamental peak in Udc for a circular reference of magnitude m (m = 1: the inscribed
    circle, fundamental 1.0 Udc), sampled continuously (n points per revolution): inside the hexagon the
    reference itself; outside it the angle-keeping clamp (Minas eq. (5) with T0 = 0: the boundary point at
    the reference's angle), and with ``six_step`` the vector's position on the hexagon side stretched from the
    side's middle by g = overmod_gain(m) (the boundary point's distance from the middle times g, at most half
    a side): held at the vertex where g times it reaches half a side. g = 1 is the clamp; g -> infinity
    six-step (SIX_STEP). Fundamental = |mean(v e^(-j theta))| of the vector in inscribed-circle units."""
    th = (np.arange(n) + 0.5) / n * _TWO_PI
    sector, tp = split_angle(th)
    da, db = m * np.sin(SECTOR_RAD - tp), m * np.sin(tp)
    tot = da + db
    out = tot > 1.0
    q = np.minimum(da, db) / np.where(out, tot, 1.0)        # the nearer vertex's partner's fraction on the side
    if six_step:
        q = 0.5 - np.minimum(0.5, overmod_gain(m) * (0.5 - q))
    first = da <= db
    da = np.where(out, np.where(first, q, 1.0 - q), da)
    db = np.where(out, np.where(first, 1.0 - q, q), db)
    v = (da * np.exp(1j * sector * SECTOR_RAD) + db * np.exp(1j * (sector + 1) * SECTOR_RAD)) * (2.0 / _SQRT3)
    return float(abs(np.mean(v * np.exp(-1j * th))))


def overmod_m_for(fundamental: float, six_step: bool = True) -> float:
    """The m whose line fundamental (overmod_fundamental) is ``fundamental`` Udc (bisection on the monotonic
    map): the linear command of the overmodulation range. Raises beyond what the law reaches."""
    hi = 2.0 - 2.0 ** -15
    top = overmod_fundamental(hi, six_step)
    if not 0.0 <= fundamental <= top:
        raise ValueError(f"line fundamental {fundamental} Udc outside 0 .. {top:.5f} Udc "
                         f"({'six-step law' if six_step else 'angle-keeping clamp'})")
    if fundamental <= 1.0:
        return fundamental
    lo = 1.0
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if overmod_fundamental(mid, six_step) < fundamental:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)
