#!/usr/bin/env bash
# dev/slower_machine.sh plays a slower machine: the command on one core, the estimator's layers at the level
# asked for (it says so), OpenCV held to it; a bad level refused; the command's own exit status kept.
# usage: slower_machine_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
slower=$source/dev/slower_machine.sh
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$("$slower" --load 0 -- nproc 2>/dev/null)" = 1 ] || fail "not on one core"
out=$("$slower" --load 0 --level sse2 -- "$build/estimator/hkf-estimator" --source "$source/../shared/data/videos/d3.mp4" \
  --max-frames 5 --second-model none --lcm-url memq:// 2>&1)
grep -q "own layers at sse2" <<<"$out" || { echo "$out" >&2; fail "the estimator's layers not at sse2"; }
status=0
"$slower" --load 0 --level avx3 -- true 2>/dev/null || status=$?
[ "$status" = 2 ] || fail "a bad level: exit $status"
status=0
"$slower" --load 0 -- sh -c 'exit 7' 2>/dev/null || status=$?
[ "$status" = 7 ] || fail "the command's exit status lost: $status"
echo "slower_machine_test: one core, the level played, a bad level refused, the exit status kept"
