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
from svpwm_model.analysis import line_fundamental, phase_switching, word_at
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
    r = CoreModel().run(idle, SCHED, len(SCHED))
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
