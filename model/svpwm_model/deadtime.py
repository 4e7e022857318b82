# SPDX-License-Identifier: Apache-2.0
"""Dead-time insertion model of rtl/deadtime.sv: an exact event-driven version and a per-clock reference.

The FSM per leg (state: hi, lo, cnt = clocks the state has lasted, this clock included, saturating).
Two dead times: dt (rising: the high side turns on dt after the low side turned off) and dtf (falling: the
low side turns on dtf after the high side turned off); dtf = None means dtf = dt (one dead time).

* target OFF (core disabled / no valid pole): both gates off on the next clock.
* target BRAKE (trip with "low sides on"): the high side turns off on the next clock, then the low side
  turns on after the falling dead time (directly when dtf == 0).
* a gate is on and the pole asks for the other side: once cnt >= max(dt, dtf, mp) the gate turns off
  (minimum on-time); with a zero dead time for the other gate's edge (dt for the high side, dtf for the
  low side) the other gate turns on on the same clock edge.
* both gates off: once cnt >= max(dt, 1) the high side, once cnt >= max(dtf, 1) the low side turns on
  when wanted.
* cnt is 0 only in the first clock after reset, and nothing is "held" then, even with dt == 0 (the RTL
  precomputes its compares a clock ahead; in that clock it has none).
* a reset is a turn-off of unknown dead time (the dead-time registers are cleared with it): until the first
  change after it (``hold``), nothing is held before cnt has saturated at ``sat`` (2^DtWidth - 1), so the
  first turn-on after a reset release comes at the earliest at cycle sat + 1.

Times are clock-cycle indices; a value "at cycle c" is the register value during cycle c.
"""
from __future__ import annotations

from dataclasses import dataclass

OFF, LO, HI, BRAKE = 0, 1, 2, 3


@dataclass
class LegState:
    hi: int = 0
    lo: int = 0
    cnt: int = 0        # saturating at sat
    hold: bool = False  # since a reset, no change yet: nothing turns on before cnt == sat

    def key(self) -> tuple[int, int]:
        return self.hi, self.lo


def step_cycle(s: LegState, tgt: int, dt: int, sat: int, mp: int = 0, dtf: int | None = None) -> LegState:
    """One clock of the FSM (the per-clock reference; mirrors the always_comb of rtl/deadtime.sv).
    ``dt``: rising dead time (before the high side turns on), ``dtf``: falling (before the low side;
    None: dt)."""
    if dtf is None:
        dtf = dt
    hi, lo = s.hi, s.lo
    floor = sat if s.hold else 1
    held_r = s.cnt >= max(dt, floor)
    held_f = s.cnt >= max(dtf, floor)
    held_on = s.cnt >= max(dt, dtf, mp, 1)
    if tgt == OFF:
        hi, lo = 0, 0
    elif s.hi:
        if tgt == BRAKE or (tgt == LO and held_on):
            hi, lo = 0, int(dtf == 0)
    elif s.lo:
        if tgt == HI and held_on:
            hi, lo = int(dt == 0), 0
    elif tgt == HI:
        hi = int(held_r)
    else:
        lo = int(held_f)
    chg = (hi, lo) != (s.hi, s.lo)
    cnt = 1 if chg else min(s.cnt + 1, sat)
    return LegState(hi, lo, cnt, s.hold and not chg)


def simulate_cycles(tgt: list[int], dt: list[int], sat: int, init: LegState | None = None,
                    mp: list[int] | None = None,
                    dtf: list[int | None] | None = None) -> list[tuple[int, int]]:
    """Per-clock reference: gate (hi, lo) at cycles 0..len(tgt) given per-cycle target, rising dead time,
    minimum pulse (default 0) and falling dead time (default: the rising one)."""
    s = init or LegState(0, 0, 0, True)    # reset: off, the longest dead time counts from the release
    out = [s.key()]
    for i, (t, d) in enumerate(zip(tgt, dt)):
        s = step_cycle(s, t, d, sat, mp[i] if mp is not None else 0, dtf[i] if dtf is not None else None)
        out.append(s.key())
    return out


def simulate_events(changes: list[tuple], end: int, sat: int,
                    init: LegState | None = None, start: int = 0) -> tuple[list[tuple[int, int, int]], LegState]:
    """Event-driven FSM: exact same result as simulate_cycles, in time proportional to the edges.

    ``changes``: sorted (cycle, target, dt[, mp[, dtf]]) -- the inputs from that cycle on (the first at
    ``start``); dt is the rising dead time, dtf the falling one (missing or None: dt).
    Returns the gate changes [(cycle, hi, lo), ...] (the new value holds from that cycle) for cycles in
    (start, end], and the state at cycle ``end``.
    """
    s = LegState(init.hi, init.lo, init.cnt, init.hold) if init else LegState(0, 0, 0, True)
    out: list[tuple[int, int, int]] = []
    c = start
    for i, ch in enumerate(changes):
        c0, tgt, dt = ch[:3]
        mp = ch[3] if len(ch) > 3 else 0
        dtf = ch[4] if len(ch) > 4 and ch[4] is not None else dt
        assert c0 == c, (c0, c)
        c_next = changes[i + 1][0] if i + 1 < len(changes) else end
        while c < c_next:
            # first cycle c' >= c at which the FSM decides a change (taking effect at c' + 1)
            if tgt == OFF:
                dec = c if (s.hi or s.lo) else None
            elif (s.hi and tgt == HI) or (s.lo and tgt in (LO, BRAKE)):
                dec = None
            elif s.hi and tgt == BRAKE:
                dec = c
            elif s.hi or s.lo:                         # minimum on-time, then off (or swap)
                dec = c + max(0, max(dt, dtf, mp, 1) - s.cnt)
            else:                                      # the edge's dead time, then on
                dec = c + max(0, max(dt if tgt == HI else dtf, sat if s.hold else 1) - s.cnt)
            if dec is None or dec >= c_next:
                s.cnt = min(s.cnt + (c_next - c), sat)
                c = c_next
                break
            hi, lo = s.hi, s.lo
            if tgt == OFF:
                hi, lo = 0, 0
            elif s.hi:
                hi, lo = 0, int(dtf == 0)
            elif s.lo:
                hi, lo = int(dt == 0), 0
            else:
                hi, lo = int(tgt == HI), int(tgt in (LO, BRAKE))
            s = LegState(hi, lo, 1, False)
            c = dec + 1
            out.append((c, hi, lo))
    return out, s
