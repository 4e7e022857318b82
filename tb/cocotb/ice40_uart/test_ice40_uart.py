# SPDX-License-Identifier: Apache-2.0
"""iCE40 system level (svpwm_ice40_sys) through its UART pins only: register reads / writes with the
frames of scripts/svpwmctl.py (so its encoder / decoder is checked against the RTL), writes that take
effect on the gates (enable, carrier period), malformed and truncated frames rejected without any
register change, the fault input. Fast UART in simulation: 16 clocks per bit, 40-bit-time timeout.
"""
from __future__ import annotations

import os
import sys
from pathlib import Path

import cocotb
from cocotb.clock import Clock  # noqa: F401  (clock is generated in the harness)
from cocotb.triggers import ClockCycles, FallingEdge, RisingEdge, with_timeout

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "scripts"))
import svpwmctl as ctl  # noqa: E402
from svpwm_model import fixed  # noqa: E402

CPB = 16                # clocks per bit (harness parameter)
TIMEOUT_BITS = 40
R = {k: a for k, (a, _) in ctl.REGS.items()}
RW = [n for n, (_, w) in ctl.REGS.items() if w]


class Uart:
    def __init__(self, dut):
        self.dut = dut
        self.rx_bytes: list[int] = []
        dut.rx_i.value = 1
        cocotb.start_soon(self._monitor())

    async def send(self, data: bytes, stop_ok: bool = True, gap_bits: int = 0):
        for i, b in enumerate(data):
            bits = [0] + [(b >> k) & 1 for k in range(8)] + [1 if stop_ok else 0]
            for bit in bits:
                self.dut.rx_i.value = bit
                await ClockCycles(self.dut.clk, CPB)
            self.dut.rx_i.value = 1
            if gap_bits:
                await ClockCycles(self.dut.clk, CPB * gap_bits)

    async def _monitor(self):
        while True:
            await FallingEdge(self.dut.tx_o)
            await ClockCycles(self.dut.clk, CPB // 2)
            if self.dut.tx_o.value != 0:
                continue
            v = 0
            for k in range(8):
                await ClockCycles(self.dut.clk, CPB)
                v |= int(self.dut.tx_o.value) << k
            await ClockCycles(self.dut.clk, CPB)
            assert int(self.dut.tx_o.value) == 1, "tx stop bit low"
            self.rx_bytes.append(v)

    async def recv(self, n: int, max_bits: int = 200) -> bytes:
        for _ in range(max_bits):
            if len(self.rx_bytes) >= n:
                break
            await ClockCycles(self.dut.clk, CPB)
        out, self.rx_bytes = bytes(self.rx_bytes[:n]), self.rx_bytes[n:]
        return out

    async def quiet(self, bits: int = 30) -> bytes:
        """Wait and return whatever arrived (expect nothing for rejected frames)."""
        await ClockCycles(self.dut.clk, CPB * bits)
        out, self.rx_bytes = bytes(self.rx_bytes), []
        return out

    async def read(self, reg) -> int:
        await self.send(ctl.encode_read(R[reg] if isinstance(reg, str) else reg))
        return ctl.decode_read_reply(await self.recv(5))

    async def write(self, reg, value: int):
        await self.send(ctl.encode_write(R[reg] if isinstance(reg, str) else reg, value))
        ctl.decode_write_reply(await self.recv(1))


async def setup(dut) -> Uart:
    dut.rst_ni.value = 0
    dut.fault_ni.value = 1
    dut.rx_i.value = 1
    await ClockCycles(dut.clk, 5)
    dut.rst_ni.value = 1
    await ClockCycles(dut.clk, 5)
    return Uart(dut)


async def snapshot(u: Uart) -> dict:
    return {n: await u.read(n) for n in RW}


@cocotb.test()
async def id_and_reset_values(dut):
    """ID / VERSION / CONFIG / CLK_HZ, reset values, reserved addresses read 0."""
    u = await setup(dut)
    assert await u.read("ID") == ctl.ID_VALUE
    assert await u.read("VERSION") == 0x0001_0000
    cfg = ctl.Config.from_regs(await u.read("CLK_HZ"), await u.read("CONFIG"))
    assert (cfg.clk_hz, cfg.phase_width, cfg.freq_width, cfg.cnt_width, cfg.dt_width) == (100_000_000, 34, 24, 16, 10)
    assert await snapshot(u) == {"CTRL": 0, "FREQ": 0, "M": 0, "PERIOD": 1536, "DT": 48}
    for a in (0x0A, 0x20, 0x80, 0xFF):
        assert await u.read(a) == 0, f"reserved 0x{a:02x}"
    await u.write(0x20, 0xDEADBEEF)            # ignored, still answered
    assert await u.read(0x20) == 0
    await u.write("ID", 0)                     # read-only
    assert await u.read("ID") == ctl.ID_VALUE
    assert int(dut.gate_hi_o.value) == 0 and int(dut.gate_lo_o.value) == 0


@cocotb.test()
async def writes_drive_the_gates(dut):
    """Register writes take effect: enable -> gates switch, PERIOD sets the carrier, stop -> off."""
    u = await setup(dut)
    await u.write("FREQ", 0)                   # standing vector: every period identical
    await u.write("M", ctl.m_word(0.5))
    await u.write("PERIOD", 64)
    await u.write("DT", 3)
    vals = await snapshot(u)
    assert vals == {"CTRL": 0, "FREQ": 0, "M": 0x4000, "PERIOD": 64, "DT": 3}
    await ClockCycles(dut.clk, 400)
    assert int(dut.edge_count.value) == 0, "gates switched while disabled"
    await u.write("CTRL", ctl.CTRL_EN)
    await ClockCycles(dut.clk, 1000)
    assert int(dut.edge_count.value) > 10, "gates do not switch after CTRL.en = 1"
    assert int(dut.a_hi_interval.value) == 128, f"carrier 2P = {int(dut.a_hi_interval.value)}, expected 128"
    st = await u.read("STATUS")
    assert st & 1 and int(dut.led_run_o.value) == 1, f"STATUS 0x{st:x}: not running"
    await u.write("PERIOD", 100)
    await ClockCycles(dut.clk, 1200)
    assert int(dut.a_hi_interval.value) == 200, f"carrier 2P = {int(dut.a_hi_interval.value)}, expected 200"
    await u.write("PERIOD", 8)                 # below MinPeriod: clamped, flagged
    await ClockCycles(dut.clk, 600)
    assert (await u.read("STATUS")) & 4, "period_clamp not reported"
    assert int(dut.a_hi_interval.value) == 2 * fixed.MIN_PERIOD   # the system's MinPeriod (48)
    await u.write("PERIOD", 64)
    await u.write("FREQ", 0x7FFFFF)            # fast rotation: the sector must move
    sectors = set()
    for _ in range(8):
        await ClockCycles(dut.clk, 700)
        sectors.add((await u.read("STATUS") >> 8) & 7)
    assert len(sectors) >= 3, f"sector does not advance: {sectors}"
    await u.write("CTRL", 0)
    await ClockCycles(dut.clk, 4)
    assert int(dut.gate_hi_o.value) == 0 and int(dut.gate_lo_o.value) == 0
    assert int(dut.shoot_through.value) == 0


@cocotb.test()
async def malformed_frames_rejected(dut):
    """Bad checksum (NAK), truncated frames (timeout), framing errors, junk: no register changes."""
    u = await setup(dut)
    await u.write("PERIOD", 777)
    await u.write("DT", 5)
    before = await snapshot(u)
    good = ctl.encode_write(R["PERIOD"], 1234)

    bad = bytearray(good); bad[-1] ^= 0x01     # checksum wrong
    await u.send(bytes(bad))
    assert await u.recv(1) == bytes([ctl.RSP_NAK])
    bad = bytearray(good); bad[3] ^= 0x10      # data corrupted
    await u.send(bytes(bad))
    assert await u.recv(1) == bytes([ctl.RSP_NAK])
    await u.send(bytes(bytearray(ctl.encode_read(R["M"]))[:2] + b"\x00"))   # read with bad checksum
    assert await u.recv(1) == bytes([ctl.RSP_NAK])

    for cut in range(1, len(good)):            # truncated write frames, each dropped by the timeout
        await u.send(good[:cut])
        assert await u.quiet(TIMEOUT_BITS + 20) == b"", f"reply to a frame truncated at {cut}"
    await u.send(ctl.encode_read(R["PERIOD"])[:2])
    assert await u.quiet(TIMEOUT_BITS + 20) == b""

    # a frame whose bytes come too slowly is dropped too (gap > timeout), its tail is ignored as junk
    await u.send(good[:4])
    await ClockCycles(dut.clk, CPB * (TIMEOUT_BITS + 5))
    await u.send(good[4:])
    assert await u.quiet() == b""

    await u.send(good[:3])                     # framing error (stop bit low) in the middle
    await u.send(good[3:4], stop_ok=False)
    await u.send(good[4:])
    assert await u.quiet() in (b"", bytes([ctl.RSP_NAK])), "frame with a framing error accepted"

    await u.send(bytes([0x00, 0xFF, 0x13, 0x4B]))   # junk between frames
    assert await u.quiet() == b""
    assert await snapshot(u) == before, "a rejected frame changed a register"

    # after all that, the link still works and writes again
    await u.write("PERIOD", 1234)
    assert await u.read("PERIOD") == 1234


@cocotb.test()
async def fault_input(dut):
    """fault_ni low: gates off, fault latched and shown, CTRL.en cleared; clear-fault + start resumes."""
    u = await setup(dut)
    await u.write("M", ctl.m_word(0.5))
    await u.write("PERIOD", 64)
    await u.write("CTRL", ctl.CTRL_EN)
    await ClockCycles(dut.clk, 600)
    assert int(dut.edge_count.value) > 0
    dut.fault_ni.value = 0
    await ClockCycles(dut.clk, 5)
    assert int(dut.gate_hi_o.value) == 0 and int(dut.gate_lo_o.value) == 0
    assert int(dut.led_fault_o.value) == 1
    dut.fault_ni.value = 1
    st = await u.read("STATUS")
    assert st & 8 and not st & 1, f"STATUS 0x{st:x}"
    assert await u.read("CTRL") == 0
    await u.write("CTRL", ctl.CTRL_FAULT_CLR)
    assert not (await u.read("STATUS")) & 8 and int(dut.led_fault_o.value) == 0
    await u.write("CTRL", ctl.CTRL_EN)
    n = int(dut.edge_count.value)
    await ClockCycles(dut.clk, 600)
    assert int(dut.edge_count.value) > n, "no restart after clear-fault + start"


def test_ice40_uart(sim):
    from simrun import run_sim
    srcs = (sorted(Path(os.environ.get("ICE40_RTL_DIR", REPO / "rtl")).glob("*.sv")) + sorted((REPO / "fpga/ice40/common").glob("*.sv"))
            + [Path(__file__).parent / "tb_ice40_uart.sv"])
    run_sim(sim, toplevel="tb_ice40_uart", sources=srcs, test_module="test_ice40_uart",
            test_dir=Path(__file__).parent, build_name="default")
