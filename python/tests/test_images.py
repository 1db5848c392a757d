"""Images in and out, mip chains and comparisons: known answers and the CLI's bytes."""
import numpy as np
import pytest

import texproc as tp


def test_read_sample_png(samples):
    a = tp.read_image(str(samples / "albedo_desert_512.png"))
    assert a.shape == (512, 512, 3) and a.dtype == np.uint8
    info = tp.probe_image(str(samples / "albedo_desert_512.png"))
    assert (info["width"], info["height"], info["channels"], info["dtype"]) == (512, 512, 3, "uint8")


def test_read_exr_through_module(samples):
    a = tp.read_image(str(samples / "sky_forest_512x256.exr"))
    assert a.shape[:2] == (256, 512) and a.dtype == np.float32


@pytest.mark.parametrize("dtype,ext", [(np.uint8, "png"), (np.uint16, "png"), (np.uint16, "tif"),
                                       (np.float32, "exr"), (np.uint8, "tga")])
def test_write_read_round_trip(tmp_path, dtype, ext):
    rng = np.random.default_rng(1)
    if dtype == np.float32:
        a = rng.random((17, 23, 4), dtype=np.float32)
    else:
        a = rng.integers(0, np.iinfo(dtype).max, (17, 23, 4), dtype=dtype, endpoint=True)
    path = str(tmp_path / f"a.{ext}")
    tp.write_image(path, a)
    b = tp.read_image(path)
    assert b.dtype == a.dtype and np.array_equal(a, b)


def test_two_dimensional_input_is_one_channel(tmp_path):
    a = np.arange(64, dtype=np.uint8).reshape(8, 8)
    tp.write_image(str(tmp_path / "g.png"), a)
    assert np.array_equal(tp.read_image(str(tmp_path / "g.png"))[:, :, 0], a)


def test_strided_and_sliced_inputs_read_the_same_pixels():
    rng = np.random.default_rng(2)
    big = rng.integers(0, 255, (64, 96, 4), dtype=np.uint8)
    for view in (big[:, :64], big[::2, :32], big[:, ::-1], np.asfortranarray(big)):
        assert np.array_equal(tp.generate_mips(view)[0], np.ascontiguousarray(view))


def test_mip_of_black_and_white_is_srgb_188():
    # Two texels, sRGB 0 and 255: their mean light is 0.5, sRGB code 188
    # (a byte average would give 128).
    a = np.array([[[0, 0, 0], [255, 255, 255]]], dtype=np.uint8)
    levels = tp.generate_mips(a, filter="box")
    assert [lv.shape for lv in levels] == [(1, 2, 3), (1, 1, 3)]
    assert levels[1].tolist() == [[[188, 188, 188]]]
    linear = tp.generate_mips(a, filter="box", color_space="linear")
    assert linear[1].tolist() == [[[128, 128, 128]]]


def test_mip_chain_of_constant_image_is_constant():
    a = np.full((37, 20, 4), [10, 200, 77, 255], dtype=np.uint8)
    levels = tp.generate_mips(a, filter="kaiser")
    assert len(levels) == 6 and levels[-1].shape == (1, 1, 4)
    for lv in levels:
        assert (lv == [10, 200, 77, 255]).all()


def test_mip_bytes_equal_the_cli(tmp_path, samples, cli):
    src = samples / "albedo_desert_512.png"
    cli("mip", src, "-o", tmp_path / "cli.dds")
    levels = tp.generate_mips(tp.read_image(str(src)))
    ours = tp.Texture.from_levels(levels, srgb=True).to_bytes("dds")
    assert ours == (tmp_path / "cli.dds").read_bytes()


def test_compare_known_answers():
    a = np.zeros((4, 4, 1), dtype=np.uint8)
    b = a.copy()
    b[0, 0, 0] = 255
    d = tp.compare(a, b)
    assert d.differing_texels == 1
    assert d.mse == pytest.approx(1 / 16)
    assert d.psnr == pytest.approx(10 * np.log10(16))
    assert tp.compare(a, a).psnr == float("inf")
    assert tp.ssim(a, a) == [pytest.approx(1.0)]


def test_compare_counts_nan_as_difference():
    a = np.zeros((2, 2, 3), dtype=np.float32)
    b = a.copy()
    b[1, 1, 2] = np.nan
    d = tp.compare(a, b)
    assert d.nonfinite_texels == 1 and d.differing_texels == 1 and np.isnan(d.psnr)
