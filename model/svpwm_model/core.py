# SPDX-License-Identifier: Apache-2.0
"""Clock-exact model of rtl/svpwm_core.sv: per-period compare values and every pole and gate edge.

Time base: cycle 0 is the first clock with en_i = 1 (the valley of carrier period 0). A value "at
cycle c" is a register's value during clock c; an edge "at cycle c" means the new value holds from c.

Timeline (see README "Timing"):
* period n starts at valley t_n with half period P_n: t_{n+1} = t_n + 2 P_n; its peak is t_n + P_n.
* at the peak of period n the core samples the inputs u_n (freq, m, period, dt) and the angle; the
  compare values computed from them, P_{n+1} = clamp(u_n.period) and dt_{n+1} = u_n.dt are active
  from valley t_{n+1} on. Period 0 runs with the idle inputs' period and dead time and no compare
  values (gates off); the first modulated period is n = 1.
* the angle advances every running clock by the frequency word in force: the idle word until the
  peak of period 0, u_n.freq from the peak of period n (inclusive) on.
* pole x is high during cycles [t_n + C + 1, t_n + 2 P_n - C + 1) of period n (n >= 1).
* gates: rtl/deadtime.sv per leg (model: deadtime.py), target OFF until cycle t_1 + 1.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field
from typing import Callable, Sequence

from . import fixed
from .deadtime import HI, LO, OFF, LegState, simulate_events


@dataclass(frozen=True)
class Inputs:
    """Values on the core's input ports when they are sampled."""
    freq: int = 0           # signed frequency word
    m: int = 0              # UQ1.15
    period: int = 1536      # half period, clocks
    dt: int = 0             # dead time, clocks
    mp: int = 0             # minimum gate pulse, clocks


@dataclass
class Run:
    """Result of CoreModel.run(); arrays are indexed by carrier period n = 0..N-1 unless stated."""
    valley: list[int] = field(default_factory=list)      # t_n, n = 0..N (t_N: the valley after the last)
    period: list[int] = field(default_factory=list)      # P_n
    dt: list[int] = field(default_factory=list)          # dead time active in period n
    mp: list[int] = field(default_factory=list)          # minimum pulse active in period n
    cmp: list[tuple[int, int, int] | None] = field(default_factory=list)   # (C_a, C_b, C_c), None for n = 0
    sector: list[int | None] = field(default_factory=list)                 # sector of the compare values
    theta: list[int | None] = field(default_factory=list)  # exact full angle (sector*2^W + angle) used
    m: list[int | None] = field(default_factory=list)      # clamped m used
    pole_edges: list[tuple[int, int]] = field(default_factory=list)    # (cycle, pole word {c,b,a})
    gate_edges: list[tuple[int, int]] = field(default_factory=list)    # (cycle, {lo[2:0], hi[2:0]})
    end: int = 0                                           # edges are listed for cycles < end


def _merge(words: dict[int, list[tuple[int, int]]], bits: int) -> list[tuple[int, int]]:
    """Merge per-bit change lists {bit: [(cycle, value)]} into word changes [(cycle, word)]."""
    ev: dict[int, dict[int, int]] = {}
    for b, lst in words.items():
        for c, v in lst:
            ev.setdefault(c, {})[b] = v
    out, word = [], 0
    for c in sorted(ev):
        for b, v in ev[c].items():
            word = (word & ~(1 << b)) | (v << b)
        if not out or out[-1][1] != word:
            out.append((c, word))
    return out


class CoreModel:
    """The golden model. State carried between runs: the angle and the dead-time FSMs."""

    def __init__(self, sector: int = 0, angle: int = 0):
        self.theta = (sector << fixed.PHASE_WIDTH) + angle      # full angle, units 60deg / 2^PHASE_WIDTH
        self.legs = [LegState(0, 0, 0) for _ in range(3)]     # reset: off, dead time counts from release

    def run(self, idle: Inputs, inputs: Sequence[Inputs] | Callable[[int], Inputs], n_periods: int,
            stop: int | None = None) -> Run:
        """Enable the core with ``idle`` on the inputs and run ``n_periods`` carrier periods.

        ``inputs(n)`` / ``inputs[n]`` are the inputs sampled at the peak of period n (n = 0..N-1).
        ``stop``: en_i goes low at cycle t_N + stop (0 <= stop <= P_N; default: no stop, the run ends
        at t_N with the core still running -- the gate edges are then complete up to t_N).
        """
        get = inputs if callable(inputs) else (lambda n: inputs[n])
        full = 6 << fixed.PHASE_WIDTH
        r = Run()
        p_cur, _ = fixed.clamp_period(idle.period, idle.dt, idle.mp)
        dt_cur, mp_cur = idle.dt, idle.mp
        f_cur, _ = fixed.clamp_freq(idle.freq)
        t, theta = 0, self.theta
        cmp_cur: tuple[int, int, int] | None = None
        pole_hi: list[list[tuple[int, int]]] = [[], [], []]   # high intervals per phase
        for n in range(n_periods + 1):
            r.valley.append(t)
            if n == n_periods:
                break
            r.period.append(p_cur)
            r.dt.append(dt_cur)
            r.mp.append(mp_cur)
            r.cmp.append(cmp_cur)
            if cmp_cur is not None:
                for ph, c in enumerate(cmp_cur):
                    if c < p_cur:
                        pole_hi[ph].append((t + c + 1, t + 2 * p_cur - c + 1))
            # peak of period n: the angle has advanced P_n clocks at f_cur since the valley
            theta = (theta + f_cur * p_cur) % full
            u = get(n)
            p_next, _ = fixed.clamp_period(u.period, u.dt, u.mp)
            m_next, _ = fixed.clamp_m(u.m)
            sector, angle = theta >> fixed.PHASE_WIDTH, theta & ((1 << fixed.PHASE_WIDTH) - 1)
            a16 = angle >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS)
            cmp_next = tuple(fixed.snap_min_pulse(c, p_next, u.dt + u.mp)
                             for c in fixed.compare_values(sector, a16, m_next, p_next))
            r.sector.append(sector)
            r.theta.append(theta)
            r.m.append(m_next)
            f_cur, _ = fixed.clamp_freq(u.freq)
            # rest of period n (peak to next valley): P_n clocks at the new frequency
            theta = (theta + f_cur * p_cur) % full
            t += 2 * p_cur
            p_cur, dt_cur, mp_cur, cmp_cur = p_next, u.dt, u.mp, cmp_next
        t_end = t
        # the sector/theta/m lists describe the compare values of the NEXT period; shift them so that
        # index n describes period n (None for period 0)
        r.sector = [None] + r.sector[:-1]
        r.theta = [None] + r.theta[:-1]
        r.m = [None] + r.m[:-1]
        stop_cycle = None
        if stop is not None:
            if not 0 <= stop <= p_cur:
                raise ValueError("stop must lie between the last valley and the following peak")
            stop_cycle = t_end + stop
            if cmp_cur is not None:       # period N runs until the stop
                for ph, c in enumerate(cmp_cur):
                    if c < p_cur:
                        pole_hi[ph].append((t_end + c + 1, t_end + 2 * p_cur - c + 1))
            theta = (theta + f_cur * stop) % full
            end = stop_cycle + 2          # the gates are off from stop_cycle + 1
        else:
            end = t_end
        self.theta = theta
        r.end = end
        # ---- poles: merge touching intervals, clip at the stop (pole regs clear the cycle after) ----
        pole_ch: dict[int, list[tuple[int, int]]] = {}
        for ph in range(3):
            iv: list[list[int]] = []
            for a, b in pole_hi[ph]:
                if stop_cycle is not None:
                    a, b = a, min(b, stop_cycle + 1)
                    if a >= b:
                        continue
                if iv and iv[-1][1] == a:
                    iv[-1][1] = b
                else:
                    iv.append([a, b])
            lst = []
            for a, b in iv:
                lst += [(a, 1), (b, 0)]
            pole_ch[ph] = [(c, v) for c, v in lst if c < end]
        r.pole_edges = _merge(pole_ch, 3)
        # ---- gates: target per leg, piecewise constant; dead time and minimum pulse change at valleys ----
        valid_from = r.valley[1] + 1 if n_periods >= 1 else end      # pole_valid_q
        gate_ch: dict[int, list[tuple[int, int]]] = {}
        for ph in range(3):
            times = {0, valid_from} | {c for c, _ in pole_ch[ph]} | set(r.valley[:n_periods])
            if stop_cycle is not None:
                times |= {t_end, stop_cycle}
            times = sorted(x for x in times if 0 <= x < end)
            pole_val = dict(pole_ch[ph])
            changes, pv = [], 0
            for c in times:
                pv = pole_val.get(c, pv)
                if stop_cycle is not None and c >= stop_cycle:
                    tgt = OFF
                elif c < valid_from:
                    tgt = OFF
                else:
                    tgt = HI if pv else LO
                k = bisect.bisect_right(r.valley, c) - 1
                dt = r.dt[k] if k < len(r.dt) else dt_cur
                mp = r.mp[k] if k < len(r.mp) else mp_cur
                changes.append((c, tgt, dt, mp))
            ev, self.legs[ph] = simulate_events(changes, end, (1 << fixed.DT_WIDTH) - 1, self.legs[ph])
            gate_ch[ph] = [(c, h) for c, h, _ in ev if c < end]
            gate_ch[ph + 3] = [(c, lo) for c, _, lo in ev if c < end]
        r.gate_edges = _merge(gate_ch, 6)
        return r

    def idle(self, cycles: int) -> None:
        """The core idles (en_i low) for ``cycles`` clocks: gates off, dead-time counters run on."""
        sat = (1 << fixed.DT_WIDTH) - 1
        for leg in self.legs:
            assert not (leg.hi or leg.lo), "gates must be off when idle"
            leg.cnt = min(leg.cnt + cycles, sat)
