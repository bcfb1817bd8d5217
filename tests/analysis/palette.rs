//! The point colours of the figures and the visualiser: the first eight
//! (a scene of up to eight points) are told apart. Any two differ by at
//! least 20 in CIEDE2000, and two of one hue (within 30°, both with chroma
//! above 15) by at least 20 in lightness L*: Okabe-Ito's vermillion and
//! orange (hues 56° and 78°, lightness 54 and 71) drew points 1 and 4 of
//! the paper's five-point scene as one orange.

use crate::support::colour::{ciede2000, contrast, lch};

fn check(name: &str, colours: &[[u8; 3]], backgrounds: &[[u8; 3]], min_contrast: f64) {
    // points 0 and 4, blue and sky blue, read as one colour in the README's
    // small images at 22 (Okabe-Ito's blue, 0 114 178); now 31
    let d04 = ciede2000(colours[0], colours[4]);
    assert!(
        d04 >= 30.0,
        "{name}: colours 0 {:?} and 4 {:?}: CIEDE2000 {d04:.1} < 30",
        colours[0],
        colours[4]
    );
    for (i, &a) in colours.iter().enumerate() {
        for bg in backgrounds {
            let c = contrast(a, *bg);
            assert!(
                c >= min_contrast,
                "{name}: colour {i} {a:?} on {bg:?}: contrast {c:.2} < {min_contrast}"
            );
        }
        for (j, &b) in colours.iter().enumerate().skip(i + 1) {
            let d = ciede2000(a, b);
            assert!(
                d >= 20.0,
                "{name}: colours {i} {a:?} and {j} {b:?}: CIEDE2000 {d:.1} < 20"
            );
            let ((la, ca, ha), (lb, cb, hb)) = (lch(a), lch(b));
            let dh = (ha - hb).abs().min(360.0 - (ha - hb).abs());
            if ca > 15.0 && cb > 15.0 && dh < 30.0 {
                assert!(
                    (la - lb).abs() >= 20.0,
                    "{name}: colours {i} {a:?} and {j} {b:?} are one hue ({ha:.0}° and {hb:.0}°) \
                     of lightness {la:.0} and {lb:.0}"
                );
            }
        }
    }
}

#[test]
fn the_colour_distance_is_ciede2000() {
    // Sharma, Wu & Dalal (2005), Table 1: pairs 1, 7, 17, 25
    use crate::support::colour::{ciede2000_lab, lab};
    for (a, b, want) in [
        ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
        ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
        ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
        (
            [60.2574, -34.0099, 36.2677],
            [60.4626, -34.1751, 39.4387],
            1.2644,
        ),
    ] {
        let d = ciede2000_lab(a, b);
        assert!((d - want).abs() < 1e-4, "{a:?} {b:?}: {d} != {want}");
        assert!((ciede2000_lab(b, a) - want).abs() < 1e-4, "not symmetric");
    }
    let l = lab([255, 255, 255]);
    assert!(
        (l[0] - 100.0).abs() < 0.01 && l[1].abs() < 0.05 && l[2].abs() < 0.05,
        "{l:?}"
    );
    // the pair this test is about fails the one-hue rule
    let ((l1, _, h1), (l2, _, h2)) = (lch([213, 94, 0]), lch([230, 159, 0]));
    assert!((h1 - h2).abs() < 30.0 && (l1 - l2).abs() < 20.0);
}

#[test]
fn the_figures_first_eight_colours_are_told_apart_on_white() {
    let colours: Vec<[u8; 3]> = tirecontact::output::figures::PALETTE[..8]
        .iter()
        .map(|c| [c.0, c.1, c.2])
        .collect();
    check("figures", &colours, &[[255, 255, 255]], 2.0);
}

#[cfg(feature = "gui")]
#[test]
fn the_visualisers_first_eight_colours_are_told_apart_in_both_themes() {
    use tirecontact::gui::views::point_color;
    let colours: Vec<[u8; 3]> = (0..8)
        .map(|i| {
            let c = point_color(i);
            [c.r(), c.g(), c.b()]
        })
        .collect();
    let bg = |v: egui::Visuals| {
        let c = v.extreme_bg_color;
        [c.r(), c.g(), c.b()]
    };
    check(
        "visualiser",
        &colours,
        &[bg(egui::Visuals::dark()), bg(egui::Visuals::light())],
        1.9,
    );
}
