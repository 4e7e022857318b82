# SPDX-License-Identifier: Apache-2.0
"""sine_rom against the golden model fixed.sine_table() (exact, ==), and its one-clock read latency.

Every address 0..256 is read in order (neighbouring entries differ, so a wrong latency shows), then
the addresses above 256 that must read the 60 deg value (257, 300, 511, ...), then all 512 addresses
in a seeded random order. For every read: the data is still the previous address's value just before
the next rising edge and is the new address's value right after it (exactly one clock of latency).
"""
from __future__ import annotations

import random
from pathlib import Path

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer

from simrun import REPO, run_sim
from svpwm_model import fixed

TABLE = fixed.sine_table()


def expected(addr: int) -> int:
    return TABLE[min(addr, fixed.ROM_SIZE)]       # addresses above 256 read the 60 deg value


async def read_sequence(dut, addrs):
    prev = None
    for i, a in enumerate(addrs):
        await FallingEdge(dut.clk)
        dut.addr_i.value = a
        await Timer(1, "ns")
        await ReadOnly()
        if prev is not None:                      # not yet the new address: registered read
            got = int(dut.data_o.value)
            assert got == expected(prev), (f"read #{i}: before the clock edge data = {got}, expected "
                                           f"the previous address {prev}: {expected(prev)}")
        await RisingEdge(dut.clk)
        await ReadOnly()
        got = int(dut.data_o.value)
        assert got == expected(a), f"read #{i}: addr {a}: data {got} != sine_table {expected(a)}"
        prev = a


@cocotb.test()
async def table_and_latency(dut):
    """All of 0..256 in order, the addresses above 256, then every address in random order."""
    assert len(TABLE) == fixed.ROM_SIZE + 1
    assert all(b > a for a, b in zip(TABLE, TABLE[1:])), "the table is strictly increasing"
    await read_sequence(dut, list(range(fixed.ROM_SIZE + 1)))
    await read_sequence(dut, [257, 300, 511, 0, 256, 384, 258, 255, 510, 1, 511])
    order = list(range(512))
    random.Random(0x517E).shuffle(order)
    await read_sequence(dut, order)


@cocotb.test()
async def held_address(dut):
    """An address held for several clocks keeps reading the same value."""
    for a in (0, 128, 256, 511):
        await FallingEdge(dut.clk)
        dut.addr_i.value = a
        for _ in range(4):
            await RisingEdge(dut.clk)
            await ReadOnly()
            assert int(dut.data_o.value) == expected(a)


def test_sine_rom(sim):
    run_sim(sim, toplevel="tb_sine_rom",
            sources=[REPO / "rtl/sine_rom.sv", Path(__file__).parent / "tb_sine_rom.sv"],
            test_module="test_sine_rom", test_dir=Path(__file__).parent, build_name="default")
