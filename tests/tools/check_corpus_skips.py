#!/usr/bin/python3
"""One rule for every test that reads ../shared/corpus: its body checks
have_corpus() (and skips with GTEST_SKIP when the corpus is absent) before
it names a corpus file. Checked on tests/**/*.cpp: a TEST body that mentions
corpus_dir() or TEXPROC_CORPUS_DIR without have_corpus() fails, naming the
test. Run by ctest (Tests.CorpusUsersSkip).

  tests/tools/check_corpus_skips.py [SOURCE_DIR]
  tests/tools/check_corpus_skips.py --self-test
"""
import os
import re
import sys

TEST = re.compile(r"^TEST(_F|_P)?\(\s*(\w+)\s*,\s*(\w+)\s*\)")
USES = re.compile(r"\bcorpus_dir\(\)|\bTEXPROC_CORPUS_DIR\b")


def bodies(text):
    """(name, body) of each TEST in a file, by brace matching from its line."""
    lines = text.split("\n")
    for i, line in enumerate(lines):
        m = TEST.match(line)
        if not m:
            continue
        depth, body, started = 0, [], False
        for j in range(i, len(lines)):
            code = re.sub(r'"([^"\\]|\\.)*"', '""', lines[j])
            code = re.sub(r"//.*", "", code)
            body.append(lines[j])
            depth += code.count("{") - code.count("}")
            started = started or "{" in code
            if started and depth == 0:
                break
        yield f"{m.group(2)}.{m.group(3)}", "\n".join(body)


DEFINES = re.compile(r"^[A-Za-z][\w:<>,\s\*&]*?\b(\w+)\([^;]*\)\s*(const\s*)?\{\s*$")


def helpers(text):
    """Names of the functions (not tests) in a file that read the corpus."""
    names = set()
    lines = text.split("\n")
    for i, line in enumerate(lines):
        m = DEFINES.match(line)
        if not m or TEST.match(line) or m.group(1) in ("if", "for", "while", "switch"):
            continue
        depth, started = 0, False
        for j in range(i, len(lines)):
            code = re.sub(r"//.*", "", lines[j])
            if USES.search(code):
                names.add(m.group(1))
            depth += code.count("{") - code.count("}")
            started = started or "{" in code
            if started and depth == 0:
                break
    return names


def problems(root):
    out = []
    for dirpath, _, files in os.walk(os.path.join(root, "tests")):
        if "node_modules" in dirpath:
            continue
        for f in sorted(files):
            if not f.endswith(".cpp"):
                continue
            path = os.path.join(dirpath, f)
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
            called = helpers(text) - {"corpus_dir", "have_corpus"}
            uses = re.compile(USES.pattern + "".join(r"|\b%s\(" % re.escape(n) for n in sorted(called)))
            for name, body in bodies(text):
                if uses.search(body) and "have_corpus()" not in body:
                    out.append(f"{os.path.relpath(path, root)}: {name} reads the corpus without have_corpus()")
    return out


def self_test():
    import tempfile
    with tempfile.TemporaryDirectory() as d:
        os.makedirs(os.path.join(d, "tests", "unit"))
        with open(os.path.join(d, "tests", "unit", "t.cpp"), "w") as f:
            f.write('TEST(A, Good) {\n  if (!have_corpus()) GTEST_SKIP();\n  read(corpus_dir() + "/x");\n}\n'
                    'TEST(A, Bad) {\n  read(std::string(TEXPROC_CORPUS_DIR) + "/x");\n}\n'
                    'Image corpus_image(int n) {\n  return read(corpus_dir() + "/y");\n}\n'
                    'TEST(A, BadThroughAHelper) {\n  corpus_image(3);\n}\n'
                    'TEST(A, GoodThroughAHelper) {\n  if (!have_corpus()) GTEST_SKIP();\n  corpus_image(3);\n}\n')
        found = problems(d)
        ok = len(found) == 2 and "A.Bad " in found[0] and "A.BadThroughAHelper" in found[1]
        print("self-test:", "ok" if ok else f"wrong: {found}")
        return 0 if ok else 1


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--self-test":
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    found = problems(root)
    for p in found:
        print(p)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
