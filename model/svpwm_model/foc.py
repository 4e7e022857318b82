# SPDX-License-Identifier: Apache-2.0
"""Field-oriented current control around the core: ADC model, dq PI controller, angle and sign words, metrics.

Plain Python + numpy, used by the closed-loop RTL runs (tb/cocotb/demo/demo_runs.py, run_foc_point) the way a
controller in software or in another FPGA block would drive the core (README "Current loop"): once per carrier
period the three phase currents are sampled at the core's ADC trigger (``adc_trig_o`` at the valley), the PI
computes (v_d, v_q), and theta_i / v1_i = v_d / v2_i = v_q / isign_i are written before the core samples them
(P - L - 1 clocks after the trigger for the update at the next peak).

Conventions (README "Conventions"): theta_i is the electrical angle, 2^16 = 360 deg, 0 = phase a's axis,
positive a -> b -> c; DQ mode (mode_i = 4): v1 = v_d along theta_i, v2 = v_q 90 deg ahead, signed Q2.14 with
0x4000 = 1.0 = the inscribed circle, i.e. a phase fundamental peak of Udc / sqrt3; isign_i bit k = 1 when phase
k's current is negative (into the leg).  Space vectors are amplitude invariant (pmsm.py).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from . import fixed

SQRT3 = math.sqrt(3.0)
TWO_PI = 2 * math.pi


# ---- ADC -------------------------------------------------------------------------------------------------
@dataclass
class Adc12:
    """Three-channel 12-bit ADC behind low-side shunt amplifiers: code = round(mid + offset + (1 + gain_err)
    i / lsb + noise), clipped to 0 .. 4095; the controller converts with the nominal mid-scale and lsb (a real
    calibration would remove the offset; ``offset_lsb`` / ``gain_err`` model what is left).  Full scale
    +-``i_fs`` A (default +-30 A, twice the servo's rated 14.85 A peak: 14.6 mA per code)."""
    i_fs: float = 30.0
    bits: int = 12
    offset_lsb: tuple[float, float, float] = (0.0, 0.0, 0.0)
    gain_err: tuple[float, float, float] = (0.0, 0.0, 0.0)
    noise_lsb: float = 0.0          # rms, per sample
    seed: int = 1
    rng: np.random.Generator = field(init=False, repr=False)

    def __post_init__(self):
        self.rng = np.random.default_rng(self.seed)

    @property
    def lsb(self) -> float:
        return 2 * self.i_fs / (1 << self.bits)

    @property
    def mid(self) -> int:
        return 1 << (self.bits - 1)

    def convert(self, currents) -> tuple[int, int, int]:
        top = (1 << self.bits) - 1
        out = []
        for k, i in enumerate(currents):
            x = self.mid + self.offset_lsb[k] + (1 + self.gain_err[k]) * i / self.lsb
            if self.noise_lsb:
                x += self.rng.normal(0.0, self.noise_lsb)
            out.append(min(top, max(0, int(math.floor(x + 0.5)))))
        return tuple(out)

    def amps(self, codes) -> tuple[float, float, float]:
        return tuple((c - self.mid) * self.lsb for c in codes)


# ---- transforms and core words ---------------------------------------------------------------------------
def clarke(ia: float, ib: float) -> complex:
    """Amplitude-invariant Clarke from two phases (i_c = -i_a - i_b): i_alpha + j i_beta."""
    return complex(ia, (ia + 2 * ib) / SQRT3)


def park(i_ab: complex, theta: float) -> complex:
    """Stationary -> rotor frame: i_d + j i_q = i_ab e^{-j theta}."""
    return i_ab * complex(math.cos(theta), -math.sin(theta))


def theta_word(theta: float) -> int:
    """Electrical angle (rad) -> the core's 16-bit theta_i (2^16 = 360 deg, 0 = phase a)."""
    return int(math.floor(theta / TWO_PI * 65536 + 0.5)) & 0xFFFF


def v_word(v: float, udc: float) -> int:
    """A dq voltage (V, phase peak) -> signed Q2.14 (0x4000 = Udc / sqrt3), saturated to the 16-bit range."""
    w = int(math.floor(v / (udc / SQRT3) * fixed.V_ONE + 0.5))
    return max(-(1 << 15), min((1 << 15) - 1, w))


def v_of_word(w: int, udc: float) -> float:
    return w / fixed.V_ONE * udc / SQRT3


class SignDetector:
    """isign_i from measured phase currents with a hysteresis band (A): a phase's sign changes only when its
    current is beyond the band on the other side (band 0: the plain sign; exactly 0 counts as positive)."""

    def __init__(self, band: float = 0.0):
        self.band = band
        self.neg = [False, False, False]

    def update(self, currents) -> int:
        h = self.band
        for k, i in enumerate(currents):
            if h == 0:
                self.neg[k] = i < 0
            elif self.neg[k] and i > h:
                self.neg[k] = False
            elif not self.neg[k] and i < -h:
                self.neg[k] = True
        return sum(1 << k for k in range(3) if self.neg[k])


# ---- PI current controller -------------------------------------------------------------------------------
@dataclass
class PiGains:
    kp_d: float
    ki_d: float
    kp_q: float
    ki_q: float
    sigma: float           # the small time constant the gains were tuned for (s)


def technical_optimum(R: float, Ld: float, Lq: float, ts: float, delay_periods: float = 1.5) -> PiGains:
    """PI gains by the technical (modulus) optimum for the plant 1 / (R + s L) behind the loop's small delay
    sigma = ``delay_periods`` * Ts (Froehr and Orttenburger; Schroeder, "Elektrische Antriebe - Regelung von
    Antriebssystemen", sec. 3.1): the PI zero cancels the electrical time constant (T_i = L / R) and
    K_p = L / (2 sigma), i.e. the open loop 1 / (2 sigma s (1 + sigma s)); closed loop ~ 1 / (1 + 2 sigma s),
    step response: 4.3 % overshoot, rise time (10-90 %) ~ 3.4 sigma, bandwidth ~ 1 / (2 pi 2 sigma).
    sigma here: the sample-and-compute delay of one carrier period (ADC at the valley, the new voltage
    acts from the next peak, its pulses centred on the valley one period after the sample) plus half a
    period for the PWM's own hold: 1.5 Ts."""
    sigma = delay_periods * ts
    return PiGains(kp_d=Ld / (2 * sigma), ki_d=R / (2 * sigma), kp_q=Lq / (2 * sigma), ki_q=R / (2 * sigma),
                   sigma=sigma)


@dataclass
class DqPi:
    """Discrete PI per axis, run once per carrier period (Ts), output in volts (phase peak), limited to the
    inscribed circle |v| <= v_max (= Udc / sqrt3, the linear range of SVPWM; d has priority, q gets what is
    left). Anti-windup: the integrator of an axis holds while its output is limited and the error would
    drive it further (conditional integration). ``decouple``: adds the feed-forward of the steady state,
    R i_ref - w_e L_q i_q on d and R i_ref + w_e (L_d i_d + psi_m) on q (the cross-coupling and back-EMF from
    the measured currents and speed, the resistive drop of the reference): the integrators then only correct
    parameter errors and the dead time, and a step that saturates the voltage leaves no slow tail (without
    the R i_ref term the held integrator would close its gap with the plant's L / R = 2.4 ms)."""
    gains: PiGains
    ts: float
    v_max: float
    decouple: bool = True
    R: float = 0.0
    Ld: float = 0.0
    Lq: float = 0.0
    psi_m: float = 0.0
    sign: float = 1.0            # -1 breaks the loop on purpose (the tests' check that a broken loop fails)
    int_d: float = 0.0
    int_q: float = 0.0
    sat: bool = False

    def step(self, id_ref: float, iq_ref: float, i_d: float, i_q: float, w_e: float) -> tuple[float, float]:
        g = self.gains
        e_d, e_q = self.sign * (id_ref - i_d), self.sign * (iq_ref - i_q)
        ff_d = self.R * id_ref - w_e * self.Lq * i_q if self.decouple else 0.0
        ff_q = self.R * iq_ref + w_e * (self.Ld * i_d + self.psi_m) if self.decouple else 0.0
        vd_u = ff_d + g.kp_d * e_d + self.int_d + g.ki_d * self.ts * e_d
        vd = max(-self.v_max, min(self.v_max, vd_u))
        vq_lim = math.sqrt(max(self.v_max ** 2 - vd * vd, 0.0))
        vq_u = ff_q + g.kp_q * e_q + self.int_q + g.ki_q * self.ts * e_q
        vq = max(-vq_lim, min(vq_lim, vq_u))
        if vd == vd_u or (vd_u > vd) != (e_d > 0):
            self.int_d += g.ki_d * self.ts * e_d
        if vq == vq_u or (vq_u > vq) != (e_q > 0):
            self.int_q += g.ki_q * self.ts * e_q
        self.sat = vd != vd_u or vq != vq_u
        return vd, vq


# ---- metrics ---------------------------------------------------------------------------------------------
def step_response(t, x, t_step: float, x0: float, x1: float, t_end: float) -> dict:
    """Rise time (10-90 % of the step x0 -> x1, from the first sample at or after t_step, linear
    interpolation between samples), overshoot beyond x1 in % of |x1 - x0|, and the final value (mean of
    the last quarter of [t_step, t_end))."""
    t, x = np.asarray(t, float), np.asarray(x, float)
    sel = (t >= t_step) & (t < t_end)
    tt, xx = t[sel], x[sel]
    d = x1 - x0
    y = (xx - x0) / d                                   # 0 -> 1

    def cross(level):
        k = np.nonzero(y >= level)[0]
        if not len(k):
            return None
        k = k[0]
        if k == 0:
            return float(tt[0])
        return float(tt[k - 1] + (level - y[k - 1]) / (y[k] - y[k - 1]) * (tt[k] - tt[k - 1]))

    a, b = cross(0.1), cross(0.9)
    q = tt >= tt[0] + 0.75 * (tt[-1] - tt[0])
    return dict(rise_s=None if a is None or b is None else b - a, t10_s=a, t90_s=b,
                overshoot_pct=float(max(0.0, 100 * (np.max(y) - 1))), final=float(np.mean(xx[q])),
                final_err_pct=float(100 * (np.mean(xx[q]) - x1) / abs(d)))


def averaged_loop(mp, pi: DqPi, iq_ref, n_periods: int, ts: float, w_e: float, id_ref=None,
                  sub: int = 16) -> dict:
    """The current loop on an averaged inverter (no PWM ripple, no dead time, the angle advance exact): the
    sample at valley k sets the voltage that acts from the peak after it to the next peak (the core's peak
    update); the dq equations (pmsm.py) with that voltage, held speed, RK4 with ``sub`` steps per half period.
    ``iq_ref(k)`` / ``id_ref(k)``: the references at sample k.  For tuning and as the reference of the
    RTL runs' step response.  Returns the per-sample arrays k, i_d, i_q, v_d, v_q."""
    i_d = i_q = 0.0
    v_old = (0.0, w_e * mp.psi_m) if pi.decouple else (0.0, 0.0)
    R, Ld, Lq, psi = mp.R, mp.Ld, mp.Lq, mp.psi_m
    h = ts / 2 / sub
    log = {k: [] for k in ("i_d", "i_q", "v_d", "v_q")}

    def f(x, v):
        return ((v[0] - R * x[0] + w_e * Lq * x[1]) / Ld, (v[1] - R * x[1] - w_e * (Ld * x[0] + psi)) / Lq)

    for k in range(n_periods):
        vd, vq = pi.step(id_ref(k) if id_ref else 0.0, iq_ref(k), i_d, i_q, w_e)
        for key, val in (("i_d", i_d), ("i_q", i_q), ("v_d", vd), ("v_q", vq)):
            log[key].append(val)
        for v in (v_old, (vd, vq)):
            x = (i_d, i_q)
            for _ in range(sub):
                k1 = f(x, v)
                k2 = f((x[0] + h / 2 * k1[0], x[1] + h / 2 * k1[1]), v)
                k3 = f((x[0] + h / 2 * k2[0], x[1] + h / 2 * k2[1]), v)
                k4 = f((x[0] + h * k3[0], x[1] + h * k3[1]), v)
                x = (x[0] + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]),
                     x[1] + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))
            i_d, i_q = x
        v_old = (vd, vq)
    return {k: np.asarray(v) for k, v in log.items()} | {"k": np.arange(n_periods)}
