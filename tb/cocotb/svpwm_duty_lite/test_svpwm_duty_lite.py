# SPDX-License-Identifier: Apache-2.0
"""svpwm_duty_lite (the compact core's serial calculator) against the golden model, exact (==), and its handshake.

Expected results (model/svpwm_model/fixed.py): t1, t2, sat = hex_clamp(*duties(a16, m));
C = dwell_compare(sector, t1, t2, P) (= compare_values(..., DPWM_OFF)); cmp = snap_min_pulse(C_k, P, thr) per
phase; sector_o = sector_i.

Handshake (RTL header): start_i high in cycle c (sampled by the rising edge that ends cycle c) is accepted when
idle; busy_o is high in cycles c+1 .. c+LATENCY-1, done_o is a one-cycle pulse in cycle c+LATENCY together with
the new sector_o / cmp_o / sat_o, which then hold until the next done_o; start_i is ignored while busy_o; the done
cycle is idle, so a start there is accepted (back to back). LATENCY = fixed.LITE_DUTY_LATENCY (the harness
checks the busy length against it on every clock, the test the done time).

Checks:
* `run_vectors` (event driven: wakes at the start edge, at done_o and once per vector): results == model,
  done_o exactly LATENCY - 1 periods after the sampling edge; one clock after the start busy_o = 1,
  done_o = 0 and the previous results still held. While busy, start_i stays HIGH with scrambled inputs (sometimes
  scrambled again mid-computation): ignored. 3 % of the vectors are preceded by an aborted junk computation.
* the harness (tb_svpwm_duty_lite.sv) checks every clock: outputs change only with done_o, done_o one clock
  wide, exactly LATENCY - 1 busy clocks before each done_o; its sticky chk_o is asserted 0.
* `protocol`: per-clock reference of the handshake, every output on every clock (short), incl. abort_i pulses.
* `abort`: abort_i 0 .. LATENCY-1 clocks after a start (0: with start_i, which is then not taken): back to idle
  at once, no done_o, results hold; the next vector is exact.

Vectors: `directed` (same on both simulators): every sector x angles 0, 1, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF
x m 0, 1, 0x4000, 0x7FFF, 0x8000, 0x8001, 0x93CD (vertex), 0x93CE, 0xC000, 0xFFFF x (P, thr) corners: small P,
P = 2 thr with thr 0 / odd / even / the largest, P = 2^CntWidth - 1; plus every ROM interval end (angle
k*256 - 1, k*256) at the vertex and m = 0xFFFF. `angle_sweep`: every angle 0 .. 0xFFFF (every 61st on Icarus)
with m = vertex, vertex + 1, 0xFFFF or random. `random`: seeded, 100000 on Verilator, 5000 on Icarus
(LITE_NRAND overrides), with thr near P/2 and snapping values made likely.
Builds: CntWidth 16 and 12 (DtWidth 10). The vector runner, the handshake reference and the harness checker
are shared with svpwm_duty's test: tb/cocotb/calc_tb.py, tb/cocotb/calc_handshake_chk.sv.
"""
from __future__ import annotations

import math
import os
import random
from pathlib import Path
from dataclasses import dataclass

import cocotb
import pytest

from calc_tb import CalcTB, icarus
from simrun import REPO, run_sim
from svpwm_model import fixed

LATENCY = fixed.LITE_DUTY_LATENCY   # clocks: start_i in cycle c -> done_o in cycle c + LATENCY
P_MIN = 8                           # shortest period exercised (stated minimum of the RTL header: none needed)
M_VERTEX = int(round(2 / math.sqrt(3) * fixed.M_ONE))        # 0x93CD, the hexagon vertex
ANGLES = (0, 1, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF)
MS = (0, 1, 0x4000, 0x7FFF, 0x8000, 0x8001, M_VERTEX, M_VERTEX + 1, 0xC000, 0xFFFF)


@dataclass(frozen=True)
class Vec:
    sector: int = 0
    angle: int = 0
    m: int = 0
    period: int = P_MIN
    thr: int = 0


def model(v: Vec) -> tuple[int, int, int, int, int]:
    """(sector, C_a, C_b, C_c, sat) of the golden model."""
    t1, t2, sat = fixed.hex_clamp(*fixed.duties(v.angle, v.m))
    c = fixed.dwell_compare(v.sector, t1, t2, v.period)
    assert c == fixed.compare_values(v.sector, v.angle, v.m, v.period, fixed.DPWM_OFF)
    return (v.sector, *(fixed.snap_min_pulse(x, v.period, v.thr) for x in c), int(sat))


class LiteTB(CalcTB):
    LATENCY = LATENCY
    FLAGS = ("sat_o",)
    IDLE = Vec()

    def __init__(self, dut):
        super().__init__(dut)
        self.thr_max = (1 << len(dut.thr_i)) - 2      # 2^(DtWidth+1) - 2 (dead time + minimum pulse)

    def expect(self, v: Vec):
        assert 2 * v.thr <= v.period <= self.top, v
        res = model(v)
        assert all(0 <= x <= v.period for x in res[1:4]), (v, res)
        return res

    def drive(self, start: int, v: Vec):
        d = self.dut
        d.start_i.value = start
        d.sector_i.value = v.sector
        d.angle_i.value = v.angle
        d.m_i.value = v.m
        d.period_i.value = v.period
        d.thr_i.value = v.thr

    def junk(self, rng: random.Random) -> Vec:
        """Any input word at all (what start_i must ignore while busy); sector 6, 7 included."""
        return Vec(rng.randrange(8), rng.randrange(1 << 16), rng.randrange(1 << 16), rng.randrange(self.top + 1),
                   rng.randrange(self.thr_max + 2))

    def legal(self, rng: random.Random) -> Vec:
        p = rng.randint(P_MIN, self.top)
        return Vec(rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16), p,
                   rng.randint(0, min(self.thr_max, p // 2)))


# ---- vectors --------------------------------------------------------------------------------------------

def corners(top: int, thr_max: int) -> list[tuple[int, int]]:
    """(P, thr): small periods, P = 2 thr (the boundary) with thr 0 / 1 / odd / even / largest, the top period."""
    out = [(P_MIN, 0), (P_MIN, 4), (P_MIN, 3), (9, 4), (48, 0), (48, 7), (48, 24), (1000, 0), (1000, 37),
           (2 * thr_max, thr_max), (2 * thr_max - 1, thr_max - 1), (2 * 101, 101), (2 * 100, 100),
           (top, 0), (top, 1), (top, 113), (top, thr_max)]
    return [(p, t) for p, t in out if 2 * t <= p <= top]


def directed(top: int, thr_max: int) -> list[Vec]:
    cs = corners(top, thr_max)
    vecs = []
    i = 0
    for s in range(6):
        for a in ANGLES:
            for m in MS:
                for p, t in (cs[i % len(cs)], cs[(i + 7) % len(cs)]):
                    vecs.append(Vec(s, a, m, p, t))
                i += 1
    # every (P, thr) corner with a few references
    for p, t in cs:
        for s, a, m in ((0, 0, 0), (1, 0x8000, 0x8000), (5, 0xFFFF, 0xFFFF), (2, 1, M_VERTEX), (4, 0x4000, 0x93CE)):
            vecs.append(Vec(s, a, m, p, t))
    # ROM interval ends at the vertex / full scale
    for k in range(0, 257, 8):
        for a in ((k << 8) - 1, k << 8):
            if 0 <= a <= 0xFFFF:
                vecs.append(Vec(k % 6, a, (M_VERTEX, 0xFFFF)[k & 1], top, (k * 7) % (thr_max + 1)))
    return vecs


def rand_vectors(rng: random.Random, n: int, top: int, thr_max: int) -> list[Vec]:
    out = []
    for _ in range(n):
        r = rng.random()
        p = P_MIN if r < 0.03 else top if r < 0.08 else rng.randint(P_MIN, min(top, 4 * thr_max)) if r < 0.5 \
            else rng.randint(P_MIN, top)
        tmax = min(thr_max, p // 2)
        r = rng.random()
        t = tmax if r < 0.1 else 0 if r < 0.15 else rng.randint(0, tmax)
        r = rng.random()
        m = rng.randrange(1 << 16) if r < 0.5 else rng.randint(0, M_VERTEX + 64) if r < 0.8 \
            else rng.randint(0xF000, 0xFFFF)
        out.append(Vec(rng.randrange(6), rng.randrange(1 << 16), m, p, t))
    return out


# ---- cocotb tests -----------------------------------------------------------------------------------------

@cocotb.test()
async def directed_vectors(dut):
    """Directed vectors (module docstring)."""
    tb = LiteTB(dut)
    await tb.reset()
    await tb.run_vectors(directed(tb.top, tb.thr_max), random.Random(0x11E), "directed")


@cocotb.test()
async def random_vectors(dut):
    """Seeded random vectors: all sectors, angles, m; periods [8, 2^CntWidth - 1] with thr up to min(P/2, max)."""
    tb = LiteTB(dut)
    n = int(os.environ.get("LITE_NRAND", 5000 if icarus() else 100000))
    rng = random.Random(0x1D7E + tb.W)
    await tb.reset()
    await tb.run_vectors(rand_vectors(rng, n, tb.top, tb.thr_max), rng, "random")


@cocotb.test()
async def angle_sweep(dut):
    """Every in-sector angle 0 .. 0xFFFF (Verilator; every 61st on Icarus) at the vertex m and beyond, random
    sector, period and thr: every ROM interval and interpolation fraction, both clamp branches."""
    tb = LiteTB(dut)
    rng = random.Random(0x5EE9 + tb.W)
    step = 61 if icarus() else 1
    vecs = []
    for a in range(0, 1 << 16, step):
        v = tb.legal(rng)
        vecs.append(Vec(v.sector, a, (M_VERTEX, M_VERTEX + 1, 0xFFFF, v.m)[a & 3], v.period, v.thr))
    await tb.reset()
    await tb.run_vectors(vecs, rng, "angle sweep")


@cocotb.test()
async def protocol(dut):
    """Every output on every clock against the reference: single starts with gaps, start_i held high with
    inputs changing every clock (ignored while busy, back-to-back restarts), random start and abort pulses."""
    tb = LiteTB(dut)
    rng = random.Random(0xB05 + tb.W)
    await tb.reset()
    sched = []
    for gap in (0, 1, 2, 15):
        sched += [(1, 0, tb.legal(rng))] + [(0, 0, tb.junk(rng)) for _ in range(LATENCY - 1 + gap)]
    sched += [(1, 0, tb.legal(rng)) for _ in range(3 * LATENCY + 3)]
    for k in (LATENCY - 2, LATENCY - 1, 5):
        sched += [(1, 0, tb.legal(rng))] + [(1, 0, tb.legal(rng)) for _ in range(k - 1)] + [(1, 1, tb.legal(rng))]
        sched += [(0, 0, tb.junk(rng)) for _ in range(3)]
    sched += [(int(rng.random() < 0.05), int(rng.random() < 0.004), tb.legal(rng)) for _ in range(600)]
    sched += [(0, 0, tb.junk(rng)) for _ in range(LATENCY + 2)]
    await tb.protocol(sched, 8)


@cocotb.test()
async def abort(dut):
    """abort_i k = 0 .. LATENCY-1 clocks after a start: back to idle, no done_o, results held; then exact."""
    tb = LiteTB(dut)
    rng = random.Random(0xAB0 + tb.W)
    await tb.reset()
    vecs = rand_vectors(rng, LATENCY, tb.top, tb.thr_max)
    await tb.run_vectors(vecs[:1], rng, "before abort")
    for k in range(LATENCY):
        await tb.aborted_start(rng, k)
        await tb.run_vectors([vecs[k]], rng, f"after abort at {k}")


BUILDS = {"cnt16": {"CntWidth": 16, "DtWidth": 10}, "cnt12": {"CntWidth": 12, "DtWidth": 10}}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_duty_lite(sim, build):
    run_sim(sim, toplevel="tb_svpwm_duty_lite",
            sources=[REPO / "rtl/sine_rom.sv", REPO / "rtl/svpwm_sector_sel.sv", REPO / "rtl/svpwm_duty_lite.sv",
                     REPO / "tb/cocotb/calc_handshake_chk.sv", Path(__file__).parent / "tb_svpwm_duty_lite.sv"],
            test_module="test_svpwm_duty_lite", test_dir=Path(__file__).parent,
            parameters={**BUILDS[build], "Latency": fixed.LITE_DUTY_LATENCY}, build_name=build)
