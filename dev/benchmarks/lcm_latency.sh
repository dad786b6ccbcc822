#!/usr/bin/env bash
# Raw -> filtered latency over LCM through hkf-filter, at 30 Hz and 1 kHz, in a
# private network namespace (root; no traffic leaves the machine).
# usage: lcm_latency.sh BUILD_DIR [SECONDS]
set -euo pipefail
build=$(cd "$1" && pwd)
seconds=${2:-10}
source "$(dirname "$0")/live_filter.sh"
start_live_filter "$build"
echo "raw -> filtered latency through hkf-filter over LCM (udpm on loopback, $(nproc) cores), $seconds s per rate:"
for rate in 30 1000; do
  "$build/dev/benchmarks/hkf-bench-latency" --rate "$rate" --seconds "$seconds" --lcm-url "$url"
  sleep 1.2  # each run is a new publisher (its seq starts at 0): hkf-filter follows it after 1 s of silence
done
kill -INT $filter
wait $filter || true
cat "$filter_log"
