# live_filter.sh - sourced by the live benchmarks (lcm_latency.sh, soak.sh):
# re-runs the calling script in a private network namespace (tools/lcm-netns;
# root, no traffic leaves the machine), then `start_live_filter BUILD_DIR
# [hkf-filter options]` starts hkf-filter there on $url, with its pid in
# $filter and its stderr in $filter_log (both cleaned up on exit).
if [ "${HKF_IN_NETNS:-}" != 1 ]; then
  HKF_IN_NETNS=1 exec "$(dirname "${BASH_SOURCE[0]}")/../../tools/lcm-netns" "$0" "$@"
fi
url="udpm://239.255.76.67:7667?ttl=0"

start_live_filter() {
  local build=$1
  shift
  filter_log=$(mktemp)
  "$build/tools/hkf-filter" --lcm-url "$url" "$@" 2>"$filter_log" &
  filter=$!
  trap 'kill $filter 2>/dev/null || true; rm -f "$filter_log"' EXIT
  sleep 0.5
}
