# SPDX-License-Identifier: Apache-2.0
"""Bit-exact fixed-point arithmetic of the svpwm core: the specification the RTL implements.

Every function here computes exactly what the RTL computes, integer by integer; tests compare the
RTL against these with ``==``.  Formats (see README "Fixed-point formats"):

* in-sector angle: unsigned PHASE_WIDTH-bit fraction of 60 deg (theta' = angle / 2**PHASE_WIDTH * 60 deg),
  sector 0..5 (= the seeds' sectors 1..6); the full angle is sector*60 deg + theta'.
* frequency word: signed FREQ_WIDTH bits, added to the angle every clock; 1 LSB = f_clk / (6 * 2**PHASE_WIDTH) Hz.
* modulation index m: UQ1.15 (M_ONE = 0x8000 = 1.0 = inscribed circle); larger inputs are clamped to M_ONE.
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
MIN_PERIOD = 32           # smallest accepted half period (clocks); smaller inputs are clamped
ROM_BITS = 8              # sine ROM: 2**ROM_BITS intervals over 0..60 deg (257 points)
INTERP_BITS = 8           # linear-interpolation fraction bits
ANGLE_BITS = ROM_BITS + INTERP_BITS   # angle bits the duty calculator uses (top of the accumulator)
SIN_BITS = 16             # UQ0.16 sine samples
M_FRAC = 15               # m is UQ1.15
M_ONE = 1 << M_FRAC
K_FRAC = 8                # fraction bits kept of P*d before the compare-value sum
DUTY_LATENCY = 12         # clocks from the duty calculator's start strobe to its done strobe
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


def clamp_m(m: int) -> tuple[int, bool]:
    """Clamp a UQ1.15 modulation index to [0, 1.0]; returns (value, clamped)."""
    if m < 0:
        raise ValueError("m is unsigned")
    return (M_ONE, True) if m > M_ONE else (m, False)


FREQ_MAX = (1 << (FREQ_WIDTH - 1)) - 1   # largest |frequency word| accepted (parameter FreqMax)


def clamp_period(p: int, dt: int = 0, mp: int = 0) -> tuple[int, bool]:
    """Clamp a half period to [max(MIN_PERIOD, 2*(dt + mp)), 2**CNT_WIDTH - 1]; returns (value, clamped).

    A period too short for the dead time plus the minimum pulse is lengthened, never the dead time
    shortened: the dead time is a safety setting."""
    top = (1 << CNT_WIDTH) - 1
    low = max(MIN_PERIOD, 2 * (dt + mp))
    if p < low:
        return low, True
    if p > top:
        return top, True
    return p, False


def clamp_freq(f: int) -> tuple[int, bool]:
    """Clamp a frequency word to [-FREQ_MAX, FREQ_MAX]; returns (value, clamped)."""
    if f > FREQ_MAX:
        return FREQ_MAX, True
    if f < -FREQ_MAX:
        return -FREQ_MAX, True
    return f, False


def snap_min_pulse(c: int, period: int, thr: int) -> int:
    """Minimum-pulse rule on one compare value (rtl/svpwm_minpulse.sv), thr = dead time + minimum pulse.

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
    """d_a = m sin(60 deg - theta'), d_b = m sin(theta') (AVR495 sec. 4.2, Minas eq. (4)) in UQ0.16."""
    sa, sb = sines(a16)
    rnd = 1 << (M_FRAC - 1)
    return (m * sa + rnd) >> M_FRAC, (m * sb + rnd) >> M_FRAC


def compare_values(sector: int, a16: int, m: int, period: int) -> tuple[int, int, int]:
    """Compare values (C_a, C_b, C_c) for one carrier period, AVR495 Table 4-3.

    C = P/2 * (1 + k) with k = +-d_a +- d_b per sector; a phase is high while the carrier is >= C
    (counting up) / > C (counting down), so its high time is 2*(P - C) clocks.  Rounded to nearest.
    """
    da, db = duties(a16, m)
    a8 = (da * period) >> (SIN_BITS - K_FRAC)
    b8 = (db * period) >> (SIN_BITS - K_FRAC)
    s, d = a8 + b8, a8 - b8
    ks = (s, -s, d, -d)
    base = (period + 1) << K_FRAC
    return tuple((base + ks[sel]) >> (K_FRAC + 1) for sel in SECTOR_SEL[sector])


def compare_values_np(sector, a16, m, period):
    """Vectorised compare_values over numpy arrays (same integers); returns an (..., 3) int64 array."""
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
    a8 = (da * period) >> (SIN_BITS - K_FRAC)
    b8 = (db * period) >> (SIN_BITS - K_FRAC)
    s, d = a8 + b8, a8 - b8
    ks = np.stack([s, -s, d, -d], axis=-1)
    sel = np.asarray(SECTOR_SEL, dtype=np.int64)[sector]            # (..., 3)
    k = np.take_along_axis(ks, sel, axis=-1)
    base = (period + 1) << K_FRAC
    return (base[..., None] + k) >> (K_FRAC + 1)


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
