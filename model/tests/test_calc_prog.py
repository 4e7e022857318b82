# SPDX-License-Identifier: Apache-2.0
"""The calculator's program (model/svpwm_model/calc_prog.py), run on the clock-exact machine model, against the
specification: calc_prog.expect = fixed.modulate + fixed.snap_min_pulse per phase, exact (==).

Programs: those of the named configurations (config.CONFIGS: full, foc, vf, minimal on the DSP multiplier, tiny
on the serial unit) and the full program on the serial multiplier (a device without a DSP). Every vector sets
every input (all mode codes 0..7 too): the program of a build must ignore what the build lacks, and give the zero
vector and err for a mode it lacks (calc_prog.expect). Every run starts from junk machine state (registers,
flags, the RAM's working words), as the RTL does after an earlier or aborted computation.
"""
from __future__ import annotations

import math
import random

import pytest

from svpwm_model import calc_prog as cp
from svpwm_model import config, fixed

PROGRAMS = {**config.CONFIGS, "full-serial": config.FULL & ~config.mask("dsp")}
IDS = list(PROGRAMS)
FEATS = list(PROGRAMS.values())
ENGINE = [f for f in FEATS if f != config.TINY]                # the programs that read the mode
ENGINE_IDS = [n for n, f in PROGRAMS.items() if f != config.TINY]
M_VERTEX = int(round(2 / math.sqrt(3) * fixed.M_ONE))          # 0x93CD, the hexagon's vertex
PERIODS = (8, 48, 100, 1536, 4095, 65535)
ANGLES = (0, 1, 0x7FFF, 0x8000, 0x8001, 0xFFFE, 0xFFFF)
MS = (0, 1, 0x4000, 0x8000, M_VERTEX, M_VERTEX + 1, 0xFFFF)
VS = (-32768, -32767, -1, 0, 1, 0x3FFF, 32767)


def _thrs(P: int) -> tuple[int, ...]:
    return tuple(sorted({0, 1, 2, 5, min(P // 2, 2047), min(P // 2 - 1, 2047) if P > 2 else 0}))


def _vec(rng: random.Random, features: int) -> dict:
    P = rng.choice(PERIODS + (rng.randint(8, 65535),) * 4)
    thr = min(rng.choice([0, 1, 2, 5, rng.randint(0, P // 2), P // 2]), P // 2, 2047)
    d = dict(period=P, thr=thr, sector=rng.randint(0, 5), a16=rng.choice(ANGLES + (rng.randint(0, 65535),) * 3),
             m=rng.choice(MS + (rng.randint(0, 65535),) * 3))
    if features != config.TINY:
        f = rng.randint(-(1 << (fixed.FREQ_WIDTH - 1)) + 1, (1 << (fixed.FREQ_WIDTH - 1)) - 1)
        d.update(mode=rng.choice(range(8)), freq=f, fabs=abs(f) >> (fixed.FREQ_WIDTH - 17),
                 theta=rng.randint(0, 65535), v1=rng.choice(VS + (rng.randint(-32768, 32767),) * 3),
                 v2=rng.choice(VS + (rng.randint(-32768, 32767),) * 3), vf_boost=rng.randint(0, 65535),
                 vf_slope=rng.randint(0, 65535), vf_mmax=rng.randint(0, 65535), dpwm=rng.randint(0, 3),
                 om=rng.randint(0, 1))
        if rng.random() < 0.5:                                     # dead-time compensation (DtWidth 10)
            hd = min(thr, 512)
            d.update(isign=rng.randint(0, 7), hdr=rng.choice([0, 1, hd, rng.randint(0, 512)]),
                     hdf=rng.choice([0, 1, hd, rng.randint(0, 512)]))
        if rng.random() < 0.5:                                     # volt-second carry in (DtWidth 10: 12 bits)
            b = rng.choice([(thr + 1) // 2 + 1, 2048])
            d["carry"] = tuple(rng.randint(-b, min(b, 2047)) for _ in range(3))
    return d


def _directed(features: int):
    """Corners: every sector x angle x m x (P, thr) corner in FREQ mode; for the full program every mode x DPWM
    setting with corner references (AB / DQ components, theta at the sector ends, V/f saturating)."""
    for sector in range(6):
        for a16 in ANGLES:
            for m in MS:
                for P in (48, 65535):
                    for thr in _thrs(P)[::2]:
                        yield dict(period=P, thr=thr, sector=sector, a16=a16, m=m)
    if features == config.TINY:
        return
    for mode in range(8):
        for dpwm in range(4):
            for v1 in VS:
                for v2 in VS[::2]:
                    for theta in (0, 0x2AAA, 0x2AAB, 0xFFFF):
                        f = max(v2 * 256, -(1 << 23) + 1)          # |f| <= FreqMax, as the core clamps it
                        yield dict(period=1536, thr=5, sector=theta % 6, a16=theta, m=(v1 & 0xFFFF),
                                   mode=mode, dpwm=dpwm, v1=v1, v2=v2, theta=theta, freq=f,
                                   fabs=abs(f) >> (fixed.FREQ_WIDTH - 17),
                                   vf_boost=0x1000, vf_slope=0xFFFF if v1 < 0 else 0x0100, vf_mmax=0xFFFF)
    # six-step overmodulation law: m from below the vertex to the largest, every angle corner, the angle-driven
    # modes (V/f with m_max = m) and AB / DQ (the law does not apply there)
    for mode in (fixed.MODE_FREQ, fixed.MODE_VF, fixed.MODE_POLAR, fixed.MODE_AB, fixed.MODE_DQ):
        for m in (0x8000, M_VERTEX - 1, M_VERTEX, M_VERTEX + 1, M_VERTEX + 200, 0xC000, 0xFFFE, 0xFFFF):
            for a16 in ANGLES:
                for dpwm in (0, 3):
                    yield dict(period=1536, thr=5, sector=a16 % 6, a16=a16, m=m, mode=mode, dpwm=dpwm, om=1,
                               theta=a16, v1=m // 2, v2=-(m // 3), freq=0x7FFFFF, fabs=0xFFFF,
                               vf_boost=0, vf_slope=0xFFFF, vf_mmax=m)
    # dead-time compensation: every current-sign pattern in every sector, compare values pushed below 0 and
    # above P (m near 0 and at the vertex, DPWM clamping a phase to a rail), the largest amounts
    for isign in range(8):
        for sector in range(6):
            for m in (0, 0x4000, M_VERTEX):
                for dpwm in range(4):
                    for hdr, hdf, thr in ((3, 5, 10), (24, 24, 48), (512, 1, 1023), (0, 512, 0)):
                        yield dict(period=1536, thr=thr, sector=sector, a16=0x3000, m=m, dpwm=dpwm,
                                   isign=isign, hdr=hdr, hdf=hdf, carry=(isign - 3, -(thr + 1) // 2, thr // 2))

def _slow(features: int) -> bool:
    """An engine program on the serial unit (several hundred clocks a run): fewer vectors."""
    return not config.has(features, "dsp") and features != config.TINY


@pytest.mark.parametrize("features", FEATS, ids=IDS)
def test_directed(features):
    mach = cp.Machine(cp.program(features))
    junk = random.Random(1)
    every = 4 if _slow(features) else 1                        # full program on the serial unit: every 4th
    n = 0
    for k, v in enumerate(_directed(features)):
        if k % every == 0:
            assert mach.run(v, junk=junk) == cp.expect(v, features), v
            assert mach.e_out == cp.expect_carry(v, features)[4], v
            n += 1
    assert n >= 1000


@pytest.mark.parametrize("features", FEATS, ids=IDS)
def test_random(features):
    mach = cp.Machine(cp.program(features))
    rng = random.Random(2024 + features)
    for _ in range(1000 if _slow(features) else 3000):
        v = _vec(rng, features)
        assert mach.run(v, junk=rng) == cp.expect(v, features), v
        assert mach.e_out == cp.expect_carry(v, features)[4], v


def test_missing_features_change_results():
    """Not vacuous: for each feature of the calculator a vector whose result in the full build differs from
    that of a build without it (so test_random compares builds that really differ)."""
    rng = random.Random(5)
    vecs = [_vec(rng, config.FULL) for _ in range(3000)]
    for name in ("freq", "vf", "polar", "ab", "dq", "dpwm", "sixstep", "dtc", "carry"):
        lacking = config.FULL & ~config.mask(name)
        assert any(cp.expect_carry(v, config.FULL) != cp.expect_carry(v, lacking) for v in vecs), name


@pytest.mark.parametrize("features", FEATS, ids=IDS)
def test_words(features):
    """The packed word decodes to the logical fields the program was built with; it fits three 16-bit block
    RAM words; the shipped programs are at most 256 words deep; the latency bounds of the issue (MinPeriod <= 256)."""
    prog = cp.program(features)
    assert cp.WORD_BITS <= 48
    names = [n for n, _ in cp.LOGICAL]
    for k, (w, word) in enumerate(zip(prog.words(), prog.encode())):
        assert 0 <= word < (1 << cp.WORD_BITS)
        got = cp.decode(word)
        for n in names:
            shared = {"wa": "we", "fidx": "fset"}
            if n in shared and not w.get(shared[n]):
                continue                                       # a shared field's bits belong to the other use
            assert got[n] == w.get(n, 0), (k, n)
    assert len(prog.steps) <= (512 if _slow(features) else 256)   # the shipped programs: one 256-word depth
    if config.has(features, "dsp"):
        assert cp.calc_latency(features) + 1 + 4 <= 256


@pytest.mark.parametrize("features", FEATS, ids=IDS)
def test_idle_word_and_fabs(features):
    """Word 0 is the idle word: no own fields (the ROM reads it whenever the machine is idle). The |f|, period
    and threshold inputs (fabs_i, period_i, thr_i) are read at step 1 at the earliest (the input register of
    the operand of step k loads in clock k - 2): svpwm_core registers them in the start clock (|f| one clock
    after the frequency word it samples with the reference), i.e. they are valid from the calculator's step 1
    on. Step 1 has no operand (it would come from the word before the start)."""
    prog = cp.program(features)
    w0 = cp.decode(prog.encode()[0])
    assert all(w0[n] == 0 for n, _ in cp.OWN_FIELDS), w0
    late = (cp.IN_FABS, cp.IN_PERIOD, cp.IN_THR)
    reads = [k for k, st in enumerate(prog.steps) if st.get("asrc") == cp.AS_IN and st.get("isel") in late]
    assert reads and all(k - 2 >= 1 for k in reads), reads   # the input of step k is taken in clock k - 2


@pytest.mark.parametrize("features", FEATS, ids=IDS)
def test_mb_acc_unused(features):
    """No step loads MB with the ACC selection (mlb with mbs = MB_ACC, mop codes 5, 9, 10 of the table): the
    program multiplies ACC only as MA. svpwm_calc's MbAcc branch of mb_d is therefore never loaded, which is
    why scripts/mutate_equivalent.json lists mutants of that branch as equivalent; a generator change that
    uses it makes this test fail (and those mutants must then be killed, not listed)."""
    words = [cp.decode(x) for x in cp.program(features).encode()]
    used = [k for k, g in enumerate(words) if g["mlb"] and g["mbs"] == cp.MB_ACC]
    assert not used, f"words {used} load MB from ACC"
    assert any(g["mlb"] for g in words)                        # (the decode sees the loads at all)


@pytest.mark.parametrize("features", [config.FULL, PROGRAMS["full-serial"]], ids=["full", "full-serial"])
def test_idle_word_equals_word_1(features):
    """The full programs (the build `make mutate` runs: it holds for foc and minimal too, not for vf, whose
    first step waits for fabs_i) have the same packed word at addresses 0 (the idle word) and 1 (step
    1: empty, its next fields are step 1's selections too). svpwm_calc's step counter then may idle at 0 or 1
    without a difference, which is why scripts/mutate_equivalent.json lists the mutants that make pc_d 1
    when idle or after an abort as equivalent; a generator change that makes the two words differ fails this
    test (and those mutants must then be killed, not listed)."""
    words = cp.program(features).encode()
    assert words[0] == words[1], (hex(words[0]), hex(words[1]))
    assert len(set(words)) > 10                                # (the program is not all one word)


@pytest.mark.parametrize("features", ENGINE, ids=ENGINE_IDS)
def test_input_operand_codes(features):
    """Every word of the engine's programs (Compact = 0) whose operand is an input (src = AS_IN) has an input
    code 0..13: svpwm_calc's `default` of in_sel (the operand field of a word whose B is a RAM word or a
    product shift) only reaches in_q when the next step does not read it, which is why
    scripts/mutate_equivalent.json lists the mutant of that default as equivalent; a generator change that
    breaks this fails here (and that mutant must then be killed, not listed)."""
    fp = cp.field_pos()
    words = cp.program(features).encode()

    def f(w, name):
        return (w >> fp[name][0]) & ((1 << fp[name][1]) - 1)

    reads = [(k, f(w, "opnd")) for k, w in enumerate(words) if f(w, "src") == cp.AS_IN]
    assert len(reads) > 10                                       # (inputs are read)
    assert all(code & 0xF <= cp.IN_MV for _, code in reads), reads


def test_misuse_is_refused():
    """The builder's packing refuses fields that share bits."""
    with pytest.raises(AssertionError):
        cp.pack(dict(we=1, wa=3, fset=1, fidx=3))
    with pytest.raises(AssertionError):
        cp.pack(dict(qsh=1, rsel=cp.ROM_I))
    with pytest.raises(AssertionError):
        cp.pack(dict(asrc=cp.AS_IN, isel=1, ra=5))
    # step 1 has no operand; step 2 no condition (its condition bits would be computed in the start clock)
    with pytest.raises(AssertionError):
        cp.Program(config.FULL, False, [{}, cp.ram(8), {}]).words()
    with pytest.raises(AssertionError):
        cp.Program(config.FULL, False, [{}, {}, cp.ram(8, rc=cp.RC_C, ci=cp.F_VF), {}]).words()
    with pytest.raises(AssertionError):
        cp.Program(config.FULL, False, [{}, {}, {}, cp.ram(8, rc=cp.RC_C, ci=cp.F_VF, binv=cp.BINV_C, bci=cp.F_VF)]).words()


@pytest.mark.parametrize("features", [config.FULL, config.TINY], ids=["full", "tiny"])
def test_random_cnt12(features):
    """CntWidth 12: the machine's width is the same (acc_width: every product and the V/f candidate need 26
    bits whatever the compare width), the compare values 12 bits."""
    assert cp.acc_width(12) == cp.acc_width(16)
    mach = cp.Machine(cp.program(features), cnt_width=12)
    rng = random.Random(12)
    for _ in range(1000):
        v = _vec(rng, features)
        v["period"] = min(v["period"], (1 << 12) - 1)
        v["thr"] = min(v["thr"], v["period"] // 2)
        assert mach.run(v, junk=rng) == cp.expect(v, features), v
