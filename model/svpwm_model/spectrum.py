# SPDX-License-Identifier: Apache-2.0
"""Exact voltage spectra of switched waveforms from their edge times; ideal SVPWM references.

Signals are switching functions s(t) in {0, 1} (a pole is connected to the + rail while s = 1), given as
lists of high intervals [a_i, b_i) in clock cycles (floats allowed: the ideal modulator's edges are real
numbers).  Voltages in units of Udc:

* pole to DC-bus midpoint:  v_x0 = s_x - 1/2              (+-Udc/2)
* line to line:             v_ab = s_a - s_b
* phase to the motor's isolated neutral: v_an = s_a - (s_a + s_b + s_c)/3

Fourier coefficients over a window [t0, t0 + T) with T = N fundamental periods (N an integer):

    c_j = 2/T * integral_{t0}^{t0+T} v(t) exp(-i 2 pi j (t - t0) / T) dt,    j = 1, 2, ...

(so a cosine of amplitude A gives |c_j| = A; c_0 is the plain mean).  Because v is piecewise constant,
every high interval contributes exactly (e^{-i w a} - e^{-i w b}) / (i w): no sampling, no FFT.  Line j is
at frequency j/T = (j/N) f1: order h = j/N, the fundamental is j = N, harmonics of f1 are j = kN and the
other j are inter-harmonics (there are none for a signal periodic in T; a PWM whose carrier is not
synchronous with f1 is only quasi-periodic, and the carrier groups, whose lines are at l f_sw + k f1,
then spread into neighbouring bins: rectangular-window leakage, exact but visible; see ``leakage``).

Figures of merit from the coefficients (always stated with the highest order h_max they include):

* THD  = sqrt(sum_{j != N, 1 <= j <= N h_max} |c_j|^2) / |c_N|                     (all lines, j != N)
* WTHD = sqrt(sum_{j != N, 1 <= j <= N h_max} (|c_j| / h_j)^2) / |c_N|,  h_j = j/N  (weighted by 1/order,
  a measure of the current distortion of an inductive load; for N = 1 it is sqrt(sum_{k>=2} (V_k/k)^2)/V_1)
* low-order level: the largest |c_j| / |c_N| over 0 < j/T < f_sw/2, j != N, in dBc, and the rss of the
  same lines ("low-order rss", dBc).

The ideal references (``ideal_intervals``): the same regularly sampled, centre-aligned SVPWM as the core
(the angle sampled at the carrier peak of period n - 1 sets the compare values of period n; pole x high
during [t_n + C_x + 1, t_n + 2P - C_x + 1), t_n = 2 P n), with the float compare values of
``ideal.ideal_compare`` at the exact float angle and the commanded float m:
``rounding=None`` keeps the edges at their exact real times, ``rounding="nearest"`` rounds C to the
nearest clock (the best any one-clock-resolution modulator can do: the quantisation bound).
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

from .ideal import ideal_compare

TWO_PI = 2.0 * math.pi


# ---- edges -> intervals ------------------------------------------------------------------------------
def high_intervals(edges, bit: int, t0: float, t1: float, initial: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """High intervals of bit ``bit`` of a (cycle, word) edge stream, clipped to [t0, t1)."""
    starts, ends = [], []
    prev, since = (initial >> bit) & 1, -math.inf
    for c, w in edges:
        v = (w >> bit) & 1
        if v == prev:
            continue
        if v:
            since = c
        else:
            starts.append(since)
            ends.append(c)
        prev = v
    if prev:
        starts.append(since)
        ends.append(math.inf)
    a = np.clip(np.asarray(starts, dtype=np.float64), t0, t1)
    b = np.clip(np.asarray(ends, dtype=np.float64), t0, t1)
    keep = b > a
    return a[keep], b[keep]


def interval_coeffs(a: np.ndarray, b: np.ndarray, t0: float, T: float, jmax: int,
                    reanchor: int = 256) -> np.ndarray:
    """c_j, j = 0..jmax, of the switching function that is 1 on the intervals [a_i, b_i) inside [t0, t0+T).

    Vectorised over the intervals; successive orders by complex rotation (z^j, re-anchored with an exact
    exp every ``reanchor`` orders, so the phase error stays ~1e-13 rad)."""
    a = (np.asarray(a, dtype=np.float64) - t0) / T          # window fraction
    b = (np.asarray(b, dtype=np.float64) - t0) / T
    out = np.empty(jmax + 1, dtype=np.complex128)
    out[0] = np.sum(b - a)                                   # mean value
    if jmax == 0 or a.size == 0:
        out[1:] = 0
        return out
    za, zb = np.exp(-1j * TWO_PI * a), np.exp(-1j * TWO_PI * b)
    ca, cb = za.copy(), zb.copy()
    for j in range(1, jmax + 1):
        if j % reanchor == 0:
            ca, cb = np.exp(-1j * TWO_PI * j * a), np.exp(-1j * TWO_PI * j * b)
        # 2/T * (e^{-iwa} - e^{-iwb}) / (iw) with w = 2 pi j / T, times in window fractions
        out[j] = np.sum(ca - cb) / (1j * math.pi * j)
        ca *= za
        cb *= zb
    return out


@dataclass
class Spectra:
    """Coefficients (units of Udc) of one window: orders h = j / n_fund, f = j / T."""
    t0: float
    T: float                  # window, clock cycles
    n_fund: int               # fundamental periods in the window (fundamental at j = n_fund)
    f_clk: float
    pole: np.ndarray          # (3, J+1) pole-to-midpoint a, b, c
    line: np.ndarray          # (3, J+1) v_ab, v_bc, v_ca
    phase: np.ndarray         # (3, J+1) v_an, v_bn, v_cn

    @property
    def freqs(self) -> np.ndarray:
        return np.arange(self.pole.shape[1]) / self.T * self.f_clk

    @property
    def orders(self) -> np.ndarray:
        return np.arange(self.pole.shape[1]) / self.n_fund


def spectra_from_intervals(iv, t0: float, T: float, n_fund: int, jmax: int, f_clk: float) -> Spectra:
    """``iv``: per phase (starts, ends) high intervals. Returns pole, line and phase-to-neutral spectra."""
    s = np.stack([interval_coeffs(a, b, t0, T, jmax) for a, b in iv])
    pole = s.copy()
    pole[:, 0] -= 0.5                                        # midpoint reference: s - 1/2
    line = np.stack([s[0] - s[1], s[1] - s[2], s[2] - s[0]])
    phase = s - s.mean(axis=0, keepdims=True)
    return Spectra(t0, T, n_fund, f_clk, pole, line, phase)


def spectra_from_edges(edges, t0: float, T: float, n_fund: int, jmax: int, f_clk: float,
                       bit_offset: int = 0) -> Spectra:
    """Spectra of the pole words {c, b, a} (bits ``bit_offset`` + 0..2) of an edge stream."""
    iv = [high_intervals(edges, bit_offset + ph, t0, t0 + T) for ph in range(3)]
    return spectra_from_intervals(iv, t0, T, n_fund, jmax, f_clk)


# ---- figures of merit --------------------------------------------------------------------------------
@dataclass
class Figures:
    fundamental: float        # |c_N|, units of Udc
    phase_rad: float          # arg c_N
    thd: float
    wthd: float
    h_max: float              # highest order included in THD/WTHD
    low_order_max_dbc: float  # largest line below f_sw/2 (j != N, j > 0), dBc
    low_order_max_at_hz: float
    low_order_rss_dbc: float  # rss of the lines below f_sw/2, dBc

    def as_dict(self) -> dict:
        return asdict(self)


def _db(x: float) -> float:
    return 20 * math.log10(x) if x > 0 else -math.inf


def figures(c: np.ndarray, n_fund: int, T: float, f_clk: float, f_sw: float, h_max: float | None = None) -> Figures:
    """THD, WTHD and the low-order level of one coefficient array c_j (see the module docstring)."""
    jmax = c.shape[0] - 1 if h_max is None else min(c.shape[0] - 1, int(round(h_max * n_fund)))
    amp = np.abs(c[: jmax + 1])
    j = np.arange(jmax + 1)
    v1 = amp[n_fund]
    other = (j >= 1) & (j != n_fund)
    thd = math.sqrt(float(np.sum(amp[other] ** 2))) / v1
    wthd = math.sqrt(float(np.sum((amp[other] / (j[other] / n_fund)) ** 2))) / v1
    low = low_order_mask(j, n_fund, T, f_clk, f_sw)
    k = int(np.argmax(np.where(low, amp, -1.0)))
    return Figures(fundamental=float(v1), phase_rad=float(np.angle(c[n_fund])), thd=float(thd), wthd=float(wthd),
                   h_max=jmax / n_fund, low_order_max_dbc=_db(amp[k] / v1),
                   low_order_max_at_hz=float(k / T * f_clk),
                   low_order_rss_dbc=_db(math.sqrt(float(np.sum(amp[low] ** 2))) / v1))


def low_order_mask(j: np.ndarray, n_fund: int, T: float, f_clk: float, f_sw: float) -> np.ndarray:
    """The low-order lines of a window of T clocks: 0 < j, j != n_fund, below f_sw/2."""
    return (j >= 1) & (j != n_fund) & (j / T * f_clk < f_sw / 2)


def low_order_floor_dbc(rss_dbc: float, n_fund: int, T: float, f_clk: float, f_sw: float) -> float:
    """The smallest largest line that lines below f_sw/2 with a total (rss) of ``rss_dbc`` can have: the rss
    spread evenly over all of them. What only moves the error in frequency inside the band (an error feedback
    on per-carrier-period values: their spectrum has no frequency above f_sw/2) cannot go below it."""
    n = int(np.count_nonzero(low_order_mask(np.arange(int(math.ceil(f_sw * T / f_clk)) + 1), n_fund, T, f_clk,
                                            f_sw)))
    return rss_dbc - 10 * math.log10(n)


def leakage(n_fund: int, T: float, f_sw: float) -> float:
    """Distance (bins) of the carrier frequency from the nearest bin of the window: 0 = no leakage."""
    x = f_sw * T
    return abs(x - round(x))


# ---- ideal references --------------------------------------------------------------------------------
def error_feedback_round(c: np.ndarray) -> np.ndarray:
    """Round each column of c (periods x phases) to integers with first-order error feedback: the rounding
    error of a period is added to the next period's value before it is rounded (a sigma-delta on the compare
    values), so the error's running sum stays within +-1/2 and its spectrum moves to high frequencies."""
    out = np.empty_like(c)
    e = np.zeros(c.shape[1:])
    for k in range(c.shape[0]):
        v = c[k] + e
        out[k] = np.floor(v + 0.5)
        e = v - out[k]
    return out


def ideal_intervals(f1_per_cycle: float, m: float, period: int, n_periods: int, theta0: float = 0.0,
                    rounding: str | None = None) -> list[tuple[np.ndarray, np.ndarray]]:
    """High intervals of the ideal regularly sampled SVPWM for carrier periods n = 1 .. n_periods - 1.

    Same timeline as the core with constant inputs from cycle 0: valley t_n = 2 P n, the angle
    theta(t) = theta0 + 2 pi f1 t is sampled at the peak of period n - 1, t = (2n - 1) P, and sets the
    compare values of period n; pole x is high during [t_n + C_x + 1, t_n + 2P - C_x + 1).
    ``rounding``: None (exact real edge times), "nearest" (C rounded to the nearest clock: the bound of
    issue 6) or "error_feedback" (first-order noise shaping, error_feedback_round: an alternative the
    core does not use, reported by `make bench` for comparison).
    ``f1_per_cycle`` is signed (negative: reverse rotation)."""
    n = np.arange(1, n_periods, dtype=np.float64)
    theta = theta0 + TWO_PI * f1_per_cycle * (2 * n - 1) * period
    c = ideal_compare(theta, m, period)                      # (n, 3)
    if rounding == "nearest":
        c = np.floor(c + 0.5)
    elif rounding == "error_feedback":
        c = error_feedback_round(c)
    elif rounding is not None:
        raise ValueError(rounding)
    c = np.clip(c, 0.0, float(period))
    tn = (2 * period * n)[:, None]
    a, b = tn + c + 1, tn + 2 * period - c + 1
    out = []
    for ph in range(3):
        keep = b[:, ph] > a[:, ph]
        out.append((a[keep, ph], b[keep, ph]))
    return out


def clip_intervals(iv, t0: float, t1: float):
    out = []
    for a, b in iv:
        a2, b2 = np.clip(a, t0, t1), np.clip(b, t0, t1)
        keep = b2 > a2
        out.append((a2[keep], b2[keep]))
    return out


def ideal_spectra(f1_per_cycle: float, m: float, period: int, t0: float, n_fund: int, jmax: int, f_clk: float,
                  rounding: str | None = None) -> Spectra:
    """Spectra of the ideal SVPWM (exact or clock-rounded edges) over [t0, t0 + n_fund / |f1|)."""
    T = n_fund / abs(f1_per_cycle)
    n_periods = int(math.ceil((t0 + T) / (2 * period))) + 2
    iv = clip_intervals(ideal_intervals(f1_per_cycle, m, period, n_periods, rounding=rounding), t0, t0 + T)
    return spectra_from_intervals(iv, t0, T, n_fund, jmax, f_clk)


def spectrum_of_samples(x: np.ndarray, n_fund: int) -> np.ndarray:
    """c_j (amplitude-normalised, j = 0..len/2) of uniform samples covering exactly n_fund periods."""
    X = np.fft.rfft(x) / len(x)
    X[1:] *= 2
    return X


def current_spectrum(t, i, t0: float, T: float, n_fund: int, ngrid: int = 1 << 16) -> np.ndarray:
    """c_j of a current sampled at irregular times ``t`` (e.g. motor.Trace: every segment end), linearly
    interpolated onto ``ngrid`` points over [t0, t0 + T), T = n_fund fundamental periods."""
    grid = t0 + np.arange(ngrid) / ngrid * T
    return spectrum_of_samples(np.interp(grid, t, i), n_fund)


def current_thd(c: np.ndarray, n_fund: int, h_max: int = 200) -> float:
    """THD of a current spectrum (current_spectrum) up to order ``h_max`` (the report's "to 200th")."""
    amp = np.abs(c[: h_max * n_fund + 1])
    j = np.arange(amp.size)
    other = (j >= 1) & (j != n_fund)
    return math.sqrt(float(np.sum(amp[other] ** 2))) / amp[n_fund]
