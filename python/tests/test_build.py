"""`oblique.build_table`: tables built from Python are those `sweep run` builds, bad configs are
refused naming the key, and an interrupted build resumes to the uninterrupted table.

Every build here is of configs/quick.toml (about a second on 2 cores) into the test's tmp_path.
"""

from __future__ import annotations

import os
import re
import signal
import subprocess
import threading
from pathlib import Path
from typing import Callable, Dict, List

import h5py
import numpy as np
import pytest

import oblique
from _oblique_helpers import ROOT

QUICK = ROOT / "configs" / "quick.toml"

#: configs/quick.toml as a dict (the test below checks that it is the same config).
QUICK_DICT = {
    "output": "out/quick.h5",
    "domain": {"gamma_min": 0.5, "gamma_max": 2.5, "alpha_max": "inf"},
    "nodes": {"placement": "aligned", "stencil": 4, "target_error": 1e-3, "leaf_intervals": 8},
    "solver": {"tol": 1e-5},
    "checks": {"per_patch": 20, "seed": 1},
}


def p_datasets(path: Path) -> Dict[str, bytes]:
    """The P datasets of a table (`P` of every patch and of the no-slip line, `P_simulated` and
    `P_interpolated` of the checks), as their bytes."""
    out: Dict[str, bytes] = {}

    def visit(name: str, obj: object) -> None:
        leaf = name.rsplit("/", 1)[-1]
        if isinstance(obj, h5py.Dataset) and (leaf == "P" or leaf.startswith("P_")):
            data = obj[()]
            assert data.dtype == np.float64, name
            out[name] = data.tobytes()

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    assert "patches/partial_high/P" in out and "checks/P_simulated" in out, sorted(out)
    return out


def same_table(a: Path, b: Path) -> None:
    pa, pb = p_datasets(a), p_datasets(b)
    assert sorted(pa) == sorted(pb)
    for name in pa:
        assert pa[name] == pb[name], f"{name} differs between {a} and {b}"


@pytest.fixture(scope="module")
def cli_table(tmp_path_factory, sweep_bin) -> Path:
    """configs/quick.toml built by `sweep run`."""
    out = tmp_path_factory.mktemp("cli") / "quick.h5"
    r = subprocess.run(
        [str(sweep_bin), "run", str(QUICK), "-o", str(out), "--quiet", "--threads", "2"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, f"sweep run failed: {r.stderr[-2000:]}"
    return out


def test_a_path_and_a_dict_build_the_table_sweep_run_builds(tmp_path, cli_table):
    from_path = oblique.build_table(QUICK, tmp_path / "path.h5", threads=2, progress=False)
    assert from_path == tmp_path / "path.h5" and isinstance(from_path, Path)
    from_str = oblique.build_table(str(QUICK), str(tmp_path / "str.h5"), progress=False)
    from_dict = oblique.build_table(QUICK_DICT, tmp_path / "dict.h5", threads=1, progress=False)
    for built in (from_path, from_str, from_dict):
        same_table(cli_table, built)
        assert not Path(f"{built}.ckpt").exists() and not Path(f"{built}.lock").exists()
    t = oblique.Table(from_dict)
    assert t.p(1.754, 1.0) == oblique.Table(cli_table).p(1.754, 1.0)
    # The dict's TOML is the config: the same keys and values as the file.
    assert t.info["gamma_min"] == 0.5 and t.info["target_error"] == 1e-3


def test_the_config_output_is_used_relative_to_the_working_directory(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    cfg = dict(QUICK_DICT, output="sub/dir/t.h5")
    out = oblique.build_table(cfg, progress=False)
    assert out == Path("sub/dir/t.h5")
    assert (tmp_path / "sub" / "dir" / "t.h5").is_file()


@pytest.mark.parametrize(
    "change, needles",
    [
        ({"nodes": {"target_error": 0.5}}, ["nodes.target_error", "0.5", "(0, 0.1)"]),
        ({"checks": {"per_patch": 0}}, ["checks.per_patch", "[1, 100000]"]),
        ({"domain": {"gamma_max": 100.0}}, ["domain.gamma_max", "64"]),
        ({"nodes": {"foo": 1}}, ["unknown field `foo`"]),
        ({"nodes": {"stencil": "four"}}, ["stencil"]),
        ({"nodes": {"stencil": None}}, ["nodes.stencil", "None"]),
        ({"run": {"threads": 5000}}, ["run.threads", "[0, 1024]"]),
    ],
)
def test_a_bad_key_or_value_raises_value_error_naming_it(tmp_path, change, needles):
    cfg = {k: (dict(v) if isinstance(v, dict) else v) for k, v in QUICK_DICT.items()}
    for table, keys in change.items():
        cfg.setdefault(table, {}).update(keys)
    with pytest.raises(ValueError) as e:
        oblique.build_table(cfg, tmp_path / "t.h5", progress=False)
    for n in needles:
        assert n in str(e.value), f"{n!r} not in: {e.value}"
    assert not list(tmp_path.iterdir()), "a refused config wrote nothing"


def test_a_bad_config_file_is_named_and_bad_arguments_are_refused(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(QUICK.read_text().replace("tol = 1e-5", "tol = 0.5"))
    with pytest.raises(ValueError, match=re.escape(f"config {bad}: `solver.tol` = 0.5")):
        oblique.build_table(bad, tmp_path / "t.h5", progress=False)
    with pytest.raises(FileNotFoundError):
        oblique.build_table(tmp_path / "missing.toml", progress=False)
    with pytest.raises(ValueError, match=r"threads = 2000: must be in \[0, 1024\]"):
        oblique.build_table(QUICK, tmp_path / "t.h5", threads=2000, progress=False)
    with pytest.raises(ValueError, match="threads = -1"):
        oblique.build_table(QUICK, tmp_path / "t.h5", threads=-1, progress=False)
    with pytest.raises(ValueError, match="exclude each other"):
        oblique.build_table(QUICK, tmp_path / "t.h5", resume=True, restart=True)
    # Outputs that cannot be written: OSError, of the subclass of the operating system's error.
    with pytest.raises(IsADirectoryError, match="is a directory"):
        oblique.build_table(QUICK, tmp_path, progress=False)
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(NotADirectoryError, match=re.escape(f"output {blocker / 't.h5'}")):
        oblique.build_table(QUICK, blocker / "t.h5", progress=False)
    # The config file itself is no output.
    cfg = tmp_path / "self.toml"
    cfg.write_text(QUICK.read_text())
    with pytest.raises(ValueError, match="is the input"):
        oblique.build_table(cfg, cfg, progress=False)
    assert cfg.read_text() == QUICK.read_text()


def note_taker(notes: List[str]) -> Callable[[oblique.BuildProgress], None]:
    """A progress callable that keeps the notes."""

    def take(report: oblique.BuildProgress) -> None:
        if report.kind == "note":
            notes.append(report.message)

    return take


def _interrupt_by_signal(report: oblique.BuildProgress) -> None:
    """Ctrl-C as a terminal sends it: SIGINT to this process, from another thread. The thread
    is joined, so that the signal is delivered before the build can end; its handler then runs
    in this callback or at the build's next check for signals."""
    if report.kind == "stage" and report.step == 3:
        sender = threading.Thread(target=os.kill, args=(os.getpid(), signal.SIGINT))
        sender.start()
        sender.join()


def _interrupt_by_raising(report: oblique.BuildProgress) -> None:
    if report.kind == "stage" and report.step == 3:
        raise KeyboardInterrupt


@pytest.mark.parametrize("interrupt", [_interrupt_by_signal, _interrupt_by_raising])
def test_an_interrupted_build_resumes_to_the_uninterrupted_table(tmp_path, cli_table, interrupt):
    out = tmp_path / "t.h5"
    ckpt = tmp_path / "t.h5.ckpt"
    seen: List[oblique.BuildProgress] = []

    def progress(report: oblique.BuildProgress) -> None:
        seen.append(report)
        interrupt(report)

    # Python's own Ctrl-C handler, even where the test runner was started with SIGINT ignored
    # (a background job of a non-interactive shell: Python then keeps SIG_IGN).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt, match=r"resume=True"):
            oblique.build_table(QUICK, out, progress=progress)
    finally:
        signal.signal(signal.SIGINT, previous)
    assert ckpt.is_file() and not out.exists()
    assert not (tmp_path / "t.h5.lock").exists(), "the lock is released"
    assert [r.stage for r in seen if r.kind == "stage"][:2] == ["preflight", "stick_low refinement"]
    if interrupt is _interrupt_by_raising:
        assert seen[-1].step == 3, "the callback hears nothing once it raised"

    # The checkpoint is not overwritten without resume=True, and the message says both ways out.
    with pytest.raises(FileExistsError) as e:
        oblique.build_table(QUICK, out, progress=False)
    assert "resume=True" in str(e.value) and "restart=True" in str(e.value)
    assert ckpt.is_file()

    notes: List[str] = []
    resumed = oblique.build_table(QUICK, out, resume=True, progress=note_taker(notes))
    assert resumed == out and not ckpt.exists()
    resuming = re.compile(r"resuming from .*t\.h5\.ckpt: [1-9]\d* nodes already computed")
    assert any(resuming.fullmatch(n) for n in notes), notes
    same_table(cli_table, out)


def test_a_checkpoint_of_another_config_is_refused_until_restart(tmp_path, cli_table):
    out = tmp_path / "t.h5"
    ckpt = tmp_path / "t.h5.ckpt"
    ckpt.write_bytes(b"not a checkpoint")
    for resume in (False, True):
        with pytest.raises(FileExistsError, match=r"no readable checkpoint.*restart=True"):
            oblique.build_table(QUICK, out, resume=resume, progress=False)
        assert ckpt.read_bytes() == b"not a checkpoint"
    notes: List[str] = []
    oblique.build_table(QUICK, out, restart=True, progress=note_taker(notes))
    assert f"discarded the checkpoint {ckpt}" in notes
    assert not ckpt.exists()
    same_table(cli_table, out)


def test_progress_goes_to_stderr_in_lines_and_false_is_silent(tmp_path, capfd):
    oblique.build_table(QUICK, tmp_path / "a.h5", progress=False)
    got = capfd.readouterr()
    assert got.out == "" and got.err == ""
    oblique.build_table(QUICK, tmp_path / "b.h5")
    got = capfd.readouterr()
    assert got.out == ""
    lines = got.err.splitlines()
    for want in (
        "[oblique] step 1/6 preflight: probing the hardest points of the domain",
        "[oblique] step 2/6 stick_low refinement: round 1: 4 open cells, 297 new nodes",
        "[oblique] step 5/6 held-out checks: 60 points",
        f"[oblique] step 6/6 writing: {tmp_path / 'b.h5'}",
    ):
        assert want in lines, f"{want!r} not in:\n{got.err}"
    assert any(line.startswith("preflight: tolerances reachable") for line in lines), got.err
    # The line `sweep run` ends with.
    wrote = rf"wrote {re.escape(str(tmp_path / 'b.h5'))}: \d+ nodes \(\d+ simulated\) \+ 60 "
    wrote += r"held-out checks, max check error \d\.\d\de-\d+, \d+\.\d s"
    assert re.fullmatch(wrote, lines[-1]), got.err
    assert "\r" not in got.err and "\x1b" not in got.err, "plain lines, no terminal control"
