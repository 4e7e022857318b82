# SPDX-License-Identifier: Apache-2.0
"""spectrum.py: exact coefficients of known waveforms; ideal SVPWM fundamental = m."""
from __future__ import annotations

import math

import numpy as np
import pytest

from svpwm_model import fixed, spectrum
from svpwm_model.analysis import line_fundamental
from svpwm_model.core import CoreModel, Inputs

F_CLK = 48e6
P = 1536


def test_square_wave_coefficients():
    T = 1000.0
    c = spectrum.interval_coeffs(np.array([0.0]), np.array([T / 2]), 0.0, T, 99)
    j = np.arange(100)
    exp = np.where(j % 2 == 1, 2 / (math.pi * np.maximum(j, 1)), 0.0)
    exp[0] = 0.5
    assert np.allclose(np.abs(c), exp, atol=1e-12)
    # phase: 2 / (i pi j) -> -90 deg for odd j
    assert np.allclose(np.angle(c[1::2]), -math.pi / 2, atol=1e-12)


def test_pulse_train_reanchor_and_duty():
    # 7 pulses of 30 % duty in a window of 7 pulse periods: lines only at multiples of 7
    T, n = 7000.0, 7
    a = np.arange(n) * 1000.0 + 100.0
    b = a + 300.0
    c = spectrum.interval_coeffs(a, b, 0.0, T, 700, reanchor=16)
    k = np.arange(701)
    on = k % n == 0
    assert np.allclose(np.abs(c[~on]), 0, atol=1e-12)
    h = k[on][1:] // n
    assert np.allclose(np.abs(c[on][1:]), 2 * np.abs(np.sin(math.pi * h * 0.3)) / (math.pi * h), atol=1e-12)
    assert c[0].real == pytest.approx(0.3)


def test_sine_samples():
    N = 4096
    t = np.arange(N) / N
    x = 0.3 + 0.7 * np.cos(2 * math.pi * 3 * t + 0.4) + 0.01 * np.sin(2 * math.pi * 9 * t)
    c = spectrum.spectrum_of_samples(x, 3)
    assert abs(c[0]) == pytest.approx(0.3)
    assert abs(c[3]) == pytest.approx(0.7) and np.angle(c[3]) == pytest.approx(0.4)
    assert abs(c[9]) == pytest.approx(0.01)
    f = spectrum.figures(c, 3, 1.0, 1.0, 1000.0)
    assert f.thd == pytest.approx(0.01 / 0.7)
    assert f.wthd == pytest.approx(0.01 / 3 / 0.7)


@pytest.mark.parametrize("m", [0.1, 0.5, 0.9, 1.0])
@pytest.mark.parametrize("f_hz,n_fund", [(50.0, 2), (5.1, 1)])
def test_ideal_svpwm_fundamental_is_m(m, f_hz, n_fund):
    f1 = fixed.freq_word(f_hz) / (6 * (1 << fixed.PHASE_WIDTH))
    t0 = 2 * P + 1
    s = spectrum.ideal_spectra(f1, m, P, t0, n_fund, 2 * n_fund, F_CLK)
    # 50 Hz, 2 revolutions = 625.0 carrier periods: no leakage, fundamental = m within 1e-4.
    # 5.1 Hz, 1 revolution = 3063.7 carrier periods: the carrier groups leak ~1e-5 (abs) into the
    # fundamental bin of the rectangular window; the tolerance there is 1e-4 absolute on top.
    leak = spectrum.leakage(n_fund, n_fund / f1, 1 / (2 * P)) > 1e-2
    for ph in range(3):
        assert abs(s.line[ph, n_fund]) == pytest.approx(m, rel=1e-4, abs=2e-5 if leak else 0)
        assert abs(s.phase[ph, n_fund]) == pytest.approx(m / math.sqrt(3), rel=1e-4, abs=2e-5 if leak else 0)
        # the pole voltage carries the common-mode carrier line; at 5.1 Hz (one revolution = 3063.7
        # carrier periods) it leaks ~1e-4 into the fundamental bin (rectangular window, exact integral)
        tol = 1e-4 * m if spectrum.leakage(n_fund, n_fund / f1, 1 / (2 * P)) < 1e-2 else 2e-4
        assert abs(s.pole[ph, n_fund]) == pytest.approx(m / math.sqrt(3), abs=tol)


def test_rounded_ideal_and_model_line_fundamental():
    """The spectrum of the bit-exact model's edges gives the same fundamental as analysis.fourier."""
    u = Inputs(freq=fixed.freq_word(50.0), m=fixed.m_word(0.9), period=P, dt=0)
    f1 = u.freq / (6 * (1 << fixed.PHASE_WIDTH))
    n = int(math.ceil(2 / f1 / (2 * P))) + 3
    run = CoreModel().run(u, lambda k: u, n)
    t0 = run.valley[1] + 1
    s = spectrum.spectra_from_edges(run.pole_edges, t0, 2 / f1, 2, 4, F_CLK)
    ref = line_fundamental(run.pole_edges, u.freq, t0, revolutions=2)
    assert abs(s.line[0, 2]) == pytest.approx(ref, rel=1e-9)
    assert abs(s.line[0, 2]) == pytest.approx(0.9, rel=1e-3)
    r = spectrum.ideal_spectra(f1, 0.9, P, t0, 2, 4, F_CLK, rounding="nearest")
    assert abs(r.line[0, 2]) == pytest.approx(0.9, rel=1e-3)


def test_figures_low_order_band():
    T, f_clk, f_sw = 1000.0, 1000.0, 100.0    # bins at 1 Hz
    c = np.zeros(200, dtype=complex)
    c[1] = 1.0
    c[30] = 0.01      # 30 Hz < f_sw/2: low order
    c[70] = 0.1       # above f_sw/2
    f = spectrum.figures(c, 1, T, f_clk, f_sw)
    assert f.low_order_max_dbc == pytest.approx(-40.0)
    assert f.low_order_max_at_hz == pytest.approx(30.0)
    assert f.thd == pytest.approx(math.hypot(0.01, 0.1))


def test_low_order_floor():
    """The floor is the largest line when the band's rss is spread evenly over every line of it (48 lines:
    j = 2 ... 49 below f_sw/2 = 50 Hz, j = 1 the fundamental), and below the largest line otherwise."""
    T, f_clk, f_sw = 1000.0, 1000.0, 100.0
    c = np.zeros(200, dtype=complex)
    c[1] = 1.0
    c[2:50] = 0.001
    f = spectrum.figures(c, 1, T, f_clk, f_sw)
    floor = spectrum.low_order_floor_dbc(f.low_order_rss_dbc, 1, T, f_clk, f_sw)
    assert floor == pytest.approx(-60.0)
    assert f.low_order_max_dbc == pytest.approx(-60.0)
    c[2:50] = 0.0
    c[30] = 0.01
    f = spectrum.figures(c, 1, T, f_clk, f_sw)
    floor = spectrum.low_order_floor_dbc(f.low_order_rss_dbc, 1, T, f_clk, f_sw)
    assert floor == pytest.approx(-40.0 - 10 * math.log10(48))


def test_error_feedback_round():
    """Error-feedback rounding: integers within 1 of the value, the running error sum within +-1/2 (so the
    mean is exact), and it differs from nearest rounding (a checker that cannot tell them apart would pass)."""
    rng = np.random.default_rng(5)
    c = rng.uniform(0, 100, size=(500, 3))
    q = spectrum.error_feedback_round(c)
    assert np.all(q == np.round(q)) and np.all(np.abs(q - c) < 1.0)
    run = np.cumsum(q - c, axis=0)
    assert np.all(np.abs(run) <= 0.5 + 1e-9)
    assert np.any(q != np.floor(c + 0.5))
    assert np.abs(np.cumsum(np.floor(c + 0.5) - c, axis=0)).max() > 0.5


def test_error_feedback_trade_off():
    """The trade-off the README states for issue 6 at 50 Hz, m = 0.5, P = 1536: error-feedback rounding
    brings the line WTHD within 0.05 % of the exact ideal (nearest rounding: +0.098 %), but its largest
    line below f_sw/2 is more than 1 dB above the nearest-rounding bound."""
    f1 = fixed.freq_word(50.0) * fixed.freq_lsb_hz() / F_CLK
    T = 2 / f1
    t0 = 2 * P + 1
    jmax = int(3 * (F_CLK / (2 * P)) * T / F_CLK)
    fig = {}
    for r in (None, "nearest", "error_feedback"):
        sp = spectrum.ideal_spectra(f1, 0.5, P, t0, 2, jmax, F_CLK, rounding=r)
        fig[r] = spectrum.figures(sp.line[0], 2, T, F_CLK, F_CLK / (2 * P))
    w0 = fig[None].wthd
    assert abs(fig["error_feedback"].wthd / w0 - 1) < 5e-4
    assert fig["nearest"].wthd / w0 - 1 > 5e-4
    assert fig["error_feedback"].low_order_max_dbc - fig["nearest"].low_order_max_dbc > 1.0
