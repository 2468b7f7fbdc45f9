"""python3 -m lpir_gseg.fleet on a 2-worker LocalCluster on 127.0.0.1: 12 scans and a truncated
one give the command line's 12 .label files byte for byte, the bad file named, exit code 1; the
same through --scheduler; one segmenter per worker process for the whole run."""
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import lpir_gseg
from conftest import REPO, run_cli, vulkan  # noqa: F401 (a fixture)

pytest.importorskip("distributed", reason="the fleet needs python3-distributed")


@pytest.fixture(scope="module")
def scans(tmp_path_factory):
    """12 simulated HDL-64E scans as KITTI .bin files and a truncated 13th."""
    folder = tmp_path_factory.mktemp("scans")
    for seed in range(12):
        points, _ = lpir_gseg.simulate("hdl64e", seed)
        points.tofile(folder / f"{seed:06}.bin")
    whole = (folder / "000000.bin").read_bytes()
    (folder / "truncated.bin").write_bytes(whole[: len(whole) // 2 + 7])
    return folder


@pytest.fixture(scope="module")
def cli_out(cli, scans, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    result = run_cli(cli, "segment", scans, "--sensor", "hdl64e", "--backend", "cpu", "--out",
                     out, "--quiet")
    assert result.returncode == 1 and "truncated.bin" in result.stderr, result.stderr
    return out


def fleet(*args, env=None):
    return subprocess.run([sys.executable, "-m", "lpir_gseg.fleet", *map(str, args)],
                          capture_output=True, text=True, timeout=300, env=env)


def expect_cli_labels(out, cli_out):
    written = sorted(p.name for p in out.iterdir())
    assert written == [f"{seed:06}.label" for seed in range(12)], written  # no .part left
    for name in written:
        assert (out / name).read_bytes() == (cli_out / name).read_bytes(), name


def test_two_local_workers_write_the_cli_labels_and_name_the_bad_file(scans, cli_out, tmp_path):
    out = tmp_path / "out"
    result = fleet(scans, "--sensor", "hdl64e", "--out", out, "--workers", 2, "--backend", "cpu")
    assert result.returncode == 1, result.stdout + result.stderr
    assert f"lpir_gseg.fleet: error: {scans / 'truncated.bin'}: size" in result.stderr
    assert "not a whole number of 16-byte points" in result.stderr
    assert "1 of 13 files failed" in result.stderr.splitlines()[-1]
    assert "frames/s on 2 workers" in result.stderr
    assert "progress: 13/13 100%" in result.stderr and "frames/s" in result.stderr
    expect_cli_labels(out, cli_out)


def test_a_running_scheduler_and_one_segmenter_per_worker(scans, cli_out, tmp_path):
    from dask.distributed import LocalCluster

    from lpir_gseg import fleet as fleet_module

    with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1",
                      dashboard_address=None) as cluster:
        out = tmp_path / "out"
        result = fleet(scans, "--sensor", "hdl64e", "--out", out, "--scheduler",
                       cluster.scheduler_address, "--backend", "cpu", "--quiet")
        assert result.returncode == 1 and "truncated.bin" in result.stderr, result.stderr
        assert "progress:" not in result.stderr
        expect_cli_labels(out, cli_out)
        # The same cluster again, through the API, one file a task: every worker process still
        # holds the one segmenter the first run made.
        files = sorted(str(p) for p in scans.glob("0*.bin"))
        stats = fleet_module.run(files, "hdl64e", str(tmp_path / "again"),
                                 scheduler=cluster.scheduler_address, backend="cpu", chunk=1,
                                 progress=False)
        assert stats.files == stats.written == 12 and not stats.failures
        assert stats.workers == 2 and stats.frames_per_second > 0
        assert 1 <= len(stats.segmenters) <= 2
        assert set(stats.segmenters.values()) == {1}, stats.segmenters


def test_vulkan_workers_batch_their_files_and_still_name_each_bad_one(scans, cli, cli_out,
                                                                     vulkan, tmp_path):
    # --max-points 125000 fails 8 of the 12 scans (and the truncated one) in the CLI and in the
    # fleet alike; tasks of 4 files go through segment_batch, which fails for the whole task and
    # falls back to each file on its own.
    limited = tmp_path / "cli"
    result = run_cli(cli, "segment", scans, "--sensor", "hdl64e", "--backend", "cpu", "--out",
                     limited, "--quiet", "--max-points", 125000)
    assert result.returncode == 1 and "9 of 13 files failed" in result.stderr, result.stderr
    out = tmp_path / "out"
    result = fleet(scans, "--sensor", "hdl64e", "--out", out, "--workers", 1, "--backend",
                   "vulkan", "--chunk", 4, "--max-points", 125000)
    assert result.returncode == 1, result.stderr
    assert "9 of 13 files failed" in result.stderr.splitlines()[-1], result.stderr
    assert "more than the segmenter's max_points of 125000" in result.stderr
    written = sorted(p.name for p in out.iterdir())
    assert written == sorted(p.name for p in limited.iterdir()) and len(written) == 4
    for name in written:
        assert (out / name).read_bytes() == (limited / name).read_bytes(), name
    # Without the limit, batches of 4 on Vulkan write the CLI's labels for all 12.
    out = tmp_path / "all"
    result = fleet(scans, "--sensor", "hdl64e", "--out", out, "--workers", 1, "--backend",
                   "vulkan", "--chunk", 4)
    assert result.returncode == 1 and "1 of 13 files failed" in result.stderr, result.stderr
    expect_cli_labels(out, cli_out)


def test_a_profile_file_travels_to_the_workers(scans, cli_out, tmp_path):
    profile = tmp_path / "mine.txt"
    profile.write_text((Path(lpir_gseg.sensors_dir()) / "hdl64e.txt").read_text())
    out = tmp_path / "out"
    files = [scans / f"{seed:06}.bin" for seed in range(3)]
    result = fleet(*files, "--sensor", profile, "--out", out, "--workers", 1, "--backend", "cpu")
    assert result.returncode == 0, result.stderr
    assert "wrote 3 label files" in result.stdout
    for f in files:
        name = f.stem + ".label"
        assert (out / name).read_bytes() == (cli_out / name).read_bytes()


def test_settings_reach_the_workers_as_segment_set_takes_them(cli, scans, tmp_path):
    files = [scans / f"{seed:06}.bin" for seed in range(3)]
    settings = ["--set", "sensor_height=1.9", "--set", "max_range=40", "--set", "h_athr=0.15"]
    expected = tmp_path / "cli"
    result = run_cli(cli, "segment", *files, "-s", "hdl64e", "-b", "cpu", "-q", "-o", expected,
                     *settings)
    assert result.returncode == 0, result.stderr
    out = tmp_path / "out"
    result = fleet(*files, "--sensor", "hdl64e", "--out", out, "--workers", 1, "--backend", "cpu",
                   *settings)
    assert result.returncode == 0, result.stderr
    for f in files:
        name = f.stem + ".label"
        assert (out / name).read_bytes() == (expected / name).read_bytes(), name
    plain = tmp_path / "plain"
    assert run_cli(cli, "segment", files[0], "-s", "hdl64e", "-b", "cpu", "-q", "-o",
                   plain).returncode == 0
    assert (plain / "000000.label").read_bytes() != (out / "000000.label").read_bytes()
    # a misspelt setting: the library's message, before any cluster
    result = fleet(*files, "--sensor", "hdl64e", "--out", tmp_path / "bad", "--set",
                   "sensr_height=1.9")
    assert result.returncode == 2
    assert "no setting 'sensr_height' (did you mean sensor_height?)" in result.stderr
    assert not (tmp_path / "bad").exists()
    result = fleet(*files, "--sensor", "hdl64e", "--out", tmp_path / "bad", "--set", "x")
    assert result.returncode == 2 and "--set expects NAME=VALUE" in result.stderr


def test_bad_arguments_exit_2_before_any_cluster(tmp_path, scans):
    result = fleet(scans, "--sensor", "nope", "--out", tmp_path / "o", "--workers", 1)
    assert result.returncode == 2 and "unknown sensor profile 'nope'" in result.stderr
    empty = tmp_path / "empty"
    empty.mkdir()
    result = fleet(empty, "--sensor", "hdl64e", "--out", tmp_path / "o", "--workers", 1)
    assert result.returncode == 2 and "folder holds no cloud files" in result.stderr
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    for folder in "ab":
        np.zeros((1, 4), np.float32).tofile(tmp_path / folder / "x.bin")
    # two inputs of one output: both named, nothing written (the command line's rule)
    result = fleet(tmp_path / "a", tmp_path / "b", "--sensor", "hdl64e", "--out", tmp_path / "o")
    assert result.returncode == 2
    assert (f"{tmp_path / 'a' / 'x.bin'} and {tmp_path / 'b' / 'x.bin'} would both write "
            f"{tmp_path / 'o' / 'x.label'}") in result.stderr
    assert not (tmp_path / "o").exists()
    # two drives of one name would share their folder and its index.csv
    for folder in "ab":
        shutil.copyfile(REPO / "tests" / "data" / "drives" / "vlp16_zstd.mcap",
                        tmp_path / folder / "drive.mcap")
    result = fleet(tmp_path / "a" / "drive.mcap", tmp_path / "b" / "drive.mcap", "--sensor",
                   "vlp16", "--out", tmp_path / "o")
    assert result.returncode == 2
    assert (f"{tmp_path / 'a' / 'drive.mcap'} and {tmp_path / 'b' / 'drive.mcap'} would both "
            f"write {tmp_path / 'o' / 'drive'}") in result.stderr
    assert not (tmp_path / "o").exists()
    result = fleet(scans, "--sensor", "hdl64e", "--out", tmp_path / "o", "--workers", 1,
                   "--scheduler", "tcp://127.0.0.1:1")
    assert result.returncode == 2 and "not allowed with" in result.stderr


class FakeTerminal:
    def __init__(self, tty):
        self.tty, self.text = tty, ""

    def isatty(self):
        return self.tty

    def write(self, text):
        self.text += text

    def flush(self):
        pass


def test_progress_bar_shows_frames_per_second():
    from lpir_gseg.fleet import Progress

    terminal = FakeTerminal(True)
    bar = Progress(4, True, terminal)
    for i in range(4):
        bar.step(1, int(i == 2), f"f{i}")
    bar.close()
    last = terminal.text.split("\r")[-1]
    assert last.startswith("[" + "#" * 30 + "] 4/4 100%") and "frames/s" in last
    assert "1 failed" in last and "f3" in last and last.endswith("\n")
    log = FakeTerminal(False)
    bar = Progress(20, True, log)
    for i in range(20):
        bar.step(1, 0)
    assert log.text.count("progress:") == 10 and "\r" not in log.text


def test_a_folder_of_clouds_and_drives_is_written_as_segment_writes_it(cli, tmp_path):
    """Two scans, an MCAP, a ROS 2 bag folder and a file that is neither: the fleet names the
    file it skips, counts the drives' messages as frames and writes what `segment` writes."""
    drives = Path(__file__).resolve().parents[2] / "tests" / "data" / "drives"
    folder = tmp_path / "mixed"
    folder.mkdir()
    for i in range(2):
        (folder / f"{i:06}.bin").write_bytes((drives / "narrow" / f"{i:06}.bin").read_bytes())
    (folder / "vlp16_zstd.mcap").write_bytes((drives / "vlp16_zstd.mcap").read_bytes())
    (folder / "bag").mkdir()
    for f in (drives / "vlp16_split_mcap").iterdir():
        name = f.name.replace("vlp16_split_mcap", "bag")  # a renamed folder: metadata.yaml rules
        (folder / "bag" / name).write_bytes(f.read_bytes())
    metadata = folder / "bag" / "metadata.yaml"
    metadata.write_text(metadata.read_text().replace("vlp16_split_mcap", "bag"))
    (folder / "README.txt").write_text("not a cloud")
    result = fleet(folder, "--sensor", "vlp16", "--out", tmp_path / "fleet", "--workers", 2,
                   "--backend", "cpu")
    assert result.returncode == 0, result.stderr
    assert f"lpir_gseg.fleet: skipped {folder / 'README.txt'}: neither a cloud file" \
        in result.stderr
    assert "wrote 8 label files" in result.stdout  # 2 scans + 3 + 3 messages
    assert "(2 files and 2 drives, 8 frames in" in result.stdout
    segment = run_cli(cli, "segment", folder, "--sensor", "vlp16", "--backend", "cpu", "--out",
                      tmp_path / "cli", "--quiet")
    assert segment.returncode == 0, segment.stderr
    cli_files = sorted(p.relative_to(tmp_path / "cli") for p in (tmp_path / "cli").rglob("*.label"))
    assert len(cli_files) == 8
    fleet_files = sorted(p.relative_to(tmp_path / "fleet")
                         for p in (tmp_path / "fleet").rglob("*.label"))
    assert fleet_files == cli_files
    for name in cli_files:
        assert (tmp_path / "fleet" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()


def test_recursive_keeps_each_input_at_its_path_below_the_folder_as_segment_does(cli, tmp_path):
    """Scans and drives of one name in two subfolders: refused without --recursive (the folder
    holds none itself), kept apart by their paths with it, the files those of `segment -r`."""
    drives = Path(__file__).resolve().parents[2] / "tests" / "data" / "drives"
    root = tmp_path / "runs"
    for sub in ("a", "b/c"):
        (root / sub).mkdir(parents=True)
        (root / sub / "000000.bin").write_bytes((drives / "narrow" / "000000.bin").read_bytes())
        (root / sub / "drive.mcap").write_bytes((drives / "vlp16_zstd.mcap").read_bytes())
    result = fleet(root, "--sensor", "vlp16", "--out", tmp_path / "fleet", "--workers", 1,
                   "--backend", "cpu")
    assert result.returncode == 2 and "--recursive (-r)" in result.stderr, result.stderr
    assert not (tmp_path / "fleet").exists()
    result = fleet(root, "-r", "--sensor", "vlp16", "--out", tmp_path / "fleet", "--workers", 2,
                   "--backend", "cpu")
    assert result.returncode == 0, result.stderr
    assert "(2 files and 2 drives, 8 frames in" in result.stdout
    segment = run_cli(cli, "segment", root, "-r", "--sensor", "vlp16", "--backend", "cpu",
                      "--out", tmp_path / "cli", "--quiet")
    assert segment.returncode == 0, segment.stderr
    cli_files = sorted(p.relative_to(tmp_path / "cli") for p in (tmp_path / "cli").rglob("*.label"))
    assert Path("a/000000.label") in cli_files and Path("b/c/000000.label") in cli_files
    assert len([p for p in cli_files if p.parent.name == "drive"]) == 6
    fleet_files = sorted(p.relative_to(tmp_path / "fleet")
                         for p in (tmp_path / "fleet").rglob("*.label"))
    assert fleet_files == cli_files
    for name in cli_files:
        assert (tmp_path / "fleet" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes()
