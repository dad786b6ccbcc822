#!/usr/bin/env bash
# The full mutation run's selection can be built: every mutant's test expression is one that
# ctest accepts and that selects a test, and the baseline selects exactly their union. Checked
# on the real list (cheap: ctest -N, nothing planted or run), then on two broken copies of its
# first mutant, which the check must refuse.
#   selection_test.sh BUILD SOURCE PYTHON
set -euo pipefail
build=$1 source=$2 python=$3
runner=$source/tests/mutation/run_mutants.py
"$python" "$runner" --check-selection "$build"

scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
first_mutant() { # first_mutant TESTS: the list's first mutant with its test expression replaced
  awk -v tests="$1" '
    /^@ / && !seen { n = split($0, f, / \| /); print f[1] " | " tests " | " f[3]; seen = 1; inside = 1; next }
    inside && /^[-+]( |$)/ { print; next }
    inside { exit }' "$source/tests/mutation/mutants.txt"
}
first_mutant '^((((((((((((hkf))))))))))))\.filter\.' >"$scratch/groups.txt"
first_mutant '^hkf\.no_such_test$' >"$scratch/none.txt"
for list in groups none; do
  if "$python" "$runner" --list "$scratch/$list.txt" --check-selection "$build" 2>"$scratch/err"; then
    echo "selection_test: the check accepted the broken list '$list'" >&2
    exit 1
  fi
  grep -q "run_mutants: " "$scratch/err" || { echo "selection_test: no reason given for '$list'" >&2; exit 1; }
  echo "selection_test: the broken list '$list' refused: $(tail -1 "$scratch/err")"
done

# --only takes numbers and ranges ("--only 242-255", as a closing note gave it, was refused before), and refuses
# what is neither with a clear error
PYTHONPATH=$source/tests/mutation "$python" - <<'PY'
import argparse, run_mutants
assert run_mutants.mutant_numbers("14") == {14}
assert run_mutants.mutant_numbers("3,7,242-245") == {3, 7, 242, 243, 244, 245}
assert run_mutants.mutant_numbers(" 5 - 6 ") == {5, 6}
for bad in ("", "a", "5-", "-5", "9-3", "1-2-3", "0"):
    try:
        run_mutants.mutant_numbers(bad)
    except argparse.ArgumentTypeError:
        continue
    raise SystemExit(f"selection_test: --only accepted {bad!r}")
print("selection_test: --only reads numbers and ranges, refuses the rest")
PY
if "$python" "$runner" --only 5-x --check 2>"$scratch/err"; then
  echo "selection_test: --only 5-x accepted" >&2
  exit 1
fi
grep -q "is not a mutant number" "$scratch/err" || { echo "selection_test: --only 5-x refused without a reason" >&2; exit 1; }
