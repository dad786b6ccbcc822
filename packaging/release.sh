#!/usr/bin/env bash
# ./run release: the Debian package built as Debian builds (prefix /usr, dpkg-buildflags'
# hardening, stripped), checked by lintian (no error and no warning: a warning is fixed, or overridden
# with its reason in debian/lintian-overrides), then installed with apt on a clean Debian 12 root and run there
# (clean_root_test.sh).
# usage: packaging/release.sh SOURCE_DIR BUILD_DIR OUT_DIR
set -euo pipefail
source=$(cd "$1" && pwd) build=$2 out=$3
mkdir -p "$out"
out=$(cd "$out" && pwd)
step() { echo "== release: $*"; }

step "build ($build: prefix /usr, Debian's build flags)"
cmake -S "$source" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DHKF_BUILD_BENCHMARKS=OFF -DHKF_WARNINGS_AS_ERRORS=OFF -DHKF_BUILD_TESTS=OFF \
  "-DCMAKE_C_FLAGS=$(dpkg-buildflags --get CPPFLAGS) $(dpkg-buildflags --get CFLAGS)" \
  "-DCMAKE_CXX_FLAGS=$(dpkg-buildflags --get CPPFLAGS) $(dpkg-buildflags --get CXXFLAGS)" \
  "-DCMAKE_EXE_LINKER_FLAGS=$(dpkg-buildflags --get LDFLAGS)" >"$out/configure.log"
cmake --build "$build" -j "$(nproc)" >"$out/build.log" 2>&1 || { tail -50 "$out/build.log" >&2; exit 1; }

step "package (cpack -G DEB)"
rm -f "$out"/hkf_*.deb
(cd "$build" && cpack -G DEB -B "$out/cpack" >"$out/cpack.log" 2>&1) || { cat "$out/cpack.log" >&2; exit 1; }
mv "$out"/cpack/hkf_*.deb "$out/"
rm -rf "$out/cpack"
deb=$(ls "$out"/hkf_*.deb)
echo "$(basename "$deb"): $(du -k "$deb" | cut -f1) KB"
dpkg-deb --field "$deb" Package Version Depends Recommends

step "lintian"
lintian --info "$deb" >"$out/lintian.txt" 2>&1 || true  # its exit status counts errors and warnings alike
cat "$out/lintian.txt"
errors=$(grep -c '^E:' "$out/lintian.txt" || true)
warnings=$(grep -c '^W:' "$out/lintian.txt" || true)
overridden=$(grep -c '^O:' "$out/lintian.txt" || true)
echo "lintian: $errors errors, $warnings warnings, $overridden overridden (packaging/debian/lintian-overrides)"
[ "$errors" = 0 ] && [ "$warnings" = 0 ] || { echo "release: lintian found errors or warnings" >&2; exit 1; }

step "a clean Debian 12 root: apt-get install ./$(basename "$deb"), then the tracker in it"
"$source/packaging/clean_root_test.sh" "$deb" "$source/../shared/data/videos/d10.mp4" "$out/root"
