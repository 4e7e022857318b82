# SPDX-License-Identifier: Apache-2.0
"""motor.py: the 0.75 kW parameters against catalogue figures, the dq model against the equivalent circuit."""
from __future__ import annotations

import math

import numpy as np
import pytest

from svpwm_model import motor as M
from svpwm_model import spectrum

MP = M.MotorParams()
P = 1536
F_CLK = 48e6
V_RATED = 230 / math.sqrt(3)


def test_rated_point_equivalent_circuit():
    s = M.slip_for_torque(MP, 50.0, V_RATED, 750 / (2 * math.pi * 1404 / 60))
    ec = M.equivalent_circuit(MP, 50.0, V_RATED, s)
    assert 1395 <= ec["speed_rpm"] <= 1420
    assert ec["p_shaft"] == pytest.approx(750, rel=0.01)
    assert 2.9 <= ec["i_s_rms"] <= 3.5
    assert 0.72 <= ec["pf"] <= 0.80
    i0 = M.equivalent_circuit(MP, 50.0, V_RATED, 1e-9)["i_s_rms"]
    assert 0.5 <= i0 / ec["i_s_rms"] <= 0.65
    tb = max(M.equivalent_circuit(MP, 50.0, V_RATED, x)["torque"] for x in np.linspace(0.05, 0.6, 200))
    assert 2.0 <= tb / ec["torque"] <= 2.6


def _pwm_motor(f_hz, m, slip, revs, fixed_speed=True, t_load=0.0):
    """Motor on ideal (float-edge) SVPWM at f, m, starting in the equivalent-circuit steady state."""
    f1 = f_hz / F_CLK
    n_per = int(math.ceil(revs / f1 / (2 * P))) + 2
    iv = spectrum.ideal_intervals(f1, m, P, n_per)
    mot = M.InverterMotor(fixed_speed=fixed_speed, t_load=t_load, h_max=10e-6)
    # voltage vector at t: the fundamental lags the sampled angle by the regular-sampling delay (1 period)
    t_start = 2 * P + 1
    v = m * M.UDC / math.sqrt(3) * np.exp(1j * 2 * math.pi * f1 * (t_start - 2 * P - 1))
    ps, pr = M.steady_state_fluxes(MP, f_hz, v, slip)
    mot.set_state(ps, pr, (1 - slip) * 2 * math.pi * f_hz / MP.p)
    mot.t = t_start
    mot.word = 0
    mot.push([(t, w) for t, w in M.word_edges(iv) if t >= t_start])
    return mot, f1, t_start


@pytest.mark.parametrize("slip", [0.02, 0.064])
def test_dq_current_matches_equivalent_circuit(slip):
    """Fundamental stator current of the dq model on ideal SVPWM (speed held) vs the equivalent circuit."""
    f_hz, m = 50.0, 0.9
    mot, f1, t0 = _pwm_motor(f_hz, m, slip, revs=3)
    t_a = t0 + 1 / f1                                  # skip one revolution
    mot.advance_to(int(t_a))
    mot.trace = M.Trace()
    mot.advance_to(int(t_a + 2 / f1) + 2)
    t, i, _ = mot.trace.arrays()
    grid = t_a + np.arange(8192) / 8192 * (2 / f1)
    ia = np.interp(grid, t, i.real)
    c = spectrum.spectrum_of_samples(ia, 2)
    ec = M.equivalent_circuit(MP, f_hz, m * M.UDC / math.sqrt(6), slip)
    assert abs(c[2]) / math.sqrt(2) == pytest.approx(ec["i_s_rms"], rel=0.01)


def test_no_load_speed_is_synchronous():
    """Free shaft, no load: starting at synchronous speed in steady state, the speed stays there."""
    f_hz = 50.0
    mot, f1, t0 = _pwm_motor(f_hz, 0.9, 1e-6, revs=5, fixed_speed=False)
    mot.advance_to(int(t0 + 4 / f1))
    n_sync = 60 * f_hz / MP.p
    assert mot.speed_rpm() == pytest.approx(n_sync, rel=0.003)      # friction slip only
    assert mot.speed_rpm() < n_sync


def test_torque_balance_under_load():
    """With a load torque the speed settles at the equivalent-circuit slip for that torque."""
    f_hz, t_load = 50.0, 3.0
    s = M.slip_for_torque(MP, f_hz, 0.9 * M.UDC / math.sqrt(6), t_load + MP.Tc + MP.B * 150)
    mot, f1, t0 = _pwm_motor(f_hz, 0.9, s, revs=8, fixed_speed=False, t_load=t_load)
    mot.advance_to(int(t0 + 7 / f1))
    assert mot.speed_rpm() == pytest.approx((1 - s) * 1500, abs=3.0)


def test_energy_balance_fixed_speed():
    """Fixed speed, steady state: inverter energy over whole revolutions = copper losses + shaft work."""
    f_hz, m, slip = 50.0, 0.9, 0.05
    mot, f1, t0 = _pwm_motor(f_hz, m, slip, revs=3)
    mot.advance_to(int(t0 + 1 / f1))
    e0, ta = mot.energy_in, mot.t
    mot.advance_to(int(t0 + 3 / f1))
    p_in = (mot.energy_in - e0) / ((mot.t - ta) / F_CLK)
    ec = M.equivalent_circuit(MP, f_hz, m * M.UDC / math.sqrt(6), slip)
    p_ec = 3 * ec["i_s_rms"] ** 2 * MP.Rs + ec["torque"] * 2 * math.pi * f_hz / MP.p
    assert p_in == pytest.approx(p_ec, rel=0.02)        # PWM ripple adds a little copper loss


def test_vf_law_and_pi():
    vf = M.VfLaw()
    assert vf.m(0) == pytest.approx(0.06)
    assert vf.m(50) == pytest.approx(0.9)
    assert vf.m(-25) == pytest.approx(0.48)
    assert vf.m(100) == 1.0
    pi = M.PISpeed(kp=0.01, ki=1.0, f_max=10)
    for _ in range(100):
        f = pi.step(700, 0, 0.1)
    assert f == 10 and pi.integ == 10                  # clamped, no wind-up beyond f_max
    assert pi.step(0, 700, 0.0) == pytest.approx(3.0)


def test_speed_loop_model_reaches_reference():
    loop, mot = M.run_speed_loop_model(0.5)
    assert mot.speed_rpm() == pytest.approx(700, abs=40)
