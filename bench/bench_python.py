#!/usr/bin/python3
"""What the Python package costs over C++: `import texproc` against Python's
own start, and the same library call made from Python and from C++
(bench_calls) on the same pixels, in interleaved rounds; medians and ratios.

  bench/bench_python.py [--build build] [--rounds 5] [--reps 3] [--python /usr/bin/python3]

Calls: a 2048x2048 BC7 encode (texproc.compress(image, "bc7_srgb")) and a
4096x4096 mip chain (texproc.generate_mips(image)), each RGB8 from the
corpus (../shared/corpus; the 4096x4096 image is the 4096x2048 starfield
twice). Each round starts one C++ and one Python process; each warms up
with one call and times --reps calls.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CORPUS = os.path.join(ROOT, "..", "shared", "corpus")

PY_CALL = r"""
import sys, time
import texproc
image = texproc.read_image(sys.argv[2])
call = (lambda: texproc.compress(image, "bc7_srgb")) if sys.argv[1] == "bc7" else (lambda: texproc.generate_mips(image))
call()
for _ in range(int(sys.argv[3])):
    t = time.perf_counter()
    call()
    print("%.3f" % ((time.perf_counter() - t) * 1000.0))
"""


def times(cmd, env):
    out = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if out.returncode != 0:
        sys.exit(f"bench_python: {' '.join(cmd)} failed:\n{out.stderr}")
    return [float(line) for line in out.stdout.split()]


def start_ms(python, code, env):
    t = time.perf_counter()
    subprocess.run([python, "-c", code], env=env, check=True, stdout=subprocess.DEVNULL)
    return (time.perf_counter() - t) * 1000.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--python", default="/usr/bin/python3")
    args = ap.parse_args()
    build = os.path.abspath(args.build)
    calls_exe = os.path.join(build, "bench", "bench_calls")
    env = dict(os.environ, PYTHONPATH=os.path.join(build, "python"))
    for need in (calls_exe, os.path.join(build, "python", "texproc")):
        if not os.path.exists(need):
            sys.exit(f"bench_python: {need} is missing (build with benchmarks and TEXPROC_BUILD_PYTHON)")
    src_2k = os.path.join(CORPUS, "albedo_srgb", "wz2100_backdrop0_2048.png")
    src_4k = os.path.join(CORPUS, "albedo_srgb", "qt3d_galaxy_starfield_4096x2048.jpg")
    if not (os.path.exists(src_2k) and os.path.exists(src_4k)):
        print("bench_python: corpus images missing; skipped")
        return 0

    # Start-up: Python alone and Python importing texproc, alternated.
    plain, imported = [], []
    for _ in range(max(20, args.rounds * 4)):
        plain.append(start_ms(args.python, "pass", env))
        imported.append(start_ms(args.python, "import texproc", env))
    p, i = statistics.median(plain), statistics.median(imported)
    print(f"start-up: python {p:.1f} ms, python + import texproc {i:.1f} ms, import adds {i - p:.1f} ms"
          f" (median of {len(plain)} each)")

    with tempfile.TemporaryDirectory() as work:
        big = os.path.join(work, "starfield_4096x4096.png")
        subprocess.run([args.python, "-c",
                        "import sys, numpy, texproc; a = texproc.read_image(sys.argv[1]);"
                        " texproc.write_image(sys.argv[2], numpy.concatenate([a, a]))", src_4k, big],
                       env=env, check=True)
        print(f"{'call':<34}{'C++ ms':>10}{'Python ms':>11}{'Python / C++':>14}")
        for name, op, path in (("BC7 normal, 2048x2048", "bc7", src_2k), ("mip chain, 4096x4096", "mips", big)):
            cpp, py = [], []
            for r in range(args.rounds):  # which goes first alternates
                runs = [(cpp, [calls_exe, op, path, str(args.reps)]),
                        (py, [args.python, "-c", PY_CALL, op, path, str(args.reps)])]
                for into, cmd in runs if r % 2 == 0 else runs[::-1]:
                    into += times(cmd, env)
            c, q = statistics.median(cpp), statistics.median(py)
            print(f"{name:<34}{c:>10.1f}{q:>11.1f}{q / c:>14.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
