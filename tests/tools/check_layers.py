#!/usr/bin/python3
"""The include rules of docs/architecture.md, checked on every source file:
exit 1 naming each file that breaks one. Run by ctest (Layers.IncludeRules).

  tests/tools/check_layers.py [SOURCE_DIR]
  tests/tools/check_layers.py --self-test   (a tree that breaks each rule must fail)
"""
import os
import re
import sys

ROOT = sys.argv[1] if len(sys.argv) > 1 and sys.argv[1] != "--self-test" else os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)

# What makes a header an encoder's: the block searches and their kernels.
ENCODER = re.compile(r'(^|/)(\w*_encode|\w*_lanes|\w*_eval|bc1_cluster|rgb_block|value_palette|block_gather)\.h$|^texproc/block_encode\.h$')


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return [(m.group(1), m.group(2)) for m in INCLUDE.finditer(f.read())]


def rules(rel):
    """(rule name, predicate over (kind, header) that is a violation) for a file."""
    out = []
    if rel.startswith("cli/"):
        out.append(("the CLI uses no Highway or TBB (the library's runtime runs its threads)",
                    lambda k, h: k == "<" and (h.startswith("hwy/") or h.startswith("tbb/"))))
        out.append(("the CLI includes only public headers and its own",
                    lambda k, h: k == '"' and "/" in h and not h.startswith("texproc/")))
    if rel.startswith("python/"):
        out.append(("the Python extension includes only public headers, pybind11 and its own",
                    lambda k, h: k == '"' and "/" in h and not h.startswith("texproc/")))
    if rel.startswith("libtexproc/include/"):
        out.append(("public headers include the standard library and texproc/ only",
                    lambda k, h: (k == '"' and not h.startswith("texproc/")) or
                    (k == "<" and (h.startswith("hwy/") or h.startswith("tbb/") or h.startswith("OpenImageIO/")))))
    base = os.path.basename(rel)
    if re.search(r"_decode\.(cpp|h)$", base) or re.match(r"libtexproc/src/(container|decode)/", rel):
        out.append(("decoders and containers include no encoder", lambda k, h: k == '"' and bool(ENCODER.search(h))))
    if re.match(r"libtexproc/src/(image|mip|normalmap|sat|conemap|cubemap)/", rel):
        out.append(("the image layers (image, mip, normalmap, sat, conemap, cubemap) include no encoder or codec internals",
                    lambda k, h: k == '"' and (bool(ENCODER.search(h)) or
                                               re.match(r"(bc|etc|astc|encode|container)/", h) is not None)))
    codec = re.match(r"libtexproc/src/(bc|etc|astc)/", rel)
    if codec:
        out.append(("a codec includes no other codec's internals (what they share is in block/)",
                    lambda k, h, own=codec.group(1): k == '"' and re.match(r"(bc|etc|astc)/", h) is not None
                    and not h.startswith(own + "/")))
    if rel.startswith("libtexproc/src/block/"):
        out.append(("block/ (the primitives every codec shares) includes core/, block/ and texproc/ only",
                    lambda k, h: k == '"' and not re.match(r"(core|block|texproc)/", h)))
    if rel.startswith("libtexproc/src/core/"):
        out.append(("core/ is the bottom layer: core/ and texproc/ only",
                    lambda k, h: k == '"' and not (h.startswith("core/") or h.startswith("texproc/"))))
    return out


def main():
    bad = 0
    checked = 0
    for top in ("cli", "libtexproc", "python"):
        for d, _, files in os.walk(os.path.join(ROOT, top)):
            for f in files:
                if not f.endswith((".cpp", ".h")):
                    continue
                path = os.path.join(d, f)
                rel = os.path.relpath(path, ROOT)
                checked += 1
                for name, broken in rules(rel):
                    for kind, header in includes(path):
                        if broken(kind, header):
                            print(f"{rel}: includes {kind}{header}{'>' if kind == '<' else kind}: {name}")
                            bad += 1
    print(f"check_layers: {checked} files, {bad} broken rule(s)")
    return 1 if bad else 0


def self_test():
    import subprocess
    import tempfile
    breaks = {
        "cli/cmd_x.cpp": "#include <tbb/parallel_for.h>\n",
        "cli/cmd_y.cpp": '#include "bc/bc1_lanes.h"\n',
        "python/src/x.cpp": '#include "core/module.h"\n',
        "libtexproc/include/texproc/x.h": "#include <hwy/highway.h>\n",
        "libtexproc/src/bc/bc_decode.cpp": '#include "bc/bc1_encode.h"\n',
        "libtexproc/src/container/ktx9.cpp": '#include "texproc/block_encode.h"\n',
        "libtexproc/src/core/x.cpp": '#include "image/ocio.h"\n',
        "libtexproc/src/cubemap/x.cpp": '#include "bc/bc_images.h"\n',
        "libtexproc/src/etc/x.cpp": '#include "bc/bc1_lanes.h"\n',
        "libtexproc/src/decode/x.cpp": '#include "etc/etc_encode.h"\n',
        "libtexproc/src/block/x.cpp": '#include "etc/etc_tables.h"\n',
    }
    with tempfile.TemporaryDirectory() as tmp:
        for rel, text in breaks.items():
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), "w") as f:
                f.write(text)
        r = subprocess.run([sys.executable, os.path.abspath(__file__), tmp], stdout=subprocess.PIPE, text=True)
        found = r.stdout.count(": includes ")
        print(r.stdout, end="")
        if r.returncode != 1 or found != len(breaks):
            print(f"check_layers --self-test: {found} of {len(breaks)} broken rules found")
            return 1
    print("check_layers --self-test: every broken rule found")
    return 0


if __name__ == "__main__":
    sys.exit(self_test() if sys.argv[1:] == ["--self-test"] else main())
