# SPDX-License-Identifier: Apache-2.0
"""svpwm_model.deadtime: the event-driven simulate_events equals the per-clock simulate_cycles (exact),
plus directed cases of the dead-time rules (runt pulses vanish or are stretched, dt = 0 swaps)."""
from __future__ import annotations

import random

import pytest

from svpwm_model.deadtime import BRAKE, HI, LO, OFF, LegState, simulate_cycles, simulate_events, step_cycle

SAT10 = (1 << 10) - 1


def events_to_cycles(events, end, init=(0, 0), start=0):
    """Expand [(cycle, hi, lo)] gate changes into the per-cycle (hi, lo) list for cycles start..end."""
    out, cur, i = [], init, 0
    for c in range(start, end + 1):
        while i < len(events) and events[i][0] == c:
            cur = events[i][1:]
            i += 1
        out.append(cur)
    assert i == len(events), "an event outside (start, end]"
    return out


def to_changes(tgt, dt, start=0):
    """Per-cycle inputs -> the (cycle, target, dt) change list simulate_events takes."""
    ch = []
    for k, (t, d) in enumerate(zip(tgt, dt)):
        if not ch or ch[-1][1:] != (t, d):
            ch.append((start + k, t, d))
    return ch


def cycles_state(tgt, dt, sat, init=None):
    s = LegState(init.hi, init.lo, init.cnt, init.hold) if init else LegState(0, 0, 0, True)   # reset state
    for t, d in zip(tgt, dt):
        s = step_cycle(s, t, d, sat)
    return s


def random_inputs(rng: random.Random, sat: int, n_seg: int):
    """Piecewise-constant target and dt with random change points: pulses around dt, OFF segments,
    dt = 0 and dt = sat (the maximum), dt changes inside and between segments."""
    tgt, dt = [], []
    d = min(rng.choice((0, 1, 3, sat)), sat)
    for _ in range(n_seg):
        if rng.random() < 0.3:
            d = min(rng.choice((0, 0, 1, 2, 5, rng.randint(0, sat), sat)), sat)   # dt <= sat (RTL: dt_i width)
        t = rng.choices((OFF, LO, HI), (1, 3, 3))[0]
        n = rng.choice((1, 2, max(1, d - 1), max(1, d), d + 1, d + 2, rng.randint(1, 3 * d + 5)))
        for _ in range(n):
            if rng.random() < 0.01:
                d = rng.randint(0, sat)
            tgt.append(t)
            dt.append(d)
    return tgt, dt


@pytest.mark.parametrize("sat", [SAT10, 15, 1])
def test_events_equal_cycles_random(sat):
    rng = random.Random(0xE7E + sat)
    for trial in range(60 if sat == SAT10 else 300):
        tgt, dt = random_inputs(rng, sat, rng.randint(1, 40))
        init = None
        if trial % 3 == 1:                 # also from a non-reset state
            init = cycles_state(tgt[:7], dt[:7], sat)
            tgt, dt = tgt[7:] or [LO], dt[7:] or [0]
        elif trial % 3 == 2:               # and from a long idle (the reset hold over)
            init = LegState(0, 0, sat)
        start = rng.choice((0, 0, 123))
        end = start + len(tgt)
        exp = simulate_cycles(tgt, dt, sat, init)
        ev, state = simulate_events(to_changes(tgt, dt, start), end, sat, init, start)
        assert [c for c, _, _ in ev] == sorted({c for c, _, _ in ev}), "events not strictly increasing"
        assert all(start < c <= end for c, _, _ in ev)
        got = events_to_cycles(ev, end, init.key() if init else (0, 0), start)
        assert got == exp, f"trial {trial}: first difference at cycle {next(i for i, (a, b) in enumerate(zip(got, exp)) if a != b)}"
        fin = cycles_state(tgt, dt, sat, init)
        assert (state.hi, state.lo, state.cnt, state.hold) == (fin.hi, fin.lo, fin.cnt, fin.hold)
        # no redundant events: every event changes the gates
        prev = init.key() if init else (0, 0)
        for _, h, lo in ev:
            assert (h, lo) != prev
            prev = (h, lo)


def test_events_split_runs():
    """Running in two pieces (the state carried over) equals one run."""
    rng = random.Random(5)
    for _ in range(100):
        tgt, dt = random_inputs(rng, SAT10, 20)
        cut = rng.randint(1, len(tgt) - 1) if len(tgt) > 1 else 1
        ev1, s1 = simulate_events(to_changes(tgt[:cut], dt[:cut]), cut, SAT10)
        ev2, s2 = simulate_events(to_changes(tgt[cut:], dt[cut:], cut), len(tgt), SAT10, s1, cut) if cut < len(tgt) \
            else ([], s1)
        ev, s = simulate_events(to_changes(tgt, dt), len(tgt), SAT10)
        assert ev1 + ev2 == ev and (s2.hi, s2.lo, s2.cnt) == (s.hi, s.lo, s.cnt)


IDLE = LegState(0, 0, SAT10)      # off for a long time (the dead-time counter saturated)


def lo_then_pulse(dt, w, tail):
    lead = dt + 3
    tgt = [LO] * lead + [HI] * w + [LO] * tail
    return lead, tgt, [dt] * len(tgt)


@pytest.mark.parametrize("dt", [1, 2, 7, 48, SAT10])
def test_short_pulse_vanishes(dt):
    """A pole pulse of width <= dt vanishes: the low gate is off for exactly dt clocks and returns."""
    for w in sorted({w for w in (1, 2, dt // 2, dt - 1, dt) if 1 <= w <= dt}):
        lead, tgt, dts = lo_then_pulse(dt, w, 2 * dt + 4)
        out = simulate_cycles(tgt, dts, SAT10, IDLE)
        assert out[lead] == (0, 1)
        assert all(h == 0 for h, _ in out), f"dt={dt} w={w}: a high-side pulse"
        notch = [c for c, g in enumerate(out) if c > lead and g == (0, 0)]
        assert notch == list(range(lead + 1, lead + dt + 1)), (dt, w, notch[:3], len(notch))
        ev, _ = simulate_events(to_changes(tgt, dts), len(tgt), SAT10, IDLE)
        assert ev == [(1, 0, 1), (lead + 1, 0, 0), (lead + dt + 1, 0, 1)]      # (1, 0, 1): lo on at once


@pytest.mark.parametrize("dt", [1, 2, 7, 48, SAT10])
def test_pulse_dt_plus_one_stretched(dt):
    """A pole pulse of dt + 1 clocks becomes a high-side pulse of exactly dt clocks (minimum on-time),
    framed by dead times of dt."""
    lead, tgt, dts = lo_then_pulse(dt, dt + 1, 3 * dt + 4)
    out = simulate_cycles(tgt, dts, SAT10, IDLE)
    hi = [c for c, (h, _) in enumerate(out) if h]
    assert hi == list(range(lead + dt + 1, lead + 2 * dt + 1))
    ev, _ = simulate_events(to_changes(tgt, dts), len(tgt), SAT10, IDLE)
    assert ev == [(1, 0, 1), (lead + 1, 0, 0), (lead + dt + 1, 1, 0), (lead + 2 * dt + 1, 0, 0),
                  (lead + 3 * dt + 1, 0, 1)]


def test_dt_zero_swaps_same_clock():
    """dt = 0: the gates swap on one clock edge (never both on, never both off) and follow the pole
    one clock later, however short the pulse. After a reset nothing turns on before the counter has
    saturated (the reset hold): the first gate turns on in cycle SAT10 + 1, whatever the dead time."""
    rng = random.Random(3)
    tgt = [rng.choice((LO, HI)) for _ in range(SAT10 + 500)]
    out = simulate_cycles(tgt, [0] * len(tgt), SAT10)
    assert all(g == (0, 0) for g in out[:SAT10 + 1])
    for k, t in enumerate(tgt[SAT10:], start=SAT10):
        assert out[k + 1] == ((1, 0) if t == HI else (0, 1))
    ev, _ = simulate_events(to_changes(tgt, [0] * len(tgt)), len(tgt), SAT10)
    assert ev[0][0] == SAT10 + 1
    swaps = [e for e in ev[1:]]
    assert all((h, lo) in ((1, 0), (0, 1)) for _, h, lo in swaps)


def test_off_turns_gates_off_next_clock():
    """OFF turns the on gate off on the next clock, even within the minimum on-time."""
    for dt in (0, 1, 5, SAT10):
        tgt = [HI] * (dt + 3) + [OFF] * 3
        out = simulate_cycles(tgt, [0] * 2 + [dt] * (len(tgt) - 2), SAT10, IDLE)
        on = out.index((1, 0))
        tgt = [HI] * on + [OFF] * 3
        out = simulate_cycles(tgt, [0] * 2 + [dt] * (len(tgt) - 2), SAT10, IDLE)
        assert out[on] == (1, 0) and out[on + 1] == (0, 0)


@pytest.mark.parametrize("sat", [SAT10, 15])
@pytest.mark.parametrize("dt", [0, 1, 7, 15])
def test_reset_counts_as_turn_off(dt, sat):
    """A reset is a turn-off of unknown dead time (the dead-time registers are cleared with it): the
    first turn-on comes when the counter has saturated, in cycle sat + 1 after the release, whatever the
    dead time in force (here <= sat), and the hold ends with it: later edges use the dead time."""
    for tgt0 in (LO, HI, BRAKE):
        tgt = [tgt0] * (sat + 4) + [HI if tgt0 != HI else LO] * (3 * sat + 4)
        out = simulate_cycles(tgt, [dt] * len(tgt), sat, mp=[0] * len(tgt))
        on = [c for c, g in enumerate(out) if g != (0, 0)][0]
        assert on == sat + 1, (tgt0, dt, sat, on)
        ev, _ = simulate_events(to_changes(tgt, [dt] * len(tgt)), len(tgt), sat)
        assert ev[0][0] == sat + 1 and events_to_cycles(ev, len(tgt)) == out
        # after the hold the dead time is the one in force again: the other gate turns on dt clocks after
        # the first turned off (a swap in the same clock when dt == 0)
        other = [c for c, g in enumerate(out) if c > on and g == ((1, 0) if tgt0 != HI else (0, 1))][0]
        off = [c for c, g in enumerate(out) if c > on and g != out[on]][0]
        assert other - off == dt, (tgt0, dt, sat, on, off, other)


# ---- separate rising (dt) and falling (dtf) dead times -------------------------------------------------

def random_inputs_asym(rng: random.Random, sat: int, n_seg: int):
    """Per-cycle target (OFF, LO, HI, BRAKE), rising dead time, falling dead time and minimum pulse,
    piecewise constant with random change points; dt != dtf mostly, either larger, zeros on one edge."""
    tgt, dt, dtf, mp = [], [], [], []
    pick = lambda: min(rng.choice((0, 0, 1, 2, 3, 5, rng.randint(0, sat), sat)), sat)   # noqa: E731
    d, f, m = pick(), pick(), 0
    for _ in range(n_seg):
        if rng.random() < 0.3:
            d, f = pick(), pick()
        if rng.random() < 0.2:
            m = pick()
        t = rng.choices((OFF, LO, HI, BRAKE), (1, 3, 3, 1))[0]
        w = max(d, f, m)
        n = rng.choice((1, 2, max(1, w - 1), max(1, w), w + 1, w + 2, rng.randint(1, 3 * w + 5)))
        for _ in range(n):
            if rng.random() < 0.01:
                d, f = rng.randint(0, sat), rng.randint(0, sat)
            tgt.append(t)
            dt.append(d)
            dtf.append(f)
            mp.append(m)
    return tgt, dt, dtf, mp


@pytest.mark.parametrize("sat", [SAT10, 15, 1])
def test_events_equal_cycles_asymmetric(sat):
    """simulate_events == simulate_cycles with dt != dtf, minimum pulses and braking, from reset and from
    a state reached by the per-clock model."""
    rng = random.Random(0xA5F + sat)
    for trial in range(80 if sat == SAT10 else 300):
        tgt, dt, dtf, mp = random_inputs_asym(rng, sat, rng.randint(1, 40))
        init = None
        if trial % 3 == 1:
            s = LegState(0, 0, 0, True)
            for k in range(min(7, len(tgt))):
                s = step_cycle(s, tgt[k], dt[k], sat, mp[k], dtf[k])
            init = s
            tgt, dt, dtf, mp = tgt[7:] or [LO], dt[7:] or [0], dtf[7:] or [3 % (sat + 1)], mp[7:] or [0]
        elif trial % 3 == 2:               # from a long idle (the reset hold over)
            init = LegState(0, 0, sat)
        start = rng.choice((0, 0, 77))
        end = start + len(tgt)
        exp = simulate_cycles(tgt, dt, sat, init, mp=mp, dtf=dtf)
        ch = []
        for k, x in enumerate(zip(tgt, dt, mp, dtf)):
            if not ch or ch[-1][1:] != x:
                ch.append((start + k,) + x)
        ev, _ = simulate_events(ch, end, sat, init, start)
        got = events_to_cycles(ev, end, init.key() if init else (0, 0), start)
        assert got == exp, f"trial {trial}: first difference at cycle {next(i for i, (a, b) in enumerate(zip(got, exp)) if a != b)}"


@pytest.mark.parametrize("dt,dtf", [(3, 9), (9, 3), (0, 5), (5, 0), (1, 2), (48, 17)])
def test_asymmetric_edges(dt, dtf):
    """From the low side on, a long high pole pulse: the high side turns on dt clocks after the low side
    turned off, and the low side dtf clocks after the high side turned off; a short high pole pulse gives
    a high-side pulse of max(dt, dtf) (minimum on-time); dtf = None is dtf = dt."""
    lead, w = max(dt, dtf) + 3, 3 * max(dt, dtf) + 5
    tgt = [LO] * lead + [HI] * w + [LO] * (2 * max(dt, dtf) + 4)
    n = len(tgt)
    out = simulate_cycles(tgt, [dt] * n, SAT10, IDLE, dtf=[dtf] * n)
    ev, _ = simulate_events([(0, LO, dt, 0, dtf), (lead, HI, dt, 0, dtf), (lead + w, LO, dt, 0, dtf)], n,
                            SAT10, IDLE)
    assert events_to_cycles(ev, n, (0, 0)) == out
    lo_off = lead + 1                                   # the low side turns off one clock after the request
    hi_on = lo_off + dt if dt else lo_off               # (dt = 0: the same clock, a swap)
    hi_off = lead + w + 1
    lo_on = hi_off + dtf if dtf else hi_off
    assert (out[hi_on], out[hi_on - 1]) == ((1, 0), (0, 0) if dt else (0, 1)), (dt, dtf, out[lead:hi_on + 2])
    assert [c for c, (h, _) in enumerate(out) if h] == list(range(hi_on, hi_off))
    assert out[lo_on] == (0, 1) and all(g == (0, 0) for g in out[hi_off:lo_on])
    # a high pole pulse of dt + 1 clocks: the high side on for max(dt, dtf) (minimum on-time), then dtf
    if dt:
        tgt = [LO] * lead + [HI] * (dt + 1) + [LO] * (3 * max(dt, dtf) + 4)
        n = len(tgt)
        out = simulate_cycles(tgt, [dt] * n, SAT10, IDLE, dtf=[dtf] * n)
        hi = [c for c, (h, _) in enumerate(out) if h]
        assert hi == list(range(lead + 1 + dt, lead + 1 + dt + max(dt, dtf)))
        assert out[hi[-1] + 1 + dtf] == (0, 1) and out[hi[-1] + dtf] == ((0, 0) if dtf else (1, 0))
    # dtf = None and dtf = dt are the symmetric FSM
    n = len(tgt)
    assert simulate_cycles(tgt, [dt] * n, SAT10, IDLE, dtf=[None] * n) == simulate_cycles(tgt, [dt] * n, SAT10, IDLE)


def test_brake_uses_falling_dead_time():
    """BRAKE from the high side on: the high side off on the next clock, the low side dtf later."""
    for dt, dtf in ((9, 3), (3, 9), (4, 0)):
        tgt = [HI] * (dt + 3) + [BRAKE] * (dtf + 4)
        n = len(tgt)
        out = simulate_cycles(tgt, [dt] * n, SAT10, IDLE, dtf=[dtf] * n)
        hi_off = dt + 3 + 1
        assert out[hi_off - 1] == (1, 0)
        assert out[hi_off + dtf] == (0, 1) and all(g == (0, 0) for g in out[hi_off:hi_off + dtf])
