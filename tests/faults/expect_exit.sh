# expect_exit.sh - sourced by the fault catalogue's round tests (faults_round5_test.sh, faults_round6_test.sh):
# a command's exit status and what it said, checked. Needs $work (a scratch folder) set before it is sourced.
fail() { echo "FAIL: $*" >&2; exit 1; }
expect_exit() { # expect_exit CODE LABEL COMMAND...: wants exit CODE (60 s at most); the output in $work/out.txt
  local want=$1 label=$2 status=0
  shift 2
  timeout 60 "$@" >"$work/out.txt" 2>&1 || status=$?
  [ "$status" = "$want" ] || { cat "$work/out.txt" >&2; fail "$label: exit $status (expected $want)"; }
  echo "$label: exit $status; $(grep -v "measurements (\|own layers at" "$work/out.txt" | head -n 1)"
}
said() { grep -q -- "$1" "$work/out.txt" || { cat "$work/out.txt" >&2; fail "expected to be told '$1'"; }; }
