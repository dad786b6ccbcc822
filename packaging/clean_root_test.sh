#!/usr/bin/env bash
# The package where a user installs it: a minimal Debian 12 root made by mmdebstrap from Debian's
# packages, `apt-get install ./hkf_*.deb` in it (apt resolves the Depends and Recommends), and then,
# inside that root and in a private network namespace (no traffic leaves the machine):
#   - every program answers --version and --help, with no Python module beyond Debian's;
#   - the filter's settings come from the conffile /etc/hkf/hkf-filter.conf (--print-config says so);
#   - `hkf-track --source clip.mp4 --opentrack` runs the whole tracker on a clip and a UDP receiver
#     (opentrack's stand-in) gets its datagrams, and with --view its live view serves the page (curl);
#   - hkf-spy's class path resolves to files that exist.
# Needs root (chroot, mounts, unshare) and Debian's mirror; exits 77 (skipped) without them.
# usage: clean_root_test.sh DEB CLIP ROOT_DIR
set -euo pipefail
deb=$(realpath "$1") clip=$(realpath "$2") root=$3
here=$(cd "$(dirname "$0")" && pwd)
fail() { echo "FAIL: $*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || { echo "SKIP: needs root (chroot)"; exit 77; }
command -v mmdebstrap >/dev/null || { echo "SKIP: no mmdebstrap (apt-get install mmdebstrap)"; exit 77; }
[ -s "$clip" ] || { echo "SKIP: no $clip"; exit 77; }

cleanup() {
  for m in proc dev/pts dev sys; do umount -l "$root/$m" 2>/dev/null || true; done
}
trap cleanup EXIT
cleanup
rm -rf "$root"
start=$SECONDS
mmdebstrap --quiet --variant=apt --mode=root bookworm "$root" http://deb.debian.org/debian \
  || fail "mmdebstrap could not make a Debian 12 root"
echo "clean root: Debian $(cat "$root/etc/debian_version"), $(du -sm "$root" | cut -f1) MB, $((SECONDS - start)) s"
mount -t proc proc "$root/proc"
mount --bind /dev "$root/dev"
mount --bind /dev/pts "$root/dev/pts"
mount -t sysfs sys "$root/sys"
cp "$deb" "$clip" "$root/tmp/"
in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root "$@"; }

start=$SECONDS
in_root apt-get update -qq
in_root sh -c "DEBIAN_FRONTEND=noninteractive apt-get install -y -qq /tmp/$(basename "$deb") >/tmp/apt.log 2>&1" \
  || { tail -30 "$root/tmp/apt.log"; fail "apt-get install ./$(basename "$deb")"; }
echo "apt-get install ./$(basename "$deb"): $((SECONDS - start)) s, $(in_root dpkg -l | grep -c '^ii') packages in the root"

python_modules=$(in_root sh -c 'command -v python3 >/dev/null && python3 -c "import lcm" 2>/dev/null && echo lcm || true')
[ -z "$python_modules" ] || fail "the root has Python's lcm module: the test would not show hkf-track needs none"
programs=(hkf-estimator hkf-annotate hkf-filter hkf-opentrack hkf-track hkf-cmd hkf-demo hkf-simlog hkf-spy hkf-view)
for p in "${programs[@]}"; do
  in_root "$p" --version >"$root/tmp/version.txt" 2>&1 || fail "$p --version: $(cat "$root/tmp/version.txt")"
  grep -q "^$p " "$root/tmp/version.txt" || fail "$p --version printed $(cat "$root/tmp/version.txt")"
  in_root "$p" --help >"$root/tmp/help.txt" 2>&1 || fail "$p --help"
  grep -qi usage "$root/tmp/help.txt" || fail "$p --help printed no usage"
  in_root man -w "$p" >/dev/null 2>&1 || [ -s "$root/usr/share/man/man1/$p.1.gz" ] || fail "no man page for $p"
done
echo "${#programs[@]} programs answer --version and --help, each with a man page; python3 $(in_root sh -c 'command -v python3 || echo absent')"

[ -f "$root/etc/hkf/hkf-filter.conf" ] || fail "no /etc/hkf/hkf-filter.conf"
in_root dpkg-query --showformat='${Conffiles}\n' --show hkf | grep -q /etc/hkf/hkf-filter.conf || fail "/etc/hkf/hkf-filter.conf is not a conffile"
in_root hkf-filter --print-config >"$root/tmp/config.txt"
grep -q "^lc_theta .*# /etc/hkf/hkf-filter.conf:[0-9]*;" "$root/tmp/config.txt" || fail "hkf-filter does not read /etc/hkf"
echo "hkf-filter reads the conffile: $(grep -c '# /etc/hkf/hkf-filter.conf' "$root/tmp/config.txt") values from /etc/hkf/hkf-filter.conf"

for entry in $(in_root hkf-spy --print-class-path | tr ':' ' '); do
  [ -f "$root$entry" ] || fail "hkf-spy's class path names $entry, which the root does not have"
done
echo "hkf-spy's class path resolves: $(in_root hkf-spy --print-class-path)"

# the whole tracker on a clip, to a UDP receiver, in a private network namespace
work=$(mktemp -d)
unshare --net bash -c '
  set -euo pipefail
  ip link set lo up; ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo
  python3 "$1/../tests/opentrack/udp_receiver.py" "$2/udp.hex" --port 4242 --seconds 300 2>"$2/receiver.txt" &
  receiver=$!
  for _ in $(seq 50); do [ -e "$2/udp.hex.ready" ] && break; sleep 0.1; done
  # the live view too: its page fetched with curl while the clip plays (the .deb installs it)
  ( for _ in $(seq 600); do curl -sf -o "$2/view.html" http://127.0.0.1:7670/ && break; sleep 0.05; done ) &
  fetch=$!
  chroot "$3" /usr/bin/env -i PATH=/usr/bin:/bin HOME=/root sh -c "cd /tmp && hkf-track --source /tmp/$4 --opentrack --view 7670" \
    >"$2/track.txt" 2>&1 || { cat "$2/track.txt"; exit 1; }
  wait "$fetch" || true
  kill -TERM "$receiver"; wait "$receiver" || true
' _ "$here" "$work" "$root" "$(basename "$clip")" || fail "hkf-track in the clean root"
tail -5 "$work/track.txt"
grep -q "the source ended" "$work/track.txt" || fail "hkf-track did not run to the clip's end"
received=$(wc -l <"$work/udp.hex")
grep -q 'name="hkf-token" content="[0-9a-f]\{32\}"' "$work/view.html" 2>/dev/null ||
  { rm -rf "$work"; fail "the live view's page (share/hkf/view) was not served from the installed package"; }
rm -rf "$work"
[ "$received" -ge 100 ] || fail "only $received datagrams reached the UDP receiver"
echo "clean_root_test: passed (hkf-track in the clean root sent $received datagrams to the UDP receiver; its live view served the page)"
