#!/usr/bin/python3
"""lpir-gseg segment over 30 files as a person sees it, on a real pseudo-terminal (pty) and
through a pipe: on the terminal the screen ends with one progress line and the summary, and no
line holds a fragment of the progress beside other text; the pipe gets no carriage return and no
escape code; --quiet prints nothing on success.

usage: cli_terminal_test.py LPIR_GSEG"""
import os
import pty
import re
import subprocess
import sys
import tempfile

FILES = 30


def screen(raw):
    """The lines a terminal shows after `raw`: '\\r' returns to the line's start, ESC [ K erases
    to its end, '\\n' moves down; any other escape sequence fails the test."""
    lines, row, col = [[]], 0, 0
    i = 0
    while i < len(raw):
        c = raw[i]
        if c == "\r":
            col = 0
        elif c == "\n":
            row += 1
            col = 0
            if row == len(lines):
                lines.append([])
        elif c == "\x1b":
            m = re.match(r"\x1b\[([0-9]*)K", raw[i:])
            assert m and m.group(1) in ("", "0"), f"unexpected escape {raw[i:i + 8]!r}"
            del lines[row][col:]
            i += len(m.group(0))
            continue
        else:
            line = lines[row]
            line.extend(" " * (col - len(line)))
            if col < len(line):
                line[col] = c
            else:
                line.append(c)
            col += 1
        i += 1
    text = ["".join(line).rstrip() for line in lines]
    while text and not text[-1]:
        text.pop()
    return text


def run_pty(argv):
    """Runs argv with stdin, stdout and stderr on one pseudo-terminal; returns (code, output)."""
    pid, fd = pty.fork()
    if pid == 0:
        os.execv(argv[0], argv)
    chunks = []
    while True:
        try:
            data = os.read(fd, 65536)
        except OSError:  # EIO: the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    _, status = os.waitpid(pid, 0)
    os.close(fd)
    return os.waitstatus_to_exitcode(status), b"".join(chunks).decode()


def main():
    cli = sys.argv[1]
    failures = []

    def check(ok, what, text):
        if not ok:
            failures.append(f"{what}\n--- output ---\n{text!r}")

    with tempfile.TemporaryDirectory() as tmp:
        scans = os.path.join(tmp, "in")
        os.mkdir(scans)
        for seed in range(FILES):
            subprocess.run([cli, "simulate", "--sensor", "vlp16", "--seed", str(seed + 1), "--out",
                            os.path.join(scans, f"{seed:06}.bin"), "--labels",
                            os.path.join(tmp, f"{seed:06}.label")],
                           check=True, stdout=subprocess.DEVNULL)
        segment = [cli, "segment", scans, "--sensor", "vlp16", "--backend", "cpu", "--out"]

        # The terminal.
        code, raw = run_pty(segment + [os.path.join(tmp, "tty")])
        check(code == 0, f"exit code {code} on the terminal", raw)
        lines = screen(raw)
        bar = re.compile(r"\[[#.]{20}\]")
        bars = [line for line in lines if bar.search(line)]
        check(len(bars) == 1, f"{len(bars)} progress lines on the screen", "\n".join(lines))
        check(all(bar.match(line) and "segmented" not in line for line in bars),
              "a progress line holds other text", "\n".join(lines))
        check(any(f"{FILES}/{FILES} 100%" in line for line in bars), "the bar does not end full",
              "\n".join(lines))
        for line in lines:
            if not bar.search(line):
                check("frames/s  " not in line and "% ground  " not in line and "[#" not in line,
                      "a fragment of the bar inside another line", line)
        check(bool(lines) and lines[-1].startswith(f"segmented {FILES} of {FILES} files"),
              "the summary is not the last line", "\n".join(lines))
        check(len(lines) == 2, f"{len(lines)} lines on the screen, not the bar and the summary",
              "\n".join(lines))

        # A pipe.
        piped = subprocess.run(segment + [os.path.join(tmp, "pipe")], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
        check(piped.returncode == 0, f"exit code {piped.returncode} piped", piped.stdout)
        check("\r" not in piped.stdout and "\x1b" not in piped.stdout,
              "a carriage return or escape code in piped output", piped.stdout)
        check("progress: " in piped.stdout, "no progress line piped", piped.stdout)
        check(piped.stdout.splitlines()[-1].startswith(f"segmented {FILES} of {FILES} files"),
              "the summary is not the last piped line", piped.stdout)

        # --quiet, on the terminal and piped.
        code, raw = run_pty(segment + [os.path.join(tmp, "quiet_tty"), "--quiet"])
        check(code == 0 and raw == "", f"--quiet on the terminal: exit code {code}, output", raw)
        quiet = subprocess.run(segment + [os.path.join(tmp, "quiet"), "--quiet"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        check(quiet.returncode == 0 and quiet.stdout == "",
              f"--quiet piped: exit code {quiet.returncode}, output", quiet.stdout)

        # A bad file among the good ones: its error is a line of its own above the bar.
        with open(os.path.join(scans, "000005x.bin"), "wb") as f:
            f.write(b"\1" * 21)
        code, raw = run_pty(segment + [os.path.join(tmp, "bad")])
        lines = screen(raw)
        check(code == 1, f"exit code {code} with a bad file", raw)
        errors = [line for line in lines if "error:" in line]
        check(len(errors) == 1 and errors[0].startswith("lpir-gseg segment: error: "),
              "the error is not a line of its own", "\n".join(lines))
        check(len([line for line in lines if bar.search(line)]) == 1,
              "not one progress line with a bad file", "\n".join(lines))
        check(lines[-1] == f"lpir-gseg segment: 1 of {FILES + 1} files failed",
              "the failures are not the last line", "\n".join(lines))

    for f in failures:
        print("FAIL:", f)
    print(f"{'FAILED' if failures else 'passed'}: terminal, pipe and --quiet over {FILES} files")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
