# SPDX-License-Identifier: Apache-2.0
"""Bus drivers for the svpwm register tests: one interface (write / read / write_many / read_many)
over cocotbext-axi's AxiLiteMaster and cocotbext-wishbone's WishboneMaster.

cocotbext-wishbone 2.0.1 works with cocotb 2.1 (it uses cocotb-bus); its master issues one
operation at a time (STB for one clock, then waits for ACK), so `WbPipe` below is a small own
driver that keeps STB high on consecutive clocks to exercise the pipelined slave at one access per
clock. Addresses and fields come only from svpwm_model.regmap (generated from rdl/svpwm.rdl).
"""
from __future__ import annotations

import logging

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, with_timeout

ALL = 0xF
CLK_NS = 10                 # the harnesses' clock (tb_svpwm_bus*.sv: always #5)
ACCESS_CLOCKS = 1000        # an AXI access not done in this many clocks hangs: fail now, not at a wall-clock limit


class AxilBus:
    name = "axil"

    def __init__(self, dut):
        from cocotbext.axi import AxiLiteBus, AxiLiteMaster

        logging.getLogger(f"cocotb.{dut._name}.s_axil").setLevel(logging.WARNING)   # one line per access
        self.m = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axil"), dut.clk, dut.rst_n,
                               reset_active_level=False)

    @staticmethod
    async def _timed(aw, n: int = 1):
        """aw (n accesses) within n * ACCESS_CLOCKS clocks, else SimTimeoutError: a slave that never answers
        fails the test in microseconds of simulated time (the AXI master itself waits forever)."""
        return await with_timeout(aw, n * ACCESS_CLOCKS * CLK_NS, "ns")

    @staticmethod
    def _lanes(strb: int) -> list[tuple[int, int]]:
        """Contiguous runs of byte lanes (AxiLiteMaster writes one run per access)."""
        runs, b = [], 0
        while b < 4:
            if strb >> b & 1:
                e = b
                while e + 1 < 4 and strb >> (e + 1) & 1:
                    e += 1
                runs.append((b, e - b + 1))
                b = e + 1
            else:
                b += 1
        return runs

    async def write(self, addr: int, value: int, strb: int = ALL) -> None:
        for off, n in self._lanes(strb):
            data = (value >> (8 * off)) & ((1 << (8 * n)) - 1)
            await self._timed(self.m.write(addr + off, data.to_bytes(n, "little")))

    async def read(self, addr: int) -> int:
        r = await self._timed(self.m.read(addr, 4))
        return int.from_bytes(r.data, "little")

    async def write_many(self, ops: list[tuple[int, int]]) -> None:
        """All writes issued at once (back-to-back on the bus)."""
        evs = []
        for addr, value in ops:
            ev = cocotb.triggers.Event()
            self.m.init_write(addr, value.to_bytes(4, "little"), event=ev)
            evs.append(ev)
        for ev in evs:
            await self._timed(ev.wait(), len(evs))

    async def read_many(self, addrs: list[int]) -> list[int]:
        evs = []
        for addr in addrs:
            ev = cocotb.triggers.Event()
            self.m.init_read(addr, 4, event=ev)
            evs.append(ev)
        out = []
        for ev in evs:
            await self._timed(ev.wait(), len(evs))
            out.append(int.from_bytes(ev.data.data, "little"))
        return out

    # AXI has independent read and write channels: reads and writes in flight together
    mixed_ordered = False


class WbBus:
    def __init__(self, dut, pipelined: bool):
        from cocotbext.wishbone.driver import WishboneMaster

        class _Classic(WishboneMaster):   # no STALL signal: the driver holds STB until ACK
            _optional_signals = ["sel", "err", "rty", "cti", "bte"]

        cls = WishboneMaster if pipelined else _Classic
        self.name = "wb" if pipelined else "wbc"
        self.dut = dut
        self.m = cls(dut, "wb", dut.clk, width=32, timeout=50)
        self.m.log.setLevel(logging.WARNING)

    async def _cycle(self, ops):
        from cocotbext.wishbone.driver import WBOp

        res = await self.m.send_cycle([WBOp(adr=a, dat=d, sel=s, acktimeout=20) for a, d, s in ops])
        assert len(res) == len(ops), f"{len(res)} acks for {len(ops)} operations"
        return res

    async def write(self, addr: int, value: int, strb: int = ALL) -> None:
        await self._cycle([(addr, value, strb)])

    async def read(self, addr: int) -> int:
        return int((await self._cycle([(addr, None, ALL)]))[0].datrd)

    async def write_many(self, ops):
        await self._cycle([(a, v, ALL) for a, v in ops])

    async def read_many(self, addrs):
        return [int(r.datrd) for r in await self._cycle([(a, None, ALL) for a in addrs])]

    async def mixed(self, ops):
        """One bus cycle of (addr, data or None, sel) in order; returns the read data (None for writes)."""
        res = await self._cycle(ops)
        return [int(r.datrd) if d is None else None for r, (_, d, _) in zip(res, ops)]

    mixed_ordered = True


class WbPipe:
    """Own minimal pipelined Wishbone master: STB high on consecutive clocks, one op per clock."""

    def __init__(self, dut):
        self.dut = dut

    async def burst(self, ops: list[tuple[int, int | None, int]]) -> tuple[list[int | None], int]:
        d = self.dut
        clk = RisingEdge(d.clk)
        acks: list[int] = []
        n = len(ops)

        async def collect():
            while len(acks) < n:
                await clk
                await ReadOnly()
                if int(d.wb_ack.value):
                    acks.append(int(d.wb_datrd.value))

        t = cocotb.start_soon(collect())
        await clk
        d.wb_cyc.value = 1
        cycles = 0
        for adr, dat, sel in ops:
            d.wb_stb.value = 1
            d.wb_adr.value = adr
            d.wb_we.value = int(dat is not None)
            d.wb_datwr.value = dat or 0
            d.wb_sel.value = sel
            await clk
            cycles += 1
            assert int(d.wb_stall.value) == 0
        d.wb_stb.value = 0
        d.wb_we.value = 0
        await t
        await FallingEdge(d.clk)
        d.wb_cyc.value = 0
        return [a if dat is None else None for a, (_, dat, _) in zip(acks, ops)], cycles
