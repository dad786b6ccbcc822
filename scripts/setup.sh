#!/usr/bin/env bash
# Installs every dependency of hkf on Debian 12, idempotently: apt packages
# that are missing (apt-get update only when something is). Safe to re-run.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config  # the build
  libcmocka-dev                                 # C unit tests
  libeigen3-dev                                 # the 6x6 reference filter (tests, benchmark)
  libopencv-dev                                 # cv::KalmanFilter (benchmark); the estimator
  valgrind                                      # instruction counts (benchmark)
  liblcm-dev liblcm-bin liblcm-java             # LCM: library, lcm-gen, logger/logplayer, lcm.jar
  libjchart2d-java                              # charts in lcm-spy (hkf-spy)
  default-jdk-headless                          # javac for the Java message types
  iproute2 util-linux                           # private network namespaces for the LCM tests
  xvfb unzip                                    # hkf-spy test: lcm-spy on a virtual display
  python3                                       # benchmark report
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=()
  [[ $(id -u) -eq 0 ]] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
echo "setup: all dependencies present"
