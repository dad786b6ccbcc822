#!/usr/bin/env bash
# Installs every dependency of hkf on Debian 12, idempotently: apt packages
# that are missing (apt-get update only when something is). Safe to re-run.
# usage: setup.sh [--release] [--system | --tools]
#   --release: also what ./run release needs
#   --system:  only the apt packages (what the build needs); --tools: only the rest (the Python tools, the
#              models, CMSIS-DSP: what the tests need), which ./run test runs beside the build
set -euo pipefail
release=0 system=1 tools=1
for option in "$@"; do
  case "$option" in
    --release) release=1 ;;
    --system) tools=0 ;;
    --tools) system=0 ;;
    *) echo "setup.sh: unknown option '$option' (usage: setup.sh [--release] [--system | --tools])" >&2; exit 2 ;;
  esac
done

packages=(
  build-essential cmake ninja-build pkg-config  # the build
  libcmocka-dev                                 # C unit tests
  libmicrohttpd-dev                             # hkf-view: the live view's HTTP server
  libeigen3-dev                                 # the 6x6 reference filter (tests, benchmark)
  libopencv-dev                                 # cv::KalmanFilter (benchmark); the estimator
  valgrind                                      # instruction counts (benchmark)
  liblcm-dev liblcm-bin liblcm-java             # LCM: library, lcm-gen, logger/logplayer, lcm.jar
  libjchart2d-java                              # charts in lcm-spy (hkf-spy)
  default-jdk-headless                          # javac for the Java message types
  iproute2 util-linux                           # private network namespaces for the LCM tests
  xvfb unzip file                               # hkf-spy test: lcm-spy on a virtual display; file(1)
  chromium                                      # the live view's test in a real browser (headless)
  python3 python3-venv python3-pip              # Python tools (.venv, from tools/requirements.txt)
  clang libclang-rt-14-dev                      # the fuzz targets (libFuzzer, tests/fuzz)
  gcc-arm-none-eabi libnewlib-arm-none-eabi     # libhkf for Cortex-M (cmake/arm-none-eabi.cmake)
  qemu-system-arm                               # ... and its target tests in an emulator (tests/mcu)
  g++-aarch64-linux-gnu qemu-user               # the estimator's layers built for aarch64 (NEON), run under qemu
  help2man                                      # the programs' man pages, from their --help
)
if ((release)); then
  packages+=(lintian mmdebstrap)                # ./run release: Debian's checks, a clean Debian 12 root
fi

if ((system)); then
  missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  command -v npm >/dev/null || missing+=(npm)   # npm pack: the canonical face (node's own npm counts)
  if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}"
    sudo_cmd=()
    [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
fi
((tools)) || exit 0
# Python tools in .venv, pinned by tools/requirements.txt.
root=$(cd "$(dirname "$0")/.." && pwd)
if [ ! -x "$root/.venv/bin/python" ]; then
  echo "setup: creating .venv"
  python3 -m venv "$root/.venv"
fi
stamp=$root/.venv/.requirements
if ! cmp -s "$root/tools/requirements.txt" "$stamp" 2>/dev/null; then
  echo "setup: installing tools/requirements.txt into .venv"
  "$root/.venv/bin/pip" install -q --disable-pip-version-check -r "$root/tools/requirements.txt"
  cp "$root/tools/requirements.txt" "$stamp"
fi

# Third-party models, converted by our scripts into .models (shared by every build).
"$root/dev/models/fetch_models.sh" "$root/.models"
# CMSIS-DSP's sources from PyPI, for the Cortex-M4F cost comparison (tests/mcu).
"$root/dev/mcu/fetch_cmsis_dsp.sh" "$root/.third_party/cmsis-dsp"
echo "setup: all dependencies present"
