//! The A/B compare view's y axis titles fit their plots: in a small window
//! the four stacked plots are short and egui_plot drew each full title
//! (rotated, centred on its plot, never shortened) longer than the plot,
//! into the neighbours' titles. Read from the painted (rotated) text shapes; a
//! shortened title shows the full one on hover over the axis.

use crate::harness::advance;
use egui::{Rect, Shape};
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use egui_plot::PlotMemory;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::View;
use tirecontact::gui::views::compare_view::{
    DISPLACEMENT_DIFF_PLOT_ID, DISPLACEMENT_PLOT_ID, FORCE_DIFF_PLOT_ID, FORCE_PLOT_ID,
};
use tirecontact::gui::{App, Command};
use tirecontact::scene::Tyre;

/// (plot id, full title, short title) of the four plots, top to bottom.
const PLOTS: [(&str, &str, &str); 4] = [
    (
        DISPLACEMENT_PLOT_ID,
        "displacement u (mm, up)",
        "u (mm, up)",
    ),
    (FORCE_PLOT_ID, "contact force q (N)", "q (N)"),
    (
        DISPLACEMENT_DIFF_PLOT_ID,
        "Δu = current − ref (mm)",
        "Δu (mm)",
    ),
    (FORCE_DIFF_PLOT_ID, "Δq = current − ref (N)", "Δq (N)"),
];

/// Rotated texts (the y axis titles) and their painted bounds.
fn rotated_texts(h: &Harness<'_, App>) -> Vec<(String, Rect)> {
    fn walk(s: &Shape, out: &mut Vec<(String, Rect)>) {
        match s {
            Shape::Vec(v) => v.iter().for_each(|s| walk(s, out)),
            Shape::Text(t) if t.angle != 0.0 => {
                out.push((t.galley.text().to_owned(), t.visual_bounding_rect()))
            }
            _ => {}
        }
    }
    let mut out = Vec::new();
    for c in &h.output().shapes {
        walk(&c.shape, &mut out);
    }
    out
}

fn frame(h: &Harness<'_, App>, id: &str) -> Rect {
    *PlotMemory::load(&h.ctx, egui::Id::unique(id))
        .expect("plot shown")
        .transform()
        .frame()
}

/// A run pinned, the scene edited and run again: four plots; the text
/// `text_scale` times egui's size (a large-text setting).
fn compare(size: [f32; 2], text_scale: f32) -> Harness<'static, App> {
    let mut scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    scene.duration_s = 0.03;
    let mut h = crate::harness::harness_sized(App::new(scene.clone(), None).unwrap(), size);
    h.ctx.all_styles_mut(|s| {
        for f in s.text_styles.values_mut() {
            f.size *= text_scale;
        }
    });
    h.run();
    advance(&mut h, 3000);
    h.state_mut().apply(Command::ShowView(View::Compare));
    h.run_steps(2);
    h.get_by_label("Pin as reference").click();
    h.run_steps(2);
    let mut edited = scene.clone();
    if let Tyre::Modal { modes } = &mut edited.tyre {
        modes[0].freq_hz *= 1.1;
    }
    h.state_mut().apply(Command::EditScene(Box::new(edited)));
    h.run_steps(1);
    advance(&mut h, 3000);
    h.run_steps(4);
    h
}

/// Checks the titles of the plots in view (the view scrolls to the
/// others); returns the plots whose title was shortened.
fn check(h: &Harness<'_, App>, size: [f32; 2]) -> Vec<usize> {
    let texts = rotated_texts(h);
    let bottom = crate::harness::status_top(h);
    let mut titles = Vec::new();
    let mut shortened = Vec::new();
    for (k, (id, full, short)) in PLOTS.iter().enumerate() {
        let f = frame(h, id);
        if f.bottom() > bottom {
            continue;
        }
        let (text, r) = texts
            .iter()
            .find(|(t, r)| {
                (t == full || t == short)
                    && r.right() <= f.left()
                    && f.y_range().contains(r.center().y)
            })
            .unwrap_or_else(|| panic!("{size:?}: no title of {id} beside {f:?} in {texts:?}"));
        eprintln!(
            "{size:?}: {id}: {text:?}, {:.1} px long ({:.1}..{:.1}) in a frame {:.1} px high ({:.1}..{:.1})",
            r.height(),
            r.top(),
            r.bottom(),
            f.height(),
            f.top(),
            f.bottom()
        );
        assert!(
            r.top() >= f.top() - 0.5 && r.bottom() <= f.bottom() + 0.5,
            "{size:?}: title {text:?} of {id} spans {:.1}..{:.1} px, its plot {:.1}..{:.1} px",
            r.top(),
            r.bottom(),
            f.top(),
            f.bottom()
        );
        if text != full || r.width() < 13.0 {
            shortened.push(k);
        }
        titles.push((text.clone(), *r));
    }
    assert!(!titles.is_empty(), "{size:?}: no plot in view");
    for (i, (a, ra)) in titles.iter().enumerate() {
        for (b, rb) in &titles[i + 1..] {
            assert!(
                !ra.intersects(*rb),
                "{size:?}: {a:?} at {ra:?} runs into {b:?} at {rb:?}"
            );
        }
    }
    shortened
}

#[test]
fn compare_titles_fit_their_plots_and_show_in_full_on_hover() {
    // the plots keep a least height: in large text some full titles are
    // longer than that
    let small = [1280.0, 720.0];
    let mut h = compare(small, 1.5);
    let bottom = crate::harness::status_top(&h);
    // the premise: some full title in body text (egui_plot's default) is
    // longer than its plot
    let body = egui::TextStyle::Body.resolve(&h.ctx.global_style());
    let too_long: Vec<&str> = PLOTS
        .iter()
        .filter(|(id, full, _)| {
            let f = frame(&h, id);
            if f.bottom() > bottom {
                return false;
            }
            let len = h.ctx.fonts_mut(|f| {
                f.layout_no_wrap(full.to_string(), body.clone(), egui::Color32::WHITE)
                    .size()
                    .x
            });
            len > f.height()
        })
        .map(|p| p.1)
        .collect();
    assert!(
        !too_long.is_empty(),
        "the premise: full titles fit at {small:?} in large text"
    );
    let shortened = check(&h, small);
    assert!(!shortened.is_empty(), "{too_long:?} are not shortened");
    // hovering the axis of a shortened title shows it in full
    let k = shortened[0];
    let (id, full, _) = PLOTS[k];
    assert!(h.query_by_label(full).is_none());
    let f = frame(&h, id);
    h.hover_at(egui::pos2(f.left() - 20.0, f.center().y));
    for _ in 0..60 {
        h.run_steps(1);
    }
    assert!(
        h.query_by_label(full).is_some(),
        "hovering the axis of {id} shows {full:?}"
    );

    for size in [[900.0, 600.0], [1280.0, 720.0], [1600.0, 1000.0]] {
        let h = compare(size, 1.0);
        check(&h, size);
    }
}
