# SPDX-License-Identifier: Apache-2.0
"""Full bus wrappers svpwm_axil / svpwm_wb (adapter + svpwm_regs + svpwm_core), both simulators.

Register addresses and fields come only from svpwm_model.regmap (generated from rdl/svpwm.rdl). The
core is probed hierarchically to check that every register field reaches its core input and every
RO field reads its core output, and that a write to M while running changes the active compare
values only at a load point; current sampling (feature adc): trigger points written over the bus make
adc_pt_o pulse at their carrier counts, and the shunt-window report reads what svpwm_model.adc computes
from CMP_A..C, PERIOD_ACT and DT read over the bus (a build without adc: 0, no pulses). Register-block
details (byte lanes, reserved addresses, back-to-back) are covered on the core-less harness in
test_svpwm_bus_regs.py.
"""
from __future__ import annotations

import os
import random
from pathlib import Path

import cocotb
from cocotb.triggers import ReadOnly, RisingEdge
from clocks import clock_cycles

from svpwm_model import adc, config, fixed
from svpwm_model import regmap as R

HERE = Path(__file__).resolve().parent
MIN_PERIOD = fixed.MIN_PERIOD          # the full core's default (its SampleLead + 4)
CLK_HZ = {"axil": 48_000_000, "wb": 100_000_000, "wbc": 12_000_000}   # ClkHz per wrapper variant
# RO live field (svpwm_regs port) -> core output it must read
RO_MAP = {"status_running_i": "running_o", "status_sat_i": "sat_o", "status_cfg_err_i": "cfg_err_o",
          "status_period_clamp_i": "period_clamp_o", "status_freq_clamp_i": "freq_clamp_o",
          "status_fault_i": "fault_o", "status_tripped_i": "tripped_o", "status_locked_i": "locked_o",
          "status_sector_i": "sector_o", "carrier_count_i": "carrier_o", "carrier_up_i": "carrier_up_o",
          "period_act_i": "period_o"}


# fields whose core input has another name, and CTRL.vsc_off, which drives the core's vsc_en_i inverted
# (a field absent in the compact variant resets to 0: "off" is the field, "on" the port)
OTHER_INPUT = {"dtc_isign_o": "isign_i", "ctrl_vsc_off_o": "vsc_en_i"}
INVERTED = {"ctrl_vsc_off_o"}
# fields that drive a slice of a core input (feature adc; CntWidth 16): port -> (input, lsb, width)
SLICE = {f"adc_pt{k}_{n}_o": (f"adc_pt_{n}_i", k * w, w) for k in range(2) for n, w in (("cnt", 16), ("dn", 1), ("en", 1))}


def core_input(f: R.Field) -> str:
    """svpwm_core input driven by a writable field: ctrl_en_o -> en_i, freq_o -> freq_i, dt_dtf_o -> dtf_i
    (the ports of a register with several fields carry its name first)."""
    return OTHER_INPUT.get(f.port) or f.port.removeprefix("ctrl_").removeprefix("dt_").removesuffix("_o") + "_i"


class TB:
    def __init__(self, dut):
        self.dut = dut
        self.kind = os.environ["SVPWM_BUS"]
        top = dut.gen_axil if self.kind == "axil" else dut.gen_wb
        self.core = top.u_dut.u_mmio.u_core
        self.bus = None
        self.rng = random.Random(3)

    async def reset(self):
        d = self.dut
        d.fault.value = 0
        d.sync_in.value = 0
        d.rst_n.value = 0
        await clock_cycles(d.clk, 1)
        if self.bus is None:     # see test_svpwm_bus_regs.TB.reset
            from busdrv import AxilBus, WbBus
            self.bus = AxilBus(d) if self.kind == "axil" else WbBus(d, pipelined=(self.kind == "wb"))
        await clock_cycles(d.clk, 2)
        d.rst_n.value = 1
        await clock_cycles(d.clk, 2)

    def cin(self, f: R.Field) -> int:
        """The field's value as its core input carries it (inverted for CTRL.vsc_off -> vsc_en_i; the
        trigger points' slice of adc_pt_*_i)."""
        if f.port in SLICE:
            name, lsb, w = SLICE[f.port]
            return (int(getattr(self.core, name).value) >> lsb) & ((1 << w) - 1)
        v = int(getattr(self.core, core_input(f)).value)
        return 1 - v if f.port in INVERTED else v

    async def wr(self, reg: R.Register, **fields) -> None:
        await self.bus.write(reg.addr, reg.encode(**fields))

    async def rd(self, reg: R.Register) -> dict[str, int]:
        return reg.decode(await self.bus.read(reg.addr))


@cocotb.test()
async def fields_reach_core(dut):
    """Reset values at the core inputs; every RW field (walking ones, all ones) reads back and drives
    its core input; CONFIG matches the core's port widths; CLK_HZ reads the wrapper's ClkHz."""
    tb = TB(dut)
    await tb.reset()
    for r in R.REGISTERS:
        for f in r.fields:
            if f.kind in ("rw", "w1s", "pulse"):
                assert tb.cin(f) == (0 if f.kind == "pulse" else f.reset), f"{r.name}.{f.name} -> {core_input(f)} after reset"
    for r in [r for r in R.REGISTERS if r.mask("rw")]:
        safe = r.mask("rw") if r is not R.CTRL else R.CTRL.mask("rw") & ~R.CTRL.encode(en=1, pol=3)
        for p in [1 << i for i in range(32)] + [0xFFFFFFFF]:
            p &= safe
            await tb.bus.write(r.addr, p)
            got = await tb.bus.read(r.addr)
            assert got == p | (r.reset & ~safe), f"{r.name}: wrote 0x{p:08X}, read 0x{got:08X}"
            for f in r.fields:
                if f.kind == "rw" and f.mask & safe:
                    assert tb.cin(f) == (p & f.mask) >> f.lsb, f"{r.name}.{f.name}: core {core_input(f)} = {tb.cin(f)}"
        await tb.bus.write(r.addr, r.reset)
    cfg = await tb.rd(R.CONFIG)
    assert cfg["cnt_width"] == len(tb.core.carrier_o) and cfg["freq_width"] == len(tb.core.freq_i)
    assert cfg["dt_width"] == len(tb.core.dt_i), cfg
    assert await tb.bus.read(R.CLK_HZ.addr) == CLK_HZ[tb.kind]


@cocotb.test()
async def status_from_core(dut):
    """RO registers read the core's outputs: running, carrier, active period and compare values,
    period clamp (below MinPeriod; with CntWidth < 16 also PERIOD = 0x8000, above the core's range: runs
    2^CntWidth - 1, flagged), lock, fault / trip / fault_clear."""
    tb = TB(dut)
    await tb.reset()
    c = tb.core
    await tb.wr(R.PERIOD, period=MIN_PERIOD + 81)
    await tb.wr(R.M, m=0x4000)
    await tb.wr(R.FREQ, freq=100000)
    await tb.wr(R.CTRL, en=1)
    await clock_cycles(dut.clk, 6 * 200)
    for _ in range(20):                                # compare with the core outputs around each read
        await clock_cycles(dut.clk, tb.rng.randrange(1, 50))
        before = {k: int(getattr(c, v).value) for k, v in RO_MAP.items()}
        cmp_b = int(c.cmp_o.value)
        st = await tb.bus.read(R.STATUS.addr)
        ca = R.CARRIER.decode(await tb.bus.read(R.CARRIER.addr))
        pa = await tb.bus.read(R.PERIOD_ACT.addr)
        cmps = [await tb.bus.read(x.addr) for x in (R.CMP_A, R.CMP_B, R.CMP_C)]
        after_cmp = int(c.cmp_o.value)
        s = R.STATUS.decode(st)
        assert s["running"] == 1, f"STATUS {s}"
        assert pa == before["period_act_i"] and 0 <= ca["count"] <= pa, f"PERIOD_ACT {pa}, CARRIER {ca}"
        w = len(c.carrier_o)                           # CntWidth: the compare values' width
        if cmp_b == after_cmp:
            assert cmps == [(cmp_b >> (w * k)) & ((1 << w) - 1) for k in range(3)], (cmps, hex(cmp_b))
        for name in ("sat", "cfg_err", "period_clamp", "freq_clamp", "fault", "tripped", "locked"):
            assert s[name] == before[f"status_{name}_i"], f"STATUS.{name} {s[name]} != core {before[f'status_{name}_i']}"
    await tb.wr(R.PERIOD, period=10)                   # below MinPeriod: clamped and flagged
    await clock_cycles(dut.clk, 3 * 200)
    assert R.STATUS.decode(await tb.bus.read(R.STATUS.addr))["period_clamp"] == 1
    assert await tb.bus.read(R.PERIOD_ACT.addr) == int(c.period_o.value) >= MIN_PERIOD
    w = len(c.carrier_o)
    if w < 16:                                         # PERIOD's top bit alone above a narrower core's range:
        await tb.wr(R.PERIOD, period=1 << 15)          # the longest period 2^CntWidth - 1, flagged
        await clock_cycles(dut.clk, 4 * MIN_PERIOD + 8)
        assert await tb.bus.read(R.PERIOD_ACT.addr) == (1 << w) - 1
        assert R.STATUS.decode(await tb.bus.read(R.STATUS.addr))["period_clamp"] == 1
    dut.fault.value = 1                                # latched trip, cleared by CTRL.fault_clear
    await clock_cycles(dut.clk, 4)
    s = await tb.rd(R.STATUS)
    assert s["fault"] == 1 and s["tripped"] == 1 and int(dut.tripped.value) == 1, s
    dut.fault.value = 0
    await clock_cycles(dut.clk, 4)
    assert (await tb.rd(R.STATUS))["tripped"] == 1, "latched trip released without fault_clear"
    await tb.wr(R.CTRL, en=1, fault_clear=1)
    await clock_cycles(dut.clk, 4)
    s = await tb.rd(R.STATUS)
    assert s["tripped"] == 0 and s["fault"] == 0, f"fault_clear did not release the trip: {s}"
    assert (await tb.rd(R.CTRL))["fault_clear"] == 0
    await tb.wr(R.CTRL, en=1, lock=1)
    await clock_cycles(dut.clk, 2)
    assert (await tb.rd(R.STATUS))["locked"] == 1 and int(c.lock_i.value) == 1


async def _m_steps(tb: TB, upd: int) -> None:
    """Write M at random moments while running (frequency 0: the compare values depend on M only)
    and check every clock: cmp_o changes only in an update_o clock, update_o only at a load point of
    the CTRL.upd setting, and every new M is in force within two load points."""
    dut, c = tb.dut, tb.core
    period = MIN_PERIOD + 20
    await tb.wr(R.PERIOD, period=period)
    await tb.wr(R.THETA, theta=0x1555)                 # unused in mode FREQ
    await tb.wr(R.M, m=0x2000)
    await tb.wr(R.CTRL, en=1, upd=upd)
    await clock_cycles(dut.clk, 6 * period)
    log: list[tuple[int, int, int, int, int]] = []   # (cmp, update, valley, peak, m_i) per clock
    stop = False

    async def monitor():
        while not stop:
            await RisingEdge(dut.clk)
            await ReadOnly()
            log.append((int(c.cmp_o.value), int(c.update_o.value), int(c.valley_o.value),
                        int(c.peak_o.value), int(c.m_i.value)))

    mon = cocotb.start_soon(monitor())
    for _ in range(8):                                 # writes 3..5 periods apart, anywhere in a period
        await clock_cycles(dut.clk, tb.rng.randrange(3 * 2 * period, 5 * 2 * period))
        m = tb.rng.choice([0x1000, 0x3000, 0x5000, 0x7000]) + tb.rng.randrange(0, 0x800)
        await tb.wr(R.M, m=m)
    await clock_cycles(dut.clk, 3 * 2 * period)
    stop = True
    await mon
    changes = [k for k in range(1, len(log)) if log[k][0] != log[k - 1][0]]
    updates = [k for k in range(len(log)) if log[k][1]]
    assert changes, "compare values never changed"
    for k in changes:
        assert log[k][1] == 1, f"clock {k}: cmp_o changed without update_o (mid-period change)"
    load = {0: (2,), 1: (3,), 2: (2, 3)}[upd]
    for k in updates:   # update_o coincides with a load point of the setting (valley / peak / both)
        assert any(log[k][i] for i in load), f"clock {k}: update_o away from a load point (upd={upd})"
    writes = [k for k in range(1, len(log)) if log[k][4] != log[k - 1][4]]
    assert len(writes) == 8, f"{len(writes)} M changes seen at the core input"
    for w in writes:    # in force by the second load point after the write: the compare values moved
        later = [u for u in updates if u > w]
        assert len(later) >= 2, "run too short"
        assert log[later[1]][0] != log[w][0], f"M written at clock {w} not in force by the second load point"


@cocotb.test()
async def m_at_load_point_valley(dut):
    tb = TB(dut)
    await tb.reset()
    await _m_steps(tb, upd=0)


@cocotb.test()
async def m_at_load_point_both(dut):
    tb = TB(dut)
    await tb.reset()
    await _m_steps(tb, upd=2)


async def _updates(tb: TB, n: int) -> None:
    """Wait for n update_o pulses (the points and WIN_MIN written before are in force after 2)."""
    d = tb.dut
    for _ in range(n):
        for _ in range(8 * 65536):
            await RisingEdge(d.clk)
            if int(d.update.value):
                break
        else:
            raise AssertionError("no update_o")


async def _check_points(tb: TB, pts: tuple[adc.Point, adc.Point], has_adc: bool, periods: int = 3) -> int:
    """Every clock of `periods` carrier periods: adc_pt_o[k] (the wrapper's output) == adc.fires(point k) at
    the core's carrier count / direction of the clock before (the pulse is registered) and PERIOD_ACT,
    adc_trig_o == their OR (CTRL.adc_trig 0). A build without adc: never. Returns the pulses seen."""
    d, c = tb.dut, tb.core
    p = await tb.bus.read(R.PERIOD_ACT.addr)
    pulses = 0
    await RisingEdge(d.clk)
    await ReadOnly()
    prev = (int(c.carrier_o.value), bool(int(c.carrier_up_o.value)))
    for _ in range(2 * p * periods):
        await RisingEdge(d.clk)
        await ReadOnly()
        count, up = prev
        got = int(d.adc_pt.value)
        exp = sum(int(has_adc and adc.fires(pt, count, up, p)) << k for k, pt in enumerate(pts))
        assert got == exp, (f"adc_pt_o = {got:02b} != {exp:02b} the clock after carrier {count} "
                            f"{'up' if up else 'down'} (P {p}, {pts})")
        prev = (int(c.carrier_o.value), bool(int(c.carrier_up_o.value)))
        assert int(d.adc_trig.value) == int(got != 0), f"adc_trig_o != adc_pt_o[0] | [1] ({got:02b})"
        pulses += bin(got).count("1")
    return pulses


async def _check_windows(tb: TB, win_min: int, has_adc: bool) -> adc.Window:
    """WIN_LO_A..C, WIN_HI_A..C and WIN_STATUS == svpwm_model.adc.window of CMP_A..C, PERIOD_ACT and the dead
    times read over the bus (static compare values: every read sees the same period)."""
    cmp = tuple([await tb.bus.read(r.addr) for r in (R.CMP_A, R.CMP_B, R.CMP_C)])
    p = await tb.bus.read(R.PERIOD_ACT.addr)
    dt = R.DT.decode(await tb.bus.read(R.DT.addr))
    mp = R.MP.decode(await tb.bus.read(R.MP.addr))["mp"]
    run = R.STATUS.decode(await tb.bus.read(R.STATUS.addr))
    valid = run["running"] and not run["tripped"]
    exp = adc.window(cmp if valid else None, p, dt["dt"], dt["dtf"] if dt["dtf_en"] else dt["dt"], mp, win_min)
    lo = tuple([await tb.bus.read(r.addr) for r in (R.WIN_LO_A, R.WIN_LO_B, R.WIN_LO_C)])
    hi = tuple([await tb.bus.read(r.addr) for r in (R.WIN_HI_A, R.WIN_HI_B, R.WIN_HI_C)])
    st = R.WIN_STATUS.decode(await tb.bus.read(R.WIN_STATUS.addr))
    got = adc.Window(lo, hi, st["ok"], st["recon"])
    if not has_adc:
        exp = adc.window(None, p, 0, 0, 0, 0)
    assert got == exp, f"window report {got} != model {exp} (CMP {cmp}, P {p}, DT {dt}, WIN_MIN {win_min})"
    return got


@cocotb.test()
async def adc_points_and_windows(dut):
    """Feature adc over the bus: trigger points (up count, down count, the valley, a count beyond P, on a
    narrower core one beyond its range, in either register) make adc_pt_o and adc_trig_o pulse at exactly their
    carrier counts once they are in force; the shunt-window report equals the model's for the values read over
    the bus, with WIN_MIN 0, between the windows (the middle one's width and one more) and beyond every window; 0 when stopped. Without adc (FEATURES):
    the registers read 0, no pulse, the report 0."""
    tb = TB(dut)
    await tb.reset()
    features = R.FEATURES.decode(await tb.bus.read(R.FEATURES.addr))["features"]
    assert features == int(os.environ["SVPWM_FEATURES"]), f"FEATURES.features 0x{features:04X}"
    has_adc = config.has(features, "adc")
    w = len(tb.core.carrier_o)                        # CntWidth
    period = MIN_PERIOD + 45
    await tb.wr(R.PERIOD, period=period)
    await tb.wr(R.DT, dt=7, dtf=12, dtf_en=1)         # rising 7, falling 12 (a build without dtf: 7 both)
    await tb.wr(R.M, m=0x6000)
    await tb.wr(R.FREQ, freq=100000)
    pts = (adc.Point(True, False, period // 3), adc.Point(True, True, period // 2 + 5))
    for reg, pt in zip((R.ADC_PT0, R.ADC_PT1), pts):
        await tb.wr(reg, cnt=pt.cnt, dn=int(pt.dn), en=int(pt.en))
        exp = reg.encode(cnt=pt.cnt, dn=int(pt.dn), en=int(pt.en)) if has_adc else 0
        assert await tb.bus.read(reg.addr) == exp, f"{reg.name} does not read back"
    await tb.wr(R.CTRL, en=1)
    await clock_cycles(dut.clk, 6 * 200)
    await tb.wr(R.FREQ, freq=0)                       # the angle stays where it is: static compare values
    await _updates(tb, 3)
    n = await _check_points(tb, pts, has_adc)
    assert n == (6 if has_adc else 0), f"{n} trigger pulses in 3 periods"
    # the valley (either direction) and a count beyond P: the peak; on a core narrower than 16 bits a count
    # beyond its range (truncated it would be the valley)
    beyond = 1 << w if w < 16 else 0xFFFF
    for pts in ((adc.Point(True, True, 0), adc.Point(True, False, beyond)),      # each register's clamp
                (adc.Point(True, True, beyond + 3 if w < 16 else 0xFFFE), adc.Point(True, False, 0))):
        for reg, pt in zip((R.ADC_PT0, R.ADC_PT1), pts):
            await tb.wr(reg, cnt=pt.cnt, dn=int(pt.dn), en=int(pt.en))
        await _updates(tb, 3)
        assert await _check_points(tb, pts, has_adc, periods=2) == (4 if has_adc else 0)
    await tb.wr(R.ADC_PT1, cnt=period // 4, en=0)     # off: point 0 only
    await _updates(tb, 3)
    await _check_points(tb, (pts[0], adc.Point(False, False, period // 4)), has_adc, periods=1)

    cmp = [await tb.bus.read(r.addr) for r in (R.CMP_A, R.CMP_B, R.CMP_C)]
    assert len(set(cmp)) == 3, f"compare values {cmp} not distinct: a swap of phases would not show"
    win = await _check_windows(tb, 0, has_adc)
    if has_adc:                                        # plausible: windows inside the period, all readable
        assert all(0 < x < 2 * period for x in win.lo + win.hi) and win.ok == 7, win
    mid = sorted(win.lo)[1]                            # WIN_MIN between the windows: two of three readable,
    top = (1 << (w + 1)) if w < 16 else 0x1FFFF        # one more: one; beyond every window (a narrow core's range)
    for win_min in (mid, mid + 1, top):
        await tb.wr(R.WIN_MIN, win_min=win_min)
        assert await tb.bus.read(R.WIN_MIN.addr) == (win_min if has_adc else 0)
        await _updates(tb, 3)
        win = await _check_windows(tb, win_min, has_adc)
        if has_adc:
            assert win.ok == (sum(1 << k for k in range(3) if win.lo[k] >= win_min) if win_min != top else 0), win
            assert win.ok != 7 and (win_min == top or win.ok), win
    await tb.wr(R.CTRL, en=0)                         # stopped: not valid, all 0
    await clock_cycles(dut.clk, 8)
    assert await _check_windows(tb, win_min, has_adc) == adc.window(None, 0, 0, 0, 0, 0)


import pytest  # noqa: E402


# the builds: each bus at CntWidth 16; the AXI4-Lite wrapper also at CntWidth 12 (the RO registers from
# the core: the compare values' slices of a 12-bit core; the RW fields' walk assumes a 16-bit PERIOD; the
# trigger points and WIN_MIN beyond its range); the classic Wishbone wrapper also in the build vf (no adc:
# its registers read 0, no trigger pulses)
BUILDS = {"axil": ("axil", 16, None, "full"), "wb": ("wb", 16, None, "full"), "wbc": ("wbc", 16, None, "full"),
          "axil_cnt12": ("axil", 12, ["status_from_core", "adc_points_and_windows"], "full"),
          "wbc_vf": ("wbc", 16, "adc_points_and_windows", "vf")}


@pytest.mark.parametrize("build", list(BUILDS))
def test_svpwm_bus(sim, build):
    from simrun import rtl_sources, run_sim

    bus, cnt_width, testcase, cfg = BUILDS[build]
    run_sim(sim, toplevel="tb_svpwm_bus", sources=rtl_sources() + [HERE / "tb_svpwm_bus.sv"],
            test_module="test_svpwm_bus", test_dir=HERE,
            parameters={"Bus": {"axil": 0, "wb": 1, "wbc": 2}[bus], "MinPeriod": MIN_PERIOD, "ClkHz": CLK_HZ[bus],
                        "CntWidth": cnt_width, "Features": config.CONFIGS[cfg]},
            build_name=build, extra_env={"SVPWM_BUS": bus, "SVPWM_FEATURES": config.CONFIGS[cfg]}, testcase=testcase)
