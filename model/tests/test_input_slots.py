# SPDX-License-Identifier: Apache-2.0
"""svpwm_core keeps the sampled reference in three 16-bit slots chosen by the mode (fixed.input_slots); the
calculator's inputs of one slot all read it. That is exact only if no mode reads two inputs of one slot:
fixed.modulate on the slot view equals fixed.modulate on the inputs themselves, for every mode (the invalid
ones too) and DPWM setting, directed corners and random vectors; and on the calculator's machine model."""
from __future__ import annotations

import random

import pytest

from svpwm_model import calc_prog as cp
from svpwm_model import config, fixed

REF = ("m", "theta", "v1", "v2", "vf_boost", "vf_slope", "vf_mmax")
VS = (-32768, -32767, -1, 0, 1, 0x3FFF, 0x4000, 32767)
US = (0, 1, 0x4000, 0x8000, 0x93CD, 0xFFFF)


def _ref(rng: random.Random) -> dict:
    return dict(m=rng.choice(US + (rng.randint(0, 0xFFFF),)), theta=rng.randint(0, 0xFFFF),
                v1=rng.choice(VS + (rng.randint(-32768, 32767),)), v2=rng.choice(VS + (rng.randint(-32768, 32767),)),
                vf_boost=rng.randint(0, 0xFFFF), vf_slope=rng.randint(0, 0xFFFF), vf_mmax=rng.randint(0, 0xFFFF))


def _both(mode, sector, a16, period, freq, dpwm, ref):
    slots = fixed.input_slots(mode, **ref)
    assert set(slots) == set(REF)
    got = fixed.modulate(mode, sector, a16, period, freq=freq, dpwm=dpwm, **slots)
    exp = fixed.modulate(mode, sector, a16, period, freq=freq, dpwm=dpwm, **ref)
    return got, exp


@pytest.mark.parametrize("mode", range(8))
def test_slots_change_nothing(mode):
    rng = random.Random(100 + mode)
    for k in range(3000):
        ref = _ref(rng)
        f = rng.randint(-(1 << (fixed.FREQ_WIDTH - 1)) + 1, (1 << (fixed.FREQ_WIDTH - 1)) - 1)
        got, exp = _both(mode, rng.randint(0, 5), rng.randint(0, 0xFFFF), rng.choice((48, 1536, 65535)), f,
                         k % 4, ref)
        assert got == exp, (mode, ref)


def test_slots_differ_from_inputs():
    """The check above can fail: a mode that reads two inputs of one slot (v1 and m both in s0) would not
    survive the slot view -- FREQ mode on a view whose m is v1's slot changes the result."""
    ref = dict(m=0x4000, theta=0, v1=0x1000, v2=0, vf_boost=0, vf_slope=0, vf_mmax=0)
    wrong = fixed.input_slots(fixed.MODE_AB, **ref)           # AB's slots read in FREQ mode: m becomes v1
    a = fixed.modulate(fixed.MODE_FREQ, 0, 0x4000, 1536, **wrong)
    b = fixed.modulate(fixed.MODE_FREQ, 0, 0x4000, 1536, **ref)
    assert a != b


@pytest.mark.parametrize("mode", range(8))
def test_slots_on_the_machine(mode):
    """The full program on the machine model with the slot view == the specification on the inputs."""
    mach = cp.Machine(cp.program(config.FULL))
    rng, junk = random.Random(7 + mode), random.Random(8)
    for _ in range(150):
        ref = _ref(rng)
        f = rng.randint(-(1 << (fixed.FREQ_WIDTH - 1)) + 1, (1 << (fixed.FREQ_WIDTH - 1)) - 1)
        P = rng.choice((48, 1536, 65535))
        v = dict(period=P, thr=min(5, P // 2), sector=rng.randint(0, 5), a16=rng.randint(0, 0xFFFF), mode=mode,
                 freq=f, fabs=abs(f) >> (fixed.FREQ_WIDTH - 17), dpwm=rng.randint(0, 3), **ref)
        seen = dict(v, **fixed.input_slots(mode, **ref))
        assert mach.run(seen, junk=junk) == cp.expect(v), (mode, ref)
