#!/usr/bin/env bash
# hkf-filter --offline on a simulated drive written by hkf-simlog: deterministic,
# one pose per usable measurement, CSV export, --rate extrapolation, and the
# bad-input paths (undecodable message, missing file, bad setting).
# usage: offline_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
ulimit -f 1048576 # KiB: a filter that loops writing poses fails here at 1 GiB instead of filling the disk
build=$1 source=$2
simlog=$build/tools/hkf-simlog filter=$build/tools/hkf-filter
python=$source/.venv/bin/python  # with PyPI lcm (scripts/setup.sh)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$simlog" --out "$work/raw.lcmlog" --seconds 30 --seed 5
"$filter" --offline "$work/raw.lcmlog" "$work/a.lcmlog" --csv "$work/a.csv" 2>"$work/a.txt"
"$filter" --offline "$work/raw.lcmlog" "$work/b.lcmlog" 2>"$work/b.txt"
cat "$work/a.txt"
cmp -s "$work/a.lcmlog" "$work/b.lcmlog" || fail "two offline runs differ"
grep -q "900 measurements" "$work/a.txt" || fail "expected 900 measurements"
published=$(sed -n 's/.* \([0-9]*\) poses published.*/\1/p' "$work/a.txt")
without=$(sed -n 's/.*(\([0-9]*\) without a face).*/\1/p' "$work/a.txt")
# one pose per usable measurement, and one LOST pose at the end: the estimator falls silent
[ "$published" -ge $((900 - without + 1)) ] && [ "$published" -le 901 ] || fail "published $published of 900 ($without without a face)"
grep -q "the estimator fell silent 1 times" "$work/a.txt" || fail "the end of the log is not reported as a silence"
rows=$(($(wc -l <"$work/a.csv") - 1))
[ "$rows" -eq "$published" ] || fail "CSV has $rows rows, $published poses published"
"$python" "$source/dev/logs/compare_pose_logs.py" --types "$build/lcmtypes/python" "$work/a.lcmlog" "$work/b.lcmlog"
if grep -qi nan "$work/a.csv"; then fail "NaN in the CSV"; fi

# --rate: extrapolated poses in between, in log time
"$filter" --offline "$work/raw.lcmlog" "$work/r.lcmlog" --rate 120 2>"$work/r.txt"
cat "$work/r.txt"
extrapolated=$(sed -n 's/.*(\([0-9]*\) extrapolated).*/\1/p' "$work/r.txt")
[ "$extrapolated" -gt 2000 ] || fail "expected ~2700 extrapolated poses at 120 Hz over 30 s, got $extrapolated"

# an undecodable message is counted, never fatal
"$python" - "$work/raw.lcmlog" "$work/corrupt.lcmlog" <<'PY'
import sys
import lcm
events = [(e.timestamp, e.channel, e.data) for e in lcm.EventLog(sys.argv[1], "r")][:10]
events.insert(5, (events[4][0] + 1, "HEAD_POSE_RAW", b"\x00garbage"))
out = lcm.EventLog(sys.argv[2], "w", overwrite=True)
for timestamp, channel, data in events:
    out.write_event(timestamp, channel, data)
out.close()
PY
"$filter" --offline "$work/corrupt.lcmlog" "$work/c.lcmlog" 2>"$work/c.txt" || fail "exit status on an undecodable message"
cat "$work/c.txt"
grep -q "1 undecodable" "$work/c.txt" || fail "undecodable message not counted"
grep -q "11 measurements\|10 measurements" "$work/c.txt" || fail "the good messages were not all handled"

# one raw message stamped INT64_MAX (a corrupt stamp) among 29 good ones: rejected, nothing freezes
"$python" - "$work/raw.lcmlog" "$work/future.lcmlog" "$build/lcmtypes/python" <<'PY'
import sys
import lcm
sys.path.insert(0, sys.argv[3])
from hkf import head_pose_measurement_t
events = [e for e in lcm.EventLog(sys.argv[1], "r") if e.channel == "HEAD_POSE_RAW"][:30]
bad = head_pose_measurement_t.decode(events[10].data)
bad.utime = 2**63 - 1
out = lcm.EventLog(sys.argv[2], "w", overwrite=True)
for i, e in enumerate(events):
    out.write_event(e.timestamp, e.channel, bad.encode() if i == 10 else e.data)
out.close()
without = lcm.EventLog(sys.argv[2] + ".without", "w", overwrite=True)  # the same log without it
for i, e in enumerate(events):
    if i != 10:
        without.write_event(e.timestamp, e.channel, e.data)
without.close()
PY
"$filter" --offline "$work/future.lcmlog" "$work/f.lcmlog" 2>"$work/f.txt" || fail "exit status on a corrupt stamp"
cat "$work/f.txt"
grep -q "1 clock jumps (0 followed)" "$work/f.txt" || fail "the INT64_MAX stamp was not rejected as a clock jump"
grep -q "0 out of order" "$work/f.txt" || fail "good messages after the bad stamp were rejected"
"$filter" --offline "$work/future.lcmlog.without" "$work/w.lcmlog" 2>/dev/null
"$python" "$source/dev/logs/compare_pose_logs.py" --types "$build/lcmtypes/python" "$work/w.lcmlog" "$work/f.lcmlog" \
  || fail "the poses around the bad stamp differ from those of the log without it"

# two estimators on one channel (another drive, its own frame counter, 5 ms later): the node
# follows the first and counts the other; the output equals the first's alone
"$simlog" --out "$work/other.lcmlog" --seconds 30 --seed 9 --start-seq 100000 --start-utime 1700000000005000 >/dev/null 2>&1
"$python" - "$work/raw.lcmlog" "$work/other.lcmlog" "$work/two.lcmlog" <<'PY'
import sys
import lcm
events = sorted([(e.timestamp, i, e.channel, e.data) for i, e in enumerate(lcm.EventLog(sys.argv[1], "r"))] +
                [(e.timestamp, i, e.channel, e.data) for i, e in enumerate(lcm.EventLog(sys.argv[2], "r"))])
out = lcm.EventLog(sys.argv[3], "w", overwrite=True)
for timestamp, _, channel, data in events:
    out.write_event(timestamp, channel, data)
out.close()
PY
"$filter" --offline "$work/two.lcmlog" "$work/two_out.lcmlog" 2>"$work/two.txt" || fail "exit status with two publishers"
cat "$work/two.txt"
grep -q "900 from another publisher" "$work/two.txt" || fail "the second publisher's 900 messages were not all rejected"
"$python" "$source/dev/logs/compare_pose_logs.py" --types "$build/lcmtypes/python" "$work/a.lcmlog" "$work/two_out.lcmlog" \
  || fail "two publishers: the output is not the first publisher's alone"

# a log cut off mid-event (a power loss): the whole events are filtered, the cut is reported
size=$(stat -c %s "$work/raw.lcmlog")
head -c $((size / 2 + 37)) "$work/raw.lcmlog" >"$work/cut.lcmlog"
"$filter" --offline "$work/cut.lcmlog" "$work/cut_out.lcmlog" 2>"$work/cut.txt" || fail "exit status on a cut-off log"
cat "$work/cut.txt"
grep -q "is cut off: its last [1-9][0-9]* bytes are part of an event" "$work/cut.txt" || fail "the cut was not reported"
"$python" - "$work/a.lcmlog" "$work/cut_out.lcmlog" "$build/lcmtypes/python" <<'PY' || fail "the poses before the cut differ"
import sys
import lcm
sys.path.insert(0, sys.argv[3])
from hkf import head_pose_t
full = [head_pose_t.decode(e.data) for e in lcm.EventLog(sys.argv[1], "r") if e.channel == "HEAD_POSE"]
cut = [head_pose_t.decode(e.data) for e in lcm.EventLog(sys.argv[2], "r") if e.channel == "HEAD_POSE"]
assert 0 < len(cut) < len(full), (len(cut), len(full))
# the cut is a silence: the cut log's last pose is LOST, the ones before are the whole log's
assert cut[-1].status == head_pose_t.LOST and cut[-1].extrapolated, "no LOST pose at the cut"
assert all(c.encode() == f.encode() for c, f in zip(cut[:-1], full)), "a pose differs"
print(f"cut-off log: {len(cut) - 1} poses identical to the first of the whole log's {len(full)}, then LOST")
PY

# damage inside a log: 100 stray bytes between two events, and an event whose
# data length claims 2 GB; the rest is filtered, the damage reported
"$python" - "$work/raw.lcmlog" "$work/damaged.lcmlog" "$work/lost_one.lcmlog" <<'PY'
import struct
import sys
data = open(sys.argv[1], "rb").read()
starts = []
i = data.find(b"\xed\xa1\xda\x01")
while i >= 0:
    starts.append(i)
    i = data.find(b"\xed\xa1\xda\x01", i + 28)
middle = starts[len(starts) // 2]
open(sys.argv[2], "wb").write(data[:middle] + bytes(range(100)) + data[middle:])
# the same log without one event, and the log with that event's data length made 0x7ffffff0
after = starts[len(starts) // 2 + 1]
open(sys.argv[3], "wb").write(data[:middle] + data[after:])
open(sys.argv[3] + ".huge", "wb").write(data[:middle + 24] + struct.pack(">I", 0x7FFFFFF0) + data[middle + 28:])
PY
"$filter" --offline "$work/damaged.lcmlog" "$work/damaged_out.lcmlog" 2>"$work/damaged.txt" || fail "exit status on a damaged log"
cat "$work/damaged.txt"
grep -q "is damaged: 100 bytes between its events are no event, skipped" "$work/damaged.txt" || fail "stray bytes not reported"
cmp -s "$work/damaged_out.lcmlog" "$work/a.lcmlog" || fail "stray bytes changed the output"
"$filter" --offline "$work/lost_one.lcmlog" "$work/lost_one_out.lcmlog" 2>/dev/null
"$filter" --offline "$work/lost_one.lcmlog.huge" "$work/huge_out.lcmlog" 2>"$work/huge.txt" || fail "exit status on a 2 GB length"
cat "$work/huge.txt"
grep -q "is damaged: [1-9][0-9]* bytes" "$work/huge.txt" || fail "the bad length was not reported"
cmp -s "$work/huge_out.lcmlog" "$work/lost_one_out.lcmlog" || fail "a bad length lost more than its own event"

# a measurement stamped INT64_MAX with --rate: ends (it used to extrapolate towards it for ever)
"$python" - "$work/raw.lcmlog" "$work/future.lcmlog" "$build/lcmtypes/python" <<'PY'
import sys
import lcm
sys.path.insert(0, sys.argv[3])
from hkf import head_pose_measurement_t
out = lcm.EventLog(sys.argv[2], "w", overwrite=True)
for i, e in enumerate(list(lcm.EventLog(sys.argv[1], "r"))[:20]):
    data = e.data
    if i == 10:
        m = head_pose_measurement_t.decode(data)
        m.utime = 2**63 - 1
        data = m.encode()
    out.write_event(e.timestamp, e.channel, data)
out.close()
PY
timeout 20 "$filter" --offline "$work/future.lcmlog" "$work/future_out.lcmlog" --rate 100 2>"$work/future.txt" \
  || fail "a far-future stamp with --rate: no clean end (exit $?)"
grep -q "1 clock jumps" "$work/future.txt" || fail "the far-future stamp was not rejected as a clock jump"

# bad input: a clear error and a non-zero exit
if "$filter" --offline "$work/missing.lcmlog" "$work/x.lcmlog" 2>"$work/e.txt"; then fail "missing input accepted"; fi
grep -q "missing.lcmlog" "$work/e.txt" || fail "error does not name the file"
if "$filter" --set lc_xi=2 --print-config 2>"$work/e.txt"; then fail "lc_xi=2 accepted"; fi
grep -q "lc_xi" "$work/e.txt" || fail "error does not name lc_xi"
if "$filter" --rate -5 2>/dev/null; then fail "--rate -5 accepted"; fi
grep -q "usage: hkf-filter" <<<"$("$filter" --help)" || fail "--help"
echo "offline_test: all checks passed"
