#!/usr/bin/env bash
# What an incremental `texproc build` costs on a game-shaped folder of the
# corpus' textures: the full build, a no-op, one job's option edited, an
# input touched without change, and one input's bytes changed; each with
# the files it rebuilt. Medians of RUNS rounds (interleaved).
#
#   bench/bench_recipe_rebuild.sh TEXPROC [CORPUS=../shared/corpus] [RUNS=3]
set -euo pipefail
texproc=$(realpath "$1")
corpus=$(realpath "${2:-$(dirname "$0")/../../shared/corpus}")
runs=${3:-3}
[ -d "$corpus/albedo_srgb" ] || { echo "skip: no corpus at $corpus"; exit 0; }
t=$(mktemp -d /tmp/texproc_recipe_bench.XXXXXX)
trap 'rm -rf "$t"' EXIT
mkdir -p "$t/src"
for d in albedo_srgb alpha normal_ts height photo; do cp -r "$corpus/$d" "$t/src/"; done
write_recipe() {
  cat >"$t/recipe.toml" <<TOML
version = 1
[defaults.compress]
mips = true
[[jobs]]
name = "albedo"
command = "compress"
inputs = "src/albedo_srgb/*.png"
output = "out/desktop/{stem}.dds"
options = { format = "bc7" }
[[jobs]]
name = "albedo-mobile"
command = "compress"
inputs = "src/albedo_srgb/*.png"
output = "out/mobile/{stem}.ktx2"
options = { format = "astc-6x6" }
[[jobs]]
name = "cutouts"
command = "compress"
inputs = ["src/alpha/*.png", "src/alpha/*.tga"]
output = "out/desktop/{stem}.dds"
options = { format = "bc3", transparent-color = "bleed" }
[[jobs]]
name = "normals"
command = "compress"
inputs = "src/normal_ts/*.png"
output = "out/desktop/{stem}.ktx2"
options = { format = "bc5", normal-map = true }
[[jobs]]
name = "heights"
command = "normalmap"
inputs = "src/height/*.png"
output = "out/desktop/{stem}_n.dds"
options = { kernel = "$1", mips = true }
[[jobs]]
name = "photos"
command = "compress"
inputs = "src/photo/*.png"
output = "out/desktop/{stem}.dds"
options = { format = "bc1" }
TOML
}
# build NAME: seconds and files rebuilt
build() {
  local s e
  s=$(date +%s.%N)
  "$texproc" build "$t/recipe.toml" --json >"$t/out.json" 2>"$t/err" || { cat "$t/err"; exit 1; }
  e=$(date +%s.%N)
  python3 - "$1" "$s" "$e" "$t/out.json" <<'PY' >>"$t/results"
import json, sys
name, s, e, path = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
d = json.load(open(path))
print(f"{name}\t{e - s:.3f}\t{d['ok']}\t{d['ok'] + d['skipped']}")
PY
}
: >"$t/results"
first=$(ls "$t/src/photo"/*.png | head -1)
for ((r = 0; r < runs; ++r)); do
  rm -rf "$t/out" "$t"/.recipe.toml.*
  write_recipe sobel3
  build "full build"
  build "no-op"
  write_recipe scharr3
  build "one job's option edited"
  touch "$first"
  build "an input touched, same bytes"
  printf '\0' >>"$first"  # a PNG with a trailing byte: new bytes, same image
  build "one input's bytes changed"
  cp "$corpus/photo/$(basename "$first")" "$first"
done
python3 - "$t/results" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, sec, ok, total = line.rstrip("\n").split("\t")
    rows.setdefault(name, []).append((float(sec), int(ok), int(total)))
print(f"{'build':32} {'median s':>9} {'rebuilt':>8} {'files':>6}")
for name, v in rows.items():
    print(f"{name:32} {statistics.median(x[0] for x in v):9.3f} {v[0][1]:8d} {v[0][2]:6d}")
PY
