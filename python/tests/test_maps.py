"""Normal maps, cone maps, summed-area tables, cube maps."""
import numpy as np
import pytest

import texproc as tp


def test_normal_map_of_a_45_degree_ramp():
    # Heights rising 1/height_scale per texel: a 45 degree slope, normal
    # (-1, 0, 1)/sqrt(2) away from the edges, with every kernel.
    w = 32
    ramp = np.tile(np.arange(w, dtype=np.float32) / 8.0, (16, 1))
    for kernel in ("central", "sobel3", "scharr3", "prewitt5"):
        n = tp.normal_map(ramp, height_scale=8.0, kernel=kernel, dtype="float32")
        inner = n[4:-4, 4:-4] * 2 - 1
        assert np.allclose(inner[..., 0], -np.sqrt(0.5), atol=1e-5), kernel
        assert np.allclose(inner[..., 1], 0, atol=1e-5) and np.allclose(inner[..., 2], np.sqrt(0.5), atol=1e-5)


def test_normal_map_equals_the_cli(tmp_path, samples, cli):
    src = samples / "height_stein_256.png"
    cli("normalmap", src, "-o", tmp_path / "n.png")
    assert np.array_equal(tp.normal_map(tp.read_image(str(src))), tp.read_image(str(tmp_path / "n.png")))


@pytest.mark.parametrize("fast", [False, True])
def test_cone_map_equals_the_cli(tmp_path, samples, cli, fast):
    src = samples / "height_mount_250.png"
    cli("conemap", src, "-o", tmp_path / "c.png", *(["--fast"] if fast else []))
    ours = tp.cone_map(tp.read_image(str(src)), fast_reach=2 if fast else 0)
    assert np.array_equal(ours, tp.read_image(str(tmp_path / "c.png")))


def test_cone_ratio_of_a_flat_field_is_the_cap():
    flat = np.zeros((16, 16), dtype=np.float32)
    assert np.allclose(tp.cone_ratios(flat, max_ratio=1.0), 1.0)


def test_sat_sums_equal_numpy_and_the_cli(tmp_path, samples, cli):
    src = samples / "albedo_desert_512.png"
    a = tp.read_image(str(src))
    t = tp.build_sat(a)
    assert (t.precision, t.max_exact_box) == ("u32", 16843009)
    boxes = np.array([[0, 0, 512, 512], [3, 5, 100, 77], [10, 10, 10, 20]])
    sums = t.box_sums(boxes)
    for (x0, y0, x1, y1), s in zip(boxes, sums):
        assert s.tolist() == a[y0:y1, x0:x1].astype(np.int64).sum(axis=(0, 1)).tolist()
    assert t.box_sum(3, 5, 100, 77) == sums[1].tolist()
    t.save(str(tmp_path / "py.sat"))
    cli("sat", src, "-o", tmp_path / "cli.sat")
    assert (tmp_path / "py.sat").read_bytes() == (tmp_path / "cli.sat").read_bytes()
    assert tp.read_sat(str(tmp_path / "py.sat")).box_sum(0, 0, 512, 512) == sums[0].tolist()
    with pytest.raises(tp.BadArgumentsError, match="not inside"):
        t.box_sum(0, 0, 513, 1)


def test_box_blur_of_constant_is_constant():
    a = np.full((20, 30, 3), 0.25, dtype=np.float32)
    assert np.allclose(tp.box_blur(a, radius=3.5, color_space="linear"), 0.25, atol=1e-6)


def test_cube_of_constant_sky_and_its_lighting():
    sky = np.full((32, 64, 3), 0.5, dtype=np.float32)
    cube = tp.Cubemap.from_equirect(sky, size=16)
    assert (cube.size, cube.levels) == (16, 1)
    assert np.allclose(cube.face(2)[..., :3], 0.5, atol=1e-5)
    # A constant radiance L: irradiance / pi is L; SH: L00 = L * 2 sqrt(pi), the rest 0.
    irr = tp.irradiance(cube, size=8)
    assert np.allclose(irr.face(0)[..., :3], 0.5, atol=1e-3)
    sh = tp.sh9(cube)
    assert sh.shape == (9, 3)
    assert np.allclose(sh[0], 0.5 * 2 * np.sqrt(np.pi), rtol=1e-3) and np.allclose(sh[1:], 0, atol=1e-3)
    spec = tp.prefilter_specular(cube.with_mips(), size=16, samples=64)
    assert spec.levels >= 2 and np.allclose(spec.face(4, spec.levels - 1)[..., :3], 0.5, atol=1e-3)
    t = cube.with_mips().to_texture("float16")
    assert (t.format, t.faces, t.levels) == ("rgba16_float", 6, 5)
    view = cube.face(0)
    del cube
    assert np.allclose(view[..., :3], 0.5, atol=1e-5)
