#!/usr/bin/python3
"""Every C++ source of the tree (git's tracked .cpp and .h files) is
formatted as .clang-format says (clang-format 14, Debian 12's). Exit 1
naming each file that is not, with the first lines clang-format would
change; `clang-format -i FILE` fixes it. Run by ctest (Format.Sources).

  tests/tools/check_format.py [SOURCE_DIR]
  tests/tools/check_format.py --self-test   (an unformatted file must fail)
"""
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else os.path.dirname(
    os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def clang_format():
    for name in ("clang-format-14", "clang-format"):
        path = shutil.which(name)
        if path:
            return path
    print("check_format: no clang-format (scripts/setup.sh installs it)")
    sys.exit(77)


def sources(root):
    listed = subprocess.run(["git", "-C", root, "ls-files", "*.cpp", "*.h"], capture_output=True, text=True)
    if listed.returncode != 0:  # not a git checkout: every source under the tree's folders
        found = []
        for top in ("libtexproc", "cli", "tests", "bench", "python"):
            for d, _, files in os.walk(os.path.join(root, top)):
                found += [os.path.relpath(os.path.join(d, f), root) for f in files if f.endswith((".cpp", ".h"))]
        return sorted(found)
    return [f for f in listed.stdout.splitlines() if f]


def check(root, files):
    tool = clang_format()
    broken = []
    for f in files:
        path = os.path.join(root, f)
        if not os.path.exists(path):
            continue
        r = subprocess.run([tool, "--dry-run", "--Werror", "--style=file", path], capture_output=True, text=True,
                           cwd=root)
        if r.returncode != 0:
            first = [l for l in r.stderr.splitlines() if "error:" in l][:3]
            broken.append((f, first))
    for f, lines in broken:
        print(f"{f}: not formatted (clang-format -i {f})")
        for l in lines:
            print("  " + l.replace(root + "/", ""))
    print(f"check_format: {len(files)} files, {len(broken)} not formatted")
    return 1 if broken else 0


def self_test():
    with tempfile.TemporaryDirectory() as d:
        shutil.copy(os.path.join(ROOT, ".clang-format"), d)
        with open(os.path.join(d, "good.cpp"), "w") as f:
            f.write("int f(int a) { return a + 1; }\n")
        with open(os.path.join(d, "bad.cpp"), "w") as f:
            f.write("int  f(int a){return a+1;}\n")
        if check(d, ["good.cpp"]) != 0:
            print("self-test: a formatted file was refused")
            return 1
        if check(d, ["bad.cpp"]) != 1:
            print("self-test: an unformatted file passed")
            return 1
    print("self-test: ok")
    return 0


if __name__ == "__main__":
    sys.exit(self_test() if "--self-test" in sys.argv else check(ROOT, sources(ROOT)))
