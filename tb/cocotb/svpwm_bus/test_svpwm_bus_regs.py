# SPDX-License-Identifier: Apache-2.0
"""Register block + bus adapters (AXI4-Lite, Wishbone pipelined, Wishbone classic) without the core.

Harness tb_svpwm_bus_regs.sv: the register outputs are probed in u_regs, the status inputs are driven
from here. Every address, field, reset value and access kind comes from svpwm_model.regmap (generated
from rdl/svpwm.rdl); nothing is typed twice. Builds (parameters Features, Trim): full, foc, minimal and
the iCEstick's tiny build with the board cut (Trim = 1), each checked against R.variant(features, trim):
its registers and fields behave as in the full block, every other register and field reads 0, ignores
writes and keeps its output at 0; FEATURES reads the parameters (features, trim). cocotb tests have no
`test_` prefix (pytest does not collect them).
"""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
from cocotb.triggers import FallingEdge, ReadOnly, RisingEdge, Timer
from cocotb.utils import get_sim_time
from clocks import clock_cycles

from svpwm_model import config
from svpwm_model import regmap as R

HERE = Path(__file__).resolve().parent
ADDR_WIDTH = 8
# ClkHz per bus variant (CLK_HZ reads it): 0 (not stated), a typical clock, the largest value
CLK_HZ = {"axil": 48_000_000, "wb": 0, "wbc": 0x7FFF_FFFF, "wb_tiny_trim": 24_000_000, "wb_minimal": 12_000_000,
          "axil_foc": 96_000_000}
CLK_NS = 10
# harness status input bit -> STATUS field, in the harness's packing order
STATUS_BITS = ["running", "sat", "cfg_err", "period_clamp", "freq_clamp", "fault", "tripped", "locked"]
PATTERNS = ([1 << i for i in range(32)] + [0xFFFFFFFF ^ (1 << i) for i in range(32)]
            + [0xFFFFFFFF, 0, 0xA5A5A5A5, 0x5A5A5A5A])


class TB:
    def __init__(self, dut):
        self.dut = dut
        self.bus = None
        # wrapper parameters that give field values (rst_param): those the harness is given, the others at
        # their RDL default (the CONFIG widths)
        self.params = {f.rst_param: f.reset for r in R.REGISTERS for f in r.fields if f.rst_param}
        self.params.update({"GatePol": int(os.environ["SVPWM_GATEPOL"]), "ClkHz": int(os.environ["SVPWM_CLKHZ"]),
                            "Features": int(os.environ["SVPWM_FEATURES"]), "Trim": int(os.environ["SVPWM_TRIM"])})
        self.features, self.trim = self.params["Features"], bool(self.params["Trim"])
        self.map = R.variant(self.features, self.trim)   # the registers / fields this build has
        self.by_addr = {r.addr: r for r in self.map}
        present = {(r.name, f.name) for r in self.map for f in r.fields}
        self.absent = [(r, f) for r in R.REGISTERS for f in r.fields          # outputs without storage
                       if f.kind in ("rw", "w1s", "pulse") and (r.name, f.name) not in present]
        self.rng = random.Random(int(os.environ.get("SVPWM_SEED", "1")))

    async def reset(self, status=0, carrier=0, period_act=0, cmp=0, win_lo=0, win_hi=0, win_st=0):
        d = self.dut
        d.status.value, d.carrier.value, d.period_act.value, d.cmp.value = status, carrier, period_act, cmp
        d.win_lo.value, d.win_hi.value, d.win_st.value = win_lo, win_hi, win_st
        d.rst_n.value = 0
        await clock_cycles(d.clk, 1)
        if self.bus is None:
            # created inside the reset: cocotbext-wishbone's immediate writes at time 0 made the
            # scheduled rst_n = 0 of the same time step get lost on Icarus
            from busdrv import AxilBus, WbBus
            bus = os.environ["SVPWM_BUS"]
            self.bus = AxilBus(d) if bus == "axil" else WbBus(d, pipelined=(bus == "wb"))
        await clock_cycles(d.clk, 2)
        d.rst_n.value = 1
        await clock_cycles(d.clk, 2)

    def port(self, f: R.Field) -> int:
        return int(getattr(self.dut.u_regs, f.port).value)

    def reset_of(self, f: R.Field) -> int:
        return self.params[f.rst_param] if f.rst_param else f.reset    # KeyError: a new rst_param

    def expected_reset(self, reg: R.Register) -> int:
        """Reset read value (status fields: what the harness drives, 0 here)."""
        return sum((self.reset_of(f) << f.lsb) for f in reg.fields if f.kind in ("const", "rw", "w1s"))

    async def snapshot(self) -> dict[str, int]:
        return {r.name: await self.bus.read(r.addr) for r in self.map}

    def rw_regs(self) -> list[R.Register]:
        return [r for r in self.map if r.mask("rw")]

    def reserved_addrs(self) -> list[int]:
        """Addresses without a register in this variant (incl. the full map's others if compact)."""
        return [a for a in range(0, 1 << ADDR_WIDTH, 4) if a not in self.by_addr]

    def check_absent_ports(self, when: str) -> None:
        """Outputs of the fields this variant does not have stay at 0."""
        for r, f in self.absent:
            assert self.port(f) == 0, f"{r.name}.{f.name} (absent): port {f.port} = 0x{self.port(f):X} {when}"


# --------------------------------------------------------------------------- cocotb tests
@cocotb.test()
async def reset_values(dut):
    """Every register reads its reset value; every register output starts at its field's reset."""
    tb = TB(dut)
    await tb.reset()
    for r in tb.map:
        got = await tb.bus.read(r.addr)
        assert got == tb.expected_reset(r), f"{r.name}: reset read 0x{got:08X} != 0x{tb.expected_reset(r):08X}"
        for f in r.fields:
            if f.kind in ("rw", "w1s", "pulse"):
                exp = 0 if f.kind == "pulse" else tb.reset_of(f)
                assert tb.port(f) == exp, f"{r.name}.{f.name}: port {f.port} = {tb.port(f)} after reset != {exp}"
    tb.check_absent_ports("after reset")
    assert R.ID.reset == 0x53565057 and await tb.bus.read(R.ID.addr) == 0x53565057
    assert await tb.bus.read(R.CLK_HZ.addr) == int(os.environ["SVPWM_CLKHZ"]), "CLK_HZ is not the ClkHz parameter"
    exp = R.FEATURES.encode(features=tb.features, trim=int(tb.trim))
    assert await tb.bus.read(R.FEATURES.addr) == exp == tb.features | tb.trim << 31, "FEATURES"


@cocotb.test()
async def readback_walking(dut):
    """Walking ones / zeros and fixed patterns: every RW field reads back what was written, masked to
    its width, and drives its register output; other fields of the register keep their values."""
    tb = TB(dut)
    await tb.reset()
    for r in tb.rw_regs():
        keep = r.mask("w1s", "pulse")          # written separately (lock_fault_clear)
        for p in PATTERNS + [tb.rng.getrandbits(32) for _ in range(8)]:
            p &= ~keep
            await tb.bus.write(r.addr, p)
            exp = (p & r.mask("rw")) | (tb.expected_reset(r) & ~r.mask("rw"))
            got = await tb.bus.read(r.addr)
            assert got == exp, f"{r.name}: wrote 0x{p:08X}, read 0x{got:08X} != 0x{exp:08X}"
            for f in r.fields:
                if f.kind == "rw":
                    assert tb.port(f) == (p & f.mask) >> f.lsb, f"{r.name}.{f.name}: port {f.port} = 0x{tb.port(f):X}"
            tb.check_absent_ports(f"after {r.name} = 0x{p:08X}")     # e.g. CTRL's absent fields
        await tb.bus.write(r.addr, tb.expected_reset(r))


@cocotb.test(skip=os.environ.get("SVPWM_BUS") != "axil", timeout_time=200, timeout_unit="us")
async def axil_channel_skew(dut):
    """AXI4-Lite only: the write address and the write data arrive in different clocks, either first, 1 to 6
    clocks apart (the AW or the W channel of the master held back): the write is issued only when both are
    there, with that data, and reads back."""
    from itertools import chain, repeat

    tb = TB(dut)
    await tb.reset()
    wr = tb.bus.m.write_if
    regs = tb.rw_regs()
    for r, held in ((r, held) for r in regs[:3] for held in ("aw", "w")):
        for gap in (1, 2, 6):
            p = tb.rng.getrandbits(32) & ~r.mask("w1s", "pulse")
            chan = wr.aw_channel if held == "aw" else wr.w_channel
            chan.set_pause_generator(chain(repeat(True, gap), repeat(False)))
            await tb.bus.write(r.addr, p)
            chan.clear_pause_generator()
            exp = (p & r.mask("rw")) | (tb.expected_reset(r) & ~r.mask("rw"))
            got = await tb.bus.read(r.addr)
            assert got == exp, (f"{r.name}: {held.upper()} held {gap} clocks, wrote 0x{p:08X}, "
                                f"read 0x{got:08X} != 0x{exp:08X}")
        await tb.bus.write(r.addr, tb.expected_reset(r))


@cocotb.test()
async def ro_and_reserved_ignore_writes(dut):
    """RO registers ignore writes; reserved addresses (also the registers the build does not have,
    whatever their live inputs) read 0 and ignore writes (no register changes, no aliasing, the
    outputs of absent fields stay 0)."""
    tb = TB(dut)
    await tb.reset(status=0x5A5, carrier=0x1_2345, period_act=0x0600, cmp=0x0300_0200_0100,
                   win_lo=0x1_0600 << 34 | 0x0_0401 << 17 | 0x1_0202, win_hi=0x3_0A05_0C09_0E0D, win_st=0x1D)
    for r in tb.rw_regs():                                       # a known non-reset state
        await tb.bus.write(r.addr, 0x0F0F0F0F & r.mask("rw"))
    before = await tb.snapshot()
    for r in [r for r in tb.map if not r.mask("rw", "w1s", "pulse")]:
        for v in (0xFFFFFFFF, 0, ~before[r.name] & 0xFFFFFFFF):
            await tb.bus.write(r.addr, v)
            got = await tb.bus.read(r.addr)
            assert got == before[r.name], f"RO {r.name} changed by a write of 0x{v:08X}: 0x{got:08X}"
    for a in tb.reserved_addrs():
        assert await tb.bus.read(a) == 0, f"reserved 0x{a:02X} reads non-zero"
        for v in (0xFFFFFFFF, 0x5A5A5A5A):
            await tb.bus.write(a, v)
            assert await tb.bus.read(a) == 0, f"reserved 0x{a:02X} reads non-zero after a write of 0x{v:08X}"
        tb.check_absent_ports(f"after a write to 0x{a:02X}")
    for r in tb.rw_regs():                          # absent fields of present registers
        absent = r.mask() ^ R.BY_NAME[r.name].mask()
        if absent:
            await tb.bus.write(r.addr, absent | before[r.name])
            got = await tb.bus.read(r.addr)
            assert got == before[r.name], f"{r.name}: absent bits 0x{absent:08X} written, read 0x{got:08X}"
            tb.check_absent_ports(f"after writing the absent bits of {r.name}")
    after = await tb.snapshot()
    assert after == before, f"writes to RO / reserved addresses changed {[k for k in before if before[k] != after[k]]}"


@cocotb.test()
async def status_inputs(dut):
    """Every RO live field reads the core output it is wired to (walking ones through the inputs); the
    shunt-window report (feature adc) reads 0 whatever is driven in a build without it."""
    tb = TB(dut)
    await tb.reset()
    d = dut
    await _window_inputs(tb)
    for i, name in enumerate(STATUS_BITS):
        d.status.value = 1 << i
        got = R.STATUS.decode(await tb.bus.read(R.STATUS.addr))
        assert got == {f.name: int(f.name == name) for f in R.STATUS.fields}, f"STATUS with {name}: {got}"
    for s in range(8):
        d.status.value = s << 8
        exp = 0 if tb.trim else s                   # STATUS.sector: cut by Trim
        assert R.STATUS.decode(await tb.bus.read(R.STATUS.addr))["sector"] == exp, f"sector {s}"
    live = [R.CARRIER, R.PERIOD_ACT, R.CMP_A, R.CMP_B, R.CMP_C]
    if tb.trim:                     # not in the trimmed register set: 0 whatever the core drives
        assert not any(r.addr in tb.by_addr for r in live)
        for v in (-1, 0x5555_5555_5555, 0xAAAA_AAAA_AAAA):
            d.carrier.value, d.period_act.value, d.cmp.value = v & 0x1FFFF, v & 0xFFFF, v & (2**48 - 1)
            vals = [await tb.bus.read(r.addr) for r in live]
            assert vals == [0] * len(live), f"absent live registers read {vals}"
        return
    for i in range(17):
        d.carrier.value = 1 << i
        got = R.CARRIER.decode(await tb.bus.read(R.CARRIER.addr))
        assert got == {"count": (1 << i) & 0xFFFF, "up": int(i == 16)}, f"CARRIER bit {i}: {got}"
    for i in range(16):
        d.period_act.value = 1 << i
        assert await tb.bus.read(R.PERIOD_ACT.addr) == 1 << i
        for k, reg in enumerate((R.CMP_A, R.CMP_B, R.CMP_C)):
            d.cmp.value = (1 << i) << (16 * k)
            vals = [await tb.bus.read(x.addr) for x in (R.CMP_A, R.CMP_B, R.CMP_C)]
            assert vals == [(1 << i) if j == k else 0 for j in range(3)], f"{reg.name} bit {i}: {vals}"


async def _window_inputs(tb: TB) -> None:
    """WIN_LO_A..C, WIN_HI_A..C (17 bits each) and WIN_STATUS read the inputs they are wired to: a walking
    one through each phase's field, another bit in each of the other phases (a swap of phases or of low and
    high side shows), walking ones through WIN_STATUS; all 0 in a build without adc."""
    d = tb.dut
    has = config.has(tb.features, "adc")
    lo_regs, hi_regs = (R.WIN_LO_A, R.WIN_LO_B, R.WIN_LO_C), (R.WIN_HI_A, R.WIN_HI_B, R.WIN_HI_C)
    assert all(R.built(r, tb.features, tb.trim) == has for r in lo_regs + hi_regs + (R.WIN_STATUS,))
    for i in range(17):
        bits = [1 << i, 1 << (i + 5) % 17, 1 << (i + 11) % 17]          # phase a, b, c
        for side, regs in (("lo", lo_regs), ("hi", hi_regs)):
            other = "hi" if side == "lo" else "lo"
            getattr(d, f"win_{side}").value = sum(b << (17 * k) for k, b in enumerate(bits))
            getattr(d, f"win_{other}").value = (1 << 51) - 1                 # the other side all ones
            got = [await tb.bus.read(r.addr) for r in regs]
            exp = bits if has else [0, 0, 0]
            assert got == exp, f"WIN_{side.upper()}_A..C, bit {i}: read {[hex(g) for g in got]} != {[hex(e) for e in exp]}"
    d.win_lo.value, d.win_hi.value = 0, 0
    for i in range(5):
        d.win_st.value = 1 << i
        got = R.WIN_STATUS.decode(await tb.bus.read(R.WIN_STATUS.addr))
        exp = {"ok": (1 << i) & 7, "recon": (1 << i) >> 3} if has else {"ok": 0, "recon": 0}
        assert got == exp, f"WIN_STATUS input bit {i}: {got} != {exp}"
    d.win_st.value = 0


@cocotb.test()
async def byte_lanes(dut):
    """Partial writes (wstrb / sel) change only the enabled byte lanes of RW fields."""
    tb = TB(dut)
    await tb.reset()
    strobes = range(1, 16) if tb.bus.name != "axil" else [1, 2, 4, 8, 3, 6, 12, 7, 14, 5, 9, 10, 13, 11]
    for r in tb.rw_regs():
        m = r.mask("rw")
        for strb in strobes:
            a, b = tb.rng.getrandbits(32) & m, tb.rng.getrandbits(32) & m
            await tb.bus.write(r.addr, a)
            await tb.bus.write(r.addr, b, strb)
            lanes = sum(0xFF << (8 * i) for i in range(4) if strb >> i & 1)
            exp = ((a & ~lanes) | (b & lanes)) & m | (tb.expected_reset(r) & ~m)
            got = await tb.bus.read(r.addr)
            assert got == exp, f"{r.name} strb {strb:04b}: 0x{a:08X} then 0x{b:08X} -> 0x{got:08X} != 0x{exp:08X}"
        await tb.bus.write(r.addr, tb.expected_reset(r))


@cocotb.test()
async def back_to_back(dut):
    """Writes and reads issued back to back (AXI: all in flight at once; Wishbone: one bus cycle,
    mixed and in order), checked against a reference of the register contents."""
    tb = TB(dut)
    await tb.reset()
    ref = {r.addr: tb.expected_reset(r) for r in tb.map}
    regs = tb.rw_regs()
    for rnd in range(4):
        ops = []
        for _ in range(40):
            r = tb.rng.choice(regs)
            v = tb.rng.getrandbits(32) & r.mask("rw")
            ops.append((r.addr, v))
        t0 = get_sim_time("ns")
        await tb.bus.write_many(ops)
        t_wr = (get_sim_time("ns") - t0) / CLK_NS
        for a, v in ops:
            ref[a] = v | (ref[a] & ~tb.by_addr[a].mask("rw"))
        addrs = [r.addr for r in tb.map] + tb.reserved_addrs()[:4]
        tb.rng.shuffle(addrs)
        t0 = get_sim_time("ns")
        got = await tb.bus.read_many(addrs)
        t_rd = (get_sim_time("ns") - t0) / CLK_NS
        for a, g in zip(addrs, got):
            if tb.by_addr.get(a) is not None and tb.by_addr[a].mask("status"):
                continue
            assert g == ref.get(a, 0), f"round {rnd}: 0x{a:02X} read 0x{g:08X} != 0x{ref.get(a, 0):08X}"
        dut._log.info(f"{tb.bus.name}: {len(ops)} writes in {t_wr:.0f} clocks, {len(addrs)} reads in {t_rd:.0f}")
        if tb.bus.name == "axil":   # the adapter takes a write every 2 clocks, a read every 2 clocks
            assert t_wr <= 2 * len(ops) + 12 and t_rd <= 2 * len(addrs) + 12, (t_wr, t_rd)
    if tb.bus.mixed_ordered:          # Wishbone: reads see the writes just before them in the same cycle
        ops = []
        for _ in range(60):
            r = tb.rng.choice(regs)
            if tb.rng.random() < 0.5:
                ops.append((r.addr, tb.rng.getrandbits(32) & r.mask("rw"), 0xF))
            else:
                ops.append((r.addr, None, 0xF))
        got = await tb.bus.mixed(ops)
        for (a, v, _), g in zip(ops, got):
            if v is not None:
                ref[a] = v
            else:
                assert g == ref[a], f"mixed: 0x{a:02X} read 0x{g:08X} != 0x{ref[a]:08X}"
    if tb.bus.name == "wb":           # one access per clock, own driver (STB on consecutive clocks)
        from busdrv import WbPipe

        ops = [(r.addr, tb.rng.getrandbits(32) & r.mask("rw"), 0xF) for r in regs]
        ops += [(r.addr, None, 0xF) for r in regs]
        t0 = get_sim_time("ns")
        got, _ = await WbPipe(dut).burst(ops)
        clocks = (get_sim_time("ns") - t0) / CLK_NS
        assert clocks <= len(ops) + 3, f"pipelined burst of {len(ops)} took {clocks} clocks"
        exp = {a: v for a, v, _ in ops if v is not None}
        for (a, v, _), g in zip(ops, got):
            if v is None:
                assert g == exp[a], f"pipelined: 0x{a:02X} read 0x{g:08X} != 0x{exp[a]:08X}"


@cocotb.test()
async def lock_fault_clear(dut):
    """CTRL.lock: write 1 sets, write 0 does not clear, only reset does. CTRL.fault_clear: a write
    of 1 gives exactly one clock of pulse, reads 0; without its byte lane, no pulse."""
    tb = TB(dut)
    await tb.reset()
    lock, fc = R.CTRL.field("lock"), R.CTRL.field("fault_clear")
    d = dut
    pulses = []

    async def count_fc():
        while True:
            await RisingEdge(d.clk)
            await ReadOnly()
            pulses.append(tb.port(fc))

    mon = cocotb.start_soon(count_fc())
    await tb.bus.write(R.CTRL.addr, R.CTRL.encode(fault_clear=1, en=1))
    await clock_cycles(d.clk, 3)
    assert sum(pulses) == 1, f"fault_clear pulse lasted {sum(pulses)} clocks"
    got = R.CTRL.decode(await tb.bus.read(R.CTRL.addr))
    assert got["fault_clear"] == 0 and got["en"] == 1, got
    pulses.clear()
    if tb.bus.name != "axil":         # a write with byte lane 0 disabled does not pulse
        await tb.bus.write(R.CTRL.addr, R.CTRL.encode(fault_clear=1), strb=0xE)
        await clock_cycles(d.clk, 3)
        assert sum(pulses) == 0, "fault_clear pulsed without its byte lane"
    mon.cancel()
    assert R.CTRL.decode(await tb.bus.read(R.CTRL.addr))["lock"] == 0
    await tb.bus.write(R.CTRL.addr, R.CTRL.encode(lock=1, en=1))
    assert R.CTRL.decode(await tb.bus.read(R.CTRL.addr))["lock"] == 1 and tb.port(lock) == 1
    await tb.bus.write(R.CTRL.addr, R.CTRL.encode(lock=0, en=0))
    got = R.CTRL.decode(await tb.bus.read(R.CTRL.addr))
    assert got["lock"] == 1 and got["en"] == 0 and tb.port(lock) == 1, f"lock cleared by a write of 0: {got}"
    await tb.reset()
    assert R.CTRL.decode(await tb.bus.read(R.CTRL.addr))["lock"] == 0 and tb.port(lock) == 0


@cocotb.test(skip=os.environ.get("SVPWM_BUS") == "axil")
async def reset_clears_ack(dut):
    """Wishbone: the asynchronous reset clears ACK at once, not at the next clock edge (a reset in the
    middle of an access leaves no acknowledge behind)."""
    tb = TB(dut)
    await tb.reset()
    d = dut
    await FallingEdge(d.clk)
    d.wb_adr.value, d.wb_we.value, d.wb_datwr.value, d.wb_sel.value = R.ID.addr, 0, 0, 0xF
    d.wb_cyc.value, d.wb_stb.value = 1, 1
    await FallingEdge(d.clk)
    assert int(d.wb_ack.value) == 1, "no ACK the clock after STB"
    d.rst_n.value = 0                     # the master still holds CYC and STB
    await Timer(1, "ns")                  # no clock edge in between
    assert int(d.wb_ack.value) == 0, "ACK still high after the asynchronous reset"
    d.wb_cyc.value, d.wb_stb.value = 0, 0
    await tb.reset()
    assert await tb.bus.read(R.ID.addr) == 0x53565057


# --------------------------------------------------------------------------- pytest
import pytest  # noqa: E402


# (bus, configuration, Trim): the three bus adapters with the full map; foc and minimal (registers and
# fields of the features they lack: 0); the iCEstick's tiny build with the board cut
BUILDS = [("axil", "full", 0), ("wb", "full", 0), ("wbc", "full", 0), ("wb", "tiny", 1), ("wb", "minimal", 0),
          ("axil", "foc", 0)]


@pytest.mark.parametrize("bus, cfg, trim", BUILDS)
def test_svpwm_bus_regs(sim, bus, cfg, trim):
    from simrun import REPO, run_sim

    name = bus + ("" if cfg == "full" else f"_{cfg}") + ("_trim" if trim else "")
    gate_pol = {"axil": 0, "wb": 2, "wbc": 1, "wb_tiny_trim": 1, "wb_minimal": 3, "axil_foc": 2}[name]   # non-zero too
    features = config.CONFIGS[cfg]
    run_sim(sim, toplevel="tb_svpwm_bus_regs",
            sources=[REPO / "rtl/svpwm_pkg.sv", REPO / "rtl/svpwm_regs.sv", REPO / "rtl/svpwm_axil_if.sv",
                     REPO / "rtl/svpwm_wb_if.sv", HERE / "tb_svpwm_bus_regs.sv"],
            test_module="test_svpwm_bus_regs", test_dir=HERE,
            parameters={"Bus": {"axil": 0, "wb": 1, "wbc": 2}[bus], "AddrWidth": ADDR_WIDTH, "GatePol": gate_pol,
                        "ClkHz": CLK_HZ[name], "Features": features, "Trim": trim},
            build_name=name, extra_env={"SVPWM_BUS": bus, "SVPWM_GATEPOL": gate_pol, "SVPWM_CLKHZ": CLK_HZ[name],
                                        "SVPWM_FEATURES": features, "SVPWM_TRIM": trim})
