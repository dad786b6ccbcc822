#!/usr/bin/env bash
# The tests labelled timing (live processes held to a user's deadlines: silence detection, a display, a replay in
# real time), run again and again with stress-ng's CPU load beside them, as on a busy or slower machine.
#   dev/benchmarks/timing_under_load.sh [--runs N] [--load WORKERS] BUILD_DIR
# --runs: how many times (default 10); --load: stress-ng --cpu workers, on every core (default 2; 0: none).
# Prints each run's passes and time, then each test's passes; exit 1 if any run failed a test.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
runs=10 load=2
while [ $# -gt 0 ]; do
  case $1 in
    --runs) runs=${2:?--runs wants a number}; shift 2 ;;
    --load) load=${2:?--load wants a number of workers}; shift 2 ;;
    --help|-h) sed -n '2,6p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --version) echo "timing_under_load.sh $(cat "$root/VERSION")"; exit 0 ;;
    *) break ;;
  esac
done
build=${1:?usage: timing_under_load.sh [--runs N] [--load WORKERS] BUILD_DIR}
for n in "$runs" "$load"; do
  case $n in ''|*[!0-9]*) echo "timing_under_load.sh: --runs and --load want whole numbers, not '$n'" >&2; exit 2 ;; esac
done
[ -f "$build/CTestTestfile.cmake" ] || { echo "timing_under_load.sh: $build is not a build directory" >&2; exit 2; }
build=$(cd "$build" && pwd)
if [ "$load" -gt 0 ] && ! command -v stress-ng >/dev/null; then
  echo "timing_under_load.sh: stress-ng is not installed (apt-get install stress-ng)" >&2
  exit 2
fi
work=$(mktemp -d)
stress=""
cleanup() { [ -z "$stress" ] || { kill "$stress" 2>/dev/null; wait "$stress" 2>/dev/null || true; }; rm -rf "$work"; }
trap cleanup EXIT
if [ "$load" -gt 0 ]; then
  stress-ng --cpu "$load" --quiet --timeout 0 &
  stress=$!
fi
echo "timing-labelled tests, $runs runs, $load stress-ng CPU worker(s) beside them; CPU: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
failed_runs=0
for run in $(seq 1 "$runs"); do
  start=$SECONDS status=0
  (cd "$build" && ctest -L timing -j 2 --output-on-failure) >"$work/run$run.txt" 2>&1 || status=$?
  summary=$(grep -E 'tests passed' "$work/run$run.txt" || echo "no summary")
  echo "run $run: $summary ($((SECONDS - start)) s)"
  if [ "$status" != 0 ]; then
    failed_runs=$((failed_runs + 1))
    grep -E '\*\*\*|Failed|FAIL' "$work/run$run.txt" | head -n 20 | sed 's/^/  /'
  fi
  grep -E 'Test +#[0-9]+: ' "$work/run$run.txt" | awk '{ print $4, ($6 == "Passed") }' >>"$work/passes.txt"
done
echo "passes per test:"
awk '{ runs[$1]++; passed[$1] += $2 } END { for (t in runs) printf "  %-28s %d of %d\n", t, passed[t], runs[t] }' \
  "$work/passes.txt" | sort
echo "runs with every test passed: $((runs - failed_runs)) of $runs"
[ "$failed_runs" = 0 ]
