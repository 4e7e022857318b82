# SPDX-License-Identifier: Apache-2.0
"""svpwm_model.adc: the shunt-window report equals the gates' real on-times (the golden model's gate edges,
dead time and minimum pulse included), and the trigger-point rule (per clock, as the RTL) fires exactly once
per period at point_clock."""
from __future__ import annotations

import random

import pytest

from svpwm_model import adc, fixed
from svpwm_model.core import CoreModel, Inputs


def intervals(edges: list[tuple[int, int]], bit: int, end: int) -> list[tuple[int, int]]:
    """The intervals [a, b) in which gate word bit ``bit`` is 1."""
    val, a, out = 0, 0, []
    for c, w in edges + [(end, None)]:
        v = 0 if w is None else (w >> bit) & 1
        if v != val:
            if val == 1:
                out.append((a, c))
            val, a = v, c
    return out


def on_interval(edges, bit: int, t0: int, t1: int, end: int) -> tuple[int, int] | None:
    """The one interval of bit ``bit`` on that starts in [t0, t1) (None if none; more than one: an error)."""
    iv = [(a, b) for a, b in intervals(edges, bit, end) if t0 <= a < t1]
    assert len(iv) <= 1, iv
    return iv[0] if iv else None


CASES = [(420, 24, 31, 4), (300, 0, 0, 0), (1536, 48, 48, 10), (600, 50, 10, 3), (254, 7, 60, 1)]


@pytest.mark.parametrize("period,dt,dtf,mp", CASES)
def test_window_is_the_gates_on_time(period, dt, dtf, mp):
    rng = random.Random(period + dt)
    n_checked, seen_full, stretched = 0, set(), 0
    for _ in range(40):
        theta = rng.randrange(1 << 16)
        m = rng.choice([0, 0x1000, 0x4000, 0x8000, 0x9000, 0x93CD, 0x93A0, 0x9380, rng.randrange(0x9400)])
        dpwm = rng.choice([fixed.DPWM_OFF, 1, 2, 3])
        u = Inputs(mode=fixed.MODE_POLAR, theta=theta, m=m, period=period, dt=dt, dtf=dtf, mp=mp, dpwm=dpwm)
        exp = CoreModel().run(u, [u] * 6, 6)
        n = 3                                   # periods 2, 3, 4 have the same values
        cmp = exp.cmp[n]
        assert exp.cmp[n - 1] == cmp == exp.cmp[n + 1] and exp.cmp_peak[n] == cmp
        p, t = exp.period[n], exp.valley[n]
        w = adc.window(cmp, p, exp.dt[n], exp.dtf[n], exp.mp[n], 0)
        for ph in range(3):
            c = cmp[ph]
            # the high side's pulse of period n (it starts after the pole rises at t + C) and the low side's
            # that follows it, around valley n + 1
            hi = on_interval(exp.gate_edges, ph, t, t + 2 * p, exp.end)
            lo = on_interval(exp.gate_edges, 3 + ph, t + p, t + 3 * p, exp.end)
            if c == p:
                assert hi is None and any(a <= t and b >= t + 2 * p
                                          for a, b in intervals(exp.gate_edges, 3 + ph, exp.end))
                assert w.lo[ph] == 2 * p and w.hi[ph] == 0
                seen_full.add("lo")
            elif c == 0:
                assert lo is None and any(a <= t and b >= t + 2 * p
                                          for a, b in intervals(exp.gate_edges, ph, exp.end))
                assert w.hi[ph] == 2 * p and w.lo[ph] == 0
                seen_full.add("hi")
            else:
                assert lo is not None and lo[1] - lo[0] == w.lo[ph], (ph, c, lo, w)
                assert hi is not None and hi[1] - hi[0] == w.hi[ph], (ph, c, hi, w)
                stretched += (w.lo[ph], w.hi[ph]) != (2 * c - dtf, 2 * (p - c) - dt)   # the minimum on-time
            n_checked += 1
    assert n_checked == 120
    if mp == 0 and dt == 0:
        return
    assert stretched, "no window stretched or shortened by the minimum on-time in the sample"
    assert seen_full == {"lo", "hi"}, "no clamped phase (C = 0 or P) in the sample"


def test_window_ok_and_recon():
    w = adc.window((100, 0, 420), 420, 24, 31, 4, 0)
    assert w.lo == (169, 0, 840) and w.hi == (616, 840, 0)
    assert w.ok == 0b101 and w.recon == 1
    assert adc.window((100, 100, 300), 420, 24, 31, 4, 169).ok == 0b111
    assert adc.window((100, 100, 300), 420, 24, 31, 4, 170).ok == 0b100
    assert adc.window((100, 100, 300), 420, 24, 31, 4, 170).recon == 0      # the first of equal ones
    assert adc.window(None, 420, 24, 31, 4, 0) == adc.Window((0, 0, 0), (0, 0, 0), 0, 0)
    # the minimum on-time H = max(dt, dtf, mp) = 60 stretches a short high pulse (and shortens the low side)
    assert adc.on_times(223, 254, 7, 60, 1) == (381, 60)
    # a low pulse shorter than dtf + H is no value the minimum-pulse rule gives
    with pytest.raises(AssertionError):
        adc.on_times(14, 420, 24, 24, 4)
    i = adc.reconstruct((1.0, 99.0, -0.25), w)
    assert i == (1.0, -0.75, -0.25)


@pytest.mark.parametrize("period", [1, 2, 3, 7, 20])
def test_point_rule_fires_once_per_period(period):
    for cnt in range(0, period + 3):
        for dn in (False, True):
            pt = adc.Point(True, dn, cnt)
            hits = [k for k in range(2 * period) if adc.fires(pt, *adc.carrier_at(k, period), period)]
            assert hits == [adc.point_clock(pt, period)], (cnt, dn, hits)
            c, up = adc.carrier_at(hits[0], period)
            assert c == min(cnt, period)
    assert adc.point_clock(adc.Point(False, False, 3), 7) is None
    assert not any(adc.fires(adc.Point(False, False, 3), *adc.carrier_at(k, 7), 7) for k in range(14))
