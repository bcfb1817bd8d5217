//! The values of the fields [`super::FIELDS`] lists, reached in a scene:
//! each numeric field by its path as a mutable reference, and a grid of
//! points' own fields.

use super::super::{Contact, MAX_POINTS, Points, Preload, Scene, Tyre};
use crate::readers::fe_modes::FeDamping;
use tirecontact_core::base::error::FieldError;
use tirecontact_core::model::road::Road;

/// Every numeric field of the scene with its path, as mutable references
/// (the points' only when `with_points`: reaching them turns a grid into
/// a list). Integer fields (`tyre.ring.max_order`, ...) and text are not
/// listed; a grid's fields are [`grid_fields`].
pub fn numeric_fields(scene: &mut Scene, with_points: bool) -> Vec<(String, &mut f64)> {
    let mut f: Vec<(String, &mut f64)> = vec![
        ("speed_mps".into(), &mut scene.speed_mps),
        ("ramp_s".into(), &mut scene.ramp_s),
        ("dt_s".into(), &mut scene.dt_s),
        ("duration_s".into(), &mut scene.duration_s),
    ];
    if with_points {
        for (i, p) in scene.points.iter_mut().enumerate() {
            f.push((format!("points[{i}].x_m"), &mut p.x_m));
            f.push((format!("points[{i}].y_m"), &mut p.y_m));
            f.push((format!("points[{i}].h_m"), &mut p.h_m));
        }
    }
    road_fields(&mut scene.road, &mut f);
    if let Contact::Compliant { stiffness_n_m } = &mut scene.contact {
        for (i, k) in stiffness_n_m.iter_mut().enumerate() {
            f.push((format!("contact.stiffness_n_m[{i}]"), k));
        }
    }
    tyre_fields(&mut scene.tyre, &mut f);
    f
}

/// The road's part of [`numeric_fields`].
fn road_fields<'a>(road: &'a mut Road, f: &mut Vec<(String, &'a mut f64)>) {
    match road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => {
            f.push(("road.amplitude_m".into(), amplitude_m));
            f.push(("road.wavelength_m".into(), wavelength_m));
        }
        Road::Harmonics { components } => {
            for (k, c) in components.iter_mut().enumerate() {
                let at = |name: &str| format!("road.components[{k}].{name}");
                f.push((at("amplitude_m"), &mut c.amplitude_m));
                f.push((at("wavelength_m"), &mut c.wavelength_m));
                f.push((at("phase_rad"), &mut c.phase_rad));
            }
        }
        Road::Random {
            length_m,
            min_wavenumber_cpm,
            max_wavenumber_cpm,
            ..
        } => {
            f.push(("road.length_m".into(), length_m));
            f.push(("road.min_wavenumber_cpm".into(), min_wavenumber_cpm));
            f.push(("road.max_wavenumber_cpm".into(), max_wavenumber_cpm));
        }
        Road::Texture {
            length_m,
            width_m,
            min_wavenumber_cpm,
            max_wavenumber_cpm,
            ..
        } => {
            f.push(("road.length_m".into(), length_m));
            f.push(("road.width_m".into(), width_m));
            f.push(("road.min_wavenumber_cpm".into(), min_wavenumber_cpm));
            f.push(("road.max_wavenumber_cpm".into(), max_wavenumber_cpm));
        }
        Road::Crg {
            u_start_m,
            v_offset_m,
            ..
        } => {
            if let Some(u) = u_start_m {
                f.push(("road.u_start_m".into(), u));
            }
            f.push(("road.v_offset_m".into(), v_offset_m));
        }
        Road::Measured { .. } | Road::Surface { .. } => {}
    }
}

/// The tyre's part of [`numeric_fields`].
fn tyre_fields<'a>(tyre: &'a mut Tyre, f: &mut Vec<(String, &'a mut f64)>) {
    match tyre {
        Tyre::Modal { modes } => {
            for (k, m) in modes.iter_mut().enumerate() {
                f.push((format!("tyre.modes[{k}].freq_hz"), &mut m.freq_hz));
                f.push((
                    format!("tyre.modes[{k}].damping_ratio"),
                    &mut m.damping_ratio,
                ));
                for (i, a) in m.shape.iter_mut().enumerate() {
                    f.push((format!("tyre.modes[{k}].shape[{i}]"), a));
                }
                for (i, row) in m.residue.iter_mut().enumerate() {
                    for (j, a) in row.iter_mut().enumerate() {
                        f.push((format!("tyre.modes[{k}].residue[{i}][{j}]"), a));
                    }
                }
            }
        }
        Tyre::Ring {
            ring: r,
            identification: o,
        } => {
            let at = |name: &str| format!("tyre.ring.{name}");
            f.push((at("radius_m"), &mut r.radius_m));
            f.push((at("belt_width_m"), &mut r.belt_width_m));
            f.push((at("mass_per_length_kg_m"), &mut r.mass_per_length_kg_m));
            f.push((at("inflation_pa"), &mut r.inflation_pa));
            f.push((at("radial_stiffness_n_m2"), &mut r.radial_stiffness_n_m2));
            f.push((
                at("tangential_stiffness_n_m2"),
                &mut r.tangential_stiffness_n_m2,
            ));
            f.push((at("bending_stiffness_n_m2"), &mut r.bending_stiffness_n_m2));
            f.push((
                at("extensional_stiffness_n"),
                &mut r.extensional_stiffness_n,
            ));
            f.push((at("damping_ratio"), &mut r.damping_ratio));
            f.push(("tyre.identification.band_hz.0".into(), &mut o.band_hz.0));
            f.push(("tyre.identification.band_hz.1".into(), &mut o.band_hz.1));
            f.push((
                "tyre.identification.sample_rate_hz".into(),
                &mut o.sample_rate_hz,
            ));
            f.push(("tyre.identification.duration_s".into(), &mut o.duration_s));
        }
        Tyre::Measured {
            identification: o, ..
        } => {
            f.push(("tyre.identification.band_hz.0".into(), &mut o.band_hz.0));
            f.push(("tyre.identification.band_hz.1".into(), &mut o.band_hz.1));
            f.push(("tyre.identification.duration_s".into(), &mut o.duration_s));
        }
        Tyre::FeModes {
            damping,
            nearest_within_m,
            ..
        } => {
            match damping {
                FeDamping::Ratio(x) => f.push(("tyre.damping.0".into(), x)),
                FeDamping::Modal(v) => {
                    for (k, x) in v.iter_mut().enumerate() {
                        f.push((format!("tyre.damping.0[{k}]"), x));
                    }
                }
                FeDamping::Rayleigh {
                    alpha_per_s,
                    beta_s,
                } => {
                    f.push(("tyre.damping.alpha_per_s".into(), alpha_per_s));
                    f.push(("tyre.damping.beta_s".into(), beta_s));
                }
                FeDamping::FromFile => {}
            }
            f.push(("tyre.nearest_within_m".into(), nearest_within_m));
        }
        Tyre::Plate { plate: pl } => {
            let at = |name: &str| format!("tyre.plate.{name}");
            f.push((at("width_m"), &mut pl.width_m));
            f.push((at("circumference_m"), &mut pl.circumference_m));
            f.push((at("mass_per_area_kg_m2"), &mut pl.mass_per_area_kg_m2));
            f.push((at("bending_along_nm"), &mut pl.bending_along_nm));
            f.push((at("bending_across_nm"), &mut pl.bending_across_nm));
            f.push((at("tension_along_n_m"), &mut pl.tension_along_n_m));
            f.push((at("tension_across_n_m"), &mut pl.tension_across_n_m));
            f.push((at("foundation_n_m3"), &mut pl.foundation_n_m3));
            f.push((at("damping_ratio"), &mut pl.damping_ratio));
            f.push((at("max_freq_hz"), &mut pl.max_freq_hz));
        }
    }
}

/// The fields of a grid of points (`points: Grid(...)`) a sweep or a study
/// sets: the whole numbers of points along and rows across, the spacings
/// (m) and the preload's depth and footprint length (m). Setting one
/// expands the grid again.
pub const GRID_PATHS: [&str; 6] = [
    "points.along",
    "points.across",
    "points.spacing_m.0",
    "points.spacing_m.1",
    "points.preload.depth_m",
    "points.preload.length_m",
];

/// The grid fields of `scene`'s points that exist (a parabolic preload's
/// length only), with their values.
pub fn grid_fields(scene: &Scene) -> Vec<(&'static str, f64)> {
    let Some(g) = scene.points.grid() else {
        return Vec::new();
    };
    let (depth_m, length_m) = match g.preload {
        Preload::Flat { depth_m } => (depth_m, None),
        Preload::Parabolic { depth_m, length_m } => (depth_m, Some(length_m)),
    };
    let mut f = vec![
        (GRID_PATHS[0], g.along as f64),
        (GRID_PATHS[1], g.across as f64),
        (GRID_PATHS[2], g.spacing_m.0),
        (GRID_PATHS[3], g.spacing_m.1),
        (GRID_PATHS[4], depth_m),
    ];
    if let Some(l) = length_m {
        f.push((GRID_PATHS[5], l));
    }
    f
}

/// Sets the grid field at `path` of `scene`'s points to `value` and
/// expands the grid again; `None` when the points hold no such field.
pub fn set_grid_field(scene: &mut Scene, path: &str, value: f64) -> Option<Result<(), FieldError>> {
    let mut g = *scene.points.grid()?;
    let whole = |v: f64| -> Result<usize, FieldError> {
        if v.is_finite() && v >= 1.0 && v.fract() == 0.0 && v <= MAX_POINTS as f64 {
            Ok(v as usize)
        } else {
            Err(FieldError {
                field: path.to_string(),
                value: format!("{v}"),
                expected: format!("a whole number of points from 1 to {MAX_POINTS}"),
            })
        }
    };
    let set = (|| -> Result<bool, FieldError> {
        match (path, &mut g.preload) {
            ("points.along", _) => g.along = whole(value)?,
            ("points.across", _) => g.across = whole(value)?,
            ("points.spacing_m.0", _) => g.spacing_m.0 = value,
            ("points.spacing_m.1", _) => g.spacing_m.1 = value,
            ("points.preload.depth_m", Preload::Flat { depth_m })
            | ("points.preload.depth_m", Preload::Parabolic { depth_m, .. }) => *depth_m = value,
            ("points.preload.length_m", Preload::Parabolic { length_m, .. }) => *length_m = value,
            _ => return Ok(false),
        }
        Ok(true)
    })();
    match set {
        Ok(false) => None,
        Err(e) => Some(Err(e)),
        Ok(true) => Some(match g.check() {
            Some((field, value, expected)) => Err(FieldError {
                field,
                value,
                expected,
            }),
            None => {
                scene.points = Points::from_grid(g);
                Ok(())
            }
        }),
    }
}
