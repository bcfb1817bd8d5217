"""tirecontact: dynamic tyre/road contact by fast modal convolution.

Load a scene, change a field, run, and get numpy arrays (SI units; names
carry their unit)::

    import tirecontact as tc
    scene = tc.Scene.load("presets/paper.ron")
    scene.set("speed_mps", 15.0)
    run = tc.run(scene)
    run.q_n          # contact forces (N), time x points
    run.to_pandas()  # the columns of `tirecontact run -o`

Errors raise ``TirecontactError`` (a ``ValueError``) with the project's
messages: the field, the value and what was expected (file:line:column for
files).
"""

from ._tirecontact import (
    ModalModel,
    Run,
    Scene,
    Study,
    TirecontactError,
    identify,
    run_row,
    spectrum,
    study_rows,
    third_octave,
)
from ._tirecontact import run_scene as run

__all__ = [
    "ModalModel",
    "Run",
    "Scene",
    "Study",
    "TirecontactError",
    "identify",
    "run",
    "run_row",
    "spectrum",
    "study_rows",
    "third_octave",
]
