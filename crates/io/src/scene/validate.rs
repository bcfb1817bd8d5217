//! Validation of a scene: every value checked, every problem returned,
//! each naming the field, the value and what was expected.

mod tyre;

use super::{
    Contact, MAX_POINTS, MAX_STEPS, MAX_TREAD_STIFFNESS_N_M, Point, Scene, Tyre, load_road,
};
use tirecontact_core::base::error::{FieldError, fmt_num};
use tirecontact_core::model::road::{Road, RoadProfile};
use tyre::{validate_plate_points, validate_tyre};

impl Scene {
    /// Points whose `y` lies outside a surface file's grid (the grid does
    /// not say what the road is there), each named.
    pub fn surface_errors(&self, road: &RoadProfile) -> Vec<FieldError> {
        let Some((lo, hi)) = road.surface().and_then(|g| g.y_range_m()) else {
            return Vec::new();
        };
        self.points
            .iter()
            .enumerate()
            .filter(|(_, pt)| road.surface().is_some_and(|g| g.rows_at(pt.y_m).is_none()))
            .map(|(i, pt)| FieldError {
                field: format!("points[{i}].y_m"),
                value: fmt_num(pt.y_m),
                expected: format!(
                    "a position across the tread within the road surface's grid, {} m to {} m",
                    fmt_num(lo),
                    fmt_num(hi)
                ),
            })
            .collect()
    }

    /// What an OpenCRG road (it does not loop) refuses of a run, each
    /// named: a point starting before the file's first cross section, a
    /// run lasting past the time the first point reaches its last (the
    /// last time that fits named), a point whose path crosses a cell
    /// without height. Empty for other roads.
    pub fn crg_errors(&self, road: &RoadProfile) -> Vec<FieldError> {
        let (Road::Crg { .. }, Some(g)) = (&self.road, road.surface()) else {
            return Vec::new();
        };
        let (u0, v0) = g.file_origin_m;
        let (lo, hi) = g.x_range_m();
        let tol = tirecontact_core::model::road::surface::GRID_TOLERANCE * g.dx_m;
        let speed = self.speed_mps.max(0.0);
        let travel = speed * self.duration_s;
        let mut e = Vec::new();
        let points: Vec<(f64, f64)> = self.points.iter().map(|p| (p.x_m, p.y_m)).collect();
        for (i, &(x, _)) in points.iter().enumerate() {
            if x < lo - tol || x > hi + tol {
                e.push(FieldError {
                    field: format!("points[{i}].x_m"),
                    value: fmt_num(x),
                    expected: format!(
                        "a position on the OpenCRG road at the start: x from {} m to {} m (u from {} m to {} m, u = {} m under x = 0)",
                        fmt_num(lo),
                        fmt_num(hi),
                        fmt_num(lo + u0),
                        fmt_num(hi + u0),
                        fmt_num(u0)
                    ),
                });
            }
        }
        if !e.is_empty() {
            return e;
        }
        if speed > 0.0
            && let Some((i, x)) = points
                .iter()
                .map(|p| p.0)
                .enumerate()
                .max_by(|a, b| a.1.total_cmp(&b.1))
            && x + travel > hi + tol
        {
            let t_last = (hi - x) / speed;
            e.push(FieldError {
                field: "duration_s".into(),
                value: fmt_num(self.duration_s),
                expected: format!(
                    "a duration <= {} s: at {} m/s point {i} reaches the end of the OpenCRG road (x = {} m, u = {} m) then; the road does not loop",
                    fmt_num(t_last),
                    fmt_num(speed),
                    fmt_num(hi),
                    fmt_num(hi + u0)
                ),
            });
            return e;
        }
        for (i, &(x, y)) in points.iter().enumerate() {
            let Some(rows) = g.rows_at(y) else {
                continue; // refused by `surface_errors`
            };
            if let Some((xg, yg)) = g.gap_on_path(rows, x, x + travel) {
                e.push(FieldError {
                    field: format!("points[{i}]"),
                    value: format!("(x {} m, y {} m)", fmt_num(x), fmt_num(y)),
                    expected: format!(
                        "a path over heights: the OpenCRG file has no height at u = {} m, v = {} m (x = {} m, y = {} m), which the point reaches within the run",
                        fmt_num(xg + u0),
                        fmt_num(yg + v0),
                        fmt_num(xg),
                        fmt_num(yg)
                    ),
                });
            }
        }
        e
    }

    /// `T_ramp = 0` is allowed only where no point starts below the road
    /// (`z(x_i) - h_i <= 0` for all `i`, method §4).
    pub fn ramp_error(&self, road: &RoadProfile) -> Option<FieldError> {
        if self.ramp_s != 0.0 {
            return None;
        }
        self.points.iter().enumerate().find_map(|(i, pt)| {
            let z = road.sample_at(pt.x_m, pt.y_m).map(|s| s.0).unwrap_or(0.0);
            (z - pt.h_m > 0.0).then(|| FieldError {
                field: "ramp_s".into(),
                value: "0".into(),
                expected: format!(
                    "a ramp time > 0 s: point {i} starts {:.3e} m below the road (docs/method.md §4)",
                    z - pt.h_m
                ),
            })
        })
    }

    /// Checks every value; returns all problems found.
    pub fn validate(&self) -> Result<(), Vec<FieldError>> {
        let mut v = Validator::default();
        if let Some((field, value, expected)) = self.points.grid().and_then(|g| g.check()) {
            v.push(&field, value, &expected);
            return v.finish();
        }
        let p = self.points.len();
        if p == 0 {
            v.push("points", "[]", "at least one contact point");
        }
        if p > MAX_POINTS {
            v.push(
                "points",
                format!("{p} points"),
                &format!(
                    "at most {MAX_POINTS} contact points (the contact solver keeps ~16 P² numbers)"
                ),
            );
            // the per-point checks below are quadratic: stop here
            return v.finish();
        }
        validate_points(&mut v, &self.points);
        validate_points_across(&mut v, &self.tyre, &self.contact, &self.points);
        validate_tyre(&mut v, &self.tyre, p);
        validate_plate_points(&mut v, &self.tyre, &self.contact, &self.points);
        validate_road(&mut v, &self.road);
        if let Contact::Compliant { stiffness_n_m } = &self.contact {
            validate_tread(&mut v, stiffness_n_m, p);
        }
        self.validate_speed_and_ramp(&mut v);
        self.validate_time_step(&mut v);
        v.finish()
    }

    /// The speed, the ramp time, and a ramp time of 0 where a point starts
    /// below the road (`ramp_error`; a measured road's when its file is read).
    fn validate_speed_and_ramp(&self, v: &mut Validator) {
        if v.nonneg("speed_mps", self.speed_mps, "a finite speed >= 0 m/s")
            && self.speed_mps > 1000.0
        {
            v.push("speed_mps", self.speed_mps, "a speed <= 1000 m/s");
        }
        v.nonneg("ramp_s", self.ramp_s, "a ramp time >= 0 s");
        // (a road read from a file or generated on a grid is checked when it
        // is loaded: `PreparedModel`)
        if !matches!(
            self.road,
            Road::Measured { .. } | Road::Surface { .. } | Road::Crg { .. } | Road::Texture { .. }
        ) && let Ok(prof) = load_road(&self.road, None)
            && let Some(e) = self.ramp_error(&prof)
        {
            v.errors.push(e);
        }
    }

    /// The time step and the duration, each alone and against each other
    /// (at least one step, at most [`MAX_STEPS`]).
    fn validate_time_step(&self, v: &mut Validator) {
        // one message per field: an infinite dt_s is "not > 0 and finite", not
        // also "too large"
        if v.positive("dt_s", self.dt_s, "a finite time step > 0 s") && self.dt_s > 0.1 {
            v.push("dt_s", self.dt_s, "a time step <= 0.1 s");
        }
        let duration_ok = v.positive("duration_s", self.duration_s, "a finite duration > 0 s");
        if duration_ok && self.dt_s.is_finite() && self.dt_s > 0.0 && self.dt_s <= 0.1 {
            if self.dt_s > self.duration_s {
                v.push(
                    "dt_s",
                    self.dt_s,
                    &format!("a time step <= duration_s = {} s", fmt_num(self.duration_s)),
                );
            } else if self.duration_s / self.dt_s > MAX_STEPS {
                v.push(
                    "duration_s",
                    self.duration_s,
                    &format!(
                        "at most {MAX_STEPS:e} steps of dt_s = {} s ({:.3e} requested)",
                        fmt_num(self.dt_s),
                        self.duration_s / self.dt_s
                    ),
                );
            }
        }
    }
}

/// The contact points: finite positions, heights of a tyre deflection, no
/// two at one place `(x, y)`.
fn validate_points(v: &mut Validator, points: &[Point]) {
    for (i, pt) in points.iter().enumerate() {
        v.finite(
            &format!("points[{i}].x_m"),
            pt.x_m,
            "a finite position in m",
        );
        v.finite(
            &format!("points[{i}].y_m"),
            pt.y_m,
            "a finite position across the tread in m (0 on its centreline)",
        );
        if v.finite(&format!("points[{i}].h_m"), pt.h_m, "a finite height in m")
            && pt.h_m.abs() > 1.0
        {
            v.push(
                &format!("points[{i}].h_m"),
                pt.h_m,
                "|h| <= 1 m (a tyre deflection, in metres)",
            );
        }
        if let Some(j) = points[..i]
            .iter()
            .position(|q| q.x_m == pt.x_m && q.y_m == pt.y_m)
        {
            v.push(
                &format!("points[{i}].x_m"),
                pt.x_m,
                &format!(
                    "a place different from points[{j}]'s: both are at x_m = {} m, y_m = {} m (coincident points make the contact system singular)",
                    fmt_num(pt.x_m),
                    fmt_num(pt.y_m)
                ),
            );
        }
    }
}

/// Points at one `x` and different `y` on a ring tyre with rigid contact:
/// the ring's response does not depend on `y`, so their rows (and columns)
/// of the contact system are identical: it is singular, and nothing shares
/// their force out between them. Compliant contact adds the tread springs,
/// one per point, and solves it. A modal tyre's residues
/// may depend on `y`, and are the user's to give; a measured tyre's rows
/// are its file's responses, one per point.
fn validate_points_across(v: &mut Validator, tyre: &Tyre, contact: &Contact, points: &[Point]) {
    if !(contact.is_rigid() && matches!(tyre, Tyre::Ring { .. })) {
        return;
    }
    for (i, pt) in points.iter().enumerate() {
        if let Some(j) = points[..i]
            .iter()
            .position(|q| q.x_m == pt.x_m && q.y_m != pt.y_m)
        {
            v.push(
                &format!("points[{i}].x_m"),
                pt.x_m,
                &format!(
                    "a position different from points[{j}].x_m: points[{j}] and points[{i}] share x_m = {} m at different y_m ({} m and {} m), but a Ring tyre's response does not depend on y, so with rigid contact their rows of the contact system are identical (singular); use contact: Compliant(...) or a Modal tyre whose residues depend on y",
                    fmt_num(pt.x_m),
                    fmt_num(points[j].y_m),
                    fmt_num(pt.y_m)
                ),
            );
        }
    }
}

/// The tread stiffnesses of compliant contact with `p` points: one for all
/// or one per point, each in (0, [`MAX_TREAD_STIFFNESS_N_M`]].
fn validate_tread(v: &mut Validator, stiffness_n_m: &[f64], p: usize) {
    if stiffness_n_m.len() != 1 && stiffness_n_m.len() != p {
        v.push(
            "contact.stiffness_n_m",
            format!("{} values", stiffness_n_m.len()),
            &format!("one stiffness for all points or {p} (one per point)"),
        );
    }
    for (i, &k) in stiffness_n_m.iter().enumerate() {
        if !(k.is_finite() && k > 0.0 && k <= MAX_TREAD_STIFFNESS_N_M) {
            v.push(
                &format!("contact.stiffness_n_m[{i}]"),
                k,
                &format!("a tread stiffness > 0 and <= {MAX_TREAD_STIFFNESS_N_M:e} N/m"),
            );
        }
    }
}

fn validate_road(v: &mut Validator, road: &Road) {
    match road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => {
            if v.nonneg("road.amplitude_m", *amplitude_m, "an amplitude >= 0 m")
                && *amplitude_m > 1.0
            {
                v.push("road.amplitude_m", *amplitude_m, "an amplitude <= 1 m");
            }
            v.positive("road.wavelength_m", *wavelength_m, "a wavelength > 0 m");
        }
        Road::Harmonics { components } => {
            if components.is_empty() {
                v.push("road.components", "[]", "at least one harmonic");
            }
            for (k, c) in components.iter().enumerate() {
                v.finite(
                    &format!("road.components[{k}].amplitude_m"),
                    c.amplitude_m,
                    "a finite amplitude in m",
                );
                v.positive(
                    &format!("road.components[{k}].wavelength_m"),
                    c.wavelength_m,
                    "a wavelength > 0 m",
                );
                v.finite(
                    &format!("road.components[{k}].phase_rad"),
                    c.phase_rad,
                    "a finite phase in rad",
                );
            }
        }
        Road::Measured { file, .. } => {
            if file.as_os_str().is_empty() {
                v.push("road.file", "\"\"", "the path of a CSV of `x_m, z_m` rows");
            }
        }
        Road::Random { .. } => v.errors.extend(road.random_errors("road")),
        Road::Surface { file, .. } => {
            if file.as_os_str().is_empty() {
                v.push(
                    "road.file",
                    "\"\"",
                    "the path of a CSV of `x_m,y_m,z_m` rows (a height grid)",
                );
            }
        }
        Road::Crg {
            file,
            u_start_m,
            v_offset_m,
        } => {
            if file.as_os_str().is_empty() {
                v.push("road.file", "\"\"", "the path of an OpenCRG (.crg) file");
            }
            if let Some(u) = u_start_m {
                v.finite(
                    "road.u_start_m",
                    *u,
                    "a finite position along the road in m",
                );
            }
            v.finite(
                "road.v_offset_m",
                *v_offset_m,
                "a finite position across the road in m",
            );
        }
        Road::Texture { .. } => v.errors.extend(road.texture_errors("road")),
    }
}

/// A value as shown in a [`FieldError`]: numbers through [`fmt_num`].
trait ValueText {
    fn text(&self) -> String;
}

impl ValueText for f64 {
    fn text(&self) -> String {
        fmt_num(*self)
    }
}

impl ValueText for &str {
    fn text(&self) -> String {
        self.to_string()
    }
}

impl ValueText for String {
    fn text(&self) -> String {
        self.clone()
    }
}

#[derive(Default)]
struct Validator {
    errors: Vec<FieldError>,
}

impl Validator {
    fn push(&mut self, field: &str, value: impl ValueText, expected: &str) {
        self.errors.push(FieldError {
            field: field.to_string(),
            value: value.text(),
            expected: expected.to_string(),
        });
    }
    fn finite(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !x.is_finite() {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn nonneg(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !(x.is_finite() && x >= 0.0) {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn positive(&mut self, field: &str, x: f64, expected: &str) -> bool {
        if !(x.is_finite() && x > 0.0) {
            self.push(field, x, expected);
            return false;
        }
        true
    }
    fn finish(self) -> Result<(), Vec<FieldError>> {
        if self.errors.is_empty() {
            Ok(())
        } else {
            Err(self.errors)
        }
    }
}
