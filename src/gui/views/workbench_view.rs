//! The identification workbench: the stabilisation diagram (frequency
//! against model order, a marker per pole by how it persists from the
//! order below) over the summed `|G|` of the data, the poles picked (the
//! automatic choice to begin with; click a pole to pick or drop it), the
//! `|G|` of the worst-fitted response pair, data against the picked modes,
//! and every pair's L2 error. "Use these modes" makes them the scene's
//! modal tyre; "Save as modal preset…" writes that scene. For a measured
//! UFF file of FRFs their frequency-domain fit (method §6.5: data against
//! fit per pair, the residual terms and the driving-point check) follows,
//! folded. One line above says how many modes the run uses, how many are
//! picked and how many the frequency-domain fit found, each named for what
//! it counts. The whole view scrolls with the mouse wheel. The logic is
//! `identify::workbench` and `identify::frequency`; this view draws it and
//! pushes commands.

use super::XTitle;
use crate::Scene;
use crate::gui::model::command::{Command, ResearchCommand};
use crate::identify::driving::{self, DrivingPoint};
use crate::identify::frequency::FrfIdentification;
use crate::identify::workbench::Workbench;
use crate::model::stability::{DiagramOrder, Stability, points_of};
use crate::scene::Tyre;
use egui::{Color32, RichText, Ui};
use egui_plot::{Line, LineStyle, MarkerShape, Plot, Points};

/// Plot id of the stabilisation diagram (read by the tests).
pub const DIAGRAM_PLOT_ID: &str = "tirecontact.workbench.diagram";

/// Least height (px) of the stabilisation diagram's frame and axes.
pub const MIN_DIAGRAM_PX: f32 = 140.0;
/// Legend entry of the picked poles.
pub const PICKED: &str = "picked (click a pole to pick or drop it)";
/// Colour of the picked poles' rings.
pub const PICKED_COLOR: Color32 = Color32::from_rgb(230, 159, 0);
/// A click picks the pole nearest it within this many pixels in frequency.
pub const PICK_PX: f32 = 10.0;

/// A category's legend name, marker shape and colour in the diagram.
fn category(stability: Stability) -> (&'static str, MarkerShape, Color32) {
    match stability {
        Stability::Stable => (
            "stable in f, ξ and shape",
            MarkerShape::Circle,
            Color32::from_rgb(0, 158, 115),
        ),
        Stability::FrequencyDamping => (
            "stable in f and ξ",
            MarkerShape::Diamond,
            Color32::from_rgb(86, 180, 233),
        ),
        Stability::Frequency => (
            "stable in f",
            MarkerShape::Square,
            Color32::from_rgb(0, 114, 178),
        ),
        Stability::New => (
            "new or unstable",
            MarkerShape::Cross,
            Color32::from_rgb(150, 150, 150),
        ),
        Stability::Damped => (
            "damping above the limit (not a mode)",
            MarkerShape::Plus,
            Color32::from_rgb(204, 121, 167),
        ),
    }
}

/// Plot id of the `|G|` of the worst-fitted pair (read by the tests).
pub const PAIR_PLOT_ID: &str = "tirecontact.workbench.pair";
/// Title of the frequency-domain fit's section (read by the tests).
pub const FRF_SECTION: &str = "Frequency-domain fit of the FRFs (LSCF poles, LSFD residues)";

/// What the workbench shows: the scene, its identification and the modes
/// its run uses.
pub struct Shown<'a> {
    pub scene: &'a Scene,
    pub bench: Option<&'a Result<Workbench, String>>,
    pub frf: Option<&'a Result<FrfIdentification, String>>,
    pub computing: bool,
    /// The scene's tyre is the modes used from this workbench.
    pub in_use: bool,
    /// Modes the run uses (the side panel's list).
    pub run_modes: usize,
}

/// The workbench in a vertical scroll area that takes the mouse wheel:
/// the counts of modes, the picks and their buttons, the diagram and the
/// worst pair fill the view; the frequency-domain fit of a file of FRFs
/// follows them, folded.
pub fn show(ui: &mut Ui, s: &Shown<'_>, cmds: &mut Vec<Command>) {
    let given = match s.scene.tyre {
        Tyre::Modal { .. } => Some("a modal model given mode by mode"),
        Tyre::Plate { .. } => Some("an orthotropic plate, whose modes are in closed form"),
        Tyre::FeModes { .. } => Some("the modes of a finite-element model, read as they are"),
        Tyre::Ring { .. } | Tyre::Measured { .. } => None,
    };
    if let Some(what) = given.filter(|_| !s.in_use) {
        ui.label(format!("The workbench identifies a ring or measured tyre from its responses. This scene's tyre is {what}, with nothing to identify: open a ring or measured preset (presets/paper.ron, presets/measured_example.ron)."));
        return;
    }
    egui::ScrollArea::vertical()
        .id_salt("tirecontact.workbench.scroll")
        .auto_shrink(false)
        .show(ui, |ui| body(ui, s, cmds));
}

/// A relative error `x` as a percentage, three significant digits.
fn percent(x: f64) -> String {
    format!("{} %", crate::output::summary::short_num(100.0 * x, 3))
}

/// The count of modes each part of the workbench gives, one a line (in
/// one line the three wrapped mid-count in a 1280 px window): the run's
/// (the side panel's list), the picks' and the frequency-domain fit's,
/// each named for what it counts.
pub fn counts_text(
    run_modes: usize,
    in_use: bool,
    picked: Option<usize>,
    left_out: usize,
    frf: Option<usize>,
) -> String {
    use crate::output::count;
    let mut parts = vec![format!(
        "the run uses {} ({}, the side panel's list)",
        count(run_modes, "mode"),
        if in_use {
            "picked here"
        } else {
            "identified by LSCE"
        }
    )];
    if let Some(p) = picked {
        parts.push(if left_out > 0 && !in_use {
            format!("{p} picked here ({left_out} of the identified left out: no persisting pole)")
        } else {
            format!("{p} picked here")
        });
    }
    if let Some(k) = frf {
        parts.push(format!(
            "{k} in the frequency-domain fit (LSCF, a check of the FRFs; the run does not use it)"
        ));
    }
    format!("Modes: {}", parts.join("\n· "))
}

fn body(ui: &mut Ui, s: &Shown<'_>, cmds: &mut Vec<Command>) {
    let (bench, frf) = (s.bench, s.frf);
    if s.computing {
        ui.horizontal(|ui| {
            ui.spinner();
            ui.label("identifying the tyre's responses (LSCE, every model order)…");
        });
    }
    let picked = match bench {
        Some(Ok(w)) => Some((w.modes.len(), w.left_out_hz.len())),
        _ => None,
    };
    let frf_modes = match frf {
        Some(Ok(f)) => Some(f.poles.len()),
        _ => None,
    };
    if picked.is_some() || frf_modes.is_some() {
        ui.label(counts_text(
            s.run_modes,
            s.in_use,
            picked.map(|p| p.0),
            picked.map_or(0, |p| p.1),
            frf_modes,
        ));
    }
    let w = match bench {
        Some(Ok(w)) => w,
        Some(Err(e)) if matches!(frf, Some(Ok(_))) => {
            ui.label(format!(
                "No time-domain identification (LSCE): {e}. The frequency-domain fit below is the only one."
            ));
            if let Some(f) = frf {
                frf_section(ui, f, true);
            }
            return;
        }
        Some(Err(e)) => {
            ui.label(
                RichText::new(format!("No identification: {e}")).color(ui.visuals().error_fg_color),
            );
            if let Some(f) = frf {
                frf_section(ui, f, true);
            }
            return;
        }
        None => {
            if let Some(f) = frf {
                frf_section(ui, f, true);
            }
            return;
        }
    };
    ui.horizontal_wrapped(|ui| {
        if ui
            .button("Automatic choice")
            .on_hover_text("the poles of the order chosen from the stabilisation diagram")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::WorkbenchAutomatic));
        }
        let any = !w.modes.is_empty();
        if ui
            .add_enabled(any, egui::Button::new("Use these modes"))
            .on_hover_text("the picked modes become the scene's modal tyre (the run restarts)")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::WorkbenchUse));
        }
        if ui
            .add_enabled(any, egui::Button::new("Save as modal preset…"))
            .on_hover_text("write the scene with the picked modes as its tyre")
            .clicked()
        {
            cmds.push(Command::Research(ResearchCommand::WorkbenchSaveDialog));
        }
        ui.separator();
        ui.label(format!(
            "{} picked; time error of their fit {} (relative L2)",
            crate::output::count(w.modes.len(), "mode"),
            percent(w.time_error)
        ));
    });
    if s.in_use {
        ui.label(
            "The scene's tyre is the modes used from this diagram: pick or drop poles and \"Use these modes\" again to refine the choice.",
        );
    }
    if !w.left_out_hz.is_empty() {
        let hz: Vec<String> = w.left_out_hz.iter().map(|f| format!("{f:.0} Hz")).collect();
        ui.label(format!(
            "Left out of the automatic choice: {} (no pole within the frequency tolerance is stable in frequency, damping and shape over a run of 5 orders near the chosen one). Click the pole to pick it anyway.",
            hz.join(", ")
        ));
    }
    let fits = w.pair_fits();
    let worst = fits
        .iter()
        .max_by(|a, b| a.error.total_cmp(&b.error))
        .cloned();
    let errors: Vec<String> = fits
        .iter()
        .map(|f| format!("{}-{}: {}", f.pair.0, f.pair.1, percent(f.error)))
        .collect();
    ui.label(format!(
        "|G| error (relative L2 over the band) per pair i-j: {}",
        errors.join(", ")
    ));
    // the diagram and the worst pair share what is left of the view (the
    // scroll area's height, not its content's): the picks and the diagram
    // are seen without scrolling; the fit of the FRFs is below them
    let gap = ui.spacing().item_spacing.y;
    let left = ui.available_height() - gap;
    let h_diag = (left * 0.62).max(160.0);
    diagram(ui, w, h_diag, cmds);
    if let Some(f) = worst {
        pair_plot(ui, w, &f, (left - h_diag - gap).max(120.0));
    }
    if let Some(f) = frf {
        frf_section(ui, f, false);
    }
}

/// The stabilisation diagram over the summed `|G|`, the picked poles
/// ringed; a click picks or drops the nearest pole.
fn diagram(ui: &mut Ui, w: &Workbench, h: f32, cmds: &mut Vec<Command>) {
    let diag = &w.identification.diagram;
    let max_order = diag.iter().map(|d| d.order).max().unwrap_or(1) as f64;
    let summed = w.summed_magnitude();
    let db: Vec<f64> = summed
        .iter()
        .map(|g| 20.0 * g.max(1e-300).log10())
        .collect();
    let (lo, hi) = db
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let freqs = w.frequencies();
    // (the legend's rows are tall on a phone, where touch targets are:
    // the diagram keeps a readable height below them)
    let h = (h - diagram_legend(ui)).max(MIN_DIAGRAM_PX);
    let r = Plot::new("tirecontact.workbench.diagram")
        .id(egui::Id::unique(DIAGRAM_PLOT_ID))
        .height(h)
        .width(ui.available_width() - x_label_room_px(ui, w.band_hz.1))
        .x_title(ui, "frequency f (Hz)")
        .nice_x()
        .y_axis_label("model order")
        .include_x(w.band_hz.0)
        .include_x(w.band_hz.1)
        .include_y(0.0)
        .include_y(max_order + 1.0)
        .allow_scroll(false)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_double_click_reset(false)
        .show(ui, |pui| {
            if hi > lo {
                // the data's summed |G| (dB) scaled to the order axis
                let pts: Vec<[f64; 2]> = freqs
                    .iter()
                    .zip(&db)
                    .map(|(f, d)| [*f, 0.5 + max_order * (d - lo) / (hi - lo)])
                    .collect();
                pui.line(
                    Line::new("summed |G| of the data (dB, scaled)", pts)
                        .color(Color32::from_gray(120))
                        .width(1.0),
                );
            }
            diagram_poles(pui, diag);
            let picked: Vec<[f64; 2]> = w
                .picked
                .iter()
                .filter_map(|&(oi, k)| {
                    let d = diag.get(oi)?;
                    Some([d.poles.get(k)?.freq_hz, d.order as f64])
                })
                .collect();
            pui.points(
                Points::new(PICKED, picked)
                    .shape(MarkerShape::Circle)
                    .radius(7.0)
                    .filled(false)
                    .color(PICKED_COLOR),
            );
        });
    if r.response.clicked()
        && let Some(pos) = r.response.interact_pointer_pos()
    {
        let at = r.transform.value_from_position(pos);
        let hz_per_px = r.transform.dvalue_dpos()[0].abs();
        if let Some(p) = w.nearest(at.x, at.y, PICK_PX as f64 * hz_per_px) {
            cmds.push(Command::Research(ResearchCommand::WorkbenchToggle(p)));
        }
    }
}

/// Room (px) a plot whose frequency axis reaches about `top_hz` keeps on
/// its right: half its widest tick label. egui_plot centres a tick label
/// on its mark, and the axis (the band and egui_plot's 5 % margin) can end
/// on a labelled one, whose label then ran half past the plot into the
/// view's edge and was cut.
fn x_label_room_px(ui: &Ui, top_hz: f64) -> f32 {
    // (a label past the band's end, with a decimal when zoomed in)
    let widest = format!("{:.1}", 1.1 * top_hz.abs());
    let font = egui::TextStyle::Body.resolve(ui.style());
    let px = ui
        .painter()
        .layout_no_wrap(widest, font, Color32::PLACEHOLDER)
        .size()
        .x;
    0.5 * px
}

/// The poles of a stabilisation diagram at their frequency and model
/// order, a marker per category ([`category`]), most stable first.
fn diagram_poles(pui: &mut egui_plot::PlotUi<'_>, diagram: &[DiagramOrder]) {
    for what in Stability::ALL {
        let (name, shape, color) = category(what);
        let pts: Vec<[f64; 2]> = points_of(diagram, what).map(|(f, m)| [f, m]).collect();
        if !pts.is_empty() {
            pui.points(
                Points::new(name, pts)
                    .shape(shape)
                    .radius(3.0)
                    .color(color)
                    .filled(true),
            );
        }
    }
}

/// The diagram's legend, in a row above it (a legend inside would cover
/// poles: they fill the plot): a marker of each category's shape and
/// colour and its name. Returns the height it took (px).
fn diagram_legend(ui: &mut Ui) -> f32 {
    let top = ui.cursor().top();
    ui.horizontal_wrapped(|ui| {
        let size = ui.text_style_height(&egui::TextStyle::Body);
        // (a marker and its name on one row: where the name does not fit
        // the rest of the row, both go to the next; the marker was left at
        // a row's end without its name)
        let entry = |ui: &mut Ui, draw: &dyn Fn(&egui::Painter, egui::Pos2, f32), name: &str| {
            let font = egui::TextStyle::Body.resolve(ui.style());
            let name_px = ui
                .painter()
                .layout_no_wrap(name.to_string(), font, Color32::PLACEHOLDER)
                .size()
                .x;
            let need = size + ui.spacing().item_spacing.x + name_px;
            if ui.available_size_before_wrap().x < need
                && ui.cursor().left() > ui.min_rect().left() + 1.0
            {
                ui.end_row();
            }
            let (rect, _) = ui.allocate_exact_size(egui::vec2(size, size), egui::Sense::hover());
            draw(ui.painter(), rect.center(), size * 0.3);
            ui.label(name);
            ui.add_space(8.0);
        };
        entry(
            ui,
            &|p, c, r| {
                p.line_segment(
                    [c - egui::vec2(2.0 * r, 0.0), c + egui::vec2(2.0 * r, 0.0)],
                    egui::Stroke::new(1.0, Color32::from_gray(120)),
                );
            },
            "summed |G| of the data (dB, scaled)",
        );
        // the time-domain diagram drops over-damped poles: no such marker
        for (name, shape, color) in Stability::ALL
            .into_iter()
            .filter(|&s| s != Stability::Damped)
            .map(category)
        {
            entry(ui, &move |p, c, r| marker(p, c, r, shape, color), name);
        }
        entry(
            ui,
            &|p, c, r| {
                p.circle_stroke(c, 1.6 * r, egui::Stroke::new(1.5, PICKED_COLOR));
            },
            PICKED,
        );
    });
    ui.cursor().top() - top
}

/// A marker of `shape` as the diagram draws it, centred at `c`, radius `r`.
fn marker(p: &egui::Painter, c: egui::Pos2, r: f32, shape: MarkerShape, color: Color32) {
    use egui::{Shape, Stroke, pos2};
    match shape {
        MarkerShape::Diamond => {
            let pts = vec![
                pos2(c.x, c.y - r),
                pos2(c.x + r, c.y),
                pos2(c.x, c.y + r),
                pos2(c.x - r, c.y),
            ];
            p.add(Shape::convex_polygon(pts, color, Stroke::NONE));
        }
        MarkerShape::Square => {
            p.rect_filled(
                egui::Rect::from_center_size(c, egui::vec2(2.0 * r, 2.0 * r)),
                0.0,
                color,
            );
        }
        MarkerShape::Cross => {
            let s = Stroke::new(1.5, color);
            p.line_segment([pos2(c.x - r, c.y - r), pos2(c.x + r, c.y + r)], s);
            p.line_segment([pos2(c.x - r, c.y + r), pos2(c.x + r, c.y - r)], s);
        }
        _ => {
            p.circle_filled(c, r, color);
        }
    }
}

/// `|G|` (dB re 1 m/N) of one pair: the data and the picked modes.
fn pair_plot(ui: &mut Ui, w: &Workbench, f: &crate::identify::workbench::PairFit, h: f32) {
    let freqs = w.frequencies();
    let to_db = |v: &[f64]| -> Vec<[f64; 2]> {
        freqs
            .iter()
            .zip(v)
            .map(|(x, g)| [*x, 20.0 * g.max(1e-300).log10()])
            .collect()
    };
    let (i, j) = f.pair;
    let top_hz = freqs.iter().copied().fold(0.0, f64::max);
    Plot::new(PAIR_PLOT_ID)
        .id(egui::Id::unique(PAIR_PLOT_ID))
        .height(h)
        .width(ui.available_width() - x_label_room_px(ui, top_hz))
        .legend(egui_plot::Legend::default().position(egui_plot::Corner::RightTop))
        .x_title(ui, "frequency f (Hz)")
        .nice_x()
        .y_axis_label(format!("|G{i}{j}| (dB re 1 m/N)"))
        .allow_scroll(false)
        .show(ui, |pui| {
            pui.line(
                Line::new(format!("data, pair {i}-{j} (worst fitted)"), to_db(&f.data)).width(1.5),
            );
            pui.line(
                Line::new("picked modes", to_db(&f.model))
                    .color(PICKED_COLOR)
                    .width(1.5),
            );
        });
}

/// Pairs drawn in the FRF fit's plot (the first ones).
const FRF_PAIRS_DRAWN: usize = 4;

/// Colours of the pairs in the FRF fit's plot (Okabe-Ito).
const PAIR_COLORS: [Color32; FRF_PAIRS_DRAWN] = [
    Color32::from_rgb(0, 114, 178),
    Color32::from_rgb(213, 94, 0),
    Color32::from_rgb(0, 158, 115),
    Color32::from_rgb(204, 121, 167),
];

/// The frequency-domain fit of a measured file of FRFs: its errors, the
/// driving-point check, the residual terms and data against fit per pair.
fn frf_section(ui: &mut Ui, f: &Result<FrfIdentification, String>, open: bool) {
    egui::CollapsingHeader::new(FRF_SECTION)
        .default_open(open)
        .show(ui, |ui| {
            let id = match f {
                Ok(id) => id,
                Err(e) => {
                    ui.label(
                        RichText::new(format!("No fit: {e}")).color(ui.visuals().error_fg_color),
                    );
                    return;
                }
            };
            let set = &id.data.set;
            let short = percent;
            ui.label(format!(
                "{} at LSCF order {} over {} to {} Hz ({}); relative L2 error, all pairs: complex modes with residual terms {}, real modes {}",
                crate::output::count(id.poles.len(), "mode"),
                id.order,
                id.data.band_hz.0,
                id.data.band_hz.1,
                set.ordinate.name(),
                short(id.complex.error),
                short(id.real.error),
            ));
            ui.label(format!(
                "modes (Hz, ξ): {}",
                id.poles
                    .iter()
                    .map(|p| format!("{:.2} / {:.5}", p.freq_hz, p.damping_ratio))
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
            for (dof, d) in &id.driving {
                let text = driving::describe(d, &dof.to_string(), dof.node);
                let color = if *d == DrivingPoint::Positive {
                    ui.visuals().text_color()
                } else {
                    ui.visuals().error_fg_color
                };
                ui.label(RichText::new(text).color(color));
            }
            match &id.contact {
                Ok(c) => {
                    ui.label(format!(
                        "contact model (real modes scaled by the driving point, no residual terms): error {}",
                        short(c.error)
                    ));
                }
                Err(e) => {
                    ui.label(
                        RichText::new(format!("no contact model: {e}"))
                            .color(ui.visuals().error_fg_color),
                    );
                }
            }
            let pair_name = |k: usize| {
                let (a, b) = set.pairs[k];
                format!("{} / {}", id.data.dofs[a], id.data.dofs[b])
            };
            egui::CollapsingHeader::new(format!(
                "residual terms of the {} pairs",
                set.pairs.len()
            ))
            .default_open(set.pairs.len() <= FRF_PAIRS_DRAWN)
            .show(ui, |ui| {
                egui::Grid::new("tirecontact.workbench.residuals")
                .striped(true)
                .show(ui, |ui| {
                    ui.label("pair (response / reference)");
                    ui.label("lower residual (m/N·(rad/s)²)");
                    ui.label("upper residual (m/N)");
                    ui.end_row();
                    for k in 0..set.pairs.len() {
                        ui.label(pair_name(k));
                        ui.label(format!("{:.4e}", id.complex.lower[k]));
                        ui.label(format!("{:.4e}", id.complex.upper[k]));
                        ui.end_row();
                    }
                });
            });
            let units = set.ordinate.units();
            let to_db = |v: &[faer::c64]| -> Vec<[f64; 2]> {
                set.freq_hz
                    .iter()
                    .zip(v)
                    .map(|(x, h)| [*x, 20.0 * h.norm().max(1e-300).log10()])
                    .collect()
            };
            let drawn = set.pairs.len().min(FRF_PAIRS_DRAWN);
            ui.label(if set.pairs.len() > drawn {
                format!(
                    "data (solid) against the complex fit (dashed): the first {drawn} of {} pairs",
                    set.pairs.len()
                )
            } else {
                "data (solid) against the complex fit (dashed)".to_string()
            });
            Plot::new("tirecontact.workbench.frf_fit")
                .height(260.0)
                .legend(egui_plot::Legend::default().position(egui_plot::Corner::LeftBottom))
                .x_title(ui, "frequency f (Hz)")
        .nice_x()
                .y_axis_label(format!("|H| (dB re 1 {units})"))
                .allow_scroll(false)
                .show(ui, |pui| {
                    for k in 0..drawn {
                        let c = PAIR_COLORS[k];
                        pui.line(
                            Line::new(pair_name(k), to_db(&set.h[k]))
                                .color(c)
                                .width(1.0),
                        );
                        pui.line(
                            Line::new(pair_name(k), to_db(&id.complex.fit[k]))
                                .color(c)
                                .width(2.0)
                                .style(LineStyle::dashed_loose()),
                        );
                    }
                });
        });
}
