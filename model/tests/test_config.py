# SPDX-License-Identifier: Apache-2.0
"""The build configurations (model/svpwm_model/config.py): the package svpwm_pkg is generated from them
(test_seed_tables checks it is current); here: parsing, the named masks' content, and the README's table of
sample leads / MinPeriods against fixed.latencies (the README states them; they must not go stale)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from svpwm_model import calc_prog, config, fixed

README = Path(__file__).resolve().parents[2] / "README.md"


def test_parse():
    assert config.parse("full") == config.FULL == config.ALL
    assert config.parse("polar+dsp") == config.CONFIGS["minimal"]
    assert config.parse(str(config.CONFIGS["foc"])) == config.CONFIGS["foc"]
    assert config.parse(hex(config.CONFIGS["vf"])) == config.CONFIGS["vf"]
    with pytest.raises(ValueError, match="unknown configuration or feature"):
        config.parse("polar+warp")
    with pytest.raises(ValueError, match="outside"):
        config.parse(config.ALL + 1)


def test_named_configurations():
    c = config.CONFIGS
    assert config.modes(c["foc"]) == (fixed.MODE_POLAR, fixed.MODE_AB, fixed.MODE_DQ)
    assert config.modes(c["vf"]) == (fixed.MODE_FREQ, fixed.MODE_VF)
    assert config.names(c["minimal"]) == ["polar", "dsp"]
    assert config.names(c["tiny"]) == ["freq"]
    # a shorter program gives a shorter lead; every named configuration but tiny has its own program
    lat = {n: calc_prog.calc_latency(f) for n, f in c.items() if n != "tiny"}
    assert lat["minimal"] < lat["vf"] < lat["foc"] < lat["full"], lat
    assert len({calc_prog.program_key(f) for n, f in c.items() if n != "tiny"}) == 4


def test_readme_table():
    text = README.read_text()
    for n, f in config.CONFIGS.items():
        m = re.search(rf"^\| `{n}`[^\n]*\| (\d+) / (\d+) \|$", text, re.M)
        assert m, f"README: no row for configuration {n}"
        lat = fixed.latencies(f)
        assert (int(m[1]), int(m[2])) == (lat["SAMPLE_LEAD"], lat["MIN_PERIOD"]), n


def test_formal_minimal_mask():
    """formal/core.sby's minimal tasks set the minimal configuration's mask (typed there: .sby has no
    package)."""
    sby = (README.parent / "formal" / "core.sby").read_text()
    m = re.search(r"^minimal: chparam -set Features (\d+) svpwm_core$", sby, re.M)
    assert m and int(m[1]) == config.CONFIGS["minimal"], m and m[1]
