# SPDX-License-Identifier: Apache-2.0
"""Random stress of svpwm_core: random input ("register") writes at random moments of the period,
random fault pulses (including sub-clock glitches), trip-mode / safe-state / polarity / lock changes,
every input mode (invalid codes included), references beyond the hexagon, DPWM, update modes,
prescaler, sync start, dead-time compensation with random current signs, the six-step law, the volt-second
carry and random resets, while the in-RTL checker of tb_svpwm_core watches the pins on every clock:
never both gates of a leg on, dead time before every turn-on, no pulse shorter than max(dt, dtf, mp) unless
a forced state made it, gates off in reset and while disabled, the trip forcing, the lock.

Issue 27 scenarios (what found the safety bugs), each counted, logged and asserted above a minimum so that
the run cannot silently stop exercising them: resets while running shorter than a clock (between two clock
edges, and over one edge; ``reset_glitch``), faults raised with a reset and held across its release (some
past the end of the reset hold, braking mostly on; ``reset_fault``), fault_clear_i pulses in the clock of a
new short fault pulse (between two edges or over the clear's edge, half of them with a latched trip to clear;
``clear_fault``), fault pulses over one clock edge that fall within ~2 clocks (``short_fault``), braking
(safe_lo_i) toggled while unlocked (also in the middle of a held fault; ``brake``) and a lock with dead times
of 900 .. 1023 (``lock_big_dt``). The checker's issue-27 checks (the dead time across a reset, the reset hold,
the trip gap) must count 0 like the others.

The numbers of writes and clocks are logged and asserted (>= 10,000 writes on both simulators; the
Verilator run covers >= 10^7 clocks). Seeds are fixed, so a failure reproduces.
"""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
from cocotb.triggers import FallingEdge, Timer
from clocks import clock_cycles

from svpwm_tb import run_core_sim

CLK_NS = 10


class Stress:
    def __init__(self, dut, seed: int):
        self.dut = dut
        self.rng = random.Random(seed)
        self.writes = 0
        self.faults = 0
        self.resets = 0
        self.locked = False                 # lock_i written 1 since the last reset
        self.n = dict(reset_glitch=0, reset_glitch_gate_on=0, reset_over_edge=0, reset_fault=0,
                      reset_fault_gate_on=0, reset_fault_high_on=0, reset_fault_past_hold=0, clear_fault=0, clear_fault_latched=0,
                      short_fault=0, brake=0, brake_tripped=0, lock_big_dt=0)
        self.W_DT = len(dut.dt_i)
        self.W_P = len(dut.period_i)

    def rand_period(self) -> int:
        r = self.rng.random()
        if r < 0.15:
            return self.rng.randint(0, 60)                          # below the minimum (48): clamped
        if r < 0.75:
            return self.rng.randint(24, 400)                        # fast carriers: many edges
        return self.rng.randint(400, (1 << self.W_P) - 1)

    def rand_dt(self) -> int:
        r = self.rng.random()
        return 0 if r < 0.1 else self.rng.randint(1, 12) if r < 0.7 else self.rng.randint(0, (1 << self.W_DT) - 1)

    def write(self) -> None:
        """One random 'register write' on the core's inputs."""
        d, rng = self.dut, self.rng
        what = rng.choices(["freq", "m", "period", "dt", "mp", "en", "cbc", "safe", "pol", "lock", "clear",
                            "mode", "theta", "v", "vf", "dpwm", "upd", "presc", "adc", "sync", "dtc", "dtf"],
                           weights=[14, 14, 14, 12, 8, 8, 3, 3, 3, 0.3, 4, 6, 6, 8, 3, 4, 4, 3, 1, 2, 8, 8])[0]
        if what == "freq":
            d.freq_i.value = rng.choice([rng.randint(-(1 << 23), (1 << 23) - 1), rng.randint(-200000, 200000), 0])
        elif what == "m":
            d.m_i.value = rng.choice([rng.randint(0, 0xFFFF), rng.randint(0, 0x8000), 0x8000, 0])
        elif what == "period":
            d.period_i.value = self.rand_period()
        elif what == "dt":
            d.dt_i.value = self.rand_dt()
        elif what == "mp":
            d.mp_i.value = self.rand_dt()
        elif what == "dtf":                                     # a separate falling dead time, or none
            d.dtf_i.value = self.rand_dt()
            d.dtf_en_i.value = 1 if rng.random() < 0.7 else 0
        elif what == "en":
            d.en_i.value = 1 if rng.random() < 0.8 else 0
        elif what == "cbc":
            d.trip_cbc_i.value = rng.randint(0, 1)
        elif what == "safe":
            v = rng.randint(0, 1)
            self.toggle_brake(v)
        elif what == "pol":
            d.pol_i.value = rng.randint(0, 3)
        elif what == "lock":
            d.lock_i.value = 1
            self.locked = True
        elif what == "clear":
            d.fault_clear_i.value = rng.randint(0, 1)
        elif what == "mode":                                        # 5..7 invalid: zero vector + flag
            d.mode_i.value = rng.randint(0, 7)
        elif what == "theta":
            d.theta_i.value = rng.randint(0, 0xFFFF)
        elif what == "v":                                           # up to +-1.99 (beyond the hexagon)
            getattr(d, rng.choice(["v1_i", "v2_i"])).value = rng.choice(
                [rng.randint(-32768, 32767), rng.randint(-0x4000, 0x4000), -32768, 32767, 0])
        elif what == "vf":
            getattr(d, rng.choice(["vf_boost_i", "vf_slope_i", "vf_mmax_i"])).value = rng.randint(0, 0xFFFF)
        elif what == "dpwm":
            d.dpwm_i.value = rng.randint(0, 3)
        elif what == "upd":                                         # 3 invalid: valley + flag
            d.upd_i.value = rng.randint(0, 3)
        elif what == "presc":
            d.presc_i.value = rng.choice([0, 0, 1, 3, rng.randint(0, 255)])
        elif what == "adc":
            d.adc_trig_i.value = rng.randint(0, 3)
        elif what == "dtc":                                         # dead-time compensation, current signs,
            d.isign_i.value = rng.randint(0, 7)                     # overmodulation law, volt-second carry
            if rng.random() < 0.3:
                d.dtc_en_i.value = 1 if rng.random() < 0.7 else 0
            if rng.random() < 0.2:
                d.om_i.value = rng.randint(0, 1)
            if rng.random() < 0.2:
                d.vsc_en_i.value = 1 if rng.random() < 0.8 else 0
        else:                                                       # sync: a waiting core starts on sync_i
            d.sync_en_i.value = 1 if rng.random() < 0.3 else 0
            d.sync_i.value = rng.randint(0, 1)
        self.writes += 1

    async def fault_pulse(self) -> None:
        d, rng = self.dut, self.rng
        self.faults += 1
        if rng.random() < 0.3:                                      # glitch shorter than a clock
            await Timer(rng.randint(1, CLK_NS - 1), unit="ns")
            d.fault_i.value = 1
            await Timer(rng.randint(1, CLK_NS - 2), unit="ns")
            d.fault_i.value = 0
            await FallingEdge(d.clk)
        else:
            d.fault_i.value = 1
            n = rng.randint(1, 200)
            if n > 20 and rng.random() < 0.3:                      # braking toggled while the fault is held
                await clock_cycles(d.clk, n // 2)
                await FallingEdge(d.clk)
                self.toggle_brake(1 - int(d.safe_lo_i.value))
                n -= n // 2
            await clock_cycles(d.clk, n)
            await FallingEdge(d.clk)
            d.fault_i.value = 0

    async def reset(self) -> None:
        d = self.dut
        self.resets += 1
        d.rst_ni.value = 0
        d.lock_i.value = 0
        self.locked = False
        await clock_cycles(d.clk, self.rng.randint(1, 5))
        await FallingEdge(d.clk)
        d.rst_ni.value = 1

    # ---- issue 27 scenarios; each starts at a falling clock edge (time T: the rising edge is at T + 5 ns)
    def toggle_brake(self, v: int) -> None:
        d = self.dut
        if v != int(d.safe_lo_i.value) and not self.locked:
            self.n["brake"] += 1
            self.n["brake_tripped"] += int(d.tripped_o.value)
        d.safe_lo_i.value = v

    def gates_on(self) -> bool:
        return bool(int(self.dut.gate_hi_o.value) or int(self.dut.gate_lo_o.value))

    async def until_gates_on(self, max_clocks: int = 1100, high: bool = False) -> None:
        """Up to max_clocks (in steps of 50) until a gate (high: a high side) is on (a reset hold, a trip or a
        stop may keep them off); returns at a falling clock edge."""
        for _ in range(max_clocks // 50):
            if int(self.dut.gate_hi_o.value) if high else self.gates_on():
                return
            await clock_cycles(self.dut.clk, 50)
            await FallingEdge(self.dut.clk)

    def glitch_window(self, over_edge: bool) -> tuple[int, int]:
        """(start, length) in ns after T of a pulse between two rising edges (over_edge False) or over the one
        at T + 5 ns, ending before the next (T + 15 ns)."""
        rng = self.rng
        if over_edge:
            s = rng.randint(1, 4)
            return s, rng.randint(6, 14) - s
        s = rng.choice([1, 2, 3, 6, 7, 8])
        return s, rng.randint(1, (4 if s < 5 else 14) - s)

    async def reset_glitch(self) -> None:
        """A reset shorter than a clock while running: between two clock edges or over one edge."""
        d, rng = self.dut, self.rng
        if rng.random() < 0.8:
            await self.until_gates_on()
        over = rng.random() < 0.4
        s, n = self.glitch_window(over)
        await Timer(s, unit="ns")
        self.resets += 1
        self.n["reset_over_edge" if over else "reset_glitch"] += 1
        self.n["reset_glitch_gate_on"] += self.gates_on()
        d.rst_ni.value = 0
        d.lock_i.value = 0
        self.locked = False
        await Timer(n, unit="ns")
        d.rst_ni.value = 1
        await FallingEdge(d.clk)

    async def reset_fault(self) -> None:
        """A fault raised with a reset (or a clock before it, or in it) and held across the release, mostly with
        braking: 1 .. 20 clocks, past the reset hold (1000 .. 1100) or 1 .. 1500 after it."""
        d, rng = self.dut, self.rng
        if rng.random() < 0.8:
            await self.until_gates_on(high=True)                   # F1: a high side on at the reset
        self.n["reset_fault"] += 1
        self.n["reset_fault_gate_on"] += self.gates_on()
        self.n["reset_fault_high_on"] += int(d.gate_hi_o.value) != 0
        d.safe_lo_i.value = int(rng.random() < 0.7)               # (taken after the reset: unlocked)
        when = rng.choice(["with", "with", "before", "in"])
        if when == "before":
            d.fault_i.value = 1
            await FallingEdge(d.clk)
        self.resets += 1
        if rng.random() < 0.5:                                     # shorter than a clock
            s, n = self.glitch_window(rng.random() < 0.4)
            await Timer(s, unit="ns")
            d.rst_ni.value = 0
            d.fault_i.value = 1
            await Timer(n, unit="ns")
        else:                                                      # 1 .. 3 clock edges
            d.rst_ni.value = 0
            if when != "in":
                d.fault_i.value = 1
            await clock_cycles(d.clk, rng.randint(1, 3))
            await Timer(rng.randint(1, 4), unit="ns")
            d.fault_i.value = 1
            await FallingEdge(d.clk)
        d.lock_i.value = 0
        self.locked = False
        d.rst_ni.value = 1
        hold = rng.choice([rng.randint(1, 20), rng.randint(1000, 1100), rng.randint(1, 1500)])
        self.n["reset_fault_past_hold"] += hold > 1030
        await clock_cycles(d.clk, hold)
        await FallingEdge(d.clk)
        d.fault_i.value = 0

    async def clear_fault(self) -> None:
        """A fault_clear_i pulse in the clock of a new short fault pulse (between two edges or over the clear's
        edge); half of the time a latched trip to clear first."""
        d, rng = self.dut, self.rng
        self.n["clear_fault"] += 1
        if rng.random() < 0.5:
            if not self.locked:
                d.trip_cbc_i.value = 0
            d.fault_i.value = 1
            await clock_cycles(d.clk, 3)
            await FallingEdge(d.clk)
            d.fault_i.value = 0
            await clock_cycles(d.clk, 4)
            await FallingEdge(d.clk)
            self.n["clear_fault_latched"] += int(d.tripped_o.value)
        s, n = self.glitch_window(rng.random() < 0.5)
        d.fault_clear_i.value = 1
        await Timer(s, unit="ns")
        d.fault_i.value = 1
        await Timer(n, unit="ns")
        d.fault_i.value = 0
        await FallingEdge(d.clk)
        d.fault_clear_i.value = 0

    async def short_fault(self) -> None:
        """A fault pulse over one clock edge that falls before the next (or, 30 %, over two edges)."""
        d, rng = self.dut, self.rng
        self.n["short_fault"] += 1
        s = rng.randint(1, 4)
        e = rng.randint(6, 14) if rng.random() < 0.7 else rng.randint(16, 24)
        await Timer(s, unit="ns")
        d.fault_i.value = 1
        await Timer(e - s, unit="ns")
        d.fault_i.value = 0
        await FallingEdge(d.clk)

    def lock_big_dt(self) -> None:
        """Dead times of 900 .. 1023 (and a minimum pulse), locked until the next reset."""
        d, rng = self.dut, self.rng
        if self.locked:
            return
        self.n["lock_big_dt"] += 1
        d.dt_i.value = rng.randint(900, (1 << self.W_DT) - 1)
        d.dtf_i.value = rng.randint(900, (1 << self.W_DT) - 1)
        d.dtf_en_i.value = 1
        d.mp_i.value = rng.choice([0, rng.randint(0, 30)])
        d.lock_i.value = 1
        self.locked = True

    def violations(self) -> dict[str, int]:
        d = self.dut
        return {k: int(getattr(d, k).value) for k in
                ("shoot_through_count", "dead_time_violations", "short_pulse_count", "off_violations",
                 "trip_violations_o", "lock_violations_o", "reset_dt_violations_o", "reset_hold_violations_o",
                 "trip_gap_violations_o")}


@cocotb.test()
async def random_stress(dut):
    """Random writes, faults and resets at random moments; zero checker violations."""
    icarus = cocotb.SIM_NAME.lower().startswith("icarus")
    n_writes = int(os.environ.get("STRESS_WRITES", "10000"))
    mean_gap = 12 if icarus else 1100                 # clocks between actions (~10^7 clocks on Verilator)
    st = Stress(dut, seed=int(os.environ.get("STRESS_SEED", "20261122")))
    d = dut
    for sig, v in (("en_i", 0), ("freq_i", 0), ("m_i", 0), ("period_i", 200), ("dt_i", 5), ("dtf_i", 0), ("dtf_en_i", 0), ("mp_i", 0),
                   ("fault_i", 0), ("fault_clear_i", 0), ("trip_cbc_i", 0), ("safe_lo_i", 0), ("pol_i", 0),
                   ("lock_i", 0), ("mode_i", 0), ("theta_i", 0), ("v1_i", 0), ("v2_i", 0), ("vf_boost_i", 0),
                   ("vf_slope_i", 0), ("vf_mmax_i", 0), ("dpwm_i", 0), ("upd_i", 0), ("presc_i", 0),
                   ("adc_trig_i", 0), ("sync_en_i", 0), ("sync_i", 0), ("dtc_en_i", 0), ("isign_i", 0), ("om_i", 0), ("vsc_en_i", 1),
                   ("rst_ni", 0)):
        getattr(d, sig).value = v
    await clock_cycles(d.clk, 3)
    await FallingEdge(d.clk)
    d.rst_ni.value = 1
    t0 = cocotb.utils.get_sim_time("ns")
    while st.writes < n_writes:
        await clock_cycles(d.clk, max(1, int(st.rng.expovariate(1.0 / mean_gap))))
        await FallingEdge(d.clk)
        r = st.rng.random()
        if r < 0.015:
            await st.fault_pulse()
        elif r < 0.017:
            await st.reset()
        elif r < 0.020:
            await st.reset_glitch()
        elif r < 0.022:
            await st.reset_fault()
        elif r < 0.027:
            await st.clear_fault()
        elif r < 0.031:
            await st.short_fault()
        elif r < 0.035:
            st.toggle_brake(1 - int(d.safe_lo_i.value))
        elif r < 0.036:
            st.lock_big_dt()
        else:
            st.write()
    await clock_cycles(d.clk, 2000)
    clocks = int((cocotb.utils.get_sim_time("ns") - t0) // CLK_NS)
    v = st.violations()
    dut._log.info("stress: %d writes, %d fault pulses, %d resets, %d clocks checked; violations %s",
                  st.writes, st.faults, st.resets, clocks, v)
    dut._log.info("stress: issue-27 scenarios %s", st.n)
    assert all(x == 0 for x in v.values()), f"safety checker violations: {v}"
    assert st.writes >= 10000 and st.faults > 50 and st.resets > 5
    mins = dict(reset_glitch=12, reset_glitch_gate_on=8, reset_over_edge=8, reset_fault=10, reset_fault_gate_on=5, reset_fault_high_on=5,
                reset_fault_past_hold=3, clear_fault=25, clear_fault_latched=8, short_fault=20, brake=20,
                brake_tripped=3, lock_big_dt=4)
    low = {k: (st.n[k], m) for k, m in mins.items() if st.n[k] < m}
    assert not low, f"issue-27 scenarios exercised too rarely (count, minimum): {low}"
    if not icarus:
        assert clocks >= 10_000_000, f"only {clocks} clocks checked"


def test_svpwm_stress(sim):
    run_core_sim(sim, "test_svpwm_stress", Path(__file__).parent, "default", record=False)
