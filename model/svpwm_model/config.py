# SPDX-License-Identifier: Apache-2.0
"""Build configurations of svpwm_core: which features a build has (svpwm_core's Features parameter).

A configuration is a bit mask of FEATURES (bit i = FEATURES[i]); svpwm_pkg's Feat* / Cfg* constants are
generated from this file (scripts/gen_tables.py), so the RTL, the golden model and the tests name the same
bits. Safety is never a feature: dead time, minimum pulse, trip, safe state, lock and interlock are in every
build.

  freq vf polar ab dq   the input modes (mode_i codes 0..4); a code of a mode not built: zero vector + cfg_err_o
  dpwm                  dpwm_i (bus-clamped DPWM); without it: continuous SVPWM, dpwm_i not read
  sixstep               om_i (the six-step overmodulation law); without it: the angle-keeping clamp
  dtc                   dead-time compensation (dtc_en_i, isign_i)
  carry                 the volt-second carry of the minimum-pulse rule (vsc_en_i)
  dtf                   a separate falling dead time (dtf_i, dtf_en_i); without it: one dead time, dt_i
  upd                   the update modes beyond the valley: peak and double (upd_i); without it: valley
  presc                 the update prescaler (presc_i)
  sync                  the sync start (sync_en_i, sync_i)
  dsp                   the calculator's multiplier: 1 the registered 16 x 16 multiplier (the UP5K's SB_MAC16),
                        0 the serial shift-add unit (devices without a DSP; a longer program)
  adc                   current sampling: two programmable ADC trigger points (adc_pt_*_i, shadowed like the
                        compare values) and the per-phase shunt-window report (win_*_o) for a minimum window
                        (win_min_i); without it: adc_trig_o at the valley / peak only (adc_trig_i)

Named configurations (CONFIGS): full (every feature, the default), foc, vf, minimal, tiny. Only the programs
of the named configurations are generated (calc_prog.program); a build with another mask stops at
elaboration with a message naming the mask (add it to CONFIGS and run `make rom`).
"""
from __future__ import annotations

FEATURES = ("freq", "vf", "polar", "ab", "dq", "dpwm", "sixstep", "dtc", "carry", "dtf", "upd", "presc",
            "sync", "dsp", "adc")
BIT = {n: i for i, n in enumerate(FEATURES)}
ALL = (1 << len(FEATURES)) - 1


def mask(*names: str) -> int:
    out = 0
    for n in names:
        out |= 1 << BIT[n]
    return out


def has(features: int, name: str) -> bool:
    return bool(features >> BIT[name] & 1)


def names(features: int) -> list[str]:
    return [n for n in FEATURES if has(features, n)]


MODES = ("freq", "vf", "polar", "ab", "dq")          # index = mode code (fixed.MODE_*)
# the features the calculator's program depends on (the others live in svpwm_core around it)
CALC = mask("freq", "vf", "polar", "ab", "dq", "dpwm", "sixstep", "dtc", "carry", "dsp")
MODE_MASK = mask(*MODES)                             # at least one of them in every build

FULL = ALL
CONFIGS: dict[str, int] = {
    "full": FULL,
    "foc": mask("polar", "ab", "dq", "dtc", "carry", "dtf", "upd", "presc", "sync", "dsp", "adc"),
    "vf": mask("freq", "vf", "dtc", "carry", "sixstep", "dpwm", "dsp"),
    "minimal": mask("polar", "dsp"),
    # TRANSITIONAL: tiny is the compact core (svpwm_core Compact = 1 before issue 28) and still runs its own
    # serial datapath (rtl/svpwm_duty_lite.sv), which reads no mode: mode_i is ignored, FREQ is assumed
    "tiny": mask("freq"),
}
TINY = CONFIGS["tiny"]
DESCRIPTION = {
    "full": "every feature (the default)",
    "foc": "POLAR, AB, DQ; dead-time compensation, carry, falling dead time, peak / double update, prescaler, "
           "sync start, ADC trigger points and shunt-window report; DSP multiplier",
    "vf": "FREQ, VF; dead-time compensation, carry, six-step, DPWM; valley update; DSP multiplier",
    "minimal": "POLAR only, continuous SVPWM, valley update; DSP multiplier",
    "tiny": "FREQ only on the serial unit, valley update (the HX1K); mode_i ignored",
}


def config_name(features: int) -> str | None:
    for n, f in CONFIGS.items():
        if f == features:
            return n
    return None


def modes(features: int) -> tuple[int, ...]:
    """The mode codes a build has."""
    return tuple(i for i, n in enumerate(MODES) if has(features, n))


def mode_built(features: int, mode: int) -> bool:
    return 0 <= mode < len(MODES) and has(features, MODES[mode])


# the feature groups the core and the calculator derive (svpwm_pkg has_theta, has_xy, has_acc)
def has_theta(features: int) -> bool:
    """theta_i is read: POLAR or DQ."""
    return has(features, "polar") or has(features, "dq")


def has_xy(features: int) -> bool:
    """v1_i / v2_i are read (X, Y, Z projections): AB or DQ."""
    return has(features, "ab") or has(features, "dq")


def has_acc(features: int) -> bool:
    """The phase accumulator is built (freq_i read): FREQ or VF."""
    return has(features, "freq") or has(features, "vf")


def parse(spec: str | int) -> int:
    """A configuration name, a '+'-separated feature list or an integer mask -> the mask (ValueError if bad)."""
    if isinstance(spec, int):
        if not 0 <= spec <= ALL:
            raise ValueError(f"feature mask {spec:#x} outside 0..{ALL:#x}")
        return spec
    s = spec.strip().lower()
    if s in CONFIGS:
        return CONFIGS[s]
    try:
        return parse(int(s, 0))
    except ValueError:
        pass
    bad = [n for n in s.split("+") if n not in BIT]
    if bad:
        raise ValueError(f"unknown configuration or feature {', '.join(bad)!r}: configurations "
                         f"{', '.join(CONFIGS)}, features {', '.join(FEATURES)}")
    return mask(*s.split("+"))
