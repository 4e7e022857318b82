# SPDX-License-Identifier: Apache-2.0
"""Induction motor on a two-level inverter, driven by switching edges; V/f law with boost and a PI speed loop.

Motor: the standard dq (space-vector) model in the stationary frame (Krause, "Analysis of Electric
Machinery", ch. 4/6 with the reference frame speed 0; Leonhard, "Control of Electrical Drives" ch. 10, the
AVR495's reference [2]), states stator and rotor flux linkage space vectors psi_s, psi_r (complex, V s) and
the mechanical speed w_m (rad/s):

    d psi_s / dt = v_s - R_s i_s
    d psi_r / dt = -R_r i_r + j p w_m psi_r                (p: pole pairs; rotor quantities referred to the stator)
    i_s = (L_r psi_s - L_m psi_r) / D,   i_r = (L_s psi_r - L_m psi_s) / D,   D = L_s L_r - L_m^2
    T_e = 3/2 p Im(conj(psi_s) i_s),     J d w_m / dt = T_e - B w_m - T_c tanh(w_m / 1 rad/s) - T_load

Space vectors are amplitude invariant, x = 2/3 (x_a + a x_b + a^2 x_c), a = e^{j 2 pi/3}: a balanced set of
phase quantities with peak X maps to |x| = X, and i_a = Re(i_s).  The inverter output is
v_s = 2/3 Udc (s_a + a s_b + a^2 s_c) for the switching functions s_x in {0, 1} (the star point floats, the
common mode has no effect: 1 + a + a^2 = 0).

Integration: the voltage is constant between switching edges, so the model is stepped segment by segment
(classical RK4 over each segment, split into sub-steps of at most ``h_max`` = 20 us; the electrical time
constants are >= ~4 ms and |lambda h| <= 0.03, far inside RK4's accuracy region -- checked in
test_motor.py against the steady state of the equivalent circuit).

Dead time (``gates=True``): edges are gate words {lo[2:0], hi[2:0]} (rtl/svpwm_core.sv); while both gates of a
leg are off the freewheeling diodes set the pole by the phase current's sign: i_x > 0 (out of the inverter)
-> lower diode -> s_x = 0; i_x < 0 -> s_x = 1 (sign taken at the start of each segment; a zero crossing
inside a 1 us dead-time segment is not resolved).  The resolved pole words are recorded (``effective``) so
the dead-time-distorted voltage can be analysed like any other edge stream.
"""
from __future__ import annotations

import cmath
import math
from collections import deque
from dataclasses import dataclass, field

import numpy as np

from . import fixed

A = cmath.exp(2j * math.pi / 3)
F_CLK = 48e6


@dataclass(frozen=True)
class MotorParams:
    """A 0.75 kW, 4-pole, 50 Hz cage induction motor, star-equivalent values at 230 V line-to-line.

    Source / reasoning (no single data sheet gives dq parameters, so they are derived): catalogue data of
    IEC 80-frame 0.75 kW 4-pole IE2 motors (230 V delta / 400 V star, 50 Hz) are typically: rated speed
    1395-1420 rpm, rated current 3.2-3.5 A at 230 V, cos phi 0.74-0.78, breakdown/rated torque 2.2-2.6,
    no-load current ~55-60 % of rated, rotor inertia 0.0018-0.0024 kg m^2.  The equivalent-circuit values
    below (star equivalent of the delta-connected machine at 230 V, i.e. the 400 V-star values times
    (230/400)^2) reproduce those figures: at 230 V / 50 Hz and slip 0.064 (1404 rpm) the equivalent circuit
    gives 0.75 kW shaft power (5.1 N m), 3.1 A, cos phi 0.76; no-load current 1.9 A; breakdown torque 11.4 N m
    at slip 0.32 (test_motor.py checks these).  R_s = 3.5 ohm is the usual order for this size (the 400 V
    star value ~10.5 ohm x 1/3), L_ls = L_lr (NEMA design A/B split of the blocked-rotor reactance).
    J = 0.005 kg m^2: the motor (0.0021) plus a coupled load/brake of twice its inertia, as on a test
    bench like AVR495's; B and T_c: bearing and fan friction, ~1.5 % of rated torque at rated speed.
    """
    Rs: float = 3.5            # ohm
    Rr: float = 3.1            # ohm, referred to the stator
    Lls: float = 0.015         # H
    Llr: float = 0.015         # H
    Lm: float = 0.21           # H
    p: int = 2                 # pole pairs (4 poles)
    J: float = 0.005           # kg m^2 (motor 0.0021 + load)
    B: float = 0.0003          # N m s / rad
    Tc: float = 0.03           # N m, Coulomb friction (tanh-smoothed)
    f_rated: float = 50.0      # Hz
    V_rated_line_rms: float = 230.0
    P_rated: float = 750.0     # W

    @property
    def Ls(self) -> float:
        return self.Lls + self.Lm

    @property
    def Lr(self) -> float:
        return self.Llr + self.Lm


# Udc: rectified 230 V mains would give 325 V; we take Udc = 360 V so that the demo's 50 Hz point (m = 0.9,
# line fundamental peak m * Udc = 324 V) is the rated 230 V rms line voltage: m = 0.9 is "full voltage" in
# the V/f law and leaves 10 % for the boost/regulation headroom.
UDC = 360.0


def equivalent_circuit(mp: MotorParams, f_hz: float, v_phase_rms: float, slip: float) -> dict:
    """Steady state from the per-phase T equivalent circuit (star equivalent)."""
    w = 2 * math.pi * f_hz
    zm = 1j * w * mp.Lm
    zr = mp.Rr / slip + 1j * w * mp.Llr
    z = mp.Rs + 1j * w * mp.Lls + zm * zr / (zm + zr)
    i_s = v_phase_rms / z
    i_r = i_s * zm / (zm + zr)
    p_ag = 3 * abs(i_r) ** 2 * mp.Rr / slip
    w_sync = w / mp.p
    torque = p_ag / w_sync
    return dict(i_s_rms=abs(i_s), pf=math.cos(cmath.phase(z)), torque=torque,
                p_shaft=torque * (1 - slip) * w_sync, speed_rpm=(1 - slip) * 60 * f_hz / mp.p,
                i_s_phasor=i_s, i_r_phasor=i_r)


def steady_state_fluxes(mp: MotorParams, f_hz: float, v_peak: complex, slip: float):
    """(psi_s, psi_r) space vectors at the instant the voltage vector is ``v_peak`` (complex, phase peak):
    sinusoidal steady state at the electrical speed (1 - slip) f."""
    w = 2 * math.pi * f_hz
    wr = (1 - slip) * w
    # v = Rs is + j w psi_s ; 0 = Rr ir + j (w - wr) psi_r ; psi_s = Ls is + Lm ir ; psi_r = Lm is + Lr ir
    M = np.array([[mp.Rs + 1j * w * mp.Ls, 1j * w * mp.Lm],
                  [1j * (w - wr) * mp.Lm, mp.Rr + 1j * (w - wr) * mp.Lr]])
    i_s, i_r = np.linalg.solve(M, np.array([v_peak, 0.0]))
    return complex(mp.Ls * i_s + mp.Lm * i_r), complex(mp.Lm * i_s + mp.Lr * i_r)


def slip_for_torque(mp: MotorParams, f_hz: float, v_phase_rms: float, torque: float) -> float:
    """Smallest slip (stable branch) at which the equivalent circuit gives ``torque``."""
    lo, hi = 1e-7, 0.3
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if equivalent_circuit(mp, f_hz, v_phase_rms, mid)["torque"] < torque:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def dead_time_loss(dt: int, period: int, udc: float = UDC) -> float:
    """Phase-voltage fundamental (V, peak) an uncompensated dead time removes, along the current vector.

    With the pole set by the diodes during the dead time, each pole's mean over a carrier period is short
    by sign(i_x) dt / (2 P) Udc; the three square waves sign(i_x) have the space-vector fundamental
    4/pi along the current, so the loss is 4/pi dt / (2 P) Udc (the classical first-order result; zero
    crossings inside a carrier period and the ripple are neglected)."""
    return 4 / math.pi * dt / (2 * period) * udc


def steady_state_with_loss(mp: MotorParams, f_hz: float, v_cmd: complex, slip: float,
                           v_loss: float = 0.0, iters: int = 60):
    """(psi_s, psi_r, v_eff): the sinusoidal steady state when the voltage vector is the command ``v_cmd``
    minus ``v_loss`` along the current (dead_time_loss), solved by fixed-point iteration.  With v_loss = 0
    it is steady_state_fluxes.  The start state of the dead-time runs (tb/cocotb/demo/demo_runs.py), so that
    their warm-up only has to remove the harmonic part of the start error."""
    D = mp.Ls * mp.Lr - mp.Lm * mp.Lm
    v = v_cmd
    for _ in range(iters if v_loss else 1):
        ps, pr = steady_state_fluxes(mp, f_hz, v, slip)
        i = (mp.Lr * ps - mp.Lm * pr) / D
        v_new = v_cmd - v_loss * i / abs(i) if v_loss and abs(i) > 0 else v_cmd
        if abs(v_new - v) < 1e-12 * max(1.0, abs(v_cmd)):
            break
        v = v_new
    ps, pr = steady_state_fluxes(mp, f_hz, v, slip)
    return ps, pr, v



def dtc_start(f_word: int, m: float, period: int, dt: int, dtc: bool, t_load: float, lead: int,
              f_clk: float = F_CLK) -> dict:
    """Operating point and start state of a dead-time run at frequency word ``f_word`` (make demo's
    compensation runs, tb/cocotb/demo/demo_runs.py, and scripts/isign_hysteresis.py): the speed of the
    equivalent-circuit steady state for ``t_load`` at the commanded voltage (the same slip in all three runs
    of a point), and the fluxes of the sinusoidal steady state at the first valley t_1, with the dead time's
    fundamental loss (dead_time_loss) when the compensation is off. The voltage vector at cycle c is at the
    accumulator angle of c - (P + lead + 1): a period's pulses are centred on its peak, P clocks after the
    valley its values were sampled ``lead`` clocks before."""
    mp = MotorParams()
    f1 = f_word / (6 * (1 << fixed.PHASE_WIDTH))              # cycles^-1, signed
    f_hz = f1 * f_clk
    slip = slip_for_torque(mp, abs(f_hz), m * UDC / math.sqrt(6), t_load)
    t1 = fixed.START_DELAY + 2 * period
    ang = 2 * math.pi * f1 * (t1 - fixed.START_DELAY - (period + lead + 1))
    v_cmd = m * UDC / math.sqrt(3) * complex(math.cos(ang), math.sin(ang))
    loss = 0.0 if dtc else dead_time_loss(dt, period)
    # the steady state for the positive sequence; a negative frequency is its mirror image
    ps, pr, v_eff = steady_state_with_loss(mp, abs(f_hz), v_cmd if f1 > 0 else v_cmd.conjugate(), slip, loss)
    if f1 < 0:
        ps, pr = ps.conjugate(), pr.conjugate()
    wm = math.copysign((1 - slip) * 2 * math.pi * abs(f_hz) / mp.p, f1)
    return dict(mp=mp, slip=slip, t_start=t1, ps=complex(ps), pr=complex(pr), wm=wm,
                speed_rpm=wm * 60 / (2 * math.pi), v_loss_v=loss, v_eff_over_cmd=abs(v_eff) / abs(v_cmd))

@dataclass
class Trace:
    """Samples at every segment end (and sub-step): time (cycles), stator current vector, speed (rad/s)."""
    t: list = field(default_factory=list)
    i: list = field(default_factory=list)
    wm: list = field(default_factory=list)

    def arrays(self):
        return np.asarray(self.t, dtype=np.float64), np.asarray(self.i, dtype=np.complex128), \
            np.asarray(self.wm, dtype=np.float64)


class InverterMotor:
    """The motor on an inverter fed by edge streams; advance it with ``push`` + ``advance_to``."""

    def __init__(self, mp: MotorParams = MotorParams(), udc: float = UDC, gates: bool = False,
                 f_clk: float = F_CLK, h_max: float = 20e-6, fixed_speed: bool = False, t_load: float = 0.0,
                 trace: bool = True, trace_every: int = 1):
        self.mp, self.udc, self.gates, self.f_clk = mp, udc, gates, f_clk
        self.h_max, self.fixed_speed, self.t_load = h_max, fixed_speed, t_load
        self.ps = 0j
        self.pr = 0j
        self.wm = 0.0
        self.t = 0                     # cycles
        self.word = 0                  # current input word (pole word or gate word)
        self.pending: deque = deque()
        self.effective: list[tuple[int, int]] = []      # resolved pole words (cycle, word)
        self._eff = -1
        self.trace = Trace() if trace else None
        self.trace_every = trace_every
        self._nseg = 0
        self.energy_in = 0.0           # J delivered by the inverter (integral of 3/2 Re(v conj(i)))
        self._vs = [2.0 / 3.0 * udc * ((w & 1) + A * ((w >> 1) & 1) + A * A * ((w >> 2) & 1)) for w in range(8)]

    # ---- inputs -----------------------------------------------------------------------------------
    def push(self, edges, mask: int | None = None) -> None:
        """Queue (cycle, word) changes (cycles >= the current time, sorted); with ``mask`` only those bits."""
        mk = mask if mask is not None else -1
        for c, w in edges:
            self.pending.append((c, mk, w))

    def set_state(self, ps: complex, pr: complex, wm: float) -> None:
        self.ps, self.pr, self.wm = ps, pr, wm

    def current(self) -> complex:
        mp = self.mp
        return (mp.Lr * self.ps - mp.Lm * self.pr) / (mp.Ls * mp.Lr - mp.Lm ** 2)

    def phase_currents(self) -> tuple[float, float, float]:
        i = self.current()
        return i.real, (i * A.conjugate()).real, (i * A).real

    def speed_rpm(self) -> float:
        return self.wm * 60 / (2 * math.pi)

    def _pole_word(self) -> int:
        w = self.word
        if not self.gates:
            return w & 7
        ia, ib, ic = self.phase_currents()
        out = 0
        for ph, i in enumerate((ia, ib, ic)):
            hi, lo = (w >> ph) & 1, (w >> (ph + 3)) & 1
            if hi:
                s = 1
            elif lo:
                s = 0
            else:                      # dead time: the diodes conduct
                s = 0 if i > 0 else 1
            out |= s << ph
        return out

    # ---- integration ------------------------------------------------------------------------------
    def advance_to(self, t_end: int) -> None:
        """Integrate up to cycle ``t_end`` applying the queued edges with cycles < t_end."""
        q = self.pending
        while self.t < t_end:
            while q and q[0][0] <= self.t:
                _, mk, w = q.popleft()
                self.word = (self.word & ~mk) | (w & mk)
            nxt = min(q[0][0], t_end) if q else t_end
            self._segment(nxt)

    def _segment(self, t_next: int) -> None:
        pw = self._pole_word()
        if pw != self._eff:
            self.effective.append((self.t, pw))
            self._eff = pw
        v = self._vs[pw]
        mp = self.mp
        Rs, Rr, Ls, Lr, Lm, p = mp.Rs, mp.Rr, mp.Ls, mp.Lr, mp.Lm, mp.p
        D = Ls * Lr - Lm * Lm
        kt = 1.5 * p
        J, B, Tc, TL = mp.J, mp.B, mp.Tc, self.t_load
        fixed = self.fixed_speed
        total = (t_next - self.t) / self.f_clk
        n = max(1, int(math.ceil(total / self.h_max)))
        h = total / n
        ps, pr, wm = self.ps, self.pr, self.wm
        e_in = 0.0

        def f(ps, pr, wm):
            i_s = (Lr * ps - Lm * pr) / D
            i_r = (Ls * pr - Lm * ps) / D
            dps = v - Rs * i_s
            dpr = -Rr * i_r + 1j * p * wm * pr
            if fixed:
                return dps, dpr, 0.0, i_s
            te = kt * (ps.real * i_s.imag - ps.imag * i_s.real)
            dwm = (te - B * wm - Tc * math.tanh(wm) - TL) / J
            return dps, dpr, dwm, i_s

        tr = self.trace
        for k in range(n):
            k1 = f(ps, pr, wm)
            k2 = f(ps + 0.5 * h * k1[0], pr + 0.5 * h * k1[1], wm + 0.5 * h * k1[2])
            k3 = f(ps + 0.5 * h * k2[0], pr + 0.5 * h * k2[1], wm + 0.5 * h * k2[2])
            k4 = f(ps + h * k3[0], pr + h * k3[1], wm + h * k3[2])
            ps = ps + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            pr = pr + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            wm = wm + h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])
            i_avg = (k1[3] + 2 * k2[3] + 2 * k3[3] + k4[3]) / 6
            e_in += 1.5 * (v * i_avg.conjugate()).real * h
        self.ps, self.pr, self.wm = ps, pr, wm
        self.energy_in += e_in
        self.t = t_next
        self._nseg += 1
        if tr is not None and self._nseg % self.trace_every == 0:
            tr.t.append(t_next)
            tr.i.append((Lr * ps - Lm * pr) / D)
            tr.wm.append(wm)


# ---- V/f law and speed loop ----------------------------------------------------------------------------
@dataclass
class VfLaw:
    """Constant V/f with boost (AVR495 sec. 6.2 / Fig. 6-1), in the form of the core's V/f hardware mode:

        m = min(m_max, boost + slope * |f|)

    Defaults: m = 0.9 at 50 Hz (Udc = 360 V: 230 V rms line, the rated point) and boost = 0.06:
    0.06 * 360 V / sqrt3 = 12.5 V phase peak ~ R_s * sqrt2 * 2.5 A, the stator resistance drop at about the
    magnetising current, so the flux stays near rated at low f (AVR495 sec. 6: near f = 0 "the stator
    voltage magnitude is equal to the boost voltage").  The three named values are what the core's V/f mode
    (mode_i = 1) takes, as register words from ``vf_words``; ``from_rated`` gives them from a rated point.
    ``m`` is the continuous law: the reference for the conversion test and the small-signal analysis."""
    boost: float = 0.06
    slope: float = (0.9 - 0.06) / 50.0       # per Hz
    m_max: float = 1.0

    @classmethod
    def from_rated(cls, boost: float = 0.06, m_rated: float = 0.9, f_rated: float = 50.0, m_max: float = 1.0):
        return cls(boost=boost, slope=(m_rated - boost) / f_rated, m_max=m_max)

    def m(self, f_hz: float) -> float:
        return min(self.m_max, self.boost + self.slope * abs(f_hz))


VF_UNIT_SHIFT = fixed.FREQ_WIDTH - 17     # the core's V/f law sees |freq| >> VF_UNIT_SHIFT (its top 16 bits)
VF_SLOPE_FRAC = 8                         # vf_slope_i is UQ8.8
WORD_MAX = 0xFFFF                         # vf_boost_i, vf_slope_i, vf_mmax_i: 16 bits each


def vf_unit_hz(f_clk: float = F_CLK) -> float:
    """One unit of the core's V/f law input: 2^(FREQ_WIDTH-17) frequency-word LSBs (59.6 mHz at 48 MHz)."""
    return fixed.freq_lsb_hz(f_clk) * (1 << VF_UNIT_SHIFT)


@dataclass(frozen=True)
class VfWords:
    """The V/f law as the core's register words (mode_i = 1, docs/reference.md "Input modes"):
    ``boost`` and ``m_max`` UQ1.15 (0x8000 = m 1.0), ``slope`` UQ8.8 m-LSBs per 2^(FREQ_WIDTH-17)
    frequency-word LSBs.  The core computes
    m = min(m_max, boost + ((|freq| >> (FREQ_WIDTH-17)) * slope + 128) >> 8) (fixed.vf_m) from the frequency
    word it samples."""
    boost: int
    slope: int
    m_max: int

    def m_word(self, freq_word: int) -> int:
        """m (UQ1.15) the core computes for ``freq_word`` (bit-exact: fixed.vf_m)."""
        return fixed.vf_m(freq_word, self.boost, self.slope, self.m_max)

    def inputs(self) -> dict:
        """Keyword arguments for svpwm_model.core.Inputs: VF mode with these words."""
        return dict(mode=fixed.MODE_VF, vf_boost=self.boost, vf_slope=self.slope, vf_mmax=self.m_max)


def vf_words(vf: VfLaw, f_clk: float = F_CLK) -> VfWords:
    """Convert the named V/f values (m, m per Hz) to the core's register words, once (rounded to nearest).

    Raises ValueError, naming the value and its range, if a value does not fit: boost or m_max outside
    UQ1.15 (0 .. 1.99997), a negative slope, a slope too large for UQ8.8 at this f_clk (at most
    255.996 m-LSBs per law unit: 0.131 per Hz at 48 MHz, 10x less at 480 MHz), or a non-zero slope that
    rounds to 0.  Defaults at 48 MHz: boost 0.06 -> 1966, slope 0.0168/Hz -> 32.8125 m-LSBs per unit ->
    8400 (exact), m_max 1.0 -> 32768."""
    def uq1_15(name: str, x: float) -> int:
        w = int(round(x * fixed.M_ONE))
        if not 0 <= w <= WORD_MAX:
            raise ValueError(f"V/f {name} = {x} does not fit the core's UQ1.15 register (0 .. "
                             f"{WORD_MAX / fixed.M_ONE:.5f}, word 0 .. 0xFFFF): word {w}")
        return w

    boost, m_max = uq1_15("boost", vf.boost), uq1_15("m_max", vf.m_max)
    unit = vf_unit_hz(f_clk)
    per_unit = vf.slope * fixed.M_ONE * unit            # m-LSBs per law unit
    slope = int(round(per_unit * (1 << VF_SLOPE_FRAC)))
    slope_max = WORD_MAX / (1 << VF_SLOPE_FRAC) / fixed.M_ONE / unit      # per Hz
    if vf.slope < 0:
        raise ValueError(f"V/f slope = {vf.slope:g} per Hz is negative: the core's UQ8.8 slope is unsigned")
    if slope > WORD_MAX:
        raise ValueError(f"V/f slope = {vf.slope:g} per Hz is too large for the core's UQ8.8 register at "
                         f"f_clk = {f_clk / 1e6:g} MHz: {per_unit:.3f} m-LSBs per law unit "
                         f"({unit * 1e3:.2f} mHz = 2^{VF_UNIT_SHIFT} frequency LSBs) needs word {slope} > 0xFFFF; "
                         f"largest slope at this clock {slope_max:.5f} per Hz")
    if slope == 0 and vf.slope > 0:
        raise ValueError(f"V/f slope = {vf.slope:g} per Hz rounds to 0 in the core's UQ8.8 register at "
                         f"f_clk = {f_clk / 1e6:g} MHz (resolution {slope_max / WORD_MAX:.3g} per Hz)")
    return VfWords(boost=boost, slope=slope, m_max=m_max)


@dataclass
class PISpeed:
    """AVR495's structure (Fig. 4-8): the PI output *is* the stator frequency, f = kp e + ki int e dt,
    e = n_ref - n (rpm), f in Hz, clamped to +-f_max with a clamped integrator.

    Kept for comparison only: the frequency is not tied to the rotor speed, so the machine runs as an
    open-loop V/f drive around the operating point, whose electromechanical mode at light load is poorly
    damped (``vf_modes``: 13.7 Hz, zeta = 0.08 at 700 rpm); the proportional path lowers the damping
    further (zeta = 0.03 with these gains) and with the inverter's dead time it becomes a sustained
    ~13 Hz speed oscillation (the demo before the slip-regulated loop)."""
    kp: float = 0.01           # Hz per rpm
    ki: float = 0.3            # Hz per (rpm s)
    f_max: float = 60.0
    integ: float = 0.0

    def step(self, n_ref: float, n: float, dt: float) -> float:
        e = n_ref - n
        self.integ = min(self.f_max, max(-self.f_max, self.integ + self.ki * e * dt))
        return min(self.f_max, max(-self.f_max, self.integ + self.kp * e))


@dataclass
class SlipPISpeed:
    """Slip-regulated speed control: f = p n / 60 + f_slip, f_slip = PI(n_ref - n) limited to +-f_slip_max.

    Structure: the textbook "speed control with slip regulation" of scalar (V/f) drives with a speed sensor
    (Bose, Modern Power Electronics and AC Drives, 2002, ch. 8, scalar control), not AVR495's Fig. 4-8:
    the stator frequency is the measured electrical rotor speed plus a slip command.
    Below breakdown slip the torque is ~ proportional to the slip frequency (T ~ 3/2 p psi_r^2 w_slip / R_r,
    2.1 N m per Hz here), so the PI sees a torque actuator on an inertia instead of AVR495's
    frequency-to-speed path (Fig. 4-8, ``PISpeed``) that leaves the poorly damped open-loop V/f mode in the
    loop.  Small-signal (``closed_loop_modes``), least damped pair: 10.5 Hz, zeta = 0.29 at +-700 rpm no
    load; >= 0.22 from 100 to 700 rpm, 0 to 2.5 N m (AVR495 structure: 14.6 Hz, zeta = 0.03).

    * The slip limit is a torque (and current) limit: 1.5 Hz ~ 3 N m ~ 0.6x rated torque (breakdown slip
      is ~16 Hz at 50 Hz); stator current <= 5.2 A peak (1.2x rated) in the +-700 rpm steps.  Larger limits
      (2-3 Hz) reverse faster but overshoot more: at low frequency the flux (boost, no-load overflux) and
      the torque lag the slip command by the rotor time constant, so the speed runs past the reference
      when the slip is taken back (averaged model: 3 Hz -> 40-70 rpm overshoot).
    * Gains: plant f_slip -> n ~ K / s, K = 2.1 N m/Hz * 60/(2 pi) / J ~ 4000 rpm/(Hz s) at 700 rpm:
      kp = 0.012 Hz/rpm gives ~50 rad/s crossover (rotor transient time constant sigma L_r / R_r = 9 ms:
      24 deg lag); the PI zero at ki / kp = 5 rad/s: the integrator takes friction and load, a faster zero
      integrates the approach error and overshoots (ki = 10 kp: 15-17 rpm), a slower one leaves a 1 N m
      load error outside +-2 % for > 0.8 s (ki = 2 kp).
    * Anti-windup: conditional integration (the integrator holds while the output is limited and the error
      would drive it further), integrator also bounded to +-f_slip_max; leaving the limit the P term takes
      over without a wound-up integral.
    * ``f_max``: the stator frequency limit (the V/f law reaches m_max above it)."""
    kp: float = 0.012          # Hz of slip per rpm
    ki: float = 0.06           # Hz of slip per (rpm s)
    f_slip_max: float = 1.5    # Hz
    f_max: float = 60.0        # Hz
    p: int = 2                 # pole pairs (the electrical rotor speed is p n / 60 Hz)
    integ: float = 0.0
    f_slip: float = 0.0        # last slip command (Hz), for the log

    def step(self, n_ref: float, n: float, dt: float) -> float:
        e = n_ref - n
        lim = self.f_slip_max
        u = self.integ + self.kp * e
        if abs(u) < lim or (u > 0) != (e > 0):          # not limited, or the error pulls it back: integrate
            self.integ = min(lim, max(-lim, self.integ + self.ki * e * dt))
            u = self.integ + self.kp * e
        self.f_slip = min(lim, max(-lim, u))
        return min(self.f_max, max(-self.f_max, self.p * n / 60.0 + self.f_slip))


def make_speed_ctrl(kind: str = "slip", **kw):
    """Speed controller by name: "slip" -> SlipPISpeed (default, the demo's loop), "avr495" -> PISpeed."""
    return {"slip": SlipPISpeed, "avr495": PISpeed}[kind](**kw)


def speed_profile(t: float) -> float:
    """Speed reference (rpm): +700 rpm from t = 0 (start at rest), -700 rpm from t = 0.8 s (AVR495 Fig. 6-1)."""
    return 700.0 if t < 0.8 else -700.0


STEP_TIMES = (0.0, 0.8)           # s, the reference steps of speed_profile


@dataclass
class LoopLog:
    """Per-update log of the speed loop (one entry per carrier period at which the inputs are set)."""
    t: list = field(default_factory=list)          # s, valley time
    n_ref: list = field(default_factory=list)      # rpm
    n: list = field(default_factory=list)          # rpm
    f: list = field(default_factory=list)          # Hz commanded (before word rounding)
    m: list = field(default_factory=list)          # the core's V/f m for freq_word (fixed.vf_m / 2^15)
    freq_word: list = field(default_factory=list)  # the word written to freq_i
    m_word: list = field(default_factory=list)     # the core's V/f m, UQ1.15 (computed by the core, not an input)
    i_peak: list = field(default_factory=list)     # |i_s| (A) at the valley
    torque: list = field(default_factory=list)     # N m at the valley

    def as_arrays(self) -> dict:
        return {k: np.asarray(v) for k, v in self.__dict__.items()}


class SpeedLoop:
    """Speed controller evaluated at carrier valleys, driving the core in V/f mode (mode_i = 1):
    ``update(t_cycles, motor)`` returns the frequency word, the only input that changes; the V/f law is
    computed by the core from it.  The law's three words (``self.vf_words``, from ``vf_words``) are converted
    once here and stay on the core's vf_* inputs (``core_inputs()``).

    Used identically by the RTL co-simulation (tb/cocotb/demo/demo_runs.py), the switched model loop
    (``run_speed_loop_model``) and the averaged-inverter loop (``run_speed_loop_averaged``).  ``ctrl``: any
    object with ``step(n_ref, n, dt) -> f_hz`` (default ``SlipPISpeed``; ``PISpeed`` is AVR495's structure).
    ``every``: the controller runs every ``every`` carrier periods and holds its output in between.  The
    speed is read once per update, at the valley (no filter, no aliasing: the loop rate, 15.6 kHz, is > 1000x
    the mechanical bandwidth).  The log's ``m`` / ``m_word`` are the core's V/f output for the word written
    (fixed.vf_m, bit-exact), not an input."""

    def __init__(self, vf: VfLaw | None = None, ctrl=None, profile=speed_profile,
                 f_clk: float = F_CLK, every: int = 1, pi=None):
        self.vf = vf or VfLaw()
        self.vf_words = vf_words(self.vf, f_clk)
        self.ctrl = ctrl or pi or SlipPISpeed()
        self.pi = self.ctrl                      # old name
        self.profile, self.f_clk, self.every = profile, f_clk, every
        self.log = LoopLog()
        self._k = 0
        self._t_last = None
        self._out = 0
        self.f_m = (0.0, 0.0)                    # (f of the word written, m the core computes from it)

    def core_inputs(self) -> dict:
        """The constant core inputs of the loop: VF mode and the law's words (svpwm_model.core.Inputs kwargs)."""
        return self.vf_words.inputs()

    def update(self, t_cycles: int, motor) -> int:
        t = t_cycles / self.f_clk
        if self._k % self.every == 0:
            n = motor.speed_rpm()
            n_ref = self.profile(t)
            dt = 0.0 if self._t_last is None else t - self._t_last
            f = self.ctrl.step(n_ref, n, dt)
            fw = fixed.freq_word(f, self.f_clk)
            mw = self.vf_words.m_word(fw)
            self.f_m = (fw * fixed.freq_lsb_hz(self.f_clk), mw / fixed.M_ONE)
            self._out = fw
            self._t_last = t
            lg = self.log
            i = motor.current()
            mp = motor.mp
            pr = motor.pr
            te = 1.5 * mp.p * mp.Lm / mp.Lr * (pr.real * i.imag - pr.imag * i.real)
            for k, v in (("t", t), ("n_ref", n_ref), ("n", n), ("f", f), ("m", mw / fixed.M_ONE), ("freq_word", fw),
                         ("m_word", mw), ("i_peak", abs(i)), ("torque", te)):
                getattr(lg, k).append(v)
        self._k += 1
        return self._out


# ---- averaged (ideal sinusoidal) inverter, small-signal analysis, step metrics ---------------------------
def _dq_sync(mp: MotorParams, v: float, ws: float, ps: complex, pr: complex, wm: float, t_load: float):
    """The dq model of InverterMotor in the frame of the voltage vector (rotating at ws, v real)."""
    D = mp.Ls * mp.Lr - mp.Lm * mp.Lm
    i_s = (mp.Lr * ps - mp.Lm * pr) / D
    i_r = (mp.Ls * pr - mp.Lm * ps) / D
    dps = v - mp.Rs * i_s - 1j * ws * ps
    dpr = -mp.Rr * i_r - 1j * (ws - mp.p * wm) * pr
    te = 1.5 * mp.p * (ps.real * i_s.imag - ps.imag * i_s.real)
    dwm = (te - mp.B * wm - mp.Tc * math.tanh(wm) - t_load) / mp.J
    return dps, dpr, dwm


class AveragedMotor:
    """The same machine on an ideal sinusoidal (averaged) inverter: v = m Udc / sqrt3 at the commanded f,
    no PWM ripple, no dead time.  Integrated (RK4) in the voltage vector's frame, where the states are slow
    (|lambda h| <= 0.03 at h = 64 us), so one step per carrier period suffices.  Same interface as
    InverterMotor for SpeedLoop (speed_rpm, current, mp, pr)."""

    def __init__(self, mp: MotorParams = MotorParams(), udc: float = UDC, t_load: float = 0.0):
        self.mp, self.udc, self.t_load = mp, udc, t_load
        self.ps, self.pr, self.wm = 0j, 0j, 0.0

    def speed_rpm(self) -> float:
        return self.wm * 60 / (2 * math.pi)

    def current(self) -> complex:
        mp = self.mp
        return (mp.Lr * self.ps - mp.Lm * self.pr) / (mp.Ls * mp.Lr - mp.Lm ** 2)

    def step(self, f_hz: float, m: float, h: float) -> None:
        mp, tl = self.mp, self.t_load
        v, ws = m * self.udc / math.sqrt(3), 2 * math.pi * f_hz
        ps, pr, wm = self.ps, self.pr, self.wm
        k1 = _dq_sync(mp, v, ws, ps, pr, wm, tl)
        k2 = _dq_sync(mp, v, ws, ps + 0.5 * h * k1[0], pr + 0.5 * h * k1[1], wm + 0.5 * h * k1[2], tl)
        k3 = _dq_sync(mp, v, ws, ps + 0.5 * h * k2[0], pr + 0.5 * h * k2[1], wm + 0.5 * h * k2[2], tl)
        k4 = _dq_sync(mp, v, ws, ps + h * k3[0], pr + h * k3[1], wm + h * k3[2], tl)
        self.ps = ps + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
        self.pr = pr + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
        self.wm = wm + h / 6 * (k1[2] + 2 * k2[2] + 2 * k3[2] + k4[2])


def run_speed_loop_averaged(t_end_s: float, loop: SpeedLoop | None = None, motor: AveragedMotor | None = None,
                            period: int = 1536, delay: int = 1):
    """The speed loop on the averaged inverter, updated every carrier period (2 * period clocks) like the
    RTL loop; the command computed at a valley acts ``delay`` periods later (the core samples its inputs at
    the next peak and uses them from the following period): the word's frequency and the m the core's V/f
    mode computes from it (``loop.f_m``).  2 s of motor time in ~1 s.  Returns (loop, motor)."""
    loop = loop or SpeedLoop()
    motor = motor or AveragedMotor()
    h = 2 * period / loop.f_clk
    q = deque([(0.0, 0.0)] * delay)
    for k in range(int(round(t_end_s / h))):
        loop.update(2 * period * k, motor)
        q.append(loop.f_m)
        f, m = q.popleft()
        motor.step(f, m, h)
    return loop, motor


def _jacobian(fun, x, eps=1e-7):
    J = np.zeros((len(x), len(x)))
    for k in range(len(x)):
        d = np.zeros(len(x))
        d[k] = eps * max(1.0, abs(x[k]))
        J[:, k] = (fun(x + d) - fun(x - d)) / (2 * d[k])
    return J


def _newton(fun, x, it=60):
    for _ in range(it):
        dx = np.linalg.solve(_jacobian(fun, x), -fun(x))
        x = x + dx
        if np.max(np.abs(dx)) < 1e-11:
            break
    return x


def closed_loop_modes(ctrl, vf: VfLaw | None = None, n_ref: float = 700.0, t_load: float = 0.0,
                      mp: MotorParams = MotorParams()) -> np.ndarray:
    """Eigenvalues (1/s) of the machine + V/f law + speed controller linearised at the steady state for
    ``n_ref`` (continuous time; the 64 us loop period and its delay are neglected: < 1 deg at 15 Hz).
    ``ctrl``: ``PISpeed`` (f = PI), ``SlipPISpeed`` (f = p n / 60 + PI, unsaturated), or None: open-loop
    V/f at the synchronous frequency of n_ref (the machine's own modes).  States: psi_s, psi_r (voltage
    frame, re/im), w_m, and the PI integrator."""
    vf = vf or VfLaw()
    rpm = 60 / (2 * math.pi)
    f_sync = mp.p * n_ref / 60

    def freq(z):
        n = z[4] * rpm
        if ctrl is None:
            return f_sync
        pi = z[5] + ctrl.kp * (n_ref - n)
        return pi + (mp.p * n / 60 if isinstance(ctrl, SlipPISpeed) else 0.0)

    def G(z):
        f = freq(z)
        dps, dpr, dwm = _dq_sync(mp, vf.m(f) * UDC / math.sqrt(3), 2 * math.pi * f,
                                 complex(z[0], z[1]), complex(z[2], z[3]), z[4], t_load)
        out = [dps.real, dps.imag, dpr.real, dpr.imag, dwm]
        if ctrl is not None:
            out.append(ctrl.ki * (n_ref - z[4] * rpm))
        return np.array(out)

    ps, pr = steady_state_fluxes(mp, f_sync, vf.m(f_sync) * UDC / math.sqrt(3), 1e-4)
    z0 = [ps.real, ps.imag, pr.real, pr.imag, n_ref / rpm]
    if ctrl is not None:
        z0.append(0.0 if isinstance(ctrl, SlipPISpeed) else f_sync)
    z = _newton(G, np.array(z0))
    return np.linalg.eigvals(_jacobian(G, z))


def least_damped(ev) -> tuple[float, float]:
    """(frequency Hz, damping ratio) of the least damped oscillatory eigenvalue pair."""
    osc = [e for e in ev if e.imag > 1e-6]
    e = min(osc, key=lambda e: -e.real / abs(e))
    return e.imag / (2 * math.pi), -e.real / abs(e)


def step_metrics(t, n, n_ref, steps=STEP_TIMES, band: float = 0.02, tail: float = 0.2) -> list[dict]:
    """Per reference step (from each step time to the next or the end): reference, settling time into
    +-band * |reference| (first time after which the speed stays inside), overshoot beyond the reference
    (rpm, in the direction of the step), peak-to-peak ripple and mean error over the last ``tail`` seconds,
    and the time to first reach the reference band."""
    t, n, n_ref = np.asarray(t), np.asarray(n), np.asarray(n_ref)
    out = []
    for k, t_a in enumerate(steps):
        t_b = steps[k + 1] if k + 1 < len(steps) else t[-1] + 1e-12
        sel = (t >= t_a) & (t < t_b)
        tt, nn = t[sel], n[sel]
        target = float(n_ref[sel][-1])
        start = float(n[np.searchsorted(t, t_a)])
        tol = band * abs(target)
        inside = np.abs(nn - target) <= tol
        out_idx = np.where(~inside)[0]
        if not len(out_idx):
            settle = 0.0
        elif out_idx[-1] + 1 < len(tt):
            settle = float(tt[out_idx[-1] + 1] - t_a)
        else:
            settle = None
        reach = float(tt[np.argmax(inside)] - t_a) if inside.any() else None
        sgn = 1.0 if target >= start else -1.0
        last = tt >= tt[-1] - tail
        out.append(dict(step_at_s=float(t_a), n_ref_rpm=target, band_rpm=tol,
                        settle_s=settle, reach_s=reach,
                        overshoot_rpm=float(max(0.0, np.max(sgn * (nn - target)))),
                        ripple_pp_rpm=float(np.ptp(nn[last])), mean_error_rpm=float(np.mean(nn[last]) - target),
                        speed_at_end_rpm=float(nn[-1])))
    return out


def run_speed_loop_model(t_end_s: float, period: int = 1536, loop: SpeedLoop | None = None,
                         motor: InverterMotor | None = None, progress: bool = False):
    """The closed loop against a replica of the core's timeline and bit-exact compare values in V/f mode
    (fixed.modulate with the loop's V/f words; poles, ideal inverter, no dead time): for tuning, tests and
    as a fallback.  Returns (loop, motor)."""
    loop = loop or SpeedLoop()
    motor = motor or InverterMotor(gates=False)
    vw = loop.vf_words
    full = 6 << fixed.PHASE_WIDTH
    n_periods = int(round(t_end_s * F_CLK / (2 * period)))
    theta, f_cur, cmp_cur, t = 0, 0, None, 0
    it = range(n_periods)
    if progress:
        from tqdm import tqdm
        it = tqdm(it, desc="speed loop (model)", unit="period", mininterval=1.0)
    for n in it:
        if cmp_cur is not None:
            ev = []
            for ph, c in enumerate(cmp_cur):
                if c < period:
                    ev += [(t + c + 1, 1 << ph, 1 << ph), (t + 2 * period - c + 1, 1 << ph, 0)]
            ev.sort(key=lambda e: e[0])
            motor.pending.extend(ev)
        motor.advance_to(t)
        fw = loop.update(t, motor)
        theta = (theta + f_cur * period) % full
        sector, angle = theta >> fixed.PHASE_WIDTH, theta & ((1 << fixed.PHASE_WIDTH) - 1)
        cmp_cur_next = fixed.modulate(fixed.MODE_VF, sector, angle >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS),
                                      period, freq=fw, vf_boost=vw.boost, vf_slope=vw.slope, vf_mmax=vw.m_max)[1]
        f_cur = fw
        theta = (theta + f_cur * period) % full
        # edges of period n were queued above from cmp_cur; the next period uses cmp_cur_next
        t += 2 * period
        motor.advance_to(t - 2 * period + 1)     # keep the queue short
        cmp_cur = cmp_cur_next
    motor.advance_to(t)
    return loop, motor


def word_edges(intervals) -> list[tuple[float, int]]:
    """(time, pole word) changes from per-phase high intervals [(starts, ends)] x 3."""
    ev = []
    for ph, (a, b) in enumerate(intervals):
        ev += [(float(x), ph, 1) for x in a] + [(float(x), ph, 0) for x in b]
    ev.sort(key=lambda e: (e[0], e[2]))          # at equal times: fall before rise
    out, w = [], 0
    for t, ph, v in ev:
        w = (w & ~(1 << ph)) | (v << ph)
        if out and out[-1][0] == t:
            out[-1] = (t, w)
        else:
            out.append((t, w))
    return out
