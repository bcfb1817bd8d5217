//! Green functions of the current modal model: the impulse response g_ij(t)
//! and the receptance |G_ij(f)| (log-log), with the modal frequencies marked,
//! so that tuning a mode shows its effect at once.

use super::XTitle;
use super::point_color;
use crate::Scene;
use crate::base::modal::ModalModel;
use crate::base::modal::Mode;
use egui::{Color32, Ui};
use egui_plot::{Corner, Legend, Line, LineStyle, Plot, VLine};

/// Presentation options of the Green-function view.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct GreenOptions {
    /// Receiving point i.
    pub receiver: usize,
    /// Draw g_ij for every loaded point j (else only j = i).
    pub all_sources: bool,
}

/// Time window (s) showing the decay of the slowest mode.
pub fn time_window(model: &ModalModel) -> f64 {
    let mut t: f64 = 0.0;
    for m in &model.modes {
        let f = m.omega_rad_s / std::f64::consts::TAU;
        let decay = if m.decay_rate() > 0.0 {
            4.0 / m.decay_rate()
        } else {
            f64::INFINITY
        };
        t = t.max(decay.min(15.0 / f.max(1e-9)));
    }
    if t.is_finite() && t > 0.0 { t } else { 1.0 }
}

/// Frequency range (Hz) around the modes: a decade below the lowest, half a
/// decade above the highest.
pub fn freq_range(model: &ModalModel) -> (f64, f64) {
    let fs = model
        .modes
        .iter()
        .map(|m| m.omega_rad_s / std::f64::consts::TAU);
    let lo = fs.clone().fold(f64::INFINITY, f64::min);
    let hi = fs.fold(0.0, f64::max);
    if lo.is_finite() && hi > 0.0 {
        (lo / 10.0, hi * 5.0)
    } else {
        (1.0, 1000.0)
    }
}

fn pow10_label(v: f64) -> String {
    let x = 10f64.powf(v);
    if (v - v.round()).abs() > 1e-6 {
        return String::new();
    }
    crate::gui::widgets::number::format_number(x)
}

pub fn show(ui: &mut Ui, scene: &Scene, modes: &[Mode], opts: &mut GreenOptions) {
    let p = scene.num_points();
    let model = ModalModel::from_modes(modes, p);
    opts.receiver = opts.receiver.min(p.saturating_sub(1));
    ui.horizontal_wrapped(|ui| {
        ui.label("receiving point i");
        egui::ComboBox::from_id_salt("tirecontact.green_i")
            .selected_text(opts.receiver.to_string())
            .show_ui(ui, |ui| {
                for i in 0..p {
                    ui.selectable_value(&mut opts.receiver, i, i.to_string());
                }
            })
            .response
            .accessible_name("receiving point");
        ui.checkbox(&mut opts.all_sources, "all loaded points j (else j = i)");
        ui.separator();
        let freqs: Vec<String> = modes
            .iter()
            .take(6)
            .map(|m| format!("{:.1} Hz ξ={}", m.freq_hz, three_digits(m.damping_ratio)))
            .collect();
        let more = modes.len().saturating_sub(6);
        let more = if more > 0 {
            format!(" … and {more} more")
        } else {
            String::new()
        };
        let n = modes.len();
        let noun = if n == 1 { "mode" } else { "modes" };
        ui.label(format!("{n} {noun}: {}{more}", freqs.join(", ")));
    });
    let i = opts.receiver;
    let sources: Vec<usize> = if opts.all_sources {
        (0..p).collect()
    } else {
        vec![i]
    };
    let half = ((ui.available_height() - ui.spacing().item_spacing.y) / 2.0).max(100.0);
    let tw = time_window(&model);
    let n = 1500;
    super::nice_y_axis(Plot::new("tirecontact.green_t"))
        .height(half)
        .legend(Legend::default().position(Corner::RightTop))
        .x_title(ui, "time t (s)")
        .nice_x()
        .y_axis_label("g_ij(t) (mm/(N·s))")
        .allow_scroll(false)
        .show(ui, |pui| {
            for &j in &sources {
                let pts: Vec<[f64; 2]> = (0..=n)
                    .map(|k| {
                        let t = tw * k as f64 / n as f64;
                        [t, model.green(i, j, t).0 * 1e3]
                    })
                    .collect();
                pui.line(
                    Line::new(
                        format!("g_{i}{j}: response at {i} to an impulse at {j}"),
                        pts,
                    )
                    .color(point_color(j))
                    .width(1.5)
                    .allow_band(false),
                );
            }
        });
    let (f0, f1) = freq_range(&model);
    let (l0, l1) = (f0.log10(), f1.log10());
    Plot::new("tirecontact.green_f")
        .height(half)
        .legend(Legend::default().position(Corner::RightTop))
        .x_title(ui, "frequency f (Hz, log scale)")
        .y_axis_label("|G_ij(f)| (dB re 1 m/N)")
        .x_grid_spacer(super::log_marks)
        .x_axis_formatter(|m, _| pow10_label(m.value))
        .allow_scroll(false)
        .show(ui, |pui| {
            for &j in &sources {
                let pts: Vec<[f64; 2]> = (0..=n)
                    .filter_map(|k| {
                        let lf = l0 + (l1 - l0) * k as f64 / n as f64;
                        let g = model.frequency_response(i, j, 10f64.powf(lf)).norm();
                        (g > 0.0 && g.is_finite()).then(|| [lf, 20.0 * g.log10()])
                    })
                    .collect();
                pui.line(
                    Line::new(format!("|G_{i}{j}|"), pts)
                        .color(point_color(j))
                        .width(1.5)
                        .allow_band(false),
                );
            }
            for m in modes {
                if m.freq_hz > 0.0 {
                    pui.vline(
                        VLine::new("mode frequencies", m.freq_hz.log10())
                            .color(Color32::from_gray(150))
                            .style(LineStyle::dashed_loose()),
                    );
                }
            }
        });
}

/// `x` to three significant digits: with three decimals a light damping
/// ratio (0.0004) read "ξ=0.000", as if undamped.
fn three_digits(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return format!("{x}");
    }
    let decimals = (2.0 - x.abs().log10().floor()).max(0.0) as usize;
    format!("{x:.decimals$}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_cover_the_modes() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/single_mode.ron"
            )),
            "single_mode",
        )
        .unwrap();
        let model = ModalModel::from_modes(&crate::ModeCache::new().modes(&scene).unwrap(), 1);
        let (a, b) = freq_range(&model);
        assert!(a < 100.0 && b > 100.0);
        // 100 Hz, 5 %: decay 1/(0.05*628) = 32 ms; 4 decays = 0.127 s; 15 periods = 0.15 s
        let t = time_window(&model);
        assert!(
            (t - 4.0 / (0.05 * 200.0 * std::f64::consts::PI)).abs() < 1e-9,
            "{t}"
        );
        assert_eq!(pow10_label(2.0), "100");
        assert_eq!(pow10_label(2.3), "");
    }
}
