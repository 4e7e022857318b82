"""Smoke test of the simulation infrastructure (cocotb 2.x + Verilator/Icarus).

pytest part: `test_smoke[sim]` builds tb_smoke.sv and runs the cocotb tests
below.  `test_sim_speed[sim]` (marker `slow`, only with SVPWM_SMOKE_SPEED=1)
measures simulated clock cycles per second with the SV-generated clock.

cocotb tests are named without a `test_` prefix so pytest does not collect them.
"""

import os
import time
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import ReadOnly, RisingEdge, Timer
from cocotb.utils import get_sim_time

HERE = Path(__file__).resolve().parent
CLK_PERIOD_NS = 10  # `always #5 clk = ~clk`
RESET_RELEASE_NS = 22


# --------------------------------------------------------------------------- cocotb
async def _reset(dut):
    dut.rst_n.value = 0
    await Timer(RESET_RELEASE_NS, unit="ns")
    dut.rst_n.value = 1


def _first_posedge_after(t_ns):
    # posedges at 5, 15, 25, ... ns
    n = (t_ns - 5) // CLK_PERIOD_NS + 1
    return 5 + n * CLK_PERIOD_NS


@cocotb.test()
async def counter_edges(dut):
    """Wait on rising edges of `tick` (not on every clock) and check exact values."""
    tick_log2 = int(os.environ["SMOKE_TICK_LOG2"])
    period = 1 << tick_log2
    await _reset(dut)
    t_first = _first_posedge_after(RESET_RELEASE_NS)  # count becomes 1 here
    for k in range(1, 9):
        await RisingEdge(dut.tick)
        await ReadOnly()
        expect = k * period - 1
        assert int(dut.count.value) == expect, f"tick #{k}: count={int(dut.count.value)} != {expect}"
        t_expect = t_first + (expect - 1) * CLK_PERIOD_NS
        assert get_sim_time("ns") == t_expect, f"tick #{k} at {get_sim_time('ns')} ns, expected {t_expect} ns"


@cocotb.test()
async def counter_reset_midway(dut):
    """Asynchronous reset in the middle of a run restarts the count from 0."""
    await _reset(dut)
    await Timer(1000, unit="ns")
    dut.rst_n.value = 0
    await Timer(1, unit="ns")
    await ReadOnly()
    assert int(dut.count.value) == 0
    await Timer(20, unit="ns")
    dut.rst_n.value = 1
    await Timer(CLK_PERIOD_NS * 10, unit="ns")
    await ReadOnly()
    assert 9 <= int(dut.count.value) <= 10


@cocotb.test()
async def sim_speed(dut):
    """Run SMOKE_SPEED_CYCLES clock cycles waiting on `tick` edges; log cycles/s."""
    cycles = int(os.environ["SMOKE_SPEED_CYCLES"])
    period = 1 << int(os.environ["SMOKE_TICK_LOG2"])
    await _reset(dut)
    t0 = time.perf_counter()
    for _ in range(cycles // period):
        await RisingEdge(dut.tick)
    dt = time.perf_counter() - t0
    await ReadOnly()
    n = int(dut.count.value)
    assert n == (cycles // period) * period - 1
    rate = n / dt
    dut._log.info("SIM SPEED: %d cycles in %.2f s = %.0f cycles/s", n, dt, rate)
    out = os.environ.get("SMOKE_SPEED_OUT")
    if out:
        Path(out).write_text(f"{n} {dt:.3f} {rate:.0f}\n")


# --------------------------------------------------------------------------- pytest
def _run(sim, build_name, testcase, params, extra_env=None):
    from simrun import run_sim

    env = {"SMOKE_TICK_LOG2": str(params["TICK_LOG2"])}
    env.update(extra_env or {})
    return run_sim(
        sim,
        toplevel="tb_smoke",
        sources=[HERE / "tb_smoke.sv"],
        test_module="test_smoke",
        test_dir=HERE,
        parameters=params,
        build_name=build_name,
        extra_env=env,
        testcase=testcase,
    )


def test_smoke(sim):
    _run(sim, "tick4", ["counter_edges", "counter_reset_midway"], {"TICK_LOG2": 4})


@pytest.mark.slow
@pytest.mark.skipif(os.environ.get("SVPWM_SMOKE_SPEED") != "1", reason="set SVPWM_SMOKE_SPEED=1")
def test_sim_speed(sim, tmp_path):
    cycles = int(os.environ.get("SMOKE_SPEED_CYCLES", 2_000_000 if sim == "verilator" else 200_000))
    out = tmp_path / "speed.txt"
    _run(sim, "speed", "sim_speed", {"TICK_LOG2": 16},
         {"SMOKE_SPEED_CYCLES": str(cycles), "SMOKE_SPEED_OUT": str(out)})
    n, dt, rate = out.read_text().split()
    print(f"\n[{sim}] {n} cycles in {dt} s -> {int(rate):,} cycles/s")
