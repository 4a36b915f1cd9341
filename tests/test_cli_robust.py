"""The command line under bad input, failures and signals (issue 7).

Every case asserts the exit status, exactly one stderr line naming the option
or the problem, no traceback, no file left behind and a bounded time.
"""

from __future__ import annotations

import errno
import importlib
import os
import shutil
import signal
import stat
import subprocess
import sys
import time

import numpy as np
import pytest

from lumped import cli
from lumped.cli import main, option_message

#: A run of 1e9 Algorithm 1 steps: about 24 s with the C kernel, so a case
#: that returns within TIME_BOUND was refused before computing.
LONG_RUN = ["--t-end", "1000", "--dt", "1e-6", "--save-every", "1000000"]
TIME_BOUND = 5.0
BIG = str(2**63)
#: The driver's module (``lumped.simulate`` the attribute is the function).
DRIVER = importlib.import_module("lumped.simulate")


def _one_line(err: str) -> str:
    assert "Traceback" not in err, err
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    return lines[0]


def _main(argv, capsys) -> tuple[int, str]:
    """``main`` in this process: its status and its one stderr line, timed."""
    start = time.monotonic()
    status = main(argv)
    assert time.monotonic() - start < TIME_BOUND
    return status, _one_line(capsys.readouterr().err)


# --- bad command lines: status 2, one line naming the real problem -----------------

BAD = [  # (arguments after "simulate", folders to create first, words the line must hold)
    (["--output", "d.csv", *LONG_RUN], ["d.csv"], ["--output", "'d.csv' is a directory"]),
    (["--output", "sub/", *LONG_RUN], ["sub"], ["--output", "is a directory"]),
    (["--output", "nope/o.csv", *LONG_RUN], [], ["--output", "does not exist"]),
    (["--output", ".csv"], [], ["--output", "no file name"]),
    (["--output", "sub/.NPZ"], ["sub"], ["--output", "no file name"]),
    (["--output", ""], [], ["--output", "empty"]),
    (["--output", "o.txt"], [], ["--output", ".csv or .npz"]),
    (["--mass", "--output", "o.csv"], [], ["--mass", "expected one argument"]),
    (["--output", "o.csv", "--dt"], [], ["--dt", "expected one argument"]),
    (["--dt", "1e-3", "--output"], [], ["--output", "expected one argument"]),
    (["--dt", "1e-3", "--dt=1e-4", "--output", "o.csv"], [], ["--dt", "more than once"]),
    (["--output", "a.csv", "--output", "b.csv"], [], ["--output", "more than once"]),
    (["--x00", "1", "--output", "o.csv"], [], ["--x00"]),
    (["--mas", "2", "--output", "o.csv"], [], ["--mas"]),  # no abbreviations
    (["--gamma", "1e400", "--output", "o.csv"], [], ["--gamma", "double precision"]),
    (["--save-every", "-1", "--output", "o.csv"], [], ["--save-every", "integer >= 1"]),
    (["--t-end", "1e5", "--dt", "1e-4", "--output", "o.csv"], [], ["--save-every", "GiB"]),  # fmt: skip
    (["--t-end", "1e9", "--dt", "1e-9", "--output", "o.csv"], [], ["--t-end/--dt"]),
    (["--method", "exact", "--force-amplitude", "10", "--force-omega", "1e300",
      "--output", "o.csv"], [], ["exact"]),  # fmt: skip  (API: will name --force-omega instead)
]


@pytest.mark.parametrize(("args", "folders", "words"), BAD, ids=[" ".join(a[:4]) for a, _, _ in BAD])
def test_bad_command_line(tmp_path, monkeypatch, capsys, args, folders, words):
    monkeypatch.chdir(tmp_path)
    for folder in folders:
        os.mkdir(folder)
    status, line = _main(["simulate", *args], capsys)
    assert status == 2
    assert line.startswith("lumped")
    if words == ["exact"]:  # either the API's refusal or the CLI's belt and braces
        assert "--force-omega" in line or "the exact run failed" in line
    else:
        assert all(word in line for word in words), line
    assert sorted(os.listdir(tmp_path)) == sorted(folders)


def test_gamma_inf_is_coulomb_and_writes(tmp_path, capsys):
    status, line = _main(["simulate", "--gamma", "inf", "--x0", "0.5", "--t-end", "0.2",
                          "--output", str(tmp_path / "c.csv")], capsys)  # fmt: skip
    assert status == 0 and "wrote" in line
    assert os.listdir(tmp_path) == ["c.csv"]


def test_huge_save_every_gives_one_line(tmp_path, capsys):
    """Status 0 (t = 0 and the last point) or 2, never a traceback."""
    status, line = _main(["simulate", "--t-end", "0.01", "--save-every", BIG,
                          "--output", str(tmp_path / "o.csv")], capsys)  # fmt: skip
    assert status in (0, 2) and line.startswith("lumped simulate")
    assert os.listdir(tmp_path) == (["o.csv"] if status == 0 else [])


@pytest.mark.parametrize("method", [
    "backward-euler",
    "exact",
])  # fmt: skip
def test_huge_save_every_keeps_first_and_last(tmp_path, capsys, method):
    out = tmp_path / "o.csv"
    status, _ = _main(["simulate", "--method", method, "--t-end", "0.01", "--save-every", BIG,
                       "--output", str(out)], capsys)  # fmt: skip
    assert status == 0
    assert np.loadtxt(out, delimiter=",", skiprows=1)[:, 0].tolist() == [0.0, 0.01]


OVERFLOW = [
    (["--x0", "1e307"], ("--x0",)),
    (["--v0", "1e307"], ("--v0",)),
    (["--force-amplitude", "1e307", "--force-omega", "1"], ("--force-amplitude",)),
    (["--stiffness", "1e300", "--x0", "1e10"], ("--stiffness", "--x0")),
    (["--method", "exact", "--force-amplitude", "10", "--force-omega", "1e300"], ("--force-omega",)),
]


@pytest.mark.parametrize(("args", "options"), OVERFLOW, ids=[" ".join(a) for a, _ in OVERFLOW])
def test_overflow_is_refused_naming_the_option(tmp_path, capsys, args, options):
    status, line = _main(["simulate", *args, "--t-end", "0.01", "--output",
                          str(tmp_path / "o.csv")], capsys)  # fmt: skip
    assert status == 2 and any(option in line for option in options), line
    assert os.listdir(tmp_path) == []


# --- API errors and failures during the run: one line, the temporary file removed ---


def _raise(exc):
    def run(*args, **kwargs):
        raise exc

    return run


def _sigterm(*args, **kwargs):
    os.kill(os.getpid(), signal.SIGTERM)  # the handler runs on return from kill()
    raise AssertionError("SIGTERM did not unwind the run")


FAILURES = [  # (the driver's behaviour, status, the whole line after "lumped simulate: ")
    (_raise(ValueError("x0: the initial state overflows (|x0| k = 1e310 N)")), 2,
     "error: --x0: the initial state overflows (|x0| k = 1e310 N)"),
    (_raise(ValueError("force_amplitude must be finite, got inf")), 2,
     "error: --force-amplitude must be finite, got inf"),
    (_raise(ValueError("t_end/dt: 3e+10 steps would take about 700 s; raise dt or shorten t_end")), 2,
     "error: --t-end/--dt: 3e+10 steps would take about 700 s; raise dt or shorten t_end"),
    (_raise(ValueError("the run overflowed at t = 1.5: x = inf")), 2,
     "error: the run overflowed at t = 1.5: x = inf"),
    (_raise(ValueError("two\nlines")), 2, "error: two lines"),
    (_raise(OverflowError("math range error")), 2,
     "error: the backward-euler run failed: OverflowError: math range error"),
    (_raise(FloatingPointError("overflow")), 2,
     "error: the backward-euler run failed: FloatingPointError: overflow"),
    (_raise(MemoryError()), 2, "error: out of memory; raise --save-every or --dt"),
    (_raise(KeyboardInterrupt()), 130, "interrupted; no output written"),
    (_sigterm, 143, "interrupted; no output written"),
]  # fmt: skip


@pytest.mark.parametrize(("run", "status", "line"), FAILURES, ids=[f[2][:40] for f in FAILURES])
def test_failure_during_the_run(tmp_path, monkeypatch, capsys, run, status, line):
    monkeypatch.setattr(DRIVER, "simulate", run)
    before = signal.getsignal(signal.SIGTERM)
    assert _main(["simulate", "--output", str(tmp_path / "o.csv")], capsys) == (
        status, "lumped simulate: " + line)
    assert os.listdir(tmp_path) == []
    assert signal.getsignal(signal.SIGTERM) is before  # handlers restored


def test_disk_full_during_the_write(tmp_path, monkeypatch, capsys):
    def full(*args, **kwargs):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(np, "savetxt", full)
    out = tmp_path / "o.csv"
    status, line = _main(["simulate", "--t-end", "0.01", "--output", str(out)], capsys)
    assert status == 2
    assert line == ("lumped simulate: error: --output: "
                    f"cannot write {str(out)!r}: No space left on device")  # fmt: skip
    assert os.listdir(tmp_path) == []


def test_unwritable_folder_is_refused_before_the_run(tmp_path, monkeypatch, capsys):
    def denied(*args, **kwargs):
        raise PermissionError(errno.EACCES, os.strerror(errno.EACCES))

    monkeypatch.setattr(cli.tempfile, "mkstemp", denied)
    monkeypatch.setattr(DRIVER, "simulate", _raise(AssertionError("ran")))
    status, line = _main(["simulate", "--output", str(tmp_path / "o.csv")], capsys)
    assert status == 2
    assert line == ("lumped simulate: error: --output: "
                    f"cannot create a file in {str(tmp_path)!r}: Permission denied")  # fmt: skip


def _make_unwritable(folder) -> list[str]:
    """Make ``folder`` unwritable even for root; return the command that undoes it."""
    folder.chmod(0o555)
    if not os.access(folder, os.W_OK):
        return ["chmod", "755", str(folder)]
    # root ignores the mode bits; the immutable attribute (ext4) stops it too
    if shutil.which("chattr") and subprocess.run(["chattr", "+i", str(folder)]).returncode == 0:
        return ["chattr", "-i", str(folder)]
    folder.chmod(0o755)
    pytest.skip("running as root on a file system without chattr +i: cannot make a folder unwritable")


def test_read_only_folder(tmp_path, capsys):
    folder = tmp_path / "ro"
    folder.mkdir()
    undo = _make_unwritable(folder)
    try:
        status, line = _main(["simulate", *LONG_RUN, "--output", str(folder / "o.csv")], capsys)
        assert status == 2 and "--output: cannot create a file in" in line
        assert os.listdir(folder) == []
    finally:
        subprocess.run(undo, check=True)
        folder.chmod(0o755)


@pytest.mark.parametrize(
    ("message", "expected"),
    [
        ("mass must be > 0 and finite, got 0.0", "--mass must be > 0 and finite, got 0.0"),
        ("save_every: the output would need 5 GiB", "--save-every: the output would need 5 GiB"),
        ("x0: |x0| k = 1e310 N overflows", "--x0: |x0| k = 1e310 N overflows"),  # a formula
        ("t_end/dt must be at most 2e+09 steps", "--t-end/--dt must be at most 2e+09 steps"),
        ("force_until must be >= 0", "--force-until must be >= 0"),
        ("gamma: 1e400 is beyond double precision", "--gamma: 1e400 is beyond double precision"),
        ("mass must be a number, got 'dt'", "--mass must be a number, got 'dt'"),  # the user's value
        ("massive failure: dt", "massive failure: dt"),
        ("the run overflowed at t = 2: dt too large", "the run overflowed at t = 2: dt too large"),
        ("t must be sorted", "t must be sorted"),  # an API name with no option
    ],
)  # fmt: skip
def test_option_message(message, expected):
    assert option_message(message) == expected


# --- the summary comes from the method's full-resolution run -----------------------


def test_summary_independent_of_save_every(tmp_path, capsys):
    lines = []
    for k in ("1", "1000"):
        argv = ["simulate", "--x0", "0.5", "--t-end", "4", "--dt", "1e-4", "--save-every", k,
                "--output", str(tmp_path / f"k{k}.npz")]  # fmt: skip
        lines.append(_main(argv, capsys)[1].split(";")[0])
    assert lines[0] == lines[1]
    assert "at rest from t = 3.1458 s" in lines[0]


def test_exact_summary_is_the_event_time(tmp_path, capsys):
    argv = ["simulate", "--method", "exact", "--x0", "0.5", "--t-end", "4", "--dt", "1e-4",
            "--save-every", "1000", "--output", str(tmp_path / "e.npz")]  # fmt: skip
    assert "at rest from t = 3.145527023 s" in _main(argv, capsys)[1]


def test_still_moving_names_the_grids_last_time(tmp_path, capsys):
    argv = ["simulate", "--x0", "0.5", "--t-end", "1.00005", "--dt", "1e-4", "--save-every", "7",
            "--output", str(tmp_path / "m.csv")]  # fmt: skip
    assert "still moving at t = 1.0001 s" in _main(argv, capsys)[1]


# --- subprocesses: the interpreter's own behaviour, umask, signals -----------------


def _cli(*args, cwd, **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "lumped", *args], cwd=cwd, capture_output=True,
                          text=True, timeout=30, **kwargs)  # fmt: skip


def test_no_command(tmp_path):
    proc = _cli(cwd=tmp_path)
    assert proc.returncode == 2 and "COMMAND" in _one_line(proc.stderr)


def test_help(tmp_path):
    proc = _cli("simulate", "--help", cwd=tmp_path)
    assert proc.returncode == 0 and proc.stderr == ""
    assert proc.stdout.startswith("usage: lumped simulate") and "--save-every" in proc.stdout


@pytest.mark.parametrize(("umask", "existing", "mode"), [
    (0o022, None, 0o644),
    (0o077, None, 0o600),
    (0o077, 0o644, 0o644),
    (0o022, 0o600, 0o600),
])  # fmt: skip
def test_file_mode(tmp_path, umask, existing, mode):
    out = tmp_path / "o.csv"
    if existing is not None:
        out.write_text("old\n")
        out.chmod(existing)
    proc = _cli("simulate", "--t-end", "0.01", "--output", "o.csv", cwd=tmp_path, umask=umask)
    assert proc.returncode == 0, proc.stderr
    assert stat.S_IMODE(out.stat().st_mode) == mode
    assert out.read_text().startswith("t,x,v,F_s,F_d,F\n")


def _interrupt(tmp_path, args, sig, *, started, env=None, wait=3.0):
    """Start a run, wait until ``started(temporary file)``, send ``sig``; returns the
    finished process and the seconds it took after the signal (at most ``wait``)."""
    env = {**os.environ, **(env or {})}
    proc = subprocess.Popen([sys.executable, "-m", "lumped", "simulate", *args, "--output", "o.csv"],
                            cwd=tmp_path, env=env, stderr=subprocess.PIPE, text=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))  # fmt: skip
    try:
        deadline = time.monotonic() + 10
        while not any(started(tmp_path / f) for f in os.listdir(tmp_path)):
            assert proc.poll() is None and time.monotonic() < deadline, "the run did not start"
            time.sleep(0.02)
        time.sleep(0.2)
        proc.send_signal(sig)
        sent = time.monotonic()
        _, err = proc.communicate(timeout=wait)
    finally:
        proc.kill()
    return subprocess.CompletedProcess(proc.args, proc.returncode, "", err), time.monotonic() - sent


def _exists(path) -> bool:
    return True


def _has_data(path) -> bool:
    return path.stat().st_size > 0


PHASES = {  # the phase the signal reaches -> (arguments, environment, when to send)
    # Algorithm 1 in the Python loop (1e8 steps, about 30 s): interruptible anywhere
    "run": (["--t-end", "100", "--dt", "1e-6", "--save-every", "100000000"],
            {"LUMPED_PURE_PYTHON": "1"}, _exists),
    # 2e6 rows: the C kernel takes 0.05 s, writing the 55 MB of CSV about 5 s
    "write": (["--t-end", "20", "--dt", "1e-5"], None, _has_data),
}  # fmt: skip


@pytest.mark.parametrize("phase", PHASES)
@pytest.mark.parametrize(("sig", "status"), [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_signal_removes_the_temporary_file(tmp_path, phase, sig, status):
    args, env, started = PHASES[phase]
    proc, _ = _interrupt(tmp_path, args, sig, started=started, env=env)
    assert proc.returncode == status
    assert _one_line(proc.stderr) == "lumped simulate: interrupted; no output written"
    assert os.listdir(tmp_path) == []


def test_sigint_stops_the_c_kernel_at_once(tmp_path):
    proc, waited = _interrupt(tmp_path, LONG_RUN, signal.SIGINT, started=_exists, wait=1.5)
    assert proc.returncode == 130 and waited < 1.0
    assert os.listdir(tmp_path) == []
