# SPDX-License-Identifier: Apache-2.0
"""svpwm_calc (the core's one calculator) against the golden model, exact (==), and its handshake; both
variants: Compact = 0 (every input mode, DPWM) and Compact = 1 (FREQ mode, continuous SVPWM).

Expected results: model/svpwm_model/calc_prog.py expect_carry(inp, compact) = fixed.modulate (incl. the six-step
overmodulation law, om_i, and the dead-time compensation + volt-second carry in, fixed.dtc_shift: isign_i, hdr_i,
hdf_i, carry_i when carry_en_i) + fixed.snap_carry per phase (the snapped compare values and carry_o). VF: the
RTL gets fabs_i =
|freq| >> (fixed.FREQ_WIDTH - 17) as the core computes it; the model gets the signed freq word (fixed.vf_m takes
the same bits of it). Compact = 1 ignores mode_i, theta_i, fabs_i, v1_i, v2_i, vf_*_i, dpwm_i, isign_i, hdr_i,
hdf_i, om_i, carry_i and carry_en_i: the compact vectors carry random words there (held while busy), the model
gets FREQ mode with dpwm, om and the compensation off, and carry_o must be 0.

Contract (checked here):
* start_i in cycle c (sampled by the rising edge ending cycle c) is accepted when idle (not busy_o) and
  abort_i is low; busy_o is high in cycles c+1 .. c+LATENCY-1; done_o is a one-cycle pulse in cycle
  c+LATENCY; start_i is ignored while busy_o; the done cycle is idle, so a start there is accepted (back to
  back).
* sector_o, cmp_o, sat_o, err_o are the results ONLY in the done_o cycle; they may change while busy (so no
  check of them outside done cycles). carry_o is valid from the second clock after done_o (two registered
  stages after the last out step) until the next computation's out steps: checked at done_o + 2, also when
  the next computation started in the done cycle (its out steps, the last steps of its program, come later).
* sector_i and angle_i are read at start_i only (scrambled here while busy); every other input (mode, theta,
  m, fabs, v1, v2, vf_*, dpwm, om, period, thr, isign, hdr, hdf, carry, carry_en) must hold from start_i until
  done_o, i.e. at every clock edge from the one sampling start_i to the one raising done_o (the done cycle may
  already carry the next start's inputs) -- except thr_i, which carry_o's limit +ceil(thr / 2) reads once
  more, in the done cycle (rtl/svpwm_calc.sv: hthr_q in the choice stage; the core holds its calc_thr_q from
  one start to the next). The test holds them while busy and scrambles them only while idle, thr_i from the
  clock after the done cycle on: a vector started in the done cycle (back to back) gets its thr_i one clock
  late, which the calculator allows (fabs_i, period_i, thr_i, hdr_i, hdf_i may arrive one clock after start_i;
  the others are driven with start_i here; model/tests/test_calc_prog.py runs the program with them late;
  Compact = 1 reads thr_i with start_i and has no carry: thr_i with start_i there); the harness checks the hold.
* abort_i: back to idle at once (busy_o low in the next cycle), no done_o for that computation; abort_i
  together with start_i: the start is not taken; the next computation is exact.
* restrictions kept by the vectors: period_i >= 2 thr_i, thr_i <= 2^(DtWidth+1) - 2 (dead time + minimum
  pulse, each DtWidth bits), sector_i 0..5 for a computation that completes; hdr_i, hdf_i <= 2^(DtWidth-1) =
  ceil((2^DtWidth - 1) / 2), the largest the core gives (fixed.dtc_amounts; junk / ignored inputs: any word);
  carry_i any DtWidth + 2-bit word per phase, with compensation + carry in DtWidth + 2 bits signed when
  carry_en_i (the calculator adds them in that width; the core's |carry| <= 2^DtWidth, |hd| <= 2^(DtWidth-1)).
LATENCY (clocks start_i -> done_o) is defined in one place below from the model; the harness gets it on its
input latency_i and checks busy_o / done_o on every clock against a reference of the handshake (chk_o), the test
checks the done time of every vector.

Checks:
* harness (tb_svpwm_calc.sv), every clock: busy_o and done_o == the handshake reference for the stimulus
  actually applied (starts, ignored starts, aborts); and that the test kept the held inputs while busy.
  Its sticky chk_o is asserted 0 after every run.
* `run_vectors`: the vectors, the model's results for each and the schedule around each are written to a file
  of records, which the harness's vector player (tb_svpwm_calc.sv) runs back to back and checks in its own
  clock, so Python does not wake per vector (it waits for the player's end and asserts its failure count is 0;
  the first failure is reported with the vector, its schedule, the RTL's outputs and the model's results).
  Per vector, as the Python loop of earlier versions did it: start_i on a falling edge; one clock later busy_o
  = 1, done_o = 0; 1 ns after the edge that must raise done_o (LATENCY - 1 periods after the sampling edge)
  (busy_o, done_o, sector_o, C_a, C_b, C_c, sat_o, err_o) === (0, 1, model) (and, by the harness's checker,
  done_o never before); carry_o === model 1 ns after the second rising edge after that one (done_o + 2, the
  harness's carry check, while the record after runs); the next start in the done cycle (back to back, its
  thr_i one clock late: Contract). While busy, start_i stays HIGH and
  sector_i / angle_i are scrambled (25 %: again at a random clock mid-computation, start_i random): ignored.
  2 % of the vectors follow an idle gap of 1..3 clocks with all inputs scrambled, 3 % an aborted computation
  of junk inputs (abort_i k = 0 .. LATENCY-1 clocks after its start, sector_i / angle_i scrambled and start_i
  random while it is busy; busy_o, done_o low at once and in the clock after).
* `protocol`: every clock driven from Python against a reference (busy_o, done_o every clock, results in
  every done cycle, carry_o two clocks later): single starts with gaps, start_i held high (ignored,
  back-to-back restarts), random start pulses, aborts in the first / last busy clocks, random start + abort
  pulses.
* `abort`: abort_i k = 0 .. LATENCY-1 clocks after a start (0: with start_i): idle at once, no done_o; then a
  vector is exact.

Vectors (`directed_*` the same on both simulators; (P, thr) corners: small P (8, 9, 48), P = 2 thr with thr
0 / odd / even / the largest, P = 2^CntWidth - 1 with thr 0, 1, 113, the largest):
* `directed_freq`: 6 sectors x theta' 0, 1, 30 deg +-1, 60 deg - 1/2 LSB x m 0, 1, 0x4000, 0x7FFF, 0x8000,
  0x8001, vertex 0x93CD, 0x93CE, 0xC000, 0xFFFF x (full) every DPWM setting x two (P, thr) corners (one
  with P = 2^CntWidth - 1).
* `directed_corners`: every (P, thr) corner x 5 references (x every DPWM setting, full); every ROM interval
  end (angle k 256 - 1, k 256) at the vertex and m = 0xFFFF.
* `directed_dtc` (dead-time compensation): every isign 0..7 x sector (the sector fixes which phase is of class
  hi / lo / mid, so every sign x class pattern) x m 0, 0x4000, vertex x every DPWM setting x 9 (hdr, hdf, thr,
  P): (3, 5, 10), (24, 24, 48), (0, 512, 0) at P 1536 and a small P = 2 thr (P_MIN for thr 0); (512, 1, 1023)
  at P = 2 thr = 2046 (1536 < 2 thr) and 2^CntWidth - 1; (1, 512, 2) at 2^CntWidth - 1 (C + hdf beyond P and
  the counter width); theta' cycled through ANGLES; FREQ mode (5,184 vectors). Compact: every isign x sector
  once with the settings and m cycled (48 vectors, the compensation ignored).
* `directed_carry` (the volt-second carry near both rails, FREQ mode): (m, DPWM) = m 0, 1, 0x100 with DPWMMIN
  and DPWMMAX (phases at / near 0 or P) and m 0x7FFF, 0x8000, vertex in SVPWM (phases near both) x thr 0, 1,
  30, 255 x carry in 0, +-limit, +-(limit + 1) (limit = ceil(thr / 2), the largest carry out) on every phase,
  all equal and mixed, and carry_en 0 with a carry word x P 1000 and 2^CntWidth - 1 (792 vectors). Compact:
  every (m, thr) once (72 vectors, carry_o 0).
* full only: `directed_vf` (V/f law: f = 0, linear, at / beyond mmax, -f, +-FreqMax, boost > mmax, zero /
  full-scale parameters), `directed_polar` (theta every 30 deg +-3 LSB x m, a full revolution),
  `directed_ab` (grid incl. -32768 / 32767, the zero vector, rings |v| 0.5 .. 1.99 at every 30 deg, vectors
  exactly on the 60 deg sector lines), `directed_dq` (vector grid x theta every 30 deg +-3 LSB incl.
  theta' = 30 deg exactly, a full revolution), `directed_invalid` (modes 5..7: zero vector + err_o),
  `directed_om` (om = 1, the six-step law: m 0x8000 .. 0xFFFF around the vertex 0x93CD (OM_MS) x (FREQ) every
  sector x theta' corner, (VF) m = boost and m = mmax, (POLAR) theta every 30 deg +-1; AB rings |v| 1 .. 1.99
  and extremes, DQ vectors at three thetas: these keep the clamp); each spread over every DPWM setting and the
  (P, thr) corners, half of them at P = 2^CntWidth - 1.
* Verilator runs every directed vector. Icarus runs `directed_corners`, `_vf`, `_ab`, `_invalid` in full and
  a complete subset of the six large sets (`icarus_subset`: every ICARUS_STRIDE = 3rd vector (`directed_dtc`:
  64th, `_carry` 16th, `_om` 32nd: ICARUS_STRIDES) plus the first vector of every category no kept vector
  covers yet;
  CALC_DIRECTED_STRIDE overrides, scripts/mutate.py sets 1): every (P, thr) corner and DPWM setting in each,
  and `directed_freq` every sector x theta' x m (1,411 of 3,360 vectors in the full variant), `directed_polar`
  every theta and every m (521 of 1,016), `directed_dq` every theta and every (v1, v2) (724 of 1,944),
  `directed_dtc` every isign x sector x DPWM setting (so every sign x class pattern with every clamped phase),
  every isign and every m at every (hdr, hdf, thr, P) (326 of 5,184), `directed_carry` every (m, DPWM) and
  every carry in pattern at every thr (118 of 792), `directed_om` every m of every mode, every AB / DQ vector,
  every sector x theta' (FREQ) and theta (POLAR) (203 of 1,140).
* `angle_sweep`: every in-sector angle 0 .. 0xFFFF (every 61st on Icarus) at m = vertex, vertex + 1, 0xFFFF
  or random, random sector, legal (P, thr), DPWM, om on / off (every other 4 angles), the carry in as below
  (full, FREQ mode).
* `random_vectors`: seeded; full: every mode incl. 5..7, DPWM, V/f parameters, saturation, om random, half of
  them with the dead-time compensation (isign random, hdr / hdf each 0, 1, ceil(thr / 2), 512 or uniform in
  0..512), the other half 0 / 0; independently half with carry_en 1 and the carry in per phase within
  +-(ceil(thr / 2) + 1) (a fifth of them: any DtWidth + 2-bit value, the sum with the compensation in range),
  the other half carry_en 0 (carry_i a random word half of the time: ignored); carry_o always checked (with
  carry_en 0: command - snapped); compact: junk on the ignored inputs; P in [8, 2^CntWidth - 1] (often
  <= 4 thr_max) with thr up to min(P/2, thr_max), thr_max / 0 often (snapping likely). 50,000 vectors on
  Verilator, 1,000 on Icarus (the cross-simulator check of the same stream's start); CALC_NRAND overrides.
* Icarus runs every scenario of the 16-bit builds and the directed and handshake scenarios of the 12-bit ones
  (ICARUS_CNT12_ONLY: every vector category at CntWidth 12); their modes, sweep and random run on Verilator.
* Icarus's cost: ~22 us per clock of the busy calculator (Compact = 0), the simulator's evaluation of the RTL
  itself (the same without cocotb, with the harness or the bare svpwm_calc; idle: ~4 us): vvp's behavioural
  processes of svpwm_calc (~27 per clock), not the ROMs, the harness's checker or Python. Verilator:
  ~0.4 us per clock without cocotb, ~0.5 with it (the player; the per-vector Python loop it replaced: ~0.6).

* `serial_vectors` (build full_serial only: Compact = 0 with Dsp = 0, the serial multiplier no core builds):
  every CALC_SERIAL_STRIDE-th vector of every directed set (`directed_dtc`: every 4 x CALC_SERIAL_STRIDE-th,
  SERIAL_THIN) + CALC_SERIAL_NRAND random vectors; LATENCY is then the full program's length on the serial
  unit (calc_prog.calc_latency(FULL without dsp)).

Builds: Compact 0 / 1 x CntWidth 16 / 12 (DtWidth 10), and full_serial (Dsp = 0, CntWidth 16: the groups
`serial` only; its random part includes aborted computations); pytest items: build x scenario group x
simulator, each in its own build directory (they run in parallel under pytest -n).
"""
from __future__ import annotations

import itertools
import math
import os
import random
import time
import zlib
from dataclasses import dataclass, replace
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge, Timer

from simrun import REPO, rtl_sources, run_sim, sims_to_run
from svpwm_model import config, fixed
from svpwm_model.calc_prog import calc_latency, expect_carry as calc_expect

# the simulator process learns its variant from the pytest item (extra_env); the pytest process does not need it
FEATURES = int(os.environ.get("SVPWM_CALC_FEATURES", str(config.FULL)))   # the build (svpwm_calc Features)
COMPACT = FEATURES == config.TINY                          # the tiny build (its own serial datapath)
SERIAL = not COMPACT and not config.has(FEATURES, "dsp")   # an engine program on the serial multiplier
# clocks from start_i (cycle c) to done_o (cycle c + LATENCY): the one place the test states it (the serial
# build: the length of the full program on the serial unit, calc_prog.calc_latency(its features))
LATENCY = calc_latency(FEATURES) if SERIAL else {False: fixed.SAMPLE_LEAD - 1, True: fixed.LITE_SAMPLE_LEAD - 1}[COMPACT]

CLK_NS = 10                  # the harness's clock period
# player records (tb_svpwm_calc.sv: the vector player): an input set, the control word's fields (offset, width)
CTL_W = 192
PIN_W = 280
REC_W = CTL_W + 3 * PIN_W
MAX_VEC = 65600
PIN_FIELDS = ((0, 3), (3, 3), (6, 16), (22, 16), (38, 16), (54, 16), (70, 16), (86, 16), (102, 16), (118, 16),
              (134, 16), (150, 2), (152, 16), (168, 16), (184, 3), (192, 16), (208, 16),   # Vec's mode .. hdf
              (224, 1), (225, 1), (232, 16), (248, 16), (264, 16))      # om, carry_en, carry a, b, c (16-bit slots)
assert PIN_FIELDS[-1][0] + PIN_FIELDS[-1][1] <= PIN_W
CTL_FIELDS = {"pre": (0, 2), "ak": (2, 9), "gap": (11, 2), "ast": (13, 1), "asec": (14, 3), "aang": (17, 16),
              "mid": (33, 1), "mk": (34, 9), "mst": (43, 1), "msec": (44, 3), "mang": (47, 16), "ssec": (63, 3),
              "sang": (66, 16), "esec": (82, 3), "ea": (85, 16), "eb": (101, 16), "ec": (117, 16),
              "esat": (133, 1), "eerr": (134, 1), "eca": (135, 16), "ecb": (151, 16), "ecc": (167, 16)}
P_MIN = 8                    # shortest period exercised (the RTL header states no minimum besides 2 thr)
FSHIFT = fixed.FREQ_WIDTH - 17
M_VERTEX = int(round(2 / math.sqrt(3) * fixed.M_ONE))        # 0x93CD, the hexagon vertex
ANGLES = (0, 1, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF)
MS = (0, 1, 0x4000, 0x7FFF, 0x8000, 0x8001, M_VERTEX, M_VERTEX + 1, 0xC000, 0xFFFF)
VS = (-32768, -32767, -28378, -16384, -8192, -1, 0, 1, 8192, 16384, 18919, 28378, 32767)


def icarus() -> bool:
    return cocotb.SIM_NAME.lower().startswith("icarus")


@dataclass(frozen=True)
class Vec:
    mode: int = fixed.MODE_FREQ
    sector: int = 0          # accumulator sector (FREQ, VF, compact)
    angle: int = 0           # accumulator theta', UQ0.16 of 60 deg (FREQ, VF, compact)
    theta: int = 0           # 16 bits = 360 deg (POLAR, DQ)
    m: int = 0               # UQ1.15 (FREQ, POLAR, compact)
    freq: int = 0            # signed frequency word (VF); the RTL gets |freq| >> FSHIFT
    v1: int = 0              # Q2.14 v_alpha / v_d
    v2: int = 0              # Q2.14 v_beta / v_q
    boost: int = 0
    slope: int = 0
    mmax: int = 0
    dpwm: int = 0
    period: int = P_MIN
    thr: int = 0
    isign: int = 0           # current signs {c, b, a}, 1 = negative (dead-time compensation)
    hdr: int = 0             # compensation: C - hdr for a positive current (0: off)
    hdf: int = 0             # compensation: C + hdf for a negative current (0: off)
    om: int = 0              # 1: the six-step overmodulation law (FREQ, VF, POLAR)
    carry_en: int = 0        # 1: add carry (0: carry_i is ignored, the model gets (0, 0, 0))
    carry: tuple[int, int, int] = (0, 0, 0)   # volt-second carry in per phase (a, b, c), signed DtWidth + 2 bits


def fabs(freq: int) -> int:
    """fabs_i as the core computes it from the signed frequency word."""
    return abs(freq) >> FSHIFT


class CalcTB:
    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.period_i)
        self.top = (1 << self.W) - 1
        self.thr_max = (1 << len(dut.thr_i)) - 2      # dead time + minimum pulse, each DtWidth bits
        self.hd_word = (1 << len(dut.hdr_i)) - 1      # the largest hdr_i / hdf_i word (DtWidth bits)
        self.hd_max = (self.hd_word + 2) >> 1         # the largest the core gives: ceil(dead time / 2)
        self.ew = len(dut.carry_i) // 3               # carry bits per phase (DtWidth + 2, signed)
        self.car_min, self.car_max = -(1 << (self.ew - 1)), (1 << (self.ew - 1)) - 1
        self.lat = LATENCY
        self.nplay = 0

    # ---- model and pins -------------------------------------------------------------------------------
    def dtc_carry(self, v: Vec) -> tuple[int, ...]:
        """Per phase what the calculator adds to the command: the compensation (+ hdf / - hdr) + the carry in."""
        return tuple((v.hdf if (v.isign >> ph) & 1 else -v.hdr) + (v.carry[ph] if v.carry_en else 0)
                     for ph in range(3))

    def expect(self, v: Vec) -> tuple[int, ...]:
        """(sector, C_a, C_b, C_c, sat, err, carry_a, carry_b, carry_c) of the golden model (Compact: carry 0)."""
        assert 2 * v.thr <= v.period <= self.top and v.thr <= self.thr_max and 0 <= v.sector < 6, v
        assert 0 <= v.isign < 8 and 0 <= v.hdr <= self.hd_word and 0 <= v.hdf <= self.hd_word, v
        assert all(self.car_min <= x <= self.car_max for x in v.carry) and v.om in (0, 1), v
        # the calculator adds compensation + carry in DtWidth + 2 bits signed (the core's amounts: |hd| <=
        # 2^(DtWidth-1), |carry| <= 2^DtWidth, RTL header), so a compensated vector keeps the sum in range too
        assert COMPACT or all(self.car_min <= x <= self.car_max for x in self.dtc_carry(v)), v
        inp = dict(period=v.period, thr=v.thr, sector=v.sector, a16=v.angle, m=v.m, mode=v.mode, freq=v.freq,
                   fabs=fabs(v.freq), theta=v.theta, v1=v.v1, v2=v.v2, vf_boost=v.boost, vf_slope=v.slope,
                   vf_mmax=v.mmax, dpwm=v.dpwm, isign=v.isign, hdr=v.hdr, hdf=v.hdf, om=v.om,
                   carry=v.carry if v.carry_en else (0, 0, 0))
        sec, c, sat, err, e = calc_expect(inp, FEATURES)
        if COMPACT:
            e = (0, 0, 0)                                   # the compact build drives carry_o to 0
        hthr = (v.thr + 1) >> 1
        assert all(0 <= x <= v.period for x in c) and all(-hthr <= x <= hthr for x in e), (v, c, e)
        return (sec, *c, int(sat), int(err), *e)

    def carry_out(self) -> tuple[int, int, int]:
        """carry_o per phase (a, b, c), signed."""
        w, ew = int(self.dut.carry_o.value), self.ew
        return tuple((((w >> (ph * ew)) & ((1 << ew) - 1)) ^ (1 << (ew - 1))) - (1 << (ew - 1)) for ph in range(3))

    def outputs(self) -> tuple[int, ...]:
        """(busy, done, sector, C_a, C_b, C_c, sat, err)."""
        d, W = self.dut, self.W
        cmp = int(d.cmp_o.value)
        return (int(d.busy_o.value), int(d.done_o.value), int(d.sector_o.value), cmp & self.top,
                (cmp >> W) & self.top, (cmp >> 2 * W) & self.top, int(d.sat_o.value), int(d.err_o.value))

    def drive(self, start: int, v: Vec) -> None:
        d = self.dut
        d.start_i.value = start
        d.mode_i.value = v.mode
        d.sector_i.value = v.sector
        d.angle_i.value = v.angle
        d.theta_i.value = v.theta
        d.m_i.value = v.m
        d.fabs_i.value = fabs(v.freq)
        d.v1_i.value = v.v1 & 0xFFFF
        d.v2_i.value = v.v2 & 0xFFFF
        d.vf_boost_i.value = v.boost
        d.vf_slope_i.value = v.slope
        d.vf_mmax_i.value = v.mmax
        d.dpwm_i.value = v.dpwm
        d.period_i.value = v.period
        d.thr_i.value = v.thr
        d.isign_i.value = v.isign
        d.hdr_i.value = v.hdr
        d.hdf_i.value = v.hdf
        d.om_i.value = v.om
        d.carry_en_i.value = v.carry_en
        d.carry_i.value = sum((x & ((1 << self.ew) - 1)) << (ph * self.ew) for ph, x in enumerate(v.carry))

    def drive_scrambled(self, start: int, v: Vec) -> None:
        """start_i and the inputs read at start_i only (sector_i, angle_i) of `scramble(v)`: what changes
        while busy (the other inputs hold)."""
        d = self.dut
        d.start_i.value = start
        d.sector_i.value = v.sector
        d.angle_i.value = v.angle

    # ---- stimulus ------------------------------------------------------------------------------------
    def junk(self, rng: random.Random) -> Vec:
        """Any input word at all (idle, or an aborted computation): sector 6, 7, P < 2 thr included."""
        return Vec(rng.randrange(8), rng.randrange(8), rng.randrange(1 << 16), rng.randrange(1 << 16),
                   rng.randrange(1 << 16), rng.randint(-fixed.FREQ_MAX, fixed.FREQ_MAX),
                   rng.randint(-32768, 32767), rng.randint(-32768, 32767), rng.randrange(1 << 16),
                   rng.randrange(1 << 16), rng.randrange(1 << 16), rng.randrange(4), rng.randrange(self.top + 1),
                   rng.randrange(self.thr_max + 2), rng.randrange(8), rng.randrange(self.hd_word + 1),
                   rng.randrange(self.hd_word + 1), rng.randrange(2), rng.randrange(2), self.rand_carry(rng))

    def rand_carry(self, rng: random.Random) -> tuple[int, int, int]:
        """Any carry word (DtWidth + 2 bits signed per phase)."""
        return tuple(rng.randint(self.car_min, self.car_max) for _ in range(3))

    def carry_in(self, v: Vec, rng: random.Random) -> Vec:
        """v with a volt-second carry: half of the vectors carry_en 1, carry within +-(ceil(thr / 2) + 1) (one
        beyond the largest carry out), 20 % of those anywhere in the DtWidth + 2 bits with compensation + carry
        in range (RTL header); the other half carry_en 0 with a random carry word (ignored) half of the time."""
        if rng.random() < 0.5:
            return replace(v, carry_en=0, carry=self.rand_carry(rng) if rng.random() < 0.5 else (0, 0, 0))
        lim = ((v.thr + 1) >> 1) + 1
        if rng.random() < 0.2:                                   # the full word, the sum kept in range
            hd = self.dtc_carry(replace(v, carry_en=0))
            car = tuple(rng.randint(self.car_min - min(h, 0), self.car_max - max(h, 0)) for h in hd)
        else:
            car = tuple(rng.choice((-lim, lim, 0)) if rng.random() < 0.25 else rng.randint(-lim, lim)
                        for _ in range(3))
        return replace(v, carry_en=1, carry=car)

    @staticmethod
    def scramble(v: Vec, rng: random.Random) -> Vec:
        """v with the inputs read at start_i only scrambled (what the calculator must ignore while busy)."""
        return replace(v, sector=rng.randrange(8), angle=rng.randrange(1 << 16))

    def ignored(self, v: Vec, rng: random.Random) -> Vec:
        """Compact: random words on the inputs the compact variant ignores; full: v."""
        if not COMPACT:
            return v
        return replace(v, mode=rng.randrange(8), theta=rng.randrange(1 << 16),
                       freq=rng.randint(-fixed.FREQ_MAX, fixed.FREQ_MAX), v1=rng.randint(-32768, 32767),
                       v2=rng.randint(-32768, 32767), boost=rng.randrange(1 << 16), slope=rng.randrange(1 << 16),
                       mmax=rng.randrange(1 << 16), dpwm=rng.randrange(4), isign=rng.randrange(8),
                       hdr=rng.randrange(self.hd_word + 1), hdf=rng.randrange(self.hd_word + 1),
                       om=rng.randrange(2), carry_en=rng.randrange(2), carry=self.rand_carry(rng))

    def p_thr(self, rng: random.Random) -> tuple[int, int]:
        """A legal (P, thr), snapping likely."""
        r = rng.random()
        p = P_MIN if r < 0.03 else self.top if r < 0.08 else \
            rng.randint(P_MIN, min(self.top, 4 * self.thr_max)) if r < 0.5 else rng.randint(P_MIN, self.top)
        tmax = min(self.thr_max, p // 2)
        r = rng.random()
        return p, (tmax if r < 0.1 else 0 if r < 0.15 else rng.randint(0, tmax))

    def rand_vec(self, rng: random.Random) -> Vec:
        """A legal random vector: every mode incl. 5..7 (full), DPWM, V/f, saturation, the overmodulation law
        (om random), the compensation (half), the carry in (carry_in); compact: junk on the ignored inputs."""
        fm = fixed.FREQ_MAX
        p, t = self.p_thr(rng)
        r = rng.random()
        m = rng.randrange(1 << 16) if r < 0.5 else rng.randint(0, M_VERTEX + 64) if r < 0.8 \
            else rng.randint(0xF000, 0xFFFF)
        if COMPACT:
            return self.ignored(Vec(sector=rng.randrange(6), angle=rng.randrange(1 << 16), m=m, period=p, thr=t), rng)
        mode = rng.choice((0, 0, 1, 1, 2, 2, 3, 3, 3, 4, 4, 4, 5, 6, 7))
        if rng.random() < 0.5:                                   # uniform words
            v1, v2 = rng.randint(-32768, 32767), rng.randint(-32768, 32767)
        else:                                                    # uniform magnitude 0 .. 1.99, any angle
            mag, ph = rng.uniform(0, 1.99) * fixed.V_ONE, rng.uniform(0, 2 * math.pi)
            v1, v2 = (max(-32768, min(32767, round(mag * f(ph)))) for f in (math.cos, math.sin))
        freq = rng.randint(-fm, fm) if rng.random() < 0.5 else rng.randint(-(1 << 20), 1 << 20)
        isign, hdr, hdf = 0, 0, 0
        if rng.random() < 0.5:                                   # dead-time compensation (else off: 0 / 0)
            hd = (0, 1, min(self.hd_max, (t + 1) // 2), self.hd_max)
            isign = rng.randrange(8)
            hdr, hdf = (rng.choice(hd) if rng.random() < 0.4 else rng.randint(0, self.hd_max) for _ in range(2))
        v = Vec(mode, rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16), m, freq, v1, v2,
                rng.randrange(0x4000), rng.randrange(1 << 16) >> rng.randrange(17),
                rng.choice((rng.randrange(1 << 16), 0x8000, M_VERTEX, 0xFFFF)), rng.randrange(4), p, t,
                isign, hdr, hdf, rng.randrange(2))
        return self.carry_in(v, rng)

    # ---- runs ----------------------------------------------------------------------------------------
    async def reset(self) -> None:
        dut = self.dut
        self.drive(0, Vec())
        dut.abort_i.value = 0
        dut.play_i.value = 0
        dut.latency_i.value = self.lat
        dut.rst_ni.value = 0
        await FallingEdge(dut.clk)
        await FallingEdge(dut.clk)
        dut.rst_ni.value = 1
        assert self.outputs()[:2] == (0, 0)

    def check_harness(self, what: str) -> None:
        chk, cyc = int(self.dut.chk_o.value), int(self.dut.err_cyc_o.value)
        assert chk == 0, (f"{what}: harness checker chk_o = {chk:03b} at clock {cyc} after reset (bit 0: busy_o, "
                          f"bit 1: done_o differ from the handshake with LATENCY = {self.lat}; bit 2: the test "
                          f"changed a held input while busy)")

    async def aborted_start(self, rng: random.Random, k: int) -> None:
        """Start junk, abort_i k clocks after the start edge (k = 0: together with start_i, which then is not
        accepted; k = LATENCY - 2, - 1: in the last busy clocks, so no done_o must follow); sector_i / angle_i
        scrambled while busy, start_i random. busy_o and done_o low afterwards."""
        dut = self.dut
        v = self.junk(rng)
        self.drive(1, v)
        dut.abort_i.value = int(k == 0)
        await FallingEdge(dut.clk)
        if k:
            self.drive(int(rng.random() < 0.5), self.scramble(v, rng))
            await Timer((k - 1) * CLK_NS + 2, "ns")            # 2 ns after falling edge k (before rising edge k)
            dut.abort_i.value = 1
            await FallingEdge(dut.clk)
        self.drive(0, self.junk(rng))                           # idle: anything
        dut.abort_i.value = 0
        got = self.outputs()
        assert got[:2] == (0, 0), f"abort {k} clocks after the start: busy_o, done_o = {got[:2]}, expected idle"
        await FallingEdge(dut.clk)                              # no done_o on its way
        assert self.outputs()[:2] == (0, 0), f"abort {k} clocks after the start: busy_o / done_o after the abort"

    @staticmethod
    def pins(v: Vec) -> int:
        """The calculator's input word of `v` in a player record (tb_svpwm_calc.sv: PinW; PIN_FIELDS)."""
        word = 0
        for (off, w), x in zip(PIN_FIELDS, (v.mode, v.sector, v.angle, v.theta, v.m, fabs(v.freq), v.v1 & 0xFFFF,
                                            v.v2 & 0xFFFF, v.boost, v.slope, v.mmax, v.dpwm, v.period, v.thr,
                                            v.isign, v.hdr, v.hdf, v.om, v.carry_en,
                                            *(x & 0xFFFF for x in v.carry)), strict=True):
            assert 0 <= x < (1 << w), (v, off, x)
            word |= x << off
        return word

    def record(self, i: int, v: Vec, exp: tuple[int, ...], rng: random.Random) -> tuple[int, dict]:
        """Vector i's player record (tb_svpwm_calc.sv: CtlW, the vector, junk A, junk B), its schedule drawn
        from rng: 3 % an aborted junk computation before it (abort_i k = 0 .. LATENCY-1 clocks after its
        start; sector_i / angle_i scrambled and start_i random while that is busy), 2 % an idle gap of 1..3
        clocks with every input scrambled; one clock after the start sector_i / angle_i scrambled with start_i
        high, and 25 % of the vectors once more at a random clock mid-computation with start_i random."""
        lat = self.lat
        ctl, junk_a, junk_b = {}, Vec(), Vec()
        r = rng.random()
        if r < 0.03:                                        # a junk computation aborted after k clocks
            k = rng.randint(0, lat - 1)
            junk_a = self.junk(rng)
            ctl.update(pre=1, ak=k)
            if k:
                ctl["ast"] = int(rng.random() < 0.5)
                sc = self.scramble(junk_a, rng)
                ctl.update(asec=sc.sector, aang=sc.angle)
            junk_b = self.junk(rng)
        elif r < 0.05:                                      # an idle gap, every input scrambled
            junk_a = self.junk(rng)
            ctl.update(pre=2, gap=rng.randint(1, 3))
        sc = self.scramble(v, rng)                          # start_i held high: ignored while busy
        ctl.update(ssec=sc.sector, sang=sc.angle)
        if lat > 4 and rng.random() < 0.25:                 # scramble once more mid-computation
            ctl.update(mid=1, mk=rng.randint(1, lat - 3))
            ctl["mst"] = int(rng.random() < 0.5)
            sc = self.scramble(v, rng)
            ctl.update(msec=sc.sector, mang=sc.angle)
        sec, ca, cb, cc, sat, err, e_a, e_b, e_c = exp
        ctl.update(esec=sec, ea=ca, eb=cb, ec=cc, esat=sat, eerr=err, eca=e_a & 0xFFFF, ecb=e_b & 0xFFFF,
                   ecc=e_c & 0xFFFF)
        word = 0
        for k, val in ctl.items():
            off, w = CTL_FIELDS[k]
            assert 0 <= val < (1 << w), (k, val)
            word |= val << off
        word |= (self.pins(v) | (self.pins(junk_a) << PIN_W if ctl.get("pre") else 0)
                 | (self.pins(junk_b) << 2 * PIN_W if ctl.get("pre") == 1 else 0)) << CTL_W
        return word, ctl

    async def run_vectors(self, vecs: list[Vec], rng: random.Random, name: str) -> None:
        """The harness's player runs the vectors back to back with their schedules (`record`), the model's
        results in each record; it checks every vector in its clock (module docstring: `run_vectors`)."""
        dut, lat = self.dut, self.lat
        t0 = time.perf_counter()
        exps = [self.expect(v) for v in vecs]
        recs = [self.record(i, v, e, rng) for i, (v, e) in enumerate(zip(vecs, exps))]
        assert len(vecs) <= MAX_VEC
        self.nplay += 1
        f = Path(f"calc_stim_{os.getpid()}_{self.nplay}.hex")     # cwd: the item's own sim directory
        f.write_text("".join(f"{w:0{REC_W // 4}x}\n" for w, _ in recs))
        t1 = time.perf_counter()
        assert len(str(f)) <= len(dut.stim_file_i) // 8, f
        dut.stim_file_i.value = int.from_bytes(str(f).encode(), "big")
        dut.stim_n_i.value = len(vecs)
        end = int(dut.play_end_o.value)
        dut.play_i.value = 1
        while int(dut.play_end_o.value) == end:
            await dut.play_end_o.value_change
        dut.play_i.value = 0
        f.unlink()
        nfail = int(dut.fail_n_o.value)
        if nfail:
            i, what, got = int(dut.fail_idx_o.value), int(dut.fail_what_o.value), int(dut.fail_got_o.value)
            ew, wc = self.ew, int(dut.fail_car_o.value)
            car = tuple((((wc >> (ph * ew)) & ((1 << ew) - 1)) ^ (1 << (ew - 1))) - (1 << (ew - 1)) for ph in range(3))
            W, ctl = self.W, recs[i][1]
            got = ((got >> (3 * W + 6)) & 1, (got >> (3 * W + 5)) & 1, (got >> (3 * W + 2)) & 7,
                   (got >> 2) & self.top, (got >> (W + 2)) & self.top, (got >> (2 * W + 2)) & self.top,
                   (got >> 1) & 1, got & 1)
            what = {1: "busy_o, done_o one clock after the start != (1, 0)",
                    2: f"RTL (busy, done, sector, Ca, Cb, Cc, sat, err) != (0, 1, model {exps[i][:6]}) (LATENCY {lat}: "
                       f"done_o expected {(lat - 1) * CLK_NS} ns after the start edge)",
                    3: f"busy_o, done_o after the abort at {ctl.get('ak')} clocks != (0, 0)",
                    4: f"busy_o, done_o in the clock after the abort at {ctl.get('ak')} clocks != (0, 0)",
                    5: f"carry_o {car} at done_o + 2 != model {exps[i][6:]} (the player stopped after the next "
                       f"vector: the check falls in its computation)"}[what]
            raise AssertionError(f"{name}: the player stopped at vector {i} of {len(vecs)} ({nfail} failed check(s) "
                                 f"there), the first: {vecs[i]} "
                                 f"(schedule {ctl}): {what}; RTL outputs (busy, done, sector, Ca, Cb, Cc, sat, err) "
                                 f"= {got}")
        self.check_harness(name)
        dut._log.info("%s: %d vectors == model in %.1f s (LATENCY %d; records %.1f s)", name, len(vecs),
                      time.perf_counter() - t0, lat, t1 - t0)

    async def protocol(self, sched: list[tuple[int, int, Vec]], min_starts: int) -> None:
        """Every clock: busy_o, done_o against a reference of the handshake for the schedule of (start_i,
        abort_i, inputs) per clock, the results in every done cycle and carry_o two clocks later against the
        model. While the reference is busy the held inputs of the accepted vector are driven (sector_i /
        angle_i from the schedule); in a done cycle thr_i keeps its value (a vector started there gets its
        thr_i one clock late: the carry limit reads thr_i in the done cycle, tb_svpwm_calc.sv)."""
        dut, lat = self.dut, self.lat
        st, done, latch, starts, aborted, car_chk, thr = 0, 0, None, 0, 0, None, 0
        for cyc, (start, abort, v) in enumerate(sched):
            got = self.outputs()
            assert got[:2] == (int(st != 0), done), f"cycle {cyc}: busy_o, done_o = {got[:2]}, reference " \
                                                    f"{(int(st != 0), done)}"
            if done:
                exp = self.expect(latch)
                assert got[2:] == exp[:6], f"cycle {cyc} {latch}: RTL results {got[2:]}, model {exp[:6]}"
                car_chk = (cyc + 2, latch, exp[6:])
            if car_chk and car_chk[0] == cyc:
                assert self.carry_out() == car_chk[2], f"cycle {cyc} {car_chk[1]}: RTL carry_o at done_o + 2 " \
                                                      f"{self.carry_out()}, model {car_chk[2]}"
            if st:
                v = replace(latch, sector=v.sector, angle=v.angle)
            self.drive(start, replace(v, thr=thr) if done and not COMPACT else v)
            thr = thr if done and not COMPACT else v.thr
            dut.abort_i.value = abort
            done = 0                                            # the reference's next cycle
            if abort:
                aborted += st != 0
                st = 0
            elif st == lat - 1:
                st, done = 0, 1
            elif st:
                st += 1
            elif start:
                st, latch = 1, v
                starts += 1
            await FallingEdge(dut.clk)
        assert st == 0 and not done, "schedule ends busy"
        assert starts >= min_starts, f"only {starts} starts accepted"
        self.check_harness("protocol")
        dut._log.info("protocol: %d clocks, %d starts (%d aborted), LATENCY %d", len(sched), starts, aborted, lat)


# ---- directed vectors -------------------------------------------------------------------------------------

def corners(top: int, thr_max: int) -> tuple[list[tuple[int, int]], list[tuple[int, int]]]:
    """(P, thr) corners: (those with P = 2^CntWidth - 1, the others): small periods, P = 2 thr (the boundary)
    with thr 0 / 1 / odd / even / largest, the top period with thr 0, 1, 113, the largest."""
    out = [(P_MIN, 0), (P_MIN, 4), (P_MIN, 3), (9, 4), (48, 0), (48, 7), (48, 24), (1000, 0), (1000, 37),
           (2 * thr_max, thr_max), (2 * thr_max - 1, thr_max - 1), (2 * 101, 101), (2 * 100, 100)]
    lo = [(p, t) for p, t in out if 2 * t <= p < top]
    hi = [(top, t) for t in (0, 1, 113, thr_max) if 2 * t <= top]
    return hi, lo


def spread(base: list[Vec], hi, lo, dpwm: bool = True) -> list[Vec]:
    """Every vector of `base` once: DPWM cycled (full), (P, thr) alternating between the top-P corners and
    the others, each list cycled."""
    out = []
    for i, v in enumerate(base):
        k = i // 4 if dpwm else i
        p, t = (hi[(k // 2) % len(hi)] if k % 2 == 0 else lo[(k // 2) % len(lo)])
        out.append(replace(v, dpwm=(i % 4) if dpwm else v.dpwm, period=p, thr=t))
    return out


def boundary_thetas() -> list[int]:
    """theta at every 30 deg (k 2^16 / 12, rounded) +- 3 LSB: theta' near 0, 60 deg - 1 and 30 deg, all sectors.
    (6 theta is even, so theta' = 0 exactly only at 0 / 180 deg and theta' = 30 deg exactly only at
    theta = 16384 / 49152; theta' = 60 deg - 2 LSB is the largest reachable.)"""
    return sorted({(round(k * 65536 / 12) + d) & 0xFFFF for k in range(12) for d in range(-3, 4)})


BOUNDARY = frozenset(boundary_thetas())


def ab_on_lines() -> list[tuple[int, int]]:
    """(v_alpha, v_beta) exactly on a 60 deg sector line: Z = v_beta/2 - sqrt3/2 v_alpha = 0 or Y = 0 in the
    RTL's integers (a projection q_k exactly 0: the tie in the sector search)."""
    out = []
    for va in (-32768, -30001, -20000, -9999, -2, 2, 9998, 20000, 30000, 32767):
        a = fixed._mul_v(va, fixed.SQRT3_2)
        if a % 2 == 0 and -32768 <= a // 2 <= 32767:
            out += [(va, a // 2), (va, -(a // 2))]
    return out


DTC_MS = (0, 0x4000, M_VERTEX)       # the dead-time compensation set's m: the zero vector, inside, the vertex


def dtc_settings(top: int, hd_max: int) -> list[tuple[int, int, int, int]]:
    """(hdr, hdf, thr, P) of the dead-time compensation set: small / equal / extreme amounts (hd_max = the
    largest the core gives, ceil(dead time / 2)) at P = 1536 and a small P = 2 thr (P_MIN for thr 0); thr =
    2 hd_max - 1 (P = 1536 < 2 thr: P = 2 thr instead) and hdf = hd_max also at the top P (C + hdf beyond P)."""
    b = 2 * hd_max - 1
    out = [(3, 5, 10, 1536), (3, 5, 10, 20), (24, 24, 48, 1536), (24, 24, 48, 96), (hd_max, 1, b, 2 * b),
           (hd_max, 1, b, top), (0, hd_max, 0, 1536), (0, hd_max, 0, P_MIN), (1, hd_max, 2, top)]
    assert all(2 * t <= p <= top for _, _, t, p in out)
    return out


# the carry set: (m, DPWM) with phases at a rail (m near 0: DPWMMIN clamps one phase to 0 and keeps the others
# near it, DPWMMAX the same at P; m near 1 in SVPWM: phases near 0 and P) x thr x the carry in patterns
CARRY_RAILS = ((0, 1), (1, 1), (0x0100, 1), (0, 2), (1, 2), (0x0100, 2), (0x7FFF, 0), (0x8000, 0), (M_VERTEX, 0))
CARRY_THRS = (0, 1, 30, 255)


def carry_patterns(thr: int) -> list[tuple[int, tuple[int, int, int]]]:
    """(carry_en, carry in) of the carry set at thr: every value of 0, +-limit, +-(limit + 1) (limit =
    ceil(thr / 2), the largest carry out) on every phase, all three equal and mixed; and carry_en 0 with a
    carry word that must be ignored."""
    lim = (thr + 1) >> 1
    vals = (0, lim, -lim, lim + 1, -(lim + 1))
    out = [(1, (x, x, x)) for x in vals]
    out += [(1, (vals[i], vals[(i + 1) % 5], vals[(i + 3) % 5])) for i in range(5)]
    return out + [(0, (lim + 1, -(lim + 1), lim))]


# the six-step law: m from 1 to the top around the vertex magnitude (g = 1 + (m - M_VERTEX) / 128 above it)
OM_MS = (0x8000, 0x9000, M_VERTEX - 1, M_VERTEX, M_VERTEX + 1, M_VERTEX + 2, 0x9800, 0xA000, 0xB000, 0xC000,
         0xE000, 0xFFFE, 0xFFFF)


def directed(key: str, top: int, thr_max: int, hd_max: int) -> list[Vec]:
    hi, lo = corners(top, thr_max)
    ndp = 1 if COMPACT else 4
    F, VF, PO, AB, DQ = fixed.MODE_FREQ, fixed.MODE_VF, fixed.MODE_POLAR, fixed.MODE_AB, fixed.MODE_DQ
    if key == "freq":            # sector x theta' x m (x DPWM) x two (P, thr) corners, one at the top P
        out, i = [], 0
        for s, a, m in itertools.product(range(6), ANGLES, MS):
            for d in range(ndp):
                for p, t in (hi[i % len(hi)], lo[(i * 5) % len(lo)]):
                    out.append(Vec(F, s, a, m=m, dpwm=d, period=p, thr=t))
                i += 1
        return out
    if key == "corners":         # every corner x 5 references (x DPWM); ROM interval ends
        out = [Vec(F, s, a, m=m, dpwm=d, period=p, thr=t) for p, t in hi + lo
               for s, a, m in ((0, 0, 0), (1, 0x8000, 0x8000), (5, 0xFFFF, 0xFFFF), (2, 1, M_VERTEX),
                               (4, 0x4000, 0x93CE)) for d in range(ndp)]
        for k in range(0, 257, 8):
            for a in ((k << 8) - 1, k << 8):
                if 0 <= a <= 0xFFFF:
                    out.append(Vec(F, k % 6, a, m=(M_VERTEX, 0xFFFF)[k & 1], dpwm=k % ndp, period=top,
                                   thr=(k * 7) % (thr_max + 1)))
        return out
    if key == "dtc":             # dead-time compensation: every isign x sector x m x DPWM x (hdr, hdf, thr, P)
        sets = dtc_settings(top, hd_max)
        if COMPACT:              # ignored there: every isign x sector once, the settings and m cycled
            return [Vec(F, s, ANGLES[(8 * s + g) % len(ANGLES)], m=DTC_MS[(8 * s + g) % 3], period=p, thr=t,
                        isign=g, hdr=r, hdf=f)
                    for s in range(6) for g in range(8) for r, f, t, p in [sets[(8 * s + g) % len(sets)]]]
        out, i = [], 0
        for (r, f, t, p), m, d, s, g in itertools.product(sets, DTC_MS, range(ndp), range(6), range(8)):
            out.append(Vec(F, s, ANGLES[i % len(ANGLES)], m=m, dpwm=d, period=p, thr=t, isign=g, hdr=r, hdf=f))
            i += 1
        return out
    if key == "carry":           # the volt-second carry near both rails: (m, DPWM) x thr x carry in, two P
        out, i = [], 0
        for (m, d), t in itertools.product(CARRY_RAILS, CARRY_THRS):
            pats = carry_patterns(t)
            if COMPACT:              # ignored (carry_o 0): every (m, thr) once, the patterns cycled
                pats = pats[i % len(pats):][:1]
            for (en, car), p in itertools.product(pats, (1000, top)):
                out.append(Vec(F, i % 6, ANGLES[(i // 6) % len(ANGLES)], m=m, dpwm=d, period=p, thr=t,
                               carry_en=en, carry=car))
                i += 1
        return out
    assert not COMPACT, key
    fm = fixed.FREQ_MAX
    if key == "om":              # the six-step law (om = 1): FREQ, VF, POLAR; AB and DQ keep the clamp
        om = [Vec(F, s, a, m=m) for s, a, m in itertools.product(range(6), ANGLES, OM_MS)]
        for i, m in enumerate(OM_MS):
            for j in range(3):
                k = 3 * i + j
                om += [Vec(VF, k % 6, ANGLES[k % len(ANGLES)], freq=(k - 20) << FSHIFT, boost=m, slope=0,
                           mmax=0xFFFF),                                         # m = boost
                       Vec(VF, (k + 3) % 6, ANGLES[(k + 3) % len(ANGLES)], freq=-(0x3000 << FSHIFT) - k,
                           boost=0x4000, slope=0xFFFF, mmax=m)]                  # m = mmax
        om += [Vec(PO, theta=(round(k * 65536 / 12) + d) & 0xFFFF, m=m)
               for k in range(12) for d in (-1, 0, 1) for m in OM_MS]
        for r in (1.0, 2 / math.sqrt(3), 1.2, 1.5, 1.99):
            for k in range(4):
                ph = math.radians(97 * k + 7 * r)
                om.append(Vec(AB, v1=max(-32768, min(32767, round(r * fixed.V_ONE * math.cos(ph)))),
                              v2=max(-32768, min(32767, round(r * fixed.V_ONE * math.sin(ph))))))
        om += [Vec(AB, v1=a, v2=b) for a, b in ((-32768, -32768), (32767, 32767), (-32768, 32767), (32767, 0))]
        om += [Vec(DQ, theta=(k * 21845 + 1000) & 0xFFFF, v1=a, v2=b) for k in range(3)
               for a, b in ((0x4000, 0), (0, 0x4000), (32767, 32767), (-32768, -32768), (-32768, 32767),
                            (12345, -23456), (M_VERTEX // 2, 0), (0x7000, 0x3000))]
        return [replace(v, om=1) for v in spread(om, hi, lo)]
    if key == "vf":              # the law (f = 0 -> boost, linear, at / beyond mmax, sign, extremes)
        laws = [(0x0800, 0x0100, 0x8000), (0x0800, 0x0181, 0x93CD), (0x1000, 0x0100, 0x8000),
                (0x9000, 0x0010, 0x8000), (0, 0, 0), (0xFFFF, 0xFFFF, 0xFFFF), (0x0123, 0xFFFF, 0xFFFF),
                (0x4000, 0x0001, 0x0000), (0, 0x0080, 0xFFFF)]
        freqs = (0, 1, (1 << FSHIFT) - 1, 1 << FSHIFT, -(1 << FSHIFT), 0x3000 << FSHIFT, -(0x3000 << FSHIFT),
                 (0x6FFF << FSHIFT) + 5, 0x7000 << FSHIFT, -((0x7000 << FSHIFT) + 127), 0x7001 << FSHIFT,
                 0x8000 << FSHIFT, fm, -fm, 123456, -123456)
        return spread([Vec(VF, (i * 5) % 6, ANGLES[i % len(ANGLES)], freq=f, boost=b, slope=s, mmax=mx)
                       for i, ((b, s, mx), f) in enumerate(itertools.product(laws, freqs))], hi, lo)
    if key == "polar":           # every 30 deg +- 3 LSB x m; a full revolution in 257-LSB steps
        ms = (0, 0x4000, 0x8000, M_VERTEX, M_VERTEX + 1, 0xFFFF)
        po = [Vec(PO, theta=t, m=m) for t in boundary_thetas() for m in ms]
        po += [Vec(PO, theta=t, m=m) for t in range(0, 1 << 16, 257) for m in (0x8000, M_VERTEX)]
        return spread(po, hi, lo)
    if key == "ab":              # grid (extremes, zero), rings at every 30 deg +- a little, exact sector lines
        ab = [(a, b) for a in VS for b in VS]
        for r in (0.5, 1.0, 2 / math.sqrt(3), 1.5, 1.99):
            for k in range(12):
                for d in (-1e-4, 0.0, 1e-4):
                    ph = math.radians(30 * k) + d
                    ab.append(tuple(max(-32768, min(32767, round(r * fixed.V_ONE * f(ph))))
                                    for f in (math.cos, math.sin)))
        ab += ab_on_lines()
        return spread([Vec(AB, v1=a, v2=b) for a, b in ab], hi, lo)
    if key == "dq":              # vector grid x theta at every 30 deg +- 3 (incl. theta' = 30 deg), a revolution
        dqv = [(0, 0), (0x4000, 0), (0, 0x4000), (-0x4000, 0), (0, -0x4000), (32767, 32767), (-32768, -32768),
               (-32768, 32767), (32767, -32768), (1, 0), (0, 1), (-1, -1), (12345, -23456), (M_VERTEX // 2, 0)]
        dq = [Vec(DQ, theta=t, v1=a, v2=b) for t in boundary_thetas() for a, b in dqv]
        dq += [Vec(DQ, theta=t, v1=a, v2=b) for t in range(0, 1 << 16, 257)
               for a, b in ((0x4000, 0), (9000, 30000), (-32768, -32768))]
        return spread(dq, hi, lo)
    if key == "invalid":         # zero vector + err_o whatever the other inputs, every DPWM x 4 corners
        rng = random.Random(5)
        bad = [Vec(md, rng.randrange(6), rng.randrange(1 << 16), rng.randrange(1 << 16), rng.randrange(1 << 16),
                   rng.randint(-fm, fm), rng.randint(-32768, 32767), rng.randint(-32768, 32767),
                   0x8000, 0x100, 0xFFFF) for md in (5, 6, 7) for _ in range(2)]
        pts = hi[:1] + hi[-1:] + lo[:1] + lo[-5:-4]
        return [replace(v, dpwm=d, period=p, thr=t) for v in bad for d in range(4) for p, t in pts]
    raise KeyError(key)


# ---- cocotb tests -----------------------------------------------------------------------------------------

DIRECTED = ("freq", "corners", "dtc", "carry", "vf", "polar", "ab", "dq", "invalid", "om")   # vf ..: full only


# Icarus (~22 us per clock of the busy calculator, the simulator's own evaluation of the RTL: see the module
# docstring) runs a complete subset of the four large sets: every ICARUS_STRIDE-th vector and, in list order,
# every vector that is the first of a category (below) no kept vector has covered yet. Verilator runs them all.
ICARUS_STRIDE = 3
ICARUS_STRIDES = {"dtc": 64, "carry": 16, "om": 32}   # sets whose categories below already are most of the subset
_CAT_COMMON = (lambda v: (v.period, v.thr), lambda v: v.dpwm)
CATEGORIES = {
    "freq":  (lambda v: (v.sector, v.angle, v.m),),                            # every sector x theta' x m
    "polar": (lambda v: v.theta, lambda v: v.m, lambda v: (v.theta in BOUNDARY, v.m)),   # every theta, every m
    "dq":    (lambda v: v.theta, lambda v: (v.v1, v.v2), lambda v: (v.theta in BOUNDARY, v.v1, v.v2)),
    # every isign x sector (the sector fixes each phase's class hi / lo / mid: every sign x class pattern)
    # x DPWM setting (the clamped phase with either sign), every isign and every m at every (hdr, hdf, thr, P)
    "dtc":   (lambda v: (v.isign, v.sector, v.dpwm), lambda v: (v.isign, v.hdr, v.hdf, v.thr, v.period),
              lambda v: (v.m, v.hdr, v.hdf, v.thr, v.period)),
    # every rail case (m, DPWM) at every thr, every carry in pattern at every thr
    "carry": (lambda v: (v.m, v.dpwm, v.thr), lambda v: (v.thr, v.carry_en, v.carry)),
    # every m of every mode (VF: both laws; AB, DQ: every vector), every sector x angle corner (FREQ) and
    # theta (POLAR)
    "om":    (lambda v: (v.mode, v.m, v.boost, v.mmax, v.v1, v.v2),
              lambda v: (v.mode, v.sector, v.angle) if v.mode == fixed.MODE_FREQ
              else (v.mode, v.theta) if v.mode == fixed.MODE_POLAR else v.mode),
}


def icarus_subset(key: str, vecs: list[Vec], stride: int) -> list[Vec]:
    """`vecs` itself for stride 1 or a set not in CATEGORIES; else every stride-th vector plus the first vector
    of every category (CATEGORIES[key] and the common ones: (P, thr) corner, DPWM setting) not yet covered."""
    if stride <= 1 or key not in CATEGORIES:
        return vecs
    cats = _CAT_COMMON + CATEGORIES[key]
    seen: list[set] = [set() for _ in cats]
    out = []
    for i, v in enumerate(vecs):
        ks = [c(v) for c in cats]
        if i % stride == 0 or any(k not in s for k, s in zip(ks, seen)):
            out.append(v)
            for k, s in zip(ks, seen):
                s.add(k)
    return out


def _directed_test(key: str):
    async def t(dut):
        tb = CalcTB(dut)
        vecs = directed(key, tb.top, tb.thr_max, tb.hd_max)
        default = ICARUS_STRIDES.get(key, ICARUS_STRIDE) if icarus() else 1
        stride = int(os.environ.get("CALC_DIRECTED_STRIDE", default))
        sub = icarus_subset(key, vecs, stride)
        if len(sub) < len(vecs):
            dut._log.info("%s: %d of the %d vectors (stride %d + every category)", key, len(sub), len(vecs), stride)
        await tb.reset()
        await tb.run_vectors(sub, random.Random(zlib.crc32(key.encode())), key)
    t.__name__ = t.__qualname__ = f"directed_{key}"
    t.__doc__ = f"Directed vectors, set {key!r} (module docstring)."
    return cocotb.test()(t)


for _k in DIRECTED:
    globals()[f"directed_{_k}"] = _directed_test(_k)


@cocotb.test()
async def angle_sweep(dut):
    """Every in-sector angle 0 .. 0xFFFF (Verilator; every 61st on Icarus) at the vertex m and beyond, random
    sector, (P, thr) and DPWM, the six-step law on and off (om: every other 4 angles), the carry in as the
    random vectors: every ROM interval and interpolation fraction, both clamp branches, the law's gain."""
    tb = CalcTB(dut)
    rng = random.Random(0x5EE9 + tb.W)
    step = int(os.environ.get("CALC_SWEEP_STEP", 61 if icarus() else 1))
    vecs = []
    for a in range(0, 1 << 16, step):
        p, t = tb.p_thr(rng)
        m = (M_VERTEX, M_VERTEX + 1, 0xFFFF, rng.randrange(1 << 16))[a & 3]
        v = Vec(sector=rng.randrange(6), angle=a, m=m, dpwm=rng.randrange(4), period=p, thr=t, om=(a >> 2) & 1)
        vecs.append(tb.ignored(tb.carry_in(v, rng), rng))
    await tb.reset()
    await tb.run_vectors(vecs, rng, "angle sweep")


@cocotb.test()
async def random_vectors(dut):
    """Seeded random vectors (module docstring); CALC_NRAND overrides the count."""
    tb = CalcTB(dut)
    n = int(os.environ.get("CALC_NRAND", 1000 if icarus() else 50000))
    rng = random.Random(0xCA1C + tb.W + (COMPACT << 8))
    await tb.reset()
    await tb.run_vectors([tb.rand_vec(rng) for _ in range(n)], rng, "random")


SERIAL_THIN = {"dtc": 4}     # the compensation adds no product: a quarter of the usual share (and half the random)


@cocotb.test()
async def serial_vectors(dut):
    """The full program on the serial multiplier (Dsp = 0, which no core builds): every SERIAL_STRIDE-th
    vector of every directed set and seeded random vectors, == model; the multiplier's products reach
    every result, so a wrong product, shift or iteration count fails here."""
    tb = CalcTB(dut)
    stride = int(os.environ.get("CALC_SERIAL_STRIDE", 23 if icarus() else 5))
    rng = random.Random(0x5E71 + tb.W)
    vecs = [v for k in DIRECTED
            for v in directed(k, tb.top, tb.thr_max, tb.hd_max)[::stride * SERIAL_THIN.get(k, 1)]]
    vecs += [tb.rand_vec(rng) for _ in range(int(os.environ.get("CALC_SERIAL_NRAND", 60 if icarus() else 600)))]
    await tb.reset()
    await tb.run_vectors(vecs, rng, "serial")


@cocotb.test()
async def protocol(dut):
    """Every clock against the reference: single starts with gaps, start_i held high with inputs changing
    every clock (ignored while busy, back-to-back restarts), random start pulses, aborts."""
    tb = CalcTB(dut)
    lat = tb.lat
    rng = random.Random(0xB05 + tb.W)
    await tb.reset()
    sched = []
    for gap in (0, 1, 2, 15):                                 # single start pulses
        sched += [(1, 0, tb.rand_vec(rng))] + [(0, 0, tb.junk(rng)) for _ in range(lat - 1 + gap)]
    sched += [(1, 0, tb.rand_vec(rng)) for _ in range(3 * lat + 3)]   # start held high
    for k in (lat - 2, lat - 1, 1, 5):                        # abort in the last / first busy clocks, start high
        sched += [(1, 0, tb.rand_vec(rng))] + [(1, 0, tb.rand_vec(rng)) for _ in range(k - 1)]
        sched += [(1, 1, tb.rand_vec(rng))] + [(0, 0, tb.junk(rng)) for _ in range(3)]
    sched += [(1, 1, tb.rand_vec(rng)), (0, 0, tb.junk(rng))]   # abort with start: not taken
    sched += [(int(rng.random() < 0.1), 0, tb.rand_vec(rng)) for _ in range(4 * lat)]     # random pulses
    sched += [(int(rng.random() < 0.3), int(rng.random() < 1 / lat), tb.rand_vec(rng)) for _ in range(6 * lat)]
    sched += [(0, 0, tb.junk(rng)) for _ in range(lat + 2)]
    await tb.protocol(sched, 12)


@cocotb.test()
async def abort(dut):
    """abort_i k = 0 .. LATENCY-1 clocks after a start (0: with start_i): idle at once, no done_o; then exact."""
    tb = CalcTB(dut)
    rng = random.Random(0xAB0 + tb.W)
    await tb.reset()
    vecs = [tb.rand_vec(rng) for _ in range(tb.lat + 1)]
    await tb.run_vectors(vecs[:1], rng, "before abort")
    for k in range(tb.lat):
        await tb.aborted_start(rng, k)
        await tb.run_vectors([vecs[k + 1]], rng, f"after abort at {k}")


# ---- pytest items: build x scenario group x simulator ---------------------------------------------------------
# Verilator: one build directory per build, shared by its scenario items (the C++ build is ~25 s, the
# incremental rebuild ~1 s; simrun serialises the users of one directory); Icarus (rebuilt every run, ~1 s):
# one directory per item.

BUILDS = {
    "full_cnt16":    {"Features": config.FULL, "CntWidth": 16, "DtWidth": 10},
    "full_cnt12":    {"Features": config.FULL, "CntWidth": 12, "DtWidth": 10},
    "full_serial":   {"Features": config.FULL & ~config.mask("dsp"), "CntWidth": 16, "DtWidth": 10},
    "compact_cnt16": {"Features": config.TINY, "CntWidth": 16, "DtWidth": 10},
    "compact_cnt12": {"Features": config.TINY, "CntWidth": 12, "DtWidth": 10},
}
SCENARIOS = {
    "directed":  ["directed_freq", "directed_corners", "directed_dtc", "directed_carry"],
    "modes":     ["directed_vf", "directed_polar", "directed_ab", "directed_dq", "directed_invalid", "directed_om"],
    "sweep":     ["angle_sweep"],
    "random":    ["random_vectors"],
    "handshake": ["protocol", "abort"],
    "serial":    ["serial_vectors"],
}
# builds interleaved: pytest-xdist hands the first items out round robin, so the two workers start on
# different builds (the Verilator items of one build share its build directory, see below)
# (the serial build runs only its own short group: the same program, a slower multiplier)
# Icarus runs the 12-bit builds' directed and handshake scenarios (every category of vector at CntWidth 12);
# their modes, sweep and random scenarios run on Verilator (the 16-bit builds run all of them on both)
ICARUS_CNT12_ONLY = ("directed", "handshake")
ITEMS = [(m, b, s) for m in sims_to_run() for s in SCENARIOS for b in BUILDS
         if not (BUILDS[b]["Features"] == config.TINY and s == "modes")
         and (b == "full_serial") == (s == "serial")
         and not (m == "icarus" and BUILDS[b]["CntWidth"] == 12 and s not in ICARUS_CNT12_ONLY)]


@pytest.mark.parametrize("simulator,build,scenario", ITEMS, ids=[f"{m}-{b}-{s}" for m, b, s in ITEMS])
def test_svpwm_calc(simulator, build, scenario):
    sim = simulator
    here = Path(__file__).parent
    run_sim(sim, toplevel="tb_svpwm_calc", sources=[*rtl_sources(), here / "tb_svpwm_calc.sv"],
            test_module="test_svpwm_calc", test_dir=here,
            parameters=BUILDS[build],
            build_name=build if sim == "verilator" else f"{build}-{scenario}", testcase=SCENARIOS[scenario],
            extra_env={"SVPWM_CALC_FEATURES": str(BUILDS[build]["Features"])},
            vpi_top_only=True)
