"""Shared fixtures of the lpir_gseg suite: where the real scans and the command line are, and the
scans the command line's own equality test uses (tests/cli_backend_vk_test.cpp)."""
import os
import subprocess
from pathlib import Path

import pytest

import lpir_gseg

REPO = Path(__file__).resolve().parents[2]
DATA = Path(os.environ.get("LPIR_DATA_DIR", REPO.parent / "shared" / "data"))
CLI = Path(os.environ.get("LPIR_CLI", REPO / "build" / "lpir-gseg"))

# Every real scan, grouped by the sensor it is segmented as.
REAL_SCANS = {
    "hdl64e": ["kitti/07/velodyne/000964.bin", "kitti/unknown/velodyne/000056.bin"] +
              [f"kitti/00/velodyne/00000{i}.bin" for i in range(6)],
    "hdl32e": ["nuscenes/n015-2018-07-24-11-22-45+0800__LIDAR_TOP__1532402927647951.pcd.bin",
               "hdl32e/source.ply", "hdl32e/target.ply"],
    "os1-64": ["rellis3d/os1/000104.bin", "rellis3d/os1/frame000104-1581624663_170.ply"],
    "vlp32c": ["rellis3d/vlp32c/000104.bin"],
    "mid70": ["livox/00/velodyne/000000.bin", "livox/05/velodyne/000003.bin",
              "livox/08/velodyne/000007.bin"],
}


def data_file(relative: str) -> Path:
    path = DATA / relative
    if not path.is_file():
        pytest.skip(f"{relative} is not under {DATA} (the real scans are not committed)")
    return path


@pytest.fixture(scope="session")
def cli() -> Path:
    if not CLI.is_file():
        pytest.skip(f"no lpir-gseg at {CLI} (scripts/build.sh builds it; LPIR_CLI points elsewhere)")
    return CLI


def run_cli(cli: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True)


def vulkan_usable() -> bool:
    return any(line.endswith(": usable") for line in lpir_gseg.devices())


@pytest.fixture(scope="session")
def vulkan():
    if not vulkan_usable():
        pytest.skip("no usable Vulkan device (scripts/test.sh points VK_ICD_FILENAMES at lavapipe)")
