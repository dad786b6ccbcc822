#!/usr/bin/env bash
# hkf-filter's settings files: with no --config, the system's file (here $HKF_SYSTEM_CONFIG_DIR, in
# the package /etc/hkf) and then the user's (~/.config/hkf, or $XDG_CONFIG_HOME/hkf) are read, each
# over the one before, and --set over both; --print-config says where each value came from; --config
# replaces the search; a bad found file is a clear error (exit 2); --help answers whatever they hold.
# usage: config_files_test.sh BUILD_DIR
set -euo pipefail
filter=$1/tools/hkf-filter
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
mkdir -p "$work/etc" "$work/home/.config/hkf" "$work/xdg/hkf"
printf 'lc_theta = 3\ngate_sigma = 2\n' >"$work/etc/hkf-filter.conf"
printf '# the user'"'"'s\ngate_sigma = 4\n' >"$work/home/.config/hkf/hkf-filter.conf"
printf 'coast_time = 0.4\n' >"$work/xdg/hkf/hkf-filter.conf"
export HKF_SYSTEM_CONFIG_DIR=$work/etc HOME=$work/home
unset XDG_CONFIG_HOME

# value_of KEY FILE: "VALUE # WHERE" of KEY's line
value_of() { sed -n "s/^$1 *= *\([^ ]*\) *# \([^;]*\);.*/\1 # \2/p" "$2"; }
expect() { # expect KEY "VALUE # WHERE" FILE
  [ "$(value_of "$1" "$3")" = "$2" ] || fail "$1: '$(value_of "$1" "$3")', expected '$2' ($(grep "^$1 " "$3"))"
}

"$filter" --set coast_time=0.5 --print-config >"$work/both.txt"
expect lc_theta "3 # $work/etc/hkf-filter.conf:1" "$work/both.txt"
expect gate_sigma "4 # $work/home/.config/hkf/hkf-filter.conf:2" "$work/both.txt"  # the user's over the system's
expect coast_time "0.5 # --set" "$work/both.txt"
expect max_dt "1 # default" "$work/both.txt"
grep -q "^noise.yaw .*# built in;" "$work/both.txt" || fail "a built-in model's curve is not marked 'built in'"

XDG_CONFIG_HOME=$work/xdg "$filter" --print-config >"$work/xdg.txt"  # XDG_CONFIG_HOME replaces ~/.config
expect coast_time "0.4 # $work/xdg/hkf/hkf-filter.conf:1" "$work/xdg.txt"
expect gate_sigma "2 # $work/etc/hkf-filter.conf:2" "$work/xdg.txt"

printf 'lc_xi = 0.5\n' >"$work/mine.conf"
"$filter" --config "$work/mine.conf" --print-config >"$work/explicit.txt"  # --config: no search
expect lc_xi "0.5 # $work/mine.conf:1" "$work/explicit.txt"
expect lc_theta "2 # default" "$work/explicit.txt"

printf 'lc_theta = banana\n' >"$work/home/.config/hkf/hkf-filter.conf"
status=0
"$filter" --print-config >/dev/null 2>"$work/bad.txt" || status=$?
[ "$status" = 2 ] || fail "a bad user file: exit $status, not 2"
grep -q "$work/home/.config/hkf/hkf-filter.conf:1" "$work/bad.txt" || fail "a bad user file is not named: $(cat "$work/bad.txt")"
"$filter" --help >/dev/null || fail "--help with a bad user file"

# round 4: a dangling or looping link found by the search is a bad file, not none
for target in nowhere hkf-filter.conf; do
  rm -f "$work/home/.config/hkf/hkf-filter.conf"
  ln -s "$target" "$work/home/.config/hkf/hkf-filter.conf"
  status=0
  "$filter" --print-config >/dev/null 2>"$work/bad.txt" || status=$?
  [ "$status" = 2 ] || fail "a link to $target as the user's file: exit $status, not 2"
  grep -q "cannot read '$work/home/.config/hkf/hkf-filter.conf'" "$work/bad.txt" || fail "the link is not named: $(cat "$work/bad.txt")"
done
rm "$work/home/.config/hkf/hkf-filter.conf"
printf 'lc_theta = 6\n' >"$work/home/.config/hkf/hkf-filter.conf"
# an option's value that reads like --config is no --config: the search stays on
"$filter" --csv --config --print-config >"$work/value.txt"
expect lc_theta "6 # $work/home/.config/hkf/hkf-filter.conf:1" "$work/value.txt"
[ ! -e ./--config ] || fail "--print-config wrote a CSV"

HKF_SYSTEM_CONFIG_DIR=$work/none HOME=$work/none "$filter" --print-config >"$work/none.txt"
grep -q "$work" "$work/none.txt" && fail "a file was read where none exists"
echo "config_files_test: system, user, XDG, --set and --config origins as expected; a bad file is exit 2"
