#!/usr/bin/env bash
# Runs a command as a slower machine would (checks proven on a fast AVX-512 machine failed on a 2-core
# AVX2 one): on one core (taskset), with stress-ng's CPU load beside it on that core, the estimator's layers and
# OpenCV's own held to a lower instruction-set level (HKF_SIMD, OPENCV_CPU_DISABLE: dev/benchmarks/
# opencv_cpu_levels.txt), and Mesa's software renderer as it is (LIBGL_ALWAYS_SOFTWARE=1).
#   dev/slower_machine.sh [--level avx2|avx|sse2] [--load WORKERS] [--core N] [--] COMMAND [ARGS...]
# --level: the level played (default avx2); --load: stress-ng CPU workers on the core beside the command
# (default 1; 0: none; stress-ng is installed with apt when missing and root); --core: the core (default 0),
# or a list for taskset (0,1: a 2-core machine at the level).
# Examples: dev/slower_machine.sh ./run flightgear; dev/slower_machine.sh --level sse2 ./run e2e;
#           dev/slower_machine.sh --core 0,1 --load 0 ./run test
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
level=avx2 load=1 core=0
while [ $# -gt 0 ]; do
  case $1 in
    --level) level=${2:?--level wants avx2, avx or sse2}; shift 2 ;;
    --load) load=${2:?--load wants a number of workers}; shift 2 ;;
    --core) core=${2:?--core wants a core number or a list}; shift 2 ;;
    --help|-h) sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --version) echo "slower_machine.sh $(cat "$root/VERSION")"; exit 0 ;;
    --) shift; break ;;
    *) break ;;
  esac
done
[ $# -gt 0 ] || { echo "slower_machine.sh: no command given (see --help)" >&2; exit 2; }
disable=$(awk -v level="$level" '$1 == level { print $2; found = 1 } END { exit !found }' \
  "$root/dev/benchmarks/opencv_cpu_levels.txt") || { echo "slower_machine.sh: --level is avx512, avx2, avx or sse2, not '$level'" >&2; exit 2; }
case $load in ''|*[!0-9]*) echo "slower_machine.sh: --load wants a number of workers, not '$load'" >&2; exit 2 ;; esac
case $core in ''|*[!0-9,-]*) echo "slower_machine.sh: --core wants a core number or a list (0,1), not '$core'" >&2; exit 2 ;; esac
stress=""
if [ "$load" -gt 0 ]; then
  if ! command -v stress-ng >/dev/null && [ "$(id -u)" = 0 ]; then
    apt-get install -y -qq stress-ng >/dev/null 2>&1 || true
  fi
  if command -v stress-ng >/dev/null; then
    taskset -c "$core" stress-ng --cpu "$load" --quiet --timeout 0 &
    stress=$!
    trap 'kill "$stress" 2>/dev/null; wait "$stress" 2>/dev/null || true' EXIT
  else
    echo "slower_machine.sh: stress-ng is not installed (apt-get install stress-ng): no load beside the command" >&2
  fi
fi
echo "slower_machine.sh: on core $core, level $level, $load stress-ng worker(s) beside it: $*" >&2
export HKF_SIMD=$level HKF_PLAY_CPU_LEVEL=$level OPENCV_CPU_DISABLE=$disable LIBGL_ALWAYS_SOFTWARE=1
status=0
taskset -c "$core" "$@" || status=$?
exit "$status"
