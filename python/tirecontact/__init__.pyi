"""Type stubs of tirecontact (units in the names: _s seconds, _m metres,
_mps metres per second, _n newtons, _hz hertz)."""

from os import PathLike
from typing import Any, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

_Path = Union[str, PathLike[str]]

class TirecontactError(ValueError):
    """A refused scene, study or run: the field, the value, what was expected."""

class Scene:
    @staticmethod
    def load(path: _Path) -> Scene:
        """Reads and validates a scene preset (RON)."""
    @staticmethod
    def from_ron(text: str) -> Scene:
        """Parses and validates a scene from RON text."""
    def to_ron(self) -> str: ...
    def get(self, path: str) -> float:
        """A numeric field by path, e.g. "speed_mps", "tyre.modes[0].damping_ratio"."""
    def set(self, path: str, value: float) -> None:
        """Sets a numeric field by path; "points[*].h_m" sets every point."""
    def validate(self) -> None: ...
    def param_paths(self) -> list[str]: ...
    @staticmethod
    def param_label(path: str) -> str:
        """The field as the visualiser names it, with its unit: "speed V (m/s)"."""
    @staticmethod
    def param_unit(path: str) -> Optional[str]:
        """The field's SI unit; None for a count or an unknown path."""
    @property
    def name(self) -> str: ...
    @property
    def num_points(self) -> int: ...

class Run:
    """A run's history, time x points: a row at t = 0, then every `every` steps."""
    t_s: npt.NDArray[np.float64]
    """Times (s), shape (T,)."""
    u_m: npt.NDArray[np.float64]
    """Displacements (m, up), shape (T, P)."""
    v_mps: npt.NDArray[np.float64]
    """Velocities (m/s), shape (T, P)."""
    q_n: npt.NDArray[np.float64]
    """Contact forces (N), the mean over the row's steps, shape (T, P)."""
    gap_m: npt.NDArray[np.float64]
    """Gaps u - r (m), shape (T, P)."""
    contact: npt.NDArray[np.bool_]
    """In contact at the row's time, shape (T, P)."""
    dt_s: float
    every: int
    ramp_s: float
    @property
    def stats(self) -> dict[str, Any]:
        """steps, events, worst_penetration_m (m), wall_s (s), and per point:
        force_max_n and force_rms_n (N, the contact force without impacts),
        impacts_per_s (1/s), impulse_mean_ns and impulse_max_ns (N·s),
        window_force_max_n (N, the largest 1 ms mean force, impacts
        included), contact_fraction (-)."""
    def to_pandas(self) -> Any:
        """A DataFrame with the columns of `tirecontact run -o`."""

def run(
    scene: Scene,
    dt_s: Optional[float] = None,
    duration_s: Optional[float] = None,
    every: int = 1,
) -> Run:
    """Runs the scene to its end (GIL released; Ctrl-C stops it)."""

class ModalModel:
    @property
    def freq_hz(self) -> npt.NDArray[np.float64]: ...
    @property
    def damping_ratio(self) -> npt.NDArray[np.float64]: ...
    @property
    def residues(self) -> npt.NDArray[np.float64]:
        """Residue matrices A_k (1/kg), shape (K, P, P)."""
    @property
    def report(self) -> Optional[dict[str, Any]]:
        """The identification's fit report; None for a modal tyre."""
    def green(self, t_s: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """g_ij(t) (m/(N s)), shape (T, P, P)."""
    def frf(self, freq_hz: npt.ArrayLike) -> npt.NDArray[np.complex128]:
        """G_ij(f) (m/N), shape (F, P, P)."""

def identify(scene: Scene) -> ModalModel:
    """The scene's modes, identified by LSCE for a ring or measured tyre."""

def spectrum(run: Run, start_s: Optional[float] = None) -> dict[str, npt.NDArray[np.float64]]:
    """freq_hz, amplitude_n, psd_n2_per_hz of the total force's steady part."""

def third_octave(
    run: Run,
    start_s: Optional[float] = None,
    lo_hz: float = 20.0,
    hi_hz: float = 5000.0,
) -> dict[str, npt.NDArray[np.float64]]:
    """nominal_hz, level_db (dB re 1 N) of the total force's steady part."""

class Study:
    @staticmethod
    def load(path: _Path) -> Study: ...
    @property
    def header(self) -> list[str]: ...
    def __len__(self) -> int: ...
    def write_table(self, path: _Path, records: Sequence[Sequence[str]]) -> None:
        """Writes records as the study's table, byte for byte as `study merge`."""

def study_rows(study: Study) -> list[tuple[int, list[float], int]]:
    """(row_id, factor values, replicate) of every row."""

def run_row(study: Study, row_id: int) -> list[str]:
    """Runs one row; its table record (the error, if any, in the last field)."""
