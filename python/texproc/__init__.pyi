# Type stubs of the texproc package (the extension module texproc._texproc).
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

# uint8, uint16 or float32; H x W x C (C 1 to 4) or H x W.
ImageLike = npt.ArrayLike
DType = Union[str, type, np.dtype]
Surfaces = Union[ImageLike, Sequence[ImageLike]]

__version__: str
version_info: tuple[int, int, int]

class Error(Exception):
    code: int

class BadArgumentsError(Error, ValueError): ...
class IoError(Error, OSError): ...
class InvalidFileError(Error): ...
class UnsupportedError(Error): ...

def hardware_threads() -> int: ...
def thread_limit() -> int: ...
def simd_target() -> str: ...

class threads:
    def __init__(self, count: int) -> None: ...
    def __enter__(self) -> None: ...
    def __exit__(self, *args: Any) -> None: ...

# Images
def read_image(path: str) -> np.ndarray: ...
def probe_image(path: str) -> dict[str, Any]: ...
def write_image(
    path: str,
    image: ImageLike,
    *,
    half: bool = False,
    compression: str = "",
    color_space: str = "",
    quality: int = 95,
    red_green: bool = False,
) -> None: ...
def generate_mips(
    image: ImageLike,
    *,
    filter: str = "gaussian",
    sigma: float = 0.5,
    wrap: str = "clamp",
    color_space: str = "",
    output_color_space: str = "",
    dtype: Optional[DType] = None,
    premultiplied_alpha: bool = True,
    alpha_coverage: Optional[float] = None,
    normal_map: bool = False,
    max_levels: int = 0,
    min_size: int = 1,
) -> list[np.ndarray]: ...

class Difference:
    width: int
    height: int
    channels: int
    mse: float
    mse_rgb: float
    max_abs: float
    differing_texels: int
    nonfinite_texels: int
    hdr: bool
    psnr: float
    psnr_rgb: float
    log_rmse_rgb: float
    channel_mse: list[float]
    channel_max_abs: list[float]
    def psnr_channel(self, channel: int) -> float: ...

def compare(a: ImageLike, b: ImageLike) -> Difference: ...
def ssim(a: ImageLike, b: ImageLike) -> list[float]: ...

# Textures and block compression
class Texture:
    format: str
    width: int
    height: int
    levels: int
    faces: int
    layers: int
    is_array: bool
    def level_size(self, level: int) -> tuple[int, int]: ...
    def image(self, level: int = 0, layer: int = 0, face: int = 0) -> np.ndarray: ...
    def decode(self, level: int = 0, layer: int = 0, face: int = 0, dtype: DType = "uint8") -> np.ndarray: ...
    def to_bytes(self, container: str = "ktx2", *, zstd: int = 0, dds_header: str = "auto") -> bytes: ...
    def save(self, path: str, *, zstd: int = 0, dds_header: str = "auto") -> None: ...
    @staticmethod
    def from_bytes(data: Union[bytes, bytearray, memoryview], name: str = "<bytes>") -> Texture: ...
    @staticmethod
    def from_levels(levels: Sequence[ImageLike], *, srgb: bool = False, half: bool = False) -> Texture: ...
    @staticmethod
    def from_surfaces(
        chains: Sequence[Sequence[ImageLike]],
        *,
        faces: int = 1,
        is_array: bool = False,
        srgb: bool = False,
        half: bool = False,
    ) -> Texture: ...

def read_texture(path: str) -> Texture: ...
def compress(
    image: Surfaces,
    format: str,
    *,
    quality: str = "normal",
    mips: bool = False,
    faces: int = 1,
    is_array: bool = False,
    color_space: str = "",
    normal_map: bool = False,
    transparent_color: str = "keep",
    bc1_black: bool = False,
    astc_effort: Optional[float] = None,
    filter: str = "gaussian",
    sigma: float = 0.5,
    wrap: str = "clamp",
    alpha_coverage: Optional[float] = None,
    premultiplied_alpha: bool = True,
    max_levels: int = 0,
    min_size: int = 1,
) -> Texture: ...
def format_names() -> list[str]: ...
def format_info(format: str) -> dict[str, Any]: ...

# Normal maps, cone maps, summed-area tables
def normal_map(
    heights: ImageLike,
    *,
    kernel: str = "sobel3",
    height_channel: str = "auto",
    invert: bool = False,
    height_scale: float = 8.0,
    strength: float = 1.0,
    wrap: str = "clamp",
    y_up: bool = True,
    channels: str = "xyz",
    multiscale_weights: Optional[Sequence[float]] = None,
    dtype: Optional[DType] = None,
) -> np.ndarray: ...
def cone_map(
    heights: ImageLike,
    *,
    depth: float = 1.0,
    max_ratio: float = 1.0,
    wrap: str = "repeat",
    fast_reach: int = 0,
    mode: str = "conservative",
    bilinear_safe: bool = False,
    height_channel: str = "auto",
    invert: bool = False,
    channels: int = 3,
    dtype: Optional[DType] = None,
) -> np.ndarray: ...
def cone_ratios(
    heights: ImageLike,
    *,
    depth: float = 1.0,
    max_ratio: float = 1.0,
    wrap: str = "repeat",
    fast_reach: int = 0,
    mode: str = "conservative",
    bilinear_safe: bool = False,
    height_channel: str = "auto",
    invert: bool = False,
) -> np.ndarray: ...

class SummedAreaTable:
    width: int
    height: int
    channels: int
    precision: str
    max_exact_box: int
    def error_bound(self) -> float: ...
    def box_sum(self, x0: int, y0: int, x1: int, y1: int) -> list[float]: ...
    def box_sums(self, boxes: npt.ArrayLike) -> np.ndarray: ...
    def save(self, path: str) -> None: ...

def build_sat(image: ImageLike, *, precision: str = "") -> SummedAreaTable: ...
def read_sat(path: str) -> SummedAreaTable: ...
def box_blur(
    image: ImageLike,
    *,
    radius: float = 4.0,
    radius_map: Optional[ImageLike] = None,
    wrap: str = "clamp",
    color_space: str = "",
) -> np.ndarray: ...

# Cube maps and image-based lighting
class Cubemap:
    size: int
    levels: int
    def face(self, face: int, level: int = 0) -> np.ndarray: ...
    @staticmethod
    def from_equirect(panorama: ImageLike, *, size: int = 0, flip: str = "none", color_space: str = "") -> Cubemap: ...
    @staticmethod
    def from_faces(faces: Sequence[ImageLike], *, color_space: str = "") -> Cubemap: ...
    @staticmethod
    def from_layout(image: ImageLike, layout: str = "auto", *, color_space: str = "") -> Cubemap: ...
    def with_mips(self, max_levels: int = 0) -> Cubemap: ...
    def to_equirect(self, width: int, level: int = 0) -> np.ndarray: ...
    def to_layout(self, layout: str, level: int = 0) -> np.ndarray: ...
    def to_texture(self, dtype: str = "float16") -> Texture: ...

def prefilter_specular(
    source: Cubemap,
    *,
    size: int = 0,
    levels: int = 0,
    min_size: int = 8,
    samples: int = 512,
    exact_budget: float = 1.0e9,
) -> Cubemap: ...
def irradiance(source: Cubemap, *, size: int = 32) -> Cubemap: ...
def sh9(source: Cubemap) -> np.ndarray: ...
