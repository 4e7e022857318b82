# SPDX-License-Identifier: Apache-2.0
"""The whole LiteX SoC (fpga/litex/svpwm_soc.py SimSoC: VexRiscv + the firmware sw/firmware in its ROM +
UART console + the core) in LiteX's Verilator simulation, driven through the console only, as a user
would: commands go to the simulation's stdin (serial2console), replies come from its stdout.

fpga/litex/sim/svpwm_soc_rec.sv (sim only) logs every gate edge and every bus write to the core with its
clock, and drives the fault pad. From that log:
  - refused commands wrote nothing, and accepted values are what scripts/svpwmctl.py converts them to;
  - the gate edges after the firmware's CTRL.en write are, edge for edge (==), those of the golden model
    (svpwm_model.core) for the register values the firmware wrote (its cycle 0 = the clock the write is
    in the register, i.e. the first clock with en_i = 1);
  - the pin checker (svpwm_model.analysis.check_legs): no shoot-through, dead time, no short pulses;
  - a fault on the pad turns the gates off in the same clock and they stay off until the firmware clears
    the trip after the pad is released; the firmware reports the trip on its own and refuses to clear it
    while the pad is active;
  - the V/f ramp: the V/f registers, the 50 FREQ steps 0 -> 50 Hz at timer0's pace, and its gate edges ==
    the golden model fed with the register values the core sampled in each carrier period.

Build first: `make soc-sim` (or python fpga/litex/svpwm_soc.py --target sim).
"""
from __future__ import annotations

import re
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from fractions import Fraction
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
sys.path[:0] = [str(REPO / "model"), str(REPO / "scripts")]
import svpwmctl as ctl  # noqa: E402
from svpwm_model import core, fixed  # noqa: E402
from svpwm_model import regmap as R  # noqa: E402
from svpwm_model.analysis import check_legs  # noqa: E402

GW = REPO / "build" / "litex" / "sim" / "gateware"
VSIM = GW / "obj_dir" / "Vsim"
CLK_HZ = 24_000_000                         # svpwm_soc.SYS_CLK_HZ, read back from CLK_HZ below
CFG = ctl.Config(CLK_HZ, fixed.PHASE_WIDTH, fixed.FREQ_WIDTH, 16, 10)   # the host tool's unit conversions
PROMPT = "svpwm> "
TIMEOUT = 120.0                             # wall-clock seconds for any one reply
# the fault pulse: long enough (~0.1 s simulated, seconds of wall clock) for the test to send the first
# `clear` while the pad is still active, however slowly this machine runs the test beside the simulation
FAULT_LEN = 2_000_000


# --------------------------------------------------------------------------- the simulation
@dataclass
class Rec:
    """fpga/litex/sim/svpwm_soc_rec.sv's log: (cycle, ...) tuples, in time order."""
    gates: list[tuple[int, int]] = field(default_factory=list)              # (cycle, {lo, hi})
    writes: list[tuple[int, int, int, int]] = field(default_factory=list)   # (cycle, byte offset, data, sel)
    fault: list[tuple[int, int]] = field(default_factory=list)
    running: list[tuple[int, int]] = field(default_factory=list)
    tripped: list[tuple[int, int]] = field(default_factory=list)
    last: int = 0                                                           # last cycle logged


def read_rec(path: Path) -> Rec:
    r = Rec()
    text = path.read_text()
    for line in text[:text.rfind("\n") + 1].splitlines():       # complete lines only (the sim is running)
        p = line.split()
        c = int(p[1])
        r.last = max(r.last, c)
        if p[0] == "G":
            r.gates.append((c, int(p[2], 16)))
        elif p[0] == "W" and len(p) == 5:
            r.writes.append((c, int(p[2], 16), int(p[3], 16), int(p[4], 16)))
        elif p[0] in "FRT":
            getattr(r, {"F": "fault", "R": "running", "T": "tripped"}[p[0]]).append((c, int(p[2])))
    return r


class Soc:
    """The simulation binary with its console on a pipe."""

    def __init__(self, tmp: Path, *plusargs: str):
        if not VSIM.exists():
            pytest.fail(f"{VSIM.relative_to(REPO)} not built: run `make soc-sim`", pytrace=False)
        self.rec_path = tmp / "svpwm_rec.log"
        # cwd: the ROM / RAM .init files and the sim modules are found relative to the gateware directory
        self.p = subprocess.Popen([str(VSIM), f"+rec={self.rec_path}", *plusargs], cwd=GW,
                                  stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
        self.buf = ""
        self.pos = 0                         # console output consumed so far
        self.lock = threading.Lock()
        threading.Thread(target=self._reader, daemon=True).start()
        self.expect(re.escape(PROMPT))       # booted: the firmware's first prompt

    def _reader(self):
        while True:
            b = self.p.stdout.read1(4096)
            if not b:
                return
            with self.lock:
                self.buf += b.decode(errors="replace").replace("\r", "")

    def expect(self, pattern: str, timeout: float = TIMEOUT) -> re.Match:
        end = time.monotonic() + timeout
        while True:
            with self.lock:
                m = re.compile(pattern).search(self.buf, self.pos)
                if m:
                    self.pos = m.end()
                    return m
                tail = self.buf[-600:]
            if time.monotonic() > end or self.p.poll() is not None:
                raise AssertionError(f"console: no {pattern!r} (simulation {'ended' if self.p.poll() is not None else 'running'}); "
                                     f"last output:\n{tail}")
            time.sleep(0.02)

    def cmd(self, line: str) -> str:
        """Send one command line; returns the firmware's reply (the lines between the echo and the prompt)."""
        self.p.stdin.write((line + "\n").encode())
        self.p.stdin.flush()
        self.expect(re.escape(line) + "\n")                          # the echo
        m = self.expect(r"(?s)(.*?)" + re.escape(PROMPT))
        return m.group(1)

    def rec(self) -> Rec:
        return read_rec(self.rec_path)

    def wait_cycle(self, cycle: int, timeout: float = TIMEOUT) -> Rec:
        """Until the recorder has logged a line at or after `cycle` (the core runs: gates switch)."""
        end = time.monotonic() + timeout
        while True:
            r = self.rec()
            if r.last >= cycle:
                return r
            if time.monotonic() > end or self.p.poll() is not None:
                raise AssertionError(f"simulation did not reach cycle {cycle} (last logged {r.last})")
            time.sleep(0.05)

    def close(self):
        if self.p.poll() is None:
            self.p.kill()
        self.p.wait()


@pytest.fixture
def soc_factory(tmp_path):
    socs = []

    def make(*plusargs):
        s = Soc(tmp_path, *plusargs)
        socs.append(s)
        return s

    yield make
    for s in socs:
        s.close()


# --------------------------------------------------------------------------- registers from the log
RW_REGS = [r for r in R.REGISTERS if r.mask("rw")]


def regs_at(writes, cycle: int) -> dict[str, int]:
    """Register values in force at `cycle`: the map's reset values (CTRL.pol: GatePol 0) + the logged writes
    (byte lanes applied) that are in their register by then."""
    v = {r.name: r.reset for r in RW_REGS}
    by_addr = {r.addr: r for r in RW_REGS}
    for c, a, d, sel in writes:
        if c > cycle or a not in by_addr:
            continue
        r = by_addr[a]
        lanes = sum(0xFF << (8 * i) for i in range(4) if sel >> i & 1)
        keep = r.mask("rw")
        v[r.name] = (v[r.name] & ~(lanes & keep)) | (d & lanes & keep)
    return v


def inputs_of(v: dict[str, int]) -> core.Inputs:
    """The core's inputs from the register values (field names of the generated map)."""
    ctrl = R.CTRL.decode(v["CTRL"])

    def f(name):
        return next(iter(R.BY_NAME[name].decode(v[name]).values()))

    return core.Inputs(freq=f("FREQ"), m=f("M"), period=f("PERIOD"), dt=f("DT"), mp=f("MP"), mode=ctrl["mode"],
                       theta=f("THETA"), v1=f("V1"), v2=f("V2"), vf_boost=f("VF_BOOST"), vf_slope=f("VF_SLOPE"),
                       vf_mmax=f("VF_MMAX"), dpwm=ctrl["dpwm"], upd=ctrl["upd"], presc=f("PRESC"), om=ctrl["om"],
                       vsc=1 - ctrl["vsc_off"], dtc=R.DTC.decode(v["DTC"])["en"], isign=R.DTC.decode(v["DTC"])["isign"])


def en_writes(writes) -> list[int]:
    """Cycles from which a CTRL write turned en on (0 -> 1)."""
    out, en = [], 0
    for c, a, d, sel in writes:
        if a == R.CTRL.addr and sel & 1:
            new = R.CTRL.decode(d)["en"]
            if new and not en:
                out.append(c)
            en = new
    return out


def word_at(edges, cycle: int) -> int:
    w = 0
    for c, x in edges:
        if c > cycle:
            break
        w = x
    return w


def configure(s: Soc, fsw=20000, dt="0.5", m="0.9", hz="500") -> core.Inputs:
    """The console commands of a start, each reply and each value written checked against svpwmctl's
    conversion of the same value."""
    expect = {"DT": CFG.clocks(Fraction(dt), "dead time"), "PERIOD": CFG.half_period(Fraction(fsw)),
              "M": ctl.m_word(Fraction(m)), "FREQ": CFG.freq_word(Fraction(hz))}
    for line, reg in ((f"dt {dt}", "DT"), (f"fsw {fsw}", "PERIOD"), (f"m {m}", "M"), (f"freq {hz}", "FREQ")):
        n0 = len(s.rec().writes)
        reply = s.cmd(line)
        assert not reply.startswith("error"), f"{line}: {reply}"
        w = s.rec().writes[n0:]
        assert [(a, d & R.BY_NAME[reg].mask("rw")) for _, a, d, _ in w] == \
            [(R.BY_NAME[reg].addr, R.BY_NAME[reg].encode(**{R.BY_NAME[reg].fields[0].name: expect[reg]}))], \
            f"{line}: wrote {w}, svpwmctl gives {reg} = {expect[reg]}"
    return expect


# --------------------------------------------------------------------------- tests
def test_soc_console_and_gates_vs_model(soc_factory):
    """Boot, refusals, configuration, start; gates == golden model over six revolutions; pin checker."""
    s = soc_factory()
    assert f"CLK_HZ {CLK_HZ}" in s.buf and "core ID 0x53565057" in s.buf, s.buf
    # out of range: refused with a message and nothing written (svpwmctl refuses the same values)
    refused = {
        "freq 2000": lambda: CFG.freq_word(Fraction(2000)),
        "freq -2000": lambda: CFG.freq_word(Fraction(-2000)),
        "m 2": lambda: ctl.m_word(Fraction(2)),
        "m -0.1": lambda: ctl.m_word(Fraction("-0.1")),
        "dt 50": lambda: CFG.clocks(Fraction(50), "dead time"),
        "dt 0.01": lambda: CFG.clocks(Fraction("0.01"), "dead time"),
        "period 100": None, "period 70000": None, "fsw 100": None, "fsw 0": None,
        "start": None,            # DT is 0 (svpwmctl start refuses it too)
        "mode foo": None, "ramp 0": None, "ramp 70000": None, "freq abc": None, "bogus": None,
    }
    for line, host in refused.items():
        if host is not None:
            with pytest.raises(ValueError):
                host()
        n0 = len(s.rec().writes)
        reply = s.cmd(line)
        assert reply.startswith("error:"), f"{line!r} was not refused: {reply!r}"
        assert len(s.rec().writes) == n0, f"{line!r} refused but wrote {s.rec().writes[n0:]}"
    exp = configure(s)
    # dead time longer than the period allows: refused (PERIOD 600 < 2 * 960)
    n0 = len(s.rec().writes)
    assert s.cmd("dt 40").startswith("error:") and len(s.rec().writes) == n0
    assert s.cmd("mode freq") == "CTRL.mode = freq\n"
    assert s.cmd("start") == "started\n"
    r = s.rec()
    (c0,) = en_writes(r.writes)
    inp = inputs_of(regs_at(r.writes, c0))
    assert (inp.freq, inp.period, inp.dt, inp.m, inp.mode) == (exp["FREQ"], exp["PERIOD"], exp["DT"], exp["M"],
                                                               fixed.MODE_FREQ)
    n = 6 * round(Fraction(CLK_HZ, 500) / (2 * inp.period))          # six revolutions of 500 Hz
    r = s.wait_cycle(c0 + 2 * inp.period * (n + 1))
    st = s.cmd("status")
    assert "running 1 tripped 0" in st and "CLK_HZ 24000000" in st, st
    later = [c for c, *_ in r.writes if c > c0]
    model = core.CoreModel().run(inp, [inp] * n, n)
    assert not later or later[0] >= c0 + model.end, f"a write at {later[0]} inside the compared window"
    assert [e for e in r.gates if e[0] < c0] == [], "gates switched before CTRL.en"
    got = [(c - c0, w) for c, w in r.gates if c0 <= c < c0 + model.end]
    assert len(got) > 10 * n and set(model.sector[1:]) == set(range(6)), "the window is not a real run"
    assert got == model.gate_edges, ("gate edges differ from the golden model:\n"
                                     + next(f"first difference at edge {i}: rtl {g} != model {e}"
                                            for i, (g, e) in enumerate(zip(got + [None] * len(model.gate_edges),
                                                                           model.gate_edges + [None] * len(got)))
                                            if g != e))
    rep = check_legs(got, lambda c: inp.dt)
    assert rep.ok, rep
    assert s.cmd("stop") == "stopped\n"


def test_soc_fault(soc_factory):
    """The fault pad (sim stimulus 30000 clocks after running_o rises, for FAULT_LEN clocks): gates off in the
    same clock, the firmware reports the trip unasked, refuses to clear it while the pad is active, clears
    it after; the gates stay off until then and switch again after; pin checker over the whole run."""
    s = soc_factory("+fault_after=30000", f"+fault_len={FAULT_LEN}")
    exp = configure(s)
    assert s.cmd("start") == "started\n"
    s.expect(r"FAULT: tripped, gates safe \(fault input 1\)\n")
    reply = s.cmd("clear")
    assert reply == "error: still tripped: the fault input is active\n", reply
    r = s.rec()
    (cf, v1), = r.fault[:1]
    assert v1 == 1 and r.writes[-1][0] < cf + FAULT_LEN, "the first clear did not happen while the pad was active"
    assert word_at(r.gates, cf - 1) != 0 and word_at(r.gates, cf) == 0, \
        f"gates not off in the fault clock {cf}: {[e for e in r.gates if cf - 3 <= e[0] <= cf + 3]}"
    r = s.wait_cycle(cf + FAULT_LEN + 1000)
    assert r.fault[1] == (cf + FAULT_LEN, 0), r.fault
    st = s.cmd("status")
    assert "tripped 1 fault 0" in st, f"trip not latched after the pad was released: {st}"
    assert s.cmd("clear") == "fault cleared\n"
    r = s.rec()
    c_clr = r.writes[-1][0]
    assert R.CTRL.decode(r.writes[-1][2])["fault_clear"] == 1 and r.writes[-1][1] == R.CTRL.addr
    assert [e for e in r.gates if cf < e[0] < c_clr] == [], "gates switched while tripped"
    r = s.wait_cycle(c_clr + 20 * exp["PERIOD"])
    assert any(c > c_clr and w for c, w in r.gates), "no switching after the clear"
    assert r.tripped and r.tripped[0][0] >= cf and r.tripped[-1][1] == 0 and r.tripped[-1][0] > c_clr - 2
    assert "running 1 tripped 0 fault 0" in s.cmd("status")
    rep = check_legs(r.gates, lambda c: exp["DT"], forced_off=[cf])
    assert rep.ok, rep


def test_soc_vf_ramp(soc_factory):
    """ramp 20: V/f registers from the m at 50 Hz, then FREQ 0 -> the 50 Hz word in 50 equal steps, one per
    timer0 period (20 ms / 50) from the start, each within the timer setup and polling latency; the gates
    during the ramp == the golden model fed with the registers as the core samples them; pin checker."""
    s = soc_factory()
    exp = configure(s, hz="0")
    n0 = len(s.rec().writes)
    reply = s.cmd("ramp 20")
    assert reply.startswith("ramp: 0 -> 50 Hz in 20 ms, V/f up to m 0.89999: done"), reply
    w = s.rec().writes[n0:]
    w50 = CFG.freq_word(Fraction(50))
    fa50 = w50 >> (fixed.FREQ_WIDTH - 17)
    slope = int(ctl.round_half_away(Fraction(exp["M"] * 256, fa50)))
    setup = [(a, d) for _, a, d, _ in w[:6]]
    assert setup[:4] == [(R.FREQ.addr, 0), (R.VF_BOOST.addr, 0), (R.VF_MMAX.addr, exp["M"]),
                         (R.VF_SLOPE.addr, slope)], setup
    assert R.CTRL.decode(setup[4][1])["mode"] == fixed.MODE_VF and R.CTRL.decode(setup[5][1])["en"] == 1
    steps = [(c, d) for c, a, d, _ in w[6:] if a == R.FREQ.addr]
    assert [d for _, d in steps] == [int(ctl.round_half_away(Fraction(w50 * k, 50))) for k in range(1, 51)]
    period = CLK_HZ // 1000 * 20 // 50                     # timer0 reload: 20 ms / 50 steps
    t0 = w[5][0]                                           # CTRL.en; timer0 is started right after it
    for k, (c, _) in enumerate(steps, 1):
        # on timer0's grid, not drifting: step k after k periods, late by the timer's setup and the polling
        # loop only (on SERV 1063 .. 1439 clocks measured; bound 2000 clocks = 83 us)
        late = c - (t0 + k * period)
        assert 0 <= late < 2000, f"step {k} at {c}: {late} clocks after t0 + {k} timer0 periods of {period}"
    assert fixed.vf_m(w50, 0, slope, exp["M"]) == exp["M"], "V/f law does not reach m at 50 Hz"
    st = s.cmd("status")
    assert f"(word {w50})" in st and "mode vf" in st and "running 1" in st, st
    # the whole ramp and 20 carrier periods at 50 Hz against the golden model, edge for edge: the inputs of
    # carrier period n are the registers as the core reads them, at S - 1 with S = t_(n+1) - SAMPLE_LEAD
    # (model: Update.sample; valley updates, PERIOD / DT / MP constant: t_n = 2 P n)
    p = exp["PERIOD"]
    n = (steps[-1][0] - t0) // (2 * p) + 20
    r = s.wait_cycle(t0 + 2 * p * (n + 1))
    inp0 = inputs_of(regs_at(r.writes, t0))
    assert inp0.period == p and inp0.mode == fixed.MODE_VF
    assert [c for c, a, *_ in r.writes if c > t0 and a not in (R.FREQ.addr,)] == [], "writes other than FREQ"

    def at_sample(k):
        return inputs_of(regs_at(r.writes, t0 + fixed.START_DELAY + 2 * p * (k + 1) - fixed.SAMPLE_LEAD - 1))

    model = core.CoreModel().run(inp0, at_sample, n)
    got = [(c - t0, x) for c, x in r.gates if t0 <= c < t0 + model.end]
    assert [e for e in r.gates if e[0] < t0] == [], "gates switched before CTRL.en"
    assert model.m[-1] == exp["M"] and len(got) > 10 * n, "the ramp did not reach m at 50 Hz in the window"
    assert got == model.gate_edges, ("gate edges differ from the golden model during the ramp:\n"
                                     + next(f"first difference at edge {i}: rtl {g} != model {e}"
                                            for i, (g, e) in enumerate(zip(got + [None] * len(model.gate_edges),
                                                                           model.gate_edges + [None] * len(got)))
                                            if g != e))
    rep = check_legs(got, lambda c: exp["DT"])
    assert rep.ok, rep
