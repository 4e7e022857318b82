# SPDX-License-Identifier: Apache-2.0
"""deadtime against the golden model svpwm_model.deadtime.simulate_cycles (exact, ==, every clock).

Inputs are driven per clock (en_i, pole_i; dt_i, dtf_i and mp_i one clock ahead, as the RTL reads them);
the model's target is OFF while en_i is low, else HI / LO from pole_i; its saturation is 2^DtWidth - 1 (the
RTL counter's all-ones reset value). Sequences are seeded random pole pulses shorter than, equal to and just
longer than dt (and long ones), en_i drops (also mid-pulse), dt = 0 (complementary, same-edge swap),
dt = 2^DtWidth - 1 and dt changing while running; the same with separate rising (dt_i) and falling (dtf_i)
dead times, random and corner pairs (zero on one edge, the maximum, 1 / 2). Without a falling dead time in
the schedule dtf_i = dt_i. Besides model equality every trace is checked directly: never both gates on; the
high side turns on only after both were off for at least the dt in force, the low side after dtf (a direct
swap only when that edge's dead time is 0); an on-pulse lasts >= max(dt, dtf, mp) unless en_i dropped (or
braking cut a high side). Builds: DtWidth 10 (default), 4 and 1.
"""
from __future__ import annotations

import random
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import FallingEdge
from clocks import clock_cycles

from simrun import REPO, run_sim
from svpwm_model.deadtime import BRAKE, HI, LO, OFF, LegState, simulate_cycles


class DtTB:
    def __init__(self, dut):
        self.dut = dut
        self.W = len(dut.dt_i)
        self.max = (1 << self.W) - 1
        self.icarus = cocotb.SIM_NAME.lower().startswith("icarus")

    async def run(self, sched, what=""):
        """sched: per clock (en, pole, dt[, brake, mp[, dtf]]), dtf None or missing: dtf_i = dt. Resets,
        drives, compares (hi, lo) every clock with the model, checks the direct properties; returns the RTL
        trace (hi, lo) at clocks 0..len(sched)."""
        d = self.dut
        sched = pad(sched)
        d.en_i.value = 0
        d.brake_i.value = 0
        d.pole_i.value = 0
        d.dt_i.value = 0
        d.dtf_i.value = 0
        d.mp_i.value = 0
        d.rst_ni.value = 0
        await FallingEdge(d.clk)
        await FallingEdge(d.clk)
        d.rst_ni.value = 1
        # idle (en_i low) until the dead-time counter has saturated: the schedule starts "off for long"
        # (test_reset_turn_off checks the reset state itself)
        await clock_cycles(d.clk, self.max + 1)
        d.dt_i.value = sched[0][2]          # dt_i / dtf_i / mp_i are read one clock ahead: the ports carry
        d.dtf_i.value = sched[0][5]         # the values in force in the next clock
        d.mp_i.value = sched[0][4]
        await FallingEdge(d.clk)
        tgt = [OFF if not en else BRAKE if brake else (HI if pole else LO) for en, pole, _, brake, _, _ in sched]
        exp = simulate_cycles(tgt, [x[2] for x in sched], self.max, LegState(0, 0, self.max),
                              mp=[x[4] for x in sched], dtf=[x[5] for x in sched])
        trace = []
        for k, (en, pole, _, brake, _, _) in enumerate(sched):
            got = (int(d.hi_o.value), int(d.lo_o.value))
            assert got == exp[k], (f"{what} clock {k}: RTL (hi, lo) = {got}, model {exp[k]}; inputs (en, pole, dt) "
                                   f"from clock {max(0, k - 4)}: {sched[max(0, k - 4):k + 1]}")
            trace.append(got)
            d.en_i.value = en
            d.brake_i.value = brake
            d.pole_i.value = pole
            nxt = sched[min(k + 1, len(sched) - 1)]
            d.dt_i.value = nxt[2]
            d.dtf_i.value = nxt[5]
            d.mp_i.value = nxt[4]
            await FallingEdge(d.clk)
        got = (int(d.hi_o.value), int(d.lo_o.value))
        assert got == exp[-1], f"{what} last clock: RTL {got}, model {exp[-1]}"
        trace.append(got)
        check_properties(trace, sched, what)
        return trace


def pad(sched):
    """Schedule entries as (en, pole, dt, brake, mp, dtf) with dtf resolved (None / missing: dt)."""
    out = []
    for x in sched:
        x = tuple(x) + (0, 0, None)[len(x) - 3:]
        out.append(x[:5] + (x[2] if x[5] is None else x[5],))
    return out


def check_properties(trace, sched, what=""):
    """Safety directly on the trace (no model): see the module docstring."""
    off_run = 1 << 30                      # clocks both gates have been off (reset: long ago)
    on_since = [None, None]
    sched = pad(sched)
    for c in range(1, len(trace)):
        prev, cur = trace[c - 1], trace[c]
        en, _, dt, brake, mp, dtf = sched[c - 1]   # inputs of the deciding clock c - 1
        assert cur != (1, 1), f"{what}: both gates on at clock {c}"
        for g in (0, 1):
            d = (dt, dtf)[g]                        # the high side waits dt, the low side dtf
            if cur[g] and not prev[g]:                                  # turn-on
                if prev[1 - g]:
                    assert d == 0, f"{what}: direct swap to {'hl'[g]} at clock {c} with its dead time {d}"
                else:
                    assert off_run >= d, f"{what}: gap {off_run} < {('dt', 'dtf')[g]} {d} before the turn-on at {c}"
                on_since[g] = c
            if prev[g] and not cur[g]:                                  # turn-off
                if en and not (brake and g == 0) and on_since[g] is not None:
                    assert c - on_since[g] >= max(dt, dtf, mp), \
                        f"{what}: on-pulse {c - on_since[g]} < max(dt {dt}, dtf {dtf}, mp {mp}) ending at {c}"
        off_run = off_run + 1 if cur == (0, 0) and prev == (0, 0) else (1 if cur == (0, 0) else 0)


def random_sched(rng: random.Random, dt_of, n_seg: int, max_len: int):
    """Pole pulses with lengths around dt (dt-1, dt, dt+1, dt+2, 1, 2dt, random), en_i drops before, after
    and within pulses. dt_of(segment index) gives the dead time of each segment (changes while running)."""
    sched = []
    pole = 0
    for i in range(n_seg):
        dt = dt_of(i)
        pole ^= 1
        n = rng.choice([max(1, dt - 1), max(1, dt), dt + 1, dt + 2, 1, 2 * dt + 1,
                        rng.randint(1, min(max_len, 3 * dt + 4))])
        r = rng.random()
        if r < 0.12:                                        # en_i drops mid-pulse
            a = rng.randint(0, n)
            b = rng.randint(1, dt + 3)
            sched += [(1, pole, dt)] * a + [(0, rng.randint(0, 1), dt)] * b + [(1, pole, dt)] * (n - a)
        elif r < 0.2:                                       # an OFF segment between pulses
            sched += [(0, pole, dt)] * rng.randint(1, dt + 3) + [(1, pole, dt)] * n
        else:
            sched += [(1, pole, dt)] * n
    return sched


@cocotb.test()
async def reset_turn_off(dut):
    """A reset in mid-pulse is a turn-off of unknown dead time (the reset hold): after its release nothing
    turns on before the counter has saturated, i.e. the first gate turns on in clock 2^DtWidth (tb.max + 1)
    after the release, whatever the dead time in force, also with braking; later edges use the dead time."""
    tb = DtTB(dut)
    d = dut
    for dt, brake in ((0, 0), (3, 1), (min(40, tb.max), 0), (tb.max, 1)):
        d.dt_i.value = dt
        d.dtf_i.value = dt
        d.mp_i.value = 0
        d.brake_i.value = 0
        d.en_i.value = 1
        d.pole_i.value = 1
        d.rst_ni.value = 0
        await FallingEdge(d.clk)
        await FallingEdge(d.clk)                    # a rising edge with the reset low
        d.rst_ni.value = 1
        await clock_cycles(d.clk, tb.max + 2 * dt + 3)
        await FallingEdge(d.clk)
        assert str(d.hi_o.value) == "1", (f"dt={dt}: hi {d.hi_o.value} lo {d.lo_o.value} en {d.en_i.value} "
                                          f"brake {d.brake_i.value} pole {d.pole_i.value} dt {d.dt_i.value} "
                                          f"mp {d.mp_i.value} rst {d.rst_ni.value} ~(cnt+1) {d.u_dut.ncnt1_q.value} chg {d.u_dut.chg_q.value}")
        d.rst_ni.value = 0                          # reset while the high side is on
        await FallingEdge(d.clk)
        assert (int(d.hi_o.value), int(d.lo_o.value)) == (0, 0)
        d.pole_i.value = 0
        d.brake_i.value = brake                     # braking wants the low side at once: the hold decides
        d.rst_ni.value = 1
        n = tb.max + dt + 4
        exp = simulate_cycles([BRAKE if brake else LO] * n, [dt] * n, tb.max)
        for k in range(n):
            got = (int(d.hi_o.value), int(d.lo_o.value))
            assert got == exp[k], f"dt={dt} brake={brake} clock {k} after reset: RTL {got}, model {exp[k]}"
            await FallingEdge(d.clk)
        first_on = exp.index((0, 1))
        assert first_on == tb.max + 1, first_on     # the hold: the counter saturates first
        d.brake_i.value = 0


@cocotb.test()
async def brake_and_min_pulse(dut):
    """Braking (trip safe state "low sides on") arrives at random moments: the high side goes off on the
    next clock, the low side follows after the dead time; minimum on-pulses longer than the dead time."""
    tb = DtTB(dut)
    rng = random.Random(0xB4A4E + tb.W)
    for dt, mp in ((0, 0), (0, 5), (3, 0), (3, 9), (min(7, tb.max), min(2, tb.max)), (tb.max, tb.max),
                   (0, 1), (1, 1), (1, 2), (2, 3), (0, 3)):   # mp = 1, 2: the flags' "count restarts at 1"
        #                                             values; mp = 3 > dt: the minimum pulse alone decides
        base = random_sched(rng, lambda i: dt, 40 if tb.icarus else 100, 4 * max(dt, mp) + 8)
        sched = []
        for en, pole, d_ in base:
            brake = 1 if rng.random() < 0.03 else 0
            sched.append((en, pole, d_, brake, mp))
        # stretch braking requests into runs
        for i in range(1, len(sched)):
            if sched[i - 1][3] and rng.random() < 0.9:
                sched[i] = sched[i][:3] + (1, mp)
        await tb.run(sched, f"dt={dt} mp={mp}")


@cocotb.test()
async def random_constant_dt(dut):
    """Seeded random pulse sequences at dead times 0, 1, 2, 3, 5, 13 (and the maximum on DtWidth 4)."""
    tb = DtTB(dut)
    rng = random.Random(0xDEAD + tb.W)
    n_seg = 60 if tb.icarus else 150
    for dt in sorted({0, 1, 2, 3, 5, min(13, tb.max), tb.max if tb.max < 64 else 0}):
        await tb.run(random_sched(rng, lambda i: dt, n_seg, 64), f"dt={dt}")


@cocotb.test()
async def dt_zero_complementary(dut):
    """dt = 0: the gates follow the pole one clock later, complementary, swapping on the same edge."""
    tb = DtTB(dut)
    rng = random.Random(7)
    sched = [(1, rng.randint(0, 1), 0) for _ in range(200)] + [(1, k & 1, 0) for k in range(20)]
    sched[50:53] = [(0, 1, 0)] * 3
    trace = await tb.run(sched, "dt=0")
    for k in range(1, len(sched)):
        en, pole, _ = sched[k]
        if en and sched[k - 1][0]:                  # enabled for two clocks: a full gate follows the pole
            assert trace[k + 1] == (pole, 1 - pole), f"clock {k + 1}: {trace[k + 1]} for pole {pole}"
    swaps = sum(1 for a, b in zip(trace, trace[1:]) if a != (0, 0) and b != (0, 0) and a != b)
    assert swaps > 20


@cocotb.test()
async def dt_maximum(dut):
    """dt = 2^DtWidth - 1: pulses of max - 1, max, max + 1, 2 max + 1, en_i drops."""
    tb = DtTB(dut)
    m = tb.max
    lens = [m - 1, m, m + 1, 2 * m + 1, 1, m + 1] if m > 1 else [1, 2, 3]
    sched = [(1, 0, m)] * (m + 2)
    for i, n in enumerate(lens):
        sched += [(1, (i + 1) & 1, m)] * n
    sched += [(1, 0, m)] * (m // 2 + 1) + [(0, 0, m)] * 3 + [(1, 1, m)] * (2 * m + 3)
    sched += [(1, 0, m)] * (m + 5) + [(1, 1, m)] * (m + 1) + [(0, 1, m)] * 2 + [(1, 0, m)] * (2 * m + 2)
    await tb.run(sched, f"dt=max={m}")


@cocotb.test()
async def dt_changing(dut):
    """The dead time changes while running, also within a dead time or a minimum on-time."""
    tb = DtTB(dut)
    rng = random.Random(0xC4A + tb.W)
    choices = [0, 1, 2, 3, 4, 7, min(12, tb.max), min(20, tb.max)]
    dts = [rng.choice(choices) for _ in range(400)]
    n_seg = 80 if tb.icarus else 200
    sched = random_sched(rng, lambda i: dts[i], n_seg, 40)
    # dt also changes inside segments
    sched = [(en, p, rng.choice(choices)) if rng.random() < 0.03 else (en, p, dt) for en, p, dt in sched]
    await tb.run(sched, "dt changing")


@cocotb.test()
async def short_pulses(dut):
    """Directed: starting low-side on, a high pole pulse of width <= dt vanishes (the low gate is back
    after a notch of exactly dt clocks); a pulse of dt + 1 gives a high-side pulse of exactly dt."""
    tb = DtTB(dut)
    for dt in sorted({1, 2, 5, tb.max if tb.max < 64 else 9}):
        for w in range(1, dt + 2):
            lead = dt + 3
            sched = [(1, 0, dt)] * lead + [(1, 1, dt)] * w + [(1, 0, dt)] * (3 * dt + 4)
            trace = await tb.run(sched, f"dt={dt} w={w}")
            c0 = lead                                       # first clock with the high pole request
            assert trace[c0] == (0, 1)
            if w <= dt:
                assert all(t[0] == 0 for t in trace), f"dt={dt} w={w}: a high-side pulse appeared"
                notch = [c for c, t in enumerate(trace) if c > c0 and t == (0, 0)]
                assert notch == list(range(c0 + 1, c0 + dt + 1)), f"dt={dt} w={w}: notch {notch}"
            else:
                hi = [c for c, t in enumerate(trace) if t[0]]
                assert hi == list(range(c0 + dt + 1, c0 + 2 * dt + 1)), f"dt={dt} w={w}: high pulse {hi}"


@cocotb.test()
async def one_bit_width(dut):
    """DtWidth = 1 (dead times and minimum pulse 0 or 1, the counter saturating at 1): random pulses, en_i
    drops, braking, dt, dtf and mp changing while running (independently). Runs on the 1-bit build only (the other tests
    use dead times a 1-bit port cannot hold)."""
    tb = DtTB(dut)
    if tb.W != 1:
        return
    rng = random.Random(0x1B17)
    sched = []
    for _ in range(600 if not tb.icarus else 300):
        sched.append((int(rng.random() > 0.05), int(rng.random() < 0.5) if rng.random() < 0.4 else
                      (sched[-1][1] if sched else 0), rng.randint(0, 1), int(rng.random() < 0.03),
                      rng.randint(0, 1), rng.randint(0, 1)))
    await tb.run(sched, "DtWidth 1")


@cocotb.test()
async def asym_random(dut):
    """Separate rising / falling dead times: seeded random pole sequences (pulses around both dead times,
    en_i drops, braking, minimum pulses) at random pairs dt != dtf, both orders, also changing while
    running; per clock == model and the direct checks."""
    tb = DtTB(dut)
    if tb.W == 1:
        return
    rng = random.Random(0xA5D7 + tb.W)
    vals = sorted({0, 1, 2, 3, 5, 8, min(13, tb.max), min(40, tb.max), tb.max})
    n_seg = 40 if tb.icarus else 120
    for trial in range(4 if tb.icarus else 8):
        pairs = []
        while len(pairs) < 6:
            a, b = rng.choice(vals), rng.choice(vals)
            if a != b:
                pairs.append((a, b))
        mp = rng.choice((0, 0, 1, 3, min(17, tb.max)))
        base = random_sched(rng, lambda i: max(pairs[(i // 15) % len(pairs)]), n_seg, 64)
        sched = []
        for k, (en, pole, _) in enumerate(base):
            dt, dtf = pairs[(k // 97) % len(pairs)]              # a new pair every 97 clocks
            if rng.random() < 0.01:                              # and one-clock changes in between
                dt, dtf = rng.choice(vals), rng.choice(vals)
            brake = 1 if (trial % 2 and rng.random() < 0.02) else 0
            sched.append((en, pole, dt, brake, mp, dtf))
        for i in range(1, len(sched)):                           # braking requests in runs
            if sched[i - 1][3] and rng.random() < 0.9:
                sched[i] = sched[i][:3] + (1,) + sched[i][4:]
        await tb.run(sched, f"asym trial {trial} pairs {pairs} mp {mp}")


@cocotb.test()
async def asym_corners(dut):
    """Corner pairs (dt, dtf): zero on one edge (a swap there, a dead time on the other), 1 and 2 (the
    flags' restart values), the maximum against 0 and against max - 1. Directed edges from the low side on:
    a long high pole pulse (the high side on dt after the low side off, the low side dtf after the high
    side off), then a high pole pulse of one clock (the high side on for max(dt, dtf)); then braking from
    the high side on (the low side dtf after the high side off)."""
    tb = DtTB(dut)
    m = tb.max
    pairs = [(0, 3), (3, 0), (1, 2), (2, 1), (0, 1), (1, 0), (m, 0), (0, m), (m, m - 1), (m - 1, m),
             (min(5, m), min(9, m)), (min(9, m), min(5, m))]
    for dt, dtf in sorted({p for p in pairs if p[0] != p[1]}):
        w = max(dt, dtf)
        lead = w + 3
        sched = ([(1, 0, dt, 0, 0, dtf)] * lead + [(1, 1, dt, 0, 0, dtf)] * (3 * w + 5)
                 + [(1, 0, dt, 0, 0, dtf)] * (2 * w + 4))
        t1 = len(sched)
        sched += [(1, 1, dt, 0, 0, dtf)] + [(1, 0, dt, 0, 0, dtf)] * (3 * w + 6)
        t2 = len(sched)
        sched += [(1, 1, dt, 0, 0, dtf)] * (2 * w + 4) + [(1, 1, dt, 1, 0, dtf)] * (w + 4)
        trace = await tb.run(sched, f"dt={dt} dtf={dtf}")
        lo_off = lead + 1                                  # the low side turns off one clock after the request
        hi_on = lo_off + dt
        assert trace[hi_on] == (1, 0) and trace[hi_on - 1] == ((0, 0) if dt else (0, 1)), \
            f"dt={dt} dtf={dtf}: high side on at {hi_on}? {trace[lead:hi_on + 2]}"
        hi_off = lead + 3 * w + 5 + 1
        assert trace[hi_off - 1] == (1, 0) and trace[hi_off + dtf] == (0, 1), \
            f"dt={dt} dtf={dtf}: low side on at {hi_off + dtf}? {trace[hi_off - 1:hi_off + dtf + 2]}"
        assert all(t == (0, 0) for t in trace[hi_off:hi_off + dtf])
        # the one-clock pole pulse: the low side off at t1 + 1. dt > 0: the pole is back before the high
        # side may turn on, so the low side returns after the falling dead time (a notch of max(dtf, 1));
        # dt = 0: a swap to the high side, held for the minimum on-time max(dt, dtf) (at least one clock)
        hi = [c for c in range(t1, t2 + 1) if trace[c][0]]
        if dt == 0:
            assert hi == list(range(t1 + 1, t1 + 1 + max(w, 1))), f"dt=0 dtf={dtf}: high pulse {hi}"
        else:
            n = max(dtf, 1)
            assert hi == [], f"dt={dt} dtf={dtf}: a one-clock pole pulse reached the high side: {hi}"
            assert trace[t1 + 1 + n] == (0, 1) and all(t == (0, 0) for t in trace[t1 + 1:t1 + 1 + n]), \
                f"dt={dt} dtf={dtf}: notch {trace[t1:t1 + n + 3]}"
        # braking from the high side: off on the next clock, the low side dtf later
        tb_ = t2 + 2 * w + 4
        assert trace[tb_] == (1, 0) and trace[tb_ + 1 + dtf] == (0, 1), \
            f"dt={dt} dtf={dtf}: braking {trace[tb_:tb_ + dtf + 3]}"


# the 1-bit build runs only the test made for it (the others need wider dead times)
BUILDS = {"dt10": ({"DtWidth": 10}, None), "dt4": ({"DtWidth": 4}, None), "dt1": ({"DtWidth": 1}, "one_bit_width")}


@pytest.mark.parametrize("build", list(BUILDS))
def test_deadtime(sim, build):
    params, only = BUILDS[build]
    run_sim(sim, toplevel="tb_deadtime",
            sources=[REPO / "rtl/deadtime.sv", Path(__file__).parent / "tb_deadtime.sv"],
            test_module="test_deadtime", test_dir=Path(__file__).parent,
            parameters=params, build_name=build, testcase=only)
