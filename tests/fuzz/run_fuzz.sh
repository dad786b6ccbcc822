#!/usr/bin/env bash
# Runs one fuzz target for SECONDS from seeds made from real data, and prints
# what it did: executions, coverage, and the target's own count of filter
# steps or messages. A finding (crash, sanitizer report, failed check) exits
# non-zero and leaves the input in out/fuzz/TARGET/.
# usage: run_fuzz.sh FUZZ_BUILD_DIR SOURCE_DIR PYTHON TARGET SECONDS
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) python=$3 target=$4 seconds=$5
out="$source/out/fuzz/$target"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$out" "$work/corpus"
"$build/tools/hkf-simlog" --out "$work/drive.lcmlog" --seconds 10 --seed 7 >/dev/null 2>&1
"$python" "$source/tests/fuzz/make_seeds.py" "$work/drive.lcmlog" "$source/filter_node/hkf-filter.conf" \
  "$work/seeds" >/dev/null
[ -d "$work/seeds/$target" ] && cp "$work/seeds/$target"/* "$work/corpus/"
options=()
if [ "$target" = fuzz_onnx_model ]; then  # the shipped models (all but the plain WHENet graph) and small graphs
  for model in "$source/.models"/*.onnx; do [ "$(basename "$model")" = whenet.onnx ] || cp "$model" "$work/corpus/"; done
  "$python" "$source/tests/fuzz/make_onnx_seeds.py" "$work/corpus" >/dev/null
  options=(-max_len=2500000 -timeout=30)  # the face models whole; WHENet's 17 MB taken by their first 2.5 MB
fi
[ -d "$out/corpus" ] && cp "$out/corpus"/* "$work/corpus/" 2>/dev/null || true   # what earlier runs found
status=0
(cd "$work" && "$build/tests/fuzz/$target" corpus "${options[@]}" -max_total_time="$seconds" -print_final_stats=1 \
  -artifact_prefix="$out/" -rss_limit_mb=2048) >"$work/log.txt" 2>&1 || status=$?
mkdir -p "$out/corpus" && cp "$work/corpus"/* "$out/corpus/" 2>/dev/null || true
executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log.txt")
coverage=$(grep -o 'cov: [0-9]*' "$work/log.txt" | tail -1 | cut -d' ' -f2 || true)
counted=$(grep -h "^$target: .* in total" "$work/log.txt" | tail -1 | sed "s/^$target: //" || true)
echo "$target: ${seconds} s, ${executions:-?} executions, coverage ${coverage:-?} edges${counted:+, $counted}"
if [ "$status" != 0 ]; then
  grep -E "^$target:|ERROR|runtime error|SUMMARY" "$work/log.txt" | head -20 >&2
  echo "$target: FINDING (exit $status); the input is in $out/" >&2
  exit 1
fi
