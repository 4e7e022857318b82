# SPDX-License-Identifier: Apache-2.0
"""scripts/isign_hysteresis.py: the model-only loop is the core's timeline (its gate edges == CoreModel.run for
the isign words it applied), its sign detector holds the sign inside the band, and with the currents taken in
the sample clock S - 1 it reproduces `make demo`'s Fig. 10 current THD (docs/demo.md: 1.21 % uncompensated,
0.14 % compensated; the same motor inputs, edge for edge)."""
from __future__ import annotations

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))

import isign_hysteresis as H  # noqa: E402


def test_sign_detector_hysteresis():
    d = H.SignDetector(0.1, (1.0, -1.0, 0.05))
    assert d.bits == 0b010
    assert d((0.05, -0.05, -0.05)) == 0b010           # inside the band: kept
    assert d((-0.2, 0.2, -0.11)) == 0b101             # beyond it: the new sign, bit k = phase k, 1 = negative
    assert H.SignDetector(0.0, (0.0, -1e-9, 1e-9)).bits == 0b010


def test_loop_equals_core_model():
    for dtc, band, sample in ((True, 5.0, "valley"), (True, 0.0, "lead"), (False, 0.0, "valley")):
        r = H.run(50.0, 0.9, dt=H.DT_1US, dtc=dtc, band_pct=band, noise_pct=2.0, sample=sample, n_periods=40,
                  check=True)                           # asserts the gate edges equal CoreModel.run's
        assert r["checked_edges"] > 40 * 6


def test_fig10_reproduces_demo():
    f_hz, m, revs, wu = H.POINTS["fig10"]
    thd = {dtc: H.run(f_hz, m, dt=H.DT_1US, dtc=dtc, sample="lead", revs=revs, warmup_revs=wu)["i_thd"]
           for dtc in (False, True)}
    assert (round(100 * thd[False], 2), round(100 * thd[True], 2)) == (1.21, 0.14), thd
