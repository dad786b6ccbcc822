#!/usr/bin/env bash
# The house's bounds on functions (issue "The house"): no function of the shipped programs longer than 60
# lines or with more than 6 parameters, none of libhkf longer than 40 (its inline helpers included).
# lizard (PyPI, in .venv) measures each function's length from its first line to its closing brace.
#   function_sizes_test.sh SOURCE LIZARD
set -euo pipefail
source=$1 lizard=$2
cd "$source"
status=0
check() { # check WHAT LENGTH PARAMETERS DIR...
  local what=$1 length=$2 parameters=$3
  shift 3
  local found
  # -C: no complexity bound here; -w: only the functions beyond a bound, one line each
  found=$("$lizard" -L "$length" -a "$parameters" -C 1000 -w "$@" || true)
  if [ -n "$found" ]; then
    echo "function_sizes: $what beyond $length lines or $parameters parameters:" >&2
    echo "$found" >&2
    status=1
  else
    echo "function_sizes: $what: every function within $length lines and $parameters parameters"
  fi
}
check "the shipped programs" 60 6 filter_node tools estimator messages program_helpers sim
check "libhkf" 40 6 libhkf
exit $status
