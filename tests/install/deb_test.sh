#!/usr/bin/env bash
# Package.Deb: `cpack -G DEB` of a build, checked as a user of Debian 12
# would meet it: the files it installs (tool, library, headers, CMake and
# pkg-config files, runtime modules, Python package), the dependencies it
# declares (read off the binaries, and resolvable by apt on this system),
# and the tool and the Python package run from the unpacked tree, writing
# the same bytes.
#   tests/install/deb_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
BUILD=$(cd "$1" && pwd)
SRC=$(cd "$2" && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/texproc_deb.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
unset TEXPROC_MODULE_DIR TEXPROC_EXR_MODULE TEXPROC_OIIO_MODULE TEXPROC_OCIO_MODULE

(cd "$WORK" && cpack -G DEB --config "$BUILD/CPackConfig.cmake" -B "$WORK/out" >"$WORK/cpack.log" 2>&1) ||
  { cat "$WORK/cpack.log"; fail "cpack -G DEB"; }
DEB=$(find "$WORK/out" -maxdepth 1 -name 'texproc_*.deb' | head -1)
[ -n "$DEB" ] || fail "no texproc_*.deb made"

dpkg-deb -c "$DEB" | awk '{print $6}' >"$WORK/files"
need() { grep -Eq "$1" "$WORK/files" || fail "the package has no $1"; }
need '^\./usr/bin/texproc$'
need '^\./usr/lib/(x86_64-linux-gnu/)?libtexproc\.a$'
need '^\./usr/include/texproc/mip\.h$'
need '^\./usr/include/texproc/version\.h$'
need '^\./usr/lib/(x86_64-linux-gnu/)?cmake/texproc/texprocConfig\.cmake$'
need '^\./usr/lib/(x86_64-linux-gnu/)?pkgconfig/texproc\.pc$'
for m in exr oiio ocio; do need "^\./usr/lib/(x86_64-linux-gnu/)?texproc/texproc_$m\.so$"; done
need '^\./usr/share/doc/texproc/LICENSE$'
HAS_PYTHON=0
if grep -q '^TEXPROC_BUILD_PYTHON:BOOL=ON' "$BUILD/CMakeCache.txt"; then
  HAS_PYTHON=1
  need '^\./usr/lib/python3/dist-packages/texproc/__init__\.py$'
  need '^\./usr/lib/python3/dist-packages/texproc/__init__\.pyi$'
  need '^\./usr/lib/python3/dist-packages/texproc/_texproc\..*\.so$'
fi

DEPENDS=$(dpkg-deb -f "$DEB" Depends)
for d in libc6 libstdc++6 libtbb12 libhwy1 libspng0 libopenexr libopenimageio libopencolorio; do
  echo "$DEPENDS" | grep -q "$d" || fail "Depends does not name $d: $DEPENDS"
done
[ "$HAS_PYTHON" = 0 ] || echo "$DEPENDS" | grep -q "python3-numpy" || fail "Depends does not name python3-numpy"
# Every declared dependency resolves from this system's Debian archive.
if command -v apt-get >/dev/null; then
  apt-get install -s -q "$DEB" >"$WORK/apt.log" 2>&1 || { cat "$WORK/apt.log"; fail "apt cannot install the package"; }
fi

# The unpacked tree works where it lies: modules beside or relative to each binary.
dpkg-deb -x "$DEB" "$WORK/root"
"$WORK/root/usr/bin/texproc" --version | grep -q "^texproc " || fail "texproc --version"
"$WORK/root/usr/bin/texproc" mip "$SRC/samples/albedo_desert_512.png" -o "$WORK/a.exr" -q || fail "texproc mip -> .exr"
"$WORK/root/usr/bin/texproc" compress "$SRC/samples/albedo_desert_512.png" -o "$WORK/cli.ktx2" --format bc7 --mips -q
if [ "$HAS_PYTHON" = 1 ]; then
  env -u PYTHONPATH PYTHONPATH="$WORK/root/usr/lib/python3/dist-packages" /usr/bin/python3 -c "
import sys, texproc
assert texproc.__file__.startswith(sys.argv[1]), texproc.__file__
texproc.read_image(sys.argv[2])
t = texproc.compress(texproc.read_image(sys.argv[3]), 'bc7_srgb', mips=True)
open(sys.argv[4], 'wb').write(t.to_bytes('ktx2'))
" "$WORK/root" "$SRC/samples/sky_forest_512x256.exr" "$SRC/samples/albedo_desert_512.png" "$WORK/py.ktx2" ||
    fail "the packaged Python package"
  cmp -s "$WORK/py.ktx2" "$WORK/cli.ktx2" || fail "the packaged Python package and tool wrote other bytes"
fi
echo "deb: $(basename "$DEB"), $(wc -l <"$WORK/files") entries; files, dependencies and the unpacked tree: ok"
