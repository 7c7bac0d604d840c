#!/usr/bin/env bash
# Installs every dependency of contactsim on Debian bookworm, idempotently:
# the Debian packages the C++ build needs and a Python virtual environment
# (.venv) with the lcm bindings, numpy, matplotlib, tqdm, pytest, aiohttp, selenium, ray,
# gymnasium, pandas, PyBullet and pinocchio (robot-model oracles of the tests), Drake (whose iiwa driver
# systems drive the simulated arm), MuJoCo's C library and headers (the mujoco-core wheel, for the
# MuJoCo peer of `make bench`) and the contactsim client installed editable, and three.js for the viewer
# (npm ci). Works as root and through sudo.
set -euo pipefail
cd "$(dirname "$0")/.."

# What the .deb's build needs (LCM, Eigen, protobuf, spdlog, GoogleTest,
# Google Benchmark, CLI11, libsodium, the JDK for the lcm-spy jar, ...) is
# listed once, in packaging/build-depends, which docker/Dockerfile reads too.
mapfile -t APT_PACKAGES < <(grep -v '^#' packaging/build-depends | grep .)
APT_PACKAGES+=(
  ccache
  clang libclang-rt-14-dev                   # the sanitizer and libFuzzer build (make test-asan, make fuzz)
  libfcl-dev                                 # oracle tests only (tests/oracle), never in the service
  libbullet-dev libode-dev                   # peer runners of `make bench` only (bench/peers), never in the service
  valgrind                                   # instructions a step in `make bench` and bench/scripts/*_instructions.py
  python3-venv python3-dev                   # Python client
  chromium chromium-driver                   # the viewer's browser tests (headless, tests/python/test_viewer.py)
)
# npm installs the viewer's three.js; Debian's nodejs and npm unless a node is already there
command -v npm >/dev/null 2>&1 || APT_PACKAGES+=(nodejs npm)

if [ "$(id -u)" -eq 0 ]; then SUDO=""; else SUDO="sudo"; fi

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "deps: installing Debian packages: ${missing[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Large STATE messages (1,000 bodies is ~120 kB) are fragmented by LCM; the
# receiver needs a socket buffer larger than the kernel default to keep them.
# Raise the cap when we may; the README says how to do it by hand otherwise.
want=8388608
have=$(cat /proc/sys/net/core/rmem_max 2>/dev/null || echo 0)
if [ "$have" -lt "$want" ]; then
  $SUDO sysctl -q -w net.core.rmem_max=$want 2>/dev/null \
    || echo "deps: could not raise net.core.rmem_max to $want (see README, troubleshooting)"
fi

PY=/usr/bin/python3
[ -x "$PY" ] || PY=$(command -v python3)
if [ ! -x .venv/bin/python ]; then
  echo "deps: creating .venv"
  "$PY" -m venv .venv
fi
if ! .venv/bin/python -c "import lcm, numpy, matplotlib, tqdm, pytest, aiohttp, selenium, wheel, ray, gymnasium, pandas, mujoco, pybullet, pinocchio, pydrake" 2>/dev/null \
   || ! .venv/bin/pip show -q contactsim >/dev/null 2>&1 || [ ! -x .venv/bin/contactsim-viewer ]; then
  echo "deps: installing Python packages into .venv"
  .venv/bin/pip install -q --upgrade pip
  .venv/bin/pip install -q -r clients/python/requirements.txt
  .venv/bin/pip install -q -e clients/python
fi
# three.js, pinned by package-lock.json, served by the viewer itself (no CDN)
VENDOR=clients/python/contactsim/viewer/vendor
if [ ! -f "$VENDOR/node_modules/three/build/three.module.js" ]; then
  echo "deps: installing three.js for the viewer (npm ci)"
  (cd "$VENDOR" && npm ci --no-audit --no-fund --loglevel=error)
fi
touch .venv/.deps-stamp
echo "deps: ok"
