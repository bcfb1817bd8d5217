"""Writes tests/data/uff/row3_58b.uff with pyuff (an independent UFF
writer, https://pypi.org/project/pyuff/, version 2.5.8): dataset 164 (SI
units), then one FRF row of MODEL3 (scripts/measured_example.py) as binary
dataset 58b — response node 101 +Z, reference nodes 101, 102, 103 +Z,
accelerance in g/N (units labels `g` and `N`), 0 to 500 Hz every 2 Hz,
noise-free — and the coherence of the driving point (function type 6,
0.99). pyuff writes 8-byte values in the host's byte order (little endian
here) and the ID line's byte count of the values, not their components.
Run once; the file is committed, CI does not run this script.

    pip install pyuff numpy
    python3 scripts/uff_binary_fixture.py
"""
import os

import numpy as np
import pyuff

from measured_example import MODEL3, receptance

G0 = 9.80665


def main():
    path = "tests/data/uff/row3_58b.uff"
    if os.path.exists(path):
        os.remove(path)
    f = np.arange(0.0, 500.0 + 1e-9, 2.0)
    w = 2 * np.pi * f
    sets = [pyuff.prepare_164(units_code=1, units_description="SI", temp_mode=2,
                              length=1.0, force=1.0, temp=1.0, temp_offset=273.15)]
    for j in range(3):
        acc = -w * w * receptance(MODEL3, 0, j, f) / G0
        sets.append(pyuff.prepare_58(
            binary=1, id1=f"A1{j + 1}", func_type=4, rsp_ent_name="TYRE", rsp_node=101,
            rsp_dir=3, ref_ent_name="TYRE", ref_node=101 + j, ref_dir=3,
            data=acc, x=f, abscissa_spacing=1, abscissa_spec_data_type=18,
            ordinate_spec_data_type=12, orddenom_spec_data_type=13, ord_data_type=6,
            abscissa_axis_units_lab="Hz", ordinate_axis_units_lab="g",
            orddenom_axis_units_lab="N",
        ))
    sets.append(pyuff.prepare_58(
        binary=1, id1="coherence 11", func_type=6, rsp_ent_name="TYRE", rsp_node=101,
        rsp_dir=3, ref_ent_name="TYRE", ref_node=101, ref_dir=3,
        data=np.full(f.size, 0.99), x=f, abscissa_spacing=1, abscissa_spec_data_type=18,
        ordinate_spec_data_type=0, orddenom_spec_data_type=0, ord_data_type=4,
    ))
    pyuff.UFF(path).write_sets(sets, mode="add")


if __name__ == "__main__":
    main()
