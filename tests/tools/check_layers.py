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

# The layers of docs/architecture.md, bottom up. Each may include its own
# headers and those of the layers it lists, internal or public, and nothing
# else of texproc's.
LAYERS = {
    "core": [],
    "images": ["core"],
    "formats": ["core", "images"],
    "block": ["core", "images"],
    "decoders": ["core", "images", "formats"],
    "containers": ["core", "images", "formats", "decoders"],
    "encoders": ["core", "images", "formats", "block", "decoders"],
    "io": ["core", "images", "formats", "decoders", "containers"],
}

# Internal files by folder under libtexproc/src; the decoders sit beside
# their encoders in bc/, etc/ and astc/ and are named here one by one.
FOLDERS = {
    "core": "core", "image": "images", "mip": "images", "normalmap": "images", "sat": "images",
    "conemap": "images", "cubemap": "images", "format": "formats", "block": "block", "decode": "decoders",
    "container": "containers", "bc": "encoders", "etc": "encoders", "astc": "encoders", "encode": "encoders",
    "io": "io",
}
DECODERS = re.compile(r"^(bc/(bc_decode\.(cpp|h)|bptc_decode\.cpp|bptc_tables\.h|bc6h_shared\.h)|"
                      r"etc/(etc_decode\.cpp|etc_tables\.h)|astc/astc_decode\.h)$")

# Each public header belongs to the layer that implements it.
PUBLIC = {
    "error.h": "core", "runtime.h": "core", "read_limits.h": "core", "tools.h": "core", "version.h": "core",
    "image.h": "images", "channels.h": "images", "color.h": "images", "filters.h": "images", "metrics.h": "images",
    "transparent_color.h": "images", "mip.h": "images", "normalmap.h": "images", "sat.h": "images",
    "conemap.h": "images", "cubemap.h": "images",
    "texture.h": "formats",
    "block_decode.h": "decoders",
    "container.h": "containers",
    "block_encode.h": "encoders",
    "image_io.h": "io",
}


def layer_of(header):
    """The layer of a header or source named as an include names it (\"bc/bc1_encode.h\",
    \"texproc/image.h\"); None for what is not texproc's."""
    if header.startswith("texproc/"):
        name = header[len("texproc/"):]
        return PUBLIC.get(name.replace(".h.in", ".h"), "unmapped public header")
    if DECODERS.match(header):
        return "decoders"
    return FOLDERS.get(header.split("/")[0]) if "/" in header else None


def includes(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return [(m.group(1), m.group(2)) for m in INCLUDE.finditer(f.read())]


def layer_rule(rel):
    """The allow-list of the layer `rel` (a path under the source root) is in."""
    if rel.startswith("libtexproc/include/"):
        own = layer_of(rel[len("libtexproc/include/"):])
    elif rel.startswith("libtexproc/src/"):
        own = layer_of(rel[len("libtexproc/src/"):])
    else:
        return None
    if own not in LAYERS:
        return ("every file belongs to a layer (tests/tools/check_layers.py: FOLDERS, PUBLIC)", lambda k, h: True)
    allowed = set(LAYERS[own]) | {own}

    def broken(kind, header, allowed=allowed):
        if kind != '"':
            return False
        target = layer_of(header)
        return target is not None and target not in allowed
    return (f"{own} may include {', '.join(sorted(allowed))} only", broken)


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
    rule = layer_rule(rel)
    if rule:
        out.append(rule)
    codec = re.match(r"libtexproc/src/(bc|etc|astc)/", rel)
    if codec:
        out.append(("a codec includes no other codec's internals (what they share is in block/)",
                    lambda k, h, own=codec.group(1): k == '"' and re.match(r"(bc|etc|astc)/", h) is not None
                    and not h.startswith(own + "/")))
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
        "libtexproc/include/texproc/tools.h": "#include <hwy/highway.h>\n",
        "libtexproc/include/texproc/image.h": '#include "texproc/image_io.h"\n',
        "libtexproc/src/bc/bc_decode.cpp": '#include "bc/bc1_encode.h"\n',
        "libtexproc/src/container/ktx9.cpp": '#include "texproc/block_encode.h"\n',
        "libtexproc/src/core/x.cpp": '#include "image/ocio.h"\n',
        "libtexproc/src/cubemap/x.cpp": '#include "bc/bc_images.h"\n',
        "libtexproc/src/image/y.cpp": '#include "texproc/container.h"\n',
        "libtexproc/src/format/x.cpp": '#include "io/codecs/codecs.h"\n',
        "libtexproc/src/etc/x.cpp": '#include "bc/bc1_lanes.h"\n',
        "libtexproc/src/decode/x.cpp": '#include "etc/etc_encode.h"\n',
        "libtexproc/src/block/x.cpp": '#include "etc/etc_tables.h"\n',
        "libtexproc/src/newdir/x.cpp": '#include "texproc/error.h"\n',
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
