//! The status bar in one row that fits the window: each label has a full
//! and a short text; when the full texts do not fit (classroom mode's large
//! text in a 1280 px window ran ~100 px past the edge), the history, then
//! the run statistics, then the document label take their short text, and
//! a document label still too long is cut with "…". A shortened label shows
//! its full text on hover. Never wraps: a second row moved the widgets above
//! it (and broke clicks on them).

use crate::gui::widgets::fields::ERROR_COLOR;
use egui::{Label, RichText, TextStyle, TextWrapMode, Ui, WidgetText};
use std::path::Path;

/// What the status bar shows, read from the app each frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Status<'a> {
    /// The document's file, if it has one.
    pub path: Option<&'a Path>,
    /// The document came from a scene link (and has no file since).
    pub from_link: bool,
    pub scene_name: &'a str,
    /// The scene differs from its saved version.
    pub dirty: bool,
    pub points: usize,
    pub modes: usize,
    /// Solver steps and contact events of the run.
    pub steps: u64,
    pub events: u64,
    /// Points in contact now.
    pub in_contact: usize,
    /// Samples in the history, and the solver steps per sample.
    pub samples: usize,
    pub stride: u64,
    pub playing: bool,
    /// Frames per second, and the solver and UI code's time per frame (ms).
    pub fps: f64,
    pub app_ms: f64,
    pub exporting_csv: bool,
}

/// A status bar label: its full text and its short text for narrow windows.
#[derive(Debug, Clone, PartialEq)]
pub struct StatusText {
    pub full: String,
    pub short: String,
}

/// The status bar's labels, left to right: document, run, history.
pub fn texts(s: &Status) -> [StatusText; 3] {
    [
        match (s.path, s.from_link) {
            (None, true) => StatusText {
                full: marked(
                    format!("{} (from a link)", s.scene_name),
                    s.dirty,
                    "unsaved changes",
                ),
                short: marked(format!("{} (link)", s.scene_name), s.dirty, "unsaved"),
            },
            _ => StatusText {
                full: document_label(s.path, s.scene_name, s.dirty),
                short: short_document_label(s.path, s.scene_name, s.dirty),
            },
        },
        StatusText {
            full: format!(
                "{} · {} · {} · {} · {} in contact",
                count(s.points, "point"),
                count(s.modes, "mode"),
                count(s.steps as usize, "step"),
                count(s.events as usize, "event"),
                s.in_contact
            ),
            short: format!(
                "{} pts · {} steps · {} in contact",
                s.points, s.steps, s.in_contact
            ),
        },
        StatusText {
            full: history_text(s.samples, s.stride),
            short: format!("history: {}", count(s.samples, "sample")),
        },
    ]
}

pub use crate::output::count;

/// The history label: how many samples are kept and how often one is taken
/// ("history: 20 001 samples, every step" / "…, 1 per 4 steps").
pub fn history_text(samples: usize, stride: u64) -> String {
    let every = if stride == 1 {
        "every step".to_string()
    } else {
        format!("1 per {stride} steps")
    };
    format!("history: {}, {every}", count(samples, "sample"))
}

/// `doc`, then `(mark)` if `dirty`.
fn marked(doc: String, dirty: bool, mark: &str) -> String {
    if dirty {
        format!("{doc} ({mark})")
    } else {
        doc
    }
}

/// The document label for narrow windows: the file's name without its
/// folder, "(unsaved)" for "(unsaved changes)".
pub fn short_document_label(
    path: Option<&std::path::Path>,
    scene_name: &str,
    dirty: bool,
) -> String {
    let doc = match path {
        Some(p) => p.file_name().map_or_else(
            || p.display().to_string(),
            |f| f.to_string_lossy().into_owned(),
        ),
        None => format!("{scene_name} (preset)"),
    };
    if dirty {
        format!("{doc} (unsaved)")
    } else {
        doc
    }
}

/// How the labels are shown: `short[k]` takes label `k`'s short text;
/// `doc_max_px`, when set, cuts the document label to that width;
/// `no_history`: the history label is left out (a phone's width), its text
/// in the run label's hover.
#[derive(Debug, Clone, PartialEq)]
pub struct Fit {
    pub short: [bool; 3],
    pub doc_max_px: Option<f32>,
    pub no_history: bool,
}

/// Order in which labels give up their full text (history, run, document).
const SHORTEN_ORDER: [usize; 3] = [2, 1, 0];

/// Chooses full or short texts for labels `full_px[k]` / `short_px[k]`
/// wide (px) so that they plus `other_px` (separators, gaps, the frame
/// rate) fit `avail_px`: labels shorten in `SHORTEN_ORDER` only as far as
/// needed; if even the short texts do not fit, the document label is cut to
/// what is left (at least `min_doc_px`).
pub fn fit(full_px: [f32; 3], short_px: [f32; 3], other_px: f32, avail_px: f32) -> Fit {
    let mut short = [false; 3];
    let width = |short: &[bool; 3]| -> f32 {
        (0..3)
            .map(|k| if short[k] { short_px[k] } else { full_px[k] })
            .sum::<f32>()
            + other_px
    };
    for k in SHORTEN_ORDER {
        if width(&short) <= avail_px {
            return Fit {
                short,
                doc_max_px: None,
                no_history: false,
            };
        }
        short[k] = true;
    }
    let mut over = width(&short) - avail_px;
    // the document cut to its least width still leaves no room: the
    // history label goes (a phone)
    let no_history = over > short_px[0] - MIN_DOC_PX;
    if no_history {
        over -= short_px[2] + HISTORY_GAP_PX;
    }
    let doc_max_px = (over > 0.0).then(|| (short_px[0] - over).max(MIN_DOC_PX));
    Fit {
        short,
        doc_max_px,
        no_history,
    }
}

/// The room (px) of the separator before the history label.
const HISTORY_GAP_PX: f32 = 18.0;

/// The least width (px) the document label is cut to.
pub const MIN_DOC_PX: f32 = 60.0;

/// Width (px) of `text` in the body style on one line.
fn text_px(ui: &Ui, text: &str) -> f32 {
    WidgetText::from(text)
        .into_galley(
            ui,
            Some(TextWrapMode::Extend),
            f32::INFINITY,
            TextStyle::Body,
        )
        .size()
        .x
}

/// The status bar: document, run statistics, history, CSV export, frame rate.
pub fn show(ui: &mut Ui, status: &Status) {
    let texts = texts(status);
    let gap = ui.spacing().item_spacing.x;
    // a separator is its spacing (6 px) wide plus a gap on each side
    let separator_px = 6.0 + 2.0 * gap;
    // measured over a second of play; paused, frames come only on input,
    // and the last rate measured would be stale
    let playing = status.playing;
    let fps_text = if playing && status.fps > 0.0 {
        format!("{:.0} fps", status.fps)
    } else {
        "– fps".to_string()
    };
    let mut other_px = 2.0 * separator_px + text_px(ui, "0000 fps") + 2.0 * gap;
    if status.exporting_csv {
        other_px += separator_px
            + ui.text_style_height(&egui::TextStyle::Body)
            + gap
            + text_px(ui, "writing CSV…");
    }
    let full_px = [0, 1, 2].map(|k| text_px(ui, &texts[k].full));
    let short_px = [0, 1, 2].map(|k| text_px(ui, &texts[k].short));
    let f = fit(full_px, short_px, other_px, ui.available_width());
    // a row of text (a phone's touch-target height made it 47 px high)
    crate::gui::widgets::text_row(ui, |ui| {
        for (k, t) in texts.iter().enumerate() {
            if k == 2 && f.no_history {
                break;
            }
            if k > 0 {
                ui.separator();
            }
            let text = if f.short[k] { &t.short } else { &t.full };
            let mut rich = RichText::new(text);
            if k == 0 && status.dirty {
                rich = rich.color(ERROR_COLOR);
            }
            let label = Label::new(rich).show_tooltip_when_elided(false);
            let r = match f.doc_max_px.filter(|_| k == 0) {
                Some(w) => {
                    ui.scope(|ui| {
                        ui.set_max_width(w);
                        ui.add(label.truncate())
                    })
                    .inner
                }
                None => ui.add(label.extend()),
            };
            if k == 1 && f.no_history {
                r.on_hover_text(format!("{}\n{}", t.full, texts[2].full));
            } else if f.short[k] {
                r.on_hover_text(&t.full);
            }
        }
        if status.exporting_csv {
            ui.separator();
            ui.add(egui::Spinner::new().size(ui.text_style_height(&egui::TextStyle::Body)));
            ui.label("writing CSV…");
        }
        ui.with_layout(egui::Layout::right_to_left(egui::Align::Center), |ui| {
            ui.label(RichText::new(fps_text).weak())
                .on_hover_text(if playing {
                    format!(
                        "frames per second; solver and UI code take {:.1} ms per frame",
                        status.app_ms
                    )
                } else {
                    "frames per second, measured while playing (paused, the window \
                     is drawn only when something changes)"
                        .to_string()
                });
        });
    });
}

/// What the status bar says of the document: its file, or for a scene
/// without one (the embedded default, a shipped or guided preset) its name
/// as a built-in preset; "unsaved changes" only once it was edited.
pub fn document_label(path: Option<&std::path::Path>, scene_name: &str, dirty: bool) -> String {
    let doc = match path {
        Some(p) => p.display().to_string(),
        None => format!("{scene_name} (built-in preset)"),
    };
    if dirty {
        format!("{doc} (unsaved changes)")
    } else {
        doc
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FULL: [f32; 3] = [400.0, 420.0, 300.0];
    const SHORT: [f32; 3] = [250.0, 260.0, 120.0];

    #[test]
    fn counts_and_history_read_as_english() {
        assert_eq!(history_text(1, 1), "history: 1 sample, every step");
        assert_eq!(
            history_text(20001, 4),
            "history: 20001 samples, 1 per 4 steps"
        );
    }

    #[test]
    fn full_texts_when_they_fit() {
        let f = fit(FULL, SHORT, 100.0, 1220.0);
        assert_eq!(f.short, [false; 3]);
        assert_eq!(f.doc_max_px, None);
    }

    #[test]
    fn labels_shorten_history_first_and_only_as_far_as_needed() {
        // 1220 px wanted: 1100 px leaves the history short only
        let f = fit(FULL, SHORT, 100.0, 1100.0);
        assert_eq!(f.short, [false, false, true]);
        // 1040 px wanted with a short history: the run too
        let f = fit(FULL, SHORT, 100.0, 900.0);
        assert_eq!(f.short, [false, true, true]);
        assert_eq!(f.doc_max_px, None);
        // 880 px with both: the document too
        let f = fit(FULL, SHORT, 100.0, 750.0);
        assert_eq!(f.short, [true, true, true]);
        assert_eq!(f.doc_max_px, None);
    }

    #[test]
    fn the_document_label_is_cut_to_what_is_left() {
        // short texts take 630 + 100 px: 700 px leaves 220 px for the document
        let f = fit(FULL, SHORT, 100.0, 700.0);
        assert_eq!(f.short, [true; 3]);
        assert_eq!(f.doc_max_px, Some(220.0));
        assert!(!f.no_history);
        // never below the least width: the history label goes first
        // (630 + 100 px wanted, 500 px: without its 120 + 18 px the
        // document keeps 250 - 92 = 158 px)
        let f = fit(FULL, SHORT, 100.0, 500.0);
        assert!(f.no_history);
        assert_eq!(f.doc_max_px, Some(158.0));
        let f = fit(FULL, SHORT, 100.0, 100.0);
        assert!(f.no_history);
        assert_eq!(f.doc_max_px, Some(MIN_DOC_PX));
    }

    #[test]
    fn the_short_document_label_drops_the_folder() {
        let p = std::path::Path::new("presets/guided_1a_soft_tyre.ron");
        assert_eq!(
            short_document_label(Some(p), "x", true),
            "guided_1a_soft_tyre.ron (unsaved)"
        );
        assert_eq!(short_document_label(None, "Paper", false), "Paper (preset)");
    }

    #[test]
    fn a_built_in_preset_is_named_and_unsaved_only_once_edited() {
        let name = "Paper: ring tyre, five points, sine road";
        assert_eq!(
            document_label(None, name, false),
            "Paper: ring tyre, five points, sine road (built-in preset)"
        );
        assert_eq!(
            document_label(None, name, true),
            "Paper: ring tyre, five points, sine road (built-in preset) (unsaved changes)"
        );
        assert_eq!(
            document_label(Some(std::path::Path::new("presets/a.ron")), name, false),
            "presets/a.ron"
        );
        assert_eq!(
            document_label(Some(std::path::Path::new("presets/a.ron")), name, true),
            "presets/a.ron (unsaved changes)"
        );
    }
}
