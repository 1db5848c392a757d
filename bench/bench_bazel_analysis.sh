#!/usr/bin/env bash
# How long Bazel takes to load and analyse a content build of N textures
# declared with texproc's rules (texproc_textures: one action per texture),
# from a started server with no analysis cache: what every build of a large
# project pays before its first action. Prints each run and the median.
#
#   bench/bench_bazel_analysis.sh TEXPROC [TEXTURES=20000] [RUNS=3]
set -euo pipefail
texproc=$(realpath "$1")
n=${2:-20000}
runs=${3:-3}
src=$(cd "$(dirname "$0")/.." && pwd)
command -v bazel >/dev/null || { echo "no bazel (scripts/setup.sh installs bazel-bootstrap)"; exit 1; }
t=$(mktemp -d /tmp/texproc_bazel_bench.XXXXXX)
root="$t/root"
trap '(cd "$t/ws" && bazel --output_user_root="$root" shutdown) >/dev/null 2>&1 || true; rm -rf "$t"' EXIT
mkdir -p "$t/ws"
cp -r "$src/bazel" "$t/rules"
cat >"$t/ws/WORKSPACE" <<WS
local_repository(name = "texproc_rules", path = "$t/rules")
load("@texproc_rules//:texproc.bzl", "texproc_tool_repository")
texproc_tool_repository(name = "texproc", texproc = "$texproc")
WS
echo "build --spawn_strategy=processwrapper-sandbox" >"$t/ws/.bazelrc"
# N textures in packages of 1,000 (an asset tree's folders), each a small file.
per=1000
for ((p = 0; p * per < n; ++p)); do
  d="$t/ws/textures/set$p"
  mkdir -p "$d"
  count=$((n - p * per < per ? n - p * per : per))
  (cd "$d" && seq -f "t%05g.png" 0 $((count - 1)) | xargs touch)
  cat >"$d/BUILD.bazel" <<BUILD
load("@texproc_rules//:texproc.bzl", "texproc_textures")
texproc_textures(
    name = "textures",
    srcs = glob(["*.png"]),
    out_dir = "cooked",
    extension = ".dds",
    args = ["--format", "bc7", "--mips"],
)
BUILD
done
cd "$t/ws"
bz() { bazel --output_user_root="$root" "$@"; }
bz build --nobuild //... >/dev/null 2>&1  # fetch the repositories once
times=()
for ((r = 0; r < runs; ++r)); do
  bz shutdown >/dev/null 2>&1
  bz info >/dev/null 2>&1  # a started server, nothing loaded
  start=$(date +%s.%N)
  bz build --nobuild //... >"$t/log" 2>&1 || { cat "$t/log"; exit 1; }
  end=$(date +%s.%N)
  s=$(python3 -c "print(f'{$end - $start:.2f}')")
  targets=$(grep -o "Analyzed [0-9]* targets" "$t/log" | grep -o "[0-9]*")
  echo "run $((r + 1)): $targets targets loaded and analysed in $s s"
  times+=("$s")
done
median=$(printf '%s\n' "${times[@]}" | sort -n | sed -n "$(((runs + 1) / 2))p")
echo "median: $median s for $n textures ($(nproc) cores; Bazel $(dpkg-query -W -f '${Version}' bazel-bootstrap 2>/dev/null || bazel --version))"
