# SPDX-License-Identifier: Apache-2.0
"""Bit-exact fixed-point arithmetic of the svpwm core: the specification the RTL implements.

Every function here computes exactly what the RTL computes, integer by integer; tests compare the
RTL against these with ``==``.  Formats (see docs/reference.md "Fixed-point formats"):

* in-sector angle: unsigned PHASE_WIDTH-bit fraction of 60 deg (theta' = angle / 2**PHASE_WIDTH * 60 deg),
  sector 0..5 (= the seeds' sectors 1..6); the full angle is sector*60 deg + theta'.
* frequency word: signed FREQ_WIDTH bits, added to the angle every clock; 1 LSB = f_clk / (6 * 2**PHASE_WIDTH) Hz.
* modulation index m: UQ1.15 (M_ONE = 0x8000 = 1.0 = inscribed circle), 0 .. 0xFFFF (1.99997); a vector
  beyond the hexagon (m > 1 / cos(theta' - 30 deg), i.e. 2/sqrt(3) at the vertices) is clamped to its boundary.
* voltage components v_alpha, v_beta, v_d, v_q: signed Q2.14 (V_ONE = 0x4000 = 1.0, same scale as m).
* electrical angle theta (polar and dq modes): 16 bits over 360 deg.
* dwell times T1, T2 (fractions of the carrier period spent in the two active vectors): UQ0.16 units,
  D_ONE = 2**16 = the whole period (Minas eq. (4)/(5): T1 = m sin(60 deg - theta'), T2 = m sin(theta')).
* sine ROM: UQ0.16, round(sin(i * 60deg / 256) * 2**16) for i = 0..256 (AVR495 sec. 6 uses a 0..60 deg table too).
* period P: half carrier period in clocks (f_sw = f_clk / (2P)); compare values C in [0, P].
"""
from __future__ import annotations

import math

import numpy as np

# ---- parameters (defaults of rtl/svpwm_core.sv) -------------------------------------------------
PHASE_WIDTH = 34          # fraction bits of the in-sector angle accumulator
FREQ_WIDTH = 24           # signed frequency word
CNT_WIDTH = 16            # carrier / period / compare width
DT_WIDTH = 10             # dead-time counter width (clocks)
MIN_PERIOD_BASE = 48      # rtl/svpwm_pkg.sv MinPeriodBase: the floor of the MinPeriod defaults
ARM_CLOCKS = 4            # rtl/svpwm_pkg.sv ArmClocks: the core runs this many clocks after reset at the earliest
START_DELAY = 1           # the modulator starts this many clocks after en_i rises (svpwm_core's run register)
ROM_BITS = 8              # sine ROM: 2**ROM_BITS intervals over 0..60 deg (257 points)
INTERP_BITS = 8           # linear-interpolation fraction bits
ANGLE_BITS = ROM_BITS + INTERP_BITS   # angle bits the duty calculator uses (top of the accumulator)
SIN_BITS = 16             # UQ0.16 sine samples
M_FRAC = 15               # m is UQ1.15
M_ONE = 1 << M_FRAC
K_FRAC = 8                # fraction bits kept of P*d before the compare-value sum
V_FRAC = 14               # v_alpha, v_beta, v_d, v_q are signed Q2.14
V_ONE = 1 << V_FRAC
D_ONE = 1 << SIN_BITS     # dwell time of a whole period
T_CAP = D_ONE - 1         # dwell times enter the 16x16 multiplier: capped at 1 - 2^-16
SQRT3_2 = int(round(math.sqrt(3) / 2 * (1 << SIN_BITS)))   # sqrt(3)/2, UQ0.16 (56756)

# input modes (mode_i) -- docs/reference.md "Input modes"
MODE_FREQ, MODE_VF, MODE_POLAR, MODE_AB, MODE_DQ = range(5)
MODE_NAMES = ("freq", "vf", "polar", "alphabeta", "dq")
# zero-vector placement (dpwm_i): continuous SVPWM, or discontinuous (bus-clamped) PWM
DPWM_OFF, DPWM_MIN, DPWM_MAX, DPWM_60 = range(4)
# update points (upd_i): new compare values at the valley, at the peak, or at both (double update)
UPD_VALLEY, UPD_PEAK, UPD_BOTH = range(3)
F_CLK_DEFAULT = 48e6      # default core clock (Hz)

ROM_SIZE = 1 << ROM_BITS

# Table 4-3 of AVR495 (4*C/Ts - 1 per sector, sectors 1..6) as selection codes per phase a, b, c:
# 0: +(da+db)  1: -(da+db)  2: +(da-db)  3: -(da-db)
SECTOR_SEL = (
    (1, 2, 0),   # sector 1:  -da-db,  da-db,  da+db
    (3, 1, 0),   # sector 2:  -da+db, -da-db,  da+db
    (0, 1, 2),   # sector 3:   da+db, -da-db,  da-db
    (0, 3, 1),   # sector 4:   da+db, -da+db, -da-db
    (2, 0, 1),   # sector 5:   da-db,  da+db, -da-db
    (1, 0, 3),   # sector 6:  -da-db,  da+db, -da+db
)


def sine_table() -> list[int]:
    """The sine ROM: 257 UQ0.16 samples of sin over [0, 60 deg] (index 256 = 60 deg)."""
    return [int(round(math.sin(math.radians(60.0 * i / ROM_SIZE)) * (1 << SIN_BITS)))
            for i in range(ROM_SIZE + 1)]


_ROM = sine_table()


FREQ_MAX = (1 << (FREQ_WIDTH - 1)) - 1   # largest |frequency word| accepted (parameter FreqMax)


def clamp_period(p: int, dt: int = 0, mp: int = 0, min_period: int | None = None,
                 dtf: int | None = None) -> tuple[int, bool]:
    """Clamp a half period to [max(min_period, 2*(max(dt, dtf) + mp)), 2**CNT_WIDTH - 1]; returns (value,
    clamped); min_period defaults to the full core's MIN_PERIOD, dtf (the falling dead time) to dt.

    A period too short for the dead time plus the minimum pulse is lengthened, never the dead time
    shortened: the dead time is a safety setting."""
    top = (1 << CNT_WIDTH) - 1
    dtx = dt if dtf is None else max(dt, dtf)
    low = max(_latency("MIN_PERIOD") if min_period is None else min_period, 2 * (dtx + mp))
    if p < low:
        return low, True
    if p > top:
        return top, True
    return p, False


def clamp_freq(f: int, fmax: int = FREQ_MAX) -> tuple[int, bool]:
    """Clamp a frequency word to [-fmax, fmax] (fmax: the core's FreqMax); returns (value, clamped)."""
    if f > fmax:
        return fmax, True
    if f < -fmax:
        return -fmax, True
    return f, False


def snap_min_pulse(c: int, period: int, thr: int) -> int:
    """Minimum-pulse rule on one compare value (the last part of svpwm_calc's program), thr = dead time +
    minimum pulse; c may lie outside [0, P] (dead-time compensation): below 0 it gives 0, above P it gives P.

    A pole pulse shorter than thr would reach its gate shorter than the minimum pulse (the dead time
    eats dt of it), so such pulses are dropped or widened to thr, whichever is nearer:
    the low pulse around the valley is built from the C of the two periods it straddles, so each C is
    0 or >= thr; the high pulse around the peak is 2 (P - C) clocks, so P - C is 0 or >= ceil(thr/2).
    The map is monotonic, so the order of the three phases (the Table I sequence) is kept.
    Requires period >= 2 * thr (clamp_period guarantees it)."""
    hthr = (thr + 1) >> 1
    if c < thr:
        return 0 if 2 * c < thr else thr
    if period - c < hthr:
        return period if 2 * (period - c) < hthr else period - hthr
    return c


def snap_carry(c: int, period: int, thr: int) -> tuple[int, int]:
    """The minimum-pulse rule with its volt-second carry: (snap_min_pulse(c), e), e = what the rule dropped or
    widened, c - snapped, limited to +-hthr = +-ceil(thr / 2). The core adds e to the same phase's next
    command (c here includes the carry in): a first-order error feedback, so over a few periods the average
    pulse equals the command. For a command inside [0, P] the limit never acts (the rule moves a value to the
    nearer end: |e| <= hthr); it bounds what a command beyond a rail (dead-time compensation at a clamped
    phase) would pile up."""
    snapped = snap_min_pulse(c, period, thr)
    hthr = (thr + 1) >> 1
    return snapped, max(-hthr, min(hthr, c - snapped))


def sines(a16: int) -> tuple[int, int]:
    """sin(60 deg - theta') and sin(theta') in UQ0.16 by linear interpolation between ROM points.

    ``a16`` is the top ANGLE_BITS of the in-sector angle: index = a16 >> 8, fraction = a16 & 0xff.
    """
    idx, fr = a16 >> INTERP_BITS, a16 & ((1 << INTERP_BITS) - 1)
    half = 1 << (INTERP_BITS - 1)
    r0, r1 = _ROM[idx], _ROM[idx + 1]
    r2, r3 = _ROM[ROM_SIZE - idx], _ROM[ROM_SIZE - 1 - idx]
    sb = r0 + (((r1 - r0) * fr + half) >> INTERP_BITS)
    sa = r2 - (((r2 - r3) * fr + half) >> INTERP_BITS)
    return sa, sb


def duties(a16: int, m: int) -> tuple[int, int]:
    """d_a = m sin(60 deg - theta'), d_b = m sin(theta') (AVR495 sec. 4.2, Minas eq. (4)) in UQ0.16.

    These are the dwell times T1, T2 of the polar path; for m > 1 they may leave the hexagon."""
    sa, sb = sines(a16)
    rnd = 1 << (M_FRAC - 1)
    return (m * sa + rnd) >> M_FRAC, (m * sb + rnd) >> M_FRAC


M_VERTEX = 0x93CD         # round(2 / sqrt(3) * M_ONE): m of the hexagon's vertices
OM_G_ONE = 256            # overmodulation gain g, UQ8.8: 1.0 = the angle-keeping clamp


def om_gain(m: int, om: bool, mode: int = MODE_FREQ) -> int:
    """Gain g (UQ8.8) of the six-step overmodulation law (om = 1, the angle-driven modes FREQ, VF, POLAR):
    g = 1 + (m - M_VERTEX) / 128 above the vertex magnitude, 1 below it, 1 with om = 0 or in the AB / DQ modes.
    g = 256 + 2 max(0, m - M_VERTEX) <= 55652 for m <= 0xFFFF."""
    if not om or mode not in (MODE_FREQ, MODE_VF, MODE_POLAR):
        return OM_G_ONE
    return OM_G_ONE + 2 * max(0, m - M_VERTEX)


def hex_clamp(t1: int, t2: int, g: int = OM_G_ONE) -> tuple[int, int, bool]:
    """Overmodulation: a vector outside the hexagon (T1 + T2 > 1) is clamped to its boundary keeping its angle.

    The angle inside the sector is set by the ratio T1 : T2, so the smaller of the two is rescaled,
    q = floor(min * 2^16 / (T1 + T2)), and the larger becomes 1 - q: T0 = 1 - T1 - T2 is never negative
    (Minas eq. (5), T0 = Ts - T1 - T2). Returns (T1, T2, saturated); both are capped at T_CAP (16 bits).

    Six-step law (g > 1, om_gain): on the hexagon side, d = 1/2 - q is the distance from the side's middle;
    it is stretched, d' = min(1/2, g d) (q' = 2^15 - round(g d / 2^8), at least 0): the vector moves towards
    the nearer vertex and stays there (q' = 0) while g d >= 1/2, the hold angle growing with g until the
    whole sector sits at its vertices (six-step, g -> infinity; 1.10266 U_dc of 1.10266 at m = 0xFFFF).
    Continuous in the angle (d = 0 stays 0), monotonic in g; g = 1 is the angle-keeping clamp exactly."""
    s = t1 + t2
    sat = s > D_ONE
    if sat:
        q = (min(t1, t2) << SIN_BITS) // s
        if g != OM_G_ONE:
            q = max(0, (1 << (SIN_BITS - 1)) - ((g * ((1 << (SIN_BITS - 1)) - q) + 128) >> 8))
        t1, t2 = (q, D_ONE - q) if t1 <= t2 else (D_ONE - q, q)
    return min(t1, T_CAP), min(t2, T_CAP), sat


def dwell_compare(sector: int, t1: int, t2: int, period: int) -> tuple[int, int, int]:
    """Compare values (C_a, C_b, C_c) of one carrier period from the dwell times, AVR495 Table 4-3.

    C = P/2 * (1 + k) with k = +-d_a +- d_b per sector (d_a = T1, d_b = T2); a phase is high while the
    carrier is >= C (counting up) / > C (counting down), so its high time is 2*(P - C) clocks.  Rounded
    to nearest; requires T1 + T2 <= 1 (hex_clamp)."""
    a8 = (t1 * period) >> (SIN_BITS - K_FRAC)
    b8 = (t2 * period) >> (SIN_BITS - K_FRAC)
    s, d = a8 + b8, a8 - b8
    ks = (s, -s, d, -d)
    base = (period + 1) << K_FRAC
    return tuple((base + ks[sel]) >> (K_FRAC + 1) for sel in SECTOR_SEL[sector])


def dpwm_shift(c: tuple[int, int, int], period: int, dpwm: int) -> tuple[int, int, int]:
    """Zero-vector placement. Continuous SVPWM (DPWM_OFF) splits the zero time equally between V0 (around the
    valley) and V7 (around the peak), Minas eq. (6)/(7). The discontinuous modes move all of it into one:
    DPWM_MIN  no V7: every C moves up by P - max(C), the latest phase stays low (clamped to the - rail);
    DPWM_MAX  no V0: every C moves down by min(C), the earliest phase stays high (+ rail);
    DPWM_60   per 60 deg the phase with the largest |reference| is clamped to its rail (DPWM1). The
              three references sum to zero, so the highest one is the largest exactly when the middle
              one is negative, i.e. its C above P/2: DPWM_MAX if 2 mid(C) > P, else DPWM_MIN.
              (min(C) + max(C) cannot decide it: continuous SVPWM centres them, their sum is P or P + 1.)
    Only the common-mode part changes, so the line voltages and the Table I state order are kept."""
    if dpwm == DPWM_OFF:
        return c
    lo, hi = min(c), max(c)
    mid = sum(c) - lo - hi
    if dpwm == DPWM_MAX or (dpwm == DPWM_60 and 2 * mid > period):
        sh = -lo
    else:
        sh = period - hi
    return tuple(x + sh for x in c)


def dtc_amounts(dt_r: int, dt_f: int, en: bool) -> tuple[int, int]:
    """Dead-time compensation amounts (hdr, hdf) in compare-value clocks: half of each dead time, rounded
    up, hdr = (dt_r + 1) >> 1, hdf = (dt_f + 1) >> 1; (0, 0) when the compensation is off."""
    if not en:
        return 0, 0
    return (dt_r + 1) >> 1, (dt_f + 1) >> 1


def dtc_shift(c: tuple[int, int, int], isign: int, hdr: int, hdf: int,
              carry: tuple[int, int, int] = (0, 0, 0)) -> tuple[int, int, int]:
    """Pulse-based dead-time compensation (applied after the zero-vector placement, before the minimum-pulse
    rule). ``isign`` bit k (phase a = bit 0) is the sign of phase k's current, 1 = negative (flowing into the
    leg). During a dead time both switches of a leg are off and the current alone sets the pole through the
    free-wheeling diodes: a positive current holds the pole low until the delayed high side turns on, so the
    high pulse loses dt_r (the rising-edge dead time); a negative current holds it high until the delayed low
    side turns on, so it gains dt_f. The high pulse is 2 (P - C) clocks, so C moves by half the dead time:
    C - hdr for a positive current, C + hdf for a negative one. The result may leave [0, P]: the
    minimum-pulse rule (snap_min_pulse) maps it back. With the compensation the pole *voltages* keep their
    order (each moves by about dt / 2 the same way); the switch commands of two phases within a dead time of
    each other and with opposite currents may cross. ``carry``: the volt-second carry of each phase (snap_carry
    of its previous update), added here too."""
    return tuple(x + (hdf if (isign >> ph) & 1 else -hdr) + carry[ph] for ph, x in enumerate(c))


def compare_values(sector: int, a16: int, m: int, period: int, dpwm: int = DPWM_OFF) -> tuple[int, int, int]:
    """Compare values (C_a, C_b, C_c) of the angle-driven path: sector + in-sector angle + m (any m <= 0xFFFF)."""
    t1, t2, _ = hex_clamp(*duties(a16, m))
    return dpwm_shift(dwell_compare(sector, t1, t2, period), period, dpwm)


def compare_values_np(sector, a16, m, period):
    """Vectorised compare_values (DPWM_OFF) over numpy arrays (same integers); returns an (..., 3) int64 array."""
    sector, a16, m, period = np.broadcast_arrays(*(np.asarray(x, dtype=np.int64)
                                                   for x in (sector, a16, m, period)))
    rom = np.asarray(_ROM, dtype=np.int64)
    idx, fr = a16 >> INTERP_BITS, a16 & ((1 << INTERP_BITS) - 1)
    half = 1 << (INTERP_BITS - 1)
    r0, r1, r2, r3 = rom[idx], rom[idx + 1], rom[ROM_SIZE - idx], rom[ROM_SIZE - 1 - idx]
    sb = r0 + (((r1 - r0) * fr + half) >> INTERP_BITS)
    sa = r2 - (((r2 - r3) * fr + half) >> INTERP_BITS)
    rnd = 1 << (M_FRAC - 1)
    da, db = (m * sa + rnd) >> M_FRAC, (m * sb + rnd) >> M_FRAC
    tot = da + db                                                     # hex_clamp, vectorised
    sat = tot > D_ONE
    q = (np.minimum(da, db) << SIN_BITS) // np.maximum(tot, 1)
    first = da <= db
    da, db = (np.where(sat, np.where(first, q, D_ONE - q), da),
              np.where(sat, np.where(first, D_ONE - q, q), db))
    da, db = np.minimum(da, T_CAP), np.minimum(db, T_CAP)
    a8 = (da * period) >> (SIN_BITS - K_FRAC)
    b8 = (db * period) >> (SIN_BITS - K_FRAC)
    s, d = a8 + b8, a8 - b8
    ks = np.stack([s, -s, d, -d], axis=-1)
    sel = np.asarray(SECTOR_SEL, dtype=np.int64)[sector]            # (..., 3)
    k = np.take_along_axis(ks, sel, axis=-1)
    base = (period + 1) << K_FRAC
    return (base[..., None] + k) >> (K_FRAC + 1)


# ---- input modes: V/f law, polar, alpha-beta, dq + theta -----------------------------------------------

def vf_m(freq: int, boost: int, slope: int, m_max: int) -> int:
    """V/f law (AVR495 sec. 5: voltage proportional to frequency, with a boost at low frequency):
    m = min(m_max, boost + |f| * slope). |f| enters as its top 16 bits, fa = |freq| >> (FREQ_WIDTH - 17)
    (one unit = 2^(FREQ_WIDTH-17) frequency LSBs, 59.6 mHz at 48 MHz); slope is UQ8.8 m-LSBs per unit:
    m = min(m_max, boost + ((fa * slope + 128) >> 8)). boost, m_max, m: UQ1.15. The law depends on |f| only,
    so a reversal through zero passes through m = boost with the angle continuous: no step."""
    fa = abs(freq) >> (FREQ_WIDTH - 17)
    return min(m_max, boost + ((fa * slope + 128) >> 8))


def theta_split(theta: int) -> tuple[int, int]:
    """A 16-bit electrical angle (2^16 = 360 deg) as sector 0..5 and the 16-bit in-sector angle a16
    (2^16 = 60 deg): 6 * theta = sector * 2^16 + a16, exact (no rounding)."""
    t6 = 6 * (theta & 0xFFFF)
    return t6 >> 16, t6 & 0xFFFF


def _mul_v(v: int, k: int) -> int:
    """Signed Q2.14 voltage times an unsigned UQ0.16 constant or sine, in dwell units (2^16 = 1): sign and
    magnitude, rounded to nearest (ties away from zero), so -v gives exactly the negative result."""
    p = (abs(v) * k + (1 << (V_FRAC - 1))) >> V_FRAC
    return p if v >= 0 else -p


def xyz_sector(x: int, y: int, z: int) -> tuple[int, int, int]:
    """Sector and dwell times from the three projections X = v_beta, Y = (sqrt3 v_alpha + v_beta)/2,
    Z = (v_beta - sqrt3 v_alpha)/2 (X = Y + Z), without trigonometry (Minas eq. (5) in all six sectors).

    With q_k = |v| sin(phi - k 60 deg) = (X, Z, -Y, -X, -Z, Y)[k], sector s is the one with q_s >= 0 and
    q_{s+1} < 0 (unique for v != 0 because q_k = q_{k-1} + q_{k+1}); then T2 = q_s and T1 = -q_{s+1},
    both >= 0. The zero vector gives sector 0 and T1 = T2 = 0."""
    q = (x, z, -y, -x, -z, y)
    for s in range(6):
        if q[s] >= 0 and q[(s + 1) % 6] < 0:
            return s, -q[(s + 1) % 6], q[s]
    return 0, 0, 0


def ab_dwell(v_alpha: int, v_beta: int) -> tuple[int, int, int]:
    """alpha-beta (stator frame) reference, Q2.14, to (sector, T1, T2): one product sqrt(3)/2 * v_alpha."""
    a = _mul_v(v_alpha, SQRT3_2)          # sqrt(3)/2 v_alpha, dwell units
    x = v_beta << (SIN_BITS - V_FRAC)     # v_beta in dwell units
    h = v_beta << (SIN_BITS - V_FRAC - 1)  # v_beta / 2
    return xyz_sector(x, a + h, h - a)


def dq_trig(a16: int) -> tuple[int, int, int, int]:
    """sin(60 - theta'), sin(theta'), cos(theta'), cos(60 - theta') from the 0..60 deg table alone.

    With u = |theta' - 30 deg| and g = sin(60 - u), h = sin(u) (both from the table): sin(60 + u) = g + h
    (sin(60+u) - sin(60-u) = 2 cos 60 sin u), so for theta' < 30: cos theta' = sin(60 + u) = g + h,
    cos(60 - theta') = sin(60 - u) = g; for theta' >= 30 the two swap. g + h is capped at 1 - 2^-16."""
    sa, sb = sines(a16)
    u = abs(a16 - (1 << (ANGLE_BITS - 1)))
    g, h = sines(u)
    gh = min(g + h, T_CAP)
    ct, c60 = (gh, g) if a16 < (1 << (ANGLE_BITS - 1)) else (g, gh)
    return sa, sb, ct, c60


def dq_dwell(theta: int, v_d: int, v_q: int) -> tuple[int, int, int]:
    """dq reference + electrical angle to (sector, T1, T2): inverse Park evaluated in the frame of theta's own
    sector. theta = s 60 deg + theta'; w = (v_d + j v_q) e^(j theta') has X = v_d sin theta' + v_q cos theta'
    and Z = -v_d sin(60 - theta') + v_q cos(60 - theta'), Y = X - Z. The vector v = w e^(j s 60 deg) has the same
    dwell times as w, its sector is (sector(w) + s) mod 6 (q_k(v) = q_{k-s}(w))."""
    s, a16 = theta_split(theta)
    sa, sb, ct, c60 = dq_trig(a16)
    x = _mul_v(v_d, sb) + _mul_v(v_q, ct)
    z = _mul_v(v_q, c60) - _mul_v(v_d, sa)
    sw, t1, t2 = xyz_sector(x, x - z, z)
    return (sw + s) % 6, t1, t2


def modulate(mode: int, acc_sector: int, acc_a16: int, period: int, *, freq: int = 0, m: int = 0,
             theta: int = 0, v1: int = 0, v2: int = 0, vf_boost: int = 0, vf_slope: int = 0,
             vf_mmax: int = 0, dpwm: int = DPWM_OFF, isign: int = 0, hdr: int = 0,
             hdf: int = 0, om: int = 0,
             carry: tuple[int, int, int] = (0, 0, 0)) -> tuple[int, tuple[int, int, int], bool, bool]:
    """The whole compute path for one update: reference (any mode) -> sector, dwell times -> hexagon clamp
    -> compare values (Table 4-3) -> zero-vector placement -> dead-time compensation (dtc_shift; hdr = hdf =
    0: none) and the volt-second carry (``carry``, per phase). om = 1: the six-step overmodulation law in the
    clamp (om_gain, hex_clamp). Returns (sector, (C_a, C_b, C_c), sat, cfg_err).

    acc_sector / acc_a16: the phase accumulator (freq and vf modes). An unknown mode gives the zero vector
    (T1 = T2 = 0, all phases 50 %) and cfg_err. The minimum-pulse rule (snap_min_pulse) comes after this."""
    err = False
    g = OM_G_ONE
    if mode in (MODE_FREQ, MODE_VF, MODE_POLAR):
        if mode == MODE_VF:
            m = vf_m(freq, vf_boost, vf_slope, vf_mmax)
        g = om_gain(m, bool(om), mode)
        sector, a16 = (acc_sector, acc_a16) if mode != MODE_POLAR else theta_split(theta)
        t1, t2 = duties(a16, m)
    elif mode == MODE_AB:
        sector, t1, t2 = ab_dwell(v1, v2)
    elif mode == MODE_DQ:
        sector, t1, t2 = dq_dwell(theta, v1, v2)
    else:
        sector, t1, t2, err = 0, 0, 0, True
    t1, t2, sat = hex_clamp(t1, t2, g)
    c = dpwm_shift(dwell_compare(sector, t1, t2, period), period, dpwm)
    return sector, dtc_shift(c, isign, hdr, hdf, carry), sat, err


def input_slots(mode: int, *, m: int = 0, theta: int = 0, v1: int = 0, v2: int = 0, vf_boost: int = 0,
                vf_slope: int = 0, vf_mmax: int = 0) -> dict:
    """The reference as svpwm_core's calculator sees it: the core keeps three 16-bit slots of the sampled
    inputs, chosen by the mode (s0 = vf_boost in VF, v1 in AB / DQ, else m; s1 = vf_slope in VF, else theta;
    s2 = vf_mmax in VF, else v2), and every calculator input of a slot reads it. Returns the keyword inputs
    of modulate() so; modulate() gives the same result for them as for the inputs themselves, because no
    mode reads two inputs of one slot (model/tests/test_input_slots.py)."""
    s0 = vf_boost if mode == MODE_VF else v1 if mode in (MODE_AB, MODE_DQ) else m
    s1 = vf_slope if mode == MODE_VF else theta
    s2 = vf_mmax if mode == MODE_VF else v2
    s0, s1, s2 = s0 & 0xFFFF, s1 & 0xFFFF, s2 & 0xFFFF
    signed = lambda x: x - 0x10000 if x & 0x8000 else x      # noqa: E731  (v1 / v2 ports are Q2.14)
    return dict(m=s0, vf_boost=s0, v1=signed(s0), theta=s1, vf_slope=s1, v2=signed(s2), vf_mmax=s2)


def angle_step(sector: int, angle: int, step: int, clocks: int) -> tuple[int, int]:
    """Advance the phase accumulator by ``clocks`` clocks of frequency word ``step`` (exact, modulo 360 deg)."""
    full = 6 << PHASE_WIDTH
    total = (sector << PHASE_WIDTH) + angle + step * clocks
    total %= full
    return total >> PHASE_WIDTH, total & ((1 << PHASE_WIDTH) - 1)


def freq_lsb_hz(f_clk: float = F_CLK_DEFAULT) -> float:
    """Output-frequency resolution: one LSB of the frequency word in Hz."""
    return f_clk / (6 * (1 << PHASE_WIDTH))


def freq_word(f_out_hz: float, f_clk: float = F_CLK_DEFAULT) -> int:
    """Frequency word for an output frequency (rounded; negative = reverse rotation). Raises if out of range."""
    w = int(round(f_out_hz / freq_lsb_hz(f_clk)))
    lim = 1 << (FREQ_WIDTH - 1)
    if not -lim <= w < lim:
        raise ValueError(f"{f_out_hz} Hz needs frequency word {w}, outside the signed {FREQ_WIDTH}-bit range "
                         f"(|f| < {lim * freq_lsb_hz(f_clk):.1f} Hz at f_clk = {f_clk / 1e6:g} MHz)")
    return w


def m_word(m: float) -> int:
    """UQ1.15 modulation-index word for m in [0, 1] (m = 1: inscribed circle). Raises if out of range."""
    if not 0.0 <= m <= 1.0:
        raise ValueError(f"m = {m} outside [0, 1] (m = 1 is the inscribed circle, line fundamental peak = Udc)")
    return int(round(m * M_ONE))


# ---- latencies: from the calculator's program (calc_prog.py; rtl/svpwm_pkg.sv is generated from the same) ---
# full core: the program on the registered multiplier; compact core (svpwm_core Compact = 1, the iCEstick's
# HX1K: FREQ mode, SVPWM, valley updates only): the FREQ program on the serial unit. Computed on first use
# (calc_prog builds on the arithmetic above): fixed.SAMPLE_LEAD etc. read like constants.
#   CALC_LATENCY / LITE_CALC_LATENCY   clocks svpwm_calc start -> done (full / compact core)
#   SAMPLE_LEAD / LITE_SAMPLE_LEAD     clocks from an input sample to its update point (+ 1 load clock)
#   MIN_PERIOD / LITE_MIN_PERIOD       smallest accepted half period, svpwm_core's MinPeriod default
#                                      (lead + 4, at least MIN_PERIOD_BASE); smaller inputs are clamped
# Until the engine's compact build fits the HX1K (it does not yet: 1,685 / 1,280 LC for the iCEstick system),
# the compact core keeps its own serial datapath, rtl/svpwm_duty_lite.sv, behind svpwm_calc's ports:
LITE_DUTY_LATENCY = 225   # clocks start -> done of rtl/svpwm_duty_lite.sv (svpwm_pkg LiteDutyLatency)
_LATENCIES: dict[str, int] = {}


def _latency(name: str) -> int:
    if not _LATENCIES:
        from . import config
        for pre, feats in (("", config.FULL), ("LITE_", config.TINY)):
            _LATENCIES.update({f"{pre}{k}": v for k, v in latencies(feats).items()})
    return _LATENCIES[name]


def latencies(features: int) -> dict[str, int]:
    """CALC_LATENCY, SAMPLE_LEAD and MIN_PERIOD of a build (config.py feature mask; svpwm_pkg's calc_latency,
    sample_lead and min_period of the same)."""
    from . import calc_prog, config
    lat = LITE_DUTY_LATENCY if features == config.TINY else calc_prog.calc_latency(features)
    return {"CALC_LATENCY": lat, "SAMPLE_LEAD": lat + 1, "MIN_PERIOD": max(lat + 1 + 4, MIN_PERIOD_BASE)}


def __getattr__(name: str) -> int:
    if name in ("CALC_LATENCY", "LITE_CALC_LATENCY", "SAMPLE_LEAD", "LITE_SAMPLE_LEAD", "MIN_PERIOD",
                "LITE_MIN_PERIOD"):
        return _latency(name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
