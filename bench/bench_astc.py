#!/usr/bin/python3
"""ASTC: texproc (astc-encoder's library through texproc) against `astcenc`
(ARM's CLI over the same library) on 256x256 centre crops of the corpus's
colour textures, at every preset, 4x4 / 6x6 / 8x8, on one and two threads,
in interleaved rounds (every tool once per round), medians; and beside them
ETC2 and BC1 at texproc's `normal`, so the docs can say what each format buys.

  bench/bench_astc.py [--texproc build/cli/texproc] [--rounds 3] [--work DIR]
                      [--footprints 4x4,6x6,8x8] [--presets fastest,fast,...]

PSNR: pooled over the crops (mean squared error over RGB of every crop, 8-bit
scale), as astcenc reports "PSNR (LDR-RGB)"; both tools code the same bytes,
so the two columns must agree. Speed: megatexels per second of encoding
(astcenc's "Coding time"; texproc's encode_seconds for the same image, in one
batch process whose astc-encoder context is made once, during the first crop:
both tools' speeds leave the first crop out), and the whole-process
wall time of the batch (texproc: one call for every crop; astcenc: one call
per crop, as it takes one image). Linear LDR (-tl, --linear) throughout.
Needs python3-pil and astcenc (Debian: astcenc).
"""
import argparse
import json
import math
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
CORPUS = os.path.join(ROOT, "..", "shared", "corpus")

# texproc's --quality names and astc-encoder's presets (effort 0-100).
PRESETS = {"fastest": 0, "fast": 10, "medium": 60, "thorough": 98, "verythorough": 99, "exhaustive": 100}
QUALITY_OF = {"fast": "fast", "medium": "normal", "thorough": "high", "exhaustive": "max"}


def crops(work, size=256):
    from PIL import Image
    out = []
    with open(os.path.join(CORPUS, "MANIFEST.tsv")) as f:
        rows = [line.rstrip("\n").split("\t") for line in f][1:]
    for r in rows:
        path, cat, w, h = r[0], r[1], int(r[2]), int(r[3])
        if cat not in ("albedo_srgb", "photo") or w < size or h < size:
            continue
        im = Image.open(os.path.join(CORPUS, path)).convert("RGB")
        x0, y0 = (im.width - size) // 2, (im.height - size) // 2
        name = os.path.join(work, os.path.basename(path).rsplit(".", 1)[0] + ".png")
        im.crop((x0, y0, x0 + size, y0 + size)).save(name)
        out.append(name)
    return out


def pooled_psnr(psnrs):
    mse = statistics.mean(10 ** (-p / 10.0) for p in psnrs)  # relative to peak^2
    return -10.0 * math.log10(mse)


def run(cmd):
    t = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    dt = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd[:3])} failed ({r.returncode}): {r.stderr.decode(errors='replace')[-400:]}")
    return dt, r.stdout.decode(errors="replace")


def texproc_batch(texproc, images, fmt, flags, threads, work):
    """One process over every crop: (wall seconds, [encode seconds], [PSNR RGB])."""
    out = os.path.join(work, "tp_out") + "/"
    cmd = [texproc, "compress", *images, "-o", out + "{stem}.ktx2", "--format", fmt, "--linear", "--report",
           "--json", "-f", "--threads", str(threads), "--jobs", "1", *flags]
    wall, text = run(cmd)
    files = json.loads(text)["files"]  # details are merged into each file's record
    enc = [f["encode_seconds"] for f in files]
    psnr = [f["report"]["psnr_rgb"] for f in files]
    return wall, enc, psnr


def astcenc_batch(images, footprint, effort, threads, work):
    wall, enc, psnr = 0.0, [], []
    for im in images:
        dt, text = run(["astcenc", "-tl", im, os.path.join(work, "ae.png"), footprint, str(effort), "-j", str(threads)])
        wall += dt
        enc.append(float(re.search(r"Coding time:\s+([0-9.]+)", text).group(1)))
        psnr.append(float(re.search(r"PSNR \(LDR-RGB\):\s+([0-9.]+)", text).group(1)))
    return wall, enc, psnr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--texproc", default=os.path.join(ROOT, "build", "cli", "texproc"))
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--work")
    ap.add_argument("--footprints", default="4x4,6x6,8x8")
    ap.add_argument("--presets", default=",".join(PRESETS))
    ap.add_argument("--threads", default="1,2")
    args = ap.parse_args()
    if not shutil.which("astcenc"):
        sys.exit("bench_astc: astcenc is not installed (Debian: astcenc)")
    work = args.work or tempfile.mkdtemp(prefix="bench_astc_")
    images = crops(work)
    texels = len(images) * 256 * 256
    print(f"# bench_astc: {len(images)} crops of 256x256, {args.rounds} interleaved rounds, medians")
    print(f"# {'fmt':<9} {'preset':<12} {'thr':>3} | {'texproc MT/s':>12} {'astcenc MT/s':>12} {'ratio':>6} | "
          f"{'wall tp s':>9} {'wall ae s':>9} | {'PSNR tp':>8} {'PSNR ae':>8} {'diff':>6}")
    for fp in args.footprints.split(","):
        for preset in args.presets.split(","):
            effort = PRESETS[preset]
            flags = ["--quality", QUALITY_OF[preset]] if preset in QUALITY_OF else ["--astc-effort", str(effort)]
            for threads in (int(t) for t in args.threads.split(",")):
                tp, ae = [], []
                for _ in range(args.rounds):
                    tp.append(texproc_batch(args.texproc, images, "astc-" + fp, flags, threads, work))
                    ae.append(astcenc_batch(images, fp, effort, threads, work))
                # Speed over every crop but the first, for both tools:
                # texproc makes its context during the first (astcenc's
                # "Coding time" leaves its own out).
                def med(rs):
                    return (statistics.median(r[0] for r in rs), statistics.median(sum(r[1][1:]) for r in rs),
                            pooled_psnr(rs[0][2]))
                (tw, te, tq), (aw, aenc, aq) = med(tp), med(ae)
                steady = texels * (len(images) - 1) / len(images)
                print(f"  astc-{fp:<4} {preset:<12} {threads:>3} | {steady / te / 1e6:12.3f} {steady / aenc / 1e6:12.3f} "
                      f"{aenc / te:6.2f} | {tw:9.2f} {aw:9.2f} | {tq:8.2f} {aq:8.2f} {tq - aq:+6.2f}",
                      flush=True)
    print("\n# the other mobile and desktop formats at texproc's normal, same crops (bits per texel, PSNR RGB, MT/s)")
    for fmt, bpt in (("etc2", 4.0), ("bc1", 4.0), ("etc2a", 8.0), ("bc3", 8.0)):
        for threads in (int(t) for t in args.threads.split(",")):
            rs = [texproc_batch(args.texproc, images, fmt, ["--quality", "normal"], threads, work) for _ in range(args.rounds)]
            te = statistics.median(sum(r[1]) for r in rs)
            print(f"  {fmt:<9} normal       {threads:>3} | {bpt:4.2f} bpt | {texels / te / 1e6:10.3f} MT/s | "
                  f"PSNR {pooled_psnr(rs[0][2]):6.2f}", flush=True)
    print("# ASTC bits per texel: 4x4 8.00, 6x6 3.56, 8x8 2.00")
    if not args.work:
        shutil.rmtree(work)


if __name__ == "__main__":
    main()
