# SPDX-License-Identifier: Apache-2.0
"""The overmodulation laws of the bit-exact model (fixed.hex_clamp / om_gain) against the floating-point map of
ideal.py (overmod_fundamental): the line fundamental of a revolution of compare values, the angle-keeping clamp
(om = 0) and the six-step law (om = 1), monotonic in m and within 1 % of the map up to six-step."""
from __future__ import annotations

import math

import numpy as np
import pytest

from svpwm_model import fixed, ideal

P = 1536
N = 3072                                   # samples per revolution (512 per sector)
MS = (0x7000, 0x8000, 0x8800, 0x9000, fixed.M_VERTEX, 0x9400, 0x9480, 0x9600, 0x9800, 0xA000, 0xC000, 0xFFFF)


def line_fundamental(m: int, om: int) -> float:
    """|fundamental| of v_ab = (d_a - d_b) Udc, d_x = (P - C_x) / P, over N equally spaced angles."""
    vab = np.empty(N)
    for k in range(N):
        t6 = 6 * k * (1 << 16) // N                          # 6 theta in 2^16 units: sector . a16
        _, c, _, _ = fixed.modulate(fixed.MODE_FREQ, t6 >> 16, t6 & 0xFFFF, P, m=m, om=om)
        vab[k] = (c[1] - c[0]) / P
    th = 2 * math.pi * np.arange(N) / N
    return float(abs(2 * np.mean(vab * np.exp(-1j * th))))


@pytest.mark.parametrize("om", (0, 1), ids=("clamp", "six-step"))
def test_overmod_map(om):
    got = [line_fundamental(m, om) for m in MS]
    want = [ideal.overmod_fundamental(m / fixed.M_ONE, bool(om)) for m in MS]
    for m, g, w in zip(MS, got, want):
        assert abs(g - w) <= 0.01 * w, f"m = 0x{m:04x}: fundamental {g:.5f} Udc, map {w:.5f}"
    assert all(b >= a - 1e-4 for a, b in zip(got, got[1:])), f"not monotonic in m: {got}"
    if om:
        assert abs(got[-1] - ideal.SIX_STEP) <= 2e-3 * ideal.SIX_STEP, f"m = 0xFFFF: {got[-1]:.5f}, not six-step"
    else:
        assert abs(got[-1] - ideal.overmod_fundamental(2.0)) <= 2e-3, "the clamp's limit (the hexagon)"


def test_overmod_gain_and_inverse():
    assert fixed.om_gain(fixed.M_VERTEX, True) == fixed.OM_G_ONE == fixed.om_gain(0xFFFF, False)
    assert fixed.om_gain(0xFFFF, True) == 256 + 2 * (0xFFFF - fixed.M_VERTEX) <= 0xFFFF
    assert fixed.om_gain(0xFFFF, True, fixed.MODE_AB) == fixed.OM_G_ONE          # AB / DQ: the clamp
    # g = 1: the clamp exactly; the law never leaves [0, 2^16]
    for t1, t2 in ((40000, 40000), (65535, 2), (30000, 50000), (65536, 65536)):
        assert fixed.hex_clamp(t1, t2, fixed.OM_G_ONE) == fixed.hex_clamp(t1, t2)
        a, b, sat = fixed.hex_clamp(t1, t2, 55652)
        assert sat and 0 <= a <= fixed.T_CAP and 0 <= b <= fixed.T_CAP
    for f in (0.5, 1.0, 1.03, 1.06, 1.09, 1.1):              # the linear command through the map
        assert abs(ideal.overmod_fundamental(ideal.overmod_m_for(f), True) - f) < 1e-6
    with pytest.raises(ValueError, match="outside"):
        ideal.overmod_m_for(1.2)
