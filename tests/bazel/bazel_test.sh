#!/usr/bin/env bash
# texproc's Bazel rules against the real engine (Debian's Bazel 4.2.3):
#  1. samples/bazel builds, and @textures (samples/recipe.toml through
#     texproc_recipe) is byte-identical to `texproc build` of the recipe;
#  2. nginx with WebDAV as --remote_cache: after `bazel clean` every action
#     is a cache hit; a second checkout at another path hits too; a changed
#     input runs exactly one action; a changed texproc binary runs them all;
#  3. Bazel's RemoteWorker, compiled from bazel-bootstrap-source, as
#     --remote_executor: every action runs remotely, the same bytes.
# Servers listen on 127.0.0.1 and are stopped on exit. Exit 77 (skipped)
# where Bazel, nginx or the worker's sources are missing.
#
#   tests/bazel/bazel_test.sh TEXPROC SOURCE_DIR
set -euo pipefail
texproc=$(realpath "$1")
src=$(realpath "$2")
for tool in bazel nginx javac java; do
  command -v "$tool" >/dev/null || { echo "skip: no $tool (scripts/setup.sh installs it)"; exit 77; }
done
worker_src=/usr/src/bazel-bootstrap/src/tools/remote/src/main/java/com/google/devtools/build/remote/worker
[ -d "$worker_src" ] || { echo "skip: no bazel-bootstrap-source"; exit 77; }

t=$(mktemp -d /tmp/texproc_bazel.XXXXXX)
pids=()
roots=()
cleanup() {
  for r in "${roots[@]}"; do (cd "$t/a/samples/bazel" && bazel --output_user_root="$r" shutdown) >/dev/null 2>&1 || true; done
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  [ -f "$t/nginx/nginx.pid" ] && kill "$(cat "$t/nginx/nginx.pid")" 2>/dev/null || true
  chmod -R u+w "$t" 2>/dev/null || true
  rm -rf "$t"
}
trap cleanup EXIT
fail() { echo "FAIL: $*"; exit 1; }
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

# A checkout: the samples and the rules, as in the source tree.
checkout() {
  mkdir -p "$1"
  cp -r "$src/samples" "$src/bazel" "$1/"
  rm -rf "$1"/samples/bazel/bazel-*
}
checkout "$t/a"
export TEXPROC="$texproc"
root="$t/root"
roots+=("$root")
# bazel ARGS...: in checkout $dir, its output printed to $t/log.
dir="$t/a"
bz() {
  (cd "$dir/samples/bazel" && bazel --output_user_root="$root" "$@" --color=no --curses=no --noshow_progress) >"$t/log" 2>&1 ||
    { cat "$t/log"; fail "bazel $*"; }
}
# How many actions the last build ran in each way ("remote cache hit", "processwrapper-sandbox", "remote").
count() { grep -o "[0-9]* $1[,.]" "$t/log" | head -1 | grep -o "^[0-9]*" || echo 0; }
outputs="textures/albedo_desert_512.dds textures/cutout_fence_512x256.dds textures/normal_stein_256.ktx2
  textures/mobile/albedo_desert_512.ktx2 textures/height_mount_250_n.dds textures/height_stein_256_n.dds
  textures/height_stein_256_cones.png previews/height_stein_256_cones_preview.png env/sky_forest_512x256.ktx2
  env/sky_forest_512x256_specular.ktx2 env/sky_forest_512x256_specular_irradiance.ktx2"
same_as_build() {
  for f in $outputs; do
    cmp -s "$dir/samples/bazel/bazel-bin/external/textures/$f" "$t/ref/$f" || fail "$1: $f differs from texproc build"
  done
}
"$texproc" build "$t/a/samples/recipe.toml" --out-dir "$t/ref" -q
actions=12  # 9 from the recipe, 3 in samples/bazel/BUILD.bazel

echo "== 1. the rules build the samples"
bz build //... @textures//:textures
[ -f "$t/a/samples/bazel/bazel-bin/cooked/albedo_desert_512_bc7.dds" ] || fail "no albedo_desert_512_bc7.dds"
[ -f "$t/a/samples/bazel/bazel-bin/cooked/height_stein_256_n.dds" ] || fail "no height_stein_256_n.dds"
same_as_build "local build"
"$texproc" compress "$t/a/samples/albedo_desert_512.png" -o "$t/bc7.dds" --format bc7 --mips -q
cmp -s "$t/bc7.dds" "$t/a/samples/bazel/bazel-bin/cooked/albedo_desert_512_bc7.dds" || fail "texproc_texture differs"

echo "== 2. nginx (WebDAV) as the remote cache"
mkdir -p "$t/nginx/tmp" "$t/cache"
port=$(free_port)
{
  [ "$(id -u)" = 0 ] && echo "user root root;"
  cat <<CONF
worker_processes 1;
pid $t/nginx/nginx.pid;
error_log $t/nginx/error.log;
events {}
http {
  access_log $t/nginx/access.log;
  client_body_temp_path $t/nginx/tmp;
  proxy_temp_path $t/nginx/tmp;
  fastcgi_temp_path $t/nginx/tmp;
  uwsgi_temp_path $t/nginx/tmp;
  scgi_temp_path $t/nginx/tmp;
  server {
    listen 127.0.0.1:$port;
    root $t/cache;
    client_max_body_size 0;
    location / {
      dav_methods PUT;
      create_full_put_path on;
    }
  }
}
CONF
} >"$t/nginx/nginx.conf"
nginx -p "$t/nginx" -c "$t/nginx/nginx.conf" -e "$t/nginx/error.log"
cache="--remote_cache=http://127.0.0.1:$port"
bz clean
bz build //... @textures//:textures "$cache"
[ "$(count processwrapper-sandbox)" = $actions ] || { cat "$t/log"; fail "first build: expected $actions actions run"; }
bz clean
bz build //... @textures//:textures "$cache"
[ "$(count 'remote cache hit')" = $actions ] || { cat "$t/log"; fail "after clean: expected $actions cache hits"; }
[ "$(count processwrapper-sandbox)" = 0 ] || { cat "$t/log"; fail "after clean: actions ran"; }
same_as_build "from the cache"
echo "after bazel clean: $actions of $actions actions were cache hits"
# A second checkout at another path, with its own output base.
checkout "$t/b/elsewhere"
dir="$t/b/elsewhere"
bz build //... @textures//:textures "$cache"
[ "$(count 'remote cache hit')" = $actions ] || { cat "$t/log"; fail "second checkout: expected $actions cache hits"; }
same_as_build "second checkout"
echo "second checkout: $actions of $actions actions were cache hits"
# One changed input: one action.
cp "$dir/samples/normal_stein_256.png" "$dir/samples/cutout_fence_512x256.png"
bz build //... @textures//:textures "$cache"
[ "$(count processwrapper-sandbox)" = 1 ] || { cat "$t/log"; fail "one changed input: expected 1 action run"; }
echo "one changed input: 1 action ran"
# Another texproc binary (one byte more): every action runs again.
mkdir -p "$t/tool2"
for f in $("$texproc" --runtime-files); do cp "$f" "$t/tool2/"; done
printf '\0' >>"$t/tool2/$(basename "$texproc")"
TEXPROC="$t/tool2/$(basename "$texproc")" bz build //... @textures//:textures "$cache"
[ "$(count processwrapper-sandbox)" = $actions ] || { cat "$t/log"; fail "changed texproc: expected $actions actions run"; }
echo "changed texproc binary: $actions actions ran"
kill "$(cat "$t/nginx/nginx.pid")"

echo "== 3. Bazel's RemoteWorker as the remote executor"
dir="$t/a"
cp=/usr/share/bazel/A-server.jar:$(ls /usr/share/java/*.jar | tr '\n' ':')
mkdir -p "$t/worker/classes" "$t/worker/work" "$t/worker/cas"
javac -nowarn -d "$t/worker/classes" -cp "$cp" $(find "$worker_src" -name '*.java') 2>"$t/javac.log" ||
  { cat "$t/javac.log"; fail "javac RemoteWorker"; }
wport=$(free_port)
java -cp "$t/worker/classes:$cp" com.google.devtools.build.remote.worker.RemoteWorker --listen_port="$wport" \
  --work_path="$t/worker/work" --cas_path="$t/worker/cas" >"$t/worker/log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do grep -q "Starting gRPC server" "$t/worker/log" && break; sleep 0.2; done
bz clean
bz build //... @textures//:textures --remote_executor="grpc://127.0.0.1:$wport" --spawn_strategy=remote
[ "$(count remote)" = $actions ] || { cat "$t/log"; fail "expected $actions actions run remotely"; }
same_as_build "remote execution"
echo "remote execution: $actions actions ran on the worker, the same bytes"
echo "PASS"
