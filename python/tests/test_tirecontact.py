"""The Python package against the command line and closed forms."""

import csv
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import tirecontact as tc

REPO = Path(__file__).resolve().parents[2]
PRESETS = REPO / "presets"


def cli():
    """The command-line binary: $TIRECONTACT_BIN, else the repository's build."""
    env = os.environ.get("TIRECONTACT_BIN")
    if env:
        return env
    for p in ("target/release/tirecontact", "target/debug/tirecontact"):
        if (REPO / p).exists():
            return str(REPO / p)
    pytest.skip("no tirecontact binary: build it or set TIRECONTACT_BIN")


def test_arrays_equal_the_cli_csv_of_the_same_scene(tmp_path):
    scene = tc.Scene.load(PRESETS / "three_points.ron")
    scene.set("speed_mps", 13.0)
    path = tmp_path / "scene.ron"
    path.write_text(scene.to_ron())
    for every in (1, 7):
        out = tmp_path / f"run{every}.csv"
        subprocess.run(
            [cli(), "run", str(path), "--duration", "0.03", "--every", str(every), "-o", str(out)],
            check=True,
            capture_output=True,
        )
        with open(out) as f:
            rows = list(csv.reader(f))
        header, data = rows[0], np.array(rows[1:], dtype=float)
        run = tc.run(scene, duration_s=0.03, every=every)
        df = run.to_pandas()
        assert list(df.columns) == header
        p = scene.num_points
        assert run.q_n.shape == (len(data), p)
        # the CSV keeps ten significant digits
        for k, name in enumerate(header):
            want = data[:, k]
            got = df[name].to_numpy(dtype=float)
            np.testing.assert_allclose(got, want, rtol=1e-9, atol=1e-300, err_msg=name)
        # impacts and releases happen: the comparison covers both states
        assert run.contact.any() and not run.contact.all()


def test_the_arrays_are_handed_over_without_a_copy():
    run = tc.run(tc.Scene.load(PRESETS / "single_mode.ron"), duration_s=0.01)
    # a view of the vector the solver filled, not a copy of it
    assert not run.u_m.flags["OWNDATA"] and run.u_m.base is not None
    assert run.u_m.flags["C_CONTIGUOUS"]


def test_run_stats_are_the_forces_without_impacts_and_the_impulses():
    scene = tc.Scene.load(PRESETS / "three_points.ron")
    runs = [tc.run(scene, dt_s=dt, duration_s=0.2) for dt in (1e-5, 5e-6)]
    for run in runs:
        st = run.stats
        # every step's mean force includes the impacts; the steps' contact
        # states give the contact fraction
        assert np.all(np.array(st["force_max_n"]) <= run.q_n.max(axis=0) * (1 + 1e-12))
        np.testing.assert_allclose(st["contact_fraction"], run.contact[1:].mean(axis=0), rtol=1e-12)
        assert st["steps"] == len(run.t_s) - 1
    a, b = (r.stats for r in runs)
    assert min(a["force_max_n"]) > 0 and min(a["impulse_max_ns"]) > 0, a
    # impacts happen, and the figures do not depend on the time step, unlike
    # the largest step-mean force (impulse / dt), which doubles
    assert sum(a["impacts_per_s"]) > 0
    np.testing.assert_allclose(a["force_max_n"], b["force_max_n"], rtol=1e-2)
    np.testing.assert_allclose(a["impulse_max_ns"], b["impulse_max_ns"], rtol=1e-2)
    peak = [r.q_n.max() for r in runs]
    assert peak[1] > 1.8 * peak[0], peak


def test_get_set_and_errors_carry_the_project_messages(tmp_path):
    scene = tc.Scene.load(PRESETS / "three_points.ron")
    scene.set("tyre.modes[0].damping_ratio", 0.07)
    assert scene.get("tyre.modes[0].damping_ratio") == 0.07
    scene.set("points[*].h_m", -0.002)
    assert scene.get("points[2].h_m") == -0.002
    with pytest.raises(tc.TirecontactError, match=r"speed_kmh.*speed_mps"):
        scene.set("speed_kmh", 50.0)
    with pytest.raises(tc.TirecontactError, match=r"dt_s.*-1"):
        scene.set("dt_s", -1.0)
    bad = tmp_path / "bad.ron"
    text = (PRESETS / "single_mode.ron").read_text().replace("damping_ratio: 0.", "damping_ratio: -0.")
    bad.write_text(text)
    line = next(i for i, l in enumerate(text.splitlines(), 1) if "damping_ratio: -0." in l)
    with pytest.raises(tc.TirecontactError, match=rf"bad.ron:{line}:\d+.*damping_ratio"):
        tc.Scene.load(bad)
    with pytest.raises(tc.TirecontactError, match=r"<text>:1:\d+"):
        tc.Scene.from_ron("Scene(name: 1)")
    study = tmp_path / "study.ron"
    study.write_text(
        'Study(\n    preset: "%s",\n    factors: [\n        Factor(path: "speed_kmh", values: List([1.0])),\n    ],\n    design: FullFactorial,\n)'
        % (PRESETS / "single_mode.ron")
    )
    with pytest.raises(tc.TirecontactError, match=r"study.ron:4:\d+: factors\[0\].path"):
        tc.Study.load(study)
    assert issubclass(tc.TirecontactError, ValueError)


def test_every_parameter_has_a_label_and_the_units_are_the_field_table_s():
    scene = tc.Scene.load(PRESETS / "three_points.ron")
    for path in scene.param_paths():
        label = tc.Scene.param_label(path)
        assert label and "_" not in label.split(" (")[0] or "shape" in path or "residue" in path, path
    assert tc.Scene.param_label("speed_mps") == "speed V (m/s)"
    assert tc.Scene.param_label("tyre.modes[1].freq_hz") == "mode 1 frequency (Hz)"
    assert tc.Scene.param_unit("contact.stiffness_n_m[0]") == "N/m"
    assert tc.Scene.param_unit("points.along") is None


def test_a_modal_tyre_model_is_its_modes_in_closed_form():
    scene = tc.Scene.load(PRESETS / "single_mode.ron")
    m = tc.identify(scene)
    assert m.report is None
    f, xi = m.freq_hz[0], m.damping_ratio[0]
    a = m.residues[0]
    w = 2 * np.pi * f
    wd = w * np.sqrt(1 - xi**2)
    t = np.linspace(0.0, 0.05, 11)
    g = m.green(t)[:, 0, 0]
    np.testing.assert_allclose(g, a[0, 0] * np.exp(-xi * w * t) * np.sin(wd * t) / wd, rtol=1e-12, atol=1e-15)
    freq = np.array([0.0, f, 3 * f])
    h = m.frf(freq)[:, 0, 0]
    om = 2 * np.pi * freq
    np.testing.assert_allclose(h, a[0, 0] / (w**2 - om**2 + 2j * xi * w * om), rtol=1e-12)


def test_a_ring_is_identified_with_its_report():
    m = tc.identify(tc.Scene.load(PRESETS / "paper.ron"))
    assert m.report is not None and m.report["magnitude_error"] < 0.05
    assert ((m.freq_hz > 0) & (m.freq_hz <= 500.0)).all()
    assert m.residues.shape == (len(m.freq_hz), 5, 5)
    # reciprocity: every residue matrix is symmetric
    np.testing.assert_allclose(m.residues, m.residues.transpose(0, 2, 1), rtol=0, atol=1e-9 * abs(m.residues).max())


def test_bands_match_the_cli_band_table(tmp_path):
    scene = tc.Scene.load(PRESETS / "three_points.ron")
    run = tc.run(scene)
    bands = tc.third_octave(run)
    subprocess.run(
        [cli(), "run", str(PRESETS / "three_points.ron"), "--spectrum", str(tmp_path / "s.csv")],
        check=True,
        capture_output=True,
    )
    with open(tmp_path / "s_bands.csv") as f:
        rows = list(csv.DictReader(f))
    cli_db = {float(r["band_hz"]): float(r["q_total_db_re_1N"]) for r in rows}
    checked = 0
    for f, level in zip(bands["nominal_hz"], bands["level_db"]):
        if f in cli_db and np.isfinite(level):
            # (the table's six decimals)
            assert abs(level - cli_db[f]) < 2e-6, f
            checked += 1
    assert checked >= 10


def _timed_duration_s(scene, wall_s):
    """A run duration (s of simulated time) that takes about `wall_s` here."""
    tc.run(scene, duration_s=0.01)  # the ring identified once, not timed
    t = time.perf_counter()
    tc.run(scene, duration_s=0.2, every=1000)
    per_sim_s = (time.perf_counter() - t) / 0.2
    return min(200.0, max(0.2, wall_s / max(per_sim_s, 1e-6)))


def test_a_run_releases_the_gil():
    # While a worker thread is inside `run`, the main thread keeps running
    # Python. Were the GIL held, the main thread would stand still for the
    # whole run: its longest pause would be the run's length.
    scene = tc.Scene.load(PRESETS / "paper.ron")
    duration = _timed_duration_s(scene, 0.4)
    span = {}

    def worker():
        span["start"] = time.perf_counter()
        tc.run(scene, duration_s=duration, every=1000)
        span["end"] = time.perf_counter()

    th = threading.Thread(target=worker)
    gaps = []  # the main thread's pauses of over 1 ms: (from, to)
    # (timed from before the start: the worker may take the GIL at once)
    last = time.perf_counter()
    th.start()
    while th.is_alive():
        now = time.perf_counter()
        if now - last > 1e-3:
            gaps.append((last, now))
        last = now
    gaps.append((last, time.perf_counter()))
    th.join()
    start, end = span["start"], span["end"]
    # the longest pause within the run
    longest = max([min(b, end) - max(a, start) for a, b in gaps] + [0.0])
    assert end - start > 0.1, f"the run took {end - start:.3f} s"
    assert longest < 0.5 * (end - start), (
        f"the main thread stood still for {longest:.3f} s of a {end - start:.3f} s run"
    )


def test_two_threads_run_two_scenes_at_once():
    # Two runs on two threads use two cores at once: the process's CPU time
    # is well above its wall time (with the GIL held it could not exceed it).
    cpus = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (os.cpu_count() or 1)
    quota = Path("/sys/fs/cgroup/cpu.max")
    if quota.exists():
        limit, period = (quota.read_text().split() + ["100000"])[:2]
        if limit != "max":
            cpus = min(cpus, int(limit) // int(period))
    if cpus < 2:
        pytest.skip("fewer than two CPUs for this process")
    scene = tc.Scene.load(PRESETS / "paper.ron")
    duration = _timed_duration_s(scene, 0.5)

    def one():
        tc.run(scene, duration_s=duration, every=1000)

    t = time.perf_counter()
    one()
    single = time.perf_counter() - t
    # a busy machine can take a core away for a while: three tries
    tries = []
    for _ in range(3):
        threads = [threading.Thread(target=one) for _ in range(2)]
        t, c = time.perf_counter(), time.process_time()
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        wall, cpu = time.perf_counter() - t, time.process_time() - c
        tries.append((wall, cpu))
        if cpu > 1.3 * wall:
            break
    print(f"one run {single:.3f} s; two on two threads (wall s, CPU s): {tries}")
    assert cpu > 1.3 * wall, f"two threads, (wall s, CPU s) of each try: {tries}"


def test_the_dask_example_writes_the_cli_table(tmp_path):
    pytest.importorskip("dask.distributed")
    out = tmp_path / "dask.csv"
    subprocess.run(
        [sys.executable, str(REPO / "examples" / "dask_study.py"), str(REPO / "examples" / "study.ron"), str(out), "--workers", "2"],
        check=True,
        capture_output=True,
        timeout=600,
    )
    ref = tmp_path / "cli.csv"
    subprocess.run([cli(), "study", "run", str(REPO / "examples" / "study.ron"), "-o", str(ref)], check=True, capture_output=True)
    assert out.read_bytes() == ref.read_bytes()


def test_study_rows_and_run_row_make_the_table(tmp_path):
    study = tc.Study.load(REPO / "examples" / "study.ron")
    rows = tc.study_rows(study)
    assert len(rows) == len(study) == 10
    records = [tc.run_row(study, r) for r, _, _ in reversed(rows)]
    out = tmp_path / "t.csv"
    study.write_table(out, records)
    ref = tmp_path / "cli.csv"
    subprocess.run([cli(), "study", "run", str(REPO / "examples" / "study.ron"), "-o", str(ref)], check=True, capture_output=True)
    assert out.read_bytes() == ref.read_bytes()
    with pytest.raises(tc.TirecontactError, match="row_id = 10"):
        tc.run_row(study, 10)


def test_ctrl_c_stops_a_long_run():
    code = (
        # (Python leaves Ctrl+C ignored in a process started with it ignored,
        # as a shell's background job is: the handler is put back)
        "import signal; signal.signal(signal.SIGINT, signal.default_int_handler)\n"
        "import tirecontact as tc, sys\n"
        f"s = tc.Scene.load({str(PRESETS / 'paper.ron')!r})\n"
        "tc.run(s, duration_s=0.01)\n"
        "print('ready', flush=True)\n"
        "try:\n"
        "    tc.run(s, duration_s=500.0, every=1000000)\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n"
        "    sys.exit(3)\n"
    )
    proc = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True)
    assert proc.stdout.readline().strip() == "ready"
    time.sleep(0.5)
    t = time.perf_counter()
    proc.send_signal(signal.SIGINT)
    out, _ = proc.communicate(timeout=60)
    # 500 s of the paper preset take about 20 s: stopped long before
    assert proc.returncode == 3 and "interrupted" in out, (proc.returncode, out)
    assert time.perf_counter() - t < 2.0


def test_a_patch_run_carries_the_points_coordinates():
    scene = tc.Scene.load(PRESETS / "patch_wheel_path.ron")
    run = tc.run(scene, duration_s=0.002)
    # the grid's order: along the rolling direction within each row across
    assert run.x_m.shape == run.y_m.shape == (run.q_n.shape[1],) == (96,)
    np.testing.assert_allclose(np.unique(run.y_m), [-0.05, -0.03, -0.01, 0.01, 0.03, 0.05], atol=1e-15)
    assert np.all(np.diff(run.x_m[:16]) > 0) and np.all(run.y_m[:16] == run.y_m[0])
    assert run.y_m[16] > run.y_m[0]
