"""Writes the measured-tyre example and the UFF fixtures with pyuff, an
independent UFF writer (https://pypi.org/project/pyuff/), from modal models
whose modes are stated here. Run once; the files are committed, CI does not
run this script.

    python3 -m venv /tmp/uff && /tmp/uff/bin/pip install pyuff numpy
    /tmp/uff/bin/python scripts/measured_example.py

Writes:
- presets/measured_example.uff: receptances (UFF 58, FRF, displacement over
  force) of the five-point model MODEL5 from 0 to 1000 Hz every 2 Hz, the
  upper triangle of pairs only, with 1 % complex Gaussian noise (seed 2026)
  relative to each FRF's RMS magnitude;
- tests/data/uff/frf3.uff: receptances of MODEL3, noise-free, every pair,
  0 to 1000 Hz every 1 Hz;
- tests/data/uff/accel3.uff: accelerances of MODEL3 (acceleration over
  force, the lower triangle of pairs);
- tests/data/uff/time3.uff: impulse responses of MODEL3 (time responses,
  displacement over force impulse), 2000 Hz for 0.5 s, the upper triangle.
"""
import numpy as np
import pyuff

# (frequency Hz, damping ratio, mode shape) per mode: residues A = phi phi^T
MODEL5 = [
    (48.0, 0.04, [1.0, 0.9, 0.8, 0.9, 1.0]),
    (96.0, 0.03, [0.9, 0.4, 0.0, -0.4, -0.9]),
    (163.0, 0.03, [0.7, -0.3, -0.8, -0.3, 0.7]),
    (251.0, 0.025, [0.5, -0.6, 0.0, 0.6, -0.5]),
    (372.0, 0.02, [0.4, -0.7, 0.6, -0.7, 0.4]),
]
MODEL3 = [
    (52.0, 0.03, [1.0, 0.6, 0.2]),
    (131.0, 0.02, [0.5, -0.4, -0.9]),
    (247.0, 0.04, [0.3, -0.8, 0.7]),
]


def receptance(model, i, j, f):
    """G_ij(f) = sum A_ij / (w^2 - W^2 + 2 i xi w W), W = 2 pi f (m/N)."""
    big = 2 * np.pi * f
    g = np.zeros_like(big, dtype=complex)
    for fk, xi, phi in model:
        w = 2 * np.pi * fk
        g += phi[i] * phi[j] / (w * w - big * big + 2j * xi * w * big)
    return g


def impulse(model, i, j, t):
    """g_ij(t) = sum A_ij exp(-xi w t) sin(wd t) / wd (m/(N s))."""
    g = np.zeros_like(t)
    for fk, xi, phi in model:
        w = 2 * np.pi * fk
        wd = w * np.sqrt(1 - xi * xi)
        g += phi[i] * phi[j] * np.exp(-xi * w * t) * np.sin(wd * t) / wd
    return g


def frf_set(i, j, f, data, spec=8):
    return pyuff.prepare_58(
        binary=0, id1=f"G{i}{j}", func_type=4, rsp_ent_name="TYRE", rsp_node=101 + i,
        rsp_dir=3, ref_ent_name="TYRE", ref_node=101 + j, ref_dir=3,
        data=data, x=f, abscissa_spacing=1, abscissa_spec_data_type=18,
        ordinate_spec_data_type=spec, orddenom_spec_data_type=13, ord_data_type=6,
    )


def write(path, sets):
    import os
    if os.path.exists(path):
        os.remove(path)
    pyuff.UFF(path).write_sets(sets, mode="add")


def main():
    rng = np.random.default_rng(2026)
    f = np.arange(0.0, 1000.0 + 1e-9, 2.0)
    sets = []
    for i in range(5):
        for j in range(i, 5):
            h = receptance(MODEL5, i, j, f)
            rms = np.sqrt(np.mean(np.abs(h) ** 2))
            noise = 0.01 * rms * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size)) / np.sqrt(2)
            sets.append(frf_set(i, j, f, h + noise))
    write("presets/measured_example.uff", sets)

    f3 = np.arange(0.0, 1000.0 + 1e-9, 1.0)
    write("tests/data/uff/frf3.uff", [frf_set(i, j, f3, receptance(MODEL3, i, j, f3)) for i in range(3) for j in range(3)])
    acc = []
    for i in range(3):
        for j in range(i + 1):
            big = 2 * np.pi * f3
            acc.append(frf_set(i, j, f3, -big * big * receptance(MODEL3, i, j, f3), spec=12))
    write("tests/data/uff/accel3.uff", acc)
    t = np.arange(0, 1000) / 2000.0
    times = []
    for i in range(3):
        for j in range(i, 3):
            times.append(pyuff.prepare_58(
                binary=0, id1=f"g{i}{j}", func_type=1, rsp_ent_name="TYRE", rsp_node=101 + i,
                rsp_dir=3, ref_ent_name="TYRE", ref_node=101 + j, ref_dir=3,
                data=impulse(MODEL3, i, j, t), x=t, abscissa_spacing=1, abscissa_spec_data_type=17,
                ordinate_spec_data_type=8, orddenom_spec_data_type=13, ord_data_type=4,
            ))
    write("tests/data/uff/time3.uff", times)


if __name__ == "__main__":
    main()
