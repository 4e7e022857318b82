# SPDX-License-Identifier: Apache-2.0
"""Current sampling (svpwm_core feature ``adc``, rtl/svpwm_adc.sv): ADC trigger points and the shunt-window
report, bit-exact with the RTL.

Carrier (rtl/svpwm_carrier.sv): a period of half period P is 2P clocks; clock k = 0 .. 2P-1 of it has the
count k while counting up (k < P, the valley k = 0 included) and 2P - k while counting down (the peak k = P
included). A trigger point (en, dn, cnt) fires once per period in the clock

    k = 0                 if cnt == 0 (the valley, either direction)
    k = P                 if cnt >= P (the peak, either direction; a count beyond P is clamped to it)
    k = cnt               if counting up (dn = 0), else k = 2P - cnt.

The points and the minimum window are sampled with the reference and take effect with the compare values
computed from it (the update), so the points of a period are those its compare values came with.

Shunt windows (the gates' on-times in a period whose neighbour has the same values; rtl/svpwm_compare.sv: a
pole is high for the clocks [C, 2P - C) of a period, so 2C clocks low around the valley and 2(P - C) high
around the peak; the gate that turns on waits the dead time, the one that turns off does not):

    lo = 2P if C == P else max(2C - dtf, 0)        low side, around the valley (dtf: falling dead time,
                                                   the wait before a low side)
    hi = 2P if C == 0 else max(2(P - C) - dt, 0)   high side, around the peak (dt: rising dead time)
    ok = lo >= max(win_min, 1)                     readable with a low-side shunt
    recon = the phase with the smallest lo (the first of equal ones): the one to reconstruct from the other
            two (i_a + i_b + i_c = 0)

All zero (recon 0) while the compare values are not valid (stopped, or tripped). test_adc.py checks these
formulas against the model's gate edges (core.run + deadtime).
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Point:
    """One ADC trigger point: on, on the down count, carrier count."""
    en: bool = False
    dn: bool = False
    cnt: int = 0


def point_clock(pt: Point, period: int) -> int | None:
    """Clock index k (0 .. 2P-1, 0 = the valley) of a period at which the point fires; None if it is off."""
    if not pt.en:
        return None
    if pt.cnt == 0:
        return 0
    if pt.cnt >= period:
        return period
    return 2 * period - pt.cnt if pt.dn else pt.cnt


def fires(pt: Point, count: int, up: bool, period: int) -> bool:
    """The RTL's rule, per clock (svpwm_adc gen_point): the carrier at (count, up) of a running period."""
    if not pt.en:
        return False
    return ((count == pt.cnt and up == (not pt.dn)) or (count == period and pt.cnt >= period)
            or (count == 0 and pt.cnt == 0))


def carrier_at(k: int, period: int) -> tuple[int, bool]:
    """(count, up) at clock k of a period."""
    return (k, True) if k < period else (2 * period - k, False)


@dataclass(frozen=True)
class Window:
    lo: tuple[int, int, int]
    hi: tuple[int, int, int]
    ok: int                  # bit x: phase x readable
    recon: int               # the phase to reconstruct


def window(cmp: tuple[int, int, int] | None, period: int, dt: int, dtf: int, win_min: int) -> Window:
    """The report for the active compare values ``cmp`` (None: not valid -> all zero)."""
    if cmp is None:
        return Window((0, 0, 0), (0, 0, 0), 0, 0)
    lo = tuple(2 * period if c == period else max(2 * c - dtf, 0) for c in cmp)
    hi = tuple(2 * period if c == 0 else max(2 * (period - c) - dt, 0) for c in cmp)
    ok = sum(1 << ph for ph in range(3) if lo[ph] >= max(win_min, 1))
    recon = min(range(3), key=lambda ph: (lo[ph], ph))
    return Window(lo, hi, ok, recon)


def reconstruct(i_meas: tuple[float, float, float], w: Window) -> tuple[float, float, float]:
    """Phase currents from a sample with low-side shunts: the phase ``w.recon`` is replaced by minus the sum
    of the other two. (With two phases unreadable, ``w.ok`` has fewer than two bits: no reconstruction can
    help; keep the previous sample or a prediction.)"""
    i = list(i_meas)
    r = w.recon
    i[r] = -sum(i[ph] for ph in range(3) if ph != r)
    return (i[0], i[1], i[2])
