#!/usr/bin/python3
"""The project speaks of the software alone: no file of the tree (docs,
README, sources, scripts, tests) refers to how the work on it was organised
(numbered work periods, tracker tickets and their goals). Design history
belongs in commit messages or docs/design/, told as what changed and why.
Run by ctest (Docs.SpeakOfTheSoftware).

  tests/tools/check_wording.py [SOURCE_DIR]
  tests/tools/check_wording.py --self-test
"""
import os
import re
import sys

PATTERNS = [
    re.compile(r"\bsessions? \d+", re.I),
    re.compile(r"\b(this|last|previous|next|earlier) session\b", re.I),
    re.compile(r"\bsession's\b", re.I),
    re.compile(r"\bissues? #?\d+", re.I),
    re.compile(r"\bthe (\w+ )?issues?'s?\b(?! tracker)", re.I),
]
EXTENSIONS = (".md", ".cpp", ".h", ".hpp", ".py", ".sh", ".txt", ".cmake", ".in", ".toml", ".json", ".bzl")
SKIP_DIRS = {".git", "node_modules", "out"}


def problems(name, text):
    out = []
    for n, line in enumerate(text.split("\n"), 1):
        for p in PATTERNS:
            m = p.search(line)
            if m:
                out.append(f"{name}:{n}: '{m.group(0)}' (describe the software, not the work on it)")
                break
    return out


def scan(root):
    found = []
    for d, dirs, files in os.walk(root):
        dirs[:] = [x for x in dirs if x not in SKIP_DIRS and not x.startswith("build")]
        for f in files:
            if not f.endswith(EXTENSIONS) or f == os.path.basename(__file__):
                continue
            path = os.path.join(d, f)
            with open(path, encoding="utf-8", errors="replace") as fh:
                found += problems(os.path.relpath(path, root), fh.read())
    return found


def self_test():
    # The phrases are assembled here so that this file does not hold them.
    w, t = "sess" + "ion", "iss" + "ue"
    bad = [f"Measured in {w} 18 on two cores.", f"As {t} 21 asks,", f"the {t}'s target: 30x",
           f"this {w}'s run", f"Against the ETC {t}'s targets"]
    good = ["SessionOptions s = session_options();", "a KTX2 issue tracker link", "the session options",
            "texproc issues an error"]
    for b in bad:
        assert problems("x", b), b
    for g in good:
        assert not problems("x", g), (g, problems("x", g))
    print("self-test passed")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return 0
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "..")
    found = scan(root)
    for f in found:
        print(f)
    print(f"{len(found)} reference(s) to how the work was organised" if found else "no file refers to how the work was organised")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
