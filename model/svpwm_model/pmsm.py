# SPDX-License-Identifier: Apache-2.0
"""Permanent-magnet synchronous motor (surface or interior) on a two-level inverter, driven by switching edges.

The machine in the rotor (d, q) frame (Krause, "Analysis of Electric Machinery", ch. 7; Pillay and Krishnan,
IEEE Trans. Ind. Appl. 25(2), 1989), amplitude-invariant space vectors as in motor.py:

    L_d di_d/dt = v_d - R i_d + w_e L_q i_q
    L_q di_q/dt = v_q - R i_q - w_e (L_d i_d + psi_m)
    T_e = 3/2 p (psi_m i_q + (L_d - L_q) i_d i_q)
    J dw_m/dt = T_e - B w_m - T_load,    d theta_e/dt = w_e = p w_m

theta_e is the d axis (the magnet's north pole) from phase a's axis, positive a -> b -> c; v_d + j v_q =
v_s e^{-j theta_e}, v_s = 2/3 Udc (s_a + a s_b + a^2 s_c) (the star point floats), i_s = (i_d + j i_q) e^{j theta_e},
i_a = Re(i_s).  The core's conventions (README "Conventions") are the same: theta_i = 0 is phase a's axis,
v1 = v_d along theta_i, v2 = v_q 90 deg ahead.

Integration as motor.InverterMotor: the inverter voltage is constant between switching edges, so the model is
stepped segment by segment (classical RK4 over each segment, sub-steps of at most ``h_max``; the electrical
time constant L/R is 2.4 ms and w_e h <= 0.03 at 3500 rpm and h = 5 us, well inside RK4's accuracy region --
test_pmsm.py checks the steady state against the dq phasor equations).  The states are i_d, i_q, theta_e and
w_m; the stationary voltage of a segment turns in the rotor frame, which RK4 integrates with theta_e as a state.

Dead time (``gates=True``): edges are gate words {lo[2:0], hi[2:0]} (rtl/svpwm_core.sv); while both gates of
a leg are off the freewheeling diodes set the pole by the phase current's sign, i_x > 0 -> s_x = 0,
i_x < 0 -> s_x = 1 (sign at the start of each segment; a zero crossing inside a 1 us dead-time segment is not
resolved, and a leg whose current is exactly 0 is taken as s_x = 1 -- the model has no open-phase state:
start it at the first update, when the gates start switching).  The resolved pole words are kept
(``effective``).  ``fixed_speed``: w_m held (a dynamometer); otherwise the mechanics above.

Parameters (``PmsmParams``): a 400 W, 48 V, 3000 rpm, 8-pole (4 pole pairs) servo motor of the common 60 mm
flange class.  Catalogue figures of such motors (e.g. the 60-frame 400 W / 48 V low-voltage AC servos of
Leadshine's ACM and Teknic's CPM families): rated torque 1.27 N m, rated current 10-11 A rms, torque constant
0.12 N m/A rms, line resistance 0.4-0.6 ohm, line inductance 1.0-1.4 mH, rotor inertia 0.6e-4 kg m^2 (these
are typical figures of the class, not one data sheet).  Per phase (star): R = 0.25 ohm, L_d = L_q = 0.6 mH
(surface magnets); psi_m from the torque constant: 1.27 N m at 10.5 A rms = 14.85 A peak, T = 3/2 p psi_m i_q
-> psi_m = 14.25 mWb (back-EMF 17.9 V phase peak at 3000 rpm, 31 V line peak: it fits a 48 V bus, the
rated point needs m = 0.83 of the inscribed circle).  J = 2e-4 kg m^2: the rotor and a coupled load of
about twice its inertia; B = 1e-4 N m s/rad (0.03 N m of drag at 3000 rpm, ~2.5 % of rated torque).
An interior-magnet variant: ``PmsmParams(Ld=0.45e-3, Lq=0.75e-3)`` (saliency 1.7).
"""
from __future__ import annotations

import cmath
import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

A = cmath.exp(2j * math.pi / 3)
F_CLK = 48e6


@dataclass(frozen=True)
class PmsmParams:
    """A 400 W, 48 V, 3000 rpm, 4-pole-pair servo (module docstring: where the values come from)."""
    R: float = 0.25            # ohm, per phase (star)
    Ld: float = 0.6e-3         # H
    Lq: float = 0.6e-3         # H
    psi_m: float = 14.25e-3    # V s (Wb), magnet flux linkage, phase peak
    p: int = 4                 # pole pairs
    J: float = 2e-4            # kg m^2 (rotor 0.6e-4 + coupled load)
    B: float = 1e-4            # N m s / rad
    udc: float = 48.0          # V, DC bus
    i_rated: float = 14.85     # A peak (10.5 A rms): 1.27 N m
    n_rated_rpm: float = 3000.0

    @property
    def kt(self) -> float:
        """Torque per ampere of i_q (peak), surface part: 3/2 p psi_m."""
        return 1.5 * self.p * self.psi_m

    def torque(self, i_d: float, i_q: float) -> float:
        return 1.5 * self.p * (self.psi_m * i_q + (self.Ld - self.Lq) * i_d * i_q)


def steady_state_dq(mp: PmsmParams, w_e: float, v_d: float, v_q: float) -> tuple[float, float]:
    """(i_d, i_q) of the sinusoidal steady state at electrical speed ``w_e`` for the voltage (v_d, v_q):
    v_d = R i_d - w_e L_q i_q, v_q = R i_q + w_e (L_d i_d + psi_m)."""
    M = np.array([[mp.R, -w_e * mp.Lq], [w_e * mp.Ld, mp.R]])
    i_d, i_q = np.linalg.solve(M, np.array([v_d, v_q - w_e * mp.psi_m]))
    return float(i_d), float(i_q)


def voltage_dq(mp: PmsmParams, w_e: float, i_d: float, i_q: float) -> tuple[float, float]:
    """(v_d, v_q) the steady state (i_d, i_q) at ``w_e`` needs."""
    return mp.R * i_d - w_e * mp.Lq * i_q, mp.R * i_q + w_e * (mp.Ld * i_d + mp.psi_m)


@dataclass
class Trace:
    """Samples at every segment end: time (cycles), stator current vector (stationary), theta_e, w_m."""
    t: list = field(default_factory=list)
    i: list = field(default_factory=list)
    th: list = field(default_factory=list)
    wm: list = field(default_factory=list)

    def arrays(self):
        return (np.asarray(self.t, dtype=np.float64), np.asarray(self.i, dtype=np.complex128),
                np.asarray(self.th, dtype=np.float64), np.asarray(self.wm, dtype=np.float64))


class InverterPmsm:
    """The PMSM on an inverter fed by edge streams; ``push`` + ``advance_to`` as motor.InverterMotor."""

    def __init__(self, mp: PmsmParams = PmsmParams(), gates: bool = True, f_clk: float = F_CLK,
                 h_max: float = 5e-6, fixed_speed: bool = True, t_load: float = 0.0, trace: bool = True):
        self.mp, self.gates, self.f_clk, self.h_max = mp, gates, f_clk, h_max
        self.fixed_speed, self.t_load = fixed_speed, t_load
        self.i_d = self.i_q = 0.0
        self.th = 0.0                  # electrical angle (rad, unwrapped)
        self.wm = 0.0                  # mechanical speed (rad/s)
        self.t = 0                     # cycles
        self.word = 0
        self.pending: deque = deque()
        self.effective: list[tuple[int, int]] = []
        self._eff = -1
        self.trace = Trace() if trace else None
        # energy bookkeeping (J): delivered by the inverter, copper loss, friction, load, (kinetic and magnetic
        # energy follow from the state)
        self.e_in = self.e_cu = self.e_fric = self.e_load = 0.0
        self._vs = [2.0 / 3.0 * mp.udc * ((w & 1) + A * ((w >> 1) & 1) + A * A * ((w >> 2) & 1)) for w in range(8)]

    # ---- state ------------------------------------------------------------------------------------
    def set_state(self, i_d: float, i_q: float, th: float, wm: float) -> None:
        self.i_d, self.i_q, self.th, self.wm = i_d, i_q, th, wm

    def current(self) -> complex:
        """Stator current space vector (stationary frame, A peak)."""
        return complex(self.i_d, self.i_q) * cmath.exp(1j * self.th)

    def phase_currents(self) -> tuple[float, float, float]:
        i = self.current()
        return i.real, (i * A.conjugate()).real, (i * A).real

    def theta_e(self) -> float:
        """Electrical angle in [0, 2 pi)."""
        return self.th % (2 * math.pi)

    def w_e(self) -> float:
        return self.mp.p * self.wm

    def speed_rpm(self) -> float:
        return self.wm * 60 / (2 * math.pi)

    def torque(self) -> float:
        return self.mp.torque(self.i_d, self.i_q)

    def stored_energy(self) -> float:
        """Kinetic plus magnetic energy (J): 1/2 J w^2 + 3/4 (L_d i_d^2 + L_q i_q^2) (amplitude-invariant
        vectors: the three phases store 3/2 of the dq figure; the magnet's own energy is constant)."""
        mp = self.mp
        return 0.5 * mp.J * self.wm ** 2 + 0.75 * (mp.Ld * self.i_d ** 2 + mp.Lq * self.i_q ** 2)

    # ---- inputs -----------------------------------------------------------------------------------
    def push(self, edges) -> None:
        """Queue (cycle, word) changes (cycles >= the current time, sorted)."""
        self.pending.extend(edges)

    def _pole_word(self) -> int:
        w = self.word
        if not self.gates:
            return w & 7
        cur = self.phase_currents()
        out = 0
        for ph in range(3):
            hi, lo = (w >> ph) & 1, (w >> (ph + 3)) & 1
            s = 1 if hi else 0 if lo else (0 if cur[ph] > 0 else 1)
            out |= s << ph
        return out

    # ---- integration ------------------------------------------------------------------------------
    def advance_to(self, t_end: int) -> None:
        """Integrate up to cycle ``t_end`` applying the queued edges with cycles < t_end."""
        q = self.pending
        while self.t < t_end:
            while q and q[0][0] <= self.t:
                self.word = q.popleft()[1]
            nxt = min(q[0][0], t_end) if q else t_end
            self._segment(nxt)

    def _segment(self, t_next: int) -> None:
        pw = self._pole_word()
        if pw != self._eff:
            self.effective.append((self.t, pw))
            self._eff = pw
        v = self._vs[pw]
        vr, vi = v.real, v.imag
        mp = self.mp
        R, Ld, Lq, psi, p = mp.R, mp.Ld, mp.Lq, mp.psi_m, mp.p
        J, B, TL = mp.J, mp.B, self.t_load
        kt = 1.5 * p
        fixed = self.fixed_speed
        total = (t_next - self.t) / self.f_clk
        n = max(1, int(math.ceil(total / self.h_max)))
        h = total / n
        i_d, i_q, th, wm = self.i_d, self.i_q, self.th, self.wm
        cos, sin = math.cos, math.sin

        def f(i_d, i_q, th, wm):
            c, s = cos(th), sin(th)
            v_d = vr * c + vi * s                 # v e^{-j th}
            v_q = vi * c - vr * s
            we = p * wm
            did = (v_d - R * i_d + we * Lq * i_q) / Ld
            diq = (v_q - R * i_q - we * (Ld * i_d + psi)) / Lq
            te = kt * (psi * i_q + (Ld - Lq) * i_d * i_q)
            dwm = 0.0 if fixed else (te - B * wm - TL) / J
            # powers: inverter in, copper loss, friction, load
            return did, diq, we, dwm, 1.5 * (v_d * i_d + v_q * i_q), 1.5 * R * (i_d * i_d + i_q * i_q), B * wm * wm, \
                TL * wm

        e = [0.0, 0.0, 0.0, 0.0]
        for _ in range(n):
            k1 = f(i_d, i_q, th, wm)
            k2 = f(i_d + 0.5 * h * k1[0], i_q + 0.5 * h * k1[1], th + 0.5 * h * k1[2], wm + 0.5 * h * k1[3])
            k3 = f(i_d + 0.5 * h * k2[0], i_q + 0.5 * h * k2[1], th + 0.5 * h * k2[2], wm + 0.5 * h * k2[3])
            k4 = f(i_d + h * k3[0], i_q + h * k3[1], th + h * k3[2], wm + h * k3[3])
            i_d += h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            i_q += h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            th += h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
            wm += h / 6 * (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3])
            for j in range(4):
                e[j] += h / 6 * (k1[4 + j] + 2 * k2[4 + j] + 2 * k3[4 + j] + k4[4 + j])
        self.i_d, self.i_q, self.th, self.wm = i_d, i_q, th, wm
        self.e_in += e[0]
        self.e_cu += e[1]
        self.e_fric += e[2]
        self.e_load += e[3]
        self.t = t_next
        tr = self.trace
        if tr is not None:
            tr.t.append(t_next)
            tr.i.append(complex(i_d, i_q) * cmath.exp(1j * th))
            tr.th.append(th)
            tr.wm.append(wm)
