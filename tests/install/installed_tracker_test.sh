#!/usr/bin/env bash
# The whole tracker installed, then moved, or packaged: `cmake --install BUILD --prefix P`
# then P moved elsewhere (MODE prefix), or `cpack -G DEB` unpacked into a temporary root
# (MODE deb). From another folder, the installed hkf-estimator (models and descriptions
# found from its own place) runs on a shared clip into an LCM log, the installed hkf-filter
# filters it with the installed config, the installed Python types read the poses, the jar
# for lcm-spy is there, and every installed program answers --version.
# usage: installed_tracker_test.sh BUILD_DIR SOURCE_DIR prefix|deb
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd) mode=$3
python=$source/.venv/bin/python
clip=$source/../shared/data/videos/d10.mp4
fail() { echo "FAIL: $*" >&2; exit 1; }
[ -s "$clip" ] || { echo "SKIP: no $clip"; exit 77; }
[ -s "$source/.models/face_landmark.onnx" ] || { echo "SKIP: no converted models (scripts/setup.sh)"; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [ "$mode" = prefix ]; then
  cmake --install "$build" --prefix "$work/first" >"$work/install.txt" || fail "cmake --install"
  mv "$work/first" "$work/moved"
  root=$work/moved
elif [ "$mode" = deb ]; then
  (cd "$work" && cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/package" >"$work/cpack.txt" 2>&1) \
    || { cat "$work/cpack.txt"; fail "cpack -G DEB"; }
  deb=$(ls "$work"/package/*.deb)
  dpkg-deb --info "$deb" >"$work/info.txt" || fail "dpkg-deb --info"
  grep -q "Depends:.*liblcm" "$work/info.txt" || { cat "$work/info.txt"; fail "the package does not depend on LCM's library"; }
  dpkg-deb -x "$deb" "$work/root" || fail "dpkg-deb -x"
  root=$work/root/usr
  echo "package: $(basename "$deb"), $(du -k "$deb" | cut -f1) KB"
else
  fail "mode prefix or deb, not '$mode'"
fi

cd "$work"  # neither the source nor the build tree
# (each output to a file first: grep -q may stop reading early, and under pipefail the writer's SIGPIPE would fail)
for program in hkf-estimator hkf-filter hkf-opentrack hkf-cmd hkf-demo hkf-simlog hkf-annotate hkf-spy hkf-track hkf-view; do
  "$root/bin/$program" --version >"$work/version.txt" || fail "$program --version"
  grep -q "^$program " "$work/version.txt" || fail "$program --version: $(cat "$work/version.txt")"
done
# the installed hkf-view serves the installed page (share/hkf/view), not the source tree's
port=$((20000 + RANDOM % 20000))
"$root/bin/hkf-view" --lcm-url memq:// --listen "127.0.0.1:$port" --seconds 20 >"$work/view.txt" 2>&1 &
view=$!
for _ in $(seq 100); do curl -sf -o "$work/view.html" "http://127.0.0.1:$port/" && break; sleep 0.1; done
kill -INT "$view" 2>/dev/null; wait "$view" || true
grep -q 'name="hkf-token" content="[0-9a-f]\{32\}"' "$work/view.html" 2>/dev/null || fail "the installed hkf-view served no page"
grep -q "^hkf-view: the page's files from $root/bin/../share/hkf/view$" "$work/view.txt" ||
  fail "the installed hkf-view does not serve the installed page: $(cat "$work/view.txt")"
"$root/bin/hkf-spy" --print-class-path >"$work/class_path.txt" || fail "hkf-spy --print-class-path"
grep -q "$root/bin/../share/hkf/java/hkf_lcmtypes.jar" "$work/class_path.txt" || fail "hkf-spy does not use the installed jar"
"$root/bin/hkf-estimator" --help >"$work/help.txt" || fail "hkf-estimator --help"
grep -q "default $root/share/hkf/models" "$work/help.txt" || fail "the estimator does not find its installed models"
"$root/bin/hkf-estimator" --source "$clip" --max-frames 60 --lcm-url "file://$work/raw.lcmlog?mode=w" >"$work/estimator.txt" 2>&1 \
  || { cat "$work/estimator.txt"; fail "the installed estimator on $clip"; }
"$root/bin/hkf-filter" --config "$root/share/hkf/hkf-filter.conf" --offline "$work/raw.lcmlog" "$work/poses.lcmlog" \
  >"$work/filter.txt" 2>&1 || { cat "$work/filter.txt"; fail "the installed filter"; }
[ -s "$root/share/hkf/java/hkf_lcmtypes.jar" ] || fail "no jar for lcm-spy"
PYTHONPATH="$root/share/hkf/python" "$python" - "$work/poses.lcmlog" <<'PY' || fail "the installed Python types"
import sys
import lcm
import hkf
from hkf import head_pose_t
assert "share/hkf/python" in hkf.__file__, hkf.__file__
poses = [head_pose_t.decode(e.data) for e in lcm.EventLog(sys.argv[1], "r") if e.channel == "HEAD_POSE"]
tracked = [p for p in poses if p.status == head_pose_t.TRACKING]
assert len(tracked) >= 55, (len(poses), len(tracked))
print(f"installed tracker: {len(poses)} poses, {len(tracked)} tracking, from {hkf.__file__}")
PY
# hkf-track, installed, runs the installed programs (their logs in ./hkf-track-logs), with the system's
# PATH alone: no Python, no project venv; over udpm in a private network namespace (hkf-track refuses
# memq://, which its separate programs could not share)
status=0
"$source/tools/lcm-netns" env -i PATH=/usr/bin:/bin "$root/bin/hkf-track" --source "$clip" --seconds 20 \
  >"$work/track.txt" 2>&1 || status=$?
if [ "$status" = 77 ]; then
  echo "installed hkf-track: not run (a private network namespace needs root)"
else
  [ "$status" = 0 ] || { cat "$work/track.txt"; fail "the installed hkf-track: exit $status"; }
  grep -q "^hkf-estimator: " "$work/hkf-track-logs/hkf-estimator.log" || fail "hkf-track did not run the installed estimator"
fi
tail -1 "$work/estimator.txt"
