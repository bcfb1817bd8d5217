//! The workbench of the measured preset on a laptop screen (1280 × 720):
//! the picks, their buttons and the stabilisation diagram in the window
//! without scrolling, the frequency-domain fit of the FRFs folded below
//! them and reached with the mouse wheel, and one line naming what each
//! count of modes counts.

use crate::harness::{harness_sized, settle};
use egui_kittest::Harness;
use egui_kittest::kittest::{NodeT, Queryable};
use egui_plot::PlotMemory;
use tirecontact::gui::views::workbench_view::{DIAGRAM_PLOT_ID, FRF_SECTION, PAIR_PLOT_ID};
use tirecontact::gui::{App, Command, View};

const SIZE: [f32; 2] = [1280.0, 720.0];

/// The measured preset's workbench at 1280 × 720, identified.
fn measured_workbench() -> Harness<'static, App> {
    measured_workbench_sized(SIZE)
}

/// The measured preset's workbench in a window of `size`, identified.
fn measured_workbench_sized(size: [f32; 2]) -> Harness<'static, App> {
    let scene = crate::support::preset("measured_example");
    let mut h = harness_sized(App::new(scene, None).unwrap(), size);
    settle(&mut h);
    h.state_mut().apply(Command::ShowView(View::Workbench));
    h.run_steps(1);
    for _ in 0..20_000 {
        if h.state().research().workbench().is_some() && !h.state().research().workbench_computing()
        {
            h.run_steps(3);
            return h;
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
        h.run_steps(1);
    }
    panic!("the workbench never identified");
}

/// The window's bottom less the status bar: what is seen of the view.
fn view_bottom(h: &Harness<'_, App>) -> f32 {
    // the status bar's history label is at the window's bottom
    let bar = h.get_by_label_contains("history:").rect();
    bar.top().min(SIZE[1])
}

#[test]
fn the_diagram_and_the_picks_are_in_view_and_the_wheel_scrolls_to_the_fit() {
    let mut h = measured_workbench();
    assert!(
        matches!(h.state().research().frf_fit(), Some(Ok(_))),
        "the preset's file holds FRFs: {:?}",
        h.state().research().frf_fit().map(|r| r.as_ref().err())
    );
    let bottom = view_bottom(&h);
    for button in [
        "Automatic choice",
        "Use these modes",
        "Save as modal preset…",
    ] {
        let r = h.get_by_label(button).rect();
        assert!(
            r.top() >= 0.0 && r.bottom() <= bottom,
            "{button} at {r:?}, the view ends at {bottom}"
        );
    }
    let diagram = *PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID))
        .expect("the diagram")
        .transform()
        .frame();
    assert!(
        diagram.height() >= 160.0 && diagram.bottom() <= bottom,
        "the diagram at {diagram:?}, the view ends at {bottom}"
    );
    // the fit of the FRFs follows, folded: its data and errors not drawn
    let header = h.get_by_label(FRF_SECTION).rect();
    assert!(header.top() > diagram.bottom(), "{header:?} {diagram:?}");
    assert!(
        h.query_by_label_contains("residual terms of the").is_none(),
        "the fit's section is open"
    );
    // opened, the fit makes the view taller than the window: the wheel
    // over the worst pair's plot scrolls the view to it
    h.get_by_label(FRF_SECTION).click_accesskit();
    h.run_steps(3);
    assert!(h.query_by_label_contains("residual terms of the").is_some());
    let header = h.get_by_label(FRF_SECTION).rect();
    let pair = *PlotMemory::load(&h.ctx, egui::Id::unique(PAIR_PLOT_ID))
        .expect("the worst pair's plot")
        .transform()
        .frame();
    h.hover_at(pair.center());
    h.run_steps(1);
    for _ in 0..5 {
        h.event(egui::Event::MouseWheel {
            unit: egui::MouseWheelUnit::Point,
            delta: egui::vec2(0.0, -120.0),
            phase: egui::TouchPhase::Move,
            source: egui::MouseWheelSource::Unknown,
            modifiers: egui::Modifiers::NONE,
        });
        h.run_steps(2);
    }
    h.run_steps(30);
    let moved = h.get_by_label(FRF_SECTION).rect();
    assert!(
        moved.top() < header.top() - 100.0,
        "the wheel left the fit's header at {moved:?} (was {header:?})"
    );
}

#[test]
fn each_count_of_modes_says_what_it_counts() {
    let h = measured_workbench();
    let run = h.state().modes().len();
    let Some(Ok(w)) = h.state().research().workbench() else {
        panic!("no workbench")
    };
    let picked = w.modes.len();
    let left_out = w.left_out_hz.len();
    let Some(Ok(fit)) = h.state().research().frf_fit() else {
        panic!("no fit of the FRFs")
    };
    let lscf = fit.poles.len();
    // the three counts, each named, one a line: in one line they wrapped
    // mid-count at 1280 px
    let line =
        format!("Modes: the run uses {run} modes (identified by LSCE, the side panel's list)");
    let node = h.get_by_label_contains(&line);
    let a = node.accesskit_node();
    let text = a.label().or_else(|| a.value()).unwrap_or_default();
    let rows = h
        .output()
        .shapes
        .iter()
        .find_map(|c| match &c.shape {
            egui::Shape::Text(t) if t.galley.text().starts_with("Modes: ") => {
                Some(t.galley.rows.len())
            }
            _ => None,
        })
        .expect("the counts drawn");
    assert_eq!(rows, text.lines().count(), "a count wrapped: {text}");
    assert_eq!(text.lines().count(), 3, "{text}");
    assert!(text.contains(&format!("{picked} picked here")), "{text}");
    if left_out > 0 {
        assert_eq!(picked + left_out, run, "{text}");
        assert!(
            text.contains(&format!("{left_out} of the identified left out")),
            "{text}"
        );
    } else {
        assert_eq!(picked, run, "{text}");
    }
    assert!(
        text.contains(&format!(
            "{lscf} in the frequency-domain fit (LSCF, a check of the FRFs"
        )),
        "{text}"
    );
    // the side panel's list says it is the run's
    assert!(
        h.query_by_label(&format!("{run} identified modes, used by the run"))
            .is_some()
    );
}

/// On a phone the diagram keeps a readable height under its legend, whose
/// rows are touch-target tall there (it was squeezed to about 20 px, its
/// caption over it).
#[test]
fn on_a_phone_the_diagram_keeps_its_height() {
    let h = measured_workbench_sized([412.0, 915.0]);
    let diagram = *PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID))
        .expect("the diagram")
        .transform()
        .frame();
    assert!(diagram.height() >= 100.0, "the diagram's frame {diagram:?}");
    assert!(
        diagram.right() <= 412.0,
        "the diagram's frame {diagram:?} leaves the window"
    );
}

/// Each marker of the diagram's legend sits on its name's row, the name in
/// one line (a name that did not fit the rest of a row wrapped onto the
/// next, its marker left at the row's end).
#[test]
fn on_a_phone_each_legend_marker_sits_beside_its_name() {
    use tirecontact::gui::views::workbench_view::{PICKED, PICKED_COLOR};
    let h = measured_workbench_sized([412.0, 915.0]);
    let texts = crate::harness::texts(&h);
    let row_px = texts
        .iter()
        .find(|(t, _)| t == "stable in f")
        .map(|(_, r)| r.height())
        .expect("a one-word legend name");
    for name in [
        "summed |G| of the data (dB, scaled)",
        "stable in f, ξ and shape",
        "stable in f and ξ",
        "new or unstable",
        PICKED,
    ] {
        let (_, r) = texts
            .iter()
            .find(|(t, _)| t == name)
            .unwrap_or_else(|| panic!("no legend name {name:?}"));
        assert!(r.height() < 1.5 * row_px, "{name:?} wraps: {r:?}");
    }
    let (_, name) = texts.iter().find(|(t, _)| t == PICKED).unwrap();
    let diagram = *PlotMemory::load(&h.ctx, egui::Id::unique(DIAGRAM_PLOT_ID))
        .expect("the diagram")
        .transform()
        .frame();
    let rings: Vec<egui::Pos2> = crate::harness::shapes(&h)
        .into_iter()
        .filter_map(|s| match s {
            egui::Shape::Circle(c) if c.stroke.color == PICKED_COLOR => Some(c.center),
            _ => None,
        })
        .filter(|c| c.y < diagram.top())
        .collect();
    assert_eq!(rings.len(), 1, "one ring in the legend: {rings:?}");
    let ring = rings[0];
    assert!(
        ring.y >= name.top() && ring.y <= name.bottom() && ring.x <= name.left(),
        "the ring at {ring:?}, its name at {name:?}"
    );
}
