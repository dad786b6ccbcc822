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
source "$(dirname "$0")/live_filter.sh"
# 2 MB of receive buffer (about 1.5 s of answers at 1 kHz): a stall of this process on a loaded machine (156 ms once,
# 2 cores, tests beside it) overflowed the default 208 kB and lost answers the node had published
url="$url&recv_buf_size=2097152"
start_live_filter "$build"
csv=()
if [ -n "$out" ]; then
  mkdir -p "$out"
  csv=(--csv "$out/soak.csv")
fi
status=0
"$build/dev/benchmarks/hkf-soak" --rate 1000 --seconds "$seconds" --interval "$interval" --watch-pid "$filter" \
  --lcm-url "$url" "${csv[@]}" || status=$?
kill -TERM $filter
wait $filter || { echo "soak: hkf-filter did not stop cleanly" >&2; status=1; }
cat "$filter_log"
if [ -n "$out" ]; then
  "$(dirname "$0")/../../.venv/bin/python" "$(dirname "$0")/../plots/plot_soak.py" "$out/soak.csv" "$out/soak.png"
fi
exit $status
