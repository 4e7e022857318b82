# SPDX-License-Identifier: Apache-2.0
"""svpwm_duty against the golden model fixed.modulate (exact, ==) in every input mode, and its handshake.

Handshake (RTL header): start_i high in cycle c (sampled by the rising edge that ends cycle c) is accepted
when idle; busy_o is high in cycles c+1 .. c+33, done_o is a one-cycle pulse in cycle c+34
(DUTY_LATENCY = 34: done_o rises 33 clock periods after the edge that sampled start_i), together with the
new sector_o / cmp_o / sat_o / err_o, which then hold until the next done_o; start_i is ignored while busy_o.
The done cycle is idle: a start there is accepted (back to back, one result every 34 clocks).

Checks:
* `run_vectors` (event driven: wakes at the start edge, at done_o and once more per vector): results ==
  fixed.modulate; done_o exactly 33 periods after the sampling edge; one clock after the start busy_o = 1,
  done_o = 0 and the previous results still held. While busy, start_i stays HIGH with scrambled inputs (and
  sometimes they are scrambled again mid-computation): they must be ignored.
* the harness (tb_svpwm_duty.sv) checks on every clock in SystemVerilog: outputs change only with done_o,
  done_o one clock wide, exactly 33 busy clocks before each done_o; its sticky chk_o is asserted 0.
* `protocol`: a per-clock reference of the handshake, every output on every clock (short), incl. abort_i pulses.
* `abort` (and 3 % of the vectors in every run): abort_i 0 .. 33 clocks after a start: back to idle at once, no
  done_o, the previous results hold (abort_i with start_i: the start is not taken); the next vector is exact.

Vectors (`directed`, the same on both simulators; `rand_vectors`: seeded, 20000 on Verilator, 1500 on Icarus):
FREQ (6 sectors x theta' = 0, 1, 30 deg +-1 LSB, 60 deg - 1/2 LSB x m = 0 .. 1.0, 2/sqrt3 (vertex) .. 0xFFFF
x DPWM 0..3 x P = 48, 2^CntWidth - 1), VF (f = 0, linear, exactly at / beyond mmax, -f, +-FreqMax,
boost > mmax, zero / full-scale parameters), POLAR (theta at every 30 deg +-3 LSB and a full revolution),
AB (grid incl. -32768 and 32767, the zero vector, rings |v| = 0.5 .. 1.99 at every 30 deg, vectors exactly
on the 60 deg sector lines: Y = 0 / Z = 0), DQ (vector grid x theta at every 30 deg +-3 LSB incl.
theta' = 30 deg exactly (theta = 16384, 49152: the trig switch) and a full revolution), invalid modes 5..7.

Builds: CntWidth 16 (default) and 12. modulate has no width: for P < 2^CntWidth its results lie in [0, P].
The vector runner, the handshake reference and the harness checker are shared with the compact calculator's
test: tb/cocotb/calc_tb.py, tb/cocotb/calc_handshake_chk.sv.
"""
from __future__ import annotations

import itertools
import math
import os
import random
import zlib
from dataclasses import dataclass, replace
from pathlib import Path

import cocotb
import pytest

from calc_tb import CalcTB, icarus
from simrun import REPO, run_sim
from svpwm_model import fixed

LATENCY = 34                 # clocks: start_i in cycle c -> done_o in cycle c + LATENCY (RTL DutyLatency)
P_MIN = 48                   # shortest period exercised
FSHIFT = fixed.FREQ_WIDTH - 17
M_VERTEX = int(round(2 / math.sqrt(3) * fixed.M_ONE))        # 0x93CD, the hexagon vertex
ANGLES = (0, 1, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF)
MS = (0, 1, 0x4000, 0x7FFF, 0x8000, 0x8001, M_VERTEX, M_VERTEX + 1, 0xC000, 0xFFFF)
VS = (-32768, -32767, -28378, -16384, -8192, -1, 0, 1, 8192, 16384, 18919, 28378, 32767)


@dataclass(frozen=True)
class Vec:
    mode: int = fixed.MODE_FREQ
    sector: int = 0          # accumulator sector (FREQ, VF)
    angle: int = 0           # accumulator theta', UQ0.16 of 60 deg (FREQ, VF)
    theta: int = 0           # 16 bits = 360 deg (POLAR, DQ)
    m: int = 0               # UQ1.15 (FREQ, POLAR)
    freq: int = 0            # signed frequency word (VF); the RTL gets |freq| >> FSHIFT
    v1: int = 0              # Q2.14 v_alpha / v_d
    v2: int = 0              # Q2.14 v_beta / v_q
    boost: int = 0
    slope: int = 0
    mmax: int = 0
    dpwm: int = 0
    period: int = P_MIN


class DutyTB(CalcTB):
    LATENCY = LATENCY
    FLAGS = ("sat_o", "err_o")
    IDLE = Vec()

    def expect(self, v: Vec) -> tuple[int, int, int, int, int, int]:
        """(sector, C_a, C_b, C_c, sat, err) by the model; the model is width-free: check the result fits."""
        sec, c, sat, err = fixed.modulate(v.mode, v.sector, v.angle, v.period, freq=v.freq, m=v.m,
                                          theta=v.theta, v1=v.v1, v2=v.v2, vf_boost=v.boost,
                                          vf_slope=v.slope, vf_mmax=v.mmax, dpwm=v.dpwm)
        assert all(0 <= x <= v.period <= self.top for x in c), (v, c)
        return (sec, *c, int(sat), int(err))

    def drive(self, start: int, v: Vec):
        d = self.dut
        d.start_i.value = start
        d.mode_i.value = v.mode
        d.sector_i.value = v.sector
        d.angle_i.value = v.angle
        d.theta_i.value = v.theta
        d.m_i.value = v.m
        d.fabs_i.value = abs(v.freq) >> FSHIFT
        d.v1_i.value = v.v1 & 0xFFFF
        d.v2_i.value = v.v2 & 0xFFFF
        d.vf_boost_i.value = v.boost
        d.vf_slope_i.value = v.slope
        d.vf_mmax_i.value = v.mmax
        d.dpwm_i.value = v.dpwm
        d.period_i.value = v.period

    def junk(self, rng: random.Random) -> Vec:
        """Any input word at all (what start_i must ignore while busy)."""
        return Vec(rng.randrange(8), rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16),
                   rng.randrange(1 << 16), rng.randint(-fixed.FREQ_MAX, fixed.FREQ_MAX),
                   rng.randint(-32768, 32767), rng.randint(-32768, 32767), rng.randrange(1 << 16),
                   rng.randrange(1 << 16), rng.randrange(1 << 16), rng.randrange(4),
                   rng.randint(P_MIN, self.top))


# ---- vectors --------------------------------------------------------------------------------------------

def spread(base, periods, start=0):
    """Every vector of `base` once, DPWM and period cycled (all 8 combinations in every 8 vectors)."""
    return [replace(v, dpwm=(start + i) % 4, period=periods[((start + i) // 4) % len(periods)])
            for i, v in enumerate(base)]


def cross(base, periods):
    """Every vector of `base` with every DPWM setting and every period."""
    return [replace(v, dpwm=d, period=p) for v in base for d in range(4) for p in periods]


def boundary_thetas():
    """theta at every 30 deg (k 2^16 / 12, rounded) +- 3 LSB: theta' near 0, 60 deg - 1 and 30 deg, all sectors.
    (6 theta is even, so theta' = 0 exactly only at 0 / 180 deg and theta' = 30 deg exactly only at
    theta = 16384 / 49152; theta' = 60 deg - 2 LSB is the largest reachable.)"""
    return sorted({(round(k * 65536 / 12) + d) & 0xFFFF for k in range(12) for d in range(-3, 4)})


def ab_on_lines():
    """(v_alpha, v_beta) exactly on a 60 deg sector line: Z = v_beta/2 - sqrt3/2 v_alpha = 0 or Y = 0 in the
    RTL's integers (a projection q_k exactly 0: the tie in the sector search)."""
    out = []
    for va in (-32768, -30001, -20000, -9999, -2, 2, 9998, 20000, 30000, 32767):
        a = fixed._mul_v(va, fixed.SQRT3_2)
        if a % 2 == 0 and -32768 <= a // 2 <= 32767:
            out += [(va, a // 2), (va, -(a // 2))]
    return out


def directed(top: int) -> dict[str, list[Vec]]:
    periods = (P_MIN, top)
    F, VF, PO, AB, DQ = fixed.MODE_FREQ, fixed.MODE_VF, fixed.MODE_POLAR, fixed.MODE_AB, fixed.MODE_DQ
    sets: dict[str, list[Vec]] = {}
    # FREQ: the accumulator's sector + theta' (all sector edges) x m, every DPWM and period
    sets["freq"] = cross([Vec(F, s, a, m=m) for s in range(6) for a in ANGLES for m in MS], periods)
    # VF: the law itself (f = 0 -> boost, linear, at / beyond mmax, sign, extremes), then through the modulator
    fm = fixed.FREQ_MAX
    laws = [(0x0800, 0x0100, 0x8000), (0x0800, 0x0181, 0x93CD), (0x1000, 0x0100, 0x8000),
            (0x9000, 0x0010, 0x8000), (0, 0, 0), (0xFFFF, 0xFFFF, 0xFFFF), (0x0123, 0xFFFF, 0xFFFF),
            (0x4000, 0x0001, 0x0000), (0, 0x0080, 0xFFFF)]
    freqs = (0, 1, (1 << FSHIFT) - 1, 1 << FSHIFT, -(1 << FSHIFT), 0x3000 << FSHIFT, -(0x3000 << FSHIFT),
             (0x6FFF << FSHIFT) + 5, 0x7000 << FSHIFT, -((0x7000 << FSHIFT) + 127), 0x7001 << FSHIFT,
             0x8000 << FSHIFT, fm, -fm, 123456, -123456)
    vf = [Vec(VF, (i * 5) % 6, ANGLES[i % len(ANGLES)], freq=f, boost=b, slope=s, mmax=mx)
          for i, ((b, s, mx), f) in enumerate(itertools.product(laws, freqs))]
    sets["vf"] = spread(vf, periods)
    # POLAR: every 30 deg +- 3 LSB x m; a full revolution in 257-LSB steps
    ms_po = (0, 0x4000, 0x8000, M_VERTEX, M_VERTEX + 1, 0xFFFF)
    po = [Vec(PO, theta=t, m=m) for t in boundary_thetas() for m in ms_po]
    po += [Vec(PO, theta=t, m=m) for t in range(0, 1 << 16, 257) for m in (0x8000, M_VERTEX)]
    sets["polar"] = spread(po, periods)
    # AB: grid (extremes, zero), rings at every 30 deg +- a little, exact sector lines
    ab = [(a, b) for a in VS for b in VS]
    for r in (0.5, 1.0, 2 / math.sqrt(3), 1.5, 1.99):
        for k in range(12):
            for d in (-1e-4, 0.0, 1e-4):
                ph = math.radians(30 * k) + d
                ab.append(tuple(max(-32768, min(32767, round(r * fixed.V_ONE * f(ph)))) for f in (math.cos, math.sin)))
    ab += ab_on_lines()
    sets["ab"] = spread([Vec(AB, v1=a, v2=b) for a, b in ab], periods)
    # DQ: vector grid x theta at every 30 deg +- 3 (incl. theta' = 30 deg exactly), a full revolution
    dqv = [(0, 0), (0x4000, 0), (0, 0x4000), (-0x4000, 0), (0, -0x4000), (32767, 32767), (-32768, -32768),
           (-32768, 32767), (32767, -32768), (1, 0), (0, 1), (-1, -1), (12345, -23456), (M_VERTEX // 2, 0)]
    dq = [Vec(DQ, theta=t, v1=a, v2=b) for t in boundary_thetas() for a, b in dqv]
    dq += [Vec(DQ, theta=t, v1=a, v2=b) for t in range(0, 1 << 16, 257)
           for a, b in ((0x4000, 0), (9000, 30000), (-32768, -32768))]
    sets["dq"] = spread(dq, periods)
    # invalid modes: zero vector + err_o whatever the other inputs
    rng = random.Random(5)
    bad = [Vec(md, rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16), rng.randrange(1 << 16),
               rng.randint(-fm, fm), rng.randint(-32768, 32767), rng.randint(-32768, 32767),
               0x8000, 0x100, 0xFFFF) for md in (5, 6, 7) for _ in range(2)]
    sets["invalid"] = cross(bad, periods)
    return sets


def rand_vectors(rng: random.Random, n: int, top: int) -> list[Vec]:
    fm = fixed.FREQ_MAX
    out = []
    for _ in range(n):
        mode = rng.choice((0, 0, 1, 1, 2, 2, 3, 3, 3, 4, 4, 4, 5, 6, 7))
        r = rng.random()
        period = P_MIN if r < 0.05 else top if r < 0.1 else rng.randint(P_MIN, top)
        m = rng.randrange(1 << 16) if rng.random() < 0.5 else rng.randint(0, M_VERTEX + 64)
        if rng.random() < 0.5:                                   # uniform words
            v1, v2 = rng.randint(-32768, 32767), rng.randint(-32768, 32767)
        else:                                                    # uniform magnitude 0 .. 1.99, any angle
            mag, ph = rng.uniform(0, 1.99) * fixed.V_ONE, rng.uniform(0, 2 * math.pi)
            v1, v2 = (max(-32768, min(32767, round(mag * f(ph)))) for f in (math.cos, math.sin))
        freq = rng.randint(-fm, fm) if rng.random() < 0.5 else rng.randint(-(1 << 20), 1 << 20)
        out.append(Vec(mode, rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16), m, freq, v1, v2,
                       rng.randrange(0x4000), rng.randrange(1 << 16) >> rng.randrange(17),
                       rng.choice((rng.randrange(1 << 16), 0x8000, M_VERTEX, 0xFFFF)), rng.randrange(4), period))
    return out


# ---- cocotb tests -----------------------------------------------------------------------------------------

def _directed_test(key):
    async def t(dut):
        tb = DutyTB(dut)
        await tb.reset()
        await tb.run_vectors(directed(tb.top)[key], random.Random(zlib.crc32(key.encode())), key)
    t.__name__ = f"directed_{key}"
    t.__qualname__ = t.__name__
    t.__doc__ = f"Directed vectors, mode set {key!r} (module docstring)."
    return cocotb.test()(t)


directed_freq = _directed_test("freq")
directed_vf = _directed_test("vf")
directed_polar = _directed_test("polar")
directed_ab = _directed_test("ab")
directed_dq = _directed_test("dq")
directed_invalid = _directed_test("invalid")


@cocotb.test()
async def random_vectors(dut):
    """Seeded random vectors over all modes, DPWM settings and periods [48, 2^CntWidth - 1]."""
    tb = DutyTB(dut)
    n = int(os.environ.get("DUTY_NRAND", 1500 if icarus() else 20000))
    rng = random.Random(0xD07 + tb.W)
    await tb.reset()
    await tb.run_vectors(rand_vectors(rng, n, tb.top), rng, "random")


@cocotb.test()
async def protocol(dut):
    """Every output on every clock against the reference: single starts with gaps, start_i held high with
    inputs changing every clock (ignored while busy, back-to-back restarts), random start pulses."""
    tb = DutyTB(dut)
    rng = random.Random(0xB05 + tb.W)
    await tb.reset()
    assert fixed.DUTY_LATENCY == LATENCY, "model DUTY_LATENCY differs from the RTL's"
    sched = []
    for gap in (0, 1, 2, 15):                                 # single start pulses
        sched += [(1, 0, tb.junk(rng))] + [(0, 0, tb.junk(rng)) for _ in range(LATENCY - 1 + gap)]
    sched += [(1, 0, tb.junk(rng)) for _ in range(4 * LATENCY + 3)]   # start held high
    sched += [(int(rng.random() < 0.1), 0, tb.junk(rng)) for _ in range(200)]   # random pulses
    for k in (LATENCY - 2, LATENCY - 1, 5):                   # abort in the last steps / early, start held high
        sched += [(1, 0, tb.junk(rng))] + [(1, 0, tb.junk(rng)) for _ in range(k - 1)] + [(1, 1, tb.junk(rng))]
        sched += [(0, 0, tb.junk(rng)) for _ in range(3)]
    sched += [(int(rng.random() < 0.3), int(rng.random() < 0.02), tb.junk(rng)) for _ in range(300)]
    sched += [(0, 0, tb.junk(rng)) for _ in range(LATENCY + 2)]
    await tb.protocol(sched, 10)


@cocotb.test()
async def abort(dut):
    """abort_i k = 0 .. 33 clocks after a start (k = 0: with start_i): back to idle, no done_o, results held;
    then a vector computes correctly."""
    tb = DutyTB(dut)
    rng = random.Random(0xAB0 + tb.W)
    await tb.reset()
    vecs = rand_vectors(rng, LATENCY, tb.top)
    await tb.run_vectors(vecs[:1], rng, "before abort")
    for k in range(LATENCY):
        await tb.aborted_start(rng, k)
        await tb.run_vectors([vecs[k]], rng, f"after abort at {k}")


BUILDS = {"cnt16": {"CntWidth": 16}, "cnt12": {"CntWidth": 12}}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_duty(sim, build):
    run_sim(sim, toplevel="tb_svpwm_duty",
            sources=[REPO / "rtl/sine_rom.sv", REPO / "rtl/svpwm_sector_sel.sv", REPO / "rtl/svpwm_duty.sv",
                     REPO / "tb/cocotb/calc_handshake_chk.sv", Path(__file__).parent / "tb_svpwm_duty.sv"],
            test_module="test_svpwm_duty", test_dir=Path(__file__).parent,
            parameters=BUILDS[build], build_name=build)
