# SPDX-License-Identifier: Apache-2.0
"""Current sampling (svpwm_core feature ``adc``, rtl/svpwm_adc.sv): ADC trigger points and the shunt-window
report, bit-exact with the RTL.

Carrier (rtl/svpwm_carrier.sv): a period of half period P is 2P clocks; clock k = 0 .. 2P-1 of it has the
count k while counting up (k < P, the valley k = 0 included) and 2P - k while counting down (the peak k = P
included). A trigger point (en, dn, cnt) fires once per period, its pulse (adc_pt_o, a register) in the clock
after the one

    k = 0                 if cnt == 0 (the valley, either direction)
    k = P                 if cnt >= P (the peak, either direction; a count beyond P is clamped to it)
    k = cnt               if counting up (dn = 0), else k = 2P - cnt.

The points and the minimum window are sampled with the reference and take effect with the compare values
computed from it (the update), so the points of a period are those its compare values came with.

Shunt windows: the gates' on-times in the steady state of a period whose neighbours have the same values
(rtl/svpwm_compare.sv: a pole is high for the clocks [C, 2P - C) of a period, so Dh = 2(P - C) clocks high
around the peak and Dl = 2C low around the valley; rtl/deadtime.sv, deadtime.py: the gate that turns on
waits its edge's dead time after the other turned off -- dt before a high side, dtf before a low side --
and a gate, once on, stays on at least H = max(dt, dtf, mp, 1) clocks):

    C == P: lo = 2P, hi = 0          C == 0: lo = 0, hi = 2P
    else, with the pole rising at 0 and falling at Dh:
      h1 = max(Dh, dt + H)           the high side: on at dt, off at the pole's fall or after H
      hi = h1 - dt                   around the peak
      lo = 2P - h1 - dtf             around the valley: on at h1 + dtf, off at the next rise
    ok = lo >= max(win_min, 1)       readable with a low-side shunt
    recon = the phase with the smallest lo (the first of equal ones): the one to reconstruct from the other
            two (i_a + i_b + i_c = 0)

Without the minimum on-time (h1 = Dh) these are Dh - dt and Dl - dtf. The low side is never held on past
the pole's rise: the minimum-pulse rule (fixed.snap_min_pulse) keeps every C in (0, P) >= thr = max(dt, dtf)
+ mp, so Dl = 2C >= dtf + H; the high pulse only has P - C >= ceil(thr / 2), so Dh - dt may fall short of H.
(In general the low side would turn off r = max(0, dtf + H - Dl) late and the next high pulse start r later;
no compare value the calculator gives reaches that, and on_times asserts it.) test_adc.py checks them against the model's gate
edges (core.run + deadtime.py).

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
    """Clock index k (0 .. 2P-1, 0 = the valley) of a period at which the carrier is at the point (its pulse
    comes in clock k + 1); None if it is off."""
    if not pt.en:
        return None
    if pt.cnt == 0:
        return 0
    if pt.cnt >= period:
        return period
    return 2 * period - pt.cnt if pt.dn else pt.cnt


def fires(pt: Point, count: int, up: bool, period: int) -> bool:
    """The RTL's rule, per clock (svpwm_adc gen_point, pt_d): the carrier at (count, up) of a running period
    is at the point (the pulse follows in the next clock)."""
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


def on_times(c: int, period: int, dt: int, dtf: int, mp: int) -> tuple[int, int]:
    """(lo, hi): the low side's window around the valley and the high side's around the peak."""
    if c == period:
        return 2 * period, 0
    if c == 0:
        return 0, 2 * period
    h = max(dt, dtf, mp, 1)
    dh, dl = 2 * (period - c), 2 * c
    assert dl >= dtf + h, f"C = {c}: a low pole pulse shorter than dtf + H ({dtf} + {h}): not a snapped value"
    h1 = max(dh, dt + h)
    return 2 * period - h1 - dtf, h1 - dt


def window(cmp: tuple[int, int, int] | None, period: int, dt: int, dtf: int, mp: int, win_min: int) -> Window:
    """The report for the active compare values ``cmp`` (None: not valid -> all zero), the dead times and
    minimum pulse in force."""
    if cmp is None:
        return Window((0, 0, 0), (0, 0, 0), 0, 0)
    t = [on_times(c, period, dt, dtf, mp) for c in cmp]
    lo = (t[0][0], t[1][0], t[2][0])
    hi = (t[0][1], t[1][1], t[2][1])
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
