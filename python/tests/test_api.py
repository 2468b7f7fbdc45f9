"""The Python API on simulated scans (no data needed): input forms, reason codes, errors that
name the argument or the file, the simulator, the scores, the shipped profiles, the stubs."""
import ast
import inspect
import json
import os
import subprocess
import sys
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import lpir_gseg
from conftest import REPO, data_file, run_cli, vulkan_usable


@pytest.fixture(scope="module")
def scan():
    return lpir_gseg.simulate("hdl64e", 7)


@pytest.fixture(scope="module")
def cpu():
    return lpir_gseg.Segmenter("hdl64e", backend="cpu")


def test_every_input_form_gives_the_same_labels(scan, cpu):
    points, _ = scan
    expected = cpu.segment(points)
    assert expected.dtype == np.uint8 and expected.shape == (len(points),)
    assert set(np.unique(expected)) <= {0, 1} and 0 < expected.sum() < len(expected)
    copy = np.array(points)  # a plain array, not read_cloud's
    np.testing.assert_array_equal(cpu.segment(copy), expected)
    np.testing.assert_array_equal(cpu.segment(copy[:, :3], intensity=copy[:, 3]), expected)
    np.testing.assert_array_equal(cpu.segment(copy.astype(np.float64)), expected)
    np.testing.assert_array_equal(cpu.segment(np.asfortranarray(copy)), expected)
    wide = np.zeros((len(copy), 8), np.float32)
    wide[:, :4] = copy
    np.testing.assert_array_equal(cpu.segment(wide[:, :4]), expected)  # strided rows
    few = copy[:100]  # a list of lists; its labels are those of the same 100 points as an array
    np.testing.assert_array_equal(cpu.segment(few.tolist()), cpu.segment(few))


def test_why_codes(scan, cpu):
    points, _ = scan
    bad = np.array(points)
    bad[:3] = [np.nan, 0, 0, 0]
    labels, why = cpu.segment(bad, why=True)
    assert why.dtype == np.uint8 and why.shape == labels.shape
    assert list(why[:3]) == [lpir_gseg.WHY_INVALID] * 3 and not labels[:3].any()
    np.testing.assert_array_equal(labels == 1, why == lpir_gseg.WHY_GROUND)
    deep = np.array(points)
    deep[:5, 2] = -1.73 - 3.0  # 3 m under the road: reflection noise (h_noise: 2 m under it)
    labels, why = cpu.segment(deep, why=True)
    assert list(why[:5]) == [lpir_gseg.WHY_NOISE] * 5
    assert not labels[why == lpir_gseg.WHY_NOISE].any()


def test_empty_scan(cpu):
    assert cpu.segment(np.zeros((0, 4), np.float32)).shape == (0,)
    assert cpu.segment_batch([]) == []


def test_properties(cpu):
    assert cpu.backend == "cpu" and cpu.device is None and cpu.sensor == "hdl64e"
    assert cpu.max_points == 64 * 2048 * 2 and cpu.frames_in_flight == 2
    assert "CPU reference" in cpu.backend_note and "hdl64e" in repr(cpu)
    auto = lpir_gseg.Segmenter("vlp16")
    assert auto.backend in ("cpu", "vulkan") and auto.backend_note


def test_profile_by_path(scan, cpu):
    path = Path(lpir_gseg.sensors_dir()) / "hdl64e.txt"
    by_path = lpir_gseg.Segmenter(path, backend="cpu")
    np.testing.assert_array_equal(by_path.segment(scan[0]), cpu.segment(scan[0]))


def test_batch_equals_one_by_one(cpu):
    clouds = [lpir_gseg.simulate("hdl64e", seed)[0] for seed in range(3)]
    for labels, (batch_labels, why) in zip([cpu.segment(c) for c in clouds],
                                           cpu.segment_batch(clouds, why=True)):
        np.testing.assert_array_equal(labels, batch_labels)
        assert why.shape == labels.shape


def test_cpu_threads_never_change_a_label():
    clouds = [lpir_gseg.simulate("hdl64e", seed)[0] for seed in range(3)]
    one = lpir_gseg.Segmenter("hdl64e", backend="cpu", threads=1)
    assert one.threads == 1
    expected = [one.segment(c, why=True) for c in clouds]
    for threads in (2, 3, 8):
        many = lpir_gseg.Segmenter("hdl64e", backend="cpu", threads=threads)
        assert many.threads == threads
        for (labels, why), cloud in zip(expected, clouds):
            got_labels, got_why = many.segment(cloud, why=True)
            np.testing.assert_array_equal(got_labels, labels)
            np.testing.assert_array_equal(got_why, why)
        for (labels, _), got in zip(expected, many.segment_batch(clouds)):
            np.testing.assert_array_equal(got, labels)
    assert lpir_gseg.Segmenter("hdl64e", backend="cpu").threads == len(os.sched_getaffinity(0))
    with pytest.raises(ValueError, match="threads must be from 1 to 1024, not 0"):
        lpir_gseg.Segmenter("hdl64e", backend="cpu", threads=0)
    with pytest.raises(TypeError, match="threads must be an int or None"):
        lpir_gseg.Segmenter("hdl64e", backend="cpu", threads=2.0)


def test_threads_share_a_segmenter(cpu):
    clouds = [lpir_gseg.simulate("hdl64e", seed)[0] for seed in range(4)]
    expected = [cpu.segment(c) for c in clouds]
    results = [None] * 8
    errors = []

    def work(i):
        try:
            results[i] = cpu.segment(np.array(clouds[i % 4]))  # the copying path, scratch shared
        except Exception as error:  # noqa: BLE001
            errors.append(error)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for i, labels in enumerate(results):
        np.testing.assert_array_equal(labels, expected[i % 4])


def test_the_gil_is_released_while_segmenting(cpu):
    # With a switch interval far longer than the call, the main thread runs during the call only
    # if the call releases the GIL; else it runs after the worker thread has finished.
    clouds = [lpir_gseg.simulate("hdl64e", seed)[0] for seed in range(3)] * 20  # 0.5 s or more
    state = {"finished": False}
    started = threading.Event()

    def work():
        started.set()
        cpu.segment_batch(clouds)
        state["finished"] = True

    interval = sys.getswitchinterval()
    sys.setswitchinterval(30)
    try:
        thread = threading.Thread(target=work)
        thread.start()
        started.wait()
        time.sleep(0.02)
        seen_during_the_call = not state["finished"]
        thread.join()
    finally:
        sys.setswitchinterval(interval)
    assert seen_during_the_call


@pytest.mark.parametrize("points,message", [
    (np.zeros((5,), np.float32), r"points must have shape \(N, 4\).*not \(5,\)"),
    (np.zeros((5, 5), np.float32), r"not \(5, 5\)"),
    (np.zeros((5, 4), np.complex64), r"real numbers.*complex64"),
    (np.zeros((5, 4), bool), r"real numbers.*bool"),
    (np.array([["a", "b", "c", "d"]]), r"real numbers"),
    (None, r"points is None"),
])
def test_bad_points_raise_value_error(cpu, points, message):
    with pytest.raises(ValueError, match=message):
        cpu.segment(points)


def test_bad_companions_raise_value_error(cpu):
    points = np.zeros((5, 4), np.float32)
    with pytest.raises(ValueError, match="intensity= is for"):
        cpu.segment(points, intensity=np.zeros(5))
    with pytest.raises(ValueError, match=r"intensity must have shape \(5,\)"):
        cpu.segment(points[:, :3], intensity=np.zeros(4))
    with pytest.raises(ValueError, match="ring has 4 values for 5 points"):
        cpu.segment(points, ring=np.zeros(4, np.int32))
    with pytest.raises(ValueError, match="ring must hold integers"):
        cpu.segment(points, ring=np.zeros(5, np.float32))
    with pytest.raises(ValueError, match=r"ring\[0\] is 4294967295"):
        cpu.segment(points, ring=np.full(5, 2**32 - 1, np.uint32))


def test_too_many_points(scan):
    small = lpir_gseg.Segmenter("hdl64e", backend="cpu", max_points=1000)
    with pytest.raises(ValueError, match=r"points has \d+ points, more than .* 1000"):
        small.segment(scan[0])
    with pytest.raises(ValueError, match=r"clouds\[1\] has \d+ points"):
        small.segment_batch([scan[0][:10], scan[0]])
    assert small.segment(scan[0][:1000]).shape == (1000,)  # still usable


def test_labels_do_not_depend_on_the_unit_of_intensity(scan, cpu):
    points, _ = scan
    expected = cpu.segment(points)
    for scale in (0.01, 255.0, 65535.0, 0.0):
        scaled = np.array(points)
        scaled[:, 3] *= scale
        np.testing.assert_array_equal(cpu.segment(scaled), expected, err_msg=f"x{scale}")
    np.testing.assert_array_equal(cpu.segment(points[:, :3]), expected)  # no intensity at all


def test_rings_of_another_sensor_raise_value_error_naming_the_profile():
    points, _ = lpir_gseg.simulate("hdl64e", 4, rings=True)  # the array carries rings 0..63
    seg = lpir_gseg.Segmenter("vlp32c", backend="cpu", max_points=400000)
    with pytest.raises(ValueError, match=r"ring values up to 63 .*profile 'vlp32c' has 32 "
                                         r"beams: wrong --sensor\?"):
        seg.segment(points)
    with pytest.raises(ValueError, match="wrong --sensor"):
        seg.segment(np.array(points)[:, :3], ring=np.arange(len(points)) % 64)


def test_a_cloud_that_does_not_look_like_the_profiles_sensor_warns():
    points, _ = lpir_gseg.simulate("hdl64e", 4)
    seg = lpir_gseg.Segmenter("vlp16", backend="cpu", max_points=400000)
    with pytest.warns(UserWarning, match=r"below the bottom beam \(-15.0 deg\) of profile 'vlp16'"):
        labels = seg.segment(points)
    assert len(labels) == len(points)
    with pytest.warns(UserWarning, match=r"clouds\[1\]: .*profile 'vlp16'"):
        seg.segment_batch([lpir_gseg.simulate("vlp16", 1)[0], points])
    own = lpir_gseg.Segmenter("hdl64e", backend="cpu")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        own.segment(points)  # its own profile: no warning


def test_bad_segmenter_arguments(tmp_path):
    with pytest.raises(ValueError, match="unknown sensor profile 'nope'; known: .*hdl64e"):
        lpir_gseg.Segmenter("nope")
    with pytest.raises(ValueError, match="unknown backend 'gpu'"):
        lpir_gseg.Segmenter("hdl64e", backend="gpu")
    with pytest.raises(ValueError, match="max_points must be at least 1"):
        lpir_gseg.Segmenter("hdl64e", max_points=0)
    with pytest.raises(TypeError):
        lpir_gseg.Segmenter("hdl64e", max_points=1.5)
    with pytest.raises(FileNotFoundError, match="absent.txt: no such sensor profile file"):
        lpir_gseg.Segmenter(tmp_path / "absent.txt")
    profile = tmp_path / "broken.txt"
    profile.write_text("name broken\nbeams sixty-four\n")
    with pytest.raises(OSError, match="broken.txt"):
        lpir_gseg.Segmenter(profile)
    with pytest.raises(RuntimeError, match="Vulkan"):
        lpir_gseg.Segmenter("hdl64e", backend="vulkan", device="no such device")


def test_params_change_the_profile_as_the_clis_set_does(cli, scan, tmp_path):
    points, _ = scan
    plain = lpir_gseg.Segmenter("hdl64e", backend="cpu").segment(points)
    changed = lpir_gseg.Segmenter("hdl64e", backend="cpu",
                                  params={"sensor_height": 1.9, "max_range": 40,
                                          "min_component": np.int64(200), "h_athr": "0.15"})
    labels = changed.segment(points)
    assert (labels != plain).any()
    assert not labels[np.hypot(points[:, 0], points[:, 1]) > 40].any()  # out of range: non-ground
    # the labels `segment --set` writes for the same settings
    path = tmp_path / "s.bin"
    np.asarray(points, "<f4").tofile(path)
    result = run_cli(cli, "segment", path, "-s", "hdl64e", "-b", "cpu", "-q", "-o", tmp_path,
                     "--set", "sensor_height=1.9", "--set", "max_range=40", "--set",
                     "min_component=200", "--set", "h_athr=0.15")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "s.label").read_bytes() == labels.astype("<u4").tobytes()
    assert lpir_gseg.Segmenter("hdl64e", backend="cpu", params={}).segment(points).tobytes() == \
        plain.tobytes()


def test_bad_params_name_the_setting():
    with pytest.raises(ValueError, match=r"params: sensr_height=1.9: no setting 'sensr_height' "
                                         r"\(did you mean sensor_height\?\)"):
        lpir_gseg.Segmenter("hdl64e", params={"sensr_height": 1.9})
    with pytest.raises(ValueError, match="params: sensor_height=-1.0: sensor_height must be > 0"):
        lpir_gseg.Segmenter("hdl64e", params={"sensor_height": -1.0})
    with pytest.raises(ValueError, match="min_component=2.5: parameter min_component expects a "
                                         "whole number"):
        lpir_gseg.Segmenter("hdl64e", params={"min_component": 2.5})
    with pytest.raises(ValueError, match="max_range must be larger than min_range"):
        lpir_gseg.Segmenter("hdl64e", params={"max_range": 1})
    with pytest.raises(ValueError, match="h_athr=nan: h_athr: 'nan' is not a finite number"):
        lpir_gseg.Segmenter("hdl64e", params={"h_athr": float("nan")})
    with pytest.raises(TypeError, match=r"params\['h_athr'\] must be a number"):
        lpir_gseg.Segmenter("hdl64e", params={"h_athr": True})
    with pytest.raises(TypeError, match="params must be a dict"):
        lpir_gseg.Segmenter("hdl64e", params=[("h_athr", 0.1)])
    with pytest.raises(ValueError, match="unknown sensor profile 'hdl-64e' "
                                         r"\(did you mean hdl64e\?\)"):
        lpir_gseg.Segmenter("hdl-64e")


def test_read_cloud_errors_name_the_file(tmp_path):
    for name in ("missing.bin", "missing.pcd", "missing.ply", "missing.pcd.bin"):
        with pytest.raises(FileNotFoundError, match=str(tmp_path / name)):
            lpir_gseg.read_cloud(tmp_path / name)
    with pytest.raises(FileNotFoundError, match="missing.label"):
        lpir_gseg.read_labels(tmp_path / "missing.label")
    (tmp_path / "folder.bin").mkdir()
    with pytest.raises(IsADirectoryError, match="folder.bin: is a folder"):
        lpir_gseg.read_cloud(tmp_path / "folder.bin")
    truncated = tmp_path / "truncated.bin"
    truncated.write_bytes(b"\0" * 18)
    with pytest.raises(OSError, match="truncated.bin: .*size"):
        lpir_gseg.read_cloud(truncated)
    other = tmp_path / "scan.xyz"
    other.write_bytes(b"\0" * 16)
    with pytest.raises(OSError, match="scan.xyz"):
        lpir_gseg.read_cloud(other)
    garbage = tmp_path / "garbage.pcd"
    garbage.write_bytes(b"\x00\xff not a header")
    with pytest.raises(OSError, match="garbage.pcd"):
        lpir_gseg.read_cloud(garbage)
    with pytest.raises(ValueError, match="NUL"):
        lpir_gseg.read_cloud("a\0b.bin")
    with pytest.raises(TypeError):
        lpir_gseg.read_cloud(3)


def test_read_cloud_formats_round_trip(scan, tmp_path):
    points, _ = scan
    path = tmp_path / "scan.bin"
    np.asarray(points, "<f4").tofile(path)
    read = lpir_gseg.read_cloud(path)
    assert read.dtype == np.float32 and read.shape == points.shape and read.flags.c_contiguous
    np.testing.assert_array_equal(read, points)
    five = np.zeros((len(points), 5), "<f4")
    five[:, :4] = points
    five[:, 4] = 3
    five.tofile(tmp_path / "scan5.bin")
    read, ring = lpir_gseg.read_cloud(tmp_path / "scan5.bin", nuscenes=True, ring=True)
    np.testing.assert_array_equal(read, points)
    assert ring.dtype == np.int32 and (ring == 3).all()
    assert lpir_gseg.read_cloud(path, ring=True)[1] is None


def test_cloud_formats_are_the_extensions_read_and_listed(tmp_path):
    formats = lpir_gseg.cloud_formats()
    assert {".bin", ".pcd", ".ply"} <= set(formats)
    for extension in formats:
        assert lpir_gseg.is_cloud_file(tmp_path / ("scan" + extension.upper()))
    assert not lpir_gseg.is_cloud_file(tmp_path / "scan.txt")
    bad = tmp_path / "scan.txt"
    bad.write_text("1 2 3\n")
    with pytest.raises(OSError, match=r"\.bin \(KITTI\), \.pcd, \.ply"):
        lpir_gseg.read_cloud(bad)


def test_read_cloud_finds_the_intensity_by_other_writers_names_and_warns_without(tmp_path):
    header = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
    header += "property float z\n"
    cloudcompare = tmp_path / "cc.ply"  # CloudCompare's name for it
    cloudcompare.write_text(header + "property float scalar_Intensity\nend_header\n"
                            "1 2 3 40\n4 5 6 50\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning when the file has an intensity
        np.testing.assert_array_equal(lpir_gseg.read_cloud(cloudcompare)[:, 3], [40, 50])
    bare = tmp_path / "bare.ply"
    bare.write_text(header + "end_header\n1 2 3\n4 5 6\n")
    with pytest.warns(UserWarning, match=f"{bare} has no intensity field .*remission") as caught:
        points = lpir_gseg.read_cloud(bare)
    assert caught[0].filename == __file__  # names the caller's line
    np.testing.assert_array_equal(points[:, 3], [0, 0])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="bare.ply"):
            lpir_gseg.read_cloud(bare)


def test_read_cloud_reads_pcl_and_cloudcompare_files():
    fixtures = REPO / "tests" / "data" / "clouds"  # written by PCL (tools/cloud_fixtures/)
    compressed, ring = lpir_gseg.read_cloud(fixtures / "pcl_binary_compressed.pcd", ring=True)
    binary, binary_ring = lpir_gseg.read_cloud(fixtures / "pcl_binary.pcd", ring=True)
    assert compressed.shape == (640, 4)
    assert compressed.tobytes() == binary.tobytes()  # NaN points included, bit for bit
    np.testing.assert_array_equal(ring, binary_ring)
    np.testing.assert_array_equal(ring, np.arange(640) // 40)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # CloudCompare's scalar_Intensity is an intensity
        cloudcompare = lpir_gseg.read_cloud(fixtures / "cloudcompare.ply")
    np.testing.assert_array_equal(cloudcompare, binary[~np.isnan(binary[:, 0])])


def test_labels_round_trip_and_errors(tmp_path):
    path = tmp_path / "x.label"
    lpir_gseg.write_labels(path, np.array([1, 0, 1], np.uint8))
    assert path.read_bytes() == np.array([1, 0, 1], "<u4").tobytes()
    labels = lpir_gseg.read_labels(path)
    assert labels.dtype == np.uint32 and list(labels) == [1, 0, 1]
    with pytest.raises(OSError, match="x.label: holds 3 labels but the cloud has 4 points"):
        lpir_gseg.read_labels(path, 4)
    (tmp_path / "odd.label").write_bytes(b"\0" * 5)
    with pytest.raises(OSError, match="odd.label"):
        lpir_gseg.read_labels(tmp_path / "odd.label")
    with pytest.raises(ValueError, match=r"labels\[1\] is -1"):
        lpir_gseg.write_labels(path, np.array([0, -1]))
    with pytest.raises(OSError, match="no_such_folder"):
        lpir_gseg.write_labels(tmp_path / "no_such_folder" / "x.label", [1])


def test_simulate_is_deterministic_and_matches_the_cli(cli, tmp_path):
    points, labels = lpir_gseg.simulate("vlp32c", 3)
    again, labels_again = lpir_gseg.simulate("vlp32c", 3)
    np.testing.assert_array_equal(points, again)
    np.testing.assert_array_equal(labels, labels_again)
    assert labels.dtype == np.uint32 and len(labels) == len(points)
    result = run_cli(cli, "simulate", "--sensor", "vlp32c", "--seed", 3, "--out",
                     tmp_path / "s.bin", "--labels", tmp_path / "s.label")
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "s.bin").read_bytes() == points.tobytes()
    assert (tmp_path / "s.label").read_bytes() == labels.astype("<u4").tobytes()
    tilted, _ = lpir_gseg.simulate("vlp32c", 3, pitch=2.0, roll=-1.0, scene="flat-objects",
                                   range_noise=0.0, reflection_noise=False)
    assert not np.array_equal(tilted[:100], points[:100])


def test_a_files_ring_reaches_the_segmenter(scan, cpu, tmp_path):
    points, _ = scan
    five = np.zeros((len(points), 5), "<f4")
    five[:, :4] = points
    five[:, 4] = np.arange(len(points)) * 64 // len(points)  # rows top to bottom, not the truth
    five.tofile(tmp_path / "scan.pcd.bin")  # the name says nuScenes' 5 floats
    read = lpir_gseg.read_cloud(tmp_path / "scan.pcd.bin")
    ring = five[:, 4].astype(np.int32)
    with_ring = cpu.segment(read)
    np.testing.assert_array_equal(with_ring, cpu.segment(np.array(read), ring=ring))
    assert not np.array_equal(with_ring, cpu.segment(np.array(read)))
    assert not np.array_equal(with_ring, cpu.segment(read[:-1]).tolist() + [0])  # a slice: no ring


def test_simulate_errors():
    with pytest.raises(ValueError, match="seed"):
        lpir_gseg.simulate("hdl64e", -1)
    with pytest.raises(ValueError, match="pitch"):
        lpir_gseg.simulate("hdl64e", 1, pitch=31)
    with pytest.raises(ValueError, match="scene must be urban"):
        lpir_gseg.simulate("hdl64e", 1, scene="rural")
    with pytest.raises(ValueError, match="unknown sensor profile"):
        lpir_gseg.simulate("nope", 1)


def test_evaluate_on_simulated_truth(scan, cpu):
    points, truth = scan
    pred = cpu.segment(points)
    scores = lpir_gseg.evaluate(pred, truth)
    assert scores["protocol"] == "dg" and scores["ontology"] == "semantickitti"
    assert scores["frames"] == 1 and 0.9 < scores["f1"] <= 1
    assert scores["tp"] + scores["fp"] + scores["fn"] + scores["tn"] == len(points)
    p, r = scores["precision"], scores["recall"]
    assert scores["f1"] == pytest.approx(2 * p * r / (p + r))
    assert lpir_gseg.evaluate(pred.astype(bool), truth)["f1"] == scores["f1"]
    assert lpir_gseg.evaluate(pred * 7, truth)["f1"] == scores["f1"]  # non-zero is ground
    perfect = np.isin(truth, [40, 44, 48, 49, 60, 72])
    assert lpir_gseg.evaluate(perfect, truth)["f1"] == 1.0
    pw = lpir_gseg.evaluate(pred, truth, "pw", points=points)
    assert pw["protocol"] == "pw" and 0 < pw["f1"] <= 1
    sequence = lpir_gseg.evaluate([pred, pred], [truth, truth], "pp")
    assert sequence["frames"] == 2 and len(sequence["per_frame"]) == 2
    assert lpir_gseg.evaluate(pred, truth, "gg")["ignored"] > 0


def test_evaluate_by_class_and_by_range_sum_to_the_totals(scan, cpu):
    points, truth = scan
    pred = cpu.segment(points)
    for protocol in ("dg", "pp", "pw", "gg"):
        scores = lpir_gseg.evaluate([pred, pred], [truth, truth], protocol, points=[points, points],
                                    by_class=True, by_range=True)
        counts = ("tp", "fp", "fn", "tn", "ignored")
        classes, bands = scores["by_class"], scores["by_range"]
        assert [c["class"] for c in classes] == sorted(set(int(c) for c in truth & 0xFFFF))
        for key in counts:  # both split the summed counts, over two frames
            assert sum(c[key] for c in classes) == scores[key], (protocol, key)
            assert sum(b[key] for b in bands) == scores[key], (protocol, key)
        road = next(c for c in classes if c["class"] == 40)
        assert road["name"] == "road" and road["points"] == 2 * int(((truth & 0xFFFF) == 40).sum())
        assert road["predicted_ground"] == 2 * int(pred[(truth & 0xFFFF) == 40].sum())
        assert road["share"] == road["predicted_ground"] / road["points"]
        assert [b["band"] for b in bands] == ["0-5", "5-10", "10-20", "20-30", "30-40", "40-60",
                                              "60+"]
        assert bands[0]["from"] == 0 and bands[0]["to"] == 5 and bands[-1]["to"] is None
        r = np.hypot(points[:, 0], points[:, 1])
        assert bands[2]["points"] == 2 * int(((r >= 10) & (r < 20)).sum())
    plain = lpir_gseg.evaluate(pred, truth)
    assert "by_class" not in plain and "by_range" not in plain
    with pytest.raises(ValueError, match="by_range needs each point's x and y: give points="):
        lpir_gseg.evaluate(pred, truth, by_range=True)


def test_evaluate_by_class_and_by_range_give_the_clis_numbers(cli, tmp_path, scan, cpu):
    points, truth = scan
    pred = cpu.segment(points)
    (tmp_path / "velodyne").mkdir()
    (tmp_path / "labels").mkdir()
    (tmp_path / "pred").mkdir()
    np.asarray(points, "<f4").tofile(tmp_path / "velodyne" / "s.bin")
    lpir_gseg.write_labels(tmp_path / "labels" / "s.label", truth)
    lpir_gseg.write_labels(tmp_path / "pred" / "s.label", pred)
    result = run_cli(cli, "evaluate", "--pred", tmp_path / "pred", "--gt", tmp_path / "labels",
                     "--protocol", "pp", "--by-class", "--by-range", "--json")
    assert result.returncode == 0, result.stderr
    expected = json.loads(result.stdout)
    scores = lpir_gseg.evaluate(pred, truth, "pp", points=points, by_class=True, by_range=True)
    for ours, theirs in zip(scores["by_class"], expected["by_class"]):
        assert {k: ours[k] for k in ("class", "name", "points", "predicted_ground", "share")} == \
            {k: theirs[k] for k in ("class", "name", "points", "predicted_ground", "share")}
        assert {k: ours[k] for k in ("tp", "fp", "fn", "tn", "ignored")} == theirs["pp"]
    assert len(scores["by_class"]) == len(expected["by_class"])
    for ours, theirs in zip(scores["by_range"], expected["by_range"]):
        assert ours["band"] == theirs["band"] and ours["points"] == theirs["points"]
        assert ours["from"] == theirs["from"] and ours["to"] == theirs.get("to")
        assert {k: ours[k] for k in ("tp", "fp", "fn", "tn", "ignored")} == theirs["pp"]


def test_evaluate_errors(scan):
    _, truth = scan
    with pytest.raises(ValueError, match="pw needs each point's z"):
        lpir_gseg.evaluate(truth * 0, truth, "pw")
    with pytest.raises(ValueError, match="unknown protocol|protocol 'xx'"):
        lpir_gseg.evaluate(truth * 0, truth, "xx")
    with pytest.raises(ValueError, match="rellis3d"):
        lpir_gseg.evaluate(truth * 0, truth, "rellis")
    with pytest.raises(ValueError, match="ontology"):
        lpir_gseg.evaluate(truth * 0, truth, ontology="kitti")
    with pytest.raises(ValueError, match=r"pred has 3 values for \d+ points"):
        lpir_gseg.evaluate(np.zeros(3, np.uint8), truth)
    with pytest.raises(ValueError, match="pred holds 2 frames, gt_labels 1"):
        lpir_gseg.evaluate([truth, truth], [truth])
    with pytest.raises(ValueError, match="pred must hold integers or bools"):
        lpir_gseg.evaluate(np.zeros(len(truth)), truth)


def test_evaluate_rellis3d():
    labels = lpir_gseg.read_labels(data_file("rellis3d/os1/000104.label"))
    points = lpir_gseg.read_cloud(data_file("rellis3d/os1/000104.bin"))
    pred = lpir_gseg.Segmenter("os1-64", backend="cpu").segment(points)
    scores = lpir_gseg.evaluate(pred, labels, ontology="rellis3d")
    assert scores["protocol"] == "rellis" and scores["ontology"] == "rellis3d"
    assert scores["ignored"] > 0 and 0.5 < scores["f1"] <= 1


def test_sensors_ship_with_the_package():
    names = lpir_gseg.sensors()
    assert {"hdl64e", "hdl32e", "vlp16", "vlp32c", "os1-64", "os1-128"} <= set(names)
    folder = Path(lpir_gseg.sensors_dir())
    assert folder.parent == Path(lpir_gseg.__file__).resolve().parent  # inside the package
    shipped = sorted(p.stem for p in (REPO / "sensors").glob("*.txt"))
    assert names == shipped
    for name in names:  # each one loads
        assert lpir_gseg.Segmenter(name, backend="cpu").sensor == name


def test_devices_lists_lines():
    lines = lpir_gseg.devices()
    assert isinstance(lines, list) and all(isinstance(line, str) for line in lines)
    assert vulkan_usable() == any(line.endswith(": usable") for line in lines)


def test_stubs_cover_the_module():
    stub = Path(lpir_gseg.__file__).parent / "_core.pyi"
    assert stub.is_file() and (stub.parent / "py.typed").is_file()
    tree = ast.parse(stub.read_text())
    declared = set()
    for node in tree.body:
        if isinstance(node, (ast.FunctionDef, ast.ClassDef)):
            declared.add(node.name)
        elif isinstance(node, ast.AnnAssign):
            declared.add(node.target.id)
    public = {n for n in dir(lpir_gseg._core) if not n.startswith("__")}
    assert public <= declared, public - declared
    methods = {n for n in dir(lpir_gseg.Segmenter) if not n.startswith("_")}
    segmenter = next(n for n in tree.body if isinstance(n, ast.ClassDef))
    assert methods <= {n.name for n in segmenter.body if isinstance(n, ast.FunctionDef)}
    for name in lpir_gseg.__all__:
        assert getattr(lpir_gseg, name).__doc__ or name.startswith("WHY"), name
    # inspect.signature reads the docstrings' signature lines: the stubs' parameters, in order.
    def names(args):
        return [a.arg for a in args.posonlyargs + args.args + args.kwonlyargs]

    stubbed = {n.name: n for n in tree.body if isinstance(n, ast.FunctionDef)}
    stubbed.update({f"Segmenter.{n.name}": n for n in segmenter.body
                    if isinstance(n, ast.FunctionDef)})
    for name, node in stubbed.items():
        if any(isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list):
            continue
        target = lpir_gseg._core
        for part in name.split("."):
            target = getattr(target, part)
        assert list(inspect.signature(target).parameters) == names(node.args), name


def test_lpir_sensors_dir_replaces_the_shipped_profiles(tmp_path):
    (tmp_path / "mine.txt").write_text(
        (Path(lpir_gseg.sensors_dir()) / "vlp16.txt").read_text().replace("name vlp16", "name mine"))
    script = "import lpir_gseg; print(lpir_gseg.sensors(), lpir_gseg.Segmenter('mine').sensor)"
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                            env={**os.environ, "LPIR_SENSORS_DIR": str(tmp_path)})
    assert result.returncode == 0, result.stderr
    assert result.stdout.strip() == "['mine'] mine"
