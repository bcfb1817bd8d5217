//! The sweep panel: a numeric scene field (every path `crate::studies::sweep`
//! accepts), from, to, steps; Run starts it on a background thread with a
//! progress bar and Cancel; the results (max force, force RMS, contact
//! fraction, rolling-noise band levels) are plotted against the parameter
//! and exported as CSV and PNG like `tirecontact sweep`.

use super::XTitle;
use super::point_color;
use crate::Scene;
use crate::analysis::spectrum::third_octave_bands;
use crate::gui::model::command::{Command, ResearchCommand};
use crate::gui::model::sweep_request::{SweepRequest, SweepResult};
use crate::gui::research::state::SweepForm;
use crate::gui::research::sweep_job::{SweepState, default_threads};
use crate::studies::sweep::{RunSummary, get_param, param_paths};
use egui::{Color32, RichText, Ui};
use egui_plot::{Line, MarkerShape, Plot, Points};

/// The unit of a parameter (the scene format's table of fields; empty
/// for a count).
fn param_unit(path: &str) -> &'static str {
    crate::scene::fields::unit(path).unwrap_or("")
}

pub fn show(
    ui: &mut Ui,
    scene: &Scene,
    state: &SweepState,
    form: &mut SweepForm,
    cmds: &mut Vec<Command>,
) {
    let paths = param_paths(scene);
    if get_param(scene, &form.param).is_err() {
        form.param = paths.first().cloned().unwrap_or_default();
    }
    request_form(ui, scene, &paths, state.is_running(), form, cmds);
    super::scrolling_view(ui, "tirecontact.sweep.scroll", |ui, room| {
        outcome(ui, scene, state, cmds, room)
    });
}

/// The parameter, its range and steps, Run and Cancel.
fn request_form(
    ui: &mut Ui,
    scene: &Scene,
    paths: &[String],
    running: bool,
    form: &mut SweepForm,
    cmds: &mut Vec<Command>,
) {
    ui.horizontal_wrapped(|ui| {
        ui.label("parameter");
        let before = form.param.clone();
        egui::ComboBox::from_id_salt("tirecontact.sweep_param")
            .selected_text(crate::scene::fields::axis_label(&form.param))
            .height(400.0)
            .show_ui(ui, |ui| {
                // the editor's names with units; the preset path on hover
                for p in paths {
                    ui.selectable_value(
                        &mut form.param,
                        p.clone(),
                        crate::scene::fields::axis_label(p),
                    )
                    .on_hover_text(format!("preset field `{p}`"));
                }
            })
            .response
            .accessible_name("sweep parameter")
            .on_hover_text(format!("preset field `{}`", form.param));
        if form.param != before
            && let Ok(v) = get_param(scene, &form.param)
        {
            // a range around the current value
            (form.from, form.to) = if v != 0.0 {
                (0.8 * v, 1.2 * v)
            } else {
                (0.0, 1.0)
            };
        }
        let unit = param_unit(&form.param);
        if let Ok(v) = get_param(scene, &form.param) {
            ui.label(
                RichText::new(format!(
                    "(now {} {unit})",
                    crate::gui::widgets::number::format_number(v)
                ))
                .weak(),
            );
        }
        ui.separator();
        ui.label("from");
        ui.add(
            egui::DragValue::new(&mut form.from)
                .speed(0.1)
                .suffix(format!(" {unit}")),
        )
        .accessible_name("sweep from");
        ui.label("to");
        ui.add(
            egui::DragValue::new(&mut form.to)
                .speed(0.1)
                .suffix(format!(" {unit}")),
        )
        .accessible_name("sweep to");
        ui.label("steps");
        ui.add(egui::DragValue::new(&mut form.steps).range(2..=500))
            .on_hover_text("runs from `from` to `to`, both included: 2 to 500")
            .accessible_name("sweep steps");
        ui.separator();
        let run = ui.add_enabled(
            !running,
            egui::Button::new(RichText::new("Run sweep").strong()),
        );
        if run
            .on_hover_text(format!(
                "runs the scene once per value, to its end, on {} threads in the background",
                default_threads()
            ))
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::StartSweep(
                SweepRequest {
                    param: form.param.clone(),
                    from: form.from,
                    to: form.to,
                    steps: form.steps,
                },
            )));
        }
        if ui
            .add_enabled(running, egui::Button::new("Cancel"))
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::CancelSweep));
        }
    });
}

/// The sweep's progress, or how it ended, with its exports and plots.
/// `room`: where the view's content began, below the form.
fn outcome(
    ui: &mut Ui,
    scene: &Scene,
    state: &SweepState,
    cmds: &mut Vec<Command>,
    room: super::ViewRoom,
) {
    match state {
        SweepState::Idle => {
            ui.label("No sweep yet: choose a parameter and a range, then Run sweep. Each run summarises its steady part (from the end of the ramp).");
        }
        SweepState::Running(job) => {
            let f = job.progress();
            ui.add(
                egui::ProgressBar::new(f as f32)
                    .show_percentage()
                    .text(format!(
                        "{} runs of {} on {} threads: {:.0} % of the solver steps{}",
                        job.runs,
                        crate::scene::fields::label(&job.request.param),
                        job.threads,
                        100.0 * f,
                        if job.cancel_requested() {
                            " (cancelling …)"
                        } else {
                            ""
                        }
                    )),
            );
        }
        SweepState::Cancelled => {
            ui.label(RichText::new("The sweep was cancelled; no results were kept. The scene and the run are unchanged.").color(Color32::from_rgb(180, 90, 0)));
        }
        SweepState::Failed(e) => {
            ui.label(
                RichText::new(format!("The sweep failed: {e}"))
                    .color(crate::gui::widgets::fields::ERROR_COLOR),
            );
        }
        SweepState::Finished(r) => {
            ui.horizontal_wrapped(|ui| {
                ui.label(format!(
                    "{} runs of {} from {} to {} {} ({} failed) on {} threads in {} (scene “{}”)",
                    r.points.len(),
                    crate::scene::fields::label(&r.request.param),
                    r.request.from,
                    r.request.to,
                    param_unit(&r.request.param),
                    r.failed(),
                    r.threads,
                    super::wall_time_text(r.wall_s),
                    r.base.name
                ));
                if ui
                    .button("Export CSV…")
                    .on_hover_text("same table as `tirecontact sweep -o`")
                    .clicked()
                {
                    cmds.push(Command::Research(ResearchCommand::ExportSweepCsvDialog));
                }
                if ui
                    .button("Export PNG…")
                    .on_hover_text("same figure as `tirecontact sweep --plot`")
                    .clicked()
                {
                    cmds.push(Command::Research(ResearchCommand::ExportSweepPngDialog));
                }
            });
            if r.differs_from(scene) {
                ui.label(RichText::new(OTHER_SCENE_NOTE).color(Color32::from_rgb(180, 90, 0)));
            }
            // the swept scene's contact, which the results are of
            if r.base.contact.is_rigid() {
                ui.label(RichText::new(RIGID_FORCE_NOTE).weak());
            }
            let left_px = room.left_px(ui);
            plots(ui, r, left_px);
        }
    }
}

/// Under finished results once the scene differs from the one swept (an
/// edit, another document).
pub const OTHER_SCENE_NOTE: &str = "These results are of the scene as it was when the sweep \
ran; the current scene differs from it (it has been edited, or another one is open). Run \
sweep again for the current scene.";

/// What the force figures of a rigid-contact sweep hold: the force without
/// impacts, and the impacts as impulses (as impulse / dt they would be tens
/// of kN that double when dt halves).
pub const RIGID_FORCE_NOTE: &str = "Rigid contact: a landing is an impulse. The max force \
is the contact force without impacts and the impacts are shown as impulses (N·s); both \
keep their values when dt shrinks.";

/// The ids of the four plots (max force, impulse, contact, bands); their
/// plots' and legends' ids are `egui::Id::unique` of these.
pub const PLOT_IDS: [&str; 4] = [
    "tirecontact.sweep_max",
    "tirecontact.sweep_impulse",
    "tirecontact.sweep_contact",
    "tirecontact.sweep_bands",
];

/// Named, coloured curves of one plot.
type Curves = Vec<(String, Color32, Vec<[f64; 2]>)>;

/// Short y titles of the four plots, in [`PLOT_IDS`]' order: where the
/// full one (the figure's) is longer than its plot's frame.
pub const SHORT_Y_TITLES: [&str; 4] = [
    "max force (N)",
    "impulse (N·s)",
    "in contact (%)",
    "band level (dB re 1 N)",
];

/// Least height (px) of a plot of the view: its points, legend and axes
/// readable. Where two rows do not fit the view at this height, the view
/// scrolls.
pub const MIN_PLOT_PX: f32 = 180.0;

/// Least width (px) of a plot side by side with another; a narrower view
/// (a phone) stacks the four plots in one column.
pub const MIN_PLOT_WIDTH_PX: f32 = 200.0;

/// The four plots in two rows sharing `left_px` of height (one column of
/// four where two side by side would be narrower than
/// [`MIN_PLOT_WIDTH_PX`]).
fn plots(ui: &mut Ui, r: &SweepResult, left_px: f32) {
    use crate::studies::sweep::report::{Y_TITLES, band_series_name, contact_curves};
    // the sweep figure's labels (one labelling for the view and the PNG)
    let x_label = crate::scene::fields::axis_label(&r.request.param);
    let ok: Vec<(f64, &RunSummary)> = r
        .points
        .iter()
        .filter_map(|p| p.result.as_ref().ok().map(|s| (p.value, s)))
        .collect();
    let gap = ui.spacing().item_spacing;
    let columns = if ui.available_width() - gap.x >= 2.0 * MIN_PLOT_WIDTH_PX {
        2
    } else {
        1
    };
    let w = ((ui.available_width() - gap.x * (columns - 1) as f32) / columns as f32).max(1.0);
    let h = ((left_px - gap.y) / 2.0).max(MIN_PLOT_PX);
    // one labelling with the figure: a curve per point, or all the points'
    let [force, impulse, contact] = contact_curves(&r.columns, &r.points).map(|curves| -> Curves {
        curves
            .into_iter()
            .enumerate()
            .map(|(i, (name, pts))| {
                (
                    name,
                    point_color(i),
                    pts.into_iter().map(|(x, y)| [x, y]).collect(),
                )
            })
            .collect()
    });
    let bands: Curves = third_octave_bands(315.0, 2000.0)
        .iter()
        .step_by(2)
        .enumerate()
        .map(|(k, b)| {
            (
                band_series_name(b.nominal_hz),
                point_color(k),
                ok.iter()
                    .filter_map(|(v, s)| {
                        s.bands
                            .iter()
                            .find(|x| x.band.nominal_hz == b.nominal_hz)
                            .filter(|x| x.level_db.is_finite())
                            .map(|x| [*v, x.level_db])
                    })
                    .collect(),
            )
        })
        .collect();
    let grid: [(&str, (&str, &str), Curves); 4] = [
        (PLOT_IDS[0], (Y_TITLES[0], SHORT_Y_TITLES[0]), force),
        (PLOT_IDS[1], (Y_TITLES[1], SHORT_Y_TITLES[1]), impulse),
        (PLOT_IDS[2], (Y_TITLES[2], SHORT_Y_TITLES[2]), contact),
        (PLOT_IDS[3], (Y_TITLES[3], SHORT_Y_TITLES[3]), bands),
    ];
    let mut it = grid.into_iter();
    for _ in 0..4 / columns {
        ui.horizontal(|ui| {
            for _ in 0..columns {
                let Some((id, (y_label, y_short), series)) = it.next() else {
                    return;
                };
                let legend_id = egui::Id::unique(id);
                let labels: Vec<&str> = series.iter().map(|c| c.0.as_str()).collect();
                let legend_px = super::legend_place::legend_size(ui, &labels, h);
                // first to last downwards in every corner, as in the PNG
                let mut series = series;
                if super::legend_place::upwards(ui.ctx(), legend_id) {
                    series.reverse();
                }
                // the title fits the frame: a full one longer than the
                // plot ran into the text above it
                let title_id = legend_id.with("y_title");
                let title = super::axis_title::fit_plot(ui, title_id, y_label, y_short, h, true);
                let r = super::nice_y_axis(Plot::new(id))
                    .id(legend_id)
                    .width(w)
                    .height(h)
                    .legend(
                        super::legend_place::legend(ui.ctx(), legend_id, h)
                            .follow_insertion_order(true),
                    )
                    .x_title(ui, x_label.clone())
                    .nice_x()
                    .y_axis_label(title.text.clone())
                    .y_axis_min_width(56.0)
                    .allow_scroll(false)
                    .show(ui, |pui| {
                        let mut ink = super::legend_place::Ink::default();
                        for (name, c, pts) in series {
                            ink.add(pui, &pts);
                            pui.line(Line::new(name.clone(), pts.clone()).color(c).width(1.5));
                            pui.points(
                                Points::new(name, pts)
                                    .color(c)
                                    .radius(3.0)
                                    .shape(MarkerShape::Circle),
                            );
                        }
                        ink.place(pui, legend_id, legend_px);
                    });
                super::axis_title::after_plot(ui, title_id, &title, y_label, &r);
            }
        });
    }
}
