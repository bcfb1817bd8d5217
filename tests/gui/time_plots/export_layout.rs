//! The exported time plots are fit for a report at the sizes people use:
//! every curve inside its panel's plotting area, the panels sharing the
//! height (no strips beside white gaps), one type scale, and the subtitle's
//! numbers as written by hand.

use crate::harness::{advance, harness};
use std::path::Path;
use tirecontact::Scene;
use tirecontact::gui::App;
use tirecontact::gui::jobs::export::time_figure;
use tirecontact::output::figures::{PALETTE, PanelLayout, render_rgb_layout};

/// Is `(x, y)` inside `r` (left, top, right, bottom) widened by `pad` px?
fn inside(r: [i32; 4], x: i32, y: i32, pad: i32) -> bool {
    x >= r[0] - pad && x <= r[2] + pad && y >= r[1] - pad && y <= r[3] + pad
}

fn check_layout(rgb: &[u8], layouts: &[PanelLayout], width: u32, height: u32, points: usize) {
    let size = format!("{width}x{height}");
    assert_eq!(layouts.len(), 4, "{size}");
    // every drawn point of every curve inside its own plotting area
    for (n, l) in layouts.iter().enumerate() {
        for (s, curve) in l.curves_px.iter().enumerate() {
            if let Some(&(x, y)) = curve.iter().find(|&&(x, y)| !inside(l.plot_px, x, y, 0)) {
                panic!(
                    "{size}: panel {n}, series {s}: ({x}, {y}) outside {:?}",
                    l.plot_px
                );
            }
        }
    }
    // the points' colours are inked only in the plots and the legend
    // (in a plot's corner or its column)
    let boxes: Vec<[i32; 4]> = layouts
        .iter()
        .flat_map(|l| std::iter::once(l.plot_px).chain(l.legend_px))
        .collect();
    let colours: Vec<[u8; 3]> = PALETTE[..points].iter().map(|c| [c.0, c.1, c.2]).collect();
    let mut stray = 0;
    for y in 0..height as i32 {
        for x in 0..width as i32 {
            let k = 3 * (y as usize * width as usize + x as usize);
            let px = [rgb[k], rgb[k + 1], rgb[k + 2]];
            if colours.contains(&px) && !boxes.iter().any(|&b| inside(b, x, y, 2)) {
                stray += 1;
            }
        }
    }
    assert_eq!(
        stray, 0,
        "{size}: pixels of the curves' colours outside the plots"
    );
    // the panels share the height: none squashed, little left white
    let heights: Vec<i32> = layouts
        .iter()
        .map(|l| l.plot_px[3] - l.plot_px[1])
        .collect();
    let (lo, hi) = (
        *heights.iter().min().unwrap(),
        *heights.iter().max().unwrap(),
    );
    assert!(
        lo as f64 >= 0.8 * hi as f64,
        "{size}: plot heights {heights:?} px"
    );
    let total: i32 = heights.iter().sum();
    assert!(
        total as f64 >= 0.5 * height as f64,
        "{size}: the plots fill {total} of {height} px: {heights:?}"
    );
    // one type scale
    assert!(
        layouts
            .iter()
            .all(|l| l.caption_px == layouts[0].caption_px)
    );
    assert!(
        layouts
            .iter()
            .all(|l| l.axis_title_px == layouts[0].axis_title_px)
    );
    assert!(
        layouts[0].caption_px >= 11,
        "{size}: {} px captions",
        layouts[0].caption_px
    );
}

#[test]
fn the_exported_time_plots_are_fit_for_a_report() {
    let mut scene = Scene::load(Path::new("presets/paper.ron")).unwrap();
    // a step as a computation leaves it, not as typed
    scene.dt_s *= 1.0 + f64::EPSILON;
    let mut h = harness(App::new(scene, None).unwrap());
    h.run();
    advance(&mut h, 12_000);
    let app = h.state();
    let hist = app.history();
    let shown = vec![true; hist.num_points()];
    let fig = time_figure(app.scene(), app.modes(), hist, &shown, true);
    assert!(
        !fig.subtitle.contains("00000"),
        "numbers as written by hand: {}",
        fig.subtitle
    );
    for (width, height) in [(1600, 1000), (1280, 720), (1920, 1080), (800, 600)] {
        let (rgb, layouts) = render_rgb_layout(&fig, width, height).unwrap();
        if let Some(dir) = std::env::var_os("TIRECONTACT_FIGURE_DIR") {
            let path = Path::new(&dir).join(format!("time_plots_{width}x{height}.png"));
            image::RgbImage::from_raw(width, height, rgb.clone())
                .unwrap()
                .save(path)
                .unwrap();
        }
        check_layout(&rgb, &layouts, width, height, hist.num_points());
    }
}
