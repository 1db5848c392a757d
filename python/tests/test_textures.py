"""Textures, containers and block compression."""
import threading

import numpy as np
import pytest

import texproc as tp


def test_compress_bytes_equal_the_cli(tmp_path, samples, cli):
    src = samples / "albedo_desert_512.png"
    cli("compress", src, "-o", tmp_path / "cli.ktx2", "--format", "bc7", "--mips")
    t = tp.compress(tp.read_image(str(src)), "bc7_srgb", mips=True)
    assert (t.format, t.width, t.height, t.levels) == ("bc7_srgb", 512, 512, 10)
    assert t.to_bytes("ktx2") == (tmp_path / "cli.ktx2").read_bytes()


def test_compress_normal_map_bc5_equals_the_cli(tmp_path, samples, cli):
    src = samples / "normal_stein_256.png"
    cli("compress", src, "-o", tmp_path / "cli.dds", "--format", "bc5", "--normal-map", "--mips", "--quality", "fast")
    t = tp.compress(tp.read_image(str(src)), "bc5_unorm", normal_map=True, mips=True, quality="fast")
    assert t.to_bytes("dds") == (tmp_path / "cli.dds").read_bytes()


def test_constant_block_decodes_to_its_colour():
    a = np.full((8, 8, 4), [255, 0, 0, 255], dtype=np.uint8)
    for fmt in ("bc1_rgb_unorm", "bc3_unorm", "bc7_unorm", "etc2_rgb_unorm"):
        t = tp.compress(a, fmt)
        assert t.image(0).nbytes == 4 * (8 if fmt in ("bc1_rgb_unorm", "etc2_rgb_unorm") else 16)
        d = t.decode(0)
        assert (d[:, :, 0] == 255).all() and (d[:, :, 1] == 0).all(), fmt


def test_every_container_round_trips_through_bytes():
    rng = np.random.default_rng(3)
    a = rng.integers(0, 255, (16, 16, 4), dtype=np.uint8)
    t = tp.compress(a, "etc2_rgb_unorm", mips=True)
    for container in ("ktx2", "ktx", "dds"):
        if container == "dds":
            t = tp.compress(a, "bc3_unorm", mips=True)  # DDS's DXT1 cannot say "opaque BC1"
        back = tp.Texture.from_bytes(t.to_bytes(container))
        assert (back.format, back.levels) == (t.format, t.levels)
        for level in range(t.levels):
            assert np.array_equal(back.image(level), t.image(level))
    one = tp.compress(a, "etc1_rgb")
    assert np.array_equal(tp.Texture.from_bytes(one.to_bytes("pkm")).image(0), one.image(0))
    z = t.to_bytes("ktx2", zstd=19)
    assert np.array_equal(tp.Texture.from_bytes(z).image(0), t.image(0))


def test_save_and_read_texture(tmp_path):
    a = np.zeros((4, 4, 4), dtype=np.uint8)
    t = tp.compress(a, "bc4_unorm")
    t.save(str(tmp_path / "t.dds"))
    assert tp.read_texture(str(tmp_path / "t.dds")).format == "bc4_unorm"


def test_cube_faces_make_a_cube_texture():
    faces = [np.full((8, 8, 4), [i * 40, 0, 0, 255], dtype=np.uint8) for i in range(6)]
    t = tp.compress(faces, "bc1_rgb_unorm", faces=6, mips=True)
    assert (t.faces, t.layers, t.levels) == (6, 1, 4)
    assert t.decode(0, 0, 5)[0, 0, 0] == 200


def test_views_keep_their_owner_alive():
    a = np.full((8, 8, 4), 7, dtype=np.uint8)
    t = tp.compress(a, "bc7_unorm", mips=True)
    view = t.image(0)
    expected = bytes(view)
    del t
    import gc
    gc.collect()
    assert bytes(view) == expected
    assert not view.flags.writeable
    levels = tp.generate_mips(a)
    first = levels[0]
    del levels
    gc.collect()
    assert (first == 7).all() and first.flags.owndata is False and first.base is not None


def test_thread_count_does_not_change_bytes(samples):
    a = tp.read_image(str(samples / "albedo_desert_512.png"))
    with tp.threads(1):
        assert tp.thread_limit() == 1
        one = tp.compress(a, "bc1_rgb_srgb", mips=True).to_bytes("dds")
    assert tp.compress(a, "bc1_rgb_srgb", mips=True).to_bytes("dds") == one


def test_work_runs_without_the_gil(samples):
    h = tp.read_image(str(samples / "height_stein_256.png"))
    ticks = 0
    done = threading.Event()

    def work():
        for _ in range(20):
            tp.cone_map(h)
        done.set()

    worker = threading.Thread(target=work)
    worker.start()
    while not done.is_set():
        ticks += 1
    worker.join()
    # With the GIL held through each call, this loop would hardly run.
    assert ticks > 10000


def test_format_names_and_info():
    names = tp.format_names()
    assert "bc7_srgb" in names and "astc_6x6_unorm" in names
    info = tp.format_info("bc1_rgb_unorm")
    assert (info["block_width"], info["block_bytes"], info["compressed"]) == (4, 8, True)
