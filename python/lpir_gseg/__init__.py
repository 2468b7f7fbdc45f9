"""LiDAR ground segmentation with the LPIR-GSeg method, numpy in and out.

    import lpir_gseg
    seg = lpir_gseg.Segmenter("hdl64e")                  # a GPU through Vulkan, else the CPU
    labels = seg.segment(lpir_gseg.read_cloud("scan.bin"))  # (N,) uint8, 1 ground
    for stamp_ns, points in lpir_gseg.read_drive("drive.mcap", "/points"):  # .mcap .db3 .bag
        labels = seg.segment(points)

Both backends give the labels `lpir-gseg segment` writes, byte for byte. `python3 -m
lpir_gseg.fleet` labels many files and drives on a Dask cluster (docs/fleet.md).
"""
import os
from pathlib import Path

from . import _core
from ._core import (
    WHY_GROUND,
    WHY_INVALID,
    WHY_NOISE,
    WHY_NON_GROUND,
    Segmenter,
    devices,
    evaluate,
    is_cloud_file,
    cloud_formats,
    read_cloud,
    read_labels,
    sensors,
    sensors_dir,
    simulate,
    write_labels,
)
from .drive import DriveTopic, drive_topics, is_drive_file, read_drive

__version__ = "0.1.0"

# The profiles ship inside the package (setup.py copies the repository's sensors/ here);
# $LPIR_SENSORS_DIR at import replaces them, as it does for the C++ library (DefaultSensorsDir).
_core._set_sensors_dir(os.environ.get("LPIR_SENSORS_DIR") or
                       str(Path(__file__).resolve().parent / "sensors"))

__all__ = [
    "Segmenter",
    "read_cloud",
    "read_drive",
    "drive_topics",
    "DriveTopic",
    "is_drive_file",
    "read_labels",
    "write_labels",
    "evaluate",
    "simulate",
    "sensors",
    "sensors_dir",
    "devices",
    "is_cloud_file",
    "cloud_formats",
    "WHY_NON_GROUND",
    "WHY_GROUND",
    "WHY_INVALID",
    "WHY_NOISE",
]
