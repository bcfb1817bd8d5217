//! Ring tyre -> modal model: sample the ring's radial impulse responses at
//! the contact points (method §5) and identify them by LSCE (method §6); and
//! scene -> [`PreparedModel`], what a simulation is built from, with the
//! identifications kept in a [`ModeCache`] the caller owns.

use crate::readers::measured;
use crate::scene::SceneError;
use crate::scene::{Scene, Tyre};
use std::path::{Path, PathBuf};
use tirecontact_core::base::modal::ModalModel;
use tirecontact_core::model::lsce::{
    Identification, IdentifyOptions, LsceError, LsceRun, Responses, identify,
};
use tirecontact_core::model::ring::RingParams;
use tirecontact_core::model::ring::sampled_row;
use web_time::Instant;

mod cache;
pub mod driving;
pub mod frequency;
mod prepared;
pub mod workbench;
pub use cache::ModeCache;
pub use prepared::{PreparedModel, PreparedModelRun, SceneSimulation, problem_of};

/// An identification of a ring tyre, with what produced it.
#[derive(Debug, Clone)]
pub struct RingIdentification {
    pub identification: Identification,
    /// The sampled responses LSCE saw (pairs `i <= j`).
    pub responses: Responses,
    /// Relative L2 error of `|G(ω)|` of the identified model against the
    /// full ring (all orders `0..=N`, analytic receptance) over the band, all
    /// pairs (-).
    pub ring_magnitude_error: f64,
    /// Wall time of sampling and identification (s).
    pub elapsed_s: f64,
}

/// Largest relative L2 error of `|G(ω)|` over the band, identified model
/// against the full ring, that an identification may have (-): above it the
/// modes found do not represent the ring (the shipped paper preset: 0.017).
pub const MAX_MAGNITUDE_ERROR: f64 = 0.3;

/// Samples the ring's responses at the points `x_m` and identifies them;
/// an identification whose model misses the ring is an error
/// ([`LsceError::PoorFit`]), not a silently wrong tyre.
pub fn identify_ring(
    ring: &RingParams,
    x_m: &[f64],
    opts: &IdentifyOptions,
) -> Result<RingIdentification, LsceError> {
    RingIdentifyRun::new(ring, x_m, opts)?.finish()
}

/// [`identify_ring`] a stage at a time, for a caller that must return
/// between stages (a page in the browser has one thread): the responses
/// sampled a row of pairs at a time (method §5), the stages of LSCE
/// ([`LsceRun`], method §6), then the check against the ring. The same
/// stages as [`identify_ring`] in its order: the same result to the bit.
#[derive(Debug)]
pub struct RingIdentifyRun {
    ring: RingParams,
    x_m: Vec<f64>,
    opts: IdentifyOptions,
    start: Instant,
    /// What is sampled, the rows sampled so far (their pairs and data
    /// move to LSCE once every row is in).
    sampling: ModalModel,
    rows_sampled: usize,
    pairs: Vec<(usize, usize)>,
    data: Vec<Vec<f64>>,
    lsce: Option<LsceRun>,
    identification: Option<Identification>,
    stages_done: usize,
}

impl RingIdentifyRun {
    /// Checks the ring, the options and the points (the input errors of
    /// [`identify_ring`]).
    pub fn new(ring: &RingParams, x_m: &[f64], opts: &IdentifyOptions) -> Result<Self, LsceError> {
        let start = Instant::now();
        if let Some(e) = ring
            .validate("ring")
            .first()
            .or(opts.validate("identification").first())
        {
            return Err(LsceError::Input(e.to_string()));
        }
        if x_m.is_empty() {
            return Err(LsceError::Input("no contact points".into()));
        }
        // the sampled responses hold only the modes below Nyquist: without any,
        // LSCE would see zeros ("every response is zero") and not say why
        let nyquist_hz = 0.5 * opts.sample_rate_hz;
        let lowest_hz = lowest_mode_hz(ring);
        if !lowest_hz.is_finite() || lowest_hz >= nyquist_hz {
            return Err(LsceError::Input(format!(
                "no mode of the ring below the Nyquist frequency {nyquist_hz} Hz (identification.sample_rate_hz / 2; lowest mode {lowest_hz:.3e} Hz): expected a ring with modes in identification.band_hz (check ring.radius_m, the stiffnesses and mass_per_length_kg_m) or a higher sample_rate_hz"
            )));
        }
        let p = x_m.len();
        Ok(RingIdentifyRun {
            ring: ring.clone(),
            x_m: x_m.to_vec(),
            opts: opts.clone(),
            start,
            sampling: ring.sampling_model(x_m, opts.dt_s()),
            rows_sampled: 0,
            pairs: Vec::with_capacity(p * (p + 1) / 2),
            data: Vec::with_capacity(p * (p + 1) / 2),
            lsce: None,
            identification: None,
            stages_done: 0,
        })
    }

    /// Stages of the whole identification: a row of pairs per point, the
    /// stages of LSCE, the check.
    pub fn num_stages(&self) -> usize {
        let p = self.x_m.len();
        p + LsceRun::stages_for(p * (p + 1) / 2, &self.opts) + 1
    }

    /// Stages done so far.
    pub fn stages_done(&self) -> usize {
        self.stages_done
    }

    /// What the next stage does, for a progress line.
    pub fn next_stage(&self) -> &'static str {
        if self.identification.is_some() {
            "checking the modes against the ring"
        } else if self.lsce.is_some() {
            "LSCE: the stabilisation diagram, an order at a time"
        } else {
            "sampling the ring's responses"
        }
    }

    /// Runs every stage left.
    pub fn finish(mut self) -> Result<RingIdentification, LsceError> {
        loop {
            if let Some(id) = self.stage()? {
                return Ok(id);
            }
        }
    }

    /// Runs the next stage; the identification once the last one ran.
    pub fn stage(&mut self) -> Result<Option<RingIdentification>, LsceError> {
        self.stages_done += 1;
        let (opts, p) = (&self.opts, self.x_m.len());
        // (counted apart from the pairs, which LSCE takes)
        let row = self.rows_sampled;
        if row < p {
            let (pairs, data) = sampled_row(&self.sampling, row, opts.dt_s(), opts.num_samples());
            self.pairs.extend(pairs);
            self.data.extend(data);
            self.rows_sampled += 1;
            return Ok(None);
        }
        if self.identification.is_none() {
            let lsce = match &mut self.lsce {
                Some(l) => l,
                None => {
                    let responses = Responses {
                        dt_s: opts.dt_s(),
                        num_points: p,
                        pairs: std::mem::take(&mut self.pairs),
                        data: std::mem::take(&mut self.data),
                    };
                    self.lsce.insert(LsceRun::new(responses, opts)?)
                }
            };
            if let Some(id) = lsce.stage()? {
                self.identification = Some(id);
            }
            return Ok(None);
        }
        let (Some(identification), Some(lsce)) = (self.identification.take(), self.lsce.take())
        else {
            unreachable!("the check runs after LSCE");
        };
        let ring_magnitude_error = magnitude_error(
            &self.ring.modal_model(&self.x_m),
            &ModalModel::from_modes(&identification.modes, p),
            opts.band_hz,
            200,
        );
        if ring_magnitude_error.is_nan() || ring_magnitude_error > MAX_MAGNITUDE_ERROR {
            return Err(LsceError::PoorFit {
                magnitude_error: ring_magnitude_error,
                limit: MAX_MAGNITUDE_ERROR,
                lo_hz: opts.band_hz.0,
                hi_hz: opts.band_hz.1,
                lowest_source_hz: lowest_mode_hz(&self.ring),
            });
        }
        Ok(Some(RingIdentification {
            identification,
            responses: lsce.into_responses(),
            ring_magnitude_error,
            elapsed_s: self.start.elapsed().as_secs_f64(),
        }))
    }
}

/// The ring's lowest mode of nonzero frequency (Hz; infinite if none).
fn lowest_mode_hz(ring: &RingParams) -> f64 {
    ring.all_modes()
        .iter()
        .filter(|m| m.omega_rad_s > 0.0)
        .map(|m| m.freq_hz())
        .fold(f64::INFINITY, f64::min)
}

/// An identification of measured (or externally computed) responses.
#[derive(Debug, Clone)]
pub struct MeasuredIdentification {
    pub identification: Identification,
    /// The responses LSCE saw (pairs `i <= j`), cut to the options'
    /// duration.
    pub responses: Responses,
    /// What reading the file did (format, reciprocity, conversions).
    pub notes: Vec<String>,
    /// Wall time of reading and identification (s).
    pub elapsed_s: f64,
}

/// Why a tyre could not be identified: its data file (which names
/// itself), or the identification.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IdentifyError {
    /// The data file cannot be read (it names itself).
    #[error(transparent)]
    Data(#[from] measured::DataError),
    #[error(transparent)]
    Lsce(#[from] LsceError),
}

/// Reads the responses of `num_points` points in `path` (see
/// [`crate::readers::measured`]) and identifies them with `opts` at the data's own
/// sampling, over its first `opts.duration_s` seconds. A model whose
/// `|G|` misses the data's by more than [`MAX_MAGNITUDE_ERROR`] over the
/// band is an error ([`LsceError::PoorFit`]).
pub fn identify_measured(
    path: &Path,
    nodes: Option<&[i64]>,
    num_points: usize,
    opts: &IdentifyOptions,
) -> Result<MeasuredIdentification, IdentifyError> {
    let start = Instant::now();
    let data = measured::read(path, nodes, num_points)?;
    let mut responses = data.responses;
    let dt = responses.dt_s;
    let keep = ((opts.duration_s / dt).round() as usize).max(1);
    for g in &mut responses.data {
        g.truncate(keep);
    }
    let mut opts = opts.clone();
    opts.sample_rate_hz = 1.0 / dt;
    opts.duration_s = responses.data.first().map_or(0, Vec::len) as f64 * dt;
    if opts.band_hz.1 >= 0.5 * opts.sample_rate_hz {
        return Err(LsceError::Input(format!(
            "{}: tyre.identification.band_hz = ({}, {}): expected the band below the data's Nyquist frequency {} Hz (sampled every {dt:e} s)",
            path.display(),
            opts.band_hz.0,
            opts.band_hz.1,
            0.5 * opts.sample_rate_hz
        ))
        .into());
    }
    let identification = identify(&responses, &opts)?;
    let e = identification.report.magnitude_error;
    if e.is_nan() || e > MAX_MAGNITUDE_ERROR {
        return Err(LsceError::PoorFit {
            magnitude_error: e,
            limit: MAX_MAGNITUDE_ERROR,
            lo_hz: opts.band_hz.0,
            hi_hz: opts.band_hz.1,
            // a file's modes are not known: an identified pole is no hint
            lowest_source_hz: f64::NAN,
        }
        .into());
    }
    Ok(MeasuredIdentification {
        identification,
        responses,
        notes: data.notes,
        elapsed_s: start.elapsed().as_secs_f64(),
    })
}

/// An identification of a scene's ring or measured tyre, whatever its kind.
#[derive(Debug, Clone)]
pub struct TyreIdentification {
    pub identification: Identification,
    /// The responses LSCE saw (pairs `i <= j`).
    pub responses: Responses,
    /// The identification band (Hz).
    pub band_hz: (f64, f64),
    /// What the source adds for the user (the ring's |G| error against the
    /// full ring; a file's format, reciprocity, conversions).
    pub notes: Vec<String>,
    /// Wall time of sampling or reading, and identification (s).
    pub elapsed_s: f64,
}

/// Identifies `scene`'s tyre: a ring sampled at the points
/// ([`identify_ring`]), measured responses read ([`identify_measured`]);
/// `None` for a modal tyre (nothing to identify).
pub fn identify_tyre(scene: &Scene) -> Option<Result<TyreIdentification, IdentifyError>> {
    match &scene.tyre {
        Tyre::Modal { .. } | Tyre::Plate { .. } | Tyre::FeModes { .. } => None,
        Tyre::Ring {
            ring,
            identification,
        } => Some(
            identify_ring(ring, &positions(scene), identification)
                .map(|id| TyreIdentification {
                    notes: vec![format!("|G| vs full ring {:.3e}", id.ring_magnitude_error)],
                    identification: id.identification,
                    responses: id.responses,
                    band_hz: identification.band_hz,
                    elapsed_s: id.elapsed_s,
                })
                .map_err(IdentifyError::from),
        ),
        Tyre::Measured {
            file,
            identification,
            nodes,
        } => Some(
            identify_measured(
                &data_path(scene, file),
                (!nodes.is_empty()).then_some(nodes.as_slice()),
                scene.num_points(),
                identification,
            )
            .map(|id| TyreIdentification {
                notes: id.notes,
                identification: id.identification,
                responses: id.responses,
                band_hz: identification.band_hz,
                elapsed_s: id.elapsed_s,
            }),
        ),
    }
}

/// A measured tyre's data file, relative to the scene's folder.
pub fn data_path(scene: &Scene, file: &Path) -> PathBuf {
    match &scene.base_dir {
        Some(d) if file.is_relative() => d.join(file),
        _ => file.to_path_buf(),
    }
}

/// Relative L2 error of `|G_ij(ω)|` of `model` against `reference` over
/// `n` frequencies spread over the band, all pairs `i <= j` (-).
pub fn magnitude_error(
    reference: &ModalModel,
    model: &ModalModel,
    band_hz: (f64, f64),
    n: usize,
) -> f64 {
    let p = reference.num_points.min(model.num_points);
    let (mut num, mut den) = (0.0, 0.0);
    for q in 0..n {
        let f = band_hz.0 + (band_hz.1 - band_hz.0) * (q as f64 + 0.5) / n as f64;
        for i in 0..p {
            for j in i..p {
                let a = reference.frequency_response(i, j, f).norm();
                let b = model.frequency_response(i, j, f).norm();
                num += (a - b) * (a - b);
                den += a * a;
            }
        }
    }
    if den > 0.0 { (num / den).sqrt() } else { 0.0 }
}

/// The modal model of a scene's FE tyre (`Tyre::FeModes`, method §5.4):
/// its file read and sampled at the points; `None` for other tyres is an
/// error naming the tyre.
pub fn fe_model(scene: &Scene) -> Result<crate::readers::fe_modes::FeModel, SceneError> {
    let Some(spec) = scene.tyre.fe_spec(scene.base_dir.as_deref()) else {
        return Err(SceneError::Identification {
            scene: scene.name.clone(),
            message: "not an FE tyre (tyre: FeModes(...))".into(),
        });
    };
    let fail = |source| SceneError::FeModes {
        scene: scene.name.clone(),
        source,
    };
    let fe = crate::readers::fe_modes::load(&spec, &points_xy(scene)).map_err(fail)?;
    // rigid contact: the contact system is a sum of one rank-one term per
    // mode, singular with more points than modes
    if scene.contact.is_rigid() && scene.num_points() > fe.modes.len() {
        return Err(fail(crate::readers::fe_modes::FeModesError::RigidTooFew {
            points: scene.num_points(),
            modes: fe.modes.len(),
        }));
    }
    Ok(fe)
}

/// The points' positions `(x_m, y_m)` (m).
fn points_xy(scene: &Scene) -> Vec<(f64, f64)> {
    scene.points.iter().map(|p| (p.x_m, p.y_m)).collect()
}

/// The points' positions along the tyre (m).
fn positions(scene: &Scene) -> Vec<f64> {
    scene.points.iter().map(|p| p.x_m).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring identified a stage at a time takes the stages it announces,
    /// each row of responses sampled once (LSCE takes the sampled pairs:
    /// counting the rows from them sampled every row again).
    #[test]
    fn a_ring_run_takes_the_stages_it_announces() {
        // (the paper's ring and identification, three of its points)
        let (ring, opts) = (RingParams::default(), IdentifyOptions::default());
        let x_m = [-0.025, 0.0, 0.025];
        let mut run = RingIdentifyRun::new(&ring, &x_m, &opts).unwrap();
        let announced = run.num_stages();
        let mut calls = 0;
        let staged = loop {
            calls += 1;
            assert!(
                calls <= announced,
                "more stages than the {announced} announced"
            );
            if let Some(id) = run.stage().unwrap() {
                break id;
            }
        };
        assert_eq!((calls, run.stages_done()), (announced, announced));
        // every pair once, in row order
        let pairs = &staged.responses.pairs;
        assert_eq!(pairs.len(), 6);
        assert!(pairs.windows(2).all(|w| w[0] < w[1]), "{pairs:?}");
        assert!(!staged.identification.modes.is_empty());
    }
}
