//! The fidelity panel: the ring tyre's source Green functions beside the
//! modal sum in use (|G_ij(f)| over the band, per point pair), and the live
//! relative L2 error (crate::analysis::fidelity) with its band, plus what removing
//! each mode would cost. The reference is kept by the app after "Edit as a
//! modal model", so detuning or removing modes updates the figure.

use super::XTitle;
use super::log_marks;
use super::point_color;
use super::spectra_view::log_label;
use crate::Scene;
use crate::base::modal::ModalModel;
use crate::gui::research::fidelity::{FidelityFigures, FidelityRef};
use crate::gui::research::state::FidelityOptions;
use crate::scene::{Mode, Tyre};
use egui::{Color32, RichText, Ui};
use egui_plot::{Bar, BarChart, Corner, HLine, Legend, Line, LineStyle, Plot};

/// Points of the |G| curves.
const CURVE_POINTS: usize = 800;

/// The error figure as shown, the view's header (also what the tests read).
pub fn error_text(f: &FidelityFigures) -> String {
    format!(
        "relative L2 error of the modal sum against the ring: {:.3} % ({:.4e})",
        100.0 * f.fidelity.relative_l2,
        f.fidelity.relative_l2,
    )
}

/// Where the error is measured, on the line under the header (on the
/// header's line it ran to the window's edge at 1280 px).
pub fn band_text(f: &FidelityFigures, p: usize) -> String {
    format!(
        "over {:.0}–{:.0} Hz ({} frequencies, all {p}×{p} pairs)",
        f.band_hz.0, f.band_hz.1, f.num_freqs
    )
}

/// Why a scene has no source Green functions to compare its modes with,
/// by the kind of its tyre, and how to get a reference.
fn no_reference_text(tyre: &crate::scene::Tyre) -> String {
    use crate::scene::Tyre;
    let what = match tyre {
        Tyre::Modal { .. } => {
            "Its tyre is a modal model given directly (not derived from a ring tyre in this session)"
        }
        Tyre::Plate { .. } => {
            "Its tyre is an orthotropic plate whose modes are in closed form: the modal model is the plate itself, not fitted to it"
        }
        Tyre::FeModes { .. } => {
            "Its tyre's modes are read from a finite-element model's file as they are, not fitted to responses"
        }
        Tyre::Measured { .. } => {
            "Its tyre is identified from measured responses, which this view does not compare the modes with (the Identification view, key 8, shows the fit against them)"
        }
        Tyre::Ring { .. } => "Its ring tyre is not the reference of this session",
    };
    format!(
        "{what}, so there is nothing to measure its fidelity against. Open a ring-tyre preset (e.g. presets/paper.ron) and press “Edit as a modal model” in the tyre panel: the ring is then kept here as the reference while you detune or remove modes."
    )
}

pub fn show(
    ui: &mut Ui,
    scene: &Scene,
    modes: &[Mode],
    reference: Option<&FidelityRef>,
    figures: Option<&Result<FidelityFigures, String>>,
    computing: Option<f64>,
    opts: &mut FidelityOptions,
) {
    let Some(reference) = reference else {
        ui.label(RichText::new("No source Green functions for this scene.").strong());
        ui.label(no_reference_text(&scene.tyre));
        return;
    };
    let p = scene.num_points();
    opts.i = opts.i.min(p.saturating_sub(1));
    opts.j = opts.j.min(p.saturating_sub(1));
    controls(ui, scene, reference, opts);
    let Ok(figures) = status(ui, modes, figures, computing, opts, p) else {
        return;
    };
    let gap = ui.spacing().item_spacing.y;
    let h = ui.available_height() - gap;
    green_plot(ui, scene, modes, reference, opts, (0.62 * h).max(150.0));
    // what removing each mode would cost
    if let Some(figures) = figures {
        removal_costs(ui, modes, figures, (0.38 * h - gap).max(100.0));
    }
}

/// The pair of points, the frequency axis, and what the reference is.
fn controls(ui: &mut Ui, scene: &Scene, reference: &FidelityRef, opts: &mut FidelityOptions) {
    let p = scene.num_points();
    let converted = matches!(scene.tyre, Tyre::Modal { .. });
    ui.horizontal_wrapped(|ui| {
        ui.label("receiving point i");
        pick(ui, "tirecontact.fid_i", "fidelity point i", &mut opts.i, p);
        ui.label("loaded point j");
        pick(ui, "tirecontact.fid_j", "fidelity point j", &mut opts.j, p);
        ui.checkbox(&mut opts.log_x, "log frequency axis");
        ui.separator();
        ui.label(
            RichText::new(format!(
                "reference: ring of “{}” (all orders to N = {}){}",
                reference.source,
                reference.ring.max_order,
                if converted {
                    ", kept after conversion to a modal model"
                } else {
                    ""
                }
            ))
            .weak(),
        );
    });
}

/// The error figures, or the progress of their computation; `Err` when
/// they failed (said in the view: nothing else to draw).
fn status<'a>(
    ui: &mut Ui,
    modes: &[Mode],
    figures: Option<&'a Result<FidelityFigures, String>>,
    computing: Option<f64>,
    opts: &FidelityOptions,
    p: usize,
) -> Result<Option<&'a FidelityFigures>, ()> {
    // the figures of the modes in use, or a background job computing them
    // (the |G| curves below are cheap and drawn meanwhile)
    let figures = match figures {
        Some(Ok(f)) => Some(f),
        Some(Err(e)) => {
            ui.label(
                RichText::new(format!("No fidelity figure: {e}"))
                    .color(crate::gui::widgets::fields::ERROR_COLOR),
            );
            return Err(());
        }
        None => {
            ui.horizontal(|ui| {
                ui.spinner();
                ui.label(
                    RichText::new(format!(
                        "computing the relative L2 error of the {} modes and of each mode removed… {:.0} %",
                        modes.len(),
                        100.0 * computing.unwrap_or(0.0)
                    ))
                    .strong(),
                );
            });
            None
        }
    };
    if let Some(figures) = figures {
        let pair = figures
            .fidelity
            .per_pair
            .get(opts.i * p + opts.j)
            .copied()
            .unwrap_or(f64::NAN);
        ui.label(RichText::new(error_text(figures)).strong().size(16.0));
        ui.label(format!(
            "{}; pair ({}, {}): {:.3} % — {} modes in the modal sum",
            band_text(figures, p),
            opts.i,
            opts.j,
            100.0 * pair,
            modes.len()
        ));
    }
    Ok(figures)
}

/// `|G_ij(f)|` of the reference and of the modal sum, dB.
fn green_plot(
    ui: &mut Ui,
    scene: &Scene,
    modes: &[Mode],
    reference: &FidelityRef,
    opts: &FidelityOptions,
    height: f32,
) {
    let p = scene.num_points();
    let x: Vec<f64> = scene.points.iter().map(|q| q.x_m).collect();
    let src = reference.model(&x);
    let model = ModalModel::from_modes(modes, p);
    let (lo, hi) = reference.band_hz;
    let log = opts.log_x;
    let f0 = if log { lo.max(hi / 1000.0) } else { lo };
    let freqs: Vec<f64> = (0..=CURVE_POINTS)
        .map(|k| {
            let s = k as f64 / CURVE_POINTS as f64;
            if log {
                f0 * (hi / f0).powf(s)
            } else {
                f0 + (hi - f0) * s
            }
        })
        .collect();
    let curve = |g: &ModalModel| -> Vec<[f64; 2]> {
        freqs
            .iter()
            .filter_map(|&f| {
                let v = g.frequency_response(opts.i, opts.j, f).norm();
                (v > 0.0 && v.is_finite())
                    .then(|| [if log { f.log10() } else { f }, 20.0 * v.log10()])
            })
            .collect()
    };
    let mut plot = Plot::new("tirecontact.fidelity_g")
        .height(height)
        .legend(Legend::default().position(Corner::RightTop))
        .x_title(
            ui,
            if log {
                "frequency f (Hz, log scale)"
            } else {
                "frequency f (Hz)"
            },
        )
        .y_axis_label(format!("|G_{}{}(f)| (dB re 1 m/N)", opts.i, opts.j))
        .y_axis_min_width(64.0)
        .allow_scroll(false);
    if log {
        plot = plot
            .x_grid_spacer(log_marks)
            .x_axis_formatter(|m, _| log_label(m.value));
    }
    plot.show(ui, |pui| {
        pui.line(
            Line::new(format!("ring source |G_{}{}|", opts.i, opts.j), curve(&src))
                .color(Color32::from_gray(60))
                .width(2.5),
        );
        pui.line(
            Line::new(
                format!("modal sum |Ĝ_{}{}| ({} modes)", opts.i, opts.j, modes.len()),
                curve(&model),
            )
            .color(point_color(1))
            .width(1.5)
            .style(LineStyle::dashed_dense()),
        );
    });
}

/// The error with each mode removed, against the error now.
fn removal_costs(ui: &mut Ui, modes: &[Mode], figures: &FidelityFigures, height: f32) {
    let bars: Vec<Bar> = modes
        .iter()
        .zip(&figures.removal_costs)
        .enumerate()
        .map(|(k, (m, &c))| {
            Bar::new(k as f64, 100.0 * c)
                .width(0.7)
                .name(format!("mode {k} ({:.1} Hz)", m.freq_hz))
                .fill(point_color(2))
        })
        .collect();
    super::nice_y_axis(Plot::new("tirecontact.fidelity_costs"))
        .height(height)
        .legend(Legend::default().position(Corner::RightTop))
        .x_title(ui, "mode k (removed)")
        .y_axis_label("error without mode k (%)")
        .y_axis_min_width(64.0)
        .allow_scroll(false)
        .show(ui, |pui| {
            pui.bar_chart(
                BarChart::new("error with mode k removed (%)", bars).color(point_color(2)),
            );
            pui.hline(
                HLine::new(
                    format!("error now, all {} modes (%)", modes.len()),
                    100.0 * figures.fidelity.relative_l2,
                )
                .color(Color32::from_gray(60))
                .style(LineStyle::dashed_dense()),
            );
        });
}

fn pick(ui: &mut Ui, id: &str, name: &str, v: &mut usize, p: usize) {
    egui::ComboBox::from_id_salt(id)
        .selected_text(v.to_string())
        .show_ui(ui, |ui| {
            for k in 0..p {
                ui.selectable_value(v, k, k.to_string());
            }
        })
        .response
        .accessible_name(name);
}

#[cfg(test)]
mod tests {
    use super::no_reference_text;
    use crate::scene::{Scene, Tyre};

    /// Each shipped preset without a reference is told what its tyre is.
    #[test]
    fn the_missing_reference_names_the_tyre() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("presets");
        for (file, says) in [
            ("single_mode.ron", "modal model given directly"),
            ("patch_texture.ron", "orthotropic plate"),
            ("fe_plate.ron", "finite-element"),
            ("measured_example.ron", "measured responses"),
        ] {
            let scene = Scene::load(&dir.join(file)).unwrap();
            assert!(!matches!(scene.tyre, Tyre::Ring { .. }), "{file}");
            let text = no_reference_text(&scene.tyre);
            assert!(text.contains(says), "{file}: {text}");
        }
    }
}
