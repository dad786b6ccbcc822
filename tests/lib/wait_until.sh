# wait_until.sh - sourced by the live tests: wait for a state, with a deadline, instead of sleeping for a
# time that assumes the machine's speed.
# wait_until SECONDS WHAT COMMAND...: runs COMMAND every 0.1 s until it succeeds; returns 1 (saying WHAT it
# waited for) when SECONDS pass first.
wait_until() {
  local limit=$1 what=$2 start
  shift 2
  start=$(date +%s%N)
  until "$@" >/dev/null 2>&1; do
    if [ $(($(date +%s%N) - start)) -gt $((limit * 1000000000)) ]; then
      echo "wait_until: no $what after $limit s" >&2
      return 1
    fi
    sleep 0.1
  done
}
# has_line FILE PATTERN: FILE holds a line matching PATTERN (grep -E)
has_line() { grep -qE "$2" "$1" 2>/dev/null; }
