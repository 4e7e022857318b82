# SPDX-License-Identifier: Apache-2.0
"""pmsm.py: the PMSM on ideal SVPWM against the dq phasor equations, torque, energy, dead-time diodes."""
from __future__ import annotations

import cmath
import math

import numpy as np
import pytest

from svpwm_model import pmsm as PM
from svpwm_model import spectrum

P = 1536
F_CLK = 48e6
SPM = PM.PmsmParams()
IPM = PM.PmsmParams(Ld=0.45e-3, Lq=0.75e-3)


def _pwm_pmsm(mp, f_e, i_d, i_q, revs, fixed_speed=True, t_load=0.0):
    """The motor on ideal (float-edge) SVPWM whose voltage is the steady state of (i_d, i_q) at f_e, started
    in that steady state. The voltage vector at cycle t is at 2 pi f1 (t - 2P - 1) (spectrum.ideal_intervals:
    sampled at the peak before the period, centred on the period's peak); the rotor lags it by arg(v_dq)."""
    w_e = 2 * math.pi * f_e
    v = complex(*PM.voltage_dq(mp, w_e, i_d, i_q))
    m = abs(v) / (mp.udc / math.sqrt(3))
    f1 = f_e / F_CLK
    n_per = int(math.ceil(revs / f1 / (2 * P))) + 2
    iv = spectrum.ideal_intervals(f1, m, P, n_per)
    mot = PM.InverterPmsm(mp, gates=False, fixed_speed=fixed_speed, t_load=t_load)
    t0 = 2 * P + 1
    th0 = 2 * math.pi * f1 * (t0 - 2 * P - 1) - cmath.phase(v)
    mot.set_state(i_d, i_q, th0, w_e / mp.p)
    mot.t = t0
    from svpwm_model.motor import word_edges
    mot.push([(t, w) for t, w in word_edges(iv) if t >= t0])
    return mot, f1, t0, m


def _dq_mean(mot, t_a, t_b):
    t, i, th, _ = mot.trace.arrays()
    sel = (t > t_a) & (t <= t_b)
    dq = i[sel] * np.exp(-1j * th[sel])
    w = np.diff(np.concatenate([[t_a], t[sel]]))          # each sample closes its segment
    return complex(np.sum(dq * w) / np.sum(w)), dq


@pytest.mark.parametrize("mp,i_d,i_q", [(SPM, 0.0, 10.0), (SPM, -4.0, -8.0), (IPM, -5.0, 12.0)])
def test_steady_state_matches_dq_phasor_equations(mp, i_d, i_q):
    """Held speed (1500 rpm, 100 Hz electrical), ideal SVPWM: the mean dq current over whole carrier periods
    equals the phasor equations' steady state within 1 % of rated current; the ripple is the PWM's."""
    f_e = 100.0
    mot, f1, t0, m = _pwm_pmsm(mp, f_e, i_d, i_q, revs=3)
    assert 0.2 < m < 0.8
    t_a = t0 + 1 / f1
    mot.advance_to(int(t0 + 3 / f1))
    mean, dq = _dq_mean(mot, t_a, t0 + 3 / f1)
    assert abs(mean - complex(i_d, i_q)) < 0.01 * mp.i_rated, (mean, i_d, i_q)
    assert 0.01 < np.std(dq.imag) < 0.1 * mp.i_rated          # there is PWM ripple, and it is small


def test_wrong_rotor_angle_gives_other_current():
    """The check above can fail: the same voltage with the rotor 10 deg off gives another current."""
    mot, f1, t0, _ = _pwm_pmsm(SPM, 100.0, 0.0, 10.0, revs=3)
    mot.th += math.radians(10)
    mot.advance_to(int(t0 + 3 / f1))
    mean, _ = _dq_mean(mot, t0 + 2 / f1, t0 + 3 / f1)
    assert abs(mean - 10j) > 0.05 * SPM.i_rated


def test_torque_and_power_balance_interior():
    """Interior magnets, held speed, steady state: the electrical power minus the copper loss is T_e w_m with
    T_e = 3/2 p (psi_m i_q + (L_d - L_q) i_d i_q) (the reluctance part is ~6 % here)."""
    mp, f_e, i_d, i_q = IPM, 100.0, -5.0, 12.0
    mot, f1, t0, _ = _pwm_pmsm(mp, f_e, i_d, i_q, revs=2)
    mot.advance_to(int(t0 + 1 / f1))
    e_in, e_cu, ta = mot.e_in, mot.e_cu, mot.t
    mot.advance_to(int(t0 + 2 / f1))
    tt = (mot.t - ta) / F_CLK
    p_mech = (mot.e_in - e_in - (mot.e_cu - e_cu)) / tt
    te = 1.5 * mp.p * (mp.psi_m * i_q + (mp.Ld - mp.Lq) * i_d * i_q)
    assert te == pytest.approx(mp.torque(i_d, i_q))
    assert abs(1.5 * mp.p * (mp.Ld - mp.Lq) * i_d * i_q) > 0.05 * te
    assert p_mech == pytest.approx(te * 2 * math.pi * f_e / mp.p, rel=0.01)


def test_energy_conservation_free_speed():
    """Free shaft with a load: inverter energy = copper + friction + load + the change of stored energy."""
    mot, f1, t0, _ = _pwm_pmsm(SPM, 100.0, 0.0, 10.0, revs=2, fixed_speed=False, t_load=0.5)
    w0 = mot.stored_energy()
    mot.advance_to(int(t0 + 2 / f1))
    lhs = mot.e_in
    rhs = mot.e_cu + mot.e_fric + mot.e_load + mot.stored_energy() - w0
    # a synchronous machine on a fixed-frequency voltage: the load angle swings, the speed with it
    assert abs(mot.speed_rpm() - 1500) > 1 and abs(mot.stored_energy() - w0) > 1e-3
    assert lhs > 0 and lhs == pytest.approx(rhs, rel=1e-4)


def test_motoring_and_generating_signs():
    """i_q > 0 at positive speed: motoring (energy in > 0, positive torque); i_q < 0: generating."""
    for i_q, sign in ((10.0, 1), (-10.0, -1)):
        mot, f1, t0, _ = _pwm_pmsm(SPM, 100.0, 0.0, i_q, revs=1)
        mot.advance_to(int(t0 + 1 / f1))
        assert sign * mot.torque() > 0
        assert sign * (mot.e_in - mot.e_cu) > 0


def test_reverse_rotation_sign():
    """A positive i_q accelerates a free rotor from rest in the positive (a -> b -> c) direction."""
    mot = PM.InverterPmsm(SPM, gates=False, fixed_speed=False)
    mot.set_state(0.0, 10.0, 0.0, 0.0)
    mot.advance_to(20)                                      # no edges: zero vector, current decays slowly
    assert mot.wm > 0 and mot.th > 0


@pytest.mark.parametrize("i0", [5.0, -5.0])
def test_dead_time_diodes_set_the_pole(i0):
    """All gates off (a dead time held for 0.5 ms), rotor at rest: the diodes put every pole against its
    current, the current decays to zero within about L |i| / Udc, energy flows back to the bus (e_in < 0)."""
    mot = PM.InverterPmsm(SPM, gates=True, fixed_speed=True)
    mot.set_state(i0, 0.0, 0.0, 0.0)                        # i_a = i0, i_b = i_c = -i0 / 2
    mot.advance_to(1)
    eff = mot.effective[0][1]
    assert eff == (0b110 if i0 > 0 else 0b001)              # a positive i_a: lower diode, s_a = 0
    for t in range(48, int(0.5e-3 * F_CLK), 48):           # the sign is taken per segment: 1 us segments,
        mot.advance_to(t)                                   # as a dead time in the loop
    assert abs(mot.current()) < 0.05 * abs(i0)
    assert mot.e_in < 0


def test_gates_drive_the_poles():
    """Gate words {lo, hi}: a high side on gives s = 1, a low side s = 0, whatever the current."""
    mot = PM.InverterPmsm(SPM, gates=True, fixed_speed=True)
    mot.set_state(5.0, 0.0, 0.0, 0.0)
    mot.push([(0, 0b110_001)])                              # a high, b and c low
    mot.advance_to(10)
    assert mot.effective == [(0, 0b001)]
    assert mot.i_d > 5.0                                    # +2/3 Udc along phase a drives i_a up
