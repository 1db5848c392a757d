"""Every example of docs/python.md runs, in order, on the samples."""
import os
import re
import shutil
from pathlib import Path

DOC = Path(__file__).resolve().parents[2] / "docs" / "python.md"


def test_the_examples_run(tmp_path, samples, monkeypatch):
    (tmp_path / "textures").mkdir()
    for name in ("albedo_desert_512.png", "height_stein_256.png"):
        shutil.copy(samples / name, tmp_path / "textures" / name)
    shutil.copy(samples / "sky_forest_512x256.exr", tmp_path / "sky.exr")
    monkeypatch.chdir(tmp_path)
    blocks = re.findall(r"```python\n(.*?)```", DOC.read_text(), re.S)
    assert len(blocks) >= 5
    namespace = {}
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), namespace)
    assert sorted(os.listdir(tmp_path / "cooked")) == ["albedo_desert_512.ktx2", "height_stein_256.ktx2"]
    for name in ("normal.png", "cone.png", "normal.ktx2", "specular.ktx2", "irradiance.ktx2"):
        assert (tmp_path / name).stat().st_size > 0, name
    assert namespace["sums"].shape == (2, namespace["table"].channels)
