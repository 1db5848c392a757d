#!/usr/bin/python3
"""One statement per line: exit 1 naming each expression statement that
chains several with the comma operator (`a = 1, b = 2;`, `++i, ++j;`,
`f(x), g(y);`), which clang-format leaves alone. Declarations of several
variables (`int a = 1, b = 2;`) and for-loop headers are not statements
chained this way. Run by ctest (Format.OneStatementPerLine).

  tests/tools/check_statements.py [SOURCE_DIR]
  tests/tools/check_statements.py --self-test   (chained statements must be found, the rest not)
"""
import os
import re
import sys

FOLDERS = ("cli", "libtexproc", "python/src", "tests", "bench")
ASSIGNMENT = re.compile(r"^\s*[\w.\[\]>*()-]+?\s*(=|\+=|-=|\*=|/=|%=|\|=|&=|\^=|<<=|>>=)(?!=)")
INCREMENT = re.compile(r"^\s*((\+\+|--)\w|[\w.\[\]>-]+(\+\+|--)\s*$)")
CALL = re.compile(r"^\s*[\w:.>-]+\(.*\)\s*$", re.S)
DECLARATION = re.compile(r"^\s*[\w:<>]+\s+\w+\(")


def blank_literals(src):
    """`src` with comments and string and character literals blanked out,
    every offset and line kept."""
    out = []
    i, n = 0, len(src)
    while i < n:
        if src.startswith("//", i):
            j = src.find("\n", i)
            j = n if j < 0 else j
        elif src.startswith("/*", i):
            j = src.find("*/", i + 2)
            j = n if j < 0 else j + 2
        elif src.startswith('R"', i) and re.match(r'R"([^(\s]*)\(', src[i:]):
            end = ")" + re.match(r'R"([^(\s]*)\(', src[i:]).group(1) + '"'
            j = src.find(end, i)
            j = n if j < 0 else j + len(end)
        elif src[i] in "\"'":
            j = i + 1
            while j < n and src[j] != src[i]:
                j += 2 if src[j] == "\\" else 1
            j += 1
        else:
            out.append(src[i])
            i += 1
            continue
        out.append(re.sub(r"[^\n]", " ", src[i:j]))
        i = j
    return "".join(out)


def statements(code):
    """(offset, text) of each statement: up to a ';', '{' or '}' outside parentheses."""
    depth, start = 0, 0
    for i, c in enumerate(code):
        if c == "(":
            depth += 1
        elif c == ")":
            depth -= 1
        elif depth == 0 and c in ";{}":
            yield start, code[start:i + 1]
            start = i + 1


def top_level_commas(text):
    depth, found = 0, []
    for i, c in enumerate(text):
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        elif c == "," and depth == 0:
            found.append(i)
    return found


def body_of(statement):
    """The statement without a leading `else` or `if (...)`/`for (...)`/`while (...)` header."""
    s = re.sub(r"^\s*else\s+", "", statement).strip()
    if re.match(r"^(if|while|for)\s*\(", s):
        depth = 0
        for k, c in enumerate(s):
            if c == "(":
                depth += 1
            elif c == ")":
                depth -= 1
                if depth == 0:
                    return s[k + 1:].strip()
    return s


def chained(statement):
    s = body_of(statement[:-1])
    if s.startswith(("return", "using", "typedef", "template", "#", "case ", "default", "{")):
        return False
    commas = top_level_commas(s)
    if not commas:
        return False
    first = s[:commas[0]]
    if first.count("<") > first.count(">"):  # a template argument list
        return False
    while re.search(r"\[[^\[\]]+\]", first):  # subscripts, whatever their insides: a[i + 1] as a[]
        first = re.sub(r"\[[^\[\]]+\]", "[]", first)
    return bool(ASSIGNMENT.match(first) or INCREMENT.match(first) or
                (CALL.match(first) and not DECLARATION.match(first)))


def check_file(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        code = blank_literals(f.read())
    found = []
    for offset, text in statements(code):
        if text.endswith(";") and chained(text):
            line = code.count("\n", 0, offset + len(text) - len(text.lstrip())) + 1
            found.append((line, " ".join(text.split())[:100]))
    return found


def main(root):
    bad = checked = 0
    for top in FOLDERS:
        for d, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = [x for x in dirs if x not in ("node_modules", "build")]
            for f in sorted(files):
                if not f.endswith((".cpp", ".h")):
                    continue
                path = os.path.join(d, f)
                checked += 1
                for line, text in check_file(path):
                    print(f"{os.path.relpath(path, root)}:{line}: statements chained with commas; one a line: {text}")
                    bad += 1
    print(f"check_statements: {checked} files, {bad} chained statement(s)")
    return 1 if bad else 0


def self_test():
    import tempfile
    chained_lines = [
        "  a = 1, b = 2;",
        "  x[i] += 3, y.z -= 4;",
        "  fit.code[k][s.c0 + a] = q, fit.value[k][s.c0 + a] = v;",
        "  ++i, ++j;",
        "  if (k) best = k, at = i;",
        "  for (int c = 0; c < 3; ++c) lo[c] = 0, hi[c] = 255;",
        "  else w.put(1, 2), w.put(3, 4);",
    ]
    fine_lines = [
        "  int a = 1, b = 2;",
        "  std::vector<int> v(3), w(4);",
        "  for (int i = 0, j = 9; i < j; ++i, --j) f(i, j);",
        "  f(a, b);",
        '  s = "a, b = c";',
        "  // a = 1, b = 2;",
        "  std::map<int, int> m;",
        "  return a, b;",
        "  auto [x, y] = pair;",
    ]
    with tempfile.TemporaryDirectory() as tmp:
        os.makedirs(os.path.join(tmp, "cli"))
        with open(os.path.join(tmp, "cli", "x.cpp"), "w") as f:
            f.write("void g() {\n" + "\n".join(chained_lines + fine_lines) + "\n}\n")
        found = check_file(os.path.join(tmp, "cli", "x.cpp"))
    lines = [line for line, _ in found]
    want = list(range(2, 2 + len(chained_lines)))
    if lines != want:
        print(f"check_statements --self-test: found lines {lines}, want {want}")
        return 1
    print(f"check_statements --self-test: {len(chained_lines)} chained statements found, {len(fine_lines)} others left")
    return 0


if __name__ == "__main__":
    if sys.argv[1:] == ["--self-test"]:
        sys.exit(self_test())
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else
                  os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))))
