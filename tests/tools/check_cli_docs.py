#!/usr/bin/python3
"""docs/cli.md against the command line itself: every option that `--help`
of every command (and subcommand) prints appears in docs/cli.md, written as
`--name` or `-x`, and every `--name` that docs/cli.md mentions is an option
of some command. Run by ctest (Docs.CliOptionsDocumented).

  tests/tools/check_cli_docs.py TEXPROC DOCS_CLI_MD   check
  tests/tools/check_cli_docs.py TEXPROC --reference   print the options of every
                                                      command as Markdown tables
  tests/tools/check_cli_docs.py --self-test
"""
import re
import subprocess
import sys

# An option in CLI11's help: two spaces, then "-x,--name" or "--name", then
# its type or its description.
OPTION = re.compile(r"^  ((?:-\w|--[a-z0-9][a-z0-9-]*)(?:,(?:-\w|--[a-z0-9][a-z0-9-]*))*)(?:\{[^}]*\})?(?=\s|$)(.*)$")
SUBCOMMANDS = re.compile(r"^Subcommands:\s*$")
DOC_OPTION = re.compile(r"(?<![\w-])--[a-z0-9][a-z0-9-]*")


def parse_help(text):
    """(options, subcommands) of one --help: options as [(short, long, rest)]."""
    options, subs, in_subs = [], [], False
    for line in text.split("\n"):
        if SUBCOMMANDS.match(line):
            in_subs = True
            continue
        if in_subs:
            m = re.match(r"^  (\w[\w-]*)\s", line)
            if m:
                subs.append(m.group(1))
                continue
            if line.strip() and not line.startswith("   "):
                in_subs = False
        m = OPTION.match(line)
        if m:
            # "-x,--name,--no-name{default} TYPE  description": the type, if
            # any, ends at the first run of spaces.
            names = m.group(1).split(",")
            short = next((n for n in names if not n.startswith("--")), "")
            longs = [n for n in names if n.startswith("--")] or [""]
            rest = m.group(2)
            arg, desc = "", rest.strip()
            t = re.match(r"^ (\S(?:.*?\S)?)(?:\s{2,}(.*))?$", rest)
            if t:
                arg, desc = t.group(1), (t.group(2) or "").strip()
            options.append((short, longs[0], arg, desc))
            for extra in longs[1:]:  # a negated flag (--no-mips) beside its flag
                options.append(("", extra, "", "(the negation of " + longs[0] + ")"))
        elif options and line.startswith(" " * 30) and line.strip():
            short, long_, arg, desc = options[-1]
            options[-1] = (short, long_, arg, (desc + " " + line.strip()).strip())
    return options, subs


def commands(texproc):
    """{'mip': help text, 'sat blur': ..., '': the top level's}."""
    def run(args):
        return subprocess.run([texproc] + args + ["--help"], capture_output=True, text=True, check=True).stdout

    out = {}
    pending = [[]]
    while pending:
        args = pending.pop(0)
        text = run(args)
        out[" ".join(args)] = text
        pending += [args + [s] for s in parse_help(text)[1]]
    return out


def check(helps, doc):
    """Messages for each broken rule (empty: docs/cli.md is complete and current)."""
    errors, known = [], {"--help"}
    for cmd, text in sorted(helps.items()):
        for short, long_, _, _ in parse_help(text)[0]:
            known.add(long_)
            if long_ in ("--help", "--version"):
                continue
            if long_ and not re.search(r"(?<![\w-])" + re.escape(long_) + r"(?![\w-])", doc):
                errors.append(f"texproc {cmd}: {long_} is not in docs/cli.md")
            if short and not long_ and not re.search(r"`" + re.escape(short) + r"[ `]", doc):
                errors.append(f"texproc {cmd}: {short} is not in docs/cli.md")
    for name in sorted(set(DOC_OPTION.findall(doc)) - known):
        errors.append(f"docs/cli.md names {name}, which no command has")
    return errors


def reference(helps):
    """The options of every command, as Markdown."""
    lines = []
    for cmd, text in sorted(helps.items()):
        if not cmd:
            continue
        summary = text.split("\n", 1)[0].strip()
        lines += [f"### `texproc {cmd}`", "", summary, "", "| option | meaning |", "|---|---|"]
        for short, long_, arg, desc in parse_help(text)[0]:
            if long_ == "--help" or long_ in COMMON:
                continue
            name = ", ".join(x for x in (short, long_) if x)
            lines.append(f"| `{name}{' ' + arg if arg else ''}` | {desc.replace('|', '/')} |")
        lines.append("")
    return "\n".join(lines)


COMMON = {"--threads", "--jobs", "--fail-fast", "--skip-existing", "--json", "--progress", "--force", "--quiet",
          "--verbose", "--depfile", "--dry-run", "--write-if-changed", "--recursive", "--file-list"}


def self_test():
    help_text = """Usage: texproc mip [OPTIONS]

Options:
  -h,--help                   Print this help message and exit
  -o,--output TEXT REQUIRED   Output
  --filter TEXT=gaussian      Mip filter: gaussian, box,
                              triangle
  -x                          A short option alone
  --mips,--no-mips{false}     A flag and its negation

Subcommands:
  blur                        Box blur
"""
    opts, subs = parse_help(help_text)
    assert [o[1] for o in opts] == ["--help", "--output", "--filter", "", "--mips", "--no-mips"], opts
    assert opts[4][3] == "A flag and its negation", opts[4]
    assert opts[2][2] == "TEXT=gaussian" and opts[2][3] == "Mip filter: gaussian, box, triangle", opts[2]
    assert opts[3][:3] == ("-x", "", ""), opts[3]
    assert subs == ["blur"], subs
    helps = {"mip": help_text}
    good = "Use `-o` or `--output`, `--filter`, `--mips` or `--no-mips`, and `-x` alone."
    assert check(helps, good) == [], check(helps, good)
    missing = check(helps, "Use `--output`, `--mips`, `--no-mips` and `-x` alone.")
    assert missing == ["texproc mip: --filter is not in docs/cli.md"], missing
    extra = check(helps, good + " And --fliter.")
    assert extra == ["docs/cli.md names --fliter, which no command has"], extra
    # A longer option does not stand in for a shorter one's mention.
    assert "texproc mip: --filter is not in docs/cli.md" in check(helps, "`--output` `--filter-size` `-x` `--mips` `--no-mips`")
    print("self-test passed")


def main():
    if sys.argv[1:] == ["--self-test"]:
        self_test()
        return 0
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 1
    helps = commands(sys.argv[1])
    if sys.argv[2] == "--reference":
        print(reference(helps))
        return 0
    with open(sys.argv[2], encoding="utf-8") as f:
        doc = f.read()
    errors = check(helps, doc)
    for e in errors:
        print(e)
    print(f"{len(errors)} problem(s) in docs/cli.md" if errors else "docs/cli.md names every option, and only those")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
