# SPDX-License-Identifier: Apache-2.0
"""scripts/svpwmctl.py without hardware: frame encoding (golden bytes of the protocol in
fpga/ice40/README.md), reply decoding, exact unit conversions, and every command against a fake board
(FakeBoard: the frame protocol + the register semantics of the generated map, built from regmap.py),
directly and through the command line over a pseudo-terminal. The same encoder / decoder runs against
the RTL in test_ice40_uart.py.
"""
from __future__ import annotations

import os
import subprocess
import sys
import threading
import time
from fractions import Fraction
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
sys.path.insert(0, str(REPO / "scripts"))
import svpwmctl as ctl  # noqa: E402
from svpwm_model import config, fixed, ideal  # noqa: E402
from svpwm_model import regmap as R  # noqa: E402

MAP_VERSION = f"{R.VERSION.field('major').reset}.{R.VERSION.field('minor').reset}"   # generated map
CONFIG_48 = R.CONFIG.reset       # the widths of the generated map: PhaseWidth 34, FreqWidth 24, Cnt 16, Dt 10


class FakeBoard:
    """The board as svpwmctl sees it: uart_reg_bridge's frames (incl. NAK) and svpwm_regs' register
    semantics (RW masks, RO ignored, w1s sticky, pulse reads 0, unmapped reads 0), from regmap.py.
    A pyserial-like port: write(bytes) / read(n). `status` is what the core drives into STATUS; a
    CTRL.fault_clear pulse clears its tripped bit unless the fault bit is set (the core's latch).
    features, trim: the build (R.variant(features, trim): absent registers and fields read 0, ignore writes)."""

    def __init__(self, clk_hz=48_000_000, answer=True, version=None, features=config.FULL, trim=False,
                 cnt_width=16):
        self.map = {r.addr: r for r in R.variant(features, trim)}
        self.regs = {r.addr: r.reset for r in self.map.values()}
        self.regs[R.CLK_HZ.addr] = clk_hz
        self.regs[R.CONFIG.addr] = R.CONFIG.encode(**{**R.CONFIG.decode(R.CONFIG.reset), "cnt_width": cnt_width})
        self.regs[R.FEATURES.addr] = R.FEATURES.encode(features=features, trim=int(trim))
        if version is not None:
            self.regs[R.VERSION.addr] = version
        self.status = 0
        self.answer = answer
        self.writes: list[tuple[int, int]] = []       # (addr, value) of every accepted write frame
        self.reads: list[int] = []
        self._in = b""
        self._out = b""

    def value(self, reg: R.Register) -> int:
        return self.status if reg.name == "STATUS" else self.regs[reg.addr]

    def _frame(self, f: bytes) -> bytes:
        if sum(f) & 0xFF:
            return bytes([ctl.RSP_NAK])
        addr, reg = f[1], self.map.get(f[1] & 0xFC)
        if f[0] == ctl.CMD_WRITE:
            v = int.from_bytes(f[2:6], "little")
            self.writes.append((addr, v))
            if reg is not None:
                old = self.regs[reg.addr]
                self.regs[reg.addr] = (old & ~reg.mask("rw")) | (v & reg.mask("rw")) | (old & reg.mask("w1s")) \
                    | (v & reg.mask("w1s"))
                if reg.name == "CTRL" and R.CTRL.decode(v)["fault_clear"] and not R.STATUS.decode(self.status)["fault"]:
                    self.status &= ~R.STATUS.field("tripped").mask
            return bytes([ctl.RSP_ACK])
        self.reads.append(addr)
        d = (self.value(reg) if reg is not None else 0).to_bytes(4, "little")
        return d + bytes([ctl.checksum(d)])

    def write(self, data: bytes):
        if not self.answer:
            return
        self._in += data
        while self._in:
            n = {ctl.CMD_WRITE: 7, ctl.CMD_READ: 3}.get(self._in[0])
            if n is None:
                self._in = self._in[1:]               # not a frame start: ignored
            elif len(self._in) < n:
                break
            else:
                self._out += self._frame(self._in[:n])
                self._in = self._in[n:]

    def read(self, n):
        out, self._out = self._out[:n], self._out[n:]
        return out


def cmd(fb: FakeBoard, *argv, clk_hz=None) -> str:
    args = ctl.build_parser().parse_args(list(argv))
    return ctl.run(args, ctl.Board(fb, clk_hz))


# --------------------------------------------------------------------------- frames and units
def test_frames():
    assert ctl.encode_read(0x30) == bytes([0x52, 0x30, (-(0x52 + 0x30)) & 0xFF]) == bytes([0x52, 0x30, 0x7E])
    assert ctl.encode_write(0x30, 0x0000_0600) == bytes([0x57, 0x30, 0x00, 0x06, 0x00, 0x00, 0x73])
    assert ctl.encode_write(0x10, -1)[2:6] == b"\xff\xff\xff\xff"
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
    with pytest.raises(ctl.ProtocolError):
        ctl.decode_write_reply(b"X")
    with pytest.raises(ValueError):
        ctl.encode_read(256)


def test_names_come_from_regmap():
    assert ctl.lookup("period") == (R.PERIOD, 0x30, None)
    assert ctl.lookup("CLK_HZ")[1] == 0x58 and ctl.lookup("0x58")[0] is R.CLK_HZ
    assert ctl.lookup("ctrl.MODE") == (R.CTRL, 0x0C, R.CTRL.field("mode"))
    assert ctl.lookup("0xc0") == (None, 0xC0, None)
    assert ctl.lookup("win_status.recon") == (R.WIN_STATUS, 0x88, R.WIN_STATUS.field("recon"))
    for bad in ("NOPE", "CTRL.nope", "0xc0.x", "300"):
        with pytest.raises(ValueError):
            ctl.lookup(bad)


def test_units_exact():
    c = ctl.Config.from_regs(48_000_000, CONFIG_48)
    assert (c.phase_width, c.freq_width, c.cnt_width, c.dt_width) == (34, 24, 16, 10)
    # f_out = word * f_clk / (6 * 2^34): 50 Hz -> 107374.18 -> 107374 (README), and back exactly
    assert c.freq_lsb == Fraction(48_000_000, 6 << 34)
    assert c.freq_word(Fraction(50)) == 107374 and c.freq_word(Fraction(-50)) == -107374
    assert c.freq_hz(107374) == Fraction(107374 * 48_000_000, 6 << 34)
    assert c.freq_word(Fraction(5, 2) * c.freq_lsb) == 3 and c.freq_word(Fraction(-5, 2) * c.freq_lsb) == -3
    assert c.freq_word((2**23 - 1) * c.freq_lsb) == 2**23 - 1
    for hz in (Fraction(2**23) * c.freq_lsb, Fraction(-(2**23)) * c.freq_lsb, Fraction(3907)):
        with pytest.raises(ValueError, match="out of range"):
            c.freq_word(hz)
    assert c.half_period(Fraction(15625)) == 1536 and c.half_period(Fraction(20000)) == 1200
    assert c.fsw_hz(1536) == 15625
    assert c.clocks(Fraction(1), "dt") == 48 and c.clocks(Fraction(1, 96), "dt") == 1      # 0.5 clock -> 1
    assert c.clocks(Fraction(1023, 48), "dt") == 1023 and c.us(48) == 1
    for us in (Fraction(1024, 48), Fraction(-1), Fraction(1, 100)):        # too long, negative, rounds to 0
        with pytest.raises(ValueError):
            c.clocks(us, "dt")
    assert ctl.m_word(1) == 0x8000 and ctl.m_word(Fraction("0.5")) == 0x4000
    assert ctl.m_word(Fraction(0xFFFF, 0x8000)) == 0xFFFF
    for m in (2, Fraction(-1, 10)):
        with pytest.raises(ValueError, match="out of range"):
            ctl.m_word(m)


# --------------------------------------------------------------------------- commands on the fake board
def test_set_commands_write_exact_words():
    fb = FakeBoard()
    assert cmd(fb, "set-dt", "0.5") == "DT = 24 clocks (0.5 us)" and fb.regs[R.DT.addr] == 24
    assert cmd(fb, "set-mp", "0.25") == "MP = 12 clocks (0.25 us)" and fb.regs[R.MP.addr] == 12
    assert cmd(fb, "set-period", "--fsw", "20000") == "PERIOD = 1200 clocks (f_sw 20000 Hz)"
    assert fb.regs[R.PERIOD.addr] == 1200 and fb.writes[-1] == (R.PERIOD.addr, 1200)
    cmd(fb, "set-period", "--clocks", "777")
    assert fb.regs[R.PERIOD.addr] == 777
    assert cmd(fb, "set-m", "0.9") == "M = 0x7333 (m = 0.899994)" and fb.regs[R.M.addr] == 0x7333
    cmd(fb, "set-freq", "50")
    assert fb.regs[R.FREQ.addr] == 107374
    cmd(fb, "set-freq", "-50")
    assert fb.writes[-1] == (R.FREQ.addr, (-107374) & 0xFFFFFF)          # 24-bit two's complement field
    assert cmd(fb, "read", "FREQ.freq") == "-107374"
    cmd(fb, "set-mode", "vf", "--dpwm", "dpwm1", "--upd", "both")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(mode=1, dpwm=3, upd=2)
    cmd(fb, "start")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(en=1, mode=1, dpwm=3, upd=2)      # other fields kept
    cmd(fb, "set-mode", "polar")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(en=1, mode=2, dpwm=3, upd=2)
    cmd(fb, "stop")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(mode=2, dpwm=3, upd=2)
    assert cmd(fb, "set-mode", "freq", "--om", "sixstep") == "CTRL.mode = 0, CTRL.om = 1"
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(mode=0, dpwm=3, upd=2, om=1)
    cmd(fb, "set-m", "1.08", "--fundamental")                     # the six-step law's map (ideal.py)
    w = fb.regs[R.M.addr]
    assert w == round(ideal.overmod_m_for(1.08) * 0x8000) and 0x93CD < w < 0x9500
    assert abs(ideal.overmod_fundamental(w / 0x8000, True) - 1.08) < 2e-3
    assert cmd(fb, "set-m", "0.9", "--fundamental") == "M = 0x7333 (m = 0.899994)"  # linear range: m itself
    assert cmd(fb, "set-dtc", "on", "--isign", "0b101") == "DTC.en = 1, DTC.isign = 5"
    assert fb.regs[R.DTC.addr] == R.DTC.encode(en=1, isign=5) == 0x51
    assert cmd(fb, "set-carry", "off") == "CTRL.vsc_off = 1" and R.CTRL.decode(fb.regs[R.CTRL.addr])["vsc_off"]
    cmd(fb, "set-carry", "on")
    cmd(fb, "set-dtc", "off")
    assert fb.regs[R.DTC.addr] == R.DTC.encode(en=0, isign=5)                   # the signs kept


def test_status_and_reads():
    fb = FakeBoard()
    cmd(fb, "set-dt", "1")
    cmd(fb, "set-freq", "50")
    fb.status = R.STATUS.encode(running=1, sector=4, sat=1)
    st = dict(line.split(None, 1) for line in cmd(fb, "status").splitlines())
    assert st["running"] == "1" and st["sector"] == "4" and st["sat"] == "1" and st["tripped"] == "0"
    assert st["freq_word"] == "107374" and st["freq_hz"] == "49.999915"     # 107374 * 48e6 / (6 * 2^34)
    assert st["fsw_hz"] == "15625" and st["period_clocks"] == "1536" and st["dt_us"] == "1"
    assert st["clk_hz"] == "48000000" and st["mode"] == "freq" and st["m"] == "0"
    assert cmd(fb, "read", "period") == "0x00000600  period=1536"
    assert cmd(fb, "read", "status.sector") == "4"
    assert cmd(fb, "read", "0xc0") == "0x00000000"
    assert cmd(fb, "read", "CLK_HZ") == "0x02dc6c00  clk_hz=48000000"
    assert cmd(fb, "info").startswith(f"ID 0x53565057 (svpwm), register map {MAP_VERSION}, clock 48000000 Hz")
    assert cmd(fb, "info").endswith("DtWidth 10, build full (FEATURES.features 0x7fff: freq, vf, polar, ab, dq, dpwm, "
                                    "sixstep, dtc, carry, dtf, upd, presc, sync, dsp, adc)") and st["build"] == "full"
    dump = cmd(fb, "dump").splitlines()
    assert [line.split()[1] for line in dump] == [r.name for r in R.REGISTERS]
    cmd(fb, "write", "CTRL.mode", "7")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(mode=7)
    cmd(fb, "write", "ctrl", "0x101")
    assert fb.regs[R.CTRL.addr] == 0x101
    cmd(fb, "write", "FREQ.freq", "-1")
    assert fb.regs[R.FREQ.addr] == 0xFFFFFF


def test_clear_fault():
    fb = FakeBoard()
    fb.status = R.STATUS.encode(tripped=1, fault=1)
    with pytest.raises(ctl.ProtocolError, match="fault input is active"):
        cmd(fb, "clear-fault")
    assert fb.writes[-1] == (R.CTRL.addr, R.CTRL.encode(fault_clear=1))
    fb.status = R.STATUS.encode(tripped=1)
    assert cmd(fb, "clear-fault") == "fault cleared" and fb.status == 0


def test_board_clock_from_clk_hz():
    fb = FakeBoard(clk_hz=12_000_000)                  # CLK_HZ decides the conversions
    cmd(fb, "set-period", "--fsw", "20000")
    assert fb.regs[R.PERIOD.addr] == 300
    fb = FakeBoard(clk_hz=0)                           # not stated: --clk-hz needed
    with pytest.raises(ValueError, match="--clk-hz"):
        cmd(fb, "set-dt", "1")
    assert cmd(fb, "set-dt", "1", clk_hz=24_000_000) == "DT = 24 clocks (1 us)"
    with pytest.raises(ValueError, match="disagrees"):
        cmd(FakeBoard(), "set-dt", "1", clk_hz=24_000_000)
    with pytest.raises(ctl.ProtocolError, match="version 1.0"):
        cmd(FakeBoard(version=0x0001_0000), "set-dt", "1")


@pytest.mark.parametrize("argv, match", [
    (["set-freq", "3907"], "out of range"),
    (["set-freq", "fifty"], "not a number"),
    (["set-m", "2"], "out of range"),
    (["set-period", "--fsw", "100"], f"out of range {fixed.MIN_PERIOD} .. 65535"),       # 240000 clocks
    (["set-period", "--clocks", str(fixed.MIN_PERIOD - 1)], f"out of range {fixed.MIN_PERIOD} .. 65535"),
    (["set-dt", "30"], "at most 1023 clocks"),
    (["set-dt", "16.5"], "PERIOD >= 2 \\(max\\(dt, dtf\\) \\+ MP\\) = 1584"),   # 792 clocks vs PERIOD 1536
    (["set-dt", "1", "--dt-fall", "16.5"], "PERIOD >= 2 \\(max\\(dt, dtf\\) \\+ MP\\) = 1584"),   # the falling one
    (["set-dt", "1", "--dt-fall", "30"], "falling dead time 30 us = 1440 clocks is out of range"),
    (["write", "CTRL.mode", "8"], "out of range 0 .. 7"),
    (["write", "FREQ.freq", "8388608"], "out of range -8388608 .. 8388607"),
    (["write", "STATUS.sector", "1"], "read-only"),
    (["write", "PERIOD", "0x1_0000_0000"], "32 bits"),
    (["start"], "DT is 0"),
    (["set-adc-pt", "0", "--count", "65536"], "ADC_PT0.cnt = 65536 is out of range 0 .. 65535"),
    (["set-adc-pt", "1", "--count", "-1", "--down"], "ADC_PT1.cnt = -1 is out of range 0 .. 65535"),
    (["set-adc-pt", "0", "--off", "--down"], "--down with --off"),
    (["set-win-min", "--clocks", "131072"], "WIN_MIN.win_min = 131072 is out of range 0 .. 131071"),
    (["set-win-min", "--us", "2731"], "minimum window 2731 us = 131088 clocks is out of range: at most 131071"),
    (["set-win-min", "--us", "0.001"], "less than half a clock"),
])
def test_bad_values_refused_nothing_written(argv, match):
    fb = FakeBoard()
    with pytest.raises(ValueError, match=match):
        cmd(fb, *argv)
    assert fb.writes == [], f"{argv}: wrote {fb.writes} although the value was refused"


def test_falling_dead_time():
    """set-dt US --dt-fall US: DT.dt = the rising, DT.dtf = the falling dead time, DT.dtf_en = 1; set-dt
    without it: one dead time (dtf_en = 0, dtf 0); the period rules and the start check use both; status
    shows both."""
    fb = FakeBoard()
    out = cmd(fb, "set-dt", "0.5", "--dt-fall", "0.75")
    assert out == "DT = 24 clocks (0.5 us) rising, 36 clocks (0.75 us) falling (DT.dtf, dtf_en = 1)", out
    assert fb.regs[R.DT.addr] == R.DT.encode(dt=24, dtf=36, dtf_en=1) == (1 << 31) | (36 << 16) | 24
    st = dict(line.split(None, 1) for line in cmd(fb, "status").splitlines())
    assert (st["dt_clocks"], st["dt_fall_clocks"], st["dt_us"], st["dt_fall_us"]) == ("24", "36", "0.5", "0.75")
    # the period floor is 2 (max(dt, dtf) + MP): dtf 300 clocks needs PERIOD >= 600 (or refuses a shorter one)
    cmd(fb, "set-dt", "0.5", "--dt-fall", f"{300 / 48:.4f}")
    assert R.DT.decode(fb.regs[R.DT.addr]) == {"dt": 24, "dtf": 300, "dtf_en": 1}
    with pytest.raises(ValueError, match="out of range 600 .. 65535"):
        cmd(fb, "set-period", "--clocks", "599")
    cmd(fb, "set-period", "--clocks", "600")
    with pytest.raises(ValueError, match="PERIOD >= 2 \\(max\\(dt, dtf\\) \\+ MP\\) = 602"):
        cmd(fb, "set-mp", f"{1 / 48:.4f}")            # 1 clock more: 2 (300 + 1) > 600
    # back to one dead time: dtf_en cleared, dtf 0
    assert cmd(fb, "set-dt", "1") == "DT = 48 clocks (1 us)"
    assert fb.regs[R.DT.addr] == 48
    st = dict(line.split(None, 1) for line in cmd(fb, "status").splitlines())
    assert st["dt_fall_clocks"] == "48"
    # a zero falling dead time: start refuses (as with DT 0) unless --allow-zero-dt
    cmd(fb, "set-dt", "1", "--dt-fall", "0")
    n = len(fb.writes)
    with pytest.raises(ValueError, match="falling dead time DT.dtf"):
        cmd(fb, "start")
    assert len(fb.writes) == n
    cmd(fb, "start", "--allow-zero-dt")
    # locked: refused, nothing written
    fb.status = R.STATUS.encode(locked=1)
    n = len(fb.writes)
    with pytest.raises(ValueError, match="locked"):
        cmd(fb, "set-dt", "1", "--dt-fall", "2")
    assert len(fb.writes) == n


def test_locked_and_period_rules():
    fb = FakeBoard()
    p = fixed.MIN_PERIOD                               # the shortest period (254)
    cmd(fb, "set-period", "--clocks", str(p))
    with pytest.raises(ValueError, match="PERIOD >= 2"):
        cmd(fb, "set-dt", f"{(p // 2 + 1) / 48:.4f}")  # p // 2 + 1 clocks at 48 MHz: 2 dt > p
    cmd(fb, "set-dt", f"{(p // 2) / 48:.4f}")          # p // 2 clocks: 2 dt <= p fits
    cmd(fb, "set-period", "--clocks", "1536")
    fb.status = R.STATUS.encode(locked=1)
    n = len(fb.writes)
    with pytest.raises(ValueError, match="locked"):
        cmd(fb, "set-dt", "1")
    assert len(fb.writes) == n
    cmd(fb, "start")
    assert fb.regs[R.CTRL.addr] == R.CTRL.encode(en=1)


def test_tiny_trim_board():
    """The iCEstick's board (FEATURES: tiny, trim = 1): the registers and fields it has work as on the full
    board; commands and writes that need what it lacks are refused with a message naming it, nothing
    written; info / status / dump say what was built. Its 12-bit carrier (CONFIG.cnt_width): PERIOD above
    4095 is refused."""
    fb = FakeBoard(features=config.TINY, trim=True, cnt_width=12)
    info = cmd(fb, "info")
    assert info.startswith(f"ID 0x53565057 (svpwm), register map {MAP_VERSION}, clock 48000000 Hz")
    assert "CntWidth 12" in info, info
    assert info.endswith("build tiny (FEATURES.features 0x0001: freq); board cut (FEATURES.trim): no MP, "
                         "CTRL.mode, CTRL.adc_trig, STATUS.sector, CARRIER, PERIOD_ACT, CMP_*"), info
    cmd(fb, "set-dt", "0.5")
    cmd(fb, "set-period", "--fsw", "20000")
    cmd(fb, "set-freq", "50")
    cmd(fb, "set-m", "0.9")
    cmd(fb, "write", "CTRL.pol", "2")
    cmd(fb, "start")
    assert [fb.regs[r.addr] for r in (R.DT, R.PERIOD, R.FREQ, R.M, R.CTRL)] == \
        [24, 1200, 107374, 0x7333, R.CTRL.encode(en=1, pol=2)]
    assert R.MP.addr not in fb.regs                    # no MP register on this board
    cmd(fb, "write", "CTRL", "0x35")                   # only present fields: accepted
    assert fb.regs[R.CTRL.addr] == 0x35
    cmd(fb, "write", "0xc0", "1")                      # unmapped in every build: as before
    lo = fixed.latencies(config.TINY)["MIN_PERIOD"]    # the tiny build's MinPeriod (SampleLead + 4)
    assert ctl.min_period(config.TINY) == lo == fixed.LITE_MIN_PERIOD and ctl.MIN_PERIOD == fixed.MIN_PERIOD
    with pytest.raises(ValueError, match=f"out of range {lo} .. 4095"):
        cmd(fb, "set-period", "--clocks", str(lo - 1))
    with pytest.raises(ValueError, match=f"out of range {lo} .. 4095"):
        cmd(fb, "set-period", "--clocks", "4096")
    cmd(fb, "set-period", "--clocks", str(lo))
    assert fb.regs[R.PERIOD.addr] == lo
    st = dict(line.split(None, 1) for line in cmd(fb, "status").splitlines())
    assert (st["build"], st["trim"], st["mode"], st["period_act_clocks"]) == ("tiny", "1", "freq", "-")
    assert st["mp_clocks"] == "-" and st["mp_us"] == "-"
    assert [line.split()[1] for line in cmd(fb, "dump").splitlines()] == \
        [r.name for r in R.variant(config.TINY, True)]
    absent = [r for r in R.REGISTERS if not R.built(r, config.TINY, True)]
    assert {r.name for r in absent} == {"THETA", "V1", "V2", "VF_BOOST", "VF_SLOPE", "VF_MMAX", "PRESC",
                                        "CARRIER", "PERIOD_ACT", "CMP_A", "CMP_B", "CMP_C", "MP", "DTC",
                                        "ADC_PT0", "ADC_PT1", "WIN_MIN", "WIN_LO_A", "WIN_LO_B", "WIN_LO_C",
                                        "WIN_HI_A", "WIN_HI_B", "WIN_HI_C", "WIN_STATUS"}
    word = "FEATURES = 0x80000001, tiny"
    refused = {  # command -> what the message names
        ("set-mode", "vf"): "mode vf: not on this board (no vf;",
        ("set-mode", "freq"): "CTRL.mode: not on this board (board cut: FEATURES.trim = 1;",
        ("set-mode", "freq", "--dpwm", "svpwm"): "CTRL.mode: not on this board (board cut",
        ("set-mode", "freq", "--om", "sixstep"): "--om sixstep: not on this board (no sixstep;",
        ("set-mode", "freq", "--upd", "peak"): "--upd peak: not on this board (no upd;",
        ("set-mp", "0.25"): "MP: not on this board (board cut",
        ("set-dtc", "on"): "set-dtc: not on this board (no dtc;",
        ("set-carry", "off"): "set-carry: not on this board (no carry;",
        ("set-dt", "0.5", "--dt-fall", "1"): "--dt-fall: not on this board (no dtf;",
        ("write", "CTRL.mode", "0"): "CTRL.mode: not on this board (board cut",
        ("write", "CTRL.sync_en", "1"): "CTRL.sync_en: not on this board (no sync;",
        ("write", "ctrl.adc_trig", "1"): "CTRL.adc_trig: not on this board (board cut",
        ("write", "CTRL", "0x101"): "CTRL.mode: not on this board (board cut",
        ("write", "CTRL", "0x2"): "CTRL.sync_en: not on this board (no sync;",
        ("write", "THETA", "0"): "THETA: not on this board (no polar or dq;",
        ("write", "0x1c", "1"): "V1: not on this board (no ab or dq;",
        ("write", "VF_MMAX.vf_mmax", "1"): "VF_MMAX: not on this board (no vf;",   # the whole register
    }
    refused |= {("write", r.name, "0"): f"{r.name}: not on this board" for r in absent}
    refused |= {("write", f"0x{r.addr:x}", "1"): f"{r.name}: not on this board" for r in absent}
    refused |= {("write", f"{r.name}.{f.name}", "1"): f"{r.name}: not on this board"
                for r in absent for f in r.fields if f.writable}
    before = dict(fb.regs)
    fb.writes.clear()
    for argv, msg in refused.items():
        with pytest.raises(ValueError) as e:
            cmd(fb, *argv)
        assert str(e.value).startswith(msg) and word in str(e.value), (argv, str(e.value))
    assert fb.writes == [] and fb.regs == before
    with pytest.raises(ValueError, match=r"CTRL.mode, CTRL.dpwm: not on this board"):
        cmd(fb, "write", "CTRL", hex(R.CTRL.encode(mode=1, dpwm=1, en=1)))
    # the same commands on a full board are accepted; a board of map 2.x (FEATURES.compact) is refused
    fb = FakeBoard()
    for argv in refused:
        cmd(fb, *argv)
    assert fb.regs[R.THETA.addr] == 1 and fb.regs[R.FEATURES.addr] == config.FULL
    with pytest.raises(ctl.ProtocolError, match=r"register map version 2.4 is not supported \(this tool: 3.x\)"):
        cmd(FakeBoard(version=0x0002_0004), "set-mode", "vf")


def test_minimal_board():
    """A build without some features (minimal: POLAR only): its commands work, the others are refused
    naming the feature; MinPeriod is the build's."""
    fb = FakeBoard(features=config.CONFIGS["minimal"])
    assert cmd(fb, "set-mode", "polar") == "CTRL.mode = 2"
    cmd(fb, "write", "THETA", "0x4000")
    cmd(fb, "set-mp", "0.25")
    assert [fb.regs[r.addr] for r in (R.CTRL, R.THETA, R.MP)] == [R.CTRL.encode(mode=2), 0x4000, 12]
    for argv, msg in {("set-freq", "50"): "set-freq: not on this board (no freq or vf;",
                      ("set-mode", "dq"): "mode dq: not on this board (no dq;",
                      ("set-mode", "alphabeta"): "mode alphabeta: not on this board (no ab;",
                      ("set-mode", "polar", "--dpwm", "dpwm1"): "--dpwm dpwm1: not on this board (no dpwm;",
                      ("write", "V2", "1"): "V2: not on this board (no ab or dq;",
                      ("write", "CTRL", "0x10200"): "CTRL.dpwm: not on this board (no dpwm;"}.items():
        n = len(fb.writes)
        with pytest.raises(ValueError) as e:
            cmd(fb, *argv)
        assert str(e.value).startswith(msg) and "FEATURES = 0x00002004, minimal); nothing written" in str(e.value), \
            str(e.value)
        assert len(fb.writes) == n
    lo = ctl.min_period(config.CONFIGS["minimal"])
    assert lo == fixed.latencies(config.CONFIGS["minimal"])["MIN_PERIOD"] < ctl.MIN_PERIOD
    with pytest.raises(ValueError, match=f"out of range {lo} .. 65535"):
        cmd(fb, "set-period", "--clocks", str(lo - 1))
    cmd(fb, "set-period", "--clocks", str(lo))


def test_current_sampling():
    """Feature adc: set-adc-pt writes ADC_PT0 / ADC_PT1 (count, direction, on; --off keeps count and direction),
    set-win-min WIN_MIN (microseconds rounded to clocks, or clocks), windows decodes the report (WIN_LO_*,
    WIN_HI_*, WIN_STATUS: readable phases, the one to reconstruct) with WIN_MIN and the points."""
    fb = FakeBoard()
    assert cmd(fb, "set-adc-pt", "0", "--count", "100") == "ADC_PT0 = count 100 up"
    assert fb.regs[R.ADC_PT0.addr] == R.ADC_PT0.encode(cnt=100, en=1) == (1 << 31) | 100
    assert cmd(fb, "set-adc-pt", "1", "--count", "0x300", "--down") == "ADC_PT1 = count 768 down"
    assert fb.regs[R.ADC_PT1.addr] == (1 << 31) | (1 << 16) | 0x300
    assert cmd(fb, "set-adc-pt", "1", "--count", "1536", "--down") == \
        "ADC_PT1 = count 1536 down (>= the half period 1536: at the peak)"          # PERIOD (PERIOD_ACT reads 0)
    fb.regs[R.PERIOD_ACT.addr] = 1200                                              # the half period in force
    assert cmd(fb, "set-adc-pt", "1", "--count", "1300").endswith("(>= the half period 1200: at the peak)")
    assert cmd(fb, "set-adc-pt", "0", "--count", "0", "--down") == "ADC_PT0 = count 0 down (the valley)"
    assert cmd(fb, "set-adc-pt", "1", "--off") == "ADC_PT1.en = 0 (off)"
    assert fb.regs[R.ADC_PT1.addr] == R.ADC_PT1.encode(cnt=1300, dn=0, en=0)       # count and direction kept
    assert fb.regs[R.ADC_PT0.addr] == R.ADC_PT0.encode(cnt=0, dn=1, en=1)
    assert cmd(fb, "set-win-min", "--us", "2.5") == "WIN_MIN = 120 clocks (2.5 us)" and fb.regs[R.WIN_MIN.addr] == 120
    assert cmd(fb, "set-win-min", "--clocks", "131071") == "WIN_MIN = 131071 clocks (2730.65 us)"
    assert fb.regs[R.WIN_MIN.addr] == 0x1FFFF
    cmd(fb, "set-win-min", "--clocks", "200")
    # the report of a running core (the values of the bus test's frozen angle: CMP 52, 245, 247, P 299)
    for reg, v in zip((R.WIN_LO_A, R.WIN_LO_B, R.WIN_LO_C, R.WIN_HI_A, R.WIN_HI_B, R.WIN_HI_C),
                      (92, 478, 482, 487, 101, 97)):
        fb.regs[reg.addr] = v
    fb.regs[R.WIN_STATUS.addr] = R.WIN_STATUS.encode(ok=0b110, recon=0)
    fb.status = R.STATUS.encode(running=1)
    lines = cmd(fb, "windows").splitlines()
    assert lines == ["running            1",
                     "phase a            low 92 clocks (1.91667 us) too short, high 487 clocks (10.1458 us)",
                     "phase b            low 478 clocks (9.95833 us) readable, high 101 clocks (2.10417 us)",
                     "phase c            low 482 clocks (10.0417 us) readable, high 97 clocks (2.02083 us)",
                     "reconstruct        a (= -(b + c), from b and c)",
                     "win_min            200 clocks (4.16667 us)",
                     "adc_pt0            count 0 down",
                     "adc_pt1            off"], lines
    fb.status = 0
    assert cmd(fb, "windows").splitlines()[0] == "running            0  (the report reads 0 unless running)"
    # a build without adc (vf): each command refused naming the feature, nothing written
    fb = FakeBoard(features=config.CONFIGS["vf"])
    for argv, msg in {("set-adc-pt", "0", "--count", "10"): "set-adc-pt 0: not on this board (no adc;",
                      ("set-adc-pt", "1", "--off"): "set-adc-pt 1: not on this board (no adc;",
                      ("set-win-min", "--us", "1"): "set-win-min: not on this board (no adc;",
                      ("windows",): "windows: not on this board (no adc;",
                      ("write", "ADC_PT0", "1"): "ADC_PT0: not on this board (no adc;",
                      ("write", "WIN_MIN.win_min", "1"): "WIN_MIN: not on this board (no adc;"}.items():
        with pytest.raises(ValueError) as e:
            cmd(fb, *argv)
        assert str(e.value).startswith(msg) and "FEATURES = 0x000021e3, vf); nothing written" in str(e.value), \
            str(e.value)
    assert fb.writes == []


def test_no_answer():
    with pytest.raises(ctl.NoAnswer, match="does not answer"):
        cmd(FakeBoard(answer=False), "read", "ID")


# --------------------------------------------------------------------------- the command line
def _cli(args, env=None, timeout=30):
    return subprocess.run([sys.executable, str(REPO / "scripts/svpwmctl.py")] + args, capture_output=True,
                          text=True, env=env, timeout=timeout)


def test_cli_help_and_port_errors():
    cmds = ["read", "write", "dump", "info", "status", "start", "stop", "clear-fault", "set-freq", "set-m",
            "set-period", "set-dt", "set-mp", "set-mode", "set-dtc", "set-carry", "set-adc-pt", "set-win-min",
            "windows"]
    for c in [[]] + [[c] for c in cmds]:
        r = _cli(c + ["--help"])
        assert r.returncode == 0 and "usage:" in r.stdout, (c, r.stderr)
    env = {k: v for k, v in os.environ.items() if k != "SVPWM_PORT"}
    r = _cli(["status"], env=env)
    assert r.returncode != 0 and "no serial port" in r.stderr
    r = _cli(["-p", "/dev/does-not-exist", "status"])
    assert r.returncode != 0 and "cannot open serial port /dev/does-not-exist" in r.stderr


class PtyBoard:
    """A pseudo-terminal whose far end is a FakeBoard (or silent): the CLI opens the slave with pyserial."""

    def __init__(self, fb: FakeBoard):
        self.fb = fb
        self.master, slave = os.openpty()
        self.path = os.ttyname(slave)
        os.close(slave)
        self.stop = False
        self.t = threading.Thread(target=self._serve, daemon=True)
        self.t.start()

    def _serve(self):
        import select
        while not self.stop:
            if select.select([self.master], [], [], 0.05)[0]:
                try:
                    data = os.read(self.master, 64)
                except OSError:                       # slave not open (yet / any more)
                    time.sleep(0.01)
                    continue
                self.fb.write(data)
                out = self.fb.read(1 << 16)
                if out:
                    os.write(self.master, out)

    def close(self):
        self.stop = True
        self.t.join()
        os.close(self.master)


def test_cli_over_pty():
    pty = PtyBoard(FakeBoard())
    try:
        r = _cli(["-p", pty.path, "set-freq", "50"])
        assert r.returncode == 0 and r.stdout.strip() == "FREQ = 107374 (49.999915 Hz)", r.stderr
        assert pty.fb.regs[R.FREQ.addr] == 107374
        r = _cli(["-p", pty.path, "set-m", "3"])
        assert r.returncode == 4 and "error: modulation index 3 is out of range" in r.stderr
        assert pty.fb.regs[R.M.addr] == 0
        r = _cli(["-p", pty.path, "read", "CLK_HZ.clk_hz"])
        assert r.returncode == 0 and r.stdout.strip() == "48000000"
    finally:
        pty.close()
    pty = PtyBoard(FakeBoard(answer=False))            # port opens, nobody answers: timeout
    try:
        r = _cli(["-p", pty.path, "-t", "0.2", "status"])
        assert r.returncode == 3 and f"the board on {pty.path} does not answer (timeout" in r.stderr, r.stderr
    finally:
        pty.close()
