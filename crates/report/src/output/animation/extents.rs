//! The fixed drawing ranges of the animation frames: the window along the
//! contact line and the heights of the road rolled over while frames are
//! drawn.

use super::drawn_row_y_m;
use tirecontact_core::Simulation;
use tirecontact_core::model::road::{Road, RoadProfile};

/// Fixed drawing ranges of a scene for every frame: x (m) and height
/// `[y0_mm, y1_mm]` (mm).
pub(super) struct Extents {
    pub x0: f64,
    pub x1: f64,
    pub y0_mm: f64,
    pub y1_mm: f64,
    /// The row drawn in full ([`drawn_row_y_m`]), `None` for a single row.
    pub row_y_m: Option<f64>,
}

/// A change of road or speed that a run takes at `t_s` (a live edit
/// replayed from the visualiser): the frames' height axis spans the road
/// rolled over after it too.
#[derive(Debug, Clone, Copy)]
pub struct RoadChange<'a> {
    pub t_s: f64,
    pub profile: &'a RoadProfile,
    pub speed_mps: f64,
}

/// The drawn window: the points with a margin of the road's longest
/// wavelength (`road`, the scene's description of it), or for a patch
/// (several rows) half the patch's length each side; the heights of the
/// frames drawn over `frames_s` (from, to), with the road `changes`
/// ([`RoadChange`], in time order) the run will take.
pub(super) fn extents(
    sim: &Simulation,
    road: &Road,
    frames_s: (f64, f64),
    changes: &[RoadChange<'_>],
) -> Extents {
    let scene = sim.problem();
    let lo = scene
        .points
        .iter()
        .map(|p| p.x_m)
        .fold(f64::INFINITY, f64::min);
    let hi = scene
        .points
        .iter()
        .map(|p| p.x_m)
        .fold(f64::NEG_INFINITY, f64::max);
    let lambda = road.drawn_wavelength_m();
    // (a patch, several rows: the window is the patch and half its length
    // each side, whatever the road's wavelengths)
    let row_y_m = drawn_row_y_m(&scene.points);
    let margin = if row_y_m.is_some() {
        (0.5 * (hi - lo)).max(0.01)
    } else {
        (0.5 * (hi - lo)).max(0.6 * lambda.min(2.0)).max(0.05)
    };
    let (x0, x1) = (lo - margin, hi + margin);
    // the heights drawn: the road, the points' own heights (the undeformed
    // tyre, the road before the ramp) and zero; a quarter of their span
    // below, most of it above for the labels and the legend
    let (z0, z1) = scene.points.iter().map(|p| p.h_m).fold(
        road_range_m(sim, (x0, x1), row_y_m, frames_s, changes),
        |(a, b), h| (a.min(h), b.max(h)),
    );
    let (z0, z1) = (z0.min(0.0), z1.max(0.0));
    let span = (z1 - z0).max(1e-6);
    Extents {
        x0,
        x1,
        y0_mm: 1e3 * (z0 - 0.25 * span),
        y1_mm: 1e3 * (z1 + 0.9 * span),
        row_y_m,
    }
}

/// The lowest and highest road heights (m) the frames can draw: of the
/// road under the window `(x0, x1)` (tyre frame) over the frames' times
/// `frames_s` from `sim`'s time on, at the frames' resolution (at most
/// 200 000 samples a stretch of road), under the row `row_y_m` of a patch,
/// with each road and speed of `changes` from its time; `(0, 0)` where none
/// is sampled. Not the whole road's: a long measured track reaches heights
/// far from the stretch a run rolls over.
fn road_range_m(
    sim: &Simulation,
    (x0, x1): (f64, f64),
    row_y_m: Option<f64>,
    frames_s: (f64, f64),
    changes: &[RoadChange<'_>],
) -> (f64, f64) {
    let t_end = sim.problem().duration_s;
    let (from_s, to_s) = (frames_s.0.max(sim.time_s()), frames_s.1.min(t_end));
    // the stretches of one road at one speed: (start time, road, speed)
    let first = RoadChange {
        t_s: sim.time_s(),
        profile: sim.road_profile(),
        speed_mps: sim.problem().speed_mps,
    };
    let stretches: Vec<RoadChange<'_>> = std::iter::once(first)
        .chain(changes.iter().copied().filter(|c| c.t_s >= first.t_s))
        .collect();
    let mut rolled_m = sim.rolled_m();
    let mut range = (0.0f64, 0.0f64);
    for (k, c) in stretches.iter().enumerate() {
        let end_s = stretches.get(k + 1).map_or(t_end, |n| n.t_s);
        let (a_s, b_s) = (c.t_s.max(from_s), end_s.min(to_s));
        if a_s <= b_s {
            let start_m = rolled_m + c.speed_mps * (a_s - c.t_s);
            let travel_m = c.speed_mps * (b_s - a_s);
            let (lo, hi) = (
                start_m.min(start_m + travel_m),
                start_m.max(start_m + travel_m),
            );
            let (z0, z1) = road_range_between_m(c.profile, x0 + lo, x1 + hi, x1 - x0, row_y_m);
            range = (range.0.min(z0), range.1.max(z1));
        }
        rolled_m += c.speed_mps * (end_s - c.t_s);
    }
    range
}

/// The lowest and highest heights (m) of `road` over `[a, b]` (m), sampled
/// at `window_m / 600` (at most 200 000 samples), under the row `row_y_m`.
fn road_range_between_m(
    road: &RoadProfile,
    a: f64,
    b: f64,
    window_m: f64,
    row_y_m: Option<f64>,
) -> (f64, f64) {
    let step_m = (window_m / 600.0).max((b - a) / 200_000.0);
    if !(step_m > 0.0 && b > a) {
        return (0.0, 0.0);
    }
    let n = ((b - a) / step_m).ceil() as usize;
    (0..=n)
        .filter_map(|k| {
            let x = a + (b - a) * k as f64 / n as f64;
            match row_y_m {
                Some(y) => road.sample_at(x, y),
                None => road.sample(x),
            }
            .ok()
        })
        .fold((0.0, 0.0), |(lo, hi), (z, _)| (z.min(lo), z.max(hi)))
}
