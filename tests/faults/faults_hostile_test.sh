#!/usr/bin/env bash
# The fault catalogue, part 3: a hostile review's command lines, files and
# messages, on real data - the raw poses of a real clip
# (../shared/data/videos/d3.mp4) and real face images (AFLW2000). No command
# line, file or message may make a program destroy or truncate data and exit
# 0, abort, hang without saying so, or hold the pose up for longer than the
# coast time. Each fault's outcome is in the fault catalogue (docs/reliability.md).
# usage: faults_hostile_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$(cd "$1" && pwd) source=$(cd "$2" && pwd)
python=$source/.venv/bin/python types=$build/lcmtypes/python
estimator=$build/estimator/hkf-estimator filter=$build/tools/hkf-filter
opentrack=$build/tools/hkf-opentrack cmd=$build/tools/hkf-cmd
data=$source/../shared/data
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
[ -f "$data/videos/d3.mp4" ] || fail "missing $data/videos/d3.mp4 (the team's shared data)"
# expect_exit CODE LABEL COMMAND...: runs it (30 s at most), wants exit CODE; its output in $work/out.txt
expect_exit() {
  local want=$1 label=$2 status=0
  shift 2
  timeout 30 "$@" >"$work/out.txt" 2>&1 || status=$?
  [ "$status" = "$want" ] || { cat "$work/out.txt" >&2; fail "$label: exit $status (expected $want)"; }
  echo "$label: exit $status; $(grep -v "measurements (" "$work/out.txt" | head -n 1)"
}
said() { grep -q -- "$1" "$work/out.txt" || { cat "$work/out.txt" >&2; fail "expected to be told '$1'"; }; }

# one model: a measurement per frame (the cases below count them)
"$estimator" --source "$data/videos/d3.mp4" --max-frames 120 --second-model none --lcm-url "file://$work/raw.lcmlog?mode=w" \
  >"$work/estimate.txt" 2>&1 || fail "the estimator on the clip"
frames=$(sed -n 's/^hkf-estimator: \([0-9]*\) frames,.* fps;.*/\1/p' "$work/estimate.txt")
echo "the clip's raw poses: $frames frames"
sum() { sha256sum "$1" | cut -d' ' -f1; }
raw_sum=$(sum "$work/raw.lcmlog")

echo "== 1. --offline never writes over its input"
cd "$work"
ln -s raw.lcmlog link.lcmlog
expect_exit 1 "--offline IN IN" "$filter" --offline raw.lcmlog raw.lcmlog
said "refusing to write over it"
expect_exit 1 "--offline IN LINK-TO-IN" "$filter" --offline raw.lcmlog link.lcmlog
expect_exit 1 "--offline IN ./IN" "$filter" --offline raw.lcmlog "$work/./raw.lcmlog"
expect_exit 1 "--csv IN" "$filter" --offline raw.lcmlog out.lcmlog --csv raw.lcmlog
[ ! -e out.lcmlog ] || fail "an output was created although the run was refused"
expect_exit 1 "--csv OUT" "$filter" --offline raw.lcmlog out.lcmlog --csv out.lcmlog
[ "$(sum raw.lcmlog)" = "$raw_sum" ] || fail "the input log changed"
cd - >/dev/null

echo "== 2. a full disk is an error, never success"
expect_exit 1 "--offline IN /dev/full" "$filter" --offline "$work/raw.lcmlog" /dev/full
said "'/dev/full' is a character device; an output must be a regular file"  # round 5: refused before writing
expect_exit 1 "--csv /dev/full" "$filter" --offline "$work/raw.lcmlog" "$work/ok.lcmlog" --csv /dev/full
# a disk that fills midway: the file size limit (SIGXFSZ ignored, so write() fails with EFBIG)
status=0
# (no trap here: a user's shell leaves SIGXFSZ as it is, and the program must report the write itself)
(ulimit -f 4; exec "$filter" --offline "$work/raw.lcmlog" "$work/cut.lcmlog") >"$work/out.txt" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$work/out.txt"; fail "a disk full midway: exit $status (expected 1)"; }
grep -q "it is incomplete" "$work/out.txt" || fail "the cut output was not reported"
echo "disk full midway: exit 1, $(stat -c %s "$work/cut.lcmlog") of $(stat -c %s "$work/ok.lcmlog") bytes, reported"

# log_edit EDIT IN OUT: rewrites the raw log with one of the hostile edits below
log_edit() {
  "$python" - "$@" "$types" <<'PY'
import sys
import lcm
edit, src, dst, types = sys.argv[1:5]
sys.path.insert(0, types)
from hkf import head_pose_measurement_t, tracker_command_t
out = lcm.EventLog(dst, "w", overwrite=True)
for e in lcm.EventLog(src, "r"):
    m = head_pose_measurement_t.decode(e.data)
    if edit == "step-back" and m.seq >= 60:  # the machine's clock steps back 1 h: stamps and arrivals together
        m.utime -= 3600 * 10**6
        out.write_event(e.timestamp - 3600 * 10**6, e.channel, m.encode())
        continue
    out.write_event(e.timestamp, e.channel, m.encode())
    if edit == "forge" and m.seq in (30, 60, 90):  # a forged datagram: the next seq, a stamp 4.9 s ahead
        f = head_pose_measurement_t.decode(e.data)
        f.seq, f.utime, f.yaw = m.seq + 1, m.utime + 4900000, 170.0
        out.write_event(e.timestamp + 1000, e.channel, f.encode())
    if edit == "long-model" and m.seq == 10:
        f = head_pose_measurement_t.decode(e.data)
        f.model = "m" * 40
        out.write_event(e.timestamp + 1, e.channel, f.encode())
    if edit == "commands":
        c = tracker_command_t()
        c.utime, c.command = e.timestamp, 99
        out.write_event(e.timestamp + 1, "HEAD_TRACKER_CMD", c.encode())
out.close()
PY
}
# answered OUT.lcmlog RAW.lcmlog: prints "answered frames, longest wait (ms) between poses on the arrival clock"
answered() {
  "$python" - "$1" "$2" "$types" <<'PY'
import sys
import lcm
sys.path.insert(0, sys.argv[3])
from hkf import head_pose_measurement_t, head_pose_t
poses = [(e.timestamp, head_pose_t.decode(e.data)) for e in lcm.EventLog(sys.argv[1], "r") if e.channel == "HEAD_POSE"]
poses = [(t, p) for t, p in poses if not p.extrapolated]
raw = [head_pose_measurement_t.decode(e.data) for e in lcm.EventLog(sys.argv[2], "r")]
real = {m.utime for m in raw if m.valid and m.yaw != 170.0 and len(m.model) < 32}
stamps = [t for t, _ in poses]
wait = max(b - a for a, b in zip(stamps, stamps[1:]))
print(len({p.utime for _, p in poses} & real), round(wait / 1000))
PY
}

echo "== 3. the clock steps back 1 h (stamps and arrival times together) after frame 60"
log_edit step-back "$work/raw.lcmlog" "$work/back.lcmlog"
expect_exit 0 "a clock stepped back" "$filter" --offline "$work/back.lcmlog" "$work/back_out.lcmlog"
read -r got wait < <(answered "$work/back_out.lcmlog" "$work/back.lcmlog")
read -r clean _ < <("$filter" --offline "$work/raw.lcmlog" "$work/clean_out.lcmlog" 2>/dev/null; answered "$work/clean_out.lcmlog" "$work/raw.lcmlog")
echo "clock stepped back: $got of $clean frames with a face answered (clean log), longest wait ${wait} ms"
[ "$got" -ge $((clean - 2)) ] || fail "after the clock stepped back only $got of $clean frames were filtered"

echo "== 4. three forged datagrams (the next seq, a stamp 4.9 s ahead)"
log_edit forge "$work/raw.lcmlog" "$work/forged.lcmlog"
expect_exit 0 "forged datagrams" "$filter" --offline "$work/forged.lcmlog" "$work/forged_out.lcmlog"
read -r got wait < <(answered "$work/forged_out.lcmlog" "$work/forged.lcmlog")
echo "forged datagrams: $got of $clean real frames answered, longest wait between poses ${wait} ms"
[ "$got" -ge $((clean - 9)) ] || fail "forged datagrams: only $got of $clean real frames filtered"
[ "$wait" -lt 250 ] || fail "a forged datagram held the pose up for $wait ms (coast time 250 ms)"

echo "== 5. the estimator ends every run with an error and exit 1 or 2, never an abort"
expect_exit 2 "--annotate /nonexistent/o.mp4" "$estimator" --source "$data/videos/d3.mp4" --lcm-url memq:// --annotate /nonexistent/o.mp4
expect_exit 2 "--annotate o.txt" "$estimator" --source "$data/videos/d3.mp4" --lcm-url memq:// --annotate "$work/o.txt"
cp "$data/videos/d3.mp4" "$work/copy.mp4"
expect_exit 2 "--annotate the source itself" "$estimator" --source "$work/copy.mp4" --lcm-url memq:// --annotate "$work/copy.mp4"
[ "$(sum "$work/copy.mp4")" = "$(sum "$data/videos/d3.mp4")" ] || fail "the source video changed"
expect_exit 1 "--source 99999999999" "$estimator" --source 99999999999 --lcm-url memq://
ln -s loop1 "$work/loop2"
ln -s loop2 "$work/loop1"
expect_exit 1 "--source SYMLINK-LOOP" "$estimator" --source "$work/loop1" --lcm-url memq://
mkdir "$work/specs"
sed 's/^\(yaw_bins *= *[a-z]*\) 120/\1 66/' "$source/estimator/models/whenet.model" >"$work/specs/whenet_bins.model"
expect_exit 1 "a model whose bins do not match the network" "$estimator" --source "$data/videos/d3.mp4" \
  --lcm-url memq:// --max-frames 5 --second-model none --model whenet_bins --spec-dir "$work/specs"
said "the model description implies 66"
said "^hkf-estimator: [0-9]* frames,"
sed 's/^input .*/input = 100 100/' "$source/estimator/models/mesh_pnp.model" >"$work/specs/mesh_small.model"
# OpenCV DNN then asks for an absurd allocation: malloc returns NULL and OpenCV throws, which is
# what this checks; AddressSanitizer's allocator would abort there unless told to return NULL too
ASAN_OPTIONS=${ASAN_OPTIONS:+$ASAN_OPTIONS:}allocator_may_return_null=1 expect_exit 1 "a mesh whose input size does not match the network" "$estimator" --source "$data/videos/d3.mp4" \
  --lcm-url memq:// --max-frames 5 --second-model none --model mesh_small --spec-dir "$work/specs"
said "^hkf-estimator: [0-9]* frames,"

echo "== 6. a model id longer than the message allows: refused at start, explained at the filter"
expect_exit 2 "--model of 33 characters" "$estimator" --source "$data/videos/d3.mp4" --lcm-url memq:// --model "$(printf 'm%.0s' $(seq 33))"
said "1 to 31 letters"
log_edit long-model "$work/raw.lcmlog" "$work/long.lcmlog"
expect_exit 0 "a log with a 40-byte model id" "$filter" --offline "$work/long.lcmlog" "$work/long_out.lcmlog"
said "1 messages did not decode"
said "longer than the 31 bytes"

echo "== 7. unknown commands are counted, not printed one by one"
log_edit commands "$work/raw.lcmlog" "$work/commands.lcmlog"
expect_exit 0 "$frames unknown commands" "$filter" --offline "$work/commands.lcmlog" "$work/commands_out.lcmlog"
said "$frames unknown commands ignored"
[ "$(grep -c "unknown command" "$work/out.txt")" -le 6 ] || fail "unknown commands flooded the terminal"

echo "== 8. a channel name longer than LCM allows (63) is refused at start"
long_channel=$(printf 'C%.0s' $(seq 64))
expect_exit 2 "hkf-estimator --channel (64)" "$estimator" --source "$data/videos/d3.mp4" --lcm-url memq:// --channel "$long_channel"
expect_exit 2 "hkf-filter --output-channel (64)" "$filter" --lcm-url memq:// --output-channel "$long_channel"
expect_exit 2 "hkf-opentrack --channel (64)" "$opentrack" --lcm-url memq:// --channel "$long_channel"
expect_exit 2 "hkf-cmd --channel (64)" "$cmd" recenter --lcm-url memq:// --channel "$long_channel"

echo "== 9. SIGHUP (the terminal closed) stops like SIGTERM: summary, whole outputs"
"$build/tools/hkf-simlog" --out "$work/hour.lcmlog" --seconds 3600 --seed 2 >/dev/null 2>&1
"$filter" --offline "$work/hour.lcmlog" "$work/hour_out.lcmlog" --rate 10000 --csv "$work/hour.csv" >"$work/out.txt" 2>&1 &
pid=$!
sleep 1
kill -HUP $pid
status=0
wait $pid || status=$?
[ "$status" = 1 ] || fail "hkf-filter --offline after SIGHUP: exit $status (expected 1)"
said "stopped by a signal"
said "poses published"
"$filter" --offline "$work/hour_out.lcmlog" "$work/again.lcmlog" --input-channel NONE 2>"$work/reread.txt"
if grep -q "cut off\|damaged" "$work/reread.txt"; then fail "the output log is not whole after SIGHUP"; fi
[ "$(tail -c 1 "$work/hour.csv" | od -An -c | tr -d ' ')" = '\n' ] || fail "the CSV is cut mid-line after SIGHUP"
echo "hkf-filter --offline: SIGHUP -> exit 1, summary, log and CSV whole"
"$estimator" --source "$data/videos/d3.mp4" --realtime --lcm-url memq:// --annotate "$work/hup.mp4" >"$work/out.txt" 2>&1 &
pid=$!
# SIGHUP once frames are being written (paced by the file, not the clock: 10 s of waiting at most)
for _ in $(seq 100); do [ "$(stat -c %s "$work/hup.mp4" 2>/dev/null || echo 0)" -gt 20000 ] && break; sleep 0.1; done
kill -HUP $pid
status=0
wait $pid || status=$?
[ "$status" = 0 ] || fail "hkf-estimator after SIGHUP: exit $status (expected 0)"
said "^hkf-estimator: [0-9]* frames,"
"$estimator" --source "$work/hup.mp4" --second-model none --lcm-url memq:// >"$work/out.txt" 2>&1 || fail "the --annotate video after SIGHUP does not play"
said "^hkf-estimator: [0-9]* frames,"
echo "hkf-estimator: SIGHUP -> summary, the --annotate video plays ($(sed -n 's/^hkf-estimator: \([0-9]*\) frames,.* fps;.*/\1/p' "$work/out.txt") frames)"

echo "== 10. a named pipe as an input is refused at once, not waited on"
mkfifo "$work/fifo"
expect_exit 2 "--config FIFO" "$filter" --config "$work/fifo" --print-config
said "not a regular file"
expect_exit 1 "--offline FIFO OUT" "$filter" --offline "$work/fifo" "$work/x.lcmlog"
said "named pipe"
expect_exit 1 "--offline IN FIFO (no reader)" "$filter" --offline "$work/raw.lcmlog" "$work/fifo"
said "nothing reads"

echo "== 11. numbers out of range are refused"
expect_exit 2 "--region nan,nan,nan,nan" "$estimator" --source "$data/videos/d3.mp4" --lcm-url memq:// --region nan,nan,nan,nan
expect_exit 2 "hkf-opentrack --rate 1e-300" "$opentrack" --lcm-url memq:// --rate 1e-300
expect_exit 2 "hkf-filter --rate 1e-300" "$filter" --lcm-url memq:// --rate 1e-300

echo "== 12-13. model names and config errors: one rule, FILE:LINE, the real reason"
for name in 'a b' 'a]' 'a#' "$(printf 'a\nb')"; do
  expect_exit 2 "--set model.'$name'.noise.yaw" "$filter" --set "model.$name.noise.yaw=7 4 0 30" --print-config
done
printf 'start_rate = 30\nlc_xi = 5\n' >"$work/bad.conf"
expect_exit 2 "lc_xi = 5 in a file" "$filter" --config "$work/bad.conf" --print-config
said "bad.conf:2: lc_xi wants a number 0 to 1, not '5'"
printf 'r_min = 200\nr_max = 100\n' >"$work/bad_pair.conf"  # each in range, not together: both lines named
expect_exit 2 "r_min above r_max in a file" "$filter" --config "$work/bad_pair.conf" --print-config
said "bad_pair.conf:1: r_min = 200; "
said "bad_pair.conf:2: r_max = 100; invalid settings"
expect_exit 2 "--set lc_theta=1e300" "$filter" --set lc_theta=1e300 --print-config
said "beyond the range"
printf 'start_rate = 30\nlc_xi\0 = 0.5\n' >"$work/nul.conf"
expect_exit 2 "a NUL byte in a config" "$filter" --config "$work/nul.conf" --print-config
said "nul.conf:2: a NUL byte"

echo "== 15-17. image folders: frames of two sizes, an unreadable image, an image beyond the cap"
mkdir "$work/images"
for image in $(ls "$data/aflw2000/images" | head -n 4); do cp "$data/aflw2000/images/$image" "$work/images/"; done
"$python" - "$work/images" <<'PY'
import os
import sys
from PIL import Image
folder = sys.argv[1]
first = sorted(os.listdir(folder))[0]
Image.open(f"{folder}/{first}").resize((300, 300)).save(f"{folder}/z_resized.jpg")  # another size than the first
open(f"{folder}/b_broken.jpg", "wb").write(b"\xff\xd8\xff not a JPEG after all")  # unreadable
Image.new("RGB", (20000, 16)).save(f"{folder}/c_large.png")                       # beyond the size cap
PY
expect_exit 0 "a folder with 5 good, 1 damaged and 1 oversized image, --annotate" "$estimator" --source "$work/images" \
  --lcm-url memq:// --annotate "$work/images.mp4"
said "^hkf-estimator: 5 frames,"
said "2 images of the folder could not be read; skipped"
said "1 frames of another size than the first were scaled"
"$estimator" --source "$work/images.mp4" --lcm-url memq:// >"$work/out.txt" 2>&1 || fail "the --annotate video does not play"
said "^hkf-estimator: 5 frames,"
echo "== 18. LCM file:// URLs follow the rules of every output (round 3)"
cp "$data/videos/d3.mp4" "$work/clip.mp4"
clip_sum=$(sum "$work/clip.mp4")
expect_exit 1 "hkf-estimator --lcm-url file://SOURCE?mode=w" "$estimator" --source "$work/clip.mp4" --max-frames 10 \
  --lcm-url "file://$work/clip.mp4?mode=w"
said "refusing to write over it"
[ "$(sum "$work/clip.mp4")" = "$clip_sum" ] || fail "the estimator wrote over its source through an LCM URL"
cp "$work/raw.lcmlog" "$work/x.lcmlog"
expect_exit 1 "hkf-filter --input-url file://X --output-url file://X?mode=w" "$filter" --input-url "file://$work/x.lcmlog" \
  --output-url "file://$work/x.lcmlog?mode=w"
[ "$(sum "$work/x.lcmlog")" = "$raw_sum" ] || fail "hkf-filter wrote over its input log through an LCM URL"
expect_exit 1 "hkf-filter --input-url file://X?mode=w (an input that writes)" "$filter" --input-url "file://$work/x.lcmlog?mode=w"
[ "$(sum "$work/x.lcmlog")" = "$raw_sum" ] || fail "an input URL in write mode truncated the log"
# a disk that fills: a file-size limit, with SIGXFSZ as a user's shell leaves it
status=0
(ulimit -f 2; exec "$estimator" --source "$work/clip.mp4" --max-frames 60 --second-model none \
  --lcm-url "file://$work/small.lcmlog?mode=w") >"$work/out.txt" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$work/out.txt"; fail "the estimator's file:// log on a full disk: exit $status (expected 1)"; }
said "data lost"
echo "hkf-estimator onto a full disk: exit 1, $(grep -o 'holds [0-9]* of the [0-9]* events' "$work/out.txt")"
status=0
(ulimit -f 4; exec "$filter" --input-url "file://$work/raw.lcmlog?speed=0" \
  --output-url "file://$work/small_out.lcmlog?mode=w") >"$work/out.txt" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$work/out.txt"; fail "hkf-filter's file:// output on a full disk: exit $status (expected 1)"; }
said "data lost"
echo "hkf-filter --output-url onto a full disk: exit 1, $(grep -o 'holds [0-9]* of the [0-9]* events' "$work/out.txt")"
status=0
(ulimit -f 100; exec "$estimator" --source "$work/clip.mp4" --max-frames 200 --second-model none --lcm-url memq:// \
  --annotate "$work/full.mp4") >"$work/out.txt" 2>&1 || status=$?
[ "$status" = 1 ] || { cat "$work/out.txt"; fail "--annotate onto a full disk: exit $status (expected 1)"; }
said "cannot be opened: it is cut"
echo "hkf-estimator --annotate onto a full disk: exit 1, reported"
expect_exit 1 "hkf-cmd --lcm-url file:///dev/full?mode=w" "$cmd" recenter --lcm-url "file:///dev/full?mode=w"
said "not a regular file"
expect_exit 1 "hkf-estimator --lcm-url file://FIFO?mode=w" "$estimator" --source "$work/clip.mp4" --max-frames 5 \
  --lcm-url "file://$work/fifo?mode=w"
said "named pipe"
expect_exit 1 "hkf-filter --input-url file://FIFO" "$filter" --input-url "file://$work/fifo"
said "named pipe"
expect_exit 1 "hkf-cmd --lcm-url file://FIFO?mode=w" "$cmd" reset --lcm-url "file://$work/fifo?mode=w"
said "named pipe"
expect_exit 1 "hkf-opentrack --lcm-url file://FIFO" "$opentrack" --lcm-url "file://$work/fifo"
said "named pipe"

echo "== 19. positions far off, forged or bad: gated, bounded, counted (round 3)"
log_position() {
  "$python" - "$@" "$types" <<'PY'
import sys
import lcm
src, dst, types = sys.argv[1:4]
sys.path.insert(0, types)
from hkf import head_pose_measurement_t
out = lcm.EventLog(dst, "w", overwrite=True)
for e in lcm.EventLog(src, "r"):
    m = head_pose_measurement_t.decode(e.data)
    if m.valid and 30 <= m.seq < 40:  # x -1000 cm for 10 frames, then +1000 once
        m.x, m.z = -1000.0, 2.0
    elif m.valid and m.seq == 40:
        m.x, m.y, m.z = 1000.0, -1000.0, 1000.0
    elif m.valid and 41 <= m.seq < 60:  # then no position
        m.z = 0.0
    elif m.valid and m.seq in (70, 71, 72):  # bad values: NaN, a negative z, beyond the range
        m.x, m.z = (float("nan"), 60.0) if m.seq == 70 else (0.0, -4.65) if m.seq == 71 else (2000.0, 60.0)
    elif m.valid and m.seq == 90:  # one forged message
        m.x, m.y, m.z = 1000.0, -1000.0, 1000.0
    out.write_event(e.timestamp, e.channel, m.encode())
out.close()
PY
}
log_position "$work/raw.lcmlog" "$work/position.lcmlog"
expect_exit 0 "a log with far, forged and bad positions" "$filter" --offline "$work/position.lcmlog" "$work/position_out.lcmlog" \
  --csv "$work/position.csv"
said "positions: 3 bad values, [1-9][0-9]* refused by the outlier gate"
"$python" - "$work/position.csv" <<'PY' || fail "a published position beyond the range the node accepts"
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
worst = max(max(abs(float(r["x"])), abs(float(r["y"])), float(r["z"])) for r in rows)
assert all(math.isfinite(float(r[k])) for r in rows for k in ("x", "y", "z")), "non-finite"
assert all(abs(float(r[k])) <= 1000 for r in rows for k in ("x", "y", "z")), f"beyond 1000 cm: {worst}"
assert all(float(r["z"]) >= 1.0 or float(r["z"]) == 0.0 for r in rows), "z below 1 cm"
forged = [r for r in rows if int(r["seq"]) > 0 and abs(float(r["x"])) > 900]
print(f"positions published: |x|, |y|, z at most {worst:.0f} cm; {len(forged)} poses with |x| > 900 cm")
PY
echo "== 20. the estimator's inputs: a stuck decoder, an empty video, damaged weights, odd settings (round 3)"
"$python" - "$data/videos/d3.mp4" "$work" <<'PY'
import sys
import cv2
video, work = sys.argv[1:3]
capture, stream = cv2.VideoCapture(video), open(f"{work}/concat.mjpeg", "wb")
for i in range(120):  # concatenated MJPEG: the frames grow by half at frame 60
    ok, frame = capture.read()
    if i >= 60:
        frame = cv2.resize(frame, (frame.shape[1] * 3 // 2, frame.shape[0] * 3 // 2))
    stream.write(cv2.imencode(".jpg", frame)[1].tobytes())
writer = cv2.VideoWriter(f"{work}/zero.avi", cv2.VideoWriter_fourcc(*"MJPG"), 30, (320, 240))
writer.release()  # a video of no frame
PY
expect_exit 1 "frames that change size mid-stream (concatenated MJPEG)" "$estimator" --source "$work/concat.mjpeg" \
  --second-model none --lcm-url memq://
said "its decoder is stuck"
expect_exit 1 "a video of no frame" "$estimator" --source "$work/zero.avi" --lcm-url memq://
said "gave no frame: it holds none"
mkdir "$work/nan_models"
for f in "$source"/.models/*; do ln -s "$f" "$work/nan_models/"; done
rm "$work/nan_models/face_landmark.onnx"
"$python" - "$source/.models/face_landmark.onnx" "$work/nan_models/face_landmark.onnx" <<'PY'
import sys
import numpy as np
import onnx
from onnx import numpy_helper
model = onnx.load(sys.argv[1])
for weights in model.graph.initializer:  # every large float tensor NaN: damaged weights
    values = numpy_helper.to_array(weights)
    if values.dtype == np.float32 and values.size > 100:
        weights.CopyFrom(numpy_helper.from_array(np.full_like(values, np.nan), weights.name))
onnx.save(model, sys.argv[2])
PY
expect_exit 1 "a face mesh with NaN weights" "$estimator" --source "$work/clip.mp4" --max-frames 10 --second-model none \
  --lcm-url memq:// --models-dir "$work/nan_models"
said "gave NaN or infinite outputs on 10 faces"
sed 's/^roi_scale *= .*/roi_scale = 1e9/' "$source/estimator/models/mesh_pnp.model" >"$work/specs/mesh_roi.model"
expect_exit 1 "roi_scale = 1e9" "$estimator" --source "$work/clip.mp4" --max-frames 5 --second-model none \
  --lcm-url memq:// --model mesh_roi --spec-dir "$work/specs"
said "roi_scale must be above 0 and below 100"
HKF_MODELS_DIR='' expect_exit 0 "HKF_MODELS_DIR='' (as unset)" "$estimator" --source "$work/clip.mp4" --max-frames 5 \
  --second-model none --lcm-url memq://
expect_exit 1 "--models-dir without the models" "$estimator" --source "$work/clip.mp4" --max-frames 5 \
  --second-model none --lcm-url memq:// --models-dir "$work/specs"
said "an installed hkf has them in share/hkf/models"
echo "== 21. outputs named by any option, and the URL LCM resolves, never overwrite an input (round 4)"
cd "$work"
cp raw.lcmlog in.lcmlog
in_sum=$(sum in.lcmlog)
expect_exit 1 "hkf-filter --input-url file://IN --csv IN" "$filter" --input-url "file://$work/in.lcmlog" --csv in.lcmlog
said "refusing to write over it"
[ "$(sum in.lcmlog)" = "$in_sum" ] || fail "--csv truncated the input log the URL names"
expect_exit 1 "hkf-filter --output-url file://OUT?mode=w --csv OUT" "$filter" --input-url "file://$work/in.lcmlog" \
  --output-url "file://$work/o.lcmlog?mode=w" --csv o.lcmlog
mkdir src_images
for image in $(ls "$data/aflw2000/images" | head -n 3); do cp "$data/aflw2000/images/$image" src_images/; done
first_image=$(ls src_images | head -n 1)
images_sum=$(cat src_images/* | sha256sum)
expect_exit 1 "hkf-estimator --source FOLDER --lcm-url file://FOLDER/IMAGE?mode=w" "$estimator" --source src_images \
  --lcm-url "file://$work/src_images/$first_image?mode=w"
said "names a file inside"
[ "$(cat src_images/* | sha256sum)" = "$images_sum" ] || fail "the estimator wrote over an image of its source folder"
mkdir -p ds/images
head -n 4 "$data/aflw2000/labels.csv" >ds/labels.csv
for image in $(tail -n +2 ds/labels.csv | cut -d, -f1); do cp "$data/aflw2000/images/$image" ds/images/; done
dataset_sum=$(cat ds/labels.csv ds/images/* | sha256sum)
expect_exit 1 "--dataset DS --predictions DS/labels.csv" "$estimator" --dataset ds --predictions ds/labels.csv
said "refusing to write over it"
expect_exit 1 "--dataset DS --predictions DS/images/IMAGE" "$estimator" --dataset ds \
  --predictions "ds/images/$(ls ds/images | head -n 1)"
[ "$(cat ds/labels.csv ds/images/* | sha256sum)" = "$dataset_sum" ] || fail "--dataset wrote over its labels or an image"
expect_exit 1 "--dataset DS --predictions FIFO (no reader)" "$estimator" --dataset ds --predictions "$work/fifo"
said "nothing reads"
cp -r ds ds_fifo_labels && rm ds_fifo_labels/labels.csv && mkfifo ds_fifo_labels/labels.csv
expect_exit 1 "--dataset with a FIFO as labels.csv" "$estimator" --dataset ds_fifo_labels --predictions p.csv
said "not a regular file"
cp -r ds ds_fifo_image && rm "ds_fifo_image/images/$(ls ds/images | head -n 1)" && mkfifo "ds_fifo_image/images/$(ls ds/images | head -n 1)"
expect_exit 0 "--dataset with a FIFO as an image" "$estimator" --dataset ds_fifo_image --predictions p.csv
said "cannot read .*$(ls ds/images | head -n 1).*skipped"
mkdir src_fifo && cp src_images/* src_fifo/ && mkfifo src_fifo/b_fifo.jpg
expect_exit 0 "--source a folder with a FIFO in it" "$estimator" --source src_fifo --lcm-url memq://
said "^hkf-estimator: 3 frames,"
said "not a regular file"
expect_exit 1 "LCM_DEFAULT_URL=file://SOURCE?mode=w hkf-estimator --lcm-url ''" \
  env LCM_DEFAULT_URL="file://$work/clip.mp4?mode=w" "$estimator" --source clip.mp4 --max-frames 5 --lcm-url ""
[ "$(sum clip.mp4)" = "$clip_sum" ] || fail "an empty --lcm-url let \$LCM_DEFAULT_URL write over the source"
expect_exit 1 "LCM_DEFAULT_URL=file://VIDEO?mode=w hkf-cmd --lcm-url ''" \
  env LCM_DEFAULT_URL="file://$work/clip.mp4?mode=w" "$cmd" recenter --lcm-url ""
said "not an LCM log"
[ "$(sum clip.mp4)" = "$clip_sum" ] || fail "hkf-cmd wrote a log over a video"
expect_exit 1 "LCM_DEFAULT_URL=file://FIFO?mode=w hkf-cmd --lcm-url ''" \
  env LCM_DEFAULT_URL="file://$work/fifo?mode=w" "$cmd" reset --lcm-url ""
said "named pipe"
expect_exit 1 "LCM_DEFAULT_URL=file://IN?mode=w hkf-filter --output-url '' --csv" \
  env LCM_DEFAULT_URL="file://$work/in.lcmlog?mode=w" "$filter" --input-url "file://$work/in.lcmlog" --output-url ""
[ "$(sum in.lcmlog)" = "$in_sum" ] || fail "an empty --output-url let \$LCM_DEFAULT_URL write over the input log"
expect_exit 1 "LCM_DEFAULT_URL=file://FIFO hkf-opentrack --lcm-url ''" \
  env LCM_DEFAULT_URL="file://$work/fifo" "$opentrack" --lcm-url ""
said "named pipe"
status=0
"$filter" --print-config >/dev/full 2>"$work/out.txt" || status=$?
[ "$status" = 1 ] || fail "hkf-filter --print-config > /dev/full: exit $status (expected 1)"
said "writing the settings failed"
for program in "$filter" "$estimator" "$cmd" "$opentrack" "$build/tools/hkf-track"; do
  status=0
  "$program" --help >/dev/full 2>/dev/null || status=$?
  [ "$status" = 1 ] || fail "$(basename "$program") --help > /dev/full: exit $status (expected 1)"
done
echo "--print-config and --help onto a full disk: exit 1"
# an image beyond the size cap is refused from its header, not decoded first (9000 x 9000: 243 MB)
mkdir big_images big_ds big_ds/images
"$python" - big_images/a_big.png <<'PY'
import sys
from PIL import Image
Image.new("RGB", (9000, 9000), (90, 90, 90)).save(sys.argv[1])
PY
cp src_images/* big_images/
cp big_images/a_big.png big_ds/images/
{ head -n 1 ds/labels.csv; echo "a_big.png,10,5,0,100,100,300,300"; tail -n +2 ds/labels.csv; } >big_ds/labels.csv
cp ds/images/* big_ds/images/
"$python" - "$estimator" <<'PY' || fail "an image beyond the size cap was decoded"
import resource, subprocess, sys
def peak_after(args):
    subprocess.run([sys.argv[1], *args], check=True, capture_output=True)
    return resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024  # MB, the largest child so far
small = peak_after(["--source", "src_images", "--lcm-url", "memq://"])
big = peak_after(["--source", "big_images", "--lcm-url", "memq://"])
print(f"peak memory: {small:.0f} MB on 3 images, {big:.0f} MB with a 9000 x 9000 image among them")
assert big - small < 100, "decoded before it was refused"
PY
expect_exit 0 "--dataset with an image beyond the size cap" "$estimator" --dataset big_ds --predictions big.csv
said "4 images (1 unreadable"
cd - >/dev/null
echo "faults_hostile_test: all checks passed"
