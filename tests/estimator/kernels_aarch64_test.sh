#!/usr/bin/env bash
# The layers' loops built for aarch64 (NEON: the baseline level's file, the same vector code) with Debian's
# cross compiler and run under qemu-user against the double loops (test_layer_kernels.cpp); the object
# must hold NEON's fused multiply-adds on vectors. Exit 77 (skipped) without the cross tools.
# usage: kernels_aarch64_test.sh SOURCE_DIR
set -euo pipefail
source=$(cd "$1" && pwd)
if ! command -v aarch64-linux-gnu-g++ >/dev/null || ! command -v qemu-aarch64 >/dev/null; then
  echo "kernels_aarch64_test: no aarch64-linux-gnu-g++ or qemu-aarch64 (g++-aarch64-linux-gnu, qemu-user): skipped"
  exit 77
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
models=$source/estimator/src/models
flags=(-std=c++17 -fstrict-aliasing -ffp-contract=fast -Wall -Wextra -Werror -I"$models")
aarch64-linux-gnu-g++ -O3 "${flags[@]}" -c "$models/kernels/layer_kernels_baseline.cpp" -o "$work/kernels.o"
# the test's reference loops at -O1: GCC 12's aarch64 vectoriser fails (an internal error) on their reductions
aarch64-linux-gnu-g++ -O1 "${flags[@]}" -static "$source/tests/estimator/test_layer_kernels.cpp" "$work/kernels.o" \
  -o "$work/test_layer_kernels"
fused=$(aarch64-linux-gnu-objdump -d "$work/kernels.o" | grep -cE 'fmla[[:space:]]+v[0-9]+\.4s' || true)
echo "kernels_aarch64_test: $fused NEON fused multiply-adds (fmla vN.4s) in the baseline level's loops"
[ "$fused" -gt 10 ] || { echo "FAIL: the aarch64 loops are not vectorised" >&2; exit 1; }
qemu-aarch64 "$work/test_layer_kernels"
