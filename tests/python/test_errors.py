"""Bad input raises with the CLI's one-line messages; progress callbacks, cancelling and Ctrl-C."""
import os
import signal
import subprocess
import threading
import time

import numpy as np
import pytest

import isodel
from conftest import blobs


def cli_error(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    assert r.returncode == 2
    line = r.stderr.strip()
    assert line.startswith("isodel: ") and "\n" not in line
    return line[len("isodel: "):]


def test_iso_outside_range_has_the_cli_message(cli, data, tmp_path):
    path = str(data / "two_blobs.mrc")
    with pytest.raises(ValueError) as e:
        isodel.mesh(path, 5.0)
    assert str(e.value) == cli_error(cli, "mesh", path, "-o", str(tmp_path / "x.ply"), "--iso", "5", "--quiet")
    assert "outside the value range" in str(e.value)
    with pytest.raises(ValueError, match="outside the value range"):
        isodel.mesh(blobs(), 7.5)


def test_missing_file_has_the_cli_message(cli, tmp_path):
    path = str(tmp_path / "nope.mrc")
    with pytest.raises(OSError) as e:
        isodel.mesh(path, 0.5)
    assert str(e.value) == cli_error(cli, "mesh", path, "-o", str(tmp_path / "x.ply"), "--iso", "0.5", "--quiet")
    assert path in str(e.value)
    assert not os.path.exists(tmp_path / "x.ply")


@pytest.mark.parametrize("array, message", [
    (np.zeros((4, 5)), r"volume: expected a 3-d array, got 2 dimension\(s\), shape \(4, 5\)"),
    (np.zeros((2, 3, 4, 5)), "expected a 3-d array, got 4"),
    (np.zeros((0, 4, 4), np.float32), r"volume: empty array, shape \(0, 4, 4\)"),
    (np.zeros((3, 3, 3), np.complex64), "unsupported dtype complex64"),
    (np.zeros((3, 3, 3), ">f4"), "unsupported dtype"),
])
def test_bad_arrays(array, message):
    with pytest.raises(ValueError, match=message):
        isodel.mesh(array, 0.0)


def test_nan_is_refused_naming_its_index():
    arr = blobs()
    arr[3, 5, 7] = np.nan  # [z, y, x]
    with pytest.raises(ValueError, match=r"volume: NaN sample at index \(i,j,k\) = \(7, 5, 3\)"):
        isodel.mesh(arr, 0.45)
    with pytest.raises(ValueError, match=r"\(3, 5, 7\)"):
        isodel.mesh(arr, 0.45, axis_order="xyz")


@pytest.mark.parametrize("kwargs, message", [
    (dict(eps_voxels=-1), "eps"),
    (dict(eps=0.5, eps_voxels=0.5), "give one bound"),
    (dict(axis_order="yxz"), "axis_order"),
    (dict(tets="all"), "tets"),
    (dict(inside="left"), "inside"),
    (dict(spacing=(1, 0, 1)), "spacing"),
    (dict(threads=-3), "threads"),
    (dict(tets="inside", tet_spacing="coarse"), "tet_spacing"),
    (dict(tets="inside", tet_grading=0), "tet_grading"),
    (dict(tets="inside", tet_size=-1), "tet_size"),
    (dict(tets="inside", tet_min_dihedral_deg=80), "tet_min_dihedral_deg"),
    (dict(tets="inside", tet_max_dihedral_deg=30), "tet_max_dihedral_deg"),
])
def test_bad_options(kwargs, message):
    with pytest.raises(ValueError, match=message):
        isodel.mesh(blobs(), 0.45, **kwargs)


def test_a_stated_bound_raises_guarantee_violated(data):
    path = str(data / "two_blobs.mrc")
    with pytest.raises(isodel.GuaranteeViolated, match=r"^" + path + ": refinement stopped by the round bound") as e:
        isodel.mesh(path, 0.5, eps_voxels=0.1, max_rounds=1)
    assert isinstance(e.value, RuntimeError)
    # certify=True verifies before returning: a correct mesh comes back.
    assert isodel.mesh(path, 0.5, certify=True).stats["counts"]["triangles"] > 0


def test_progress_is_called_from_the_calling_thread(data):
    calls = []

    def progress(stage, fraction):
        calls.append((stage, fraction, threading.get_ident()))

    m = isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=0.5, progress=progress)
    assert len(m.triangles) > 0
    assert calls, "no progress reported"
    assert {t for _, _, t in calls} == {threading.get_ident()}
    assert all(f == -1 or 0 <= f <= 1 for _, f, _ in calls)
    stages = [s for s, _, _ in calls]
    assert "read" in stages and len(set(stages)) > 2


def test_progress_returning_false_cancels(data):
    seen = []

    def progress(stage, fraction):
        seen.append(stage)
        return stage == "read"  # False: cancel at the first stage after reading

    with pytest.raises(isodel.Cancelled, match="progress callback returned False during stage") as e:
        isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=0.5, progress=progress)
    assert isinstance(e.value, RuntimeError)
    assert seen[-1] != "read"
    # Nothing is left behind: the next run works and gives the full mesh.
    assert len(isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=0.5).triangles) > 0


def test_other_threads_run_while_meshing():
    """The GIL is released: a Python thread keeps counting during the call."""
    arr = egg_crate(32)
    counts, stop = [0], threading.Event()

    def count():
        while not stop.is_set():
            counts[0] += 1
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    try:
        t0 = time.monotonic()
        before = counts[0]
        isodel.mesh(arr, 0.1, eps_voxels=0.5)  # no progress callback: the thread must still run
        during, elapsed = counts[0] - before, time.monotonic() - t0
    finally:
        stop.set()
        t.join()
    assert elapsed > 0.2
    # Holding the GIL for the whole call would leave the thread at 0; it ticks up to 1000 times a second.
    assert during > max(10, 50 * elapsed), f"{during} counts in {elapsed:.2f}s"


def test_progress_must_be_callable():
    with pytest.raises(TypeError, match="progress: expected None or a callable"):
        isodel.mesh(blobs(), 0.45, progress=5)


def test_exception_in_progress_propagates(data):
    def progress(stage, fraction):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        isodel.mesh(data / "two_blobs.mrc", 0.5, eps_voxels=0.5, progress=progress)


def egg_crate(n=40):
    """Many small surfaces: a run of a few seconds, with progress all along."""
    z, y, x = np.meshgrid(*[np.arange(float(n))] * 3, indexing="ij")
    return (np.sin(x / 2.3) * np.sin(y / 2.9) * np.sin(z / 3.1)).astype(np.float32)


def test_ctrl_c_cancels():
    # Measured in the process's CPU time, not wall time: on a loaded machine (CI runs tests side
    # by side) the wall clock of both runs stretches unevenly, the work each does does not.
    arr = egg_crate()
    fired = []

    def progress(stage, fraction):
        # SIGINT from another thread, so it arrives while the calling thread waits; during the
        # refinement, most of a run (the parallel Delaunay insertion is one uninterrupted call).
        if stage == "closed_ball" and not fired:
            fired.append(time.process_time())
            threading.Timer(0.05, os.kill, (os.getpid(), signal.SIGINT)).start()

    with pytest.raises(KeyboardInterrupt):
        isodel.mesh(arr, 0.1, eps_voxels=0.5, progress=progress)
    stopped = time.process_time() - fired[0]
    # The same run uninterrupted does much more work than the cancelled one, and still works.
    t0 = time.process_time()
    m = isodel.mesh(arr, 0.1, eps_voxels=0.5)
    full = time.process_time() - t0
    assert len(m.triangles) > 1000
    assert stopped < 0.5 * full, f"stopped after {stopped:.2f} s of CPU, a full run takes {full:.2f} s"
