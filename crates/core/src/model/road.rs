//! Road profiles `z(x)` and the smooth ramp of preload and road (method §4).
//!
//! Road seen by point `i` at time `t` (the tyre rolls at speed `V`):
//!
//! ```text
//! r_i(t) = w(t) * ( z(x_i + V t) - h_i ),   w(t) = 3 s^2 - 2 s^3,  s = clamp(t / T_ramp, 0, 1)
//! ```

mod points;
pub mod random;
pub mod surface;
pub mod texture;

use crate::base::error::FieldError;
pub use points::{PointsRoad, STEPPER_ANCHOR_EVERY};
pub use random::RoadClass;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;
use std::path::PathBuf;
use std::sync::Arc;
pub use surface::SurfaceGrid;

/// One sinusoidal component `a sin(2π x / λ + φ)` of a multi-harmonic road.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Harmonic {
    /// Amplitude `a` (m).
    pub amplitude_m: f64,
    /// Wavelength `λ` (m), > 0.
    pub wavelength_m: f64,
    /// Phase `φ` (rad); default 0.
    #[serde(default)]
    pub phase_rad: f64,
}

/// A road profile as written in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Road {
    /// `z(x) = a sin(2π x / λ)` (method §4).
    Sine {
        /// Amplitude `a` (m), >= 0.
        amplitude_m: f64,
        /// Wavelength `λ` (m), > 0.
        wavelength_m: f64,
    },
    /// Sum of harmonics `Σ a_k sin(2π x / λ_k + φ_k)`.
    Harmonics { components: Vec<Harmonic> },
    /// A measured profile: CSV of `x_m, z_m` rows (header optional), linearly
    /// interpolated. Sampling past its ends is an error unless `looped`, in
    /// which case the profile repeats with period `x_last - x_first`.
    Measured {
        /// Path of the CSV, relative to the scene file's folder.
        file: PathBuf,
        /// Repeat the profile past its ends.
        #[serde(default)]
        looped: bool,
    },
    /// A random road of an ISO 8608 class (see [`random`]): displacement PSD
    /// `Gd(n) = 16e-6 · 4^k (n / 0.1)^-2` m³ (`k = 0` for A … 7 for H) over
    /// `[min_wavenumber_cpm, max_wavenumber_cpm]`, a sum of cosines with
    /// seeded random phases, periodic with period `length_m`.
    Random {
        /// ISO 8608 class, `A` (smoothest) … `H` (roughest).
        class: RoadClass,
        /// Seed of the phases (ChaCha8): the same seed gives the same road.
        seed: u64,
        /// Loop length `L` (m), > 0; the road repeats with this period and
        /// its spectral lines are `1/L` apart. Default 100 m.
        #[serde(default = "default_random_length_m")]
        length_m: f64,
        /// Lowest spatial frequency (cycles/m), > 0; default 1 (wavelength
        /// 1 m: longer waves move the whole contact patch together).
        #[serde(default = "default_min_cpm")]
        min_wavenumber_cpm: f64,
        /// Highest spatial frequency (cycles/m); default 100 (wavelength
        /// 1 cm). ISO 8608 classifies over 0.011-2.83 cycles/m; above, the
        /// `n^-2` law is extrapolated, as usual in tyre/road models.
        #[serde(default = "default_max_cpm")]
        max_wavenumber_cpm: f64,
    },
    /// A road that varies across the tread (method §4.8): a height grid in
    /// a CSV file, header `x_m,y_m,z_m`, one row per node of a regular grid
    /// in any order (see [`surface`]). Point `(x, y)` bears on
    /// `z(x + V t, y)`; a point whose `y` lies outside the grid is refused.
    /// With `looped` the grid is one period along `x`, of length `nx Δx`
    /// (its last column is not the first repeated).
    Surface {
        /// Path of the CSV, relative to the scene file's folder.
        file: PathBuf,
        /// Repeat the grid along `x`.
        #[serde(default)]
        looped: bool,
    },
    /// An ASAM OpenCRG road file (method §4.8; OpenCRG 1.2, read by
    /// `tirecontact_io::readers::crg`): heights on a grid along the
    /// reference line (`u`) and across it (`v`, positive to the left).
    /// Point `(x, y)` at time `t` bears on `z(u_start + x + V t, v_offset +
    /// y)`: the scene's `y` points to the left of the direction of travel,
    /// as `v` does. Along `u` heights are cubic Hermite curves through the
    /// nodes (as `Surface`), across linear; at the nodes they are the
    /// standard's evaluation (grid, reference line slope and banking) less
    /// the mean height of the file's nodes, so that `h_m` is measured from
    /// the road's mean plane. The reference line's heading and curvature
    /// do not change heights along it and are left aside. The road does not
    /// loop: a run leaving the file's `u` range is refused.
    Crg {
        /// Path of the `.crg` file, relative to the scene file's folder.
        file: PathBuf,
        /// The `u` (m) under `x = 0` at `t = 0`; default the file's first
        /// cross section.
        #[serde(default)]
        u_start_m: Option<f64>,
        /// The `v` (m) under `y = 0`; default 0 (the reference line).
        #[serde(default)]
        v_offset_m: f64,
    },
    /// A synthetic road texture (see [`texture`]): an isotropic random
    /// surface whose profiles have the PSD of ISO 8608 class `class` over
    /// `[min_wavenumber_cpm, max_wavenumber_cpm]`, periodic with `length_m`
    /// along and `width_m` across (`y` from `-width_m / 2`), seeded.
    Texture {
        /// ISO 8608 class of every profile, `A` … `H`.
        class: RoadClass,
        /// Seed of the phases (ChaCha8).
        seed: u64,
        /// Period along the road (m), > 0; default 2.
        #[serde(default = "default_texture_length_m")]
        length_m: f64,
        /// Period across the road (m), > 0; default 0.25.
        #[serde(default = "default_texture_width_m")]
        width_m: f64,
        /// Lowest radial wavenumber (cycles/m); default 10 (wavelength 10 cm).
        #[serde(default = "default_texture_min_cpm")]
        min_wavenumber_cpm: f64,
        /// Highest radial wavenumber (cycles/m); default 200 (wavelength 5 mm).
        #[serde(default = "default_texture_max_cpm")]
        max_wavenumber_cpm: f64,
    },
}

fn default_texture_length_m() -> f64 {
    2.0
}
fn default_texture_width_m() -> f64 {
    0.25
}
fn default_texture_min_cpm() -> f64 {
    10.0
}
fn default_texture_max_cpm() -> f64 {
    200.0
}

fn default_random_length_m() -> f64 {
    100.0
}
fn default_min_cpm() -> f64 {
    1.0
}
fn default_max_cpm() -> f64 {
    100.0
}

impl Road {
    /// The longest wavelength (m) a drawing of the road should show around
    /// the contact line: the sine's or the longest harmonic's, the longest
    /// of a random road or texture (`1 / min_wavenumber_cpm`), 0.5 m for a
    /// road read from a file.
    pub fn drawn_wavelength_m(&self) -> f64 {
        match self {
            Road::Sine { wavelength_m, .. } => *wavelength_m,
            Road::Harmonics { components } => components
                .iter()
                .map(|c| c.wavelength_m)
                .fold(0.0, f64::max),
            Road::Measured { .. } | Road::Surface { .. } | Road::Crg { .. } => 0.5,
            Road::Random {
                min_wavenumber_cpm, ..
            }
            | Road::Texture {
                min_wavenumber_cpm, ..
            } => 1.0 / min_wavenumber_cpm,
        }
    }

    /// Short human name of the road type.
    pub fn kind(&self) -> &'static str {
        match self {
            Road::Sine { .. } => "sine",
            Road::Harmonics { .. } => "harmonics",
            Road::Measured { .. } => "measured",
            Road::Random { .. } => "random",
            Road::Surface { .. } => "surface",
            Road::Crg { .. } => "OpenCRG",
            Road::Texture { .. } => "texture",
        }
    }

    /// The seed of a random road's or a texture's phases (`None`: the road
    /// is not random).
    pub fn seed(&self) -> Option<u64> {
        match self {
            Road::Random { seed, .. } | Road::Texture { seed, .. } => Some(*seed),
            _ => None,
        }
    }

    /// [`Road::seed`], to change it (a study's replicates and `road.seed`).
    pub fn seed_mut(&mut self) -> Option<&mut u64> {
        match self {
            Road::Random { seed, .. } | Road::Texture { seed, .. } => Some(seed),
            _ => None,
        }
    }

    /// Field errors of a texture (`at` prefixes the field names); empty for
    /// other roads and valid textures.
    pub fn texture_errors(&self, at: &str) -> Vec<FieldError> {
        let Road::Texture {
            length_m,
            width_m,
            min_wavenumber_cpm: lo,
            max_wavenumber_cpm: hi,
            ..
        } = *self
        else {
            return Vec::new();
        };
        let mut e = Vec::new();
        if !positive(length_m) {
            push_field(
                &mut e,
                at,
                "length_m",
                length_m,
                "a period along the road > 0 m".into(),
            );
        }
        if !positive(width_m) {
            push_field(
                &mut e,
                at,
                "width_m",
                width_m,
                "a period across the road > 0 m".into(),
            );
        }
        band_errors(&mut e, at, lo, hi);
        if e.is_empty()
            && let Some(msg) = texture::grid_error(length_m, width_m, hi)
        {
            push_field(&mut e, at, "max_wavenumber_cpm", hi, msg);
        }
        e
    }

    /// Field errors of a random road (`at` prefixes the field names); empty
    /// for other roads and valid random ones.
    pub fn random_errors(&self, at: &str) -> Vec<FieldError> {
        let Road::Random {
            length_m,
            min_wavenumber_cpm: lo,
            max_wavenumber_cpm: hi,
            ..
        } = *self
        else {
            return Vec::new();
        };
        let mut e = Vec::new();
        if !positive(length_m) {
            push_field(
                &mut e,
                at,
                "length_m",
                length_m,
                "a loop length > 0 m".into(),
            );
        }
        band_errors(&mut e, at, lo, hi);
        if e.is_empty() {
            let grid = random::grid_points(length_m, hi);
            if grid > random::MAX_GRID_POINTS as f64 {
                push_field(
                    &mut e,
                    at,
                    "length_m",
                    length_m,
                    format!(
                        "length_m x max_wavenumber_cpm <= {:.0} (the profile grid has {} points per shortest wavelength, at most {} points)",
                        random::MAX_GRID_POINTS as f64 / random::POINTS_PER_WAVELENGTH,
                        random::POINTS_PER_WAVELENGTH,
                        random::MAX_GRID_POINTS
                    ),
                );
            } else if random::harmonic_range(length_m, lo, hi).is_empty() {
                push_field(
                    &mut e,
                    at,
                    "max_wavenumber_cpm",
                    hi,
                    format!(
                        "a band [{lo}, {hi}] cycles/m holding at least one line j / length_m = j / {length_m} m"
                    ),
                );
            }
        }
        e
    }
}

/// Finite and > 0.
fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

/// Adds the error of field `at.field` (its value `value`).
fn push_field(e: &mut Vec<FieldError>, at: &str, field: &str, value: f64, expected: String) {
    e.push(FieldError {
        field: format!("{at}.{field}"),
        value: crate::base::error::fmt_num(value),
        expected,
    });
}

/// The errors of a band of spatial frequencies `[lo, hi]` (cycles/m):
/// both > 0, `hi >= lo`.
fn band_errors(e: &mut Vec<FieldError>, at: &str, lo: f64, hi: f64) {
    if !positive(lo) {
        push_field(
            e,
            at,
            "min_wavenumber_cpm",
            lo,
            "a spatial frequency > 0 cycles/m".into(),
        );
    }
    if !positive(hi) || (positive(lo) && hi < lo) {
        push_field(
            e,
            at,
            "max_wavenumber_cpm",
            hi,
            format!("a spatial frequency >= min_wavenumber_cpm = {lo} cycles/m"),
        );
    }
}

/// A road ready to be sampled: `z(x)` (m) and `dz/dx` (-).
#[derive(Debug, Clone, PartialEq)]
pub enum RoadProfile {
    Harmonics(Vec<Harmonic>),
    Measured {
        x_m: Vec<f64>,
        z_m: Vec<f64>,
        looped: bool,
    },
    /// Periodic grid of heights and slopes `x = m dx_m`, cubic Hermite
    /// interpolation (random roads).
    Gridded {
        dx_m: f64,
        z_m: Vec<f64>,
        dz: Vec<f64>,
    },
    /// A height grid `z(x, y)` (surface files and textures), shared: the
    /// largest take hundreds of megabytes.
    Surface(Arc<SurfaceGrid>),
}

/// Sampling a measured profile past its ends (without `looped`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OutOfRange {
    pub x_m: f64,
    pub min_m: f64,
    pub max_m: f64,
}

impl RoadProfile {
    /// The profile of a road described without a file (sine, harmonics,
    /// random, texture), its fields checked first (errors named from
    /// `road`); `None` for a road read from a file (`Measured`, `Surface`),
    /// which the I/O layer reads (`tirecontact_io::readers::road::load`).
    pub fn generated(road: &Road) -> Option<Result<Self, Vec<FieldError>>> {
        Some(Ok(match road {
            Road::Sine {
                amplitude_m,
                wavelength_m,
            } => RoadProfile::Harmonics(vec![Harmonic {
                amplitude_m: *amplitude_m,
                wavelength_m: *wavelength_m,
                phase_rad: 0.0,
            }]),
            Road::Harmonics { components } => RoadProfile::Harmonics(components.clone()),
            Road::Measured { .. } | Road::Surface { .. } | Road::Crg { .. } => return None,
            Road::Random {
                class,
                seed,
                length_m,
                min_wavenumber_cpm,
                max_wavenumber_cpm,
            } => {
                let errors = road.random_errors("road");
                if !errors.is_empty() {
                    return Some(Err(errors));
                }
                let (z_m, dz) = random::generate(
                    *class,
                    *seed,
                    *length_m,
                    *min_wavenumber_cpm,
                    *max_wavenumber_cpm,
                );
                RoadProfile::Gridded {
                    dx_m: length_m / z_m.len() as f64,
                    z_m,
                    dz,
                }
            }
            Road::Texture {
                class,
                seed,
                length_m,
                width_m,
                min_wavenumber_cpm,
                max_wavenumber_cpm,
            } => {
                let errors = road.texture_errors("road");
                if !errors.is_empty() {
                    return Some(Err(errors));
                }
                RoadProfile::Surface(Arc::new(texture::generate(
                    *class,
                    *seed,
                    (*length_m, *width_m),
                    (*min_wavenumber_cpm, *max_wavenumber_cpm),
                )))
            }
        }))
    }

    /// The surface grid of a road that varies across the tread.
    pub fn surface(&self) -> Option<&SurfaceGrid> {
        match self {
            RoadProfile::Surface(g) => Some(g),
            _ => None,
        }
    }

    /// A length scale of the profile (m): largest possible |z|.
    pub fn scale_m(&self) -> f64 {
        match self {
            RoadProfile::Harmonics(h) => h.iter().map(|c| c.amplitude_m.abs()).sum(),
            RoadProfile::Measured { z_m, .. } | RoadProfile::Gridded { z_m, .. } => {
                z_m.iter().fold(0.0, |m, z| m.max(z.abs()))
            }
            RoadProfile::Surface(g) => g.scale_m(),
        }
    }

    /// Height `z(x, y)` (m) and slope `dz/dx` at `(x, y)` (m): profile roads
    /// do not depend on `y`; a surface file's `y` is clamped to its grid.
    #[inline]
    pub fn sample_at(&self, x_m: f64, y_m: f64) -> Result<(f64, f64), OutOfRange> {
        match self {
            RoadProfile::Surface(g) => g.sample(x_m, y_m),
            _ => self.sample_side(x_m, true),
        }
    }

    /// Height `z(x)` (m) and slope `dz/dx` at `x` (m); at a breakpoint of a
    /// measured profile, the slope of the segment after it; on the
    /// centreline `y = 0` of a surface.
    #[inline]
    pub fn sample(&self, x: f64) -> Result<(f64, f64), OutOfRange> {
        self.sample_side(x, true)
    }

    /// As [`RoadProfile::sample`]; at a breakpoint, the slope after it
    /// (`after`) or before it (the road velocity at the end of an interval
    /// that reaches the breakpoint).
    #[inline]
    pub fn sample_side(&self, x: f64, after: bool) -> Result<(f64, f64), OutOfRange> {
        match self {
            RoadProfile::Harmonics(h) => {
                let mut z = 0.0;
                let mut dz = 0.0;
                for c in h {
                    let k = TAU / c.wavelength_m;
                    let (s, co) = (k * x + c.phase_rad).sin_cos();
                    z += c.amplitude_m * s;
                    dz += c.amplitude_m * k * co;
                }
                Ok((z, dz))
            }
            RoadProfile::Measured { x_m, z_m, looped } => {
                let (x0, x1) = (x_m[0], x_m[x_m.len() - 1]);
                let xx = if *looped {
                    x0 + (x - x0).rem_euclid(x1 - x0)
                } else if x < x0 || x > x1 {
                    return Err(OutOfRange {
                        x_m: x,
                        min_m: x0,
                        max_m: x1,
                    });
                } else {
                    x
                };
                // Segment k with x_m[k] <= xx <= x_m[k+1].
                // a breakpoint within KINK_SNAP_M of xx (round-off of x + V t)
                // counts as reached: the side decides the segment
                let k = if after {
                    x_m.partition_point(|&xi| xi <= xx + KINK_SNAP_M)
                } else {
                    x_m.partition_point(|&xi| xi < xx - KINK_SNAP_M)
                };
                let k = k.clamp(1, x_m.len() - 1) - 1;
                let slope = (z_m[k + 1] - z_m[k]) / (x_m[k + 1] - x_m[k]);
                Ok((z_m[k] + slope * (xx - x_m[k]), slope))
            }
            RoadProfile::Gridded { dx_m, z_m, dz } => {
                Ok(random::sample_periodic(z_m, dz, *dx_m, x))
            }
            RoadProfile::Surface(g) => g.sample(x, 0.0),
        }
    }
}

/// Distance (m) within which a point is taken to sit on a breakpoint of a
/// measured profile (far below any profile spacing, far above round-off).
pub const KINK_SNAP_M: f64 = 1e-12;

/// The ramp `w(t) = 3 s^2 - 2 s^3`, `s = clamp(t / T, 0, 1)`, and `dw/dt`
/// (method §4). `T = 0` gives `w = 1`.
#[inline]
pub fn ramp(t_s: f64, ramp_s: f64) -> (f64, f64) {
    if ramp_s <= 0.0 || t_s >= ramp_s {
        return (1.0, 0.0);
    }
    if t_s <= 0.0 {
        return (0.0, 0.0);
    }
    let s = t_s / ramp_s;
    (s * s * (3.0 - 2.0 * s), 6.0 * s * (1.0 - s) / ramp_s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ramp_is_smooth_and_monotone() {
        let t = 0.1;
        assert_eq!(ramp(0.0, t), (0.0, 0.0));
        assert_eq!(ramp(t, t), (1.0, 0.0));
        let (w, dw) = ramp(0.05, t);
        assert!((w - 0.5).abs() < 1e-15);
        assert!((dw - 1.5 / t).abs() < 1e-12);
        // derivative against a central difference
        let e = 1e-7;
        let fd = (ramp(0.03 + e, t).0 - ramp(0.03 - e, t).0) / (2.0 * e);
        assert!((fd - ramp(0.03, t).1).abs() < 1e-6);
    }

    #[test]
    fn measured_profile_interpolates_and_refuses_outside() {
        let p = RoadProfile::Measured {
            x_m: vec![0.0, 1.0, 3.0],
            z_m: vec![0.0, 1.0, -1.0],
            looped: false,
        };
        assert_eq!(p.sample(0.5).unwrap(), (0.5, 1.0));
        assert_eq!(p.sample(2.0).unwrap(), (0.0, -1.0));
        assert_eq!(p.sample(3.0).unwrap(), (-1.0, -1.0));
        assert!(p.sample(3.5).is_err());
        assert!(p.sample(-0.1).is_err());
        let l = RoadProfile::Measured {
            x_m: vec![0.0, 1.0, 3.0],
            z_m: vec![0.0, 1.0, -1.0],
            looped: true,
        };
        assert!((l.sample(3.5).unwrap().0 - 0.5).abs() < 1e-15);
        assert!((l.sample(-1.0).unwrap().0 - 0.0).abs() < 1e-15);
    }

    #[test]
    fn kinks_of_a_measured_profile() {
        let prof = RoadProfile::Measured {
            x_m: vec![0.0, 1.0, 3.0],
            z_m: vec![0.0, 1.0, -1.0],
            looped: false,
        };
        let pr = PointsRoad::new(prof, &[0.5, -0.2], &[]);
        assert_eq!(pr.next_kink(0, 0.0, 1.0), Some(0.5));
        assert_eq!(pr.next_kink(0, 0.5, 1.0), None); // at the start: ignored
        assert_eq!(pr.next_kink(1, 0.3, 1.5), Some(1.2));
        let looped = RoadProfile::Measured {
            x_m: vec![0.0, 1.0, 3.0],
            z_m: vec![0.0, 1.0, 0.0],
            looped: true,
        };
        let pr = PointsRoad::new(looped, &[0.0], &[]);
        assert!((pr.next_kink(0, 2.5, 3.6).unwrap() - 3.0).abs() < 1e-12); // the wrap point
        assert!((pr.next_kink(0, 3.2, 4.5).unwrap() - 4.0).abs() < 1e-12);
    }

    #[test]
    fn points_road_matches_direct_sampling() {
        let prof = RoadProfile::Harmonics(vec![
            Harmonic {
                amplitude_m: 0.002,
                wavelength_m: 0.5,
                phase_rad: 0.3,
            },
            Harmonic {
                amplitude_m: 0.001,
                wavelength_m: 0.013,
                phase_rad: -1.0,
            },
        ]);
        let xs = [-0.05, 0.0, 0.031];
        let pr = PointsRoad::new(prof.clone(), &xs, &[]);
        let (mut z, mut dz) = ([0.0; 3], [0.0; 3]);
        for s in [0.0, 0.37, 123.456] {
            pr.sample_all(s, true, &mut z, &mut dz).unwrap();
            for i in 0..3 {
                let (zd, dzd) = prof.sample(xs[i] + s).unwrap();
                assert!((z[i] - zd).abs() < 1e-14, "{} vs {zd}", z[i]);
                assert!((dz[i] - dzd).abs() < 1e-11 * dzd.abs().max(1.0));
            }
        }
    }

    #[test]
    fn harmonic_slope_matches_difference() {
        let p = RoadProfile::Harmonics(vec![
            Harmonic {
                amplitude_m: 0.002,
                wavelength_m: 0.5,
                phase_rad: 0.3,
            },
            Harmonic {
                amplitude_m: 0.001,
                wavelength_m: 0.13,
                phase_rad: 0.0,
            },
        ]);
        let e = 1e-7;
        let fd = (p.sample(0.2 + e).unwrap().0 - p.sample(0.2 - e).unwrap().0) / (2.0 * e);
        assert!((fd - p.sample(0.2).unwrap().1).abs() < 1e-7);
    }

    #[test]
    fn random_road_fields_are_validated_by_name() {
        let road = |len: f64, lo: f64, hi: f64| Road::Random {
            class: RoadClass::E,
            seed: 1,
            length_m: len,
            min_wavenumber_cpm: lo,
            max_wavenumber_cpm: hi,
        };
        let fields = |r: Road| -> Vec<String> {
            let e = r.random_errors("road");
            assert_eq!(RoadProfile::generated(&r).unwrap().is_err(), !e.is_empty());
            e.into_iter().map(|e| e.field).collect()
        };
        assert!(fields(road(100.0, 1.0, 100.0)).is_empty());
        assert_eq!(fields(road(-1.0, 1.0, 100.0)), ["road.length_m"]);
        assert_eq!(fields(road(f64::NAN, 1.0, 100.0)), ["road.length_m"]);
        assert_eq!(fields(road(100.0, 0.0, 100.0)), ["road.min_wavenumber_cpm"]);
        assert_eq!(fields(road(100.0, 5.0, 2.0)), ["road.max_wavenumber_cpm"]);
        // grid too large: named with the limit
        assert_eq!(fields(road(1e6, 1.0, 100.0)), ["road.length_m"]);
        // the limit is length_m x max_wavenumber_cpm <= 2^22 / 8 (checked without generating)
        assert!(road(5242.88, 1.0, 100.0).random_errors("road").is_empty());
        assert_eq!(road(5243.0, 1.0, 100.0).random_errors("road").len(), 1);
        // no spectral line in the band
        assert_eq!(fields(road(1.0, 1.2, 1.8)), ["road.max_wavenumber_cpm"]);
        // a validated random road samples anywhere (periodic)
        let p = RoadProfile::generated(&road(10.0, 1.0, 20.0))
            .unwrap()
            .unwrap();
        assert!(p.sample(-1e4).is_ok() && p.sample(1e4).is_ok());
        assert!(p.scale_m() > 0.0);
    }
}
