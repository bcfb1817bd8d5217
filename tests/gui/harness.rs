//! The kittest set-up of the GUI tests and readers of what a frame painted.

use egui_kittest::Harness;
use tirecontact::gui::{App, Command};

/// The app in a 1500 × 950 window stepped at 60 frames per second.
pub fn harness(app: App) -> Harness<'static, App> {
    harness_sized(app, [1500.0, 950.0])
}

/// Frames `Harness::run` may take before the app stops asking for more: a
/// preset or road file is read off the UI thread, and the app asks for
/// frames until it is (a few frames; more on a busy machine).
pub const MAX_RUN_FRAMES: u64 = 200;

/// The app in a window of `size` (points) stepped at 60 frames per second.
pub fn harness_sized(app: App, size: [f32; 2]) -> Harness<'static, App> {
    Harness::builder()
        .with_size(size)
        .with_step_dt(1.0 / 60.0)
        .with_max_steps(MAX_RUN_FRAMES)
        .build_ui_state(|ui, app: &mut App| app.show(ui), app)
}

/// Replaces the text of the field named `name` and commits it with Enter
/// (the frames the field needs to take the focus, the text and the key).
pub fn type_into(h: &mut Harness<'_, App>, name: &str, text: &str) {
    use egui_kittest::kittest::Queryable;
    h.get_by_label(name).focus();
    h.run();
    h.get_by_label(name).set_text_value_accesskit(text);
    h.run();
    h.key_press(egui::Key::Enter);
    h.run();
    h.run();
}

/// Takes `n` solver steps (over as many frames as the step budget needs).
pub fn advance(h: &mut Harness<'_, App>, n: u64) {
    let target = h.state().simulation().steps() + n;
    h.state_mut().apply(Command::Step(n));
    for _ in 0..100_000 {
        if h.state().simulation().steps() >= target {
            break;
        }
        h.run_steps(1);
    }
    assert_eq!(h.state().simulation().steps(), target);
}

/// Frames until no ring tyre is being identified (a new document or an edit
/// waiting for its modes), then until the UI settles. Each app identifies
/// a ring it has not seen before on a background thread.
pub fn settle(h: &mut Harness<'_, App>) {
    // a click or key waiting is handled in the next frame
    h.run_steps(1);
    for _ in 0..100_000 {
        if !h.state().identifying() {
            h.run();
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
        h.run_steps(1);
    }
    panic!("the identification never finished");
}

/// Frames until no fidelity figures are being computed (bounded).
pub fn wait_fidelity(h: &mut Harness<'_, App>) {
    for _ in 0..100_000 {
        if h.state().research().fidelity_computing().is_none() {
            h.run_steps(1);
            return;
        }
        std::thread::sleep(std::time::Duration::from_millis(1));
        h.run_steps(1);
    }
    panic!("the fidelity figures never arrived");
}

/// WCAG contrast ratio of two egui colours (1 to 21).
pub fn contrast(a: egui::Color32, b: egui::Color32) -> f64 {
    let rgb = |c: egui::Color32| [c.r(), c.g(), c.b()];
    crate::support::colour::contrast(rgb(a), rgb(b))
}

/// Every leaf shape of a painted shape (nested `Shape::Vec`s opened).
pub fn walk<'a>(s: &'a egui::Shape, out: &mut Vec<&'a egui::Shape>) {
    match s {
        egui::Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
        s => out.push(s),
    }
}

/// Every leaf shape the last frame painted (owned copies).
pub fn shapes(h: &Harness<'_, App>) -> Vec<egui::Shape> {
    let mut v = Vec::new();
    for c in &h.output().shapes {
        walk(&c.shape, &mut v);
    }
    v.into_iter().cloned().collect()
}

/// The painted open polylines of at least `min_points` points and the line
/// segments stroked in one of `colors`; a min/max band (egui_plot draws a
/// line with several samples per pixel column as one) gives each sample's
/// vertical extent and the line through their centres.
pub fn curves(
    h: &Harness<'_, App>,
    colors: &[egui::Color32],
    min_points: usize,
) -> Vec<Vec<egui::Pos2>> {
    use egui::Pos2;
    use egui::epaint::{ColorMode, PathShape, Shape};
    shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            Shape::Path(PathShape {
                points,
                stroke,
                closed: false,
                ..
            }) if points.len() >= min_points
                && matches!(stroke.color, ColorMode::Solid(c) if colors.contains(&c)) =>
            {
                Some(vec![points.clone()])
            }
            Shape::LineSegment { points, stroke } if colors.contains(&stroke.color) => {
                Some(vec![points.to_vec()])
            }
            Shape::Band(b) if colors.contains(&b.fill) => {
                let mut v: Vec<Vec<Pos2>> = b
                    .points
                    .iter()
                    .map(|p| vec![Pos2::new(p.x, p.y.min), Pos2::new(p.x, p.y.max)])
                    .collect();
                v.push(
                    b.points
                        .iter()
                        .map(|p| Pos2::new(p.x, p.y.center()))
                        .collect(),
                );
                Some(v)
            }
            _ => None,
        })
        .flatten()
        .collect()
}

/// Length (px) of `curves` inside `r`, from 0.25 px samples.
pub fn ink(r: egui::Rect, curves: &[Vec<egui::Pos2>]) -> f32 {
    let mut len = 0.0;
    for c in curves {
        for w in c.windows(2) {
            let d = w[0].distance(w[1]);
            let n = (d / 0.25).ceil().max(1.0) as usize;
            for k in 0..n {
                if r.contains(w[0].lerp(w[1], (k as f32 + 0.5) / n as f32)) {
                    len += d / n as f32;
                }
            }
        }
    }
    len
}

/// Every painted text with its visual bounding box.
pub fn texts(h: &Harness<'_, App>) -> Vec<(String, egui::Rect)> {
    shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Text(t) => Some((t.galley.text().to_owned(), t.visual_bounding_rect())),
            _ => None,
        })
        .collect()
}

/// The top (px) of the status bar: of its run label ("… steps · …").
pub fn status_top(h: &Harness<'_, App>) -> f32 {
    let top = texts(h)
        .iter()
        .filter(|(t, _)| t.contains(" steps · "))
        .map(|(_, r)| r.top())
        .fold(f32::INFINITY, f32::min);
    assert!(top.is_finite(), "no status bar text found");
    top
}

/// Turns the mouse wheel `times` times by `dy_px` (negative: scrolls the
/// content up) with the pointer at `at`, then lets the scrolling settle.
pub fn wheel(h: &mut Harness<'_, App>, at: egui::Pos2, dy_px: f32, times: usize) {
    h.hover_at(at);
    h.run_steps(1);
    for _ in 0..times {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: egui::vec2(0.0, dy_px),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(2);
    }
    h.run_steps(30);
}

/// Rotated texts (y axis titles) and their painted bounds.
pub fn rotated_texts(h: &Harness<'_, App>) -> Vec<(String, egui::Rect)> {
    shapes(h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Text(t) if t.angle != 0.0 => {
                Some((t.galley.text().to_owned(), t.visual_bounding_rect()))
            }
            _ => None,
        })
        .collect()
}

/// The frame (px) of the plot of id `egui::Id::unique(id)` as last drawn.
pub fn plot_frame(h: &Harness<'_, App>, id: &str) -> egui::Rect {
    *egui_plot::PlotMemory::load(&h.ctx, egui::Id::unique(id))
        .unwrap_or_else(|| panic!("plot {id} not shown"))
        .transform()
        .frame()
}

/// An in-memory session store: what the app saves at the end of a session
/// and reads at the next start.
#[derive(Default)]
pub struct MemStorage(pub std::collections::HashMap<String, String>);

impl eframe::Storage for MemStorage {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0.get(key).cloned()
    }
    fn set_string(&mut self, key: &str, value: String) {
        self.0.insert(key.to_string(), value);
    }
    fn remove_string(&mut self, key: &str) {
        self.0.remove(key);
    }
    fn flush(&mut self) {}
}
