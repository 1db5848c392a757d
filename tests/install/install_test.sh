#!/usr/bin/env bash
# Install.ConsumerProject: texproc installed into a temporary prefix and used
# from there as a user would. Checks: the installed files hold no path of the
# build tree; a CMake project (find_package) and a Makefile-style build
# (pkg-config) compile against the installed headers and library and run
# (a mip chain, BC1 and an OpenEXR file through the installed module); the
# installed Python package reads an EXR and compresses as the tool does; the
# installed texproc runs a sample, also from a copy of the prefix moved
# elsewhere (modules found relative to the binary).
#   tests/install/install_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
BUILD=$(cd "$1" && pwd)
SRC=$(cd "$2" && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/texproc_install.XXXXXX")
trap 'rm -rf "$WORK"' EXIT
PREFIX=$WORK/prefix
fail() { echo "FAIL: $*" >&2; exit 1; }
unset TEXPROC_MODULE_DIR TEXPROC_EXR_MODULE TEXPROC_OIIO_MODULE TEXPROC_OCIO_MODULE

cmake --install "$BUILD" --prefix "$PREFIX" >"$WORK/install.log" || { cat "$WORK/install.log"; fail "cmake --install"; }
for f in bin/texproc include/texproc/mip.h include/texproc/version.h; do
  [ -e "$PREFIX/$f" ] || fail "$f not installed"
done
LIBDIR=$(dirname "$(find "$PREFIX" -name libtexproc.a | head -1)")
[ -n "$LIBDIR" ] || fail "libtexproc.a not installed"
for m in texproc_exr.so texproc_oiio.so texproc_ocio.so; do
  [ -e "$LIBDIR/texproc/$m" ] || fail "module $m not in $LIBDIR/texproc"
done
[ -e "$LIBDIR/cmake/texproc/texprocConfig.cmake" ] || fail "texprocConfig.cmake not installed"
[ -e "$LIBDIR/pkgconfig/texproc.pc" ] || fail "texproc.pc not installed"
# No installed file may name the build tree (where modules or data would be looked for).
if grep -rlF "$BUILD" "$PREFIX" >"$WORK/named"; then
  cat "$WORK/named" >&2
  fail "installed files name the build folder $BUILD"
fi

# 1. CMake: find_package(texproc).
cmake -S "$SRC/tests/install/consumer" -B "$WORK/cmake_consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$PREFIX" >"$WORK/configure.log" 2>&1 || { cat "$WORK/configure.log"; fail "find_package(texproc)"; }
cmake --build "$WORK/cmake_consumer" >"$WORK/build.log" 2>&1 || { cat "$WORK/build.log"; fail "building the CMake consumer"; }
# A program of one's own, not installed in the prefix, names the module folder.
TEXPROC_MODULE_DIR="$LIBDIR/texproc" "$WORK/cmake_consumer/consumer" "$WORK/level1.exr" || fail "the CMake consumer"

# 2. pkg-config, as a Makefile would.
export PKG_CONFIG_PATH="$LIBDIR/pkgconfig"
c++ -std=c++20 -O1 $(pkg-config --cflags texproc) "$SRC/tests/install/consumer/consumer.cpp" \
  -o "$WORK/pc_consumer" $(pkg-config --libs texproc) || fail "building against pkg-config texproc"
TEXPROC_MODULE_DIR="$LIBDIR/texproc" "$WORK/pc_consumer" "$WORK/level1_pc.exr" || fail "the pkg-config consumer"

# 3. The Python package (where the build has it), in place and below.
PYEXT=$(find "$PREFIX" -name '_texproc*.so' | head -1)
py_check() {  # site-packages folder, output file
  env -u PYTHONPATH PYTHONPATH="$1" /usr/bin/python3 -c "
import sys, texproc
assert texproc.__file__.startswith(sys.argv[1]), texproc.__file__
sky = texproc.read_image(sys.argv[2])      # OpenEXR: the module beside the extension
t = texproc.compress(texproc.read_image(sys.argv[3]), 'bc7_srgb', mips=True)
open(sys.argv[4], 'wb').write(t.to_bytes('ktx2'))
" "$1" "$SRC/samples/sky_forest_512x256.exr" "$SRC/samples/albedo_desert_512.png" "$2"
}
if [ -n "$PYEXT" ]; then
  SITE=$(dirname "$(dirname "$PYEXT")")
  SITE_REL=${SITE#"$PREFIX"/}
  py_check "$SITE" "$WORK/py.ktx2" || fail "the installed Python package"
  "$PREFIX/bin/texproc" compress "$SRC/samples/albedo_desert_512.png" -o "$WORK/cli.ktx2" --format bc7 --mips -q
  cmp -s "$WORK/py.ktx2" "$WORK/cli.ktx2" || fail "the installed Python package and texproc wrote other bytes"
fi

# 4. The installed tool, in place and moved (modules relative to the binary).
"$PREFIX/bin/texproc" --version | grep -q "^texproc " || fail "texproc --version"
"$PREFIX/bin/texproc" mip "$SRC/samples/albedo_desert_512.png" -o "$WORK/a.exr" -q || fail "installed texproc mip -> .exr"
mv "$PREFIX" "$WORK/moved"
"$WORK/moved/bin/texproc" mip "$SRC/samples/albedo_desert_512.png" -o "$WORK/b.exr" -q ||
  fail "texproc moved to another prefix: mip -> .exr"
cmp -s "$WORK/a.exr" "$WORK/b.exr" || fail "the moved texproc wrote other bytes"
if [ -n "$PYEXT" ]; then
  py_check "$WORK/moved/$SITE_REL" "$WORK/py_moved.ktx2" || fail "the Python package moved to another prefix"
  cmp -s "$WORK/py.ktx2" "$WORK/py_moved.ktx2" || fail "the moved Python package wrote other bytes"
fi
# --module-dir names a folder; a folder without the modules is an error naming what was tried.
if "$WORK/moved/bin/texproc" --module-dir "$WORK" mip "$SRC/samples/albedo_desert_512.png" -o "$WORK/c.exr" -q \
    2>"$WORK/err"; then
  fail "--module-dir without the modules succeeded"
fi
grep -q "texproc_exr.so" "$WORK/err" || { cat "$WORK/err"; fail "the error does not name the module"; }
[ ! -e "$WORK/c.exr" ] || fail "a failed run left c.exr"
"$WORK/moved/bin/texproc" --module-dir "$(dirname "$(find "$WORK/moved" -name texproc_exr.so -not -path '*-packages*' | head -1)")" \
  mip "$SRC/samples/albedo_desert_512.png" -o "$WORK/d.exr" -q || fail "--module-dir with the modules"
echo "install, find_package, pkg-config and relocation: ok"
