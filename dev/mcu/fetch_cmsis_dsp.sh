#!/usr/bin/env bash
# Fetches Arm's CMSIS-DSP library (Apache-2.0) from PyPI: the cmsisdsp Python
# package's source distribution carries the C sources (Include/, Source/).
# Unpacked into DIR (default .third_party/cmsis-dsp); nothing is committed.
# Used only by the Cortex-M4F comparison test (tests/mcu/cmsis_dsp_filter.c).
# Idempotent. usage: dev/mcu/fetch_cmsis_dsp.sh [DIR]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=${1:-$root/.third_party/cmsis-dsp}
version=1.10.3
if [ -s "$dir/Include/arm_math.h" ] && [ "$(cat "$dir/VERSION" 2>/dev/null)" = "$version" ]; then
  exit 0
fi
python=$root/.venv/bin/python
[ -x "$python" ] || { echo "fetch_cmsis_dsp: $python missing: run scripts/setup.sh" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "fetch_cmsis_dsp: pip download cmsisdsp==$version (source distribution)" >&2
"$python" -m pip download --no-deps --no-binary cmsisdsp -q -d "$tmp" "cmsisdsp==$version" >"$tmp/pip.log" 2>&1 \
  || { cat "$tmp/pip.log" >&2; echo "fetch_cmsis_dsp: could not download cmsisdsp==$version from PyPI" >&2; exit 1; }
archive=$tmp/cmsisdsp-$version.tar.gz
tar -xzf "$archive" -C "$tmp"
rm -rf "$dir"
mkdir -p "$(dirname "$dir")"
mv "$tmp/cmsisdsp-$version" "$dir"
echo "$version" >"$dir/VERSION"
