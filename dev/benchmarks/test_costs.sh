#!/usr/bin/env bash
# What each test costs: every test of a build run alone, one after another, its wall time and its CPU time
# (user + system of the test and every process it waited for), the costliest first, with the totals. The
# figures for choosing what to cut from ./run test; a test's CPU seconds are what it takes from the tests
# beside it, its wall seconds what it adds when it runs last.
#   dev/benchmarks/test_costs.sh [--top N] BUILD_DIR [ctest options, e.g. -LE 'input|long']
# --top: rows to print (default 25). Exit 1 if a test failed (its row says so).
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
top=25
while [ $# -gt 0 ]; do
  case $1 in
    --top) top=${2:?--top wants a number}; shift 2 ;;
    --help|-h) sed -n '2,7p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    --version) echo "test_costs.sh $(cat "$root/VERSION")"; exit 0 ;;
    *) break ;;
  esac
done
build=${1:?usage: test_costs.sh [--top N] BUILD_DIR [ctest options]}
shift
case $top in ''|*[!0-9]*) echo "test_costs.sh: --top wants a whole number, not '$top'" >&2; exit 2 ;; esac
[ -f "$build/CTestTestfile.cmake" ] || { echo "test_costs.sh: $build is not a build directory" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "test_costs.sh: GNU time is not installed (apt-get install time)" >&2; exit 2; }
build=$(cd "$build" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$build" && ctest -N "$@") | sed -n 's/^ *Test *#[0-9]*: //p' >"$work/names.txt"
count=$(wc -l <"$work/names.txt")
[ "$count" -gt 0 ] || { echo "test_costs.sh: no test selected" >&2; exit 2; }
echo "$count tests of $build, one at a time; CPU: $(sed -n 's/^model name\s*: //p' /proc/cpuinfo | head -1), $(nproc) cores"
done_count=0 failed=0
while read -r name; do
  done_count=$((done_count + 1))
  status=0
  (cd "$build" && /usr/bin/time -f "%e %U %S" -o "$work/time.txt" ctest -R "^${name//./\\.}\$" >"$work/out.txt" 2>&1) || status=$?
  read -r wall user system <"$work/time.txt"
  verdict=passed
  [ "$status" = 0 ] || { verdict=FAILED; failed=$((failed + 1)); }
  awk -v u="$user" -v s="$system" -v w="$wall" -v n="$name" -v v="$verdict" 'BEGIN { print u + s, w, n, v }' >>"$work/costs.txt"
  printf '\r  %d of %d (%s)            ' "$done_count" "$count" "$name" >&2
done <"$work/names.txt"
printf '\n' >&2
printf '| test | CPU s | wall s | |\n| --- | ---: | ---: | --- |\n'
sort -rn "$work/costs.txt" | head -n "$top" | awk '{ printf "| %s | %.1f | %.1f | %s |\n", $3, $1, $2, $4 }'
awk '{ cpu += $1; wall += $2 } END { printf "all %d tests: %.0f CPU s, %.0f wall s one at a time\n", NR, cpu, wall }' "$work/costs.txt"
[ "$failed" = 0 ]
