//! The export dialogs open in the views' area: below the menu bar and the
//! toolbar, above the status bar (the animation frames dialog opened at the
//! window's top left, over the menu it came from). Opened from the menu by
//! pointer, at 1280 × 720 and 1600 × 1000; the dialog's every widget is
//! read from the accessibility tree.

use crate::harness::{harness_sized, settle};
use egui_kittest::kittest::Queryable;
use tirecontact::gui::App;

/// The rects of `names` (the dialog's title and widgets), leaving out the
/// menu bar's `menu` (the Export menu beside the dialog's Export button).
fn rects(
    h: &egui_kittest::Harness<'_, App>,
    names: &[&str],
    menu: egui::Rect,
) -> Vec<(String, egui::Rect)> {
    let mut out = Vec::new();
    for n in names {
        let found: Vec<egui::Rect> = h
            .get_all_by_label(n)
            .map(|node| node.rect())
            .filter(|r| *r != menu)
            .collect();
        assert!(!found.is_empty(), "no {n:?} in the dialog");
        out.extend(found.into_iter().map(|r| ((*n).to_owned(), r)));
    }
    out
}

#[test]
fn the_export_dialogs_open_below_the_menu_bar_and_toolbar() {
    let dialogs: [(&str, &[&str]); 2] = [
        (
            "Animation frames (PNG)…",
            &["Export animation frames", "Export", "Cancel", "Choose…"],
        ),
        ("Plots as PNG…", &["Export plots as PNG", "Cancel"]),
    ];
    for size in [[1280.0, 720.0], [1600.0, 1000.0]] {
        for (item, names) in dialogs {
            let mut h = harness_sized(App::with_default_preset(), size);
            settle(&mut h);
            // the toolbar's lowest widget and the menu bar's
            let toolbar_bottom = h.get_by_label("Reset").rect().bottom();
            let menu = h.get_by_label("Export").rect();
            h.get_by_label("Export").click();
            h.run();
            h.get_by_label(item).click();
            h.run();
            h.run();
            for (name, r) in rects(&h, names, menu) {
                assert!(
                    r.top() > toolbar_bottom + 2.0,
                    "{size:?} {item}: {name:?} at {r:?} over the menu bar {menu:?} or the toolbar (its bottom {toolbar_bottom})"
                );
                assert!(
                    r.bottom() < size[1] - 20.0 && r.left() >= 0.0 && r.right() <= size[0],
                    "{size:?} {item}: {name:?} at {r:?} out of the views"
                );
            }
        }
    }
}
