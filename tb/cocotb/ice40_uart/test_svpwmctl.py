# SPDX-License-Identifier: Apache-2.0
"""scripts/svpwmctl.py without hardware: frame encoding (golden bytes of the protocol in
fpga/ice40/README.md), reply decoding, unit conversions, and the Board class against a fake port
that implements the protocol. The same encoder / decoder is run against the RTL by test_ice40_uart.py.
"""
from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "scripts"))
import svpwmctl as ctl  # noqa: E402


def test_frames():
    assert ctl.encode_read(0x07) == bytes([0x52, 0x07, (-(0x52 + 0x07)) & 0xFF])
    f = ctl.encode_write(0x07, 0x0000_0600)
    assert f[:6] == bytes([0x57, 0x07, 0x00, 0x06, 0x00, 0x00]) and sum(f) & 0xFF == 0
    assert ctl.encode_write(0x05, -1)[2:6] == b"\xff\xff\xff\xff"
    reply = (0x5356_5057).to_bytes(4, "little")
    assert ctl.decode_read_reply(reply + bytes([ctl.checksum(reply)])) == 0x5356_5057
    with pytest.raises(ctl.ProtocolError):
        ctl.decode_read_reply(reply + bytes([ctl.checksum(reply) ^ 1]))
    with pytest.raises(ctl.NoAnswer):
        ctl.decode_read_reply(reply[:3])
    with pytest.raises(ctl.ProtocolError):
        ctl.decode_read_reply(bytes([ctl.RSP_NAK]))
    with pytest.raises(ctl.NoAnswer):
        ctl.decode_write_reply(b"")
    with pytest.raises(ValueError):
        ctl.encode_read(256)


def test_units():
    c = ctl.Config.from_regs(48_000_000, (34 << 24) | (24 << 16) | (16 << 8) | 10)
    assert (c.phase_width, c.freq_width, c.cnt_width, c.dt_width) == (34, 24, 16, 10)
    assert c.period_word(15625) == 1536
    assert c.dt_word(1.0) == 48
    assert abs(c.freq_hz(c.freq_word(50.0)) - 50.0) < 0.001
    assert c.freq_hz(c.freq_word(-50.0) & 0xFFFF_FFFF) < 0
    assert ctl.m_word(1.0) == 0x8000 and ctl.m_word(0.5) == 0x4000
    for bad in (lambda: c.dt_word(100.0), lambda: c.freq_word(1e5), lambda: ctl.m_word(1.5)):
        with pytest.raises(ValueError):
            bad()


class FakeBoard:
    """The protocol of uart_reg_bridge.sv in Python (for the Board class, not a model of the RTL)."""

    def __init__(self, answer=True):
        self.regs = {0: ctl.ID_VALUE, 2: (34 << 24) | (24 << 16) | (16 << 8) | 10, 3: 48_000_000,
                     4: 0, 5: 0, 6: 0, 7: 1536, 8: 48, 9: 0}
        self.out = b""
        self.answer = answer

    def write(self, frame: bytes):
        if not self.answer:
            return
        if sum(frame) & 0xFF:
            self.out = bytes([ctl.RSP_NAK])
        elif frame[0] == ctl.CMD_WRITE:
            self.regs[frame[1]] = int.from_bytes(frame[2:6], "little")
            self.out = bytes([ctl.RSP_ACK])
        else:
            d = self.regs.get(frame[1], 0).to_bytes(4, "little")
            self.out = d + bytes([ctl.checksum(d)])

    def read(self, n):
        out, self.out = self.out[:n], self.out[n:]
        return out


def test_board_commands():
    fb = FakeBoard()
    b = ctl.Board(fb)
    p = ctl.build_parser()
    assert "15625.0" in ctl.run(p.parse_args(["status"]), b)
    ctl.run(p.parse_args(["set-period", "--fsw", "20000"]), b)
    assert fb.regs[7] == 1200
    ctl.run(p.parse_args(["set-dt", "0.5"]), b)
    assert fb.regs[8] == 24
    ctl.run(p.parse_args(["set-m", "0.9"]), b)
    assert fb.regs[6] == round(0.9 * 0x8000)
    ctl.run(p.parse_args(["set-freq", "50"]), b)
    assert fb.regs[5] == ctl.Config.from_regs(48_000_000, fb.regs[2]).freq_word(50)
    ctl.run(p.parse_args(["start"]), b)
    assert fb.regs[4] == 1
    ctl.run(p.parse_args(["write", "PERIOD", "0x600"]), b)
    assert ctl.run(p.parse_args(["read", "period"]), b) == "0x00000600"
    with pytest.raises(ctl.NoAnswer):
        ctl.Board(FakeBoard(answer=False)).read(0)


def test_cli_help_and_errors():
    exe = [sys.executable, str(REPO / "scripts/svpwmctl.py")]
    for cmd in ([], ["status"], ["set-period"], ["set-dt"], ["read"], ["clear-fault"]):
        r = subprocess.run(exe + cmd + ["--help"], capture_output=True, text=True)
        assert r.returncode == 0 and "usage:" in r.stdout
    r = subprocess.run(exe + ["status"], capture_output=True, text=True, env={"PATH": ""})
    assert r.returncode != 0 and "no serial port" in r.stderr
    r = subprocess.run(exe + ["-p", "/dev/does-not-exist", "status"], capture_output=True, text=True)
    assert r.returncode != 0 and "cannot open serial port" in r.stderr
