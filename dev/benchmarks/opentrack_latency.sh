#!/usr/bin/env bash
# Raw pose -> opentrack datagram latency through hkf-filter and hkf-opentrack,
# at 60 and 250 Hz, in a private network namespace (root; nothing leaves the machine).
# usage: opentrack_latency.sh BUILD_DIR [SECONDS]
set -euo pipefail
build=$(cd "$1" && pwd)
seconds=${2:-10}
here=$(cd "$(dirname "$0")" && pwd)
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$here/../../tools/lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"
log=$(mktemp)
"$build/tools/hkf-filter" --lcm-url "$url" 2>"$log" &
filter=$!
"$build/tools/hkf-opentrack" --lcm-url "$url" 2>>"$log" &
bridge=$!
trap 'kill $filter $bridge 2>/dev/null || true; rm -f "$log"' EXIT
sleep 0.5
echo "raw pose -> opentrack datagram through hkf-filter and hkf-opentrack (udpm + UDP on loopback, $(nproc) cores), $seconds s per rate:"
for rate in 60 250; do
  # each rate is a new publisher (its seq starts at 1): hkf-filter follows it once the last one
  # has been silent for FILTER_NODE_STREAM_TIMEOUT_US (1 s), so give it that
  sleep 1.2
  "$here/../../.venv/bin/python" "$here/opentrack_latency.py" --types "$build/lcmtypes/python" --lcm-url "$url" \
    --rate "$rate" --seconds "$seconds"
done
kill -INT $filter $bridge
wait $filter $bridge || true
cat "$log"
