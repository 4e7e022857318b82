# SPDX-License-Identifier: Apache-2.0
"""Checks and measurements on edge streams (RTL or model): Table I sequences, leg safety, fundamentals.

Edge streams are lists of (cycle, word) where the word holds from that cycle on. Pole words are
{c, b, a} (bit 0 = phase a); gate words are {lo[2:0], hi[2:0]}.
"""
from __future__ import annotations

import bisect
import cmath
import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from . import fixed
from .fixed import PHASE_WIDTH
from .ideal import ideal_compare

# Minas Table I, first half of each row (the second half mirrors it), bits (a, b, c) -> word {c,b,a}
_TABLE_I_ROWS = (
    ("000", "100", "110", "111"),
    ("000", "010", "110", "111"),
    ("000", "010", "011", "111"),
    ("000", "001", "011", "111"),
    ("000", "001", "101", "111"),
    ("000", "100", "101", "111"),
)


def _word(bits: str) -> int:
    a, b, c = (int(x) for x in bits)
    return a | (b << 1) | (c << 2)


TABLE_I_WORDS = tuple(tuple(_word(s) for s in row[:-1] + row[::-1]) for row in _TABLE_I_ROWS)


def word_at(events: Sequence[tuple[int, int]], cycle: int, initial: int = 0) -> int:
    """Value of an edge stream at a cycle."""
    i = bisect.bisect_right(events, (cycle, 1 << 30)) - 1
    return events[i][1] if i >= 0 else initial


def window(events: Sequence[tuple[int, int]], start: int, stop: int, initial: int = 0) -> list[int]:
    """The distinct successive values of a stream over cycles [start, stop)."""
    vals = [word_at(events, start, initial)]
    lo = bisect.bisect_right(events, (start, 1 << 30))
    hi = bisect.bisect_left(events, (stop, -1))
    for _, w in events[lo:hi]:
        if w != vals[-1]:
            vals.append(w)
    return vals


def is_subsequence(seq: Sequence[int], row: Sequence[int]) -> bool:
    it = iter(row)
    return all(any(x == y for y in it) for x in seq)


@dataclass
class SequenceReport:
    periods: int = 0
    with_skips: int = 0                 # periods where a dwell time rounded to 0 (a state skipped)
    failures: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return self.periods > 0 and not self.failures


def check_table_i(pole_events, valleys: Sequence[int], sectors: Sequence[int | None]) -> SequenceReport:
    """Every modulated period's pole-state sequence is Minas Table I's row for its sector.

    Period n covers cycles [t_n + 1, t_{n+1} + 1) (the poles are registered). States may be skipped
    where a dwell time is zero, never reordered; the sequence is symmetric about the period middle.
    """
    rep = SequenceReport()
    for n in range(len(valleys) - 1):
        if sectors[n] is None:
            continue
        seq = window(pole_events, valleys[n] + 1, valleys[n + 1] + 1)
        row = TABLE_I_WORDS[sectors[n]]
        rep.periods += 1
        if not (is_subsequence(seq, row) and seq == seq[::-1]):
            fmt = ["{:03b}".format(int(f"{w:03b}"[::-1], 2)) for w in seq]
            rep.failures.append(f"period {n} (sector {sectors[n] + 1}): states {fmt} not in Table I row")
        elif len(seq) < len(row):
            rep.with_skips += 1
    return rep


@dataclass
class LegReport:
    shoot_through: list[str] = field(default_factory=list)
    dead_time: list[str] = field(default_factory=list)
    short_pulse: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not (self.shoot_through or self.dead_time or self.short_pulse)


def check_legs(gate_events, dt_at, forced_off: Sequence[int] = ()) -> LegReport:
    """Gate safety from the edges alone: never both gates of a leg on; a gate turns on only after the
    other has been off for the dead time in force (dt_at(cycle) for the deciding clock, cycle - 1: one
    dead time, or a pair (dt, dtf): the high side waits dt, the low side dtf); every on-pulse lasts at
    least max(dt, dtf) unless ended by a forced turn-off (``forced_off``: cycles at which gates were
    forced off, e.g. a disable)."""
    def edge_dts(c: int) -> tuple[int, int]:
        d = dt_at(c)
        return (d, d) if isinstance(d, int) else tuple(d)

    rep = LegReport()
    forced = set(forced_off)
    for leg in range(3):
        last_off = {0: -(1 << 40), 1: -(1 << 40)}     # cycle each gate last turned off
        on_since = {0: None, 1: None}
        prev = (0, 0)
        for c, w in gate_events:
            cur = ((w >> leg) & 1, (w >> (leg + 3)) & 1)
            if cur == prev:
                continue
            if cur == (1, 1):
                rep.shoot_through.append(f"leg {'abc'[leg]}: both gates on at cycle {c}")
            for g in (0, 1):
                if cur[g] and not prev[g]:                      # turn-on of gate g
                    other = 1 - g
                    dt = edge_dts(c - 1)[g]
                    if prev[other] and dt != 0:
                        rep.dead_time.append(f"leg {'abc'[leg]}: direct swap at cycle {c} with dt={dt}")
                    elif c - last_off[other] < dt:
                        rep.dead_time.append(f"leg {'abc'[leg]}: gap {c - last_off[other]} < dt {dt} at {c}")
                    on_since[g] = c
                if prev[g] and not cur[g]:                      # turn-off of gate g
                    last_off[g] = c
                    width = c - on_since[g] if on_since[g] is not None else None
                    if width is not None and width < max(edge_dts(c - 1)) and c not in forced:
                        rep.short_pulse.append(f"leg {'abc'[leg]}: {'hl'[g]} pulse {width} < dt at {c}")
            prev = cur
    return rep


def phase_switching(events, phase: int, bit_offset: int = 0):
    """(cycle, 0/1) changes of one phase's switching function from a word stream."""
    out, prev = [], None
    for c, w in events:
        v = (w >> (phase + bit_offset)) & 1
        if v != prev:
            out.append((c, v))
            prev = v
    return out


def fourier(events_a, events_b, t0: float, t1: float, freq: float) -> complex:
    """Complex amplitude at ``freq`` (cycles^-1) of s_a - s_b over [t0, t1), computed exactly from the
    edges (piecewise-constant integral), normalised so a cosine of amplitude A gives |result| = A."""
    w = 2 * math.pi * freq
    total = 0j
    for sign, ev in ((1, events_a), (-1, events_b)):
        # value v on [c_i, c_{i+1}): integral v * (e^{-jwc_i} - e^{-jwc_{i+1}}) / (jw)
        pts = [(t0, word_at(ev, math.floor(t0)))]
        pts += [(c, v) for c, v in ev if t0 < c < t1]
        pts.append((t1, None))
        for (ca, va), (cb, _) in zip(pts, pts[1:]):
            if va:
                total += sign * (cmath.exp(-1j * w * ca) - cmath.exp(-1j * w * cb)) / (1j * w)
    return 2 * total / (t1 - t0)


def line_fundamental(pole_events, freq_word: int, t0: int, revolutions: int) -> float:
    """Amplitude of the line-voltage (a - b) fundamental, in units of Udc, over whole revolutions."""
    f = abs(freq_word) / (6 * (1 << PHASE_WIDTH))        # cycles^-1
    t1 = t0 + revolutions / f
    a = phase_switching(pole_events, 0)
    b = phase_switching(pole_events, 1)
    return abs(fourier(a, b, t0, t1, f))


def ideal_compare_law(theta, m, period, six_step: bool = False) -> np.ndarray:
    """Compare values (..., 3) of the ideal SVPWM with the core's overmodulation law, in floating point:
    ideal.ideal_compare (the angle-keeping clamp onto the hexagon) and, with ``six_step``, the boundary
    point's distance from the side's middle stretched by ideal.overmod_gain(m) (fixed.hex_clamp's law;
    the geometry of ideal.overmod_fundamental). Inside the hexagon both are ideal_compare."""
    from .ideal import overmod_gain, split_angle
    from .tables import AVR495_TABLE_4_3
    theta, m = np.broadcast_arrays(np.asarray(theta, dtype=np.float64), np.asarray(m, dtype=np.float64))
    sector, tp = split_angle(theta)
    da, db = m * np.sin(math.pi / 3 - tp), m * np.sin(tp)
    tot = da + db
    out = tot > 1.0
    q = np.minimum(da, db) / np.where(out, tot, 1.0)
    if six_step:
        g = np.vectorize(overmod_gain)(m)
        q = 0.5 - np.minimum(0.5, g * (0.5 - q))
    first = da <= db
    da = np.where(out, np.where(first, q, 1.0 - q), da)
    db = np.where(out, np.where(first, 1.0 - q, q), db)
    coef = np.asarray(AVR495_TABLE_4_3, dtype=np.float64)[sector]          # (..., 3, 2)
    k = coef[..., 0] * da[..., None] + coef[..., 1] * db[..., None]
    return np.asarray(period, dtype=np.float64)[..., None] / 2.0 * (1.0 + k)


def duty_error(run, isign: Sequence[int | None] | None = None, hd: int = 0, om: int = 0) -> tuple[float, int]:
    """Worst |C - C_ideal| in counts of the duty calculator over a run's modulated periods, and the
    period where it occurs (a core.Run, from the model or checked equal to the RTL).

    Ideal: ideal.ideal_compare at the exact full-accumulator angle the core sampled (run.theta[n]) and the
    clamped m it used (run.m[n]); with ``om`` = 1 (the six-step law, om_i) ideal_compare_law, the law in
    floating point (the core's g is UQ8.8 and stretches the clamp's rounding by up to g = 217 at m = 0xFFFF:
    above 2/sqrt3 the error is not a calculator rounding bound). The values the core applies are these
    after the minimum-pulse rule, which moves a value by at most ceil((max(dt, dtf) + mp) / 2) counts near duty 0
    and 1 by design; that the applied values are exactly the rule applied to the calculator's (plus the
    volt-second carry the model recorded for that update, Update.carry_in, |carry| <= ceil(thr/2)), within
    that bound, is asserted.
    With dead-time compensation (``hd`` = fixed.dtc_amounts, ``isign[n]`` the current signs the values of
    period n were computed with) the calculator's values are shifted by -hd / +hd per phase
    (fixed.dtc_shift) before the rule, and the ideal by the same integer: the error is that of the
    unshifted values, the assertion covers the shift."""
    n = np.arange(1, len(run.cmp))
    if n.size == 0:
        raise ValueError("no modulated period in the run")
    th_int = np.array([run.theta[i] for i in n], dtype=np.int64)
    sector = th_int >> fixed.PHASE_WIDTH
    a16 = (th_int >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS)) & 0xFFFF
    m_w = np.array([run.m[i] for i in n], dtype=np.int64)
    p_i = np.array([run.period[i] for i in n], dtype=np.int64)
    raw = fixed.compare_values_np(sector, a16, m_w, p_i)
    if om:                                   # the six-step law where its gain is above 1 (scalar path)
        for k in np.nonzero(m_w > fixed.M_VERTEX)[0]:
            g = fixed.om_gain(int(m_w[k]), True)
            t1, t2, _ = fixed.hex_clamp(*fixed.duties(int(a16[k]), int(m_w[k])), g)
            raw[k] = fixed.dwell_compare(int(sector[k]), t1, t2, int(p_i[k]))
    carry_at = {u.load: u.carry_in for u in getattr(run, "updates", ())}   # the update of period i loads at t_i
    for k, i in enumerate(n):
        thr = max(run.dt[i], run.dtf[i] if run.dtf else run.dt[i]) + run.mp[i]    # max(dt, dtf) + mp
        hthr = (thr + 1) // 2
        sh = tuple(int(c) for c in raw[k])
        if hd and isign is not None:
            sh = fixed.dtc_shift(sh, int(isign[i]), hd, hd)
        cin = carry_at.get(run.valley[i], (0, 0, 0))
        assert all(abs(e) <= hthr for e in cin), f"period {i}: carry {cin} beyond +-{hthr}"
        cmd = tuple(c + e for c, e in zip(sh, cin))
        snapped = tuple(fixed.snap_min_pulse(c, int(p_i[k]), thr) for c in cmd)
        assert snapped == tuple(run.cmp[i]), f"period {i}: applied {run.cmp[i]} != snap(raw + carry) {snapped}"
        assert all(abs(a - b) <= hthr for a, b in zip(run.cmp[i], cmd)), f"period {i}"
    theta = th_int.astype(np.float64) / (1 << fixed.PHASE_WIDTH) * math.pi / 3
    ideal = ideal_compare_law(theta, m_w / fixed.M_ONE, p_i.astype(np.float64), bool(om))
    err = np.max(np.abs(raw - ideal), axis=-1)
    k = int(np.argmax(err))
    return float(err[k]), int(n[k])
