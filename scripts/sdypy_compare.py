"""Writes tests/data/uff/row6_noisy.uff with pyuff (an independent UFF
writer) and fits it with sdypy-EMA (an established open-source LSCF + LSFD,
https://pypi.org/project/sdypy-EMA/, version 0.31.0) for comparison with
`tirecontact identify --data tests/data/uff/row6_noisy.uff`.

The file is laid out as a roving-hammer test: accelerances (UFF 58, FRF,
acceleration over force, m/s^2 per N) of response node 1 +Z to reference
nodes 1, 2, 3 +Z, 0 to 1000 Hz every 1 Hz, of the six-mode model SIX below
(52.3 to 959.4 Hz; the same as tests/support/frf.rs), each value times
1 + 0.01 (n1 + i n2) with n1, n2 standard normal (seed 35).

sdypy-EMA: poles by its LSCF up to polynomial order 60 over 1 to 1000 Hz,
the stable poles closest to the six frequencies picked, residues by its
LSFD with lower and upper residual terms; the relative L2 error of its
reconstruction against the file's data over 1 to 1000 Hz, all pairs, is
printed (and stated in tests/identify/frf_fit.rs). Run once; the file is
committed, CI does not run this script.

    python3 -m venv /tmp/ema && /tmp/ema/bin/pip install sdypy-EMA pyuff numpy
    /tmp/ema/bin/python scripts/sdypy_compare.py
"""
import os

import numpy as np
import pyuff
from sdypy import EMA

SIX = [
    (52.3, 0.012, [0.9, 0.5, 0.2]),
    (131.7, 0.008, [0.6, -0.4, -0.8]),
    (247.1, 0.006, [0.5, -0.7, 0.6]),
    (433.9, 0.005, [0.7, 0.3, -0.5]),
    (687.2, 0.004, [0.4, -0.6, 0.3]),
    (959.4, 0.003, [0.5, 0.45, 0.35]),
]
PATH = "tests/data/uff/row6_noisy.uff"


def accelerance(i, j, f):
    w = 2 * np.pi * f
    h = np.zeros(f.size, complex)
    for fk, xi, s in SIX:
        wk = 2 * np.pi * fk
        h += s[i] * s[j] / (wk * wk - w * w + 2j * xi * wk * w)
    return -w * w * h


def main():
    rng = np.random.default_rng(35)
    f = np.arange(0.0, 1000.0 + 1e-9, 1.0)
    data = []
    for j in range(3):
        h = accelerance(0, j, f)
        h = h * (1 + 0.01 * (rng.standard_normal(f.size) + 1j * rng.standard_normal(f.size)))
        data.append(h)
    if os.path.exists(PATH):
        os.remove(PATH)
    sets = []
    for j, h in enumerate(data):
        sets.append(pyuff.prepare_58(
            binary=0, id1=f"A1{j + 1}", func_type=4, rsp_ent_name="BEAM", rsp_node=1,
            rsp_dir=3, ref_ent_name="BEAM", ref_node=1 + j, ref_dir=3,
            data=h, x=f, abscissa_spacing=1, abscissa_spec_data_type=18,
            ordinate_spec_data_type=12, orddenom_spec_data_type=13, ord_data_type=6,
            abscissa_axis_units_lab="Hz", ordinate_axis_units_lab="m/s^2",
            orddenom_axis_units_lab="N",
        ))
    pyuff.UFF(PATH).write_sets(sets, mode="add")

    # sdypy-EMA takes the band from 0 Hz (as the file holds it)
    frf = np.array(data)
    freq = f
    m = EMA.Model(frf, freq, lower=1, upper=1001, pol_order_high=60, frf_form="accelerance")
    m.get_poles(show_progress=False)
    m.select_closest_poles([s[0] for s in SIX])
    h, _ = m.get_constants(whose_poles="own", FRF_ind="all", f_lower=1, f_upper=1001)
    # its cut-off keeps the bins below `upper`: 0 to 999 Hz
    assert m.freq[1] == 1.0 and m.freq[-1] == 999.0, (m.freq[0], m.freq[-1])
    d = m.frf[:, 1:]
    err = np.linalg.norm(h[:, 1:] - d) / np.linalg.norm(d)
    fn = m.nat_freq
    xi = m.nat_xi
    for k in range(len(fn)):
        print(f"sdypy-EMA mode {k}: {fn[k]:.4f} Hz, xi {xi[k]:.6f} (true {SIX[k][0]} Hz, {SIX[k][1]})")
    print(f"sdypy-EMA LSCF+LSFD relative L2 error over 1-999 Hz, all pairs: {err:.5f}")


if __name__ == "__main__":
    main()
