#!/usr/bin/python3
"""Whole processes, as build systems run texproc: start-up, one small texture
per process, `make -j2` over 200 textures, and large files whose time goes to
reading and writing; each beside the peer tools on the same files, in
interleaved rounds (every tool once per round), reporting medians and ratios.

  bench/bench_process.py [--texproc build/cli/texproc] [--baseline OLD_TEXPROC]
                         [--rounds 5] [--work DIR] [--only NAME,...]

--baseline: an older texproc build (for example the last one that linked
OpenImageIO) measured in the same rounds. Needs python3-pil; nvcompress,
maketx, gegl and make are used where installed (missing ones are skipped).
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CORPUS = os.path.join(ROOT, "..", "shared", "corpus")


def run(cmd, **kw):
    t = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, **kw)
    dt = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(f"{cmd[0]} failed ({r.returncode}): {r.stderr.decode(errors='replace')[-400:]}")
    return dt, r.stdout.decode(errors="replace")


def interleaved(cases, rounds, repeat=1):
    """cases: {name: callable returning seconds}; every case once per round
    (repeat times in a row, the median of those), `rounds` rounds; medians."""
    times = {n: [] for n in cases}
    for _ in range(rounds):
        for name, fn in cases.items():
            times[name].append(statistics.median(fn() for _ in range(repeat)))
    return {n: statistics.median(v) for n, v in times.items()}


def table(title, med, unit="ms", ref=None):
    print(f"\n## {title}")
    scale = 1000.0 if unit == "ms" else 1.0
    for name, t in med.items():
        ratio = f"  ({t / med[ref]:.2f}x {ref})" if ref and ref in med and name != ref else ""
        print(f"  {name:<46} {t * scale:10.1f} {unit}{ratio}")


def have(tool):
    return shutil.which(tool) is not None


def make_inputs(work):
    from PIL import Image

    src = Image.open(os.path.join(CORPUS, "albedo_srgb", "wz2100_backdrop0_2048.png")).convert("RGB")
    small = os.path.join(work, "small")
    os.makedirs(small, exist_ok=True)
    # 200 distinct 128x128 textures, as a game's UI or terrain atlas pieces.
    for i in range(200):
        x, y = (i % 16) * 128, (i // 16) * 128
        src.crop((x, y, x + 128, y + 128)).save(os.path.join(small, f"t{i:03}.png"))
    src.crop((0, 0, 256, 256)).save(os.path.join(work, "s256.png"))
    big = src.resize((4096, 4096), Image.BICUBIC).convert("RGBA")
    big.save(os.path.join(work, "big.tga"))
    h = Image.open(os.path.join(CORPUS, "height", "trigger_swiss_h_1024.png")).convert("F").resize((4096, 4096), Image.BICUBIC)
    h16 = h.point(lambda v: v * 257.0).convert("I").convert("I;16")
    h16.save(os.path.join(work, "h16.png"))
    return small


MAKEFILE = """\
SRC := $(wildcard {small}/*.png)
OUT := {out}
all: $(patsubst {small}/%.png,$(OUT)/%.dds,$(SRC))
$(OUT)/%.dds: {small}/%.png
\t{cmd}
"""


def make_run(work, name, cmd_template):
    out = os.path.join(work, "make_" + name)
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    mk = os.path.join(work, f"Makefile.{name}")
    with open(mk, "w") as f:
        f.write(MAKEFILE.format(small=os.path.join(work, "small"), out=out, cmd=cmd_template))
    return run(["make", "-s", "-j2", "-f", mk])[0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--texproc", default=os.path.join(ROOT, "build", "cli", "texproc"))
    ap.add_argument("--baseline", default="")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--work", default="")
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    T, B = os.path.abspath(a.texproc), a.baseline
    only = set(a.only.split(",")) if a.only else None
    want = lambda n: only is None or n in only
    work = a.work or tempfile.mkdtemp(prefix="texproc_bench_process_")
    os.makedirs(work, exist_ok=True)
    print(f"# bench_process: {T}" + (f" (baseline {B})" if B else "") + f", {a.rounds} interleaved rounds, medians")
    print(f"# inputs in {work}")
    make_inputs(work)
    w = lambda *p: os.path.join(work, *p)
    nv = have("nvcompress")

    if want("startup"):
        run([T, "compress", w("s256.png"), "-o", w("s.dds"), "--format", "bc1", "-f", "-q"])
        cases = {
            "texproc --version": lambda: run([T, "--version"])[0],
            "texproc info x.dds": lambda: run([T, "info", w("s.dds")])[0],
            "256x256 PNG -> BC1 DDS: texproc (normal)": lambda: run(
                [T, "compress", w("s256.png"), "-o", w("s.dds"), "--format", "bc1", "-f", "-q"])[0],
        }
        if nv:
            cases["256x256 PNG -> BC1 DDS: nvcompress -bc1"] = lambda: run(
                ["nvcompress", "-bc1", "-silent", w("s256.png"), w("s_nv.dds")])[0]
        if B:
            cases["baseline --version"] = lambda: run([B, "--version"])[0]
            cases["256x256 PNG -> BC1 DDS: baseline"] = lambda: run(
                [B, "compress", w("s256.png"), "-o", w("s_b.dds"), "--format", "bc1", "-f", "-q"])[0]
        table("Start-up (one process; median of 5 runs a round)", interleaved(cases, a.rounds, repeat=5),
              ref="256x256 PNG -> BC1 DDS: nvcompress -bc1" if nv else None)

    if want("make") and have("make"):
        cases = {
            "make -j2, texproc per file": lambda: make_run(work, "tp", f"{T} compress $< -o $@ --format bc1 -q -f"),
            "one texproc process, 200 inputs, -j 2": lambda: run(
                [T, "compress"] + sorted(w("small", f) for f in os.listdir(w("small"))) +
                ["-o", w("one") + "/", "--format", "bc1", "-q", "-f", "-j", "2"])[0],
        }
        if nv:
            cases["make -j2, nvcompress per file"] = lambda: make_run(work, "nv", "nvcompress -bc1 -silent $< $@")
        if B:
            cases["make -j2, baseline per file"] = lambda: make_run(work, "base", f"{B} compress $< -o $@ --format bc1 -q -f")
        med = interleaved(cases, a.rounds)
        table("200 PNG textures (128x128) to BC1, one process each (samples/Makefile pattern)", med, unit="s",
              ref="make -j2, texproc per file")
        per, one = med["make -j2, texproc per file"], med["one texproc process, 200 inputs, -j 2"]
        print(f"  share of the make wall time spent starting processes: {100 * max(0.0, per - one) / per:.0f}%"
              f" (make -j2 minus one process doing the same work)")

    if want("mip"):
        cases = {"texproc mip": lambda: run([T, "mip", w("big.tga"), "-o", w("big.dds"), "-f", "-q"])[0]}
        if nv:
            cases["nvcompress -rgb (mips)"] = lambda: run(["nvcompress", "-rgb", "-silent", w("big.tga"), w("big_nv.dds")])[0]
        if have("maketx"):
            cases["maketx (tiled TIFF)"] = lambda: run(["maketx", w("big.tga"), "-o", w("big_mk.tif")])[0]
        if B:
            cases["baseline mip"] = lambda: run([B, "mip", w("big.tga"), "-o", w("big_b.dds"), "-f", "-q"])[0]
        table("texproc mip 4096x4096 RGBA8 TGA -> DDS (13 levels)", interleaved(cases, a.rounds), unit="s",
              ref="texproc mip")
        print("  texproc --verbose:", run([T, "mip", w("big.tga"), "-o", w("big.dds"), "-f", "-v"])[1].strip().splitlines()[-1])

    if want("normalmap"):
        cases = {"texproc normalmap (sobel3, u16)": lambda: run(
            [T, "normalmap", w("h16.png"), "-o", w("n16.png"), "--type", "u16", "-f", "-q"])[0]}
        if have("gegl"):
            cases["gegl:normal-map"] = lambda: run(["gegl", w("h16.png"), "-o", w("n16_gegl.png"), "--", "gegl:normal-map"])[0]
        if B:
            cases["baseline normalmap"] = lambda: run(
                [B, "normalmap", w("h16.png"), "-o", w("n16_b.png"), "--type", "u16", "-f", "-q"])[0]
        table("texproc normalmap 4096x4096 16-bit PNG -> 16-bit PNG", interleaved(cases, a.rounds), unit="s",
              ref="texproc normalmap (sobel3, u16)")
        print("  texproc --verbose:", run([T, "normalmap", w("h16.png"), "-o", w("n16.png"), "--type", "u16", "-f", "-v"])[1]
              .strip().splitlines()[-1])
        # What no PNG writer can beat: zlib's own inflate of this file's pixels
        # (one stream: the format allows no parallel decode).
        import zlib
        data = open(w("h16.png"), "rb").read()
        idat, i = bytearray(), 8
        while i < len(data):
            n = int.from_bytes(data[i:i + 4], "big")
            if data[i + 4:i + 8] == b"IDAT":
                idat += data[i + 8:i + 8 + n]
            i += 12 + n
        t = time.perf_counter()
        zlib.decompress(bytes(idat))
        print(f"  floor for reading it: zlib inflate alone takes {1000 * (time.perf_counter() - t):.0f} ms")

    if want("module"):
        bmp = os.path.join(CORPUS, "albedo_srgb", "scorched3d_f18_512.bmp")
        cases = {"texproc mip BMP (OpenImageIO module)": lambda: run([T, "mip", bmp, "-o", w("bmp.dds"), "-f", "-q"])[0]}
        if B:
            cases["baseline mip BMP"] = lambda: run([B, "mip", bmp, "-o", w("bmp_b.dds"), "-f", "-q"])[0]
        table("A format read through OpenImageIO (512x512 BMP -> DDS)", interleaved(cases, a.rounds),
              ref="baseline mip BMP" if B else None)

    if not a.work:
        shutil.rmtree(work, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
