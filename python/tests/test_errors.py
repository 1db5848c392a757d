"""texproc's errors as Python exceptions, with the library's messages."""
import numpy as np
import pytest

import texproc as tp


def test_missing_file_is_an_io_error_naming_it(tmp_path):
    path = str(tmp_path / "absent.png")
    with pytest.raises(tp.IoError) as e:
        tp.read_image(path)
    assert path in str(e.value) and e.value.code == 2
    assert isinstance(e.value, OSError) and isinstance(e.value, tp.Error)


def test_truncated_texture_bytes_are_invalid():
    t = tp.compress(np.zeros((8, 8, 4), dtype=np.uint8), "bc1_rgb_unorm")
    data = t.to_bytes("dds")
    with pytest.raises(tp.InvalidFileError) as e:
        tp.Texture.from_bytes(data[:-3], name="cut.dds")
    assert "cut.dds" in str(e.value) and e.value.code == 3
    with pytest.raises(tp.InvalidFileError, match="no signature"):
        tp.Texture.from_bytes(b"not a texture at all")


def test_bad_arguments_are_value_errors():
    a = np.zeros((4, 4, 3), dtype=np.uint8)
    with pytest.raises(tp.BadArgumentsError, match="float64"):
        tp.generate_mips(a.astype(np.float64))
    with pytest.raises(ValueError, match="5 dimensions|shape"):
        tp.compress(np.zeros((1, 1, 1, 1, 1), dtype=np.uint8), "bc1_rgb_unorm")
    with pytest.raises(tp.BadArgumentsError, match="bc7_srgb"):
        tp.compress(a, "bc99")
    with pytest.raises(tp.BadArgumentsError, match="gaussian"):
        tp.generate_mips(a, filter="cubic-ish")
    with pytest.raises(tp.BadArgumentsError, match="outside the texture"):
        tp.compress(a, "bc1_rgb_unorm").decode(level=3)
    with pytest.raises(tp.BadArgumentsError):
        tp.normal_map(a, height_scale=-1)


def test_write_to_a_missing_folder_leaves_nothing(tmp_path):
    with pytest.raises(tp.IoError):
        tp.write_image(str(tmp_path / "no" / "such" / "a.png"), np.zeros((2, 2, 3), dtype=np.uint8))
    assert not (tmp_path / "no").exists()


def test_non_finite_input_warns_and_reads_as_zero():
    a = np.zeros((4, 4, 4), dtype=np.float32)
    a[0, 0, 0] = np.nan
    with pytest.warns(RuntimeWarning, match="non-finite"):
        t = tp.compress(a, "bc7_unorm")
    assert (t.decode(0)[..., 0] == 0).all()
    assert np.isnan(a[0, 0, 0])  # the caller's array is never written
