#!/usr/bin/python3
"""Peak resident memory of each command on a large image, against what the
command must hold: the input image decoded (its pixels at their type) plus
the output it writes (the files' bytes); compare holds both images it
compares, decompress the texture it reads. The target is a ratio of at most
1.25 for every command.

  bench/bench_memory.py [--texproc build/cli/texproc] [--size 8192] [--work DIR]
                        [--only NAME,...]

The input is a generated --size x --size RGBA 8-bit TGA (noise over a
gradient, so compressed outputs have realistic sizes). Peak memory is the
child's ru_maxrss (Linux, KiB), read with os.wait4: the kernel's figure,
independent of machine load.
"""
import argparse
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def make_tga(path, size, height=None):
    """An uncompressed 32-bit TGA, size x height (default square), numpy-free."""
    height = height or size
    import random
    rnd = random.Random(7)
    noise = bytes(rnd.getrandbits(8) for _ in range(4096))
    with open(path, "wb") as f:
        f.write(bytes([0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 0, 0]) + size.to_bytes(2, "little") +
                height.to_bytes(2, "little") + bytes([32, 8 | 32]))
        for y in range(height):
            g = (y * 255 // max(1, height - 1)) & 0xFF
            row = bytearray(size * 4)
            for x in range(0, size * 4, 4096):
                chunk = noise[(y * 31) % 4096:] + noise
                n = min(4096, size * 4 - x)
                row[x:x + n] = chunk[:n]
            row[1::4] = bytes([g]) * size
            row[3::4] = b"\xff" * size
            f.write(row)


def measure(cmd):
    pid = os.fork()
    if pid == 0:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 1)
        os.dup2(devnull, 2)
        try:
            os.execv(cmd[0], cmd)
        finally:
            os._exit(127)
    _, status, usage = os.wait4(pid, 0)
    return os.waitstatus_to_exitcode(status), usage.ru_maxrss * 1024


def outputs_size(work, stem):
    total = 0
    for name in os.listdir(work):
        if name.startswith(stem):
            total += os.path.getsize(os.path.join(work, name))
    return total


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--texproc", default=os.path.join(ROOT, "build", "cli", "texproc"))
    ap.add_argument("--size", type=int, default=8192)
    ap.add_argument("--work", default="")
    ap.add_argument("--only", default="")
    a = ap.parse_args()
    T = os.path.abspath(a.texproc)
    work = a.work or tempfile.mkdtemp(prefix="texproc_mem_")
    os.makedirs(work, exist_ok=True)
    src = os.path.join(work, "in.tga")
    if not os.path.exists(src):
        make_tga(src, a.size)
    pano = os.path.join(work, "pano.tga")  # 2:1, for cubemap
    if not os.path.exists(pano):
        make_tga(pano, a.size, a.size // 2)
    input_bytes = a.size * a.size * 4
    cases = [
        ("info", [T, "info", src], None),
        ("mip -> dds", [T, "mip", src, "-o", "{w}/o_mip.dds", "-f", "-q"], "o_mip"),
        ("mip -> exr", [T, "mip", src, "-o", "{w}/o_exr.exr", "-f", "-q"], "o_exr"),
        ("mip -> tif", [T, "mip", src, "-o", "{w}/o_tif.tif", "-f", "-q"], "o_tif"),
        ("mip -> png", [T, "mip", src, "-o", "{w}/o_png.png", "-f", "-q"], "o_png"),
        ("sat", [T, "sat", src, "-o", "{w}/o_sat.sat", "-f", "-q"], "o_sat"),
        ("normalmap", [T, "normalmap", src, "-o", "{w}/o_nrm.png", "-f", "-q"], "o_nrm"),
        ("compress bc1 --mips", [T, "compress", src, "-o", "{w}/o_bc1.dds", "--format", "bc1", "--mips", "-f", "-q"],
         "o_bc1"),
        ("compress bc7 fast", [T, "compress", src, "-o", "{w}/o_bc7.ktx2", "--format", "bc7", "--quality", "fast",
                               "-f", "-q"], "o_bc7"),
        ("decompress", [T, "decompress", "{w}/o_bc1.dds", "-o", "{w}/o_dec.png", "-f", "-q"], "o_dec"),
        ("compress astc fast", [T, "compress", src, "-o", "{w}/o_astc.ktx2", "--format", "astc-6x6", "--quality",
                                "fast", "-f", "-q"], "o_astc"),
        ("conemap --fast", [T, "conemap", src, "-o", "{w}/o_cone.png", "--fast", "-f", "-q"], "o_cone"),
        ("cubemap --mips", [T, "cubemap", pano, "-o", "{w}/o_cube.ktx2", "--mips", "-f", "-q"], "o_cube"),
        ("compare", [T, "compare", src, "{w}/o_bc1.dds"], None),
    ]
    only = set(filter(None, a.only.split(",")))
    print(f"# peak RSS, {a.size}x{a.size} RGBA u8 input ({input_bytes / 2**20:.0f} MiB decoded)")
    print(f"{'command':<22} {'peak MiB':>9} {'in+out MiB':>11} {'ratio':>6}  target 1.25")
    worst = 0.0
    for name, cmd, stem in cases:
        if only and name not in only:
            continue
        argv = [c.replace("{w}", work) for c in cmd]
        rc, peak = measure(argv)
        if rc == 7 and name == "compare":
            rc = 0  # the images differ: compare's answer, not a failure
        if rc != 0:
            print(f"{name:<22} failed with exit {rc}")
            continue
        # decompress reads the BC1 file; compare decodes both images it compares.
        if name == "decompress":
            inp = os.path.getsize(os.path.join(work, "o_bc1.dds"))
        else:
            inp = {"compare": 2 * input_bytes, "cubemap --mips": input_bytes // 2}.get(name, input_bytes)
        out = outputs_size(work, stem) if stem else 0
        ratio = peak / (inp + out)
        worst = max(worst, ratio)
        print(f"{name:<22} {peak / 2**20:9.0f} {(inp + out) / 2**20:11.0f} {ratio:6.2f}  "
              f"{'met' if ratio <= 1.25 else 'NOT met'}")
    print(f"worst ratio {worst:.2f}")
    if not a.work:
        shutil.rmtree(work)


if __name__ == "__main__":
    sys.exit(main())
