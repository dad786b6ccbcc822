#!/usr/bin/env bash
# Raw -> filtered latency over LCM through hkf-filter, at 30 Hz and 1 kHz, in a
# private network namespace (root; no traffic leaves the machine).
# usage: lcm_latency.sh BUILD_DIR [SECONDS]
set -euo pipefail
build=$(cd "$1" && pwd)
seconds=${2:-10}
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$(dirname "$0")/../lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
log=$(mktemp)
"$build/tools/hkf-filter" --lcm-url "$url" 2>"$log" &
filter=$!
trap 'kill $filter 2>/dev/null || true; rm -f "$log"' EXIT
sleep 0.5
echo "raw -> filtered latency through hkf-filter over LCM (udpm on loopback, $(nproc) cores), $seconds s per rate:"
for rate in 30 1000; do
  "$build/tools/benchmarks/hkf-bench-latency" --rate "$rate" --seconds "$seconds" --lcm-url "$url"
done
kill -INT $filter
wait $filter || true
cat "$log"
