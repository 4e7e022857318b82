#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""svpwmctl: control an svpwm iCE40 board (iCEBreaker / iCEstick) over its UART.

Registers: the generated register map (docs/registers.md; names, byte offsets and fields from
model/svpwm_model/regmap.py). Protocol (fpga/ice40/README.md, uart_reg_bridge.sv), 115200 8N1:
  write  'W' addr d0 d1 d2 d3 chk   -> 'K'        (addr = byte offset, d0 = LSB; chk makes the byte sum 0)
  read   'R' addr chk               -> d0 d1 d2 d3 chk
  a frame with a bad checksum       -> 'N'
Physical units use the core clock the board states in CLK_HZ (--clk-hz when it reads 0) and the
widths in CONFIG; values out of range are refused, never clamped. FEATURES says what the board's build has
(FEATURES.features: the feature mask, model/svpwm_model/config.py; FEATURES.trim: the iCEstick's board cut):
a command or write that needs a feature the board lacks, or a register the cut removes (docs/registers.md,
columns features and trim), is refused with a message naming it, and nothing is written.

Examples:
  svpwmctl.py -p /dev/ttyUSB1 status
  svpwmctl.py -p /dev/ttyUSB1 set-dt 1.0 ; svpwmctl.py -p /dev/ttyUSB1 set-period --fsw 20000
  svpwmctl.py -p /dev/ttyUSB1 set-dt 0.5 --dt-fall 0.8   (rising / falling dead times, the full variant)
  svpwmctl.py -p /dev/ttyUSB1 set-freq 50 ; svpwmctl.py -p /dev/ttyUSB1 set-m 0.9 ; ... start
  svpwmctl.py -p /dev/ttyUSB1 read CTRL.mode ; svpwmctl.py -p /dev/ttyUSB1 write VF_MMAX 0x8000
  svpwmctl.py -p /dev/ttyUSB1 set-adc-pt 0 --count 100 --down ; ... set-win-min --us 2 ; ... windows
                                               (current sampling: trigger points, shunt windows; feature adc)
The port can also be given as $SVPWM_PORT. `svpwmctl.py COMMAND --help` for each command.
"""
from __future__ import annotations

import argparse
import os
import sys
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "model"))
from svpwm_model import regmap as R  # noqa: E402  (generated from rdl/svpwm.rdl)
from svpwm_model import fixed  # noqa: E402  (the cores' latencies: from the calculator's program)
from svpwm_model import config  # noqa: E402  (the feature names and the named configurations)

CMD_WRITE, CMD_READ, RSP_ACK, RSP_NAK = 0x57, 0x52, 0x4B, 0x4E
ID_VALUE = R.ID.reset
MAP_MAJOR = R.VERSION.field("major").reset
MIN_PERIOD = fixed.MIN_PERIOD                  # MinPeriod of the full build (svpwm_ice40_sys default)
# CTRL enumerations (docs/registers.md, CTRL.mode / .dpwm / .upd)
MODES = {"freq": 0, "vf": 1, "polar": 2, "alphabeta": 3, "dq": 4}
DPWM = {"svpwm": 0, "dpwmmin": 1, "dpwmmax": 2, "dpwm1": 3}
UPD = {"valley": 0, "peak": 1, "both": 2}
OM = {"clamp": 0, "sixstep": 1}


def min_period(features: int) -> int:
    """MinPeriod of a board with this build (svpwm_ice40_sys default: svpwm_pkg::min_period(Features))."""
    try:
        return fixed.latencies(features)["MIN_PERIOD"]
    except (KeyError, ValueError):     # a mask without a generated program: the full build's
        return MIN_PERIOD


def build_text(features: int, trim: bool) -> str:
    name = config.config_name(features)
    return (f"build {name or 'custom'} (FEATURES.features 0x{features:04x}: {', '.join(config.names(features)) or '-'})"
            + ("; board cut (FEATURES.trim): no MP, CTRL.mode, CTRL.adc_trig, STATUS.sector, CARRIER, PERIOD_ACT, "
               "CMP_*" if trim else ""))


class ProtocolError(RuntimeError):
    """The board answered, but not as the protocol says."""


class NoAnswer(ProtocolError):
    """The board did not answer in time."""


# --------------------------------------------------------------------------- frames
def checksum(data: bytes) -> int:
    return (-sum(data)) & 0xFF


def _check_addr(addr: int) -> None:
    if not 0 <= addr <= 0xFF:
        raise ValueError(f"address {addr} out of range 0..255")


def encode_write(addr: int, value: int) -> bytes:
    _check_addr(addr)
    body = bytes([CMD_WRITE, addr]) + (value & 0xFFFF_FFFF).to_bytes(4, "little")
    return body + bytes([checksum(body)])


def encode_read(addr: int) -> bytes:
    _check_addr(addr)
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
    if reply[0] != RSP_ACK or len(reply) != 1:
        raise ProtocolError(f"unexpected write reply {reply.hex()}")


# --------------------------------------------------------------------------- names
def lookup(spec: str) -> tuple[R.Register | None, int, R.Field | None]:
    """'CTRL', 'ctrl.en', '0x0c' or '12' -> (register or None for an unmapped address, address, field)."""
    name, _, fname = spec.partition(".")
    reg = R.BY_NAME.get(name.upper())
    if reg is None:
        try:
            addr = int(name, 0)
        except ValueError:
            raise ValueError(f"unknown register {name!r}; known: {', '.join(R.BY_NAME)} or a byte address") from None
        _check_addr(addr)
        reg = R.BY_ADDR.get(addr)
    else:
        addr = reg.addr
    if not fname:
        return reg, addr, None
    if reg is None:
        raise ValueError(f"no register at 0x{addr:02x}, so no field {fname!r}")
    try:
        return reg, addr, reg.field(fname.lower())
    except KeyError:
        raise ValueError(f"{reg.name} has no field {fname!r}; fields: "
                         f"{', '.join(f.name for f in reg.fields)}") from None


def parse_int(text: str) -> int:
    try:
        return int(text, 0)
    except ValueError:
        raise ValueError(f"not an integer: {text!r} (e.g. 1536, 0x600, -5)") from None


def parse_num(text: str) -> Fraction:
    """A decimal number, kept exact (50, 1.5, 2e4, -0.25)."""
    try:
        return Fraction(text)
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"not a number: {text!r}") from None


def round_half_away(x: Fraction) -> int:
    """Nearest integer, halves away from zero (the same for + and - frequencies)."""
    n = (abs(x) * 2 + 1) // 2
    return int(n if x >= 0 else -n)


def field_range(f: R.Field) -> tuple[int, int]:
    return (-(1 << (f.width - 1)), (1 << (f.width - 1)) - 1) if f.signed else (0, (1 << f.width) - 1)


def _fmt(x: Fraction | float, digits: int = 6) -> str:
    return f"{float(x):.{digits}g}"


# --------------------------------------------------------------------------- physical units
@dataclass(frozen=True)
class Config:
    clk_hz: int
    phase_width: int
    freq_width: int
    cnt_width: int
    dt_width: int

    @classmethod
    def from_regs(cls, clk_hz: int, config: int) -> "Config":
        c = R.CONFIG.decode(config)
        return cls(clk_hz, c["phase_width"], c["freq_width"], c["cnt_width"], c["dt_width"])

    @property
    def freq_lsb(self) -> Fraction:
        """Hz per frequency-word LSB: f_clk / (6 * 2^PhaseWidth)."""
        return Fraction(self.clk_hz, 6 << self.phase_width)

    def freq_word(self, hz: Fraction) -> int:
        w = round_half_away(Fraction(hz) / self.freq_lsb)
        lim = (1 << (self.freq_width - 1)) - 1          # the core's default FreqMax: +-(2^(W-1) - 1)
        if abs(w) > lim:
            raise ValueError(f"{_fmt(hz)} Hz is out of range: |f| <= {_fmt(lim * self.freq_lsb)} Hz "
                             f"(frequency word +-{lim} at {self.clk_hz} Hz)")
        return w

    def freq_hz(self, word: int) -> Fraction:
        return word * self.freq_lsb

    def half_period(self, fsw_hz: Fraction) -> int:
        if fsw_hz <= 0:
            raise ValueError(f"switching frequency {_fmt(fsw_hz)} Hz must be > 0")
        return round_half_away(Fraction(self.clk_hz) / (2 * Fraction(fsw_hz)))

    def fsw_hz(self, half_period: int) -> Fraction:
        return Fraction(self.clk_hz, 2 * half_period)

    def clocks(self, us: Fraction, what: str, bits: int | None = None) -> int:
        """Dead time / minimum pulse (or another time of `bits` bits) in microseconds -> clocks (DtWidth bits)."""
        if us < 0:
            raise ValueError(f"{what} {_fmt(us)} us must be >= 0")
        n = round_half_away(Fraction(us) * self.clk_hz / 1_000_000)
        top = (1 << (self.dt_width if bits is None else bits)) - 1
        if n > top:
            raise ValueError(f"{what} {_fmt(us)} us = {n} clocks is out of range: at most {top} clocks "
                             f"({_fmt(Fraction(top * 1_000_000, self.clk_hz))} us at {self.clk_hz} Hz)")
        if us > 0 and n == 0:
            raise ValueError(f"{what} {_fmt(us)} us is less than half a clock ({self.clk_hz} Hz): it would be 0")
        return n

    def us(self, clocks: int) -> Fraction:
        return Fraction(clocks * 1_000_000, self.clk_hz)


def m_word(m: Fraction | float) -> int:
    """Modulation index (1.0 = inscribed circle) -> UQ1.15, 0 .. 0xFFFF (1.99997; beyond the hexagon
    the core clamps the vector to it and flags STATUS.sat)."""
    w = round_half_away(Fraction(m) * 0x8000)
    if not 0 <= w <= 0xFFFF:
        raise ValueError(f"modulation index {_fmt(m)} is out of range 0 .. {_fmt(Fraction(0xFFFF, 0x8000))}")
    return w


# --------------------------------------------------------------------------- the board
class Board:
    """Register access over a pyserial-like port (read(n), write(b), optional reset_input_buffer())."""

    def __init__(self, port, clk_hz: int | None = None, name: str = "the board"):
        self.port = port
        self.clk_hz_override = clk_hz
        self.name = name
        self._cfg: Config | None = None
        self._features: tuple[int, bool] | None = None

    def _xfer(self, frame: bytes, n: int) -> bytes:
        if hasattr(self.port, "reset_input_buffer"):
            self.port.reset_input_buffer()
        self.port.write(frame)
        reply = self.port.read(n)
        if not reply:
            raise NoAnswer(f"{self.name} does not answer (timeout; wrong port, board not programmed, "
                           f"or wrong baud rate?)")
        return reply

    def read(self, addr: int) -> int:
        return decode_read_reply(self._xfer(encode_read(addr), 5))

    def write(self, addr: int, value: int) -> None:
        decode_write_reply(self._xfer(encode_write(addr, value), 1))

    def read_reg(self, reg: R.Register) -> dict[str, int]:
        return reg.decode(self.read(reg.addr))

    def features(self) -> tuple[int, bool]:
        """(feature mask, board cut) of the board's build: FEATURES.features, FEATURES.trim."""
        if self._features is None:
            self.config()                                  # map 3.x: the FEATURES layout read here
            f = self.read_reg(R.FEATURES)
            self._features = (f["features"], bool(f["trim"]))
        return self._features

    def map(self) -> tuple[R.Register, ...]:
        return R.variant(*self.features())

    def _refuse(self, what: str, needs: tuple[str, ...] | None) -> None:
        feats, trim = self.features()
        why = f"no {' or '.join(needs)}" if needs else "board cut: FEATURES.trim = 1"
        word = R.FEATURES.encode(features=feats, trim=int(trim))
        raise ValueError(f"{what}: not on this board ({why}; FEATURES = 0x{word:08x}, "
                         f"{config.config_name(feats) or 'custom'}); nothing written")

    def has(self, feature: str) -> bool:
        return config.has(self.features()[0], feature)

    def need(self, what: str, *features: str) -> None:
        """Refuse `what` unless the board has one of `features`."""
        if not any(self.has(f) for f in features):
            self._refuse(what, features)

    def check_present(self, reg: R.Register, mask: int) -> None:
        """Refuse a write of the bits `mask` of `reg` if the board does not have them."""
        feats, trim = self.features()
        bad = mask & R.absent_mask(reg, feats, trim)
        if not bad:
            return
        missing = [f for f in reg.fields if f.mask & bad]
        what = (reg.name if R.absent_mask(reg, feats, trim) == reg.mask()
                else ", ".join(f"{reg.name}.{f.name}" for f in missing))
        needs = next((f.features for f in missing if f.features and not R.built(f, feats, False)), None)
        self._refuse(what, needs)

    def write_fields(self, reg: R.Register, **values: int) -> int:
        """Read-modify-write of the named fields (range-checked); other RW fields keep their values,
        pulse fields not named are written 0. Fields the board does not have (FEATURES) are refused. Returns the word written."""
        for name, v in values.items():
            f = reg.field(name)
            if not f.writable:
                raise ValueError(f"{reg.name}.{name} is read-only")
            self.check_present(reg, f.mask)
            lo, hi = field_range(f)
            if not lo <= v <= hi:
                raise ValueError(f"{reg.name}.{name} = {v} is out of range {lo} .. {hi} ({f.width} bits)")
        keep = reg.mask("rw", "w1s") & ~sum(reg.field(n).mask for n in values)
        word = (self.read(reg.addr) & keep if keep else 0) | reg.encode(**values)
        self.write(reg.addr, word)
        return word

    def config(self) -> Config:
        if self._cfg is None:
            ident = self.read(R.ID.addr)
            if ident != ID_VALUE:
                raise ProtocolError(f"unexpected ID 0x{ident:08x} (expected 0x{ID_VALUE:08x}): not an svpwm board?")
            ver = self.read_reg(R.VERSION)
            if ver["major"] != MAP_MAJOR:
                raise ProtocolError(f"register map version {ver['major']}.{ver['minor']} is not supported "
                                    f"(this tool: {MAP_MAJOR}.x)")
            stated = self.read(R.CLK_HZ.addr)
            clk = stated or self.clk_hz_override
            if not clk:
                raise ValueError("the board does not state its clock (CLK_HZ reads 0): give --clk-hz")
            if stated and self.clk_hz_override and self.clk_hz_override != stated:
                raise ValueError(f"--clk-hz {self.clk_hz_override} disagrees with the board's CLK_HZ {stated}")
            self._cfg = Config.from_regs(clk, self.read(R.CONFIG.addr))
        return self._cfg

    def status(self) -> dict[str, object]:
        cfg = self.config()
        feats, trim = self.features()
        v = {r.name: self.read(r.addr) for r in self.map() if r.name not in ("ID", "VERSION", "CONFIG")}
        st, ctrl = R.STATUS.decode(v["STATUS"]), R.CTRL.decode(v["CTRL"])
        freq = R.FREQ.decode(v["FREQ"])["freq"]
        dt, dtf = dead_times(R.DT.decode(v["DT"]))
        out: dict[str, object] = {k: st[k] for k in ("running", "tripped", "fault", "sat", "cfg_err",
                                                      "period_clamp", "freq_clamp", "locked", "sector")}
        out.update({
            "build": config.config_name(feats) or f"0x{feats:04x}", "trim": int(trim),
            "en": ctrl["en"],
            "mode": next((k for k, x in MODES.items() if x == ctrl["mode"]), f"invalid ({ctrl['mode']})"),
            "dpwm": next(k for k, x in DPWM.items() if x == ctrl["dpwm"]),
            "upd": next((k for k, x in UPD.items() if x == ctrl["upd"]), f"invalid ({ctrl['upd']})"),
            "freq_hz": _fmt(cfg.freq_hz(freq), 8), "freq_word": freq,
            "m": _fmt(Fraction(v["M"], 0x8000)), "m_word": v["M"],
            "fsw_hz": _fmt(cfg.fsw_hz(v["PERIOD"]), 8) if v["PERIOD"] else "-", "period_clocks": v["PERIOD"],
            "period_act_clocks": v.get("PERIOD_ACT", "-"),          # not if trimmed
            "dt_us": _fmt(cfg.us(dt)), "dt_clocks": dt,
            "dt_fall_us": _fmt(cfg.us(dtf)), "dt_fall_clocks": dtf,                  # = dt unless DT.dtf_en
            "mp_us": _fmt(cfg.us(v["MP"])) if "MP" in v else "-", "mp_clocks": v.get("MP", "-"),  # not if trimmed
            "clk_hz": cfg.clk_hz,
        })
        return out


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


# --------------------------------------------------------------------------- command line
def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="svpwmctl", description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("-p", "--port", default=os.environ.get("SVPWM_PORT"),
                    help="serial port (default $SVPWM_PORT); iCEBreaker/iCEstick: the FTDI's 2nd port")
    ap.add_argument("-b", "--baud", type=int, default=115200, help="baud rate (default 115200)")
    ap.add_argument("-t", "--timeout", type=float, default=0.5, help="reply timeout in seconds (default 0.5)")
    ap.add_argument("--clk-hz", type=int, default=None,
                    help="core clock in Hz, for a board whose CLK_HZ reads 0 (must agree if it does not)")
    sub = ap.add_subparsers(dest="cmd", required=True, metavar="COMMAND")

    def add(name, help_):
        return sub.add_parser(name, help=help_, description=help_)

    regs = ", ".join(R.BY_NAME)
    p = add("read", f"read a register or one field by name ({regs}; e.g. CTRL, status.sector) or byte address")
    p.add_argument("reg", help="REG, REG.FIELD or a byte address (0x0c)")
    p = add("write", "write a register (raw 32-bit value) or one field (read-modify-write, range-checked)")
    p.add_argument("reg", help="REG, REG.FIELD or a byte address")
    p.add_argument("value", help="integer, e.g. 1536, 0x600, -5 (signed fields)")
    add("dump", "read every register of the map (of the board's variant), with its fields")
    add("info", "ID, register map version, core widths (CONFIG), clock (CLK_HZ) and variant (FEATURES)")
    add("status", "the state in physical units and the decoded STATUS fields")
    p = add("start", "enable modulation (CTRL.en = 1; the other CTRL fields are kept)")
    p.add_argument("--allow-zero-dt", action="store_true",
                   help="start even though DT is 0 (no dead time: only without a power stage)")
    add("stop", "disable modulation: all gates off (CTRL.en = 0)")
    add("clear-fault", "clear a latched trip (CTRL.fault_clear); fails while the fault input is active")
    p = add("set-freq", "output frequency in Hz (negative = reverse rotation), modes freq and vf")
    p.add_argument("hz", help="e.g. 50, -12.5")
    p = add("set-m", "modulation index, 1.0 = inscribed circle, up to 1.99997 (the core clamps to the hexagon)")
    p.add_argument("m", help="e.g. 0.9; with --fundamental the line fundamental in Udc, e.g. 1.08")
    p.add_argument("--fundamental", action="store_true",
                   help="m is the wanted line-voltage fundamental in Udc: converted through the six-step law's "
                        "map (ideal.overmod_m_for; set-mode --om sixstep), up to six-step, 1.1027")
    p = add("set-period", "carrier: switching frequency in Hz or half period in clocks")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--fsw", help="switching (carrier) frequency in Hz: PERIOD = f_clk / (2 f_sw), rounded")
    g.add_argument("--clocks", help="half carrier period in core clocks")
    p = add("set-dt", "dead time in microseconds (rounded to clocks): the rising one (a high side after its low "
                      "side turned off) and, without --dt-fall, the falling one too")
    p.add_argument("us")
    p.add_argument("--dt-fall", metavar="US",
                   help="a separate falling dead time in microseconds (a low side after its high side turned "
                        "off; DT.dtf with DT.dtf_en = 1): gate drivers whose turn-off delays differ. Full variant")
    p = add("set-mp", "minimum gate pulse in microseconds (rounded to clocks)")
    p.add_argument("us")
    p = add("set-mode", "input mode (CTRL.mode) and optionally the modulation (CTRL.dpwm) and load point (CTRL.upd)")
    p.add_argument("mode", choices=list(MODES))
    p.add_argument("--dpwm", choices=list(DPWM), help="zero-vector placement (default: unchanged)")
    p.add_argument("--upd", choices=list(UPD), help="compare load point (default: unchanged)")
    p.add_argument("--om", choices=list(OM), help="overmodulation beyond the hexagon: the angle-keeping clamp or the "
                   "six-step law (modes freq, vf, polar; default: unchanged)")
    p = add("set-carry", "volt-second carry of the minimum-pulse rule (CTRL.vsc_off; on after reset)")
    p.add_argument("state", choices=("on", "off"))
    p = add("set-dtc", "dead-time compensation from the phase current signs (DTC register)")
    p.add_argument("state", choices=("on", "off"))
    p.add_argument("--isign", help="current signs {c, b, a} as 3 bits, 1 = negative, e.g. 0b101 (default: unchanged)")
    p = add("set-adc-pt", "ADC trigger point 0 or 1 (ADC_PT0 / ADC_PT1, feature adc): adc_pt_o[k] and adc_trig_o "
                          "pulse once per carrier period where the carrier is at the count (0: the valley, >= the "
                          "half period: the peak), in force from the update after the next sample point")
    p.add_argument("point", type=int, choices=(0, 1))
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--count", help="carrier count in clocks, 0 .. 65535 (0 the valley; >= PERIOD_ACT the peak)")
    g.add_argument("--off", action="store_true", help="turn the point off (its count and direction are kept)")
    p.add_argument("--down", action="store_true", help="on the down count (default: the up count)")
    p = add("set-win-min", "minimum low-side shunt window (WIN_MIN, feature adc): a phase is readable "
                           "(WIN_STATUS.ok) when its low-side window is at least this long")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--us", help="in microseconds, rounded to clocks")
    g.add_argument("--clocks", help="in core clocks, 0 .. 131071")
    add("windows", "the shunt-window report (feature adc): per phase the low- and high-side windows, which phases "
                   "are readable, the phase to reconstruct; WIN_MIN and the trigger points")
    return ap


def dead_times(dt_fields: dict[str, int]) -> tuple[int, int]:
    """(rising, falling) dead time in clocks from the decoded DT register: the falling one is DT.dtf when
    DT.dtf_en is 1, else DT.dt (a build without the feature dtf reads dtf_en 0)."""
    dt = dt_fields["dt"]
    return dt, (dt_fields["dtf"] if dt_fields.get("dtf_en") else dt)


def _point_note(board: Board, n: int) -> str:
    """What a trigger-point count means for the half period in force (PERIOD_ACT, else PERIOD)."""
    p = board.read(R.PERIOD_ACT.addr) if R.built(R.PERIOD_ACT, *board.features()) else 0
    p = p or board.read(R.PERIOD.addr)
    if n == 0:
        return " (the valley)"
    return f" (>= the half period {p}: at the peak)" if n >= p else ""


def windows_report(board: Board) -> list[str]:
    """The shunt-window report and the settings it depends on, one line each (feature adc)."""
    cfg = board.config()
    lo = [board.read(r.addr) for r in (R.WIN_LO_A, R.WIN_LO_B, R.WIN_LO_C)]
    hi = [board.read(r.addr) for r in (R.WIN_HI_A, R.WIN_HI_B, R.WIN_HI_C)]
    st, wm = board.read_reg(R.WIN_STATUS), board.read(R.WIN_MIN.addr)
    running = board.read_reg(R.STATUS)["running"]
    out = [f"{'running':18} {running}" + ("" if running else "  (the report reads 0 unless running)")]
    for k, ph in enumerate("abc"):
        out.append(f"{'phase ' + ph:18} low {lo[k]} clocks ({_fmt(cfg.us(lo[k]))} us) "
                   f"{'readable' if st['ok'] >> k & 1 else 'too short'}, high {hi[k]} clocks ({_fmt(cfg.us(hi[k]))} us)")
    r = st["recon"]
    others = " and ".join("abc"[k] for k in range(3) if k != r)
    out.append(f"{'reconstruct':18} " + (f"{'abc'[r]} (= -({' + '.join(others.split(' and '))}), from {others})"
                                       if r < 3 else f"invalid ({r})"))
    out.append(f"{'win_min':18} {wm} clocks ({_fmt(cfg.us(wm))} us)")
    for k, reg in enumerate((R.ADC_PT0, R.ADC_PT1)):
        pt = board.read_reg(reg)
        out.append(f"{'adc_pt' + str(k):18} " + (f"count {pt['cnt']} {'down' if pt['dn'] else 'up'}" if pt["en"]
                                                 else "off"))
    return out


def _locked_check(board: Board, what: str) -> None:
    if board.read_reg(R.STATUS)["locked"]:
        raise ValueError(f"{what} is locked (STATUS.locked, CTRL.lock) until the board is reset")


def min_period_of(board: Board) -> int:
    return min_period(board.features()[0])


def _period_check(board: Board, cfg: Config, p: int) -> None:
    top = (1 << cfg.cnt_width) - 1
    dtx, mp = max(dead_times(board.read_reg(R.DT))), board.read(R.MP.addr)
    min_period = min_period_of(board)
    low = max(min_period, 2 * (dtx + mp))
    if not low <= p <= top:
        raise ValueError(f"half period {p} clocks is out of range {low} .. {top} (MinPeriod {min_period}, "
                         f"2 (max(dt, dtf) + MP) = {2 * (dtx + mp)}; f_sw {_fmt(cfg.fsw_hz(top))} .. "
                         f"{_fmt(cfg.fsw_hz(low))} Hz)")


def run(args, board: Board) -> str:
    c = args.cmd
    if c == "read":
        reg, addr, f = lookup(args.reg)
        v = board.read(addr)
        if f is not None:
            return str(reg.decode(v)[f.name])
        return f"0x{v:08x}" + ("  " + ", ".join(f"{k}={x}" for k, x in reg.decode(v).items()) if reg else "")
    if c == "write":
        reg, addr, f = lookup(args.reg)
        v = parse_int(args.value)
        if f is not None:
            board.write_fields(reg, **{f.name: v})
        else:
            if not -(1 << 31) <= v <= 0xFFFF_FFFF:
                raise ValueError(f"{v} does not fit 32 bits")
            if reg is not None:      # an absent register, or ones in absent fields
                feats, trim = board.features()
                absent = not any(R.built(f, feats, trim) for f in reg.fields)
                board.check_present(reg, reg.mask() if absent else v & 0xFFFF_FFFF)
            board.write(addr, v)
        return "ok"
    if c == "dump":
        lines = []
        for r in board.map():
            v = board.read(r.addr)
            fields = ", ".join(f"{k}={x}" for k, x in r.decode(v).items())
            lines.append(f"0x{r.addr:02x} {r.name:10} 0x{v:08x}  {fields}")
        return "\n".join(lines)
    if c == "info":
        cfg = board.config()
        ver = board.read_reg(R.VERSION)
        return (f"ID 0x{ID_VALUE:08x} (svpwm), register map {ver['major']}.{ver['minor']}, "
                f"clock {cfg.clk_hz} Hz{' (--clk-hz)' if not board.read(R.CLK_HZ.addr) else ''}, "
                f"PhaseWidth {cfg.phase_width}, FreqWidth {cfg.freq_width}, CntWidth {cfg.cnt_width}, "
                f"DtWidth {cfg.dt_width}, "
                + build_text(*board.features()))
    if c == "status":
        return "\n".join(f"{k:18} {v}" for k, v in board.status().items())
    if c == "start":
        dt, dtf = dead_times(board.read_reg(R.DT))
        if 0 in (dt, dtf) and not args.allow_zero_dt:
            what = "DT" if dt == 0 else "the falling dead time DT.dtf (DT.dtf_en = 1)"
            raise ValueError(f"{what} is 0 (no dead time between the gates of a leg): set-dt first "
                             "(or --allow-zero-dt without a power stage)")
        board.write_fields(R.CTRL, en=1)
        return "started"
    if c == "stop":
        board.write_fields(R.CTRL, en=0)
        return "stopped"
    if c == "clear-fault":
        board.write_fields(R.CTRL, fault_clear=1)
        st = board.read_reg(R.STATUS)
        if st["tripped"]:
            raise ProtocolError("still tripped: the fault input is active" if st["fault"]
                                else "still tripped after CTRL.fault_clear")
        return "fault cleared"
    if c == "set-mode":
        board.need(f"mode {args.mode}", args.mode if args.mode != "alphabeta" else "ab")
        vals = {"mode": MODES[args.mode]}
        if args.dpwm and args.dpwm != "svpwm":
            board.need(f"--dpwm {args.dpwm}", "dpwm")
        if args.upd and args.upd != "valley":
            board.need(f"--upd {args.upd}", "upd")
        if args.om == "sixstep":
            board.need("--om sixstep", "sixstep")
        if args.dpwm:
            vals["dpwm"] = DPWM[args.dpwm]
        if args.upd:
            vals["upd"] = UPD[args.upd]
        if args.om:
            vals["om"] = OM[args.om]
        board.write_fields(R.CTRL, **vals)
        return ", ".join(f"CTRL.{k} = {v}" for k, v in vals.items())
    if c == "set-carry":
        board.need("set-carry", "carry")
        board.write_fields(R.CTRL, vsc_off=int(args.state == "off"))
        return f"CTRL.vsc_off = {int(args.state == 'off')}"
    if c == "set-dtc":
        board.need("set-dtc", "dtc")
        vals = {"en": int(args.state == "on")}
        if args.isign is not None:
            vals["isign"] = parse_int(args.isign)
        board.write_fields(R.DTC, **vals)
        return ", ".join(f"DTC.{k} = {v}" for k, v in vals.items())
    if c == "set-adc-pt":
        reg = (R.ADC_PT0, R.ADC_PT1)[args.point]
        board.need(f"set-adc-pt {args.point}", "adc")
        if args.off:
            if args.down:
                raise ValueError("--down with --off: give the direction with --count")
            board.write_fields(reg, en=0)
            return f"{reg.name}.en = 0 (off)"
        n = parse_int(args.count)
        board.write_fields(reg, cnt=n, dn=int(args.down), en=1)
        return f"{reg.name} = count {n} {'down' if args.down else 'up'}" + _point_note(board, n)
    if c == "windows":
        board.need("windows", "adc")
        return "\n".join(windows_report(board))
    if c == "set-m":
        if args.fundamental:
            from svpwm_model.ideal import overmod_m_for
            w = m_word(Fraction(overmod_m_for(float(parse_num(args.m)))))
        else:
            w = m_word(parse_num(args.m))
        board.write_fields(R.M, m=w)
        return f"M = 0x{w:04x} (m = {_fmt(Fraction(w, 0x8000))})"
    cfg = board.config()
    if c == "set-freq":
        board.need("set-freq", "freq", "vf")
        w = cfg.freq_word(parse_num(args.hz))
        board.write_fields(R.FREQ, freq=w)
        return f"FREQ = {w} ({_fmt(cfg.freq_hz(w), 8)} Hz)"
    if c == "set-period":
        p = parse_int(args.clocks) if args.clocks is not None else cfg.half_period(parse_num(args.fsw))
        _period_check(board, cfg, p)
        board.write_fields(R.PERIOD, period=p)
        return f"PERIOD = {p} clocks (f_sw {_fmt(cfg.fsw_hz(p), 8)} Hz)"
    if c == "set-win-min":
        board.need("set-win-min", "adc")
        top = R.WIN_MIN.field("win_min").width
        if args.clocks is not None:
            n = parse_int(args.clocks)
        else:
            n = cfg.clocks(parse_num(args.us), "minimum window", top)
        board.write_fields(R.WIN_MIN, win_min=n)
        return f"WIN_MIN = {n} clocks ({_fmt(cfg.us(n))} us)"
    if c in ("set-dt", "set-mp"):
        reg, what = (R.DT, "dead time") if c == "set-dt" else (R.MP, "minimum pulse")
        fall = getattr(args, "dt_fall", None)
        board.check_present(reg, reg.fields[0].mask)  # the trimmed board has no MP
        if fall is not None:                          # a build without dtf no DT.dtf / dtf_en
            board.need("--dt-fall", "dtf")
        n = cfg.clocks(parse_num(args.us), what)
        nf = cfg.clocks(parse_num(fall), "falling dead time") if fall is not None else None
        _locked_check(board, what)
        period = board.read(R.PERIOD.addr)
        if reg is R.DT:
            dtx, mp = max(n, n if nf is None else nf), board.read(R.MP.addr)
        else:
            dtx, mp = max(dead_times(board.read_reg(R.DT))), n
        if period < 2 * (dtx + mp):
            raise ValueError(f"{what} {n} clocks needs PERIOD >= 2 (max(dt, dtf) + MP) = {2 * (dtx + mp)}, "
                             f"PERIOD is {period}: lengthen the period first")
        if reg is R.MP:
            board.write_fields(R.MP, mp=n)
            return f"MP = {n} clocks ({_fmt(cfg.us(n))} us)"
        if not board.has("dtf"):                      # one dead time for both edges
            board.write_fields(R.DT, dt=n)
            return f"DT = {n} clocks ({_fmt(cfg.us(n))} us)"
        # with dtf: both edges written (without --dt-fall the falling one is DT, dtf_en = 0)
        board.write_fields(R.DT, dt=n, dtf=0 if nf is None else nf, dtf_en=int(nf is not None))
        if nf is None:
            return f"DT = {n} clocks ({_fmt(cfg.us(n))} us)"
        return (f"DT = {n} clocks ({_fmt(cfg.us(n))} us) rising, {nf} clocks ({_fmt(cfg.us(nf))} us) falling "
                f"(DT.dtf, dtf_en = 1)")
    raise SystemExit(f"error: unknown command {c}")


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    port = open_port(args.port, args.baud, args.timeout)
    try:
        print(run(args, Board(port, args.clk_hz, name=f"the board on {args.port}")))
    except NoAnswer as e:
        print(f"error: {e}", file=sys.stderr)
        return 3
    except (ProtocolError, ValueError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 4
    finally:
        port.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
