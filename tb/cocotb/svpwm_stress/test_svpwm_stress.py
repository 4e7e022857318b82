# SPDX-License-Identifier: Apache-2.0
"""Random stress of svpwm_core: random input ("register") writes at random moments of the period,
random fault pulses (including sub-clock glitches), trip-mode / safe-state / polarity / lock changes,
every input mode (invalid codes included), references beyond the hexagon, DPWM, update modes,
prescaler, sync start, dead-time compensation with random current signs, the six-step law, the volt-second
carry and random resets, while the in-RTL checker of tb_svpwm_core watches the pins on every clock:
never both gates of a leg on, dead time before every turn-on, no pulse shorter than max(dt, dtf, mp) unless
a forced state made it, gates off in reset and while disabled, the trip forcing, the lock.

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

from simrun import REPO, rtl_sources, run_sim

CLK_NS = 10


class Stress:
    def __init__(self, dut, seed: int):
        self.dut = dut
        self.rng = random.Random(seed)
        self.writes = 0
        self.faults = 0
        self.resets = 0
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
            d.safe_lo_i.value = rng.randint(0, 1)
        elif what == "pol":
            d.pol_i.value = rng.randint(0, 3)
        elif what == "lock":
            d.lock_i.value = 1
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
            await clock_cycles(d.clk, rng.randint(1, 200))
            await FallingEdge(d.clk)
            d.fault_i.value = 0

    async def reset(self) -> None:
        d = self.dut
        self.resets += 1
        d.rst_ni.value = 0
        d.lock_i.value = 0
        await clock_cycles(d.clk, self.rng.randint(1, 5))
        await FallingEdge(d.clk)
        d.rst_ni.value = 1

    def violations(self) -> dict[str, int]:
        d = self.dut
        return {k: int(getattr(d, k).value) for k in
                ("shoot_through_count", "dead_time_violations", "short_pulse_count", "off_violations",
                 "trip_violations_o", "lock_violations_o")}


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
        else:
            st.write()
    await clock_cycles(d.clk, 2000)
    clocks = int((cocotb.utils.get_sim_time("ns") - t0) // CLK_NS)
    v = st.violations()
    dut._log.info("stress: %d writes, %d fault pulses, %d resets, %d clocks checked; violations %s",
                  st.writes, st.faults, st.resets, clocks, v)
    assert all(x == 0 for x in v.values()), f"safety checker violations: {v}"
    assert st.writes >= 10000 and st.faults > 50 and st.resets > 5
    if not icarus:
        assert clocks >= 10_000_000, f"only {clocks} clocks checked"


def test_svpwm_stress(sim):
    run_sim(sim, toplevel="tb_svpwm_core",
            sources=rtl_sources() + [REPO / "tb/cocotb/svpwm_core/tb_svpwm_core.sv"],
            test_module="test_svpwm_stress", test_dir=Path(__file__).parent, build_name="default",
            vpi_top_only=True)
