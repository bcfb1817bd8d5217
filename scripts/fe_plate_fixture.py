"""Writes the FE exports of a plate with known modes, tests/data/fe/*.uff
and presets/fe_plate.uff,
with pyuff (an independent UFF writer, https://pypi.org/project/pyuff/,
version 2.5.8): the tensioned orthotropic plate on an elastic foundation
of docs/method.md §5.3, its modes in closed form (computed here, not by
the crate), sampled on a node grid of 7 × 5 nodes (x from -30 to 30 mm
every 10 mm, y from -60 to 60 mm every 30 mm, z = 0), the modes up to
400 Hz (41 modes). Mode number 1000 n + 2 m + s: n half-waves across,
order m along, s = 1 for the sin(k x) mode of a pair.

- presets/fe_plate.uff (also the preset fe_plate.ron's): dataset 164 (user units: mm, N, tonne: length
  factor 1000, force 1), nodes in 2411 (mm), modes in 2414 (normal mode,
  data at nodes, 3 translations, double precision), mass-normalised in
  that unit system: 1/sqrt(t), so values sqrt(1000) times the SI ones;
  modal mass 1.
- plate_55_mm.uff: dataset 164 (code 5, mm and mN: masses in kg), nodes in
  15 (mm), modes in 55 (normal mode, 3 translations), not normalised:
  unit amplitude, the record's modal mass M_nm (kg).
- plate_55_m.uff: dataset 164 (SI), nodes in 15 (m), modes in 55 with six
  values per node (rotations 0), mass-normalised (1/sqrt(kg)), modal
  mass 1.

Run once; the files are committed, CI does not run this script.

    pip install pyuff numpy
    python3 scripts/fe_plate_fixture.py
"""
import os

import numpy as np
import pyuff

# the plate (SI): presets' defaults, modes up to 400 Hz
W, L, MPA = 0.16, 1.9, 10.0
BX, BY, TX, TY, S = 5.0, 1.0, 6.6e4, 1.0e4, 2.0e6
F_MAX_HZ = 400.0
XS = np.arange(-3, 4) * 0.01
YS = np.arange(-2, 3) * 0.03


def omega(n, m):
    k, q = 2 * np.pi * m / L, n * np.pi / W
    bxy = np.sqrt(BX * BY)
    return np.sqrt((BX * k**4 + 2 * bxy * k * k * q * q + BY * q**4 + TX * k * k + TY * q * q + S) / MPA)


def modal_mass(m):
    return MPA * 0.5 * W * (1.0 if m == 0 else 0.5) * L


def modes():
    out = []
    for n in range(1, 20):
        for m in range(0, 200):
            w = omega(n, m)
            if w > 2 * np.pi * F_MAX_HZ:
                break
            out.append((n, m, 0, w))
            if m > 0:
                out.append((n, m, 1, w))
    out.sort(key=lambda t: t[3])
    return out


def raw_shape(n, m, s, x, y):
    across = np.sin(n * np.pi / W * (y + W / 2))
    kx = 2 * np.pi * m / L * x
    return across * (np.sin(kx) if s else np.cos(kx))


def grid():
    nodes, x, y = [], [], []
    for j, yy in enumerate(YS):
        for i, xx in enumerate(XS):
            nodes.append(101 + 10 * j + i)
            x.append(xx)
            y.append(yy)
    return np.array(nodes), np.array(x), np.array(y)


def units(code, desc, length, force):
    return pyuff.prepare_164(units_code=code, units_description=desc, temp_mode=2,
                             length=length, force=force, temp=1.0, temp_offset=273.15)


def write(path, sets):
    if os.path.exists(path):
        os.remove(path)
    pyuff.UFF(path).write_sets(sets, mode="add")


def main():
    nodes, x, y = grid()
    zeros = np.zeros(nodes.size)
    ms = modes()
    print(len(ms), "modes,", ms[0][3] / 2 / np.pi, "to", ms[-1][3] / 2 / np.pi, "Hz")

    # 2414, mm-N-t: mass-normalised in 1/sqrt(t)
    sets = [units(9, "mm N t", 1000.0, 1.0),
            pyuff.prepare_2411(node_nums=nodes, def_cs=np.zeros(nodes.size, int),
                               disp_cs=np.zeros(nodes.size, int), color=np.zeros(nodes.size, int),
                               x=x * 1e3, y=y * 1e3, z=zeros)]
    for (n, m, s, w) in ms:
        phi = raw_shape(n, m, s, x, y) / np.sqrt(modal_mass(m)) * np.sqrt(1000.0)
        sets.append({
            "type": 2414, "analysis_dataset_label": 1000 * n + 2 * m + s,
            "analysis_dataset_name": f"plate mode n={n} m={m} {'sin' if s else 'cos'}",
            "dataset_location": 1, "id1": "plate", "id2": "normal mode", "id3": "NONE",
            "id4": "NONE", "id5": "NONE", "model_type": 1, "analysis_type": 2,
            "data_characteristic": 2, "result_type": 8, "data_type": 4,
            "number_of_data_values_for_the_data_component": 3,
            "record10_field6": 1000 * n + 2 * m + s,
            "record12_field2": w / 2 / np.pi, "record12_field3": w * w, "record12_field4": 1.0,
            "node_nums": nodes,
            "data_at_node": np.stack([zeros, zeros, phi], axis=1),
        })
    write("presets/fe_plate.uff", sets)

    # 55, mm-mN-kg: unit amplitude, modal mass M_nm (kg)
    sets = [units(5, "mm mN kg", 1000.0, 1000.0),
            pyuff.prepare_15(node_nums=nodes, x=x * 1e3, y=y * 1e3, z=zeros)]
    for (n, m, s, w) in ms:
        sets.append(pyuff.prepare_55(
            id1="plate", model_type=1, analysis_type=2, data_ch=2, spec_data_type=8,
            load_case=1, mode_n=1000 * n + 2 * m + s, freq=w / 2 / np.pi,
            modal_m=modal_mass(m), modal_damp_vis=0.0, modal_damp_his=0.0,
            node_nums=nodes, r1=zeros, r2=zeros, r3=raw_shape(n, m, s, x, y)))
    write("tests/data/fe/plate_55_mm.uff", sets)

    # 55, SI, six values per node: mass-normalised
    sets = [units(1, "SI", 1.0, 1.0),
            pyuff.prepare_15(node_nums=nodes, x=x, y=y, z=zeros)]
    for (n, m, s, w) in ms:
        sets.append(pyuff.prepare_55(
            id1="plate", model_type=1, analysis_type=2, data_ch=3, spec_data_type=8,
            load_case=1, mode_n=1000 * n + 2 * m + s, freq=w / 2 / np.pi,
            modal_m=1.0, modal_damp_vis=0.02, modal_damp_his=0.0,
            node_nums=nodes, r1=zeros, r2=zeros,
            r3=raw_shape(n, m, s, x, y) / np.sqrt(modal_mass(m)),
            r4=zeros, r5=zeros, r6=zeros))
    write("tests/data/fe/plate_55_m.uff", sets)


if __name__ == "__main__":
    main()
