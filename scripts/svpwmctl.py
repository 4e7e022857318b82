#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""svpwmctl: control an svpwm iCE40 board (iCEBreaker / iCEstick) over its UART.

Protocol (fpga/ice40/README.md, fpga/ice40/common/uart_reg_bridge.sv), 115200 8N1:
  write  'W' addr d0 d1 d2 d3 chk   -> 'K'        (d0 = LSB; chk makes the frame's byte sum 0 mod 256)
  read   'R' addr chk               -> d0 d1 d2 d3 chk
  a frame with a bad checksum       -> 'N'

Examples:
  svpwmctl.py --port /dev/ttyUSB1 status
  svpwmctl.py -p /dev/ttyUSB1 set-freq 50 && svpwmctl.py -p /dev/ttyUSB1 set-m 0.9 && ... start
  svpwmctl.py -p /dev/ttyUSB1 set-period --fsw 20000 ; svpwmctl.py -p /dev/ttyUSB1 set-dt 1.5
The port can also be given as $SVPWM_PORT. `svpwmctl.py COMMAND --help` for each command.
"""
from __future__ import annotations

import argparse
import os
import sys
from dataclasses import dataclass

CMD_WRITE, CMD_READ, RSP_ACK, RSP_NAK = 0x57, 0x52, 0x4B, 0x4E

# Minimal register set (to be replaced by the SystemRDL register map): name -> (address, writable)
REGS: dict[str, tuple[int, bool]] = {
    "ID": (0x00, False), "VERSION": (0x01, False), "CONFIG": (0x02, False), "CLK_HZ": (0x03, False),
    "CTRL": (0x04, True), "FREQ": (0x05, True), "M": (0x06, True), "PERIOD": (0x07, True),
    "DT": (0x08, True), "STATUS": (0x09, False),
}
ID_VALUE = 0x5356_5057
CTRL_EN, CTRL_FAULT_CLR = 0x1, 0x2


class ProtocolError(RuntimeError):
    """The board answered, but not as the protocol says."""


class NoAnswer(ProtocolError):
    """The board did not answer in time."""


def checksum(data: bytes) -> int:
    return (-sum(data)) & 0xFF


def encode_write(addr: int, value: int) -> bytes:
    if not 0 <= addr <= 0xFF:
        raise ValueError(f"address {addr} out of range 0..255")
    body = bytes([CMD_WRITE, addr]) + (value & 0xFFFF_FFFF).to_bytes(4, "little")
    return body + bytes([checksum(body)])


def encode_read(addr: int) -> bytes:
    if not 0 <= addr <= 0xFF:
        raise ValueError(f"address {addr} out of range 0..255")
    body = bytes([CMD_READ, addr])
    return body + bytes([checksum(body)])


def decode_read_reply(reply: bytes) -> int:
    if len(reply) == 1 and reply[0] == RSP_NAK:
        raise ProtocolError("board answered NAK (checksum error on the link)")
    if len(reply) != 5:
        raise NoAnswer(f"incomplete read reply ({len(reply)} of 5 bytes): {reply.hex()}")
    if sum(reply) & 0xFF:
        raise ProtocolError(f"read reply checksum error: {reply.hex()}")
    return int.from_bytes(reply[:4], "little")


def decode_write_reply(reply: bytes) -> None:
    if not reply:
        raise NoAnswer("no reply to a write")
    if reply[0] == RSP_NAK:
        raise ProtocolError("board answered NAK (checksum error on the link)")
    if reply[0] != RSP_ACK:
        raise ProtocolError(f"unexpected write reply 0x{reply[0]:02x}")


def reg_addr(name_or_addr: str) -> int:
    key = name_or_addr.upper()
    if key in REGS:
        return REGS[key][0]
    try:
        return int(name_or_addr, 0)
    except ValueError:
        raise SystemExit(f"error: unknown register {name_or_addr!r}; known: {', '.join(REGS)} "
                         f"or a number") from None


@dataclass
class Config:
    clk_hz: int
    phase_width: int
    freq_width: int
    cnt_width: int
    dt_width: int

    @classmethod
    def from_regs(cls, clk_hz: int, config: int) -> "Config":
        return cls(clk_hz, (config >> 24) & 0xFF, (config >> 16) & 0xFF, (config >> 8) & 0xFF, config & 0xFF)

    # physical units <-> register words
    def freq_word(self, hz: float) -> int:
        w = round(hz * 6 * (1 << self.phase_width) / self.clk_hz)
        lim = 1 << (self.freq_width - 1)
        if not -lim <= w < lim:
            raise ValueError(f"{hz} Hz out of range +-{(lim - 1) * self.clk_hz / (6 * (1 << self.phase_width)):.1f} Hz")
        return w

    def freq_hz(self, word: int) -> float:
        if word & (1 << 31):
            word -= 1 << 32
        return word * self.clk_hz / (6 * (1 << self.phase_width))

    def period_word(self, fsw_hz: float) -> int:
        p = round(self.clk_hz / (2 * fsw_hz))
        if not 1 <= p < (1 << self.cnt_width):
            raise ValueError(f"f_sw {fsw_hz} Hz needs a half period of {p} clocks, out of range")
        return p

    def dt_word(self, us: float) -> int:
        d = round(us * self.clk_hz / 1e6)
        if not 0 <= d < (1 << self.dt_width):
            raise ValueError(f"dead time {us} us = {d} clocks, out of range 0..{(1 << self.dt_width) - 1}")
        return d


def m_word(m: float) -> int:
    if not 0 <= m <= 1.0:
        raise ValueError(f"modulation index {m} out of range 0..1")
    return round(m * 0x8000)


class Board:
    """Register access over a pyserial-like port (read(n), write(b), reset_input_buffer())."""

    def __init__(self, port):
        self.port = port
        self._cfg: Config | None = None

    def _xfer(self, frame: bytes, n: int) -> bytes:
        if hasattr(self.port, "reset_input_buffer"):
            self.port.reset_input_buffer()
        self.port.write(frame)
        return self.port.read(n)

    def read(self, addr: int) -> int:
        reply = self._xfer(encode_read(addr), 5)
        if not reply:
            raise NoAnswer("the board does not answer (wrong port, not programmed, or baud rate?)")
        return decode_read_reply(reply)

    def write(self, addr: int, value: int) -> None:
        reply = self._xfer(encode_write(addr, value), 1)
        if not reply:
            raise NoAnswer("the board does not answer (wrong port, not programmed, or baud rate?)")
        decode_write_reply(reply)

    def config(self) -> Config:
        if self._cfg is None:
            ident = self.read(REGS["ID"][0])
            if ident != ID_VALUE:
                raise ProtocolError(f"unexpected ID 0x{ident:08x} (expected 0x{ID_VALUE:08x}): not an svpwm board?")
            self._cfg = Config.from_regs(self.read(REGS["CLK_HZ"][0]), self.read(REGS["CONFIG"][0]))
        return self._cfg

    def status(self) -> dict:
        cfg = self.config()
        r = {name: self.read(a) for name, (a, _) in REGS.items()}
        st = r["STATUS"]
        return {
            "enabled": bool(r["CTRL"] & CTRL_EN), "running": bool(st & 1), "sat": bool(st & 2),
            "period_clamp": bool(st & 4), "fault": bool(st & 8), "fault_pin": bool(st & 16),
            "sector": (st >> 8) & 7,
            "freq_hz": round(cfg.freq_hz(r["FREQ"]), 4), "m": r["M"] / 0x8000,
            "f_sw_hz": round(cfg.clk_hz / (2 * r["PERIOD"]), 2) if r["PERIOD"] else None,
            "period_clocks": r["PERIOD"], "dt_us": round(r["DT"] * 1e6 / cfg.clk_hz, 4), "dt_clocks": r["DT"],
            "clk_hz": cfg.clk_hz,
        }


def open_port(name: str | None, baud: int, timeout: float):
    if not name:
        raise SystemExit("error: no serial port: give --port (e.g. /dev/ttyUSB1) or set $SVPWM_PORT")
    try:
        import serial
    except ImportError:
        raise SystemExit("error: pyserial is not installed (pip install pyserial; `make venv`)") from None
    try:
        return serial.Serial(name, baud, timeout=timeout)
    except (serial.SerialException, OSError) as e:
        raise SystemExit(f"error: cannot open serial port {name}: {e}") from None


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="svpwmctl", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-p", "--port", default=os.environ.get("SVPWM_PORT"),
                    help="serial port (default $SVPWM_PORT); iCEBreaker/iCEstick: the FTDI's 2nd port")
    ap.add_argument("-b", "--baud", type=int, default=115200)
    ap.add_argument("-t", "--timeout", type=float, default=0.5, help="reply timeout in seconds")
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")

    def add(name, help_, **kw):
        return sub.add_parser(name, help=help_, description=help_, **kw)

    p = add("read", "read a register by name (ID, CTRL, FREQ, M, PERIOD, DT, STATUS, ...) or address")
    p.add_argument("reg")
    p = add("write", "write a raw value to a register by name or address")
    p.add_argument("reg")
    p.add_argument("value", help="integer, e.g. 1536 or 0x600")
    add("dump", "read all registers")
    add("status", "show the state in physical units")
    add("start", "enable modulation (CTRL.en = 1)")
    add("stop", "disable modulation: all gates off (CTRL.en = 0)")
    add("clear-fault", "clear the latched fault (modulation stays stopped until `start`)")
    p = add("set-freq", "set the output frequency in Hz (negative = reverse rotation)")
    p.add_argument("hz", type=float)
    p = add("set-m", "set the modulation index 0..1")
    p.add_argument("m", type=float)
    p = add("set-period", "set the carrier: switching frequency in Hz or half period in clocks")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--fsw", type=float, help="switching (carrier) frequency in Hz")
    g.add_argument("--clocks", type=int, help="half carrier period in core clocks")
    p = add("set-dt", "set the dead time in microseconds")
    p.add_argument("us", type=float)
    return ap


def run(args, board: Board) -> str:
    c = args.cmd
    if c == "read":
        return f"0x{board.read(reg_addr(args.reg)):08x}"
    if c == "write":
        board.write(reg_addr(args.reg), int(args.value, 0))
        return "ok"
    if c == "dump":
        return "\n".join(f"{n:8} 0x{a:02x}  0x{board.read(a):08x}" for n, (a, _) in REGS.items())
    if c == "status":
        return "\n".join(f"{k:14} {v}" for k, v in board.status().items())
    if c == "start":
        board.write(REGS["CTRL"][0], CTRL_EN)
        return "started"
    if c == "stop":
        board.write(REGS["CTRL"][0], 0)
        return "stopped"
    if c == "clear-fault":
        board.write(REGS["CTRL"][0], CTRL_FAULT_CLR)
        return "fault cleared" if not board.read(REGS["STATUS"][0]) & 8 else "fault still present (fault pin active)"
    cfg = board.config()
    if c == "set-freq":
        w = cfg.freq_word(args.hz)
        board.write(REGS["FREQ"][0], w)
        return f"FREQ = {w} ({cfg.freq_hz(w & 0xFFFF_FFFF):.4f} Hz)"
    if c == "set-m":
        w = m_word(args.m)
        board.write(REGS["M"][0], w)
        return f"M = 0x{w:04x}"
    if c == "set-period":
        w = args.clocks if args.clocks is not None else cfg.period_word(args.fsw)
        board.write(REGS["PERIOD"][0], w)
        return f"PERIOD = {w} clocks (f_sw {cfg.clk_hz / (2 * w):.2f} Hz)"
    if c == "set-dt":
        w = cfg.dt_word(args.us)
        board.write(REGS["DT"][0], w)
        return f"DT = {w} clocks ({w * 1e6 / cfg.clk_hz:.4f} us)"
    raise SystemExit(f"error: unknown command {c}")


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    port = open_port(args.port, args.baud, args.timeout)
    try:
        print(run(args, Board(port)))
    except NoAnswer as e:
        print(f"error: {args.port}: {e}", file=sys.stderr)
        return 3
    except (ProtocolError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 4
    finally:
        port.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
