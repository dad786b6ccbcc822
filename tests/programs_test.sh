#!/usr/bin/env bash
# Every program answers --help and --version (exit 0), the version being the
# one in the VERSION file at the root.
# usage: programs_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
version=$(head -n 1 "$source/VERSION")
fail() { echo "FAIL: $*" >&2; exit 1; }
programs=(tools/hkf-filter tools/hkf-opentrack tools/hkf-cmd tools/hkf-demo tools/hkf-simlog tools/hkf-spy tools/hkf-track
          estimator/hkf-estimator estimator/hkf-annotate)
for p in dev/benchmarks/hkf-soak dev/benchmarks/hkf-bench-latency dev/benchmarks/hkf-bench-update \
         dev/benchmarks/hkf-bench-estimator; do
  [ -x "$build/$p" ] && programs+=("$p")  # the benchmarks, where built
done
check() { # check NAME COMMAND...: --version prints "NAME VERSION" and --help a usage, both exit 0
  local name=$1
  shift
  out=$("$@" --version) || fail "$name --version: exit $?"
  [[ "$out" == "$name $version"* ]] || fail "$name --version printed '$out', not '$name $version'"
  help=$("$@" --help) || fail "$name --help: exit $?"
  # not `--help | grep -q` under pipefail: grep leaves at the first match and the program's later
  # lines meet a closed pipe (SIGPIPE, a failure that depends on timing)
  grep -qi "usage" <<<"$help" || fail "$name --help printed no usage"
  echo "$out"
}
for p in "${programs[@]}"; do
  check "$(basename "$p")" "$build/$p"
done
echo "programs_test: ${#programs[@]} programs answer --help and --version $version"
