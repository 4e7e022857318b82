"""Smoke test of the simulation infrastructure (cocotb 2.x + Verilator/Icarus).

pytest part: `test_smoke[sim]` builds tb_smoke.sv and runs the cocotb tests
below.  Simulation throughput is measured by `make bench` (scripts/bench.py).

cocotb tests are named without a `test_` prefix so pytest does not collect them.
"""

import os
from pathlib import Path

import cocotb
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
