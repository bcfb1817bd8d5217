//! The spectra view in small windows (900 × 600; 1280 × 720 with the mode
//! bars beside it): each of its three plots keeps a readable height, each
//! y title lies beside its own plot's frame (none runs into another), and
//! the view scrolls with the mouse wheel until the third-octave plot and
//! its axis end above the status bar.

use crate::harness::{advance, harness_sized, plot_frame, rotated_texts, status_top, texts, wheel};
use egui_kittest::Harness;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::views::spectra_view::{MIN_PLOT_PX, PLOT_IDS, Y_TITLES};
use tirecontact::gui::{App, Command, View};

/// The spectra of a run of three_points in a `size` window, the mode bars
/// shown when `bars`.
fn spectra(size: [f32; 2], bars: bool) -> Harness<'static, App> {
    let scene = Scene::load(Path::new("presets/three_points.ron")).unwrap();
    let mut h = harness_sized(App::new(scene, None).unwrap(), size);
    h.run();
    if bars {
        h.state_mut().apply(Command::ShowModeBars(true));
    }
    advance(&mut h, 8_000);
    h.state_mut().apply(Command::ShowView(View::Spectra));
    for _ in 0..2_000 {
        if h.state().research().spectra().is_some() {
            break;
        }
        std::thread::sleep(std::time::Duration::from_millis(5));
        h.run_steps(1);
    }
    assert!(
        matches!(h.state().research().spectra(), Some(Ok(_))),
        "no spectra"
    );
    h.run_steps(4);
    h
}

/// Checks the y title of every plot whose frame shows above the status
/// bar; returns which plots' titles were checked.
fn titles_beside_their_plots(h: &Harness<'_, App>, size: [f32; 2], bottom: f32) -> Vec<usize> {
    let texts = rotated_texts(h);
    let mut checked = Vec::new();
    for (k, id) in PLOT_IDS.iter().enumerate() {
        let f = plot_frame(h, id);
        if f.bottom() < 0.0 || f.top() > bottom {
            continue;
        }
        let (full, short) = Y_TITLES[k];
        let (text, r) = texts
            .iter()
            .find(|(t, r)| (t == full || t == short) && r.right() <= f.left() + 0.5)
            .unwrap_or_else(|| panic!("{size:?}: no y title of {id} in {texts:?}"));
        assert!(
            r.top() >= f.top() - 0.5 && r.bottom() <= f.bottom() + 0.5,
            "{size:?}: the title {text:?} of {id} spans {:.1}..{:.1} px, its frame {:.1}..{:.1} px",
            r.top(),
            r.bottom(),
            f.top(),
            f.bottom()
        );
        checked.push(k);
    }
    checked
}

#[test]
fn the_spectra_plots_keep_their_height_and_titles_and_the_view_scrolls() {
    for (size, bars) in [([900.0, 600.0], false), ([1280.0, 720.0], true)] {
        let mut h = spectra(size, bars);
        let bottom = status_top(&h);
        for id in PLOT_IDS {
            let f = plot_frame(&h, id);
            eprintln!("{size:?} bars {bars}: {id} frame {f:?}");
            assert!(
                f.height() >= 0.75 * MIN_PLOT_PX,
                "{size:?}: the frame of {id} is {:.0} px high",
                f.height()
            );
        }
        let mut seen = titles_beside_their_plots(&h, size, bottom);
        // the wheel over the first plot scrolls the view to its end
        let first = plot_frame(&h, PLOT_IDS[0]);
        wheel(&mut h, first.center(), -400.0, 6);
        let bands = plot_frame(&h, PLOT_IDS[2]);
        let axis = texts(&h)
            .into_iter()
            .filter(|(t, _)| t.starts_with("third-octave band (Hz"))
            .map(|(_, r)| r.bottom())
            .fold(f32::NEG_INFINITY, f32::max);
        assert!(
            bands.top() >= 0.0 && axis <= bottom,
            "{size:?}: scrolled to its end, the band plot {bands:?} with its axis title down to {axis} px, the status bar at {bottom} px"
        );
        seen.extend(titles_beside_their_plots(&h, size, bottom));
        for k in 0..PLOT_IDS.len() {
            assert!(
                seen.contains(&k),
                "{size:?}: no title of {} seen",
                PLOT_IDS[k]
            );
        }
    }
}
