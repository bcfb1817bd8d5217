//! The paper's Fig. 1 and Fig. 2 (`identify --figures`): displacement and
//! contact force of every point against time, from a [`Recording`] as
//! `run --plot` draws them; Fig. 2 clips impact spikes a margin above the
//! force without impacts and marks them by dots (or draws them whole).

use crate::output::figures::{Figure, Panel};
use crate::output::record::Recording;
use tirecontact_io::Scene;

/// File name parts (`{stem}_{part}.png`) and figures of Fig. 1
/// (displacement, mm) and Fig. 2 (force, N) of `rec`, a run of `scene` with
/// steps of `scene.dt_s`; `clip_impacts` as `run --plot`'s default.
pub fn paper_figures(
    rec: &Recording,
    scene: &Scene,
    subtitle: &str,
    clip_impacts: bool,
) -> [(&'static str, Figure); 2] {
    let name = |i: usize| point_name(scene, i);
    let win_ms = rec.window_ms(scene.dt_s);
    // (clipped impacts are said by their legend entry, CLIPPED_IMPACTS)
    let (forces, _clipped) = rec.force_series(clip_impacts, None, &name);
    let force_title = "Fig. 2: contact force on the contact points".to_string();
    let panel = |y_label: String, series| Panel {
        title: String::new(),
        x_label: "time (s)".into(),
        y_label,
        series,
        ..Panel::default()
    };
    [
        (
            "fig1_displacement",
            Figure {
                title: "Fig. 1: displacement of the contact points".into(),
                subtitle: subtitle.into(),
                panels: vec![panel(
                    "displacement u (mm), up".into(),
                    rec.displacement_series(None, &name),
                )],
            },
        ),
        (
            "fig2_force",
            Figure {
                title: force_title,
                subtitle: subtitle.into(),
                panels: vec![panel(
                    format!(
                        "contact force q (N), mean over {} windows",
                        super::summary::duration_text(win_ms * 1e-3, 3)
                    ),
                    forces,
                )],
            },
        ),
    ]
}

/// Point `i`'s name in the legends: its index and place, `y` only off the
/// centreline (`point 1 (x = 0.1 m)`, `point 2 (x = 0.1 m, y = 0.04 m)`).
fn point_name(scene: &Scene, i: usize) -> String {
    scene.points.get(i).map_or(format!("point {i}"), |p| {
        if p.y_m == 0.0 {
            format!("point {i} (x = {} m)", p.x_m)
        } else {
            format!("point {i} (x = {} m, y = {} m)", p.x_m, p.y_m)
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::impacts::ImpactTracker;
    use crate::output::record::{CLIPPED_IMPACTS, PLOT_SAMPLES};
    use tirecontact_core::Simulation;
    use tirecontact_io::SceneSimulation;
    use tirecontact_io::scene::ContactScheme;

    /// The three-point preset (impacts at every landing) recorded as
    /// `identify --figures` does, and beside it, step by step, the range of
    /// its force without impacts averaged over the same windows.
    fn run(scheme: ContactScheme) -> (Scene, Recording, (f64, f64), f64) {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        scene.duration_s = 0.06;
        scene.contact_scheme = scheme;
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let n = scene.num_steps();
        let mut rec = Recording::new(scene.num_points(), n, PLOT_SAMPLES);
        let every = rec.every();
        let p = scene.num_points();
        let mut tracker = ImpactTracker::start(&sim);
        let (mut q, mut qi) = (vec![0.0; p], vec![0.0; p]);
        let (mut smooth, mut raw) = ((f64::INFINITY, f64::NEG_INFINITY), 0.0f64);
        let mut count = 0;
        while !sim.finished() {
            sim.step().unwrap();
            rec.after_step(&sim);
            for (s, f) in q.iter_mut().zip(sim.force_n()) {
                *s += f;
            }
            tracker.add_step(&sim, &mut qi);
            count += 1;
            if count == every || sim.finished() {
                for i in 0..p {
                    let mean = q[i] / count as f64;
                    let v = (q[i] - qi[i]) / count as f64;
                    smooth = (smooth.0.min(v), smooth.1.max(v));
                    raw = raw.max(mean);
                }
                q.fill(0.0);
                qi.fill(0.0);
                count = 0;
            }
        }
        (scene, rec, smooth, raw)
    }

    /// Length (px) of the polylines `curves` inside the box `[l, t, r, b]`,
    /// from samples every 0.5 px along each segment.
    #[cfg(feature = "figures")]
    fn px_inside(curves: &[Vec<(i32, i32)>], [l, t, r, b]: [i32; 4]) -> f64 {
        let mut len = 0.0;
        for c in curves {
            for w in c.windows(2) {
                let (a, z) = (w[0], w[1]);
                let (dx, dy) = (f64::from(z.0 - a.0), f64::from(z.1 - a.1));
                let d = dx.hypot(dy);
                let n = (2.0 * d).ceil().max(1.0) as usize;
                for k in 0..=n {
                    let f = k as f64 / n as f64;
                    let (x, y) = (f64::from(a.0) + f * dx, f64::from(a.1) + f * dy);
                    if x >= f64::from(l)
                        && x <= f64::from(r)
                        && y >= f64::from(t)
                        && y <= f64::from(b)
                    {
                        len += d / (n + 1) as f64;
                    }
                }
            }
        }
        len
    }

    #[cfg(feature = "figures")]
    #[test]
    fn fig2_legend_is_beside_the_plot_where_no_curve_is() {
        use crate::output::figures::render_png_layout;
        let (scene, rec, _, _) = run(ContactScheme::Located);
        let dir = std::env::temp_dir().join(format!("tc-paper-figs-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let [_, (_, fig2)] = paper_figures(&rec, &scene, "s", true);
        let (w, h) = (1200, 700);
        let layout = render_png_layout(&fig2, &dir.join("fig2.png"), w, h).unwrap();
        let l = &layout[0];
        let [pl, pt, pr, pb] = l.plot_px;
        // the force fills the plot: every corner has curves
        let corner_w = (pr - pl) / 4;
        for (x0, y0) in [
            (pl, pt),
            (pr - corner_w, pt),
            (pl, pb - 60),
            (pr - corner_w, pb - 60),
        ] {
            let ink = px_inside(&l.curves_px, [x0, y0, x0 + corner_w, y0 + 60]);
            assert!(ink > 0.0, "corner at ({x0}, {y0}) free of curves");
        }
        let legend = l.legend_px.expect("legend beside the plot");
        let [ll, lt, lr, lb] = legend;
        eprintln!("plot {:?}, legend {legend:?}", l.plot_px);
        // right of the plot, level with its top, inside the figure
        assert!(ll > pr, "legend {legend:?} over the plot {:?}", l.plot_px);
        assert!(lr <= w as i32 && lt >= pt - 1 && lb <= pb, "{legend:?}");
        // the curves drawn (every series, in pixels) stay out of it
        let total = px_inside(&l.curves_px, l.plot_px);
        assert!(total > f64::from(pr - pl), "curves drawn: {total} px");
        assert_eq!(px_inside(&l.curves_px, legend), 0.0);
        // one entry row per series
        assert!(
            lb - lt >= fig2.panels[0].series.len() as i32 * 14,
            "{legend:?}"
        );
        // the plot keeps most of the width (0.7 before the text grew with
        // the width: the legend column is 330 px of 1200 at 22 px)
        assert!(f64::from(pr - pl) > 0.6 * f64::from(w), "{:?}", l.plot_px);
        std::fs::remove_dir_all(&dir).ok();
    }

    fn y_range(f: &Figure) -> (f64, f64) {
        f.panels[0]
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
                (lo.min(y), hi.max(y))
            })
    }

    #[test]
    fn fig2_is_scaled_by_the_force_without_impacts() {
        for scheme in [ContactScheme::Located, ContactScheme::Paper] {
            let (scene, rec, (lo, hi), raw) = run(scheme);
            // the clip level: 10 % of the range (at least 0.1 N) above it
            let top = hi + 0.1 * (hi - lo).max(1.0);
            assert!(raw > 5.0 * top, "{scheme:?}: spikes {raw} N vs {top} N");
            let [(_, fig1), (_, fig2)] = paper_figures(&rec, &scene, "s", true);
            let (y0, y1) = y_range(&fig2);
            assert!(
                (y1 - top).abs() <= 1e-9 * top,
                "{scheme:?}: Fig. 2 reaches {y1} N, clip level {top} N"
            );
            // clipping leaves the bottom to the force (never below it)
            assert!(y0 >= lo - 1e-9 && y0 < top, "{scheme:?}: {y0} N vs {lo} N");
            let marks = fig2.panels[0]
                .series
                .iter()
                .find(|s| s.name == CLIPPED_IMPACTS)
                .expect("clipped impacts marked");
            assert!(marks.points.iter().all(|p| p.1 == top));
            // said by the dots' legend entry, not again in the title
            assert!(!fig2.title.contains("clipped"), "{}", fig2.title);
            assert!(fig1.title.starts_with("Fig. 1"));
            // every point's series is named with its position
            assert!(fig2.panels[0].series[0].name.starts_with("point 0 (x = "));
            // whole on request: the spikes set the range
            let [_, (_, whole)] = paper_figures(&rec, &scene, "s", false);
            assert_eq!(y_range(&whole).1, raw, "{scheme:?}");
            assert!(!whole.title.contains("clipped"));
        }
    }

    /// Points on the centreline are named by their `x` alone; points
    /// across the tread say their `y` too.
    #[test]
    fn points_are_named_by_their_place() {
        let mut scene = Scene::load(std::path::Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )))
        .unwrap();
        assert_eq!(point_name(&scene, 0), "point 0 (x = -0.05 m)");
        scene.points[2].x_m = 0.0;
        scene.points[2].y_m = 0.04;
        assert_eq!(point_name(&scene, 1), "point 1 (x = 0 m)");
        assert_eq!(point_name(&scene, 2), "point 2 (x = 0 m, y = 0.04 m)");
        assert_eq!(point_name(&scene, 3), "point 3");
    }
}
