//! Legends of the research plots (spectra, sweep, compare) placed off the
//! data: each frame the plot's curves (in screen pixels) choose the corner
//! whose legend-sized box they cross least, and the next frame puts the
//! legend there. Short plots use a small legend text
//! ([`legend_text`]).

use egui::{Context, Id, Pos2, Rect, TextStyle, Ui, Vec2};
use egui_plot::{Corner, Legend, PlotPoint, PlotUi};

/// Height (px) under which a time plot is short: small legend text and
/// short y labels.
pub const SHORT_PLOT_PX: f32 = 160.0;

/// Text of the time plots' legends: small in short plots (small windows),
/// where body text made a legend of five points cover most of the plot.
pub fn legend_text(plot_height: f32) -> TextStyle {
    if plot_height < SHORT_PLOT_PX {
        TextStyle::Small
    } else {
        TextStyle::Body
    }
}

/// Corners in order of preference when several are equally empty.
const PREFERENCE: [Corner; 4] = [
    Corner::RightTop,
    Corner::LeftTop,
    Corner::RightBottom,
    Corner::LeftBottom,
];

fn key(id: Id) -> Id {
    id.with("tirecontact.legend_corner")
}

/// The corner chosen for plot `id` on the last frame (top right at first).
pub fn corner(ctx: &Context, id: Id) -> Corner {
    ctx.data(|d| d.get_temp::<Corner>(key(id)))
        .unwrap_or(Corner::RightTop)
}

/// Whether the legend of plot `id` stacks its entries upwards this frame:
/// egui_plot lays out a bottom corner's legend from the bottom, so its
/// entries go in reversed there for it to read first to last downwards as
/// in a top corner (and as in the PNG figures).
pub fn upwards(ctx: &Context, id: Id) -> bool {
    matches!(corner(ctx, id), Corner::LeftBottom | Corner::RightBottom)
}

/// Puts the legend of plot `id` in corner `c` on the next frame (until its
/// curves choose another).
pub fn set_corner(ctx: &Context, id: Id, c: Corner) {
    ctx.data_mut(|d| d.insert_temp(key(id), c));
}

/// The legend of plot `id`: in the corner its curves left emptiest on the
/// last frame, with small text when the plot is short.
pub fn legend(ctx: &Context, id: Id, plot_height_px: f32) -> Legend {
    Legend::default()
        .text_style(legend_text(plot_height_px))
        .position(corner(ctx, id))
}

/// Size (px) of a legend of `labels` in a plot `plot_height_px` high, about
/// as egui_plot lays it out (a row per entry: marker, gap, text).
pub fn legend_size(ui: &Ui, labels: &[&str], plot_height_px: f32) -> Vec2 {
    let style = legend_text(plot_height_px);
    let font = ui.style().text_styles.get(&style).map_or(14.0, |f| f.size);
    let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0);
    let spacing = ui.spacing().item_spacing;
    Vec2::new(
        chars as f32 * 0.6 * font + font + 3.0 * spacing.x + 8.0,
        labels.len() as f32 * (font + 2.0 * spacing.y) + 8.0,
    )
}

/// The box a legend of `size` covers in corner `c` of `frame`.
pub fn corner_box(frame: Rect, size: Vec2, c: Corner) -> Rect {
    let (x, y) = match c {
        Corner::LeftTop => (frame.left(), frame.top()),
        Corner::RightTop => (frame.right() - size.x, frame.top()),
        Corner::LeftBottom => (frame.left(), frame.bottom() - size.y),
        Corner::RightBottom => (frame.right() - size.x, frame.bottom() - size.y),
    };
    Rect::from_min_size(Pos2::new(x, y), size)
}

/// Length (px) of the polylines `curves` inside `r`, sampled every 1 px.
pub fn length_inside(r: Rect, curves: &[Vec<Pos2>]) -> f32 {
    let mut inside = 0.0;
    for c in curves {
        for w in c.windows(2) {
            let (a, b) = (w[0], w[1]);
            if !(a.x.is_finite() && a.y.is_finite() && b.x.is_finite() && b.y.is_finite()) {
                continue;
            }
            let seg = Rect::from_two_pos(a, b);
            if !seg.intersects(r) {
                continue;
            }
            let len = a.distance(b);
            let n = (len.ceil() as usize).clamp(1, 100_000);
            let step = len / n as f32;
            for k in 0..n {
                let t = (k as f32 + 0.5) / n as f32;
                if r.contains(a.lerp(b, t)) {
                    inside += step;
                }
            }
        }
    }
    inside
}

/// The corner of `frame` whose legend-sized box the curves cross least;
/// `previous` is kept unless another corner has less than half its ink (no
/// flicker between near ties).
pub fn emptiest_corner(frame: Rect, size: Vec2, curves: &[Vec<Pos2>], previous: Corner) -> Corner {
    let ink = |c: Corner| length_inside(corner_box(frame, size, c), curves);
    let mut best = PREFERENCE[0];
    let mut best_ink = f32::INFINITY;
    for c in PREFERENCE {
        let i = ink(c);
        if i < best_ink {
            best = c;
            best_ink = i;
        }
    }
    let prev_ink = ink(previous);
    if best_ink >= 0.5 * prev_ink {
        previous
    } else {
        best
    }
}

/// Curves being drawn in a plot, in screen pixels, for `place`.
#[derive(Default)]
pub struct Ink {
    curves: Vec<Vec<Pos2>>,
    /// Lowest and highest y of the curves (plot units).
    y_range: Option<(f64, f64)>,
    /// The x range the plot shows on this frame, when it is set on it: the
    /// plot's transform is still the last frame's then.
    x_bounds: Option<(f64, f64)>,
}

/// The screen x of `x` in a frame spanning `left_px..right_px` that shows
/// `lo..hi`.
pub fn screen_x(x: f64, (lo, hi): (f64, f64), (left_px, right_px): (f32, f32)) -> f32 {
    let f = if hi > lo { (x - lo) / (hi - lo) } else { 0.0 };
    left_px + (f as f32) * (right_px - left_px)
}

/// What `Ink::place` keeps of a plot for `headroom`: the curves' y range
/// (plot units) and the height of the plot's frame (px).
#[derive(Clone, Copy)]
struct Extent {
    y_range: (f64, f64),
    frame_h_px: f32,
}

fn extent_key(id: Id) -> Id {
    id.with("tirecontact.legend_extent")
}

/// The top of a y axis whose top `legend_h_px` (plus a gap) stay above
/// curves spanning `lo..=hi` in a frame `frame_h_px` high: for curves that
/// fill the whole width (time series), where every corner would cover data.
/// At most 60 % of the frame goes to the legend: a three-entry legend in
/// the 113 px plots of A/B compare at 1280 × 720 needs 52 %.
pub fn headroom_top((lo, hi): (f64, f64), legend_h_px: f32, frame_h_px: f32) -> f64 {
    let f = ((legend_h_px + 6.0) / frame_h_px.max(1.0)).clamp(0.0, 0.6) as f64;
    (hi - f * lo) / (1.0 - f)
}

/// The y a plot should include so that its legend (`legend_size`) sits
/// above the curves drawn on its last frame (none before the first).
pub fn headroom(ctx: &Context, id: Id, legend_size: Vec2) -> Option<f64> {
    let e = ctx.data(|d| d.get_temp::<Extent>(extent_key(id)))?;
    Some(headroom_top(e.y_range, legend_size.y, e.frame_h_px))
}

impl Ink {
    /// Ink of a plot whose x range is set to `lo..hi` on this frame (a time
    /// axis that follows the run): its curves are placed in that range, not
    /// in the last frame's. Placed by the last frame's axes, a run that
    /// moved on between two slow frames (5 per second in a browser with
    /// software WebGL) drew into the legends' strip past the window's end,
    /// and the legends left it for the top left while playing.
    pub fn with_x_bounds(lo: f64, hi: f64) -> Self {
        Self {
            x_bounds: Some((lo, hi)),
            ..Self::default()
        }
    }

    /// Notes a curve given in plot coordinates.
    pub fn add(&mut self, pui: &PlotUi<'_>, pts: &[[f64; 2]]) {
        for p in pts.iter().filter(|p| p[1].is_finite()) {
            let (lo, hi) = self.y_range.get_or_insert((p[1], p[1]));
            *lo = lo.min(p[1]);
            *hi = hi.max(p[1]);
        }
        let frame = *pui.transform().frame();
        let x_bounds = self.x_bounds;
        self.curves.push(
            pts.iter()
                .map(|p| {
                    let s = pui.screen_from_plot(PlotPoint::new(p[0], p[1]));
                    match x_bounds {
                        Some(b) => Pos2::new(screen_x(p[0], b, (frame.left(), frame.right())), s.y),
                        None => s,
                    }
                })
                .collect(),
        );
    }

    /// Chooses the legend corner of plot `id` for the next frame from the
    /// curves noted on this one; repaints at once when it moved.
    pub fn place(self, pui: &PlotUi<'_>, id: Id, legend_size: Vec2) {
        let ctx = pui.ctx().clone();
        let frame = *pui.transform().frame();
        if let Some(y_range) = self.y_range {
            let e = Extent {
                y_range,
                frame_h_px: frame.height(),
            };
            ctx.data_mut(|d| d.insert_temp(extent_key(id), e));
        }
        let previous = corner(&ctx, id);
        let next = emptiest_corner(frame, legend_size, &self.curves, previous);
        if next != previous {
            ctx.data_mut(|d| d.insert_temp(key(id), next));
            ctx.request_repaint();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Rect {
        Rect::from_min_size(Pos2::ZERO, Vec2::new(400.0, 200.0))
    }

    #[test]
    fn length_inside_a_box_is_the_clipped_length() {
        let r = Rect::from_min_max(Pos2::new(10.0, 0.0), Pos2::new(30.0, 50.0));
        // a horizontal line across: 20 px inside
        let c = vec![vec![Pos2::new(0.0, 10.0), Pos2::new(100.0, 10.0)]];
        assert!((length_inside(r, &c) - 20.0).abs() <= 1.0);
        // a diagonal 3-4-5 line fully inside: 25 px
        let c = vec![vec![Pos2::new(12.0, 5.0), Pos2::new(27.0, 25.0)]];
        assert!((length_inside(r, &c) - 25.0).abs() <= 1.0);
        // outside: nothing
        let c = vec![vec![Pos2::new(40.0, 5.0), Pos2::new(90.0, 45.0)]];
        assert_eq!(length_inside(r, &c), 0.0);
    }

    #[test]
    fn a_falling_curve_leaves_the_top_right_and_a_rising_one_the_top_left() {
        let size = Vec2::new(120.0, 60.0);
        // screen y grows downwards: falling data go from top left to bottom right
        let falling = vec![vec![Pos2::new(0.0, 0.0), Pos2::new(400.0, 200.0)]];
        let c = emptiest_corner(frame(), size, &falling, Corner::LeftTop);
        assert!(matches!(c, Corner::RightTop | Corner::LeftBottom), "{c:?}");
        let rising = vec![vec![Pos2::new(0.0, 200.0), Pos2::new(400.0, 0.0)]];
        let c = emptiest_corner(frame(), size, &rising, Corner::RightTop);
        assert!(matches!(c, Corner::LeftTop | Corner::RightBottom), "{c:?}");
        // a curve along the top: a bottom corner
        let top = vec![vec![Pos2::new(0.0, 20.0), Pos2::new(400.0, 20.0)]];
        let c = emptiest_corner(frame(), size, &top, Corner::RightTop);
        assert!(
            matches!(c, Corner::RightBottom | Corner::LeftBottom),
            "{c:?}"
        );
    }

    #[test]
    fn headroom_leaves_the_legend_height_above_the_curves() {
        // curves over 0..10 in a 200 px frame, legend 44 px: the top 50 px
        // (a quarter) must be above 10
        let top = headroom_top((0.0, 10.0), 44.0, 200.0);
        let px_above = 200.0 * (top - 10.0) / (top - 0.0);
        assert!((px_above - 50.0).abs() < 1e-9, "{px_above}");
        let top = headroom_top((-3.0, 1.0), 44.0, 200.0);
        assert!((200.0 * (top - 1.0) / (top + 3.0) - 50.0).abs() < 1e-9);
    }

    /// A run playing at 5 frames per second in a window that follows it,
    /// with the legends' strip past the window's end (as the time plots):
    /// placed in the range shown on the frame, the curves never reach the
    /// strip and the legend stays top right on every frame; placed by the
    /// last frame's range (the plot's transform then), the newest 0.2 s
    /// run into the strip and the legend leaves it.
    #[test]
    fn a_followed_run_keeps_its_legend_in_the_strip_while_playing() {
        let frame = Rect::from_min_size(Pos2::ZERO, Vec2::new(600.0, 150.0));
        let px = (frame.left(), frame.right());
        let size = Vec2::new(140.0, 60.0);
        let window_s = 1.0;
        // the strip is as wide as the legend plus 12 px
        let strip_s = window_s * f64::from(size.x + 12.0) / f64::from(600.0 - size.x - 12.0);
        let curve_at = |t_end: f64, range: (f64, f64)| -> Vec<Vec<Pos2>> {
            // a signal filling the window's height, sampled every 5 ms
            let n = (window_s / 0.005) as usize;
            vec![
                (0..=n)
                    .map(|k| {
                        let t = t_end - window_s + k as f64 * 0.005;
                        let y = 75.0 + 70.0 * (40.0 * t).sin() as f32;
                        Pos2::new(screen_x(t, range, px), y)
                    })
                    .collect(),
            ]
        };
        let (mut now, mut stale) = (Corner::RightTop, Corner::RightTop);
        let mut stale_moved = 0;
        for frame_k in 1..50 {
            let t_end = 1.0 + 0.2 * frame_k as f64;
            let shown = (t_end - window_s, t_end + strip_s);
            let last = (t_end - 0.2 - window_s, t_end - 0.2 + strip_s);
            now = emptiest_corner(frame, size, &curve_at(t_end, shown), now);
            assert_eq!(now, Corner::RightTop, "frame {frame_k}");
            stale = emptiest_corner(frame, size, &curve_at(t_end, last), stale);
            stale_moved += usize::from(stale != Corner::RightTop);
        }
        assert!(stale_moved > 0, "the last frame's range kept the strip too");
    }

    #[test]
    fn screen_x_maps_the_range_onto_the_frame() {
        assert_eq!(screen_x(2.0, (2.0, 4.0), (10.0, 110.0)), 10.0);
        assert_eq!(screen_x(3.0, (2.0, 4.0), (10.0, 110.0)), 60.0);
        assert_eq!(screen_x(5.0, (2.0, 4.0), (10.0, 110.0)), 160.0);
        assert_eq!(screen_x(5.0, (2.0, 2.0), (10.0, 110.0)), 10.0);
    }

    #[test]
    fn a_near_tie_keeps_the_previous_corner() {
        let size = Vec2::new(100.0, 50.0);
        // 30 px of ink top left, 20 px top right: not worth moving
        let c = vec![
            vec![Pos2::new(10.0, 10.0), Pos2::new(40.0, 10.0)],
            vec![Pos2::new(350.0, 10.0), Pos2::new(370.0, 10.0)],
            vec![Pos2::new(10.0, 190.0), Pos2::new(40.0, 190.0)],
            vec![Pos2::new(350.0, 190.0), Pos2::new(380.0, 190.0)],
        ];
        assert_eq!(
            emptiest_corner(frame(), size, &c, Corner::LeftTop),
            Corner::LeftTop
        );
    }
}
