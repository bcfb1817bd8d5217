//! Animation frames of the scene view for slides: numbered PNGs
//! `frame_00000.png`, … of the road moving under the contact line and the
//! displaced points coloured by contact state, with the contact phase of each
//! point written above it. Drawn headlessly with plotters (no GPU, no egui),
//! by re-running the scene from t = 0: the frames hold exactly the run.
//!
//! Frame `k` shows simulated time `t0 + k / (fps × slow_motion)`: with
//! `slow_motion = 20`, one second of video shows 50 ms of the run. There are
//! `round((t1 - t0) × slow_motion × fps)` frames.

use super::figures::register_fonts;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use tirecontact_core::Simulation;
use tirecontact_core::model::road::Road;
use tirecontact_core::model::road::ramp;
use tirecontact_core::solver::drive::{Probe, Watch, run_to_end};
use tirecontact_core::solver::error::RunError;
use tirecontact_core::solver::phase::{ContactPhase, PhaseTracker};

/// Most frames one export may write.
pub const MAX_FRAMES: u64 = 100_000;

/// What plotters reports when a frame cannot be drawn.
pub type DrawError = DrawingAreaErrorKind<<BitMapBackend<'static> as DrawingBackend>::ErrorType>;

/// Why frames cannot be exported: a setting (its field, value and what was
/// expected), the folder, a frame that cannot be drawn or written, or the
/// run that drives the export.
#[derive(Debug, thiserror::Error)]
pub enum FramesError {
    /// A field of [`FrameSettings`] out of range.
    #[error("{field} = {value}: expected {expected}")]
    Setting {
        field: &'static str,
        value: f64,
        expected: String,
    },
    #[error("(t1 - t0) × slow_motion × fps = {frames} frames: expected 1..={MAX_FRAMES}")]
    FrameCount { frames: u64 },
    /// The folder holds frames of an earlier export.
    #[error(
        "{} already holds {count} frames of an earlier export (frame_*.png): expected a new or empty folder, or the old frames cleared",
        .dir.display()
    )]
    OldFrames {
        /// The folder, absolute.
        dir: PathBuf,
        count: usize,
    },
    /// A file or the folder could not be removed, created or written.
    #[error("{}: {source}", .path.display())]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    #[error("{}: {source}", .path.display())]
    Draw {
        path: PathBuf,
        #[source]
        source: DrawError,
    },
    #[error("{}: frame buffer of {width}x{height} px", .path.display())]
    Buffer {
        path: PathBuf,
        width: u32,
        height: u32,
    },
    #[error("{}: {source}", .path.display())]
    Image {
        path: PathBuf,
        #[source]
        source: image::ImageError,
    },
    /// The export's cancel flag was set.
    #[error("cancelled after {done} of {total} frames")]
    Cancelled { done: u64, total: u64 },
    /// The run that drives the export stopped (a step that cannot be
    /// solved).
    #[error(transparent)]
    Run(RunError),
}

/// A frames export that stopped: its own error when a frame stopped it
/// (a cancel, a frame that cannot be written), else the run's.
impl From<RunError> for FramesError {
    fn from(e: RunError) -> Self {
        match e {
            RunError::Output(io) => io
                .downcast::<FramesError>()
                .unwrap_or_else(|io| FramesError::Run(RunError::Output(io))),
            e => FramesError::Run(e),
        }
    }
}

/// What to export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameSettings {
    /// First frame's simulated time (s).
    pub t0_s: f64,
    /// End of the interval (s), exclusive.
    pub t1_s: f64,
    /// Frames per second of the video (Hz).
    pub fps: f64,
    /// Video seconds per simulated second (1 = real time, 20 = 0.05x).
    pub slow_motion: f64,
    pub width: u32,
    pub height: u32,
}

impl FrameSettings {
    /// Number of frames: `round((t1 - t0) × slow_motion × fps)`.
    pub fn frame_count(&self) -> u64 {
        let n = ((self.t1_s - self.t0_s) * self.slow_motion * self.fps).round();
        if n.is_finite() && n > 0.0 {
            n as u64
        } else {
            0
        }
    }

    /// Simulated time between frames (s).
    pub fn frame_dt_s(&self) -> f64 {
        1.0 / (self.fps * self.slow_motion)
    }

    /// Simulated time of frame `k` (s).
    pub fn frame_time_s(&self, k: u64) -> f64 {
        self.t0_s + k as f64 * self.frame_dt_s()
    }

    /// Refuses settings that cannot be exported, naming field, value and expectation.
    pub fn check(&self, duration_s: f64) -> Result<(), FramesError> {
        let bad = |field: &'static str, value: f64, expected: &str| {
            Err(FramesError::Setting {
                field,
                value,
                expected: expected.to_string(),
            })
        };
        if !(self.fps.is_finite() && self.fps > 0.0 && self.fps <= 240.0) {
            return bad("fps", self.fps, "a frame rate in (0, 240] Hz");
        }
        if !(self.slow_motion.is_finite() && self.slow_motion > 0.0 && self.slow_motion <= 1e6) {
            return bad(
                "slow_motion",
                self.slow_motion,
                "video seconds per simulated second in (0, 1e6]",
            );
        }
        if !(self.t0_s.is_finite() && self.t0_s >= 0.0) {
            return bad("t0_s", self.t0_s, "a start time >= 0 s");
        }
        if !(self.t1_s.is_finite() && self.t1_s > self.t0_s && self.t1_s <= duration_s + 1e-12) {
            return bad(
                "t1_s",
                self.t1_s,
                &format!(
                    "an end time after t0 = {} s and at most the scene's duration {duration_s} s",
                    self.t0_s
                ),
            );
        }
        for (f, v) in [("width", self.width), ("height", self.height)] {
            if !(200..=4000).contains(&v) {
                return bad(f, f64::from(v), "200..=4000 px");
            }
        }
        let n = self.frame_count();
        if n == 0 || n > MAX_FRAMES {
            return Err(FramesError::FrameCount { frames: n });
        }
        Ok(())
    }
}

/// The road as the tyre sees it at the simulation's time, `n + 1` points
/// `[x (m), height (m)]` over `[x0, x1]`: `w z(x + rolled) + (1 − w) h(x)`,
/// the ramp weight `w` blending the point heights `h` (interpolated between
/// the points) into the road profile `z` (shared by the scene view and the
/// animation frames; positions off a measured profile are left out).
pub fn road_in_tyre_frame(sim: &Simulation, x0: f64, x1: f64, n: usize) -> Vec<[f64; 2]> {
    road_in_tyre_frame_at(sim, x0, x1, n, None)
}

/// [`road_in_tyre_frame`] under one row across the tread (`row_y_m`): the
/// road surface at that `y` ([`RoadProfile::sample_at`]) and the heights
/// of that row's points (`None`: the centreline `y = 0` and every point).
///
/// [`RoadProfile::sample_at`]: tirecontact_core::model::road::RoadProfile::sample_at
pub fn road_in_tyre_frame_at(
    sim: &Simulation,
    x0: f64,
    x1: f64,
    n: usize,
    row_y_m: Option<f64>,
) -> Vec<[f64; 2]> {
    let scene = sim.problem();
    let (w, _) = ramp(sim.time_s(), scene.ramp_s);
    let mut sorted: Vec<(f64, f64)> = scene
        .points
        .iter()
        .filter(|p| row_y_m.is_none_or(|y| p.y_m == y))
        .map(|p| (p.x_m, p.h_m))
        .collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let h_at = |x: f64| -> f64 {
        match sorted.iter().position(|p| p.0 >= x) {
            None => sorted.last().map_or(0.0, |p| p.1),
            Some(0) => sorted[0].1,
            Some(k) => {
                let (a, b) = (sorted[k - 1], sorted[k]);
                a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0)
            }
        }
    };
    let n = n.max(1);
    (0..=n)
        .filter_map(|k| {
            let x = x0 + (x1 - x0) * k as f64 / n as f64;
            let z = match row_y_m {
                Some(y) => sim.road_profile().sample_at(x + sim.rolled_m(), y),
                None => sim.road_profile().sample(x + sim.rolled_m()),
            }
            .ok()?
            .0;
            Some([x, w * z + (1.0 - w) * h_at(x)])
        })
        .collect()
}

/// Path of frame `k` in `dir`.
pub fn frame_path(dir: &Path, k: u64) -> PathBuf {
    dir.join(format!("frame_{k:05}.png"))
}

const ROAD: RGBColor = RGBColor(140, 86, 75);
const CONTACT: RGBColor = RGBColor(0, 158, 115);
const FLIGHT: RGBColor = RGBColor(213, 94, 0);
const EVENT: RGBColor = RGBColor(204, 0, 102);

/// Each frame is drawn this many times wider and higher, then scaled down:
/// plotters draws lines without antialiasing, and the sloped road line of
/// a frame drawn at its size was a staircase.
pub const SUPERSAMPLE: u32 = 2;

/// Draws the current state of `sim` as one PNG at `path`, `width × height`
/// px (drawn at [`SUPERSAMPLE`] times the size and filtered down).
fn draw_frame(
    sim: &Simulation,
    phases: &PhaseTracker,
    ext: &Extents,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<(), FramesError> {
    let draw = |source| FramesError::Draw {
        path: path.to_path_buf(),
        source,
    };
    let (w, h) = (width * SUPERSAMPLE, height * SUPERSAMPLE);
    let mut rgb = vec![0u8; w as usize * h as usize * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_frame_on(&root, sim, phases, ext, w, h).map_err(draw)?;
        root.present().map_err(draw)?;
    }
    let big = image::RgbImage::from_raw(w, h, rgb).ok_or_else(|| FramesError::Buffer {
        path: path.to_path_buf(),
        width: w,
        height: h,
    })?;
    let small = image::imageops::resize(&big, width, height, image::imageops::FilterType::Triangle);
    small.save(path).map_err(|source| FramesError::Image {
        path: path.to_path_buf(),
        source,
    })
}

/// The chart of a frame: linear x (m) and height (mm) axes.
type FrameChart<'a, 'b> = ChartContext<
    'a,
    BitMapBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// Sizes (px) of a frame's text, marks and lines: `s` px at 720 px (the
/// frame's smaller side), times `scale`.
fn px(scale: f64) -> impl Fn(f64) -> i32 + Copy {
    move |s: f64| (s * scale).round() as i32
}

/// The row across the tread drawn in full in a frame, where the points
/// form several rows (distinct `y_m`, a patch): the one nearest the
/// centreline (the first of two as near). `None` for a single row, drawn
/// whole. The other rows are drawn small and grey, without labels, as the
/// visualiser's scene view draws the rows it does not show in full.
pub fn drawn_row_y_m(points: &[tirecontact_core::solver::problem::Point]) -> Option<f64> {
    let mut rows: Vec<f64> = points.iter().map(|p| p.y_m).collect();
    rows.sort_by(f64::total_cmp);
    rows.dedup();
    if rows.len() < 2 {
        return None;
    }
    rows.into_iter().min_by(|a, b| a.abs().total_cmp(&b.abs()))
}

/// Draws the current state of `sim` on `root` (`width × height` px).
fn draw_frame_on(
    root: &DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>,
    sim: &Simulation,
    phases: &PhaseTracker,
    ext: &Extents,
    width: u32,
    height: u32,
) -> Result<(), DrawError> {
    register_fonts();
    let scene = sim.problem();
    let t = sim.time_s();
    let scale = (f64::from(height.min(width)) / 720.0).clamp(0.5, 4.0);
    let fs = px(scale);
    root.fill(&WHITE)?;
    let row = ext.row_y_m;
    let row_text = row.map_or(String::new(), |y| {
        format!(", row y = {:.0} mm (the others grey)", y * 1e3)
    });
    let caption = format!(
        "{} — t = {:.4} s, V = {:.1} km/h{row_text}",
        scene.name,
        t,
        scene.speed_mps * 3.6
    );
    let mut chart = ChartBuilder::on(root)
        .caption(caption, ("sans-serif", fs(26.0)))
        .margin(fs(12.0))
        .x_label_area_size(fs(55.0))
        .y_label_area_size(fs(80.0))
        .build_cartesian_2d(ext.x0..ext.x1, ext.y0_mm..ext.y1_mm)?;
    chart
        .configure_mesh()
        .x_desc("position along the contact line x (m)")
        .y_desc("height (mm)")
        .label_style(("sans-serif", fs(18.0)))
        .axis_desc_style(("sans-serif", fs(20.0)))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    draw_road(&mut chart, sim, ext, row, scale)?;
    let disp = draw_tyre(&mut chart, sim, row, scale)?;
    draw_points(&mut chart, sim, &disp, scale)?;
    draw_phase_labels(&mut chart, phases, t, &disp, ext, height, scale)?;
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .legend_area_size(fs(30.0))
        .label_font(("sans-serif", fs(18.0)))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()?;
    Ok(())
}

/// The road under the tyre ([`road_in_tyre_frame_at`], under the row
/// drawn in full), filled down to the bottom of the frame.
fn draw_road(
    chart: &mut FrameChart<'_, '_>,
    sim: &Simulation,
    ext: &Extents,
    row_y_m: Option<f64>,
    scale: f64,
) -> Result<(), DrawError> {
    let fs = px(scale);
    let road: Vec<(f64, f64)> = road_in_tyre_frame_at(sim, ext.x0, ext.x1, 600, row_y_m)
        .into_iter()
        .map(|[x, y]| (x, 1e3 * y))
        .collect();
    let floor = ext.y0_mm;
    chart.draw_series(std::iter::once(Polygon::new(
        road.iter()
            .copied()
            .chain([(ext.x1, floor), (ext.x0, floor)])
            .collect::<Vec<_>>(),
        ROAD.mix(0.25).filled(),
    )))?;
    chart
        .draw_series(LineSeries::new(road, ROAD.stroke_width(fs(3.0) as u32)))?
        .label("road (moving left)")
        .legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + fs(20.0), y)],
                ROAD.stroke_width(fs(3.0) as u32),
            )
        });
    Ok(())
}

/// The tyre's contact line, undeformed and displaced: the row drawn in
/// full (all the points of a single row), the other rows' points small and
/// grey. Returns the displaced points of that row `(x (m), height (mm),
/// index)`, by position.
fn draw_tyre(
    chart: &mut FrameChart<'_, '_>,
    sim: &Simulation,
    row_y_m: Option<f64>,
    scale: f64,
) -> Result<Vec<(f64, f64, usize)>, DrawError> {
    let fs = px(scale);
    let scene = sim.problem();
    let in_row = |y: f64| row_y_m.is_none_or(|r| y == r);
    let u = sim.displacement_m();
    // the other rows: small grey points under the row drawn in full
    chart.draw_series(
        scene
            .points
            .iter()
            .zip(u)
            .filter(|(p, _)| !in_row(p.y_m))
            .map(|(p, u)| {
                Circle::new((p.x_m, 1e3 * (p.h_m + u)), fs(4.0), BLACK.mix(0.3).filled())
            }),
    )?;
    let mut und: Vec<(f64, f64)> = scene
        .points
        .iter()
        .filter(|p| in_row(p.y_m))
        .map(|p| (p.x_m, 1e3 * p.h_m))
        .collect();
    und.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(LineSeries::new(und, BLACK.mix(0.4).stroke_width(1)))?
        .label("undeformed tyre")
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + fs(20.0), y)], BLACK.mix(0.4)));
    let mut disp: Vec<(f64, f64, usize)> = scene
        .points
        .iter()
        .zip(u)
        .enumerate()
        .filter(|(_, (p, _))| in_row(p.y_m))
        .map(|(i, (p, u))| (p.x_m, 1e3 * (p.h_m + u), i))
        .collect();
    disp.sort_by(|a, b| a.0.total_cmp(&b.0));
    chart
        .draw_series(LineSeries::new(
            disp.iter().map(|d| (d.0, d.1)),
            RGBColor(60, 60, 60).stroke_width(fs(2.0) as u32),
        ))?
        .label("tyre (displaced)")
        .legend(move |(x, y)| {
            PathElement::new(
                vec![(x, y), (x + fs(20.0), y)],
                RGBColor(60, 60, 60).stroke_width(fs(2.0) as u32),
            )
        });
    Ok(disp)
}

/// The displaced points `disp`, coloured by contact state.
fn draw_points(
    chart: &mut FrameChart<'_, '_>,
    sim: &Simulation,
    disp: &[(f64, f64, usize)],
    scale: f64,
) -> Result<(), DrawError> {
    let fs = px(scale);
    let contact = sim.in_contact();
    let r = fs(9.0);
    for (on, name, color) in [(true, "in contact", CONTACT), (false, "in flight", FLIGHT)] {
        chart
            .draw_series(
                disp.iter()
                    .filter(|d| contact.get(d.2).copied().unwrap_or(false) == on)
                    .map(|d| Circle::new((d.0, d.1), r, color.filled())),
            )?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + fs(10.0), y), fs(6.0), color.filled()));
    }
    Ok(())
}

/// Most points of the drawn row labelled one by one in a frame; a row of
/// more gets one line of counts per phase ([`phase_counts`]).
pub const MAX_LABELLED_POINTS: usize = 6;

/// `"1 IMPACT · 12 in contact · 3 free flight"`: how many points are in
/// each phase, in the order and words of the visualiser's phase strip
/// ([`ContactPhase::ALL`], [`ContactPhase::shown`]), those with none left
/// out.
pub fn phase_counts(phases: impl Iterator<Item = ContactPhase>) -> String {
    let mut n = [0usize; 4];
    for ph in phases {
        if let Some(k) = ContactPhase::ALL.iter().position(|&o| o == ph) {
            n[k] += 1;
        }
    }
    ContactPhase::ALL
        .iter()
        .zip(n)
        .filter(|(_, c)| *c > 0)
        .map(|(ph, c)| format!("{c} {}", ph.shown()))
        .collect::<Vec<_>>()
        .join(" · ")
}

/// Each point's contact phase at time `t`, written above it: events in
/// capitals. With several points the labels go above the highest point, in
/// lanes of text height by point index (i % 3), so that close neighbours'
/// labels do not overlap; with more than [`MAX_LABELLED_POINTS`], one line
/// of counts per phase instead.
fn draw_phase_labels(
    chart: &mut FrameChart<'_, '_>,
    phases: &PhaseTracker,
    t: f64,
    disp: &[(f64, f64, usize)],
    ext: &Extents,
    height: u32,
    scale: f64,
) -> Result<(), DrawError> {
    let fs = px(scale);
    let top = disp.iter().map(|d| d.1).fold(f64::NEG_INFINITY, f64::max);
    let plot_px = (f64::from(height) - f64::from(fs(26.0 + 55.0 + 24.0))).max(50.0);
    let lane = (ext.y1_mm - ext.y0_mm) * f64::from(fs(30.0)) / plot_px;
    if disp.len() > MAX_LABELLED_POINTS {
        // one line of counts per phase over the row (the points' colours
        // say which is which)
        let text = phase_counts(disp.iter().map(|d| phases.phase(d.2, t)));
        let x = 0.5 * (ext.x0 + ext.x1);
        let style = ("sans-serif", fs(22.0)).into_font().color(&BLACK).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Bottom,
            ),
        );
        chart.draw_series(std::iter::once(Text::new(text, (x, top + lane), style)))?;
        return Ok(());
    }
    let several = disp.len() > 1;
    for d in disp {
        let ph = phases.phase(d.2, t);
        let color = match ph {
            ContactPhase::Impact | ContactPhase::Release => EVENT,
            ContactPhase::InContact => CONTACT,
            ContactPhase::FreeFlight => FLIGHT,
        };
        let text = ph.shown();
        let size = match (several, ph.is_event()) {
            (true, _) => 22.0,
            (false, true) => 26.0,
            (false, false) => 20.0,
        };
        let style = ("sans-serif", fs(size)).into_font().color(&color).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Bottom,
            ),
        );
        let y = if several {
            top + lane * (0.5 + (d.2 % 3) as f64)
        } else {
            d.1 + 0.11 * (ext.y1_mm - ext.y0_mm)
        };
        chart.draw_series(std::iter::once(Text::new(
            format!("p{}: {text}", d.2),
            (d.0, y),
            style,
        )))?;
    }
    Ok(())
}

/// The frames of an earlier export in `dir` (`frame_NNNNN.png`), sorted.
pub fn old_frames(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("frame_") && n.ends_with(".png"))
        })
        .collect();
    v.sort();
    v
}

/// `Err` naming the folder if `dir` holds frames of an earlier export:
/// new frames would mix with them (a shorter export left the old scene's
/// last frames behind).
pub fn refuse_old_frames(dir: &Path) -> Result<(), FramesError> {
    match old_frames(dir).len() {
        0 => Ok(()),
        count => Err(FramesError::OldFrames {
            dir: std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf()),
            count,
        }),
    }
}

/// Draws the frames of `settings` into a folder as a run passes their
/// times (a [`Probe`]): frame `k` shows the first state at or past
/// `t_k - dt/2`. `progress` counts frames written; setting `cancel` stops
/// the export before the next frame. Satisfied once the last frame is
/// drawn, so a run driven with it stops there.
pub struct FrameWriter<'a> {
    dir: PathBuf,
    settings: FrameSettings,
    ext: Extents,
    phases: PhaseTracker,
    dt_s: f64,
    next: u64,
    count: u64,
    progress: &'a AtomicU64,
    cancel: &'a AtomicBool,
}

impl<'a> FrameWriter<'a> {
    /// Checks `settings` against `sim`'s scene and creates `dir`. Frames of
    /// an earlier export in `dir` would mix with the new ones (a shorter
    /// export leaves a longer one's last frames): they are removed with
    /// `clear_old`, else refused. `changes`: the road and
    /// speed changes the run will take (its axes span their roads too).
    pub fn new(
        sim: &Simulation,
        road: &Road,
        changes: &[RoadChange<'_>],
        dir: &Path,
        settings: &FrameSettings,
        clear_old: bool,
        progress: &'a AtomicU64,
        cancel: &'a AtomicBool,
    ) -> Result<Self, FramesError> {
        settings.check(sim.problem().duration_s)?;
        let io = |path: &Path| {
            let path = path.to_path_buf();
            move |source| FramesError::Io { path, source }
        };
        if clear_old {
            for p in old_frames(dir) {
                std::fs::remove_file(&p).map_err(io(&p))?;
            }
        } else {
            refuse_old_frames(dir)?;
        }
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let dt_s = sim.dt_s();
        Ok(FrameWriter {
            dir: dir.to_path_buf(),
            settings: *settings,
            ext: extents(sim, road, (settings.t0_s, settings.t1_s), changes),
            phases: PhaseTracker::new(sim.num_points(), settings.frame_dt_s().max(dt_s)),
            dt_s,
            next: 0,
            count: settings.frame_count(),
            progress,
            cancel,
        })
    }

    /// Draws every frame due at `sim`'s time; `all`: every frame left (the
    /// run ended before their times).
    fn draw_due(&mut self, sim: &Simulation, all: bool) -> std::io::Result<()> {
        while self.next < self.count
            && (all || sim.time_s() >= self.settings.frame_time_s(self.next) - 0.5 * self.dt_s)
        {
            if self.cancel.load(Ordering::Relaxed) {
                return Err(std::io::Error::new(
                    std::io::ErrorKind::Interrupted,
                    FramesError::Cancelled {
                        done: self.next,
                        total: self.count,
                    },
                ));
            }
            draw_frame(
                sim,
                &self.phases,
                &self.ext,
                &frame_path(&self.dir, self.next),
                self.settings.width,
                self.settings.height,
            )
            .map_err(std::io::Error::other)?;
            self.next += 1;
            self.progress.store(self.next, Ordering::Relaxed);
        }
        Ok(())
    }

    /// Draws the frames left after the run (none if it reached them all):
    /// returns the number of frames written.
    pub fn finish(mut self, sim: &Simulation) -> std::io::Result<u64> {
        self.draw_due(sim, true)?;
        Ok(self.next)
    }
}

impl Probe for FrameWriter<'_> {
    fn start(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.draw_due(sim, false)
    }
    fn after_step(&mut self, sim: &Simulation) -> std::io::Result<()> {
        self.phases
            .after_step(sim.time_s(), sim.in_contact(), sim.force_n());
        self.draw_due(sim, false)
    }
    fn satisfied(&self) -> bool {
        self.next >= self.count
    }
}

/// The error of a frames export that stopped: its own for a cancel or a
/// frame that cannot be written, the run's otherwise.
pub fn frames_error(e: RunError) -> FramesError {
    FramesError::from(e)
}

/// Runs `sim` (fresh, at t = 0) and writes the frames of `settings` into
/// `dir` ([`FrameWriter`]). Returns the number of frames written.
pub fn export_frames(
    mut sim: Simulation,
    road: &Road,
    dir: &Path,
    settings: &FrameSettings,
    clear_old: bool,
    progress: &AtomicU64,
    cancel: &AtomicBool,
) -> Result<u64, FramesError> {
    let mut frames = FrameWriter::new(&sim, road, &[], dir, settings, clear_old, progress, cancel)?;
    run_to_end(&mut sim, &mut frames, Watch::none())?;
    frames.finish(&sim).map_err(|e| RunError::from(e).into())
}

mod extents;

pub use extents::RoadChange;
use extents::{Extents, extents};

#[cfg(test)]
mod tests;
