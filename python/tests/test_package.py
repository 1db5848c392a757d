"""The package itself: its stubs match the module; it installs with pip offline."""
import ast
import inspect
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import texproc as tp

STUB = Path(tp.__file__).with_name("__init__.pyi")


def stub_names():
    tree = ast.parse(STUB.read_text())
    top, members = set(), {}
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            top.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            top.add(node.target.id)
        if isinstance(node, ast.ClassDef):
            members[node.name] = {n.name for n in node.body if isinstance(n, ast.FunctionDef)} | {
                n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
    return top, members


def test_stub_names_every_public_name_and_no_other():
    top, members = stub_names()
    assert top == set(tp.__all__)
    for name, names in members.items():
        cls = getattr(tp, name)
        if not issubclass(cls, Exception):
            public = {n for n in dir(cls) if not n.startswith("_")}
            assert public == names - {"__init__", "__enter__", "__exit__"}, name


def test_every_function_has_a_docstring():
    for name in tp.__all__:
        obj = getattr(tp, name)
        if callable(obj):
            assert inspect.getdoc(obj), name


def test_version_matches_the_project():
    root = Path(__file__).resolve().parents[2]
    text = (root / "CMakeLists.txt").read_text()
    assert f"project(texproc VERSION {tp.__version__}" in text
    assert ".".join(map(str, tp.version_info)) == tp.__version__


@pytest.mark.skipif(not os.environ.get("TEXPROC_CMAKE_BUILD_DIR"), reason="needs TEXPROC_CMAKE_BUILD_DIR")
def test_pip_installs_offline_and_finds_its_modules(tmp_path, samples):
    root = Path(__file__).resolve().parents[2]
    target = tmp_path / "site"
    # A copy, so that the build writes nothing into the source tree.
    shutil.copytree(root / "python", tmp_path / "src", ignore=shutil.ignore_patterns("tests", "__pycache__"))
    env = dict(os.environ, TEXPROC_SOURCE_DIR=str(root))
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index",
                    "--target", str(target), "--quiet", str(tmp_path / "src")], check=True, cwd=tmp_path, env=env)
    assert (target / "texproc" / "__init__.pyi").exists() and (target / "texproc" / "py.typed").exists()
    env = {k: v for k, v in os.environ.items() if not k.startswith("TEXPROC_") and k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(target)
    code = ("import texproc, sys; a = texproc.read_image(sys.argv[1]); print(texproc.__file__, a.dtype, a.shape)")
    out = subprocess.run([sys.executable, "-c", code, str(samples / "sky_forest_512x256.exr")], env=env,
                         check=True, capture_output=True, text=True, cwd=tmp_path).stdout
    assert str(target) in out and "float32" in out
