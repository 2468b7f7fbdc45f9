"""The labels lpir_gseg gives on every real scan are the bytes `lpir-gseg segment` writes, on
both backends, through segment, segment_batch and write_labels."""
import json
from pathlib import Path

import numpy as np
import pytest

import lpir_gseg
from conftest import DATA, REAL_SCANS, data_file, run_cli


def label_bytes(labels: np.ndarray) -> bytes:
    return labels.astype("<u4").tobytes()


@pytest.fixture(scope="module")
def cli_labels(cli, tmp_path_factory):
    """{(sensor, scan): the .label bytes the command line writes with --backend cpu}."""
    out = {}
    for sensor, scans in REAL_SCANS.items():
        present = [s for s in scans if (DATA / s).is_file()]
        if not present:
            continue
        folder = tmp_path_factory.mktemp(f"cli_{sensor}")
        files = [data_file(s) for s in present]
        result = run_cli(cli, "segment", *files, "--sensor", sensor, "--backend", "cpu", "--out",
                         folder, "--quiet")
        assert result.returncode == 0, result.stderr
        for scan, path in zip(present, files):
            out[(sensor, scan)] = (folder / (path.stem + ".label")).read_bytes()
    return out


CASES = [(sensor, scan) for sensor, scans in REAL_SCANS.items() for scan in scans]


@pytest.mark.parametrize("sensor,scan", CASES, ids=[f"{s}-{Path(p).name}" for s, p in CASES])
def test_cpu_labels_equal_the_cli(sensor, scan, cli_labels):
    path = data_file(scan)
    labels = lpir_gseg.Segmenter(sensor, backend="cpu").segment(lpir_gseg.read_cloud(path))
    assert labels.dtype == np.uint8 and labels.ndim == 1
    expected = cli_labels[(sensor, scan)]
    assert len(expected) == 4 * len(labels)
    assert label_bytes(labels) == expected, f"{scan}: labels differ from the CLI's"


@pytest.mark.parametrize("sensor", list(REAL_SCANS))
def test_vulkan_labels_equal_the_cli(sensor, cli_labels, vulkan, tmp_path):
    scans = [s for s in REAL_SCANS[sensor] if (sensor, s) in cli_labels]
    if not scans:
        pytest.skip(f"none of the {sensor} scans is under {DATA}")
    segmenter = lpir_gseg.Segmenter(sensor, backend="vulkan")
    assert segmenter.backend == "vulkan" and segmenter.device
    clouds = [lpir_gseg.read_cloud(data_file(s)) for s in scans]
    one_by_one = [segmenter.segment(c) for c in clouds]
    batched = segmenter.segment_batch(clouds)
    for scan, labels, again in zip(scans, one_by_one, batched):
        expected = cli_labels[(sensor, scan)]
        assert label_bytes(labels) == expected, f"{scan}: Vulkan labels differ from the CLI's"
        assert label_bytes(again) == expected, f"{scan}: segment_batch differs from the CLI's"
    # The writer gives the CLI's file, byte for byte.
    out = tmp_path / "out.label"
    lpir_gseg.write_labels(out, one_by_one[0])
    assert out.read_bytes() == cli_labels[(sensor, scans[0])]


def test_batched_vulkan_frames_equal_the_cpu(vulkan):
    paths = [data_file(s) for s in REAL_SCANS["hdl64e"]]
    clouds = [lpir_gseg.read_cloud(p) for p in paths]
    cpu = [lpir_gseg.Segmenter("hdl64e", backend="cpu").segment(c, why=True) for c in clouds]
    batched = lpir_gseg.Segmenter("hdl64e", backend="vulkan", batch=3,
                                  frames_in_flight=2).segment_batch(clouds, why=True)
    for (label, why), (label_vk, why_vk) in zip(cpu, batched):
        np.testing.assert_array_equal(label, label_vk)
        np.testing.assert_array_equal(why, why_vk)


def test_ring_field_travels_with_read_cloud():
    path = data_file(REAL_SCANS["hdl32e"][0])  # nuScenes: the fifth float is the ring
    points, ring = lpir_gseg.read_cloud(path, ring=True)
    assert ring is not None and ring.dtype == np.int32 and len(ring) == len(points)
    segmenter = lpir_gseg.Segmenter("hdl32e", backend="cpu")
    np.testing.assert_array_equal(segmenter.segment(points),
                                  segmenter.segment(points.copy(), ring=ring))
    # A copy loses the ring: the rows come from the elevations instead. Under hdl32e both ways
    # label this scan alike, so the check uses a 64-row profile, on which the 32 ring values and
    # the elevations put the points in different rows.
    rows64 = lpir_gseg.Segmenter("hdl64e", backend="cpu")
    with_ring = rows64.segment(points)
    np.testing.assert_array_equal(with_ring, rows64.segment(points.copy(), ring=ring))
    assert not np.array_equal(with_ring, rows64.segment(points.copy()))


def test_evaluate_matches_the_cli(cli, tmp_path):
    scans = ["kitti/07/velodyne/000964.bin", "kitti/00/velodyne/000000.bin"]
    paths = [data_file(s) for s in scans]
    gts = [data_file(s.replace("velodyne", "labels").replace(".bin", ".label")) for s in scans]
    segmenter = lpir_gseg.Segmenter("hdl64e", backend="cpu")
    preds = [segmenter.segment(lpir_gseg.read_cloud(p)) for p in paths]
    truth = [lpir_gseg.read_labels(g) for g in gts]
    (tmp_path / "pred").mkdir()
    for path, pred in zip(paths, preds):
        lpir_gseg.write_labels(tmp_path / "pred" / (path.stem + ".label"), pred)
    result = run_cli(cli, "evaluate", "--pred", tmp_path / "pred", "--gt", *gts, "--protocol",
                     "dg,pp,gg", "--json")
    assert result.returncode == 0, result.stderr
    report = json.loads(result.stdout)
    for protocol in ["dg", "pp", "gg"]:
        scores = lpir_gseg.evaluate(preds, truth, protocol)
        assert scores["frames"] == 2 and scores["protocol"] == protocol
        for key in ["precision", "recall", "f1", "iou"]:
            assert scores[key] == report["total"][protocol][key], (protocol, key)
            for frame, expected in zip(scores["per_frame"], report["frames"]):
                assert frame[key] == expected[protocol][key], (protocol, key)
        one = lpir_gseg.evaluate(preds[0], truth[0], protocol)
        assert one["f1"] == report["frames"][0][protocol]["f1"]


def test_mount_is_each_clouds_own_with_a_per_frame_profile():
    livox = [data_file(s) for s in REAL_SCANS["mid70"]]
    segmenter = lpir_gseg.Segmenter("mid70", backend="cpu")
    heights = []
    for path in livox:
        segmenter.segment(lpir_gseg.read_cloud(path))
        mount = segmenter.mount
        assert mount["estimated"] is True, path
        assert 0.1 <= mount["sensor_height"] <= 3.0 and abs(mount["k_xz"]) <= 0.5, mount
        heights.append(mount["sensor_height"])
    assert len(set(heights)) == len(heights), "three recordings, three heights"
    fixed = lpir_gseg.Segmenter("hdl64e", backend="cpu")
    with pytest.warns(UserWarning, match="above the top beam"):  # a Livox cloud, a 64-beam profile
        fixed.segment(lpir_gseg.read_cloud(livox[0]))
    assert fixed.mount == {"sensor_height": pytest.approx(1.73), "k_xz": 0.0, "k_yz": 0.0,
                           "estimated": False}
