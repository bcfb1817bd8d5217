//! Ring tyre -> modal model: sample the ring's radial impulse responses at
//! the contact points (method §5) and identify them by LSCE (method §6), with a
//! process-wide cache so that a scene is identified once per distinct ring,
//! options and point positions.

use crate::lsce::{Identification, IdentifyOptions, LsceError, Responses, identify};
use crate::modal::ModalModel;
use crate::modal::Mode;
use crate::ring::RingParams;
use std::sync::{Arc, Mutex};
use std::time::Instant;

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
    let lowest_hz = ring
        .all_modes()
        .iter()
        .filter(|m| m.omega_rad_s > 0.0)
        .map(|m| m.freq_hz())
        .fold(f64::INFINITY, f64::min);
    if !lowest_hz.is_finite() || lowest_hz >= nyquist_hz {
        return Err(LsceError::Input(format!(
            "no mode of the ring below the Nyquist frequency {nyquist_hz} Hz (identification.sample_rate_hz / 2; lowest mode {lowest_hz:.3e} Hz): expected a ring with modes in identification.band_hz (check ring.radius_m, the stiffnesses and mass_per_length_kg_m) or a higher sample_rate_hz"
        )));
    }
    let dt = opts.dt_s();
    let (pairs, data) = ring.sampled_responses(x_m, dt, opts.num_samples());
    let responses = Responses {
        dt_s: dt,
        num_points: x_m.len(),
        pairs,
        data,
    };
    let identification = identify(&responses, opts)?;
    let ring_magnitude_error = magnitude_error(
        &ring.modal_model(x_m),
        &ModalModel::from_modes(&identification.modes, x_m.len()),
        opts.band_hz,
        200,
    );
    if ring_magnitude_error.is_nan() || ring_magnitude_error > MAX_MAGNITUDE_ERROR {
        return Err(LsceError::PoorFit {
            magnitude_error: ring_magnitude_error,
            limit: MAX_MAGNITUDE_ERROR,
            lo_hz: opts.band_hz.0,
            hi_hz: opts.band_hz.1,
            lowest_source_hz: ring
                .all_modes()
                .iter()
                .filter(|m| m.omega_rad_s > 0.0)
                .map(|m| m.freq_hz())
                .fold(f64::INFINITY, f64::min),
        });
    }
    Ok(RingIdentification {
        identification,
        responses,
        ring_magnitude_error,
        elapsed_s: start.elapsed().as_secs_f64(),
    })
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

type CacheEntry = (String, Arc<Vec<Mode>>);
static CACHE: Mutex<Vec<CacheEntry>> = Mutex::new(Vec::new());
const CACHE_LEN: usize = 8;

/// The cache key of a ring, its identification options and the points.
fn cache_key(ring: &RingParams, x_m: &[f64], opts: &IdentifyOptions) -> String {
    format!("{ring:?}|{opts:?}|{x_m:?}")
}

/// Whether [`ring_modes_cached`] would answer from its cache (no
/// identification to run).
pub fn ring_modes_are_cached(ring: &RingParams, x_m: &[f64], opts: &IdentifyOptions) -> bool {
    let key = cache_key(ring, x_m, opts);
    let cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    cache.iter().any(|(k, _)| *k == key)
}

/// The identified modes of a ring at the points `x_m`, from the cache when
/// the ring, the options and the positions are unchanged (keyed on their
/// exact values; the 8 most recent are kept).
pub fn ring_modes_cached(
    ring: &RingParams,
    x_m: &[f64],
    opts: &IdentifyOptions,
) -> Result<Arc<Vec<Mode>>, LsceError> {
    let key = cache_key(ring, x_m, opts);
    {
        let cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
        if let Some((_, modes)) = cache.iter().find(|(k, _)| *k == key) {
            return Ok(Arc::clone(modes));
        }
    }
    let modes = Arc::new(identify_ring(ring, x_m, opts)?.identification.modes);
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if cache.len() >= CACHE_LEN {
        cache.remove(0);
    }
    cache.push((key, Arc::clone(&modes)));
    Ok(modes)
}
