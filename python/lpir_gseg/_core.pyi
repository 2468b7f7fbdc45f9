"""Type stubs of lpir_gseg._core (python/src/*.cpp); the docstrings there say the rest."""
import os
from typing import (
    Any,
    Dict,
    Iterable,
    List,
    Literal,
    Mapping,
    Optional,
    Sequence,
    Tuple,
    Union,
    overload,
)

import numpy as np
import numpy.typing as npt

_Path = Union[str, bytes, "os.PathLike[str]", "os.PathLike[bytes]"]
_Points = npt.ArrayLike  # (N, 4) x, y, z, intensity, or (N, 3) x, y, z (intensity= optional)
_Labels = npt.NDArray[np.uint8]

WHY_NON_GROUND: int  # 0: measured, found non-ground
WHY_GROUND: int  # 1: ground
WHY_INVALID: int  # 2: NaN/Inf coordinates, at the origin, out of range or a ring outside the beams
WHY_NOISE: int  # 3: reflection noise below the ground (non-ground)

class Segmenter:
    """Labels one sensor's scans ground (1) or non-ground (0), on Vulkan or the CPU reference."""

    def __init__(
        self,
        sensor: _Path = "hdl64e",
        backend: Literal["auto", "cpu", "vulkan"] = "auto",
        device: Union[str, int, None] = None,
        max_points: Optional[int] = None,
        frames_in_flight: int = 2,
        batch: int = 1,
        validation: bool = False,
        params: Optional[Mapping[str, Union[float, int, str]]] = None,
        threads: Optional[int] = None,
    ) -> None: ...
    @overload
    def segment(
        self,
        points: _Points,
        *,
        intensity: Optional[npt.ArrayLike] = None,
        ring: Optional[npt.ArrayLike] = None,
        why: Literal[False] = False,
    ) -> _Labels: ...
    @overload
    def segment(
        self,
        points: _Points,
        *,
        intensity: Optional[npt.ArrayLike] = None,
        ring: Optional[npt.ArrayLike] = None,
        why: Literal[True],
    ) -> Tuple[_Labels, _Labels]: ...
    @overload
    def segment_batch(
        self, clouds: Iterable[_Points], *, why: Literal[False] = False
    ) -> List[_Labels]: ...
    @overload
    def segment_batch(
        self, clouds: Iterable[_Points], *, why: Literal[True]
    ) -> List[Tuple[_Labels, _Labels]]: ...
    @property
    def backend(self) -> Literal["cpu", "vulkan"]: ...
    @property
    def device(self) -> Optional[str]: ...
    @property
    def backend_note(self) -> str: ...
    @property
    def sensor(self) -> str: ...
    @property
    def max_points(self) -> int: ...
    @property
    def frames_in_flight(self) -> int: ...
    @property
    def threads(self) -> int: ...
    @property
    def on_cpu_driver(self) -> bool: ...
    @property
    def mount(self) -> Dict[str, Union[float, bool]]: ...

@overload
def read_cloud(
    path: _Path, *, nuscenes: Optional[bool] = None, ring: Literal[False] = False
) -> npt.NDArray[np.float32]: ...
@overload
def read_cloud(
    path: _Path, *, nuscenes: Optional[bool] = None, ring: Literal[True]
) -> Tuple[npt.NDArray[np.float32], Optional[npt.NDArray[np.int32]]]: ...
def read_labels(path: _Path, expected_points: int = 0) -> npt.NDArray[np.uint32]: ...
def write_labels(path: _Path, labels: npt.ArrayLike) -> None: ...
def evaluate(
    pred: Union[npt.ArrayLike, Sequence[npt.ArrayLike]],
    gt_labels: Union[npt.ArrayLike, Sequence[npt.ArrayLike]],
    protocol: Optional[Literal["dg", "pp", "pw", "gg", "rellis"]] = None,
    ontology: Literal["semantickitti", "rellis3d"] = "semantickitti",
    *,
    points: Union[npt.ArrayLike, Sequence[npt.ArrayLike], None] = None,
    by_class: bool = False,
    by_range: bool = False,
) -> Dict[str, Any]: ...
def simulate(
    sensor: _Path,
    seed: int,
    *,
    pitch: float = 0.0,
    roll: float = 0.0,
    scene: Literal["urban", "flat", "flat-objects"] = "urban",
    range_noise: float = 0.02,
    rings: bool = False,
    reflection_noise: bool = True,
) -> Tuple[npt.NDArray[np.float32], npt.NDArray[np.uint32]]: ...
def sensors() -> List[str]: ...
def sensors_dir() -> str: ...
def devices() -> List[str]: ...
def is_cloud_file(path: _Path) -> bool: ...
def cloud_formats() -> List[str]: ...
def is_drive_file(path: _Path) -> bool: ...
def _list_inputs(
    paths: Sequence[_Path], recursive: bool = False
) -> Tuple[List[Tuple[str, str, bool]], List[Tuple[str, str]]]: ...
def _set_sensors_dir(path: str) -> None: ...
def _output_paths(
    inputs: Sequence[Tuple[str, str, bool]], out_dir: _Path, extension: str
) -> List[str]: ...

class _Drive:
    def __init__(self, path: _Path, read_threads: int = 0) -> None: ...
    @property
    def path(self) -> str: ...
    def topics(self) -> List[Tuple[str, str, str, int]]: ...
    def listing_damage(self) -> List[str]: ...
    def notes(self) -> List[str]: ...
    def chunk_count(self) -> int: ...
    def chunks_indexed(self) -> bool: ...
    def select(self, topic: str, first_chunk: int = 0, last_chunk: int = 0) -> None: ...
    def next(self) -> Tuple[Any, ...]: ...
