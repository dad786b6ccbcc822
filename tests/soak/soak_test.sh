#!/usr/bin/env bash
# The short soak: 20 s of the simulated drive at 1 kHz through a live
# hkf-filter (dev/benchmarks/soak.sh; the benchmark job runs an hour).
# Every measured pose answered, none non-finite, the node's memory flat after
# its first 10 s, and the node stops cleanly with its summary.
# usage: soak_test.sh BUILD_DIR SOURCE_DIR   (exit 77: no network namespace here)
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

status=0
"$source/dev/benchmarks/soak.sh" "$build" 20 5 >"$work/soak.txt" 2>&1 || status=$?
cat "$work/soak.txt"
[ "$status" = 77 ] && exit 77
[ "$status" = 0 ] || fail "soak.sh exit $status"
summary=$(grep "^hkf-soak: 20 s" "$work/soak.txt") || fail "no summary"
echo "$summary" | grep -q "20000 raw poses sent" || fail "not 20000 raw poses sent"
echo "$summary" | grep -q " 0 with a face dropped, 0 unexpected" || fail "drops or unexpected answers"
echo "$summary" | grep -q " 0 non-finite" || fail "non-finite poses"
grep -q "hkf-filter: 20000 measurements" "$work/soak.txt" || fail "the node's summary is missing or short"
# memory: the node's RSS at 10 s and at the end (KiB)
at10=$(awk '$1 == 10 && $9 == "KiB" {print $8}' "$work/soak.txt")
last=$(awk '$1 == 20 && $9 == "KiB" {print $8}' "$work/soak.txt")
[ -n "$at10" ] && [ -n "$last" ] || fail "no RSS figures"
growth=$((last - at10))
echo "soak_test: node RSS ${at10} KiB at 10 s, ${last} KiB at 20 s (growth ${growth} KiB)"
[ "$growth" -le 64 ] || fail "the node's memory grew by ${growth} KiB in 10 s"
echo "soak_test: all checks passed"
