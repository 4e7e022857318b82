# SPDX-License-Identifier: Apache-2.0
"""Clock-exact model of rtl/svpwm_core.sv: per-update compare values and every pole and gate edge.

Time base: cycle 0 is the first clock with en_i = 1; the core's run register follows en_i a clock later,
so the valley of carrier period 0 is cycle fixed.START_DELAY (1). A value "at cycle c" is a register's value
during clock c; an edge "at cycle c" means the new value holds from c.

Timeline (see docs/reference.md "Timing and latency"):
* period n starts at valley t_n with half period P_n: t_{n+1} = t_n + 2 P_n; its peak is t_n + P_n.
* update opportunities: the peak of every period (upd PEAK or BOTH) and the valley t_{n+1} (VALLEY or
  BOTH); with the prescaler only every (presc + 1)-th opportunity updates (counter from 0 at the start).
* an update at point T samples the reference in the clock S - 1, S = T - SAMPLE_LEAD: the angle used is
  the accumulator at cycle S, the new frequency word steps it from cycle S on; the compare values are
  active from T (a valley update is computed for P_{n+1} and its dead time, a peak update for P_n).
* before every valley (at S - 1 of the valley sample) period, dead times, minimum pulse, upd and presc are
  sampled: P_{n+1}, dt_{n+1}, dtf_{n+1}, mp_{n+1} are active from t_{n+1}; a changed (P, dt, dtf, mp)
  forces an update at that valley; upd / presc apply to the opportunities after t_{n+1}. The calculator's
  minimum-pulse threshold and the period floor use max(dt, dtf) + mp.
* ``inputs(n)`` are on the ports during the down half of period n (valley sample), ``peak_inputs(n)``
  (default: inputs(n)) during its up half (peak sample). Period 0 runs with the idle inputs.
* pole x is high during [t_n + C_up + 1, t_n + P_n + 1) if C_up < P_n and [t_n + P_n + 1,
  t_n + 2 P_n - C_dn + 1) if C_dn < P_n, C_up / C_dn the values active at the valley / the peak.
* gates: rtl/deadtime.sv per leg (model: deadtime.py), target OFF until the clock after the first update;
  dt_{n+1}, dtf_{n+1} and mp_{n+1} act on the gates from t_{n+1} + 1 (the legs read the core's registers a
  clock ahead). dt is the rising dead time (before a high side turns on), dtf the falling one (before a
  low side); Inputs.dtf = None (dtf_en_i = 0) means dtf = dt. The compact core ignores dtf.
"""
from __future__ import annotations

import bisect
from dataclasses import dataclass, field, replace
from typing import Callable, Sequence

from . import adc, calc_prog, config, fixed
from .deadtime import HI, LO, OFF, LegState, simulate_events


@dataclass(frozen=True)
class Inputs:
    """Values on the core's input ports when they are sampled."""
    freq: int = 0           # signed frequency word
    m: int = 0              # UQ1.15 magnitude (freq / polar modes)
    period: int = 1536      # half period, clocks
    dt: int = 0             # (rising) dead time, clocks
    # falling dead time, clocks (dtf_i with dtf_en_i = 1); None: dtf_en_i = 0, the falling dead time is dt.
    # Keyword-only, so the positional order of the other fields (freq, m, period, dt, mp, ...) is unchanged
    dtf: int | None = field(default=None, kw_only=True)
    mp: int = 0             # minimum gate pulse, clocks
    mode: int = fixed.MODE_FREQ
    theta: int = 0          # 16-bit electrical angle (polar, dq)
    v1: int = 0             # v_alpha / v_d, Q2.14
    v2: int = 0             # v_beta / v_q, Q2.14
    vf_boost: int = 0
    vf_slope: int = 0
    vf_mmax: int = 0
    dpwm: int = fixed.DPWM_OFF
    upd: int = fixed.UPD_VALLEY
    presc: int = 0
    isign: int = 0          # current signs {c, b, a}, 1 = negative (dead-time compensation)
    dtc: int = 0            # 1: dead-time compensation on (not in the compact core)
    om: int = 0             # overmodulation law: 0 angle-keeping clamp, 1 six-step (not in the compact core)
    vsc: int = 0            # 1: volt-second carry of the minimum-pulse rule (the register map's default; not in
                            # the compact core)
    # feature adc (svpwm_model.adc): the two ADC trigger points and the minimum shunt window, sampled with the
    # reference (keyword-only, like dtf)
    adc_pt: tuple[adc.Point, adc.Point] = field(default=(adc.Point(), adc.Point()), kw_only=True)
    win_min: int = field(default=0, kw_only=True)


@dataclass(frozen=True)
class Update:
    """One update: compare values computed from a sample and active from ``load``."""
    load: int               # cycle the values are active from (a valley or a peak)
    sample: int             # S: the accumulator value at S was used (inputs read at S - 1)
    at_peak: bool
    theta: int              # full angle sector*2^W + angle at S (freq / vf modes; also recorded otherwise)
    m: int | None           # magnitude used (freq, vf, polar), None for alpha-beta / dq
    sector: int
    cmp: tuple[int, int, int]
    sat: bool
    err: bool
    period: int             # half period the values were computed for
    carry_in: tuple[int, int, int] = (0, 0, 0)    # volt-second carry added before the minimum-pulse rule
    carry: tuple[int, int, int] = (0, 0, 0)       # what the rule dropped or widened (given to the next update)
    adc_pt: tuple[adc.Point, adc.Point] = (adc.Point(), adc.Point())   # trigger points sampled with it
    win_min: int = 0                              # minimum shunt window sampled with it


@dataclass
class Run:
    """Result of CoreModel.run(); arrays are indexed by carrier period n = 0..N-1 unless stated."""
    valley: list[int] = field(default_factory=list)      # t_n, n = 0..N (t_N: the valley after the last)
    period: list[int] = field(default_factory=list)      # P_n
    dt: list[int] = field(default_factory=list)          # (rising) dead time active in period n
    dtf: list[int] = field(default_factory=list)         # falling dead time active in period n
    mp: list[int] = field(default_factory=list)          # minimum pulse active in period n
    cmp: list[tuple[int, int, int] | None] = field(default_factory=list)      # active at valley n (up half)
    cmp_peak: list[tuple[int, int, int] | None] = field(default_factory=list)  # active at peak n (down half)
    sector: list[int | None] = field(default_factory=list)   # sector of cmp[n]
    theta: list[int | None] = field(default_factory=list)    # exact full angle cmp[n] was computed from
    m: list[int | None] = field(default_factory=list)        # magnitude cmp[n] was computed with
    sat: list[bool] = field(default_factory=list)            # cmp[n] was clamped to the hexagon (sat_o)
    err: list[bool] = field(default_factory=list)            # cmp[n] from an invalid mode (cfg_err_o part)
    updates: list[Update] = field(default_factory=list)      # every update, in time order
    pole_edges: list[tuple[int, int]] = field(default_factory=list)    # (cycle, pole word {c,b,a})
    gate_edges: list[tuple[int, int]] = field(default_factory=list)    # (cycle, {lo[2:0], hi[2:0]})
    # feature adc: (cycle, {point 1, point 0}) of every trigger-point pulse (adc_pt_o: the clock after the
    # carrier was at the point), and per half period
    # (start cycle: a valley or a peak, the report of the values active in it: adc.window) -- the report
    # outputs show it from the start + 9 on at the latest (rtl/svpwm_adc.sv)
    adc_fires: list[tuple[int, int]] = field(default_factory=list)
    windows: list[tuple[int, adc.Window]] = field(default_factory=list)
    end: int = 0                                           # edges are listed for cycles < end


def _merge(words: dict[int, list[tuple[int, int]]], bits: int) -> list[tuple[int, int]]:
    """Merge per-bit change lists {bit: [(cycle, value)]} into word changes [(cycle, word)]."""
    ev: dict[int, dict[int, int]] = {}
    for b, lst in words.items():
        for c, v in lst:
            ev.setdefault(c, {})[b] = v
    out, word = [], 0
    for c in sorted(ev):
        for b, v in ev[c].items():
            word = (word & ~(1 << b)) | (v << b)
        if not out or out[-1][1] != word:
            out.append((c, word))
    return out


def as_built(u: Inputs, features: int) -> Inputs:
    """Inputs as a build (config.py feature mask) sees them: the inputs of features it lacks are not read
    (SVPWM, valley updates, no prescaler, one dead time, no compensation, the clamp, no carry; no phase
    accumulator without FREQ and VF: freq 0), a mode it lacks is the invalid code (the zero vector and
    cfg_err_o); the tiny build (TRANSITIONAL: the compact core's own datapath) reads no mode: FREQ."""
    has = lambda n: config.has(features, n)               # noqa: E731
    mode = calc_prog.inp_mode({"mode": u.mode}, features)
    return replace(u, mode=mode, freq=u.freq if config.has_acc(features) else 0,
                   dpwm=u.dpwm if has("dpwm") else fixed.DPWM_OFF, upd=u.upd if has("upd") else fixed.UPD_VALLEY,
                   presc=u.presc if has("presc") else 0, dtf=u.dtf if has("dtf") else None,
                   dtc=u.dtc if has("dtc") else 0, isign=u.isign if has("dtc") else 0,
                   om=u.om if has("sixstep") else 0, vsc=u.vsc if has("carry") else 0,
                   adc_pt=u.adc_pt if has("adc") else (adc.Point(), adc.Point()),
                   win_min=u.win_min if has("adc") else 0)


def falling_dt(u: Inputs) -> int:
    """The falling dead time in force for inputs u (dtf_en_i = 0: dt)."""
    return u.dt if u.dtf is None else u.dtf


def _upd_code(upd: int) -> int:
    """upd_i as the core decodes it: 3 (invalid) counts as VALLEY (and raises cfg_err_o)."""
    return fixed.UPD_VALLEY if upd == 3 else upd


class CoreModel:
    """The golden model. State carried between runs: the angle and the dead-time FSMs."""

    def __init__(self, sector: int = 0, angle: int = 0, compact: bool = False,
                 min_period: int | None = None, features: int | None = None):
        """``features``: the build (svpwm_core Features, config.py; default: full); ``compact``: the tiny
        build (config.TINY). The inputs of features a build lacks are ignored (as_built), its lead is
        fixed.latencies(features). ``min_period``: the core's MinPeriod parameter (default: the build's)."""
        self.theta = (sector << fixed.PHASE_WIDTH) + angle      # full angle, units 60deg / 2^PHASE_WIDTH
        if features is None:
            features = config.TINY if compact else config.FULL
        self.features = features
        self.compact = features == config.TINY
        lat = fixed.latencies(features)
        self.lead = lat["SAMPLE_LEAD"]
        if min_period is None:
            min_period = lat["MIN_PERIOD"]
        self.min_period = min_period
        self.legs = [LegState(0, 0, 0, True) for _ in range(3)]   # reset: off, the longest dead time
        # counts from the release

    def run(self, idle: Inputs, inputs: Sequence[Inputs] | Callable[[int], Inputs], n_periods: int,
            stop: int | None = None,
            peak_inputs: Sequence[Inputs] | Callable[[int], Inputs] | None = None) -> Run:
        """Enable the core with ``idle`` on the inputs and run ``n_periods`` carrier periods.

        ``inputs(n)`` / ``inputs[n]`` are sampled before valley n + 1, ``peak_inputs(n)`` before peak n.
        ``stop``: en_i goes low at cycle t_N + stop (0 <= stop <= P_N; default: no stop, the run ends
        at t_N with the core still running -- the gate edges are then complete up to t_N).
        """
        get = inputs if callable(inputs) else (lambda n: inputs[n])
        if peak_inputs is None:
            pget = get
        else:
            pget = peak_inputs if callable(peak_inputs) else (lambda n: peak_inputs[n])
        if self.features != config.FULL:    # a build ignores the inputs of the features it lacks
            feats, get0, pget0 = self.features, get, pget
            get = lambda n: as_built(get0(n), feats)           # noqa: E731
            pget = lambda n: as_built(pget0(n), feats)         # noqa: E731
            idle = as_built(idle, feats)
        full = 6 << fixed.PHASE_WIDTH
        lead, min_period = self.lead, self.min_period
        r = Run()
        p_cur, _ = fixed.clamp_period(idle.period, idle.dt, idle.mp, min_period, dtf=falling_dt(idle))
        dt_cur, dtf_cur, mp_cur = idle.dt, falling_dt(idle), idle.mp
        f_cur, _ = fixed.clamp_freq(idle.freq)
        upd, presc, cnt = _upd_code(idle.upd), idle.presc, 0
        t = fixed.START_DELAY                  # valley of period 0: the first clock the core runs
        theta, th_t = self.theta, t            # the angle at cycle th_t (it steps from t on)
        stop_cycle = None
        active: Update | None = None           # values in force
        halves: list[tuple[int, int, Update | None]] = []   # (start cycle, half period, values) per half

        def advance(to: int) -> int:
            nonlocal theta, th_t
            theta = (theta + f_cur * (to - th_t)) % full
            th_t = to
            return theta

        carry, carry_per = (0, 0, 0), None   # volt-second carry of the last update taken, and its period
        #                                      (a run starts with none: the core clears it while stopped)

        def compute(u: Inputs, s: int, period: int, dt: int, dtf: int, mp: int, at_peak: bool) -> Update:
            nonlocal f_cur
            th = advance(s)                     # theta(S): the old frequency word up to S
            f_cur, _ = fixed.clamp_freq(u.freq)  # the new one from S on
            sector, angle = th >> fixed.PHASE_WIDTH, th & ((1 << fixed.PHASE_WIDTH) - 1)
            a16 = angle >> (fixed.PHASE_WIDTH - fixed.ANGLE_BITS)
            thr = max(dt, dtf) + mp
            hdr, hdf = fixed.dtc_amounts(dt, dtf, bool(u.dtc))
            c_in = carry if (u.vsc and period == carry_per) else (0, 0, 0)
            sec, cmp, sat, err = fixed.modulate(u.mode, sector, a16, period, freq=f_cur, m=u.m, theta=u.theta,
                                                v1=u.v1, v2=u.v2, vf_boost=u.vf_boost, vf_slope=u.vf_slope,
                                                vf_mmax=u.vf_mmax, dpwm=u.dpwm, isign=u.isign & 7, hdr=hdr,
                                                hdf=hdf, om=u.om, carry=c_in)
            sc = [fixed.snap_carry(c, period, thr) for c in cmp]
            cmp = tuple(x for x, _ in sc)
            c_out = tuple(e for _, e in sc) if u.vsc else (0, 0, 0)
            if u.mode in (fixed.MODE_FREQ, fixed.MODE_POLAR):
                m_used = u.m
            elif u.mode == fixed.MODE_VF:
                m_used = fixed.vf_m(f_cur, u.vf_boost, u.vf_slope, u.vf_mmax)
            else:
                m_used = None
            return Update(load=s + lead, sample=s, at_peak=at_peak, theta=th, m=m_used, sector=sec, cmp=cmp,
                          carry_in=c_in, carry=c_out,
                          sat=sat, err=err, period=period, adc_pt=u.adc_pt, win_min=u.win_min)

        n_total = n_periods if stop is None else n_periods + 1
        for n in range(n_total):
            last = n == n_periods                  # the partial period N before the stop
            if not last:
                r.valley.append(t)
                r.period.append(p_cur)
                r.dt.append(dt_cur)
                r.dtf.append(dtf_cur)
                r.mp.append(mp_cur)
                r.cmp.append(active.cmp if active else None)
                r.sector.append(active.sector if active else None)
                r.theta.append(active.theta if active else None)
                r.m.append(active.m if active else None)
                r.sat.append(active.sat if active else False)
                r.err.append(active.err if active else False)
            else:
                stop_cycle = t + stop
            halves.append((t, p_cur, active))
            # ---- peak opportunity ----
            pk = t + p_cur
            if upd in (fixed.UPD_PEAK, fixed.UPD_BOTH):
                ev = cnt == 0
                cnt = 0 if cnt >= presc else cnt + 1
                s = pk - lead
                # the core runs (samples, takes) up to the stop clock itself: its run register
                if ev and (stop_cycle is None or s - 1 < stop_cycle + fixed.START_DELAY):
                    u_pk = pget(n) if not last else get(n - 1)   # the ports hold the last inputs
                    up = compute(u_pk, s, p_cur, dt_cur, dtf_cur, mp_cur, True)
                    if stop_cycle is None or up.load - 1 < stop_cycle + fixed.START_DELAY:   # taken while running
                        r.updates.append(up)
                        active = up
                        carry, carry_per = up.carry, up.period
            if not last:
                r.cmp_peak.append(active.cmp if active else None)
            halves.append((pk, p_cur, active))
            if last:
                break
            # ---- valley opportunity ----
            u = get(n)
            dtf_next = falling_dt(u)
            p_next, _ = fixed.clamp_period(u.period, u.dt, u.mp, min_period, dtf=dtf_next)
            forced = (p_next, u.dt, dtf_next, u.mp) != (p_cur, dt_cur, dtf_cur, mp_cur)
            opp = upd in (fixed.UPD_VALLEY, fixed.UPD_BOTH)
            ev = (opp and cnt == 0) or forced
            if opp:
                cnt = 0 if cnt >= presc else cnt + 1
            upd, presc = _upd_code(u.upd), u.presc
            if ev:
                up = compute(u, t + 2 * p_cur - lead, p_next, u.dt, dtf_next, u.mp, False)
                r.updates.append(up)
                active = up
                carry, carry_per = up.carry, up.period
            t += 2 * p_cur
            p_cur, dt_cur, dtf_cur, mp_cur = p_next, u.dt, dtf_next, u.mp
        if stop is None:
            r.valley.append(t)
            end = t
            advance(t)
        else:
            if not 0 <= stop <= p_cur:
                raise ValueError("stop must lie between the last valley and the following peak")
            r.valley.append(t)
            end = stop_cycle + 2          # the gates are off from stop_cycle + 1
            advance(stop_cycle + fixed.START_DELAY)   # the accumulator steps in the stop clock too
        self.theta = theta
        r.end = end
        # ---- poles: per half period, merge touching intervals, clip at the stop ----
        pole_ch: dict[int, list[tuple[int, int]]] = {}
        for ph in range(3):
            iv: list[list[int]] = []
            for k, (h0, p, vals) in enumerate(halves):
                if vals is None:
                    continue
                c = vals.cmp[ph]
                if c >= p:
                    continue
                a, b = (h0 + c + 1, h0 + p + 1) if k % 2 == 0 else (h0 + 1, h0 + p - c + 1)
                if stop_cycle is not None:
                    b = min(b, stop_cycle + 1)
                    if a >= b:
                        continue
                if iv and iv[-1][1] == a:
                    iv[-1][1] = b
                else:
                    iv.append([a, b])
            lst = []
            for a, b in iv:
                lst += [(a, 1), (b, 0)]
            pole_ch[ph] = [(c, v) for c, v in lst if c < end]
        r.pole_edges = _merge(pole_ch, 3)
        # ---- feature adc: trigger points (the values of each half's update; off before the first) and the
        # shunt-window report (the dead times of the period) ----
        if config.has(self.features, "adc"):
            fires: dict[int, int] = {}
            for k, (h0, p, vals) in enumerate(halves):
                n = k // 2
                if n >= len(r.dt):
                    dt_h, dtf_h, mp_h = dt_cur, dtf_cur, mp_cur
                else:
                    dt_h, dtf_h, mp_h = r.dt[n], r.dtf[n], r.mp[n]
                r.windows.append((h0, adc.window(vals.cmp if vals else None, p, dt_h, dtf_h, mp_h,
                                                 vals.win_min if vals else 0)))
                if vals is None:
                    continue
                for j, pt in enumerate(vals.adc_pt):
                    kc = adc.point_clock(pt, p)
                    if kc is None or (kc < p) != (k % 2 == 0):
                        continue
                    c = h0 + (kc if k % 2 == 0 else kc - p)          # the carrier at the point
                    if c + 1 < end and (stop_cycle is None or c <= stop_cycle):
                        fires[c + 1] = fires.get(c + 1, 0) | 1 << j  # the registered pulse
            r.adc_fires = sorted(fires.items())
        # ---- gates: target per leg, piecewise constant; dead times and minimum pulse change one clock
        # after each valley (rtl/deadtime.sv reads the core's dt_q / dtf_q / mp_q a clock ahead) ----
        first = [x.load for x in r.updates if stop_cycle is None or x.load <= stop_cycle]
        valid_from = first[0] + 1 if first else end          # pole_valid_q
        n_val = len(r.dt)
        gate_ch: dict[int, list[tuple[int, int]]] = {}
        for ph in range(3):
            times = {0, valid_from} | {c for c, _ in pole_ch[ph]} | {v + 1 for v in r.valley[:n_val]}
            if stop_cycle is not None:
                times |= {r.valley[-1], stop_cycle}
            times = sorted(x for x in times if 0 <= x < end)
            pole_val = dict(pole_ch[ph])
            changes, pv = [], 0
            for c in times:
                pv = pole_val.get(c, pv)
                if stop_cycle is not None and c >= stop_cycle:
                    tgt = OFF
                elif c < valid_from:
                    tgt = OFF
                else:
                    tgt = HI if pv else LO
                k = max(bisect.bisect_right(r.valley, c - 1) - 1, 0)
                dt = r.dt[k] if k < n_val else dt_cur
                mp = r.mp[k] if k < n_val else mp_cur
                dtf = r.dtf[k] if k < n_val else dtf_cur
                changes.append((c, tgt, dt, mp, dtf))
            ev_, self.legs[ph] = simulate_events(changes, end, (1 << fixed.DT_WIDTH) - 1, self.legs[ph])
            gate_ch[ph] = [(c, h) for c, h, _ in ev_ if c < end]
            gate_ch[ph + 3] = [(c, lo) for c, _, lo in ev_ if c < end]
        r.gate_edges = _merge(gate_ch, 6)
        return r

    def idle(self, cycles: int) -> None:
        """The core idles (en_i low) for ``cycles`` clocks: gates off, dead-time counters run on."""
        sat = (1 << fixed.DT_WIDTH) - 1
        for leg in self.legs:
            assert not (leg.hi or leg.lo), "gates must be off when idle"
            leg.cnt = min(leg.cnt + cycles, sat)
