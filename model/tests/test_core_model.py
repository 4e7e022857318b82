# SPDX-License-Identifier: Apache-2.0
"""svpwm_model.core.CoreModel: the timeline properties the RTL core is tested against, on the model alone.

Valleys 2P apart; period 0 has no compare values and the gates stay off; each phase is high for exactly
2(P - C) clocks per period, symmetric about the peak (+1 clock for the registered pole); the angle
after N periods is fixed.angle_step of the same clocks and each update uses the angle SAMPLE_LEAD clocks
before its load point; period clamp; a stop turns the gates off on the next clock; the line-voltage
fundamental of the pole edges is the commanded m within 0.1 %.
"""
from __future__ import annotations

import math

import pytest

from svpwm_model import fixed
from svpwm_model.analysis import check_legs, duty_error, line_fundamental, phase_switching, word_at
from svpwm_model.core import CoreModel, Inputs

FW, MW = fixed.freq_word, fixed.m_word
FULL = 6 << fixed.PHASE_WIDTH


def full_angle(sector: int, angle: int) -> int:
    return (sector << fixed.PHASE_WIDTH) + angle


def advance(theta: int, step: int, clocks: int) -> int:
    return full_angle(*fixed.angle_step(theta >> fixed.PHASE_WIDTH, theta & ((1 << fixed.PHASE_WIDTH) - 1),
                                        step, clocks))


def high_intervals(pole_edges, phase):
    """[a, b) intervals where the phase's pole is high, from the merged word stream."""
    iv, start = [], None
    for c, v in phase_switching(pole_edges, phase):
        if v and start is None:
            start = c
        elif not v and start is not None:
            iv.append((start, c))
            start = None
    if start is not None:
        iv.append((start, 1 << 60))
    return iv


def clip(iv, lo, hi):
    return [(max(a, lo), min(b, hi)) for a, b in iv if min(b, hi) > max(a, lo)]


# the schedules' periods were chosen around MinPeriod 48 (two below it); they move with the core's MinPeriod
# (the calculator's lead + 4), so the same ones are clamped
O = fixed.MIN_PERIOD - fixed.MIN_PERIOD_BASE
SCHED = [Inputs(FW(f), MW(m), p + O, dt) for f, m, p, dt in
         [(120.0, 0.7, 64, 3), (120.0, 0.7, 64, 3), (-300.0, 1.0, 40, 0), (800.0, 0.05, 100, 7),
          (0.0, 0.5, 33, 1), (2000.0, 0.95, 77, 2), (-2000.0, 0.3, 64, 5), (50.0, 0.0, 90, 0)] * 4]


def test_valley_spacing_and_first_period():
    idle = Inputs(FW(120.0), MW(0.7), 50 + O, 3)
    sat = (1 << fixed.DT_WIDTH) - 1
    # started in the clock of the reset release, the reset hold keeps every gate off until cycle sat + 1
    # (the counter saturated), although the first update comes earlier
    r = CoreModel().run(idle, SCHED, len(SCHED))
    assert r.valley[1] + 2 < sat + 1 and r.gate_edges[0][0] == sat + 1
    m = CoreModel()
    m.idle(sat)                                   # the reset hold is over before the start
    r = m.run(idle, SCHED, len(SCHED))
    assert r.valley[0] == fixed.START_DELAY and r.period[0] == 50 + O
    for n in range(len(SCHED)):
        assert r.valley[n + 1] - r.valley[n] == 2 * r.period[n]
        if n:
            assert r.period[n] == fixed.clamp_period(SCHED[n - 1].period)[0]
            assert r.dt[n] == SCHED[n - 1].dt
    # period 0: no compare values, poles and gates off until the first modulated period
    assert r.cmp[0] is None and r.sector[0] is None and all(c is not None for c in r.cmp[1:])
    t1 = r.valley[1]
    assert all(c > t1 for c, _ in r.pole_edges) and all(c > t1 for c, _ in r.gate_edges)
    assert word_at(r.gate_edges, t1) == 0 and word_at(r.pole_edges, t1) == 0
    assert r.gate_edges[0][0] == t1 + 2          # targets valid from t1 + 1, gates one clock later


def test_pole_intervals_centred_on_peak():
    idle = Inputs(FW(120.0), MW(0.7), 64, 3)
    r = CoreModel(sector=2, angle=12345).run(idle, SCHED, len(SCHED))
    checked = 0
    for ph in range(3):
        iv = high_intervals(r.pole_edges, ph)
        for n in range(1, len(SCHED)):
            t, p, c = r.valley[n], r.period[n], r.cmp[n][ph]
            win = clip(iv, t + 1, r.valley[n + 1] + 1)          # the registered pole of period n
            assert c == fixed.compare_values(r.sector[n], (r.theta[n] & ((1 << fixed.PHASE_WIDTH) - 1))
                                             >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS), r.m[n], p)[ph]
            if c >= p:
                assert win == []
                continue
            assert len(win) == 1, (n, ph, win)
            rise, fall = win[0]
            peak = t + p
            assert fall - rise == 2 * (p - c)
            assert (rise - 1) + (fall - 1) == 2 * peak, "not centred on the peak"
            assert rise == t + c + 1
            checked += 1
    assert checked > 50


def test_accumulator_equals_angle_step():
    # constant frequency: the angle after N periods = angle_step over all their clocks
    for f, p, n in ((FW(50.0), 1536, 40), (FW(-777.0), 100 + O, 97), (-(1 << 23), 48 + O, 500), ((1 << 23) - 1, 49 + O, 500)):
        u = Inputs(f, MW(0.5), p, 0)
        mdl = CoreModel(sector=4, angle=(1 << fixed.PHASE_WIDTH) - 5)
        r = mdl.run(u, [u] * n, n)
        assert r.valley[-1] == fixed.START_DELAY + 2 * p * n
        f_used = fixed.clamp_freq(f)[0]      # -2^23 is clamped to -(2^23 - 1): a symmetric range
        assert mdl.theta == advance(full_angle(4, (1 << fixed.PHASE_WIDTH) - 5), f_used, 2 * p * n)
    # changing frequency and period: idle.freq until the first sample, SAMPLE_LEAD clocks before valley 1;
    # then each sample's frequency word from that sample on
    mdl = CoreModel()
    idle = Inputs(FW(10.0), 0, 48 + O, 0)
    r = mdl.run(idle, SCHED, len(SCHED))
    theta, t_prev, f = 0, fixed.START_DELAY, idle.freq
    for n in range(len(SCHED)):
        s = r.valley[n + 1] - fixed.SAMPLE_LEAD
        theta = advance(theta, f, s - t_prev)
        if n + 1 < len(SCHED):
            assert r.theta[n + 1] == theta             # sampled SAMPLE_LEAD before valley n + 1
        t_prev, f = s, SCHED[n].freq
    assert mdl.theta == advance(theta, f, r.valley[-1] - t_prev)


def test_period_clamp_and_overmodulation():
    """A too short period is lengthened to MIN_PERIOD; m beyond 1.0 is accepted and clamped to the hexagon."""
    u = Inputs(FW(200.0), 0xFFFF, 5, 2)
    r = CoreModel().run(u, [u, Inputs(FW(200.0), 0x8001, 0, 2), Inputs(FW(200.0), 0x8000, 47, 2),
                            Inputs(FW(200.0), 0x7FFF, 48, 2)], 4)
    lo = fixed.MIN_PERIOD
    assert r.period == [lo] * 4 and r.m[1:] == [0xFFFF, 0x8001, 0x8000]
    assert [b - a for a, b in zip(r.valley, r.valley[1:])] == [2 * lo] * 4
    a16 = lambda th: (th & ((1 << fixed.PHASE_WIDTH) - 1)) >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS)
    for n in (1, 2, 3):
        assert r.cmp[n] == tuple(fixed.snap_min_pulse(c, lo, 2) for c in
                                 fixed.compare_values(r.sector[n], a16(r.theta[n]), r.m[n], lo))
    assert r.updates[0].sat and not r.updates[2].sat and not r.updates[3].sat
    assert fixed.clamp_period(lo - 1) == (lo, True) and fixed.clamp_period(lo) == (lo, False)


@pytest.mark.parametrize("stop", [0, 1, 20, 32, 63, 64])
def test_stop_turns_gates_off(stop):
    u = Inputs(FW(900.0), MW(0.8), 64, 2)
    n = 6
    full = CoreModel().run(u, [u] * (n + 1), n + 1)                 # reference: no stop
    r = CoreModel().run(u, [u] * n, n, stop=stop)
    s = r.valley[n] + stop
    assert r.end == s + 2
    for c in range(0, s + 1):                                       # identical up to the stop clock
        assert word_at(r.gate_edges, c) == word_at(full.gate_edges, c), c
    assert word_at(r.gate_edges, s + 1) == 0 and word_at(r.pole_edges, s + 1) == 0
    if word_at(full.gate_edges, s) != 0:
        assert r.gate_edges[-1] == (s + 1, 0)
    assert all(c <= s + 1 for c, _ in r.gate_edges)


def test_stop_with_gates_on():
    """At least one stop point of the sweep above has gates on (so the turn-off edge is really there)."""
    u = Inputs(FW(900.0), MW(0.8), 64, 2)
    r = CoreModel().run(u, [u] * 6, 6, stop=32)
    s = r.valley[6] + 32
    assert word_at(r.gate_edges, s) != 0 and r.gate_edges[-1] == (s + 1, 0)


@pytest.mark.parametrize("m", [0.1, 0.3, 0.6, 0.9, 1.0])
def test_line_fundamental(m):
    p = 1536
    u = Inputs(FW(50.0), MW(m), p, 0)
    n = math.ceil(fixed.F_CLK_DEFAULT / (2 * p) / 50.0) + 2
    r = CoreModel().run(u, [u] * n, n)
    amp = line_fundamental(r.pole_edges, u.freq, r.valley[1] + 1, 1)
    assert abs(amp / m - 1) < 1e-3, f"m={m}: line fundamental {amp:.6f}"


def test_duty_error_against_ideal_and_min_pulse_rule():
    """analysis.duty_error: the calculator stays within 0.53 counts of the ideal at m = 1 with a dead
    time that makes the minimum-pulse rule act; a compare value off the rule is caught."""
    from svpwm_model.analysis import duty_error
    u = Inputs(FW(50.0), MW(1.0), 1536, 48)
    r = CoreModel().run(u, [u] * 320, 320)
    worst, at = duty_error(r)
    assert 0.4 < worst <= 0.53 and 1 <= at < 320
    c = list(r.cmp[100])
    c[0] += 1
    r.cmp[100] = tuple(c)
    with pytest.raises(AssertionError, match="period 100"):
        duty_error(r)


def test_clamp_period_falling_dead_time():
    """fixed.clamp_period: the floor is 2 (max(dt, dtf) + mp); dtf None (the default) is dt, so every call
    without it is the symmetric one."""
    mpd = fixed.MIN_PERIOD
    assert fixed.clamp_period(100, 10, 0) == fixed.clamp_period(100, 10, 0, dtf=None) == (mpd, True)
    assert fixed.clamp_period(300, 10, 5, dtf=150) == (310, True)        # 2 (150 + 5)
    assert fixed.clamp_period(300, 150, 5, dtf=10) == (310, True)        # the larger one, either edge
    assert fixed.clamp_period(310, 150, 5, dtf=10) == (310, False)
    assert fixed.clamp_period(400, 10, 0, min_period=20, dtf=30) == (400, False)
    assert fixed.clamp_period(50, 10, 0, min_period=20, dtf=30) == (60, True)
    for dt in (0, 7, 200):
        for mp in (0, 3):
            assert fixed.clamp_period(260, dt, mp, dtf=dt) == fixed.clamp_period(260, dt, mp)


def test_asymmetric_dead_time_threshold_and_gates():
    """CoreModel with dt != dtf: the period floor and the calculator's minimum-pulse threshold use
    max(dt, dtf) + mp (the applied compare values are snap_min_pulse of the raw ones with it, and change
    when only dtf changes); a change of dtf alone forces an update at its valley; the legs wait dt before
    a high side, dtf before a low side; the compact model ignores dtf."""
    base = dict(freq=FW(400.0), m=MW(1.0), period=600, presc=3)
    sched = ([Inputs(**base, dt=6, dtf=40, mp=2)] * 6 + [Inputs(**base, dt=6, dtf=10, mp=2)] * 6
             + [Inputs(**(base | dict(period=100)), dt=5, dtf=140)] * 4)
    r = CoreModel().run(sched[0], sched, len(sched))
    assert r.dtf[1:7] == [40] * 6 and r.dt[1:7] == [6] * 6
    assert r.period[13:] == [280] * 3                    # 2 * (max(5, 140) + 0): raised for dtf
    duty_error(r)                                        # asserts cmp == snap(raw, max(dt, dtf) + mp)
    # the snapped values are those of max(dt, dtf) + mp, not of dt + mp (m = 1: values near 0 snap)
    for u in r.updates:
        n = r.valley.index(u.load) if u.load in r.valley else None
        if n is not None and r.dtf[n] != r.dt[n]:
            thr = max(r.dt[n], r.dtf[n]) + r.mp[n]
            assert all(c == 0 or c >= thr for c in u.cmp), (n, u.cmp, thr)
    # not vacuous: the same schedule with dtf = dt gives other compare values (thr 8 instead of 42)
    sym = [Inputs(**{k: v for k, v in u.__dict__.items() if k != "dtf"}) for u in sched]
    rs = CoreModel().run(sym[0], sym, len(sym))
    assert [u.cmp for u in rs.updates[:3]] != [u.cmp for u in r.updates[:3]], "dtf did not change thr"
    # the dtf-only change at valley 7 is a forced update (the prescaler would skip it: updates at 1, 5, 9)
    assert r.valley[7] in {u.load for u in r.updates}
    # per-edge dead times on the legs: gaps before a high side >= dt, before a low side >= dtf, and the
    # exact value occurs (a low side waits dtf = 40 after a high side)
    def at(c):
        k = max(i for i, v in enumerate(r.valley[:-1]) if v <= c)
        return r.dt[k], r.dtf[k]
    assert check_legs(r.gate_edges, at).ok
    gaps = []
    for leg in range(3):
        last_hi_off, prev = None, (0, 0)
        for c, w in r.gate_edges:
            cur = ((w >> leg) & 1, (w >> (leg + 3)) & 1)
            if prev[0] and not cur[0]:
                last_hi_off = c
            if cur[1] and not prev[1] and last_hi_off is not None:
                gaps.append((at(c - 1), c - last_hi_off))
            prev = cur
    assert any(g == 40 for (dt, dtf), g in gaps if dtf == 40), gaps[:10]
    # compact: dtf ignored, the symmetric run
    rc = CoreModel(compact=True).run(sched[0], sched, len(sched))
    rs = CoreModel(compact=True).run(sym[0], sym, len(sym))
    assert rc.gate_edges == rs.gate_edges and rc.dtf == rc.dt
