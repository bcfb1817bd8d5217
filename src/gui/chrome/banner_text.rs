//! The banner's text as laid out: a preset's syntax error quotes its source
//! line with a caret under the column (`Scene::parse`), which only points at
//! the column in a monospace font. In the body font the caret of
//! "4 |     tyre: Modal(" sat under the blanks before `tyre`.

use egui::text::{LayoutJob, TextFormat};
use egui::{Color32, FontId, TextStyle, Ui};

/// Whether `line` is a line of a quoted source excerpt: `  12 | text` or
/// `       |    ^` (`scene::load::source_excerpt`).
pub fn is_excerpt_line(line: &str) -> bool {
    let t = line.trim_start();
    if t.len() == line.len() {
        return false;
    }
    let rest = t.trim_start_matches(|c: char| c.is_ascii_digit());
    rest == "|" || rest.starts_with("| ") || rest.starts_with(" | ") || rest == " |"
}

/// `text` in `color`, its excerpt lines in the monospace font, the others
/// in the body font.
pub fn layout(ui: &Ui, text: &str, color: Color32) -> LayoutJob {
    let body: FontId = TextStyle::Body.resolve(ui.style());
    let mono: FontId = TextStyle::Monospace.resolve(ui.style());
    let mut job = LayoutJob::default();
    let n = text.split('\n').count();
    for (k, line) in text.split('\n').enumerate() {
        let font = if is_excerpt_line(line) {
            mono.clone()
        } else {
            body.clone()
        };
        let mut piece = line.to_string();
        if k + 1 < n {
            piece.push('\n');
        }
        job.append(&piece, 0.0, TextFormat::simple(font, color));
    }
    job
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpt_lines_are_told_from_prose() {
        assert!(is_excerpt_line("     4 |     tyre: Modal("));
        assert!(is_excerpt_line("       |     ^"));
        assert!(is_excerpt_line("  1234 | ...abc"));
        assert!(!is_excerpt_line(
            "Cannot open this preset; the current scene is kept."
        ));
        assert!(!is_excerpt_line("/tmp/a.ron:4:5: Expected comma"));
        assert!(!is_excerpt_line(
            "  tyre.modes[0].damping_ratio = -2: expected"
        ));
        assert!(!is_excerpt_line("| not indented"));
    }
}
