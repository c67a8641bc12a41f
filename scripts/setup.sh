#!/usr/bin/env bash
# One-shot, idempotent set-up on a fresh Debian machine: Debian packages through apt-get,
# then the pinned Python tool chain in .venv/. Quick when everything is already there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"

# Debian packages the project uses (build, renderer, models, waves, formal solvers).
DEB_PKGS=(build-essential cmake pkg-config perl python3-venv
          liblz4-dev zlib1g-dev libembree-dev libassimp-dev
          glmark2-data assimp-testmodels gtkwave libgtest-dev libstb-dev z3 cvc4)

# standard cells and static timing (make asic, the gate-level bench): the OSU 0.18 um library
# (liberty, LEF, Verilog cell models) and OpenSTA
DEB_PKGS+=(qflow-tech-osu018 opensta)

# waves screenshots for docs/ (scripts/waves_shot.py: GTKWave under a virtual X server)
DEB_PKGS+=(xvfb xauth scrot)

# compiler cache of the cocotb benches' Verilator builds (msr_flow.runner): the run-time
# library, the same in each of make test's some 25 builds, is compiled once
DEB_PKGS+=(ccache)

missing=()
for p in "${DEB_PKGS[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Python environment; the stamp records which requirements and package files it was built from.
stamp=".venv/.setup-stamp"
want="$(cat requirements.txt sw_model/pyproject.toml tb/pyproject.toml flow/pyproject.toml | sha256sum | cut -d' ' -f1)"
if [ ! -x .venv/bin/python ] || [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "setup: creating .venv from requirements.txt"
  PY="${PYTHON:-python3}"
  [ -x .venv/bin/python ] || "$PY" -m venv .venv
  .venv/bin/python -m pip install -q --upgrade pip
  .venv/bin/python -m pip install -q -r requirements.txt
  # the golden model (sw_model), the build and run library (flow/: file list, runners, harness,
  # register constants, flows) and the benches' own helpers (tb/common: cocotb helpers,
  # functional coverage), in one pip run
  .venv/bin/python -m pip install -q --no-deps --no-build-isolation -e sw_model -e flow -e tb
  echo "$want" > "$stamp"
fi
