# SPDX-License-Identifier: Apache-2.0
"""The volt-second carry of the minimum-pulse rule (fixed.snap_carry, CoreModel with vsc): bounded, and the
average of the applied compare values follows the command where the rule alone drops or widens pulses."""
from __future__ import annotations

import pytest

from svpwm_model import fixed
from svpwm_model.core import CoreModel, Inputs


@pytest.mark.parametrize("thr", (1, 7, 30, 255))
def test_snap_carry_average(thr):
    P = max(2 * thr, 64)
    for c in list(range(-3, thr + 2)) + list(range(P - thr, P + 3)):
        e, applied = 0, []
        for _ in range(200):
            s, e2 = fixed.snap_carry(c + e, P, thr)
            assert s == fixed.snap_min_pulse(c + e, P, thr) and abs(e2) <= (thr + 1) // 2
            assert s in (0, P) or thr <= s <= P - (thr + 1) // 2
            applied.append(s)
            e = e2
        if 0 <= c <= P:                                     # the average equals the command to 1/200 of thr
            assert abs(sum(applied) - 200 * c) <= (thr + 1) // 2, (c, sum(applied) / 200)
        else:                                               # beyond a rail: the rail, the carry at its limit
            assert applied == [0] * 200 or applied == [P] * 200
            assert abs(e) == (thr + 1) // 2


def test_core_model_carry_follows_the_command():
    """m = 1 at 900 Hz, thr 30: per phase the applied compare values of 300 updates add up to the unsnapped ones
    within one carry with vsc, and drift by tens of counts without."""
    P = 400
    u = Inputs(freq=fixed.freq_word(900.0), m=fixed.m_word(1.0), period=P, dt=24, mp=6)
    drift = {}
    for vsc in (0, 1):
        v = Inputs(**{**u.__dict__, "vsc": vsc})
        r = CoreModel().run(v, [v] * 300, 300)
        ref = CoreModel().run(Inputs(**{**u.__dict__, "dt": 0, "mp": 0}), [Inputs(**{**u.__dict__, "dt": 0, "mp": 0})] * 300, 300)
        drift[vsc] = [sum(a.cmp[ph] for a in r.updates) - sum(b.cmp[ph] for b in ref.updates) for ph in range(3)]
    assert all(abs(d) <= 16 for d in drift[1]), drift
    assert max(abs(d) for d in drift[0]) > 40, drift
