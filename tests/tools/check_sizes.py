#!/usr/bin/python3
"""The size rules of docs/architecture.md, checked on every source file of
libtexproc/, cli/ and python/: no file over 600 lines, no function (or lambda, or
member function) body over 150 lines unless the comment just above it says
why with a line starting `// Long:`. Exit 1 naming each one that breaks a
rule. Run by ctest (Layers.Sizes).

  tests/tools/check_sizes.py [SOURCE_DIR]
  tests/tools/check_sizes.py --self-test   (a tree that breaks each rule must fail)
"""
import os
import re
import sys

MAX_FILE_LINES = 600
MAX_FUNCTION_LINES = 150
ROOT = sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

CONTROL = re.compile(r"^\s*(if|for|while|switch|else|do|catch|try)\b|\b(if|for|while|switch)\s*\(")
# A line that opens a function body: a parameter list's ')' (with
# qualifiers, a trailing return type or a constructor's initializers after
# it) and then '{'.
OPENS_FUNCTION = re.compile(r"\)\s*(const|noexcept|override|final|mutable|->[^{;]*|:[^;{]*|\s)*\{\s*$")


def strip(line):
    line = re.sub(r'"([^"\\]|\\.)*"', '""', line)
    line = re.sub(r"'([^'\\]|\\.)*'", "''", line)
    return re.sub(r"//.*", "", line)


def long_functions(lines):
    """(first line, length) of each function body longer than the limit without a `// Long:` reason."""
    out = []
    stack = []  # (line index, is a function)
    in_comment = False
    for i, raw in enumerate(lines):
        code = raw
        if in_comment:
            if "*/" not in code:
                continue
            code = code.split("*/", 1)[1]
            in_comment = False
        code = re.sub(r"/\*.*?\*/", "", code)
        if "/*" in code:
            code, in_comment = code.split("/*", 1)[0], True
        code = strip(code)
        for ch in code:
            if ch == "{":
                is_fn = bool(OPENS_FUNCTION.search(code)) and not CONTROL.search(code)
                stack.append((i, is_fn))
            elif ch == "}" and stack:
                start, is_fn = stack.pop()
                if is_fn and i - start > MAX_FUNCTION_LINES and not reasoned(lines, start):
                    out.append((start + 1, i - start))
    return out


def reasoned(lines, start):
    """Whether the comment block just above line `start` (or its signature's first line) gives a `// Long:` reason."""
    j = start - 1
    # The signature may span lines: walk up to the comment above it.
    while j >= 0 and lines[j].strip() and not lines[j].strip().startswith("//") and start - j < 6:
        j -= 1
    while j >= 0 and lines[j].strip().startswith("//"):
        if lines[j].strip().startswith("// Long:"):
            return True
        j -= 1
    return False


def main():
    bad = 0
    checked = 0
    for top in ("cli", "libtexproc", "python"):
        for d, _, files in os.walk(os.path.join(ROOT, top)):
            for f in sorted(files):
                if not f.endswith((".cpp", ".h")):
                    continue
                path = os.path.join(d, f)
                rel = os.path.relpath(path, ROOT)
                with open(path, encoding="utf-8", errors="replace") as fh:
                    lines = fh.read().split("\n")
                checked += 1
                if len(lines) - 1 > MAX_FILE_LINES:
                    print(f"{rel}: {len(lines) - 1} lines (at most {MAX_FILE_LINES}: split it by algorithm)")
                    bad += 1
                for line, length in long_functions(lines):
                    print(f"{rel}:{line}: a function of {length} lines (at most {MAX_FUNCTION_LINES}, "
                          "or a '// Long:' comment above it saying why)")
                    bad += 1
    print(f"check_sizes: {checked} files, {bad} broken rule(s)")
    return 1 if bad else 0


def self_test():
    import subprocess
    import tempfile
    body = "".join(f"  x += {k};\n" for k in range(160))
    breaks = {
        "cli/big.cpp": "int x;\n" * 601,
        "libtexproc/src/a/long.cpp": "void f(int x) {\n" + body + "}\n",
        "libtexproc/src/a/lambda.cpp": "void g() {\n  auto h = [&](int x) {\n" + body + "  };\n}\n",
    }
    fine = {
        "libtexproc/src/a/reasoned.cpp": "// Long: a reason.\nvoid f(int x) {\n" + body + "}\n",
        # Long namespaces, structs and tables are not functions.
        "libtexproc/src/a/ns.cpp": "namespace a {\n" + "".join(f"int f{k}(int x) {{ return x + {k}; }}\n" for k in range(160)) + "}\n",
        "libtexproc/src/a/struct.h": "struct S {\n" + "".join(f"  int m{k} = {k};\n" for k in range(160)) + "};\n",
        "libtexproc/src/a/table.cpp": "const int kTable[] = {\n" + "".join(f"  {k},\n" for k in range(160)) + "};\n",
    }
    with tempfile.TemporaryDirectory() as tmp:
        for rel, text in {**breaks, **fine}.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        r = subprocess.run([sys.executable, os.path.abspath(__file__), tmp], stdout=subprocess.PIPE, text=True)
        print(r.stdout, end="")
        found = sum(1 for rel in breaks if rel in r.stdout)
        wrong = [rel for rel in fine if rel in r.stdout]
        if r.returncode != 1 or found != len(breaks) or wrong:
            print(f"check_sizes --self-test: {found} of {len(breaks)} broken rules found; flagged wrongly: {wrong}")
            return 1
    print("check_sizes --self-test: every broken rule found, nothing else")
    return 0


if __name__ == "__main__":
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else main())
