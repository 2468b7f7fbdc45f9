"""lpir_gseg.read_drive, drive_topics and the fleet on the committed drive fixtures
(tests/data/drives/: three simulated VLP-16 frames written by @mcap/core, sqlite3 and
python3-rosbag; scripts/make_drive_fixtures.sh): every drive reads back as the frames' .bin
files, damage is an OSError naming the file after every readable message, and the fleet labels
every message of two drives as the Segmenter labels the frames."""
import shutil
import sqlite3
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

import lpir_gseg
from conftest import REPO, cli  # noqa: F401 (a fixture)

DRIVES = REPO / "tests" / "data" / "drives"
TOPIC = "/velodyne_points"
DRIVE_FILES = ["vlp16_zstd.mcap", "vlp16_lz4.mcap", "vlp16_none.mcap", "vlp16.db3",
               "vlp16_bz2.bag", "vlp16_lz4.bag"]
FIRST_STAMP_NS = 1_600_000_000 * 10**9  # then 100 ms apart


def frame(i):
    """Frame i as the writers read it: (points (N, 4) float32, ring (N,) int32)."""
    base = DRIVES / "frames" / f"{i:06}"
    points = np.fromfile(base.with_suffix(".bin"), dtype="<f4").reshape(-1, 4)
    ring = np.fromfile(base.with_suffix(".ring"), dtype="<u2").astype(np.int32)
    return points, ring


def same_bits(a, b):
    return a.shape == b.shape and a.dtype == b.dtype and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("name", DRIVE_FILES)
def test_read_drive_yields_the_bin_frames_with_their_stamps(name):
    messages = list(lpir_gseg.read_drive(DRIVES / name, TOPIC))
    assert [stamp for stamp, _ in messages] == [FIRST_STAMP_NS + i * 10**8 for i in range(3)]
    for i, (_, points) in enumerate(messages):
        expected, _ = frame(i)
        assert points.dtype == np.float32 and points.shape == expected.shape, (name, i)
        assert same_bits(points, expected), (name, i)


@pytest.mark.parametrize("name", DRIVE_FILES)
def test_drive_topics_and_the_default_topic(name):
    topics = lpir_gseg.drive_topics(DRIVES / name)
    assert [(t.name, t.messages) for t in topics] == [(TOPIC, 3)]
    assert topics[0].type in ("sensor_msgs/msg/PointCloud2", "sensor_msgs/PointCloud2")
    assert len(list(lpir_gseg.read_drive(str(DRIVES / name)))) == 3  # the only PointCloud2 topic


def test_the_ring_comes_with_the_points_and_reaches_the_segmenter():
    seg = lpir_gseg.Segmenter("vlp16", backend="cpu")
    messages = list(lpir_gseg.read_drive(DRIVES / "vlp16_lz4.mcap", TOPIC, ring=True))
    assert len(messages) == 3
    for i, (_, points, ring) in enumerate(messages):
        expected, expected_ring = frame(i)
        assert ring.dtype == np.int32 and np.array_equal(ring, expected_ring), i
        labels = seg.segment(points)
        assert np.array_equal(labels, seg.segment(expected, ring=expected_ring)), i
        assert 0 < labels.mean() < 1, i  # ground and non-ground both: a mix-up would show


LIVOX = DRIVES / "livox"  # two simulated Mid-70 frames; scripts/make_livox_drive_fixture.sh


def test_a_livox_drive_gives_the_labels_segment_gives_its_frames_and_its_messages(cli, tmp_path):
    """livox_ros_driver2's PointCloud2 (x y z intensity tag line timestamp, point_step 26): the
    points read back as the .bin's, `line` gives no ring, and the Segmenter, `segment` of the
    .bin files and `segment` of the drive write the same bytes."""
    bins = [LIVOX / f"{i:06}.bin" for i in range(2)]
    for inputs, out in ((bins, "bins"), ([LIVOX / "mid70.mcap"], "drive")):
        result = subprocess.run([str(cli), "segment", *map(str, inputs), "--sensor", "mid70",
                                 "--backend", "cpu", "--quiet", "--out", str(tmp_path / out)],
                                capture_output=True, text=True)
        assert result.returncode == 0, result.stderr
    drive_labels = fleet_labels(tmp_path / "drive")
    assert len(drive_labels) == 2
    seg = lpir_gseg.Segmenter("mid70", backend="cpu")
    messages = list(lpir_gseg.read_drive(LIVOX / "mid70.mcap", "/livox/lidar", ring=True))
    assert len(messages) == 2
    for i, (_, points, ring) in enumerate(messages):
        expected = np.fromfile(bins[i], dtype="<f4").reshape(-1, 4)
        assert same_bits(points, expected), i
        assert ring is None, i  # `line` is no ring
        labels = seg.segment(points).astype("<u4").tobytes()
        assert labels == (tmp_path / "bins" / f"{i:06}.label").read_bytes(), i
        assert labels == (tmp_path / "drive" / drive_labels[i]).read_bytes(), i
        assert 0 < np.frombuffer(labels, "<u4").mean() < 1, i  # ground and non-ground both


def truncated(tmp_path, name, fraction=0.85):
    """The fixture cut inside its last chunk (the third frame's, of three: 2/3 of the file on)."""
    data = (DRIVES / name).read_bytes()
    path = tmp_path / name
    path.write_bytes(data[: int(len(data) * fraction)])
    return path


@pytest.mark.parametrize("name", ["vlp16_zstd.mcap", "vlp16_none.mcap", "vlp16_bz2.bag"])
def test_a_truncated_drive_yields_what_precedes_the_cut_then_raises_naming_it(tmp_path, name):
    path = truncated(tmp_path, name)
    read = []
    with pytest.raises(OSError) as error:
        for stamp, points in lpir_gseg.read_drive(path, TOPIC):
            read.append(points)
    assert str(path) in str(error.value)
    assert "damaged" in str(error.value)
    assert len(read) == 2
    for i, points in enumerate(read):
        assert same_bits(points, frame(i)[0]), i


def test_a_db3_cut_in_its_last_page_yields_the_messages_before_the_cut(tmp_path):
    data = (DRIVES / "vlp16.db3").read_bytes()
    path = tmp_path / "vlp16.db3"
    path.write_bytes(data[: len(data) - 2048])
    read = []
    with pytest.raises(OSError, match="message 2"):
        for _, points in lpir_gseg.read_drive(path, TOPIC):
            read.append(points)
    assert len(read) == 2 and all(same_bits(p, frame(i)[0]) for i, p in enumerate(read))


def test_on_damage_warn_ends_the_iteration_with_a_warning(tmp_path):
    path = truncated(tmp_path, "vlp16_zstd.mcap")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        read = list(lpir_gseg.read_drive(path, TOPIC, on_damage="warn"))
    assert len(read) == 2
    assert [w.category for w in caught] == [RuntimeWarning]
    assert str(path) in str(caught[0].message)


def test_bad_calls_raise_at_once_naming_the_file(tmp_path):
    for name in ("absent.mcap", "absent.db3", "absent.bag"):
        with pytest.raises(FileNotFoundError, match=name):
            lpir_gseg.read_drive(tmp_path / name, TOPIC)
    with pytest.raises(FileNotFoundError, match="absent.mcap"):
        lpir_gseg.drive_topics(tmp_path / "absent.mcap")
    # a topic the drive does not have is the call's mistake: ValueError listing those it has
    with pytest.raises(ValueError, match="no topic /no_such_topic; the drive has "
                                         "/velodyne_points"):
        lpir_gseg.read_drive(DRIVES / "vlp16_zstd.mcap", "/no_such_topic")
    with pytest.raises(OSError, match="extension"):
        lpir_gseg.read_drive(DRIVES / "frames" / "000000.bin", TOPIC)
    with pytest.raises(ValueError, match="on_damage"):
        lpir_gseg.read_drive(DRIVES / "vlp16_zstd.mcap", TOPIC, on_damage="ignore")
    assert lpir_gseg.is_drive_file("a.mcap") and lpir_gseg.is_drive_file("b.db3")
    assert lpir_gseg.is_drive_file("c.bag") and not lpir_gseg.is_drive_file("d.bin")


def test_several_cloud_topics_need_one_chosen_and_none_is_the_files_fault(tmp_path):
    # vlp16.db3 with its messages logged again on a second PointCloud2 topic, and on a topic of
    # another type (Python's sqlite3 writes them)
    two = tmp_path / "two.db3"
    shutil.copyfile(DRIVES / "vlp16.db3", two)
    with sqlite3.connect(two) as db:
        qos = db.execute("SELECT offered_qos_profiles FROM topics WHERE id = 1").fetchone()[0]
        db.execute("INSERT INTO topics VALUES (2, '/front_points', 'sensor_msgs/msg/PointCloud2', "
                   "'cdr', ?)", (qos,))
        db.execute("INSERT INTO topics VALUES (3, '/imu', 'sensor_msgs/msg/Imu', 'cdr', ?)", (qos,))
        db.execute("INSERT INTO messages (topic_id, timestamp, data) "
                   "SELECT 2, timestamp, data FROM messages WHERE topic_id = 1")
    db.close()
    with pytest.raises(ValueError, match=r"two.db3: 2 PointCloud2 topics \(/velodyne_points "
                                         r".*/front_points .*\): choose one with topic="):
        lpir_gseg.read_drive(two)
    with pytest.raises(ValueError, match="topic /imu holds sensor_msgs/msg/Imu, not"):
        lpir_gseg.read_drive(two, "/imu")
    assert len(list(lpir_gseg.read_drive(two, "/front_points"))) == 3
    # no PointCloud2 topic at all: the file's fault, an OSError
    none = tmp_path / "none.db3"
    shutil.copyfile(DRIVES / "vlp16.db3", none)
    with sqlite3.connect(none) as db:
        db.execute("UPDATE topics SET type = 'sensor_msgs/msg/Imu'")
    db.close()
    with pytest.raises(OSError, match="none.db3: no sensor_msgs PointCloud2 topic"):
        lpir_gseg.read_drive(none)


def fleet_labels(folder):
    return sorted(p.name for p in folder.iterdir() if p.suffix == ".label")


def test_the_fleet_labels_every_message_of_two_drives(tmp_path):
    pytest.importorskip("distributed", reason="the fleet needs python3-distributed")
    from lpir_gseg import fleet

    damaged = truncated(tmp_path, "vlp16_none.mcap")
    out = tmp_path / "out"
    stats = fleet.run([str(DRIVES / "vlp16_zstd.mcap"), str(DRIVES / "vlp16_bz2.bag"),
                       str(damaged)], "vlp16", str(out), workers=2, backend="cpu",
                      progress=False, topic=TOPIC)
    assert (stats.files, stats.drives, stats.written) == (0, 3, 2)
    assert stats.frames == 3 + 3 + 2  # the messages segmented, not the drives
    assert [path for path, _ in stats.failures] == [str(damaged)]
    assert str(damaged) in stats.failures[0][1]
    seg = lpir_gseg.Segmenter("vlp16", backend="cpu")
    names = [f"{i:06}_{FIRST_STAMP_NS + i * 10**8}.label" for i in range(3)]
    for drive, count in (("vlp16_zstd", 3), ("vlp16_bz2", 3), ("vlp16_none", 2)):
        folder = out / drive
        assert fleet_labels(folder) == names[:count], drive
        for i in range(count):
            points, ring = frame(i)
            expected = seg.segment(points, ring=ring).astype("<u4").tobytes()
            assert (folder / names[i]).read_bytes() == expected, (drive, i)
        index = (folder / "index.csv").read_text().splitlines()
        assert index[0] == "sequence,stamp_ns,topic,points,ground_fraction,ms,file"
        assert [line.split(",")[-1] for line in index[1:]] == names[:count], drive
        assert [int(line.split(",")[3]) for line in index[1:]] == \
            [len(frame(i)[0]) for i in range(count)], drive


def test_the_fleet_writes_what_segment_writes_for_a_drive(cli, tmp_path):
    pytest.importorskip("distributed", reason="the fleet needs python3-distributed")
    from lpir_gseg import fleet

    drive = DRIVES / "vlp16_lz4.bag"
    result = subprocess.run([str(cli), "segment", str(drive), "--topic", TOPIC, "--sensor",
                             "vlp16", "--backend", "cpu", "--out", str(tmp_path / "cli"),
                             "--quiet"], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    stats = fleet.run([str(drive)], "vlp16", str(tmp_path / "fleet"), workers=1, backend="cpu",
                      progress=False)
    assert stats.written == 1 and not stats.failures
    names = fleet_labels(tmp_path / "cli")
    assert len(names) == 3 and fleet_labels(tmp_path / "fleet" / "vlp16_lz4") == names
    for name in names:
        assert (tmp_path / "fleet" / "vlp16_lz4" / name).read_bytes() == \
            (tmp_path / "cli" / name).read_bytes(), name


@pytest.mark.parametrize("name", DRIVE_FILES + ["vlp16_split_mcap"])
def test_chunk_ranges_and_the_fleet_split_give_the_whole_drives_files(tmp_path, name):
    """Each fixture chunk on its own (select with a range, then the fleet with one chunk a task)
    yields the whole run's messages with their sequences; the fleet's split run writes the same
    .label files and index rows (but the ms column) as its whole-drive task. A bag folder's
    chunks are numbered on across its files."""
    pytest.importorskip("distributed", reason="the fleet needs python3-distributed")
    from lpir_gseg import fleet

    drive = lpir_gseg._core._Drive(DRIVES / name)
    count, indexed = drive.chunk_count(), drive.chunks_indexed()
    assert (count, indexed) == ((0, False) if name.endswith(".db3") else (3, True))
    whole = []
    drive.select(TOPIC)
    for kind, *rest in iter(drive.next, ("end",)):
        assert kind == "message"
        whole.append((rest[0], rest[1], rest[2].tobytes()))
    ranged = []
    for c in range(1, count + 1):
        drive.select(TOPIC, c, c)
        for kind, *rest in iter(drive.next, ("end",)):
            ranged.append((rest[0], rest[1], rest[2].tobytes()))
    if count:
        assert ranged == whole
        with pytest.raises(OSError, match="has 3"):
            drive.select(TOPIC, 2, 4)
    else:
        with pytest.raises(OSError, match="no chunks"):
            drive.select(TOPIC, 1, 1)
    assert fleet.drive_ranges(str(DRIVES / name), 1) == \
        ([None] if count == 0 else [(1, 1), (2, 2), (3, 3)])
    assert fleet.drive_ranges(str(DRIVES / name), 3) == [None]

    outputs = {}
    for split in (64, 1):
        out = tmp_path / f"split{split}"
        stats = fleet.run([str(DRIVES / name)], "vlp16", str(out), workers=2, backend="cpu",
                          progress=False, topic=TOPIC, drive_chunks=split)
        assert stats.drives == 1 and stats.written == 1 and not stats.failures
        folder = out / Path(name).stem
        assert not [p for p in folder.iterdir() if ".part" in p.name]
        index = (folder / "index.csv").read_text().splitlines()
        labels = {p.name: p.read_bytes() for p in folder.iterdir() if p.suffix == ".label"}
        rows = [line.rsplit(",", 2)[0] + "," + line.rsplit(",", 1)[1] for line in index]
        outputs[split] = (labels, rows)
    assert len(outputs[1][0]) == 3 and len(outputs[1][1]) == 4
    assert outputs[1] == outputs[64]
    assert [row.split(",")[0] for row in outputs[1][1][1:]] == ["0", "1", "2"]


def narrow(i):
    """Frame i cut to the 11.25 degrees ahead, as the bag folders and the killed bag hold it."""
    base = DRIVES / "narrow" / f"{i:06}"
    points = np.fromfile(base.with_suffix(".bin"), dtype="<f4").reshape(-1, 4)
    ring = np.fromfile(base.with_suffix(".ring"), dtype="<u2").astype(np.int32)
    return points, ring


@pytest.mark.parametrize("folder", ["vlp16_split_mcap", "vlp16_split_db3"])
def test_a_ros2_bag_folder_reads_as_one_drive(folder):
    path = DRIVES / folder
    assert [(t.name, t.messages) for t in lpir_gseg.drive_topics(path)] == [(TOPIC, 3)]
    messages = list(lpir_gseg.read_drive(path, ring=True))
    assert [stamp for stamp, _, _ in messages] == [FIRST_STAMP_NS + i * 10**8 for i in range(3)]
    for i, (_, points, ring) in enumerate(messages):
        expected, expected_ring = narrow(i)
        assert same_bits(points, expected) and np.array_equal(ring, expected_ring), (folder, i)


def test_a_killed_ros1_recorders_bag_yields_its_finished_messages_then_raises(tmp_path):
    path = DRIVES / "vlp16_killed.bag.active"
    assert lpir_gseg.is_drive_file(path)
    read = []
    with pytest.raises(OSError, match="chunk 2") as error:
        for _, points in lpir_gseg.read_drive(path):
            read.append(points)
    assert str(path) in str(error.value)
    assert len(read) == 2 and all(same_bits(p, narrow(i)[0]) for i, p in enumerate(read))
    with pytest.raises(OSError, match="1 damaged part met while listing"):
        lpir_gseg.drive_topics(path)


def test_drive_topics_names_the_damage_a_cut_drive_shows(tmp_path):
    path = truncated(tmp_path, "vlp16_zstd.mcap")
    with pytest.raises(OSError, match="chunk 3") as error:
        lpir_gseg.drive_topics(path)
    assert str(path) in str(error.value)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        topics = lpir_gseg.drive_topics(path, on_damage="warn")
    assert [(t.name, t.messages) for t in topics] == [(TOPIC, 2)]
    assert [w.category for w in caught] == [RuntimeWarning]
    stub = tmp_path / "stub.mcap"
    stub.write_bytes((DRIVES / "vlp16_zstd.mcap").read_bytes()[:3000])
    for topic in (None, TOPIC):  # the same answer with and without the topic
        with pytest.raises(OSError, match="in what could be read: the drive is damaged"):
            lpir_gseg.read_drive(stub, topic)


def two_cloud_topics(tmp_path):
    """vlp16.db3 with its messages on a second PointCloud2 topic too (Python's sqlite3)."""
    import sqlite3

    path = tmp_path / "two.db3"
    path.write_bytes((DRIVES / "vlp16.db3").read_bytes())
    with sqlite3.connect(path) as db:
        db.execute("INSERT INTO topics VALUES (2, '/other', 'sensor_msgs/msg/PointCloud2', 'cdr', "
                   "'')")
        db.execute("INSERT INTO messages (topic_id, timestamp, data) "
                   "SELECT 2, timestamp, data FROM messages WHERE topic_id = 1")
    return path


def test_two_cloud_topics_ask_for_one_in_the_callers_words(tmp_path):
    pytest.importorskip("distributed", reason="the fleet needs python3-distributed")
    path = two_cloud_topics(tmp_path)
    with pytest.raises(ValueError, match="2 PointCloud2 topics .*: choose one with topic="):
        lpir_gseg.read_drive(path)
    result = subprocess.run([sys.executable, "-m", "lpir_gseg.fleet", str(path), "--sensor",
                             "vlp16", "--out", str(tmp_path / "out"), "--workers", "1",
                             "--backend", "cpu", "--quiet"], capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 1, result.stderr
    assert "choose one with --topic" in result.stderr and "topic=" not in result.stderr
