//! Python bindings of tirecontact: scenes, runs as numpy arrays, modal
//! models, spectra and the study engine's rows. Long work releases the GIL
//! (threads run in parallel) and checks for Ctrl-C between chunks of steps.

use numpy::{
    Complex64, IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1,
};
use pyo3::create_exception;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::PathBuf;
use std::sync::LazyLock;
use std::sync::atomic::AtomicBool;
use tirecontact_core::solver::drive::{Watch, run};
use tirecontact_report::analysis::metrics::{ContactMetrics, ContactSummary};
use tirecontact_core::base::modal::ModalModel as Model;
use tirecontact_report::output::arrays::RunArrays;
use tirecontact_report::analysis::spectrum::Window;
use tirecontact_report::studies::study::{Loaded, Row};
use tirecontact_core::SolverOptions;
use tirecontact_io::{ModeCache, PreparedModel};

create_exception!(
    _tirecontact,
    TirecontactError,
    pyo3::exceptions::PyValueError,
    "A scene, study or run refused by tirecontact: the message names the field, the value and what was expected (file:line:column for files)."
);

fn err(e: impl std::fmt::Display) -> PyErr {
    TirecontactError::new_err(e.to_string())
}

/// Ring and measured tyres identified once per process and geometry.
static CACHE: LazyLock<ModeCache> = LazyLock::new(ModeCache::new);

/// Steps run between two checks for Ctrl-C (the GIL released meanwhile).
const CHUNK_STEPS: u64 = 50_000;

/// A scene: tyre, contact points, road, speed, time step (SI units).
#[pyclass(name = "Scene", module = "tirecontact")]
#[derive(Clone)]
struct PyScene {
    inner: tirecontact_io::Scene,
}

#[pymethods]
impl PyScene {
    /// Reads and validates a scene preset (RON); relative road and data
    /// files are found from its folder.
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Ok(PyScene {
            inner: tirecontact_io::Scene::load(&path).map_err(err)?,
        })
    }

    /// Parses and validates a scene from RON text.
    #[staticmethod]
    fn from_ron(text: &str) -> PyResult<Self> {
        Ok(PyScene {
            inner: tirecontact_io::Scene::parse(text, "<text>").map_err(err)?,
        })
    }

    /// The scene as RON text (what `Scene.from_ron` reads back).
    fn to_ron(&self) -> String {
        self.inner.to_ron_string()
    }

    /// A numeric field by its path, in the field's unit: `"speed_mps"`,
    /// `"tyre.modes[0].damping_ratio"`, `"points[1].h_m"`.
    fn get(&self, path: &str) -> PyResult<f64> {
        tirecontact_report::studies::sweep::get_param(&self.inner, path).map_err(err)
    }

    /// Sets a numeric field by its path (`"points[*].h_m"` sets every
    /// point); refused values raise `TirecontactError` naming the field.
    fn set(&mut self, path: &str, value: f64) -> PyResult<()> {
        tirecontact_report::studies::sweep::set_param(&mut self.inner, path, value).map_err(err)
    }

    /// Raises `TirecontactError` listing every invalid field.
    fn validate(&self) -> PyResult<()> {
        self.inner.validate().map_err(|errors| {
            err(errors
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join("; "))
        })
    }

    /// Every numeric field's path.
    fn param_paths(&self) -> Vec<String> {
        tirecontact_report::studies::sweep::param_paths(&self.inner)
    }

    /// The field at `path` as the visualiser names it, with its unit:
    /// "speed V (m/s)", "mode 0 frequency (Hz)" (the path for a field
    /// without a name).
    #[staticmethod]
    fn param_label(path: &str) -> String {
        tirecontact_io::scene::fields::axis_label(path)
    }

    /// The SI unit of the field at `path` (`None`: a count, or no such
    /// field).
    #[staticmethod]
    fn param_unit(path: &str) -> Option<&'static str> {
        tirecontact_io::scene::fields::unit(path)
    }

    #[getter]
    fn name(&self) -> String {
        self.inner.name.clone()
    }

    /// Number of contact points.
    #[getter]
    fn num_points(&self) -> usize {
        self.inner.num_points()
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({:?}, {} points, dt_s={:e}, duration_s={})",
            self.inner.name,
            self.inner.num_points(),
            self.inner.dt_s,
            self.inner.duration_s
        )
    }
}

/// A run's history: one row at t = 0, then one every `every` steps; arrays
/// are time × points. `q_n` is the mean force over the row's steps (an
/// impact is kept as impulse / dt). `x_m`, `y_m` are the points'
/// positions along and across the tread (m), the columns' order.
#[pyclass(name = "Run", module = "tirecontact")]
struct PyRun {
    #[pyo3(get)]
    t_s: Py<PyArray1<f64>>,
    #[pyo3(get)]
    u_m: Py<PyArray2<f64>>,
    #[pyo3(get)]
    v_mps: Py<PyArray2<f64>>,
    #[pyo3(get)]
    q_n: Py<PyArray2<f64>>,
    #[pyo3(get)]
    gap_m: Py<PyArray2<f64>>,
    #[pyo3(get)]
    contact: Py<PyArray2<bool>>,
    #[pyo3(get)]
    x_m: Py<PyArray1<f64>>,
    #[pyo3(get)]
    y_m: Py<PyArray1<f64>>,
    #[pyo3(get)]
    dt_s: f64,
    #[pyo3(get)]
    every: u64,
    #[pyo3(get)]
    ramp_s: f64,
    num_points: usize,
    stats: tirecontact_core::solver::simulation::RunStats,
    forces: ContactSummary,
    wall_s: f64,
}

#[pymethods]
impl PyRun {
    /// Steps, located events, worst penetration (m), wall time of the run
    /// (s), and per point over the whole run: the largest and RMS contact
    /// force without impacts (N), impacts per second (1/s), the mean and
    /// largest impulse (N·s), the largest 1 ms mean force (N) and the
    /// contact fraction (the figures of `tirecontact run`'s summary, which
    /// converge as dt → 0; the impact count more slowly, see cli.md).
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let f = &self.forces;
        d.set_item("steps", self.stats.steps)?;
        d.set_item("events", self.stats.events)?;
        d.set_item("worst_penetration_m", self.stats.worst_penetration_m)?;
        d.set_item("wall_s", self.wall_s)?;
        d.set_item("force_max_n", f.force_max_n.clone())?;
        d.set_item("force_rms_n", f.force_rms_n.clone())?;
        d.set_item("impacts_per_s", f.impacts_per_s.clone())?;
        d.set_item("impulse_mean_ns", f.impulse_mean_ns.clone())?;
        d.set_item("impulse_max_ns", f.impulse_max_ns.clone())?;
        d.set_item("window_force_max_n", f.window_force_max_n.clone())?;
        d.set_item("contact_fraction", f.contact_fraction.clone())?;
        Ok(d)
    }

    /// A pandas DataFrame with the columns of `tirecontact run -o`'s CSV:
    /// `t_s`, `u{i}_m`, `v{i}_mps`, `q{i}_N`, `gap{i}_m`, `contact{i}`.
    fn to_pandas<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let pd = py.import("pandas")?;
        let cols = tirecontact_report::output::csv::header(self.num_points);
        let data = PyDict::new(py);
        data.set_item(&cols[0], self.t_s.bind(py))?;
        let p = self.num_points;
        let blocks: [(&Bound<'py, PyAny>, usize); 5] = [
            (self.u_m.bind(py).as_any(), 1),
            (self.v_mps.bind(py).as_any(), 1 + p),
            (self.q_n.bind(py).as_any(), 1 + 2 * p),
            (self.gap_m.bind(py).as_any(), 1 + 3 * p),
            (self.contact.bind(py).as_any(), 1 + 4 * p),
        ];
        for (array, first) in blocks {
            for i in 0..p {
                let column = array.get_item((pyo3::types::PySlice::full(py), i))?;
                data.set_item(&cols[first + i], column)?;
            }
        }
        pd.call_method1("DataFrame", (data,))
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "Run({} rows, {} points, dt_s={:e}, every={})",
            numpy::PyUntypedArrayMethods::len(self.t_s.bind(py)),
            self.num_points,
            self.dt_s,
            self.every
        )
    }
}

fn array2<'py>(py: Python<'py>, v: Vec<f64>, p: usize) -> PyResult<Py<PyArray2<f64>>> {
    let rows = v.len() / p.max(1);
    Ok(v.into_pyarray(py).reshape([rows, p])?.unbind())
}

/// Runs `scene` to its end (`dt_s`, `duration_s` override the scene's) and
/// returns its history, a row every `every` steps. The GIL is released
/// while stepping; Ctrl-C stops the run with `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scene, dt_s=None, duration_s=None, every=1))]
fn run_scene(
    py: Python<'_>,
    scene: &PyScene,
    dt_s: Option<f64>,
    duration_s: Option<f64>,
    every: u64,
) -> PyResult<PyRun> {
    if every == 0 {
        return Err(err("every = 0: expected a row every 1 or more steps"));
    }
    let mut s = scene.inner.clone();
    if let Some(dt) = dt_s {
        s.dt_s = dt;
    }
    if let Some(d) = duration_s {
        s.duration_s = d;
    }
    let start = std::time::Instant::now();
    let model = py.detach(|| PreparedModel::new(&s, &CACHE)).map_err(err)?;
    let mut sim = model.simulation(SolverOptions::default()).map_err(err)?;
    let p = s.num_points();
    let total = s.num_steps();
    let mut arrays = RunArrays::new(p, total, every);
    // the forces without impacts and the impulses, over the whole run
    let mut metrics = ContactMetrics::new(&s, Some(0.0));
    tirecontact_core::solver::drive::Probe::start(&mut arrays, &sim).map_err(err)?;
    while sim.steps() < total {
        let n = (total - sim.steps()).min(CHUNK_STEPS);
        py.detach(|| run(&mut sim, n, &mut (&mut arrays, &mut metrics), Watch::none()))
            .map_err(err)?;
        py.check_signals()?;
    }
    let wall_s = start.elapsed().as_secs_f64();
    let RunArrays {
        t_s,
        u_m,
        v_mps,
        q_n,
        gap_m,
        contact,
        ..
    } = arrays;
    let contact_rows = contact.len() / p.max(1);
    Ok(PyRun {
        t_s: t_s.into_pyarray(py).unbind(),
        u_m: array2(py, u_m, p)?,
        v_mps: array2(py, v_mps, p)?,
        q_n: array2(py, q_n, p)?,
        gap_m: array2(py, gap_m, p)?,
        contact: contact
            .into_pyarray(py)
            .reshape([contact_rows, p])?
            .unbind(),
        x_m: s
            .points
            .iter()
            .map(|pt| pt.x_m)
            .collect::<Vec<f64>>()
            .into_pyarray(py)
            .unbind(),
        y_m: s
            .points
            .iter()
            .map(|pt| pt.y_m)
            .collect::<Vec<f64>>()
            .into_pyarray(py)
            .unbind(),
        dt_s: s.dt_s,
        every,
        ramp_s: s.ramp_s,
        num_points: p,
        stats: sim.stats().clone(),
        forces: metrics.summary(),
        wall_s,
    })
}

/// A modal model: `K` modes of `P` points.
#[pyclass(name = "ModalModel", module = "tirecontact")]
struct PyModalModel {
    model: Model,
    modes: Vec<tirecontact_core::base::modal::Mode>,
    report: Option<Py<PyDict>>,
}

#[pymethods]
impl PyModalModel {
    /// Natural frequencies f_k (Hz), shape (K,).
    #[getter]
    fn freq_hz<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.modes
            .iter()
            .map(|m| m.freq_hz)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// Damping ratios ξ_k (-), shape (K,).
    #[getter]
    fn damping_ratio<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.modes
            .iter()
            .map(|m| m.damping_ratio)
            .collect::<Vec<_>>()
            .into_pyarray(py)
    }

    /// Residue matrices A_k (1/kg), shape (K, P, P): row i receives, column
    /// j is loaded.
    #[getter]
    fn residues<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let p = self.model.num_points;
        let v: Vec<f64> = self
            .model
            .modes
            .iter()
            .flat_map(|m| m.residue.iter().copied())
            .collect();
        v.into_pyarray(py).reshape([self.model.modes.len(), p, p])
    }

    /// The identification's fit report (a ring or measured tyre), or None
    /// for a modal tyre.
    #[getter]
    fn report(&self, py: Python<'_>) -> Option<Py<PyDict>> {
        self.report.as_ref().map(|r| r.clone_ref(py))
    }

    /// Green functions g_ij(t) (m/(N·s)) at the times `t_s`, shape (T, P, P).
    fn green<'py>(
        &self,
        py: Python<'py>,
        t_s: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray3<f64>>> {
        let p = self.model.num_points;
        let t = t_s.as_slice()?;
        let mut v = Vec::with_capacity(t.len() * p * p);
        for &ti in t {
            for i in 0..p {
                for j in 0..p {
                    v.push(self.model.green(i, j, ti).0);
                }
            }
        }
        v.into_pyarray(py).reshape([t.len(), p, p])
    }

    /// Frequency responses G_ij (m/N, complex) at `freq_hz`, shape (F, P, P).
    fn frf<'py>(
        &self,
        py: Python<'py>,
        freq_hz: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray3<Complex64>>> {
        let p = self.model.num_points;
        let f = freq_hz.as_slice()?;
        let mut v = Vec::with_capacity(f.len() * p * p);
        for &fi in f {
            for i in 0..p {
                for j in 0..p {
                    let g = self.model.frequency_response(i, j, fi);
                    v.push(Complex64::new(g.re, g.im));
                }
            }
        }
        v.into_pyarray(py).reshape([f.len(), p, p])
    }

    fn __repr__(&self) -> String {
        format!(
            "ModalModel({} modes, {} points, {:.1} … {:.1} Hz)",
            self.modes.len(),
            self.model.num_points,
            self.modes.first().map_or(0.0, |m| m.freq_hz),
            self.modes.last().map_or(0.0, |m| m.freq_hz)
        )
    }
}

/// The scene's modal model: its modes (a modal tyre), or those identified
/// by LSCE from a ring's or a measured tyre's responses, with the fit
/// report. The GIL is released while identifying.
#[pyfunction]
fn identify(py: Python<'_>, scene: &PyScene) -> PyResult<PyModalModel> {
    let s = scene.inner.clone();
    let p = s.num_points();
    match py.detach(|| tirecontact_io::identify::identify_tyre(&s)) {
        None => {
            let modes = CACHE.modes(&s).map_err(err)?.to_vec();
            Ok(PyModalModel {
                model: Model::from_modes(&modes, p),
                modes,
                report: None,
            })
        }
        Some(r) => {
            let id = r.map_err(err)?;
            let fit = &id.identification.report;
            let d = PyDict::new(py);
            d.set_item("time_error", fit.time_error)?;
            d.set_item("magnitude_error", fit.magnitude_error)?;
            d.set_item("model_order", id.identification.model_order)?;
            d.set_item("band_hz", id.band_hz)?;
            d.set_item("notes", id.notes.clone())?;
            d.set_item("elapsed_s", id.elapsed_s)?;
            let modes = id.identification.modes;
            Ok(PyModalModel {
                model: Model::from_modes(&modes, p),
                modes,
                report: Some(d.unbind()),
            })
        }
    }
}

/// The total contact force's steady part (from `start_s`, default the
/// ramp time) of a run recorded every step, and its sample rate.
fn steady_total(run: &PyRun, py: Python<'_>, start_s: Option<f64>) -> PyResult<(Vec<f64>, f64)> {
    if run.every != 1 {
        return Err(err(format!(
            "run every = {}: expected a run recorded every step (every=1) for a spectrum",
            run.every
        )));
    }
    let t = run.t_s.bind(py).readonly();
    let q = run.q_n.bind(py).readonly();
    let (t, q) = (t.as_slice()?, q.as_slice()?);
    let start = start_s.unwrap_or(run.ramp_s).max(0.0);
    let p = run.num_points;
    // row k > 0 is the step ending at t[k]: steady when it starts at or
    // after `start` (row 0 is the state at t = 0, no step)
    let total: Vec<f64> = (1..t.len())
        .filter(|&k| t[k] - run.dt_s >= start - 1e-9 * run.dt_s)
        .map(|k| q[k * p..(k + 1) * p].iter().sum())
        .collect();
    Ok((total, 1.0 / run.dt_s))
}

/// Spectrum of the total contact force over the steady part (Hann window,
/// mean removed): a dict of `freq_hz`, `amplitude_n` and `psd_n2_per_hz`.
#[pyfunction]
#[pyo3(signature = (run, start_s=None))]
fn spectrum<'py>(
    py: Python<'py>,
    run: &PyRun,
    start_s: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let (x, fs) = steady_total(run, py, start_s)?;
    let s = tirecontact_report::analysis::spectrum::spectrum(&x, fs, Window::Hann, true).map_err(err)?;
    let d = PyDict::new(py);
    d.set_item("freq_hz", s.freq_hz.into_pyarray(py))?;
    d.set_item("amplitude_n", s.amplitude.into_pyarray(py))?;
    d.set_item("psd_n2_per_hz", s.psd.into_pyarray(py))?;
    Ok(d)
}

/// Third-octave band levels of the total contact force (dB re 1 N) over
/// the steady part, as `run --spectrum`'s band table: a dict of
/// `nominal_hz`, `level_db` (bands 20 Hz - 5 kHz below Nyquist by default).
#[pyfunction]
#[pyo3(signature = (run, start_s=None, lo_hz=20.0, hi_hz=5000.0))]
fn third_octave<'py>(
    py: Python<'py>,
    run: &PyRun,
    start_s: Option<f64>,
    lo_hz: f64,
    hi_hz: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let (x, fs) = steady_total(run, py, start_s)?;
    let s = tirecontact_report::analysis::spectrum::spectrum(&x, fs, Window::Hann, true).map_err(err)?;
    let hi = hi_hz.min(0.5 * fs / 10f64.powf(0.05));
    let bands = s.third_octave_levels(lo_hz, hi, 1.0);
    let d = PyDict::new(py);
    d.set_item(
        "nominal_hz",
        bands
            .iter()
            .map(|b| b.band.nominal_hz)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    d.set_item(
        "level_db",
        bands
            .iter()
            .map(|b| b.level_db)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    Ok(d)
}

/// A study file loaded: its rows, and the table's header and hash.
#[pyclass(name = "Study", module = "tirecontact", frozen)]
struct PyStudy {
    loaded: Loaded,
}

#[pymethods]
impl PyStudy {
    /// Reads and checks a study file (errors name file:line:column).
    #[staticmethod]
    fn load(path: PathBuf) -> PyResult<Self> {
        Ok(PyStudy {
            loaded: tirecontact_report::studies::study::load(&path).map_err(err)?,
        })
    }

    /// The columns of the study's table (as `study run` writes them).
    #[getter]
    fn header(&self) -> Vec<String> {
        tirecontact_report::studies::study::header(&self.loaded)
    }

    /// Number of rows.
    fn __len__(&self) -> usize {
        self.loaded.rows.len()
    }

    /// Writes `records` (lists of fields, as `run_row` returns them) as the
    /// study's table, sorted by row, byte for byte as `study merge` would.
    fn write_table(&self, path: PathBuf, records: Vec<Vec<String>>) -> PyResult<()> {
        use tirecontact_report::studies::study::table;
        let rows = table::rows_by_id(records).map_err(err)?;
        table::write_table(&path, &self.header(), &rows).map_err(err)
    }
}

/// The study's rows: a list of `(row_id, factor_values, replicate)`.
#[pyfunction]
fn study_rows(study: &PyStudy) -> Vec<(usize, Vec<f64>, usize)> {
    study
        .loaded
        .rows
        .iter()
        .map(|r| (r.id, r.values.clone(), r.replicate))
        .collect()
}

/// Runs one row of the study and returns its table record (a list of
/// fields, as a line of `study run`'s CSV); a failing row's error is in its
/// last field. Any executor can run rows; the GIL is released meanwhile.
#[pyfunction]
fn run_row(py: Python<'_>, study: &PyStudy, row_id: usize) -> PyResult<Vec<String>> {
    let loaded = &study.loaded;
    let row: &Row = loaded.rows.get(row_id).ok_or_else(|| {
        err(format!(
            "row_id = {row_id}: expected 0 to {} (the study has {} rows)",
            loaded.rows.len().saturating_sub(1),
            loaded.rows.len()
        ))
    })?;
    let cancel = AtomicBool::new(false);
    let r = py.detach(|| tirecontact_report::studies::study::run_row(loaded, row, &CACHE, &cancel));
    Ok(tirecontact_report::studies::study::record(loaded, row, &r))
}

#[pymodule]
fn _tirecontact(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("TirecontactError", m.py().get_type::<TirecontactError>())?;
    m.add_class::<PyScene>()?;
    m.add_class::<PyRun>()?;
    m.add_class::<PyModalModel>()?;
    m.add_class::<PyStudy>()?;
    m.add_function(wrap_pyfunction!(run_scene, m)?)?;
    m.add_function(wrap_pyfunction!(identify, m)?)?;
    m.add_function(wrap_pyfunction!(spectrum, m)?)?;
    m.add_function(wrap_pyfunction!(third_octave, m)?)?;
    m.add_function(wrap_pyfunction!(study_rows, m)?)?;
    m.add_function(wrap_pyfunction!(run_row, m)?)?;
    Ok(())
}
