# SPDX-License-Identifier: Apache-2.0
"""foc.py: the ADC, the core's angle and voltage words, the sign hysteresis, the PI and its anti-windup, and the
averaged current loop's step response with the gains the RTL runs use."""
from __future__ import annotations

import math

import pytest

from svpwm_model import fixed, foc
from svpwm_model import pmsm as PM

MP = PM.PmsmParams()
TS = 2 * 1536 / 48e6


def test_adc_quantises_offsets_and_clips():
    adc = foc.Adc12()
    assert adc.lsb == pytest.approx(60 / 4096)
    assert adc.convert((0.0, 1.0, -1.0)) == (2048, 2048 + 68, 2048 - 68)       # 1 A = 68.27 codes
    assert adc.convert((100.0, -100.0, 29.99)) == (4095, 0, 4095)
    ia, ib, _ = adc.amps(adc.convert((5.0, -2.5, -2.5)))
    assert abs(ia - 5.0) <= adc.lsb / 2 and abs(ib + 2.5) <= adc.lsb / 2
    off = foc.Adc12(offset_lsb=(10.0, 0.0, 0.0), gain_err=(0.0, 0.02, 0.0))
    ia, ib, _ = off.amps(off.convert((0.0, 10.0, 0.0)))
    assert ia == pytest.approx(10 * off.lsb) and ib == pytest.approx(10.2, abs=off.lsb)


def test_words_follow_the_core_conventions():
    assert foc.theta_word(0.0) == 0
    assert foc.theta_word(2 * math.pi / 3) == 0x5555            # phase b's axis (README "Conventions")
    assert foc.theta_word(-math.pi / 2) == 0xC000
    assert foc.theta_word(2 * math.pi) == 0
    assert foc.v_word(MP.udc / math.sqrt(3), MP.udc) == fixed.V_ONE         # 0x4000 = the inscribed circle
    assert foc.v_word(-MP.udc, MP.udc) == -round(math.sqrt(3) * fixed.V_ONE)
    assert foc.v_word(1e6, MP.udc) == 0x7FFF
    assert foc.v_of_word(foc.v_word(10.0, 48.0), 48.0) == pytest.approx(10.0, abs=48 / math.sqrt(3) / 2 ** 14)


def test_clarke_park_amplitude_invariant():
    th = 0.7
    i = 10 * complex(math.cos(th + 0.3), math.sin(th + 0.3))            # i_d + j i_q = 10 e^{j 0.3}
    ia, ib = i.real, (i * complex(math.cos(-2 * math.pi / 3), math.sin(-2 * math.pi / 3))).real
    dq = foc.park(foc.clarke(ia, ib), th)
    assert dq.real == pytest.approx(10 * math.cos(0.3)) and dq.imag == pytest.approx(10 * math.sin(0.3))


def test_sign_detector_hysteresis():
    sd = foc.SignDetector(0.5)
    assert sd.update((1.0, -1.0, 0.0)) == 0b010
    assert sd.update((-0.4, 0.4, 0.0)) == 0b010                 # inside the band: held
    assert sd.update((-0.6, 0.6, -0.6)) == 0b101                # beyond it: changed
    assert foc.SignDetector(0.0).update((-0.01, 0.0, 0.01)) == 0b001


def test_pi_anti_windup_and_limit():
    g = foc.technical_optimum(MP.R, MP.Ld, MP.Lq, TS)
    assert g.kp_q == pytest.approx(MP.Lq / (2 * 1.5 * TS)) and g.ki_q / g.kp_q == pytest.approx(MP.R / MP.Lq)
    v_max = MP.udc / math.sqrt(3)
    pi = foc.DqPi(g, TS, v_max, decouple=False)
    for _ in range(200):                                        # a current that cannot follow: saturated
        vd, vq = pi.step(0.0, 100.0, 0.0, 0.0, 0.0)
    assert math.hypot(vd, vq) <= v_max * (1 + 1e-12) and pi.sat
    assert pi.int_q < v_max                                     # held, not wound up
    vd, vq = pi.step(0.0, 0.0, 0.0, 1.0, 0.0)                   # the error reverses: the output follows at once
    assert vq < 0


@pytest.mark.parametrize("rpm,rise_max", [(0.0, 7), (1000.0, 8)])
def test_averaged_loop_step(rpm, rise_max):
    """The gains of the RTL runs on the averaged inverter: rated step, rise within rise_max periods, overshoot
    < 5 % (technical optimum: ~4 % without the voltage limit), no steady error, i_d held."""
    g = foc.technical_optimum(MP.R, MP.Ld, MP.Lq, TS)
    w_e = MP.p * rpm * 2 * math.pi / 60
    pi = foc.DqPi(g, TS, MP.udc / math.sqrt(3), R=MP.R, Ld=MP.Ld, Lq=MP.Lq, psi_m=MP.psi_m)
    r = foc.averaged_loop(MP, pi, lambda k: 0.0 if k < 10 else MP.i_rated, 80, TS, w_e)
    sr = foc.step_response(r["k"], r["i_q"], 10, 0.0, MP.i_rated, 80)
    assert sr["t90_s"] - 10 <= rise_max and sr["overshoot_pct"] < 5.0
    assert abs(sr["final_err_pct"]) < 1.0 and max(abs(r["i_d"])) < 0.03 * MP.i_rated


def test_averaged_loop_with_wrong_sign_fails():
    g = foc.technical_optimum(MP.R, MP.Ld, MP.Lq, TS)
    pi = foc.DqPi(g, TS, MP.udc / math.sqrt(3), R=MP.R, Ld=MP.Ld, Lq=MP.Lq, psi_m=MP.psi_m, sign=-1.0)
    r = foc.averaged_loop(MP, pi, lambda k: 0.0 if k < 10 else MP.i_rated, 80, TS, 0.0)
    sr = foc.step_response(r["k"], r["i_q"], 10, 0.0, MP.i_rated, 80)
    assert sr["t90_s"] is None or abs(sr["final_err_pct"]) > 10


def test_step_response_metrics():
    t = list(range(20))
    x = [0.0] * 5 + [0.0, 5.0, 10.0, 11.0, 10.0] + [10.0] * 10
    sr = foc.step_response(t, x, 5, 0.0, 10.0, 20)
    assert sr["t10_s"] == pytest.approx(5.2) and sr["t90_s"] == pytest.approx(6.8)
    assert sr["rise_s"] == pytest.approx(1.6) and sr["overshoot_pct"] == pytest.approx(10.0)
