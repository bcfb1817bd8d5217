//! The contact patch over time (`run --patch-summary`, `--patch-frames`):
//! the total contact force, the contact area and the force per row along
//! the rolling direction, and heat maps of the force over the patch.
//!
//! Rows are the points sharing one `y` (a grid's rows across); the cell of
//! a point is `Δx Δy`, the spacings of a [`tirecontact_io::scene::PointGrid`] or, for
//! a list, the smallest spacing along within a row and between rows. The
//! contact area at a step is the number of points carrying force (a
//! contact force above 0 N in the step) times the cell: a point that only
//! touches the road without load, as every point does while the preload
//! is ramped in from 0, is not counted ([`carrying_points`]).

use crate::output::figures::FigureError;
#[cfg(feature = "figures")]
use plotters::prelude::*;
use std::io::Write;
use std::path::{Path, PathBuf};
use tirecontact_core::base::error::count;
use tirecontact_core::solver::drive::Probe;
use tirecontact_core::solver::problem::RunShape;
use tirecontact_core::solver::simulation::Simulation;

/// Why a scene's points do not make a patch.
#[derive(Debug, thiserror::Error)]
pub enum PatchError {
    #[error(
        "the scene's {} {} in {} across the tread and at most {} along it: a patch needs at least 2 rows across (points at different positions y) and 2 points along",
        count(*points, "point"),
        if *points == 1 { "lies" } else { "lie" },
        count(*rows, "row"),
        count(*along, "point")
    )]
    NotAPatch {
        points: usize,
        rows: usize,
        along: usize,
    },
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error(transparent)]
    Figure(#[from] FigureError),
}

/// The patch's rows and cells.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchLayout {
    /// `y` of each row (m), increasing.
    pub rows_y_m: Vec<f64>,
    /// The row of each point.
    pub row_of_point: Vec<usize>,
    /// `Δx`, `Δy` (m).
    pub cell_m: (f64, f64),
    /// The points' `(x, y)` (m).
    pub xy_m: Vec<(f64, f64)>,
}

impl PatchLayout {
    /// The layout of `scene`'s points.
    pub fn of(scene: &impl RunShape) -> Result<Self, PatchError> {
        let xy_m: Vec<(f64, f64)> = scene.points().iter().map(|p| (p.x_m, p.y_m)).collect();
        let mut rows_y_m: Vec<f64> = xy_m.iter().map(|p| p.1).collect();
        rows_y_m.sort_by(f64::total_cmp);
        rows_y_m.dedup();
        let row_of_point: Vec<usize> = xy_m
            .iter()
            .map(|p| rows_y_m.partition_point(|&y| y < p.1))
            .collect();
        let mut along_max = 0;
        let mut dx = f64::INFINITY;
        for r in 0..rows_y_m.len() {
            let mut xs: Vec<f64> = (0..xy_m.len())
                .filter(|&i| row_of_point[i] == r)
                .map(|i| xy_m[i].0)
                .collect();
            xs.sort_by(f64::total_cmp);
            along_max = along_max.max(xs.len());
            for w in xs.windows(2) {
                if w[1] > w[0] {
                    dx = dx.min(w[1] - w[0]);
                }
            }
        }
        let dy = rows_y_m
            .windows(2)
            .map(|w| w[1] - w[0])
            .fold(f64::INFINITY, f64::min);
        if rows_y_m.len() < 2 || along_max < 2 {
            return Err(PatchError::NotAPatch {
                points: xy_m.len(),
                rows: rows_y_m.len(),
                along: along_max,
            });
        }
        let cell_m = scene.grid_spacing_m().unwrap_or((dx, dy));
        Ok(PatchLayout {
            rows_y_m,
            row_of_point,
            cell_m,
            xy_m,
        })
    }

    /// The patch's extent, its points' cells included: `(x0, x1, y0, y1)` (m).
    pub fn extent_m(&self) -> (f64, f64, f64, f64) {
        let (dx, dy) = self.cell_m;
        self.xy_m.iter().fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(x0, x1, y0, y1), &(x, y)| {
                (
                    x0.min(x - 0.5 * dx),
                    x1.max(x + 0.5 * dx),
                    y0.min(y - 0.5 * dy),
                    y1.max(y + 0.5 * dy),
                )
            },
        )
    }

    /// The contact area (m²) of the points' `forces_n` (N): the points
    /// carrying force times the cell ([`carrying_points`]).
    pub fn contact_area_m2(&self, forces_n: &[f64]) -> f64 {
        carrying_points(forces_n) as f64 * self.cell_area_m2()
    }

    /// The area of one point's cell (m²).
    pub fn cell_area_m2(&self) -> f64 {
        self.cell_m.0 * self.cell_m.1
    }
}

/// Records the patch at every `every`-th step, and the forces at the
/// heat-map frames' steps.
#[derive(Debug, Clone)]
pub struct PatchRecorder {
    pub layout: PatchLayout,
    every: u64,
    /// Times of the recorded steps (s).
    pub t_s: Vec<f64>,
    /// Total contact force (N), the step's mean.
    pub total_n: Vec<f64>,
    /// Contact area (m²) at the step's end.
    pub area_m2: Vec<f64>,
    /// Force per row (N), row-major per recorded step.
    pub rows_n: Vec<f64>,
    /// Steps of the heat-map frames, increasing, and their forces.
    frame_steps: Vec<u64>,
    pub frames: Vec<(f64, Vec<f64>)>,
}

impl PatchRecorder {
    /// Records every `every` steps (>= 1) and `frames` heat maps evenly
    /// over the run (0: none).
    pub fn new(scene: &impl RunShape, every: u64, frames: usize) -> Result<Self, PatchError> {
        let layout = PatchLayout::of(scene)?;
        let n = scene.num_steps();
        let frame_steps = (1..=frames as u64)
            .map(|k| (k * n / frames.max(1) as u64).max(1))
            .collect();
        Ok(PatchRecorder {
            layout,
            every: every.max(1),
            t_s: Vec::new(),
            total_n: Vec::new(),
            area_m2: Vec::new(),
            rows_n: Vec::new(),
            frame_steps,
            frames: Vec::new(),
        })
    }

    /// Writes the CSV: `t_s, total_force_n, contact_area_m2` and one
    /// column of force per row, `row_force_n[y_m=…]`.
    pub fn write_csv(&self, out: &mut impl Write) -> std::io::Result<()> {
        write!(out, "t_s,total_force_n,contact_area_m2")?;
        for y in &self.layout.rows_y_m {
            write!(
                out,
                ",row_force_n[y_m={}]",
                tirecontact_core::base::error::fmt_num(*y)
            )?;
        }
        writeln!(out)?;
        let nr = self.layout.rows_y_m.len();
        for (k, t) in self.t_s.iter().enumerate() {
            write!(out, "{t:e},{:e},{:e}", self.total_n[k], self.area_m2[k])?;
            for f in &self.rows_n[k * nr..(k + 1) * nr] {
                write!(out, ",{f:e}")?;
            }
            writeln!(out)?;
        }
        Ok(())
    }

    /// Writes the CSV atomically at `path`.
    pub fn save_csv(&self, path: &Path) -> Result<(), PatchError> {
        let mut buf = Vec::new();
        self.write_csv(&mut buf).map_err(|source| PatchError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        tirecontact_io::fsio::write_atomic(path, &buf).map_err(|source| PatchError::Io {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Writes the heat maps `patch_0000.png`, … into `dir` (created), on one
    /// colour scale; returns their number.
    #[cfg(feature = "figures")]
    pub fn save_frames(
        &self,
        dir: &Path,
        title: &str,
        size: (u32, u32),
    ) -> Result<usize, PatchError> {
        std::fs::create_dir_all(dir).map_err(|source| PatchError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
        let max_n = self
            .frames
            .iter()
            .flat_map(|(_, f)| f.iter().copied())
            .fold(0.0, f64::max);
        for (k, (t, forces)) in self.frames.iter().enumerate() {
            let path = dir.join(format!("patch_{k:04}.png"));
            render_heat_map(
                &self.layout,
                forces,
                max_n,
                &format!("{title}: t = {t:.4} s"),
                &path,
                size,
            )?;
        }
        Ok(self.frames.len())
    }
}

/// The points counted in the contact area: those whose contact force is
/// above 0 N.
pub fn carrying_points(forces_n: &[f64]) -> usize {
    forces_n.iter().filter(|&&f| f > 0.0).count()
}

impl Probe for PatchRecorder {
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        let step = sim.steps();
        let q = sim.force_n();
        if step.is_multiple_of(self.every) {
            let nr = self.layout.rows_y_m.len();
            let base = self.rows_n.len();
            self.rows_n.resize(base + nr, 0.0);
            let mut total = 0.0;
            for (i, &f) in q.iter().enumerate() {
                total += f;
                self.rows_n[base + self.layout.row_of_point[i]] += f;
            }
            self.t_s.push(sim.time_s());
            self.total_n.push(total);
            self.area_m2.push(self.layout.contact_area_m2(q));
        }
        if self.frames.len() < self.frame_steps.len() && step >= self.frame_steps[self.frames.len()]
        {
            self.frames.push((sim.time_s(), q.to_vec()));
        }
        Ok(())
    }
}

/// A colour of the scale from white (0 N) through yellow and orange to dark
/// red (`max`), readable in grey scale (lightness falls monotonically).
#[cfg(feature = "figures")]
pub fn force_colour(f: f64, max: f64) -> RGBColor {
    let s = if max > 0.0 {
        (f / max).clamp(0.0, 1.0)
    } else {
        0.0
    };
    // white, yellow, orange, red, dark red
    let stops = [
        (255.0, 255.0, 255.0),
        (255.0, 230.0, 90.0),
        (245.0, 140.0, 30.0),
        (200.0, 30.0, 20.0),
        (90.0, 0.0, 10.0),
    ];
    let u = s * (stops.len() - 1) as f64;
    let k = (u.floor() as usize).min(stops.len() - 2);
    let w = u - k as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * w).round() as u8;
    RGBColor(
        mix(stops[k].0, stops[k + 1].0),
        mix(stops[k].1, stops[k + 1].1),
        mix(stops[k].2, stops[k + 1].2),
    )
}

/// A heat map of `forces` (N) over the patch, axes in mm, a colour bar in N
/// from 0 to `max_n`.
#[cfg(feature = "figures")]
pub fn render_heat_map(
    layout: &PatchLayout,
    forces: &[f64],
    max_n: f64,
    title: &str,
    path: &Path,
    (width, height): (u32, u32),
) -> Result<(), PatchError> {
    let err = |e: &dyn std::fmt::Display| FigureError::Draw {
        path: path.display().to_string(),
        message: e.to_string(),
    };
    #[cfg(target_arch = "wasm32")]
    return {
        let _ = (layout, forces, max_n, title, width, height);
        Err(err(&"a page in the browser writes no files").into())
    };
    #[cfg(not(target_arch = "wasm32"))]
    draw_heat_map(layout, forces, max_n, title, path, (width, height)).map_err(|e| err(&e).into())
}

/// [`render_heat_map`]'s drawing (plotters' file backend).
#[cfg(all(feature = "figures", not(target_arch = "wasm32")))]
fn draw_heat_map(
    layout: &PatchLayout,
    forces: &[f64],
    max_n: f64,
    title: &str,
    path: &Path,
    (width, height): (u32, u32),
) -> Result<(), Box<dyn std::error::Error>> {
    crate::output::figures::register_fonts();
    let err = |e: &dyn std::fmt::Display| -> Box<dyn std::error::Error> { e.to_string().into() };
    let (dx, dy) = layout.cell_m;
    let mm = 1e3;
    let (x0, x1, y0, y1) = layout.extent_m();
    let root = BitMapBackend::new(path, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let bar_w = (width / 9).max(90);
    let (map_area, bar_area) = root.split_horizontally(width - bar_w);
    let font = ("sans-serif", (height / 28).clamp(12, 28)).into_font();
    let mut chart = ChartBuilder::on(&map_area)
        .caption(title, font.clone())
        .margin(12)
        .x_label_area_size(height / 12)
        .y_label_area_size(width / 12)
        .build_cartesian_2d(x0 * mm..x1 * mm, y0 * mm..y1 * mm)
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("along the rolling direction x (mm)")
        .y_desc("across the tread y (mm)")
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| tick(*v))
        .label_style(font.clone())
        .axis_desc_style(font.clone())
        .draw()
        .map_err(|e| err(&e))?;
    chart
        .draw_series(layout.xy_m.iter().zip(forces).map(|(&(x, y), &f)| {
            Rectangle::new(
                [
                    ((x - 0.5 * dx) * mm, (y - 0.5 * dy) * mm),
                    ((x + 0.5 * dx) * mm, (y + 0.5 * dy) * mm),
                ],
                force_colour(f, max_n).filled(),
            )
        }))
        .map_err(|e| err(&e))?;
    // every cell outlined, so that the patch shows where no force is
    chart
        .draw_series(layout.xy_m.iter().map(|&(x, y)| {
            Rectangle::new(
                [
                    ((x - 0.5 * dx) * mm, (y - 0.5 * dy) * mm),
                    ((x + 0.5 * dx) * mm, (y + 0.5 * dy) * mm),
                ],
                RGBColor(200, 200, 200).stroke_width(1),
            )
        }))
        .map_err(|e| err(&e))?;
    // the colour bar, 0 N at the bottom
    let top = max_n.max(1e-12);
    let mut bar = ChartBuilder::on(&bar_area)
        .margin_top(height / 7)
        .margin_bottom(height / 8)
        .margin_right(8)
        .y_label_area_size(bar_w * 11 / 20)
        .caption("force (N)", font.clone())
        .build_cartesian_2d(0.0..1.0, 0.0..top)
        .map_err(|e| err(&e))?;
    bar.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_labels(6)
        .y_label_formatter(&|v| tick(*v))
        .label_style(font.clone())
        .draw()
        .map_err(|e| err(&e))?;
    let steps = 100;
    bar.draw_series((0..steps).map(|k| {
        let (a, b) = (
            k as f64 / steps as f64 * top,
            (k + 1) as f64 / steps as f64 * top,
        );
        Rectangle::new(
            [(0.0, a), (1.0, b)],
            force_colour(0.5 * (a + b), top).filled(),
        )
    }))
    .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// A tick label: no trailing zeros ("40", "2.5", "0.25").
#[cfg(all(feature = "figures", not(target_arch = "wasm32")))]
fn tick(v: f64) -> String {
    let s = format!("{v:.3}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.to_string() }
}

#[cfg(all(test, feature = "figures"))]
mod tests {
    use super::*;

    #[test]
    fn the_colour_scale_darkens_monotonically() {
        let lum = |c: RGBColor| 0.2126 * c.0 as f64 + 0.7152 * c.1 as f64 + 0.0722 * c.2 as f64;
        let mut last = f64::INFINITY;
        for k in 0..=50 {
            let l = lum(force_colour(k as f64, 50.0));
            assert!(l < last, "step {k}: {l} after {last}");
            last = l;
        }
        assert_eq!(force_colour(-1.0, 10.0), RGBColor(255, 255, 255));
        assert_eq!(force_colour(5.0, 0.0), RGBColor(255, 255, 255));
    }
}

#[cfg(test)]
mod area_tests {
    use super::*;
    use tirecontact_io::Scene;
    use tirecontact_io::SceneSimulation;

    /// The area is the points carrying force times the cell at every step,
    /// none without force (before the first step every point is on the
    /// road, at 0 N); while the preload ramps in from 0 the points touching
    /// the road carry little force, and count.
    #[test]
    fn the_contact_area_counts_the_points_carrying_force() {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/patch_chip_seal.ron"
        )))
        .unwrap();
        scene.duration_s = 200.0 * scene.dt_s;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut rec = PatchRecorder::new(&scene, 1, 0).unwrap();
        let cell = rec.layout.cell_area_m2();
        assert_eq!(rec.layout.contact_area_m2(sim.force_n()), 0.0, "at rest");
        let mut loaded = false;
        while !sim.finished() {
            sim.step().unwrap();
            rec.after_step(&sim).unwrap();
            let k = rec.area_m2.len() - 1;
            let carrying = sim.force_n().iter().filter(|&&f| f > 0.0).count();
            assert_eq!(rec.area_m2[k], carrying as f64 * cell, "step {k}");
            if rec.total_n[k] == 0.0 {
                assert_eq!(rec.area_m2[k], 0.0, "step {k}: area without force");
            } else {
                loaded = true;
            }
        }
        assert!(loaded, "no force in 200 steps");
        assert_eq!(carrying_points(&[0.0, 1.0, -0.0, 2.5]), 2);
    }

    /// Points on one line are no patch: said in words, singular and plural
    /// right, without the format's field names.
    #[test]
    fn a_line_of_points_is_refused_in_words() {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        let e = PatchLayout::of(&scene).unwrap_err().to_string();
        assert!(
            e.starts_with(
                "the scene's 3 points lie in 1 row across the tread and at most 3 points along it:"
            ),
            "{e}"
        );
        scene.points.truncate(1);
        let e = PatchLayout::of(&scene).unwrap_err().to_string();
        assert!(
            e.starts_with(
                "the scene's 1 point lies in 1 row across the tread and at most 1 point along it:"
            ),
            "{e}"
        );
        assert!(!e.contains("(s)") && !e.contains("y_m"), "{e}");
    }
}
