#!/usr/bin/env bash
# The soak: hkf-soak replays the simulated drive at 1 kHz through a live
# hkf-filter for SECONDS, in a private network namespace (root; no traffic
# leaves the machine), printing a line every INTERVAL s (memory, latency,
# drops, non-finite), then the node's own summary and, with OUT_DIR, a CSV
# and a PNG of memory and latency over time.
# usage: soak.sh BUILD_DIR SECONDS [INTERVAL] [OUT_DIR]
set -euo pipefail
build=$(cd "$1" && pwd)
seconds=$2 interval=${3:-60} out=${4:-}
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$(dirname "$0")/../lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
log=$(mktemp)
"$build/tools/hkf-filter" --lcm-url "$url" 2>"$log" &
filter=$!
trap 'kill $filter 2>/dev/null || true; rm -f "$log"' EXIT
sleep 0.5
csv=()
if [ -n "$out" ]; then
  mkdir -p "$out"
  csv=(--csv "$out/soak.csv")
fi
status=0
"$build/tools/benchmarks/hkf-soak" --rate 1000 --seconds "$seconds" --interval "$interval" --watch-pid "$filter" \
  --lcm-url "$url" "${csv[@]}" || status=$?
kill -TERM $filter
wait $filter || { echo "soak: hkf-filter did not stop cleanly" >&2; status=1; }
cat "$log"
if [ -n "$out" ]; then
  "$(dirname "$0")/../../.venv/bin/python" "$(dirname "$0")/../plots/plot_soak.py" "$out/soak.csv" "$out/soak.png"
fi
exit $status
