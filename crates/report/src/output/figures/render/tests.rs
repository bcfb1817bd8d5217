//! Unit tests of the headless figures (layout, legends, ticks).

use super::*;

#[test]
fn renders_a_png_of_the_requested_size() {
    let dir = std::env::temp_dir().join(format!("tc-fig-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("f.png");
    let fig = Figure {
        title: "test".into(),
        subtitle: "a = 1".into(),
        panels: vec![Panel {
            title: "sine".into(),
            x_label: "time (s)".into(),
            y_label: "u (mm)".into(),
            series: vec![Series::line(
                "u0",
                (0..100)
                    .map(|k| (k as f64, (k as f64 * 0.1).sin()))
                    .collect(),
            )],
            ..Panel::default()
        }],
    };
    render_png(&fig, &path, 640, 400).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // IHDR width and height
    let w = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
    let h = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
    assert_eq!((w, h), (640, 400));
    assert!(render_png(&fig, &path, 10, 400).is_err());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_legend_with_a_free_corner_stays_in_it() {
    // a curve along the bottom: the top right corner is free, so the
    // legend is drawn there (inside the plot), not beside it
    let dir = std::env::temp_dir().join(format!("tc-fig-corner-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let panel = |points: Vec<(f64, f64)>| Figure {
        title: "t".into(),
        subtitle: String::new(),
        panels: vec![Panel {
            x_label: "time (s)".into(),
            y_label: "u (mm)".into(),
            series: vec![Series::line("u0", points)],
            ..Panel::default()
        }],
    };
    let low: Vec<(f64, f64)> = (0..200)
        .map(|k| (k as f64, if k == 100 { 10.0 } else { 0.0 }))
        .collect();
    let l = render_png_layout(&panel(low), &dir.join("a.png"), 800, 500).unwrap();
    assert!(l[0].legend_px.is_none(), "{:?}", l[0].legend_px);
    // a curve over the whole height everywhere: beside the plot
    let dense: Vec<(f64, f64)> = (0..400)
        .map(|k| (k as f64, if k % 2 == 0 { 0.0 } else { 10.0 }))
        .collect();
    let l = render_png_layout(&panel(dense), &dir.join("b.png"), 800, 500).unwrap();
    let legend = l[0].legend_px.expect("beside the plot");
    assert!(legend[0] > l[0].plot_px[2], "{legend:?} {:?}", l[0].plot_px);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn stacked_panels_keep_one_plot_width_when_a_legend_goes_beside() {
    // one panel with data in every corner (its legend beside the plot),
    // one with a free corner: both plots end at the same x, and both
    // legends are in the column (the panels' time axes line up)
    let dir = std::env::temp_dir().join(format!("tc-fig-align-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let dense: Vec<(f64, f64)> = (0..400)
        .map(|k| (k as f64, if k % 2 == 0 { 0.0 } else { 10.0 }))
        .collect();
    let low: Vec<(f64, f64)> = (0..400)
        .map(|k| (k as f64, if k == 100 { 10.0 } else { 0.0 }))
        .collect();
    let panel = |name: &str, points: Vec<(f64, f64)>| Panel {
        x_label: "time (s)".into(),
        y_label: "u (mm)".into(),
        series: vec![Series::line(name, points)],
        ..Panel::default()
    };
    let fig = Figure {
        title: "t".into(),
        subtitle: String::new(),
        panels: vec![
            panel("free corner", low.clone()),
            panel("every corner taken, a longer name", dense),
            panel("u0", low),
        ],
    };
    let l = render_png_layout(&fig, &dir.join("a.png"), 900, 900).unwrap();
    for p in &l {
        assert_eq!(p.plot_px[0], l[0].plot_px[0], "{:?}", p.plot_px);
        assert_eq!(p.plot_px[2], l[0].plot_px[2], "{:?}", p.plot_px);
        let legend = p.legend_px.expect("in the column");
        assert!(legend[0] > p.plot_px[2], "{legend:?} {:?}", p.plot_px);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn tick_labels_are_plain_in_the_everyday_range() {
    for (v, log, want) in [
        (10.0, true, "10"),
        (100.0, true, "100"),
        (1000.0, true, "1000"),
        (1.0, true, "1"),
        (0.01, true, "1e-2"),
        (0.5, true, "5e-1"),
        (1e5, true, "1e5"),
        (1e-5, true, "1e-5"),
        (0.25, false, "0.25"),
        (90000.0, false, "90000"),
        (1.5e-7, false, "1.5e-7"),
        (0.0, false, "0"),
    ] {
        assert_eq!(tick_label(v, log), want, "{v} log {log}");
    }
}

/// The ticks of one linear axis share one style, whatever the scale: a
/// 0 to 2 ms time axis is all plain or all exponent, never both.
#[test]
fn an_axis_labels_every_tick_in_one_style() {
    use plotters::coord::ranged1d::{KeyPointHint, Ranged};
    for (lo, hi) in [
        (0.0, 0.0021),
        (0.0, 0.00085),
        (-3e-7, 4e-7),
        (0.0, 0.125),
        (-2.0e6, 3.0e6),
        (1e-3, 1.0e-3 + 4e-9),
        (950.0, 1040.0),
    ] {
        let ticks = plotters::coord::types::RangedCoordf64::from(lo..hi)
            .key_points(8usize.max_num_points());
        assert!(ticks.len() >= 3, "{lo}..{hi}: {ticks:?}");
        let labels: Vec<String> = ticks
            .iter()
            .map(|v| axis_tick_label(*v, false, (lo, hi)))
            .collect();
        let exp = labels.iter().filter(|l| l.contains('e')).count();
        let zero = labels.iter().filter(|l| *l == "0").count();
        assert!(
            exp == 0 || exp + zero == labels.len(),
            "{lo}..{hi}: {labels:?}"
        );
        // each label reads back as its tick, and no two are alike
        for (t, l) in ticks.iter().zip(&labels) {
            let back: f64 = l.parse().unwrap();
            let step = (ticks[1] - ticks[0]).abs();
            assert!((back - t).abs() <= 0.01 * step, "{lo}..{hi}: {t} -> {l}");
        }
        let mut unique = labels.clone();
        unique.dedup();
        assert_eq!(unique.len(), labels.len(), "{lo}..{hi}: {labels:?}");
    }
    // the short run's time axis: plain throughout
    assert_eq!(axis_tick_label(0.0002, false, (0.0, 0.0021)), "0.0002");
    assert_eq!(axis_tick_label(0.001, false, (0.0, 0.0021)), "0.001");
    assert_eq!(axis_tick_label(0.0004, false, (0.0, 0.00085)), "4e-4");
}

#[test]
fn long_captions_shrink_to_their_width() {
    let width = |t: &str, px: u32| {
        register_fonts();
        ("sans-serif", px as i32).into_font().box_size(t).unwrap().0 as i32
    };
    let short = "Displacement spectrum";
    assert_eq!(fit_font_px(short, 600, 22, 11), 22);
    let long = "Total contact force, third-octave bands 315 Hz - 2 kHz, every other band (Hann, mean removed)";
    let max_w = width(long, 22) * 3 / 4;
    let px = fit_font_px(long, max_w, 22, 11);
    assert!((11..22).contains(&px), "{px}");
    assert!(width(long, px) <= max_w, "{} > {max_w}", width(long, px));
    assert!(
        width(long, px + 1) > max_w,
        "not the largest size that fits"
    );
    // too long for any size: the smallest
    assert_eq!(fit_font_px(long, 10, 22, 11), 11);
}

#[test]
fn categorical_ticks_name_the_integers_only() {
    let names: Vec<String> = (0..5).map(|k| format!("p{k}")).collect();
    assert_eq!(name_tick_label(0.0, &names), "p0");
    assert_eq!(name_tick_label(3.0000000001, &names), "p3");
    assert_eq!(name_tick_label(4.0, &names), "p4");
    for v in [0.5, 2.3, -1.0, 5.0, 7.0] {
        assert_eq!(name_tick_label(v, &names), "", "at {v}");
    }
}

/// The pixels of exactly colour `c` in `rgb` (`w` px wide), as (x, y),
/// farther than `clear` px from every segment of `curve` (the series as
/// drawn in the plot): what is left is its legend key.
fn key_pixels(
    rgb: &[u8],
    w: u32,
    c: RGBColor,
    curve: &[(i32, i32)],
    clear: f64,
) -> Vec<(i32, i32)> {
    let near = |x: i32, y: i32| {
        let p = (f64::from(x), f64::from(y));
        let segs: Vec<((i32, i32), (i32, i32))> = if curve.len() == 1 {
            vec![(curve[0], curve[0])]
        } else {
            curve.windows(2).map(|s| (s[0], s[1])).collect()
        };
        segs.iter().any(|&(a, b)| {
            let (ax, ay, bx, by) = (
                f64::from(a.0),
                f64::from(a.1),
                f64::from(b.0),
                f64::from(b.1),
            );
            let (dx, dy) = (bx - ax, by - ay);
            let len2 = dx * dx + dy * dy;
            let t = if len2 == 0.0 {
                0.0
            } else {
                (((p.0 - ax) * dx + (p.1 - ay) * dy) / len2).clamp(0.0, 1.0)
            };
            (p.0 - ax - t * dx).hypot(p.1 - ay - t * dy) <= clear
        })
    };
    rgb.chunks_exact(3)
        .enumerate()
        .filter(|(_, px)| px[0] == c.0 && px[1] == c.1 && px[2] == c.2)
        .map(|(i, _)| ((i as u32 % w) as i32, (i as u32 / w) as i32))
        .filter(|&(x, y)| !near(x, y))
        .collect()
}

/// Width and height (px) of the box around `pts`.
fn extent(pts: &[(i32, i32)]) -> (i32, i32) {
    let (xs, ys): (Vec<i32>, Vec<i32>) = pts.iter().copied().unzip();
    let span = |v: &[i32]| v.iter().max().unwrap() - v.iter().min().unwrap() + 1;
    (span(&xs), span(&ys))
}

#[test]
fn a_one_point_series_is_keyed_by_its_dot_a_line_by_a_line_with_a_dot() {
    // the work-precision diagram: a method with a single run is one dot;
    // a line key beside it named a line nobody could find
    let r = 4;
    let series = |name: &str, points: Vec<(f64, f64)>, color: usize| Series {
        name: name.into(),
        points,
        style: Style::LineMarkers(r),
        color: Some(color),
    };
    for crowded in [false, true] {
        let mut s = vec![
            series(
                "five runs",
                (1..=5).map(|k| (k as f64, k as f64)).collect(),
                0,
            ),
            series("one run", vec![(3.0, 1.5)], 1),
        ];
        if crowded {
            // data in every corner: the legend goes in a column beside
            s.push(Series::line(
                "",
                (0..300)
                    .map(|k| {
                        (
                            1.0 + k as f64 * 4.0 / 299.0,
                            if k % 2 == 0 { 1.0 } else { 5.0 },
                        )
                    })
                    .collect(),
            ));
            s[2].style = Style::ThinLine;
            s[2].color = Some(2);
        }
        let fig = Figure {
            title: "t".into(),
            subtitle: String::new(),
            panels: vec![Panel {
                x_label: "run time (s)".into(),
                y_label: "error (-)".into(),
                series: s,
                ..Panel::default()
            }],
        };
        let (w, h) = (800, 500);
        let (rgb, l) = render_rgb_layout(&fig, w, h).unwrap();
        assert_eq!(l[0].legend_px.is_some(), crowded);
        let clear = f64::from(r) + 4.0;
        let dot = key_pixels(&rgb, w, PALETTE[1], &l[0].curves_px[1], clear);
        assert!(!dot.is_empty(), "crowded {crowded}: no key for the dot");
        let (dw, dh) = extent(&dot);
        assert!(
            dw <= 2 * r as i32 + 3 && dh >= 2 * r as i32 - 1,
            "crowded {crowded}: the one-point key is {dw}x{dh} px, not a dot of radius {r}"
        );
        let line = key_pixels(&rgb, w, PALETTE[0], &l[0].curves_px[0], clear);
        assert!(!line.is_empty(), "crowded {crowded}: no key for the line");
        let (lw, lh) = extent(&line);
        assert!(
            lw >= 19 && lh >= 2 * r as i32 - 1,
            "crowded {crowded}: the line's key is {lw}x{lh} px, not a line with a dot"
        );
    }
}

#[test]
fn the_figure_font_is_rewritten_and_its_glyphs_keep_their_side_bearings() {
    // plotters drew every glyph's ink from the pen (no left side bearing):
    // "H" touched its cell's left edge with twice its bearing on the right,
    // and a tabular "1" left a gap after it ("1 0"). Symmetric glyphs are
    // now centred in their advance, within 2 px at 60 px.
    assert!(font::with_origin_points(epaint_default_fonts::UBUNTU_LIGHT).is_some());
    register_fonts();
    let (w, h) = (400u32, 120u32);
    for text in ["H", "O", "0", "o", "8"] {
        let mut rgb = vec![255u8; (w * h * 3) as usize];
        let x0 = 100;
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            root.draw(&Text::new(
                text.to_string(),
                (x0, 20),
                ("sans-serif", 60).into_font().color(&BLACK),
            ))
            .unwrap();
            root.present().unwrap();
        }
        let inked: Vec<i32> = rgb
            .chunks_exact(3)
            .enumerate()
            .filter(|(_, p)| p[0] < 128)
            .map(|(i, _)| (i as u32 % w) as i32)
            .collect();
        let (left, right) = (*inked.iter().min().unwrap(), *inked.iter().max().unwrap());
        let advance = ("sans-serif", 60).into_font().box_size(text).unwrap().0 as i32;
        let (l_gap, r_gap) = (left - x0, x0 + advance - 1 - right);
        assert!(
            l_gap >= 2 && (l_gap - r_gap).abs() <= 2,
            "{text:?}: ink {left}..={right} in the cell {x0}..{}: bearings {l_gap} and {r_gap} px",
            x0 + advance
        );
    }
}

#[test]
fn a_thin_line_is_keyed_by_a_line_wide_enough_to_show_its_colour() {
    // spectra and run --plot draw one-pixel lines; their keys were one
    // pixel too (20 x 1 px: blue and sky blue could not be told apart)
    let mut s = Series::line(
        "thin",
        (0..50).map(|k| (k as f64, (k % 7) as f64)).collect(),
    );
    s.style = Style::ThinLine;
    s.color = Some(5);
    let fig = Figure {
        title: "t".into(),
        subtitle: String::new(),
        panels: vec![Panel {
            x_label: "frequency (Hz)".into(),
            y_label: "level (dB)".into(),
            series: vec![s],
            ..Panel::default()
        }],
    };
    let (w, h) = (800, 500);
    let (rgb, l) = render_rgb_layout(&fig, w, h).unwrap();
    let key = key_pixels(&rgb, w, PALETTE[5], &l[0].curves_px[0], 2.0);
    assert!(!key.is_empty(), "no key");
    let (kw, kh) = extent(&key);
    assert!(kw >= 19 && kh >= 3, "the key is {kw}x{kh} px");
}

/// Rows `y0..y1`, columns `x0..x1` of `rgb` (`w` px wide) holding dark ink
/// (every channel below 128): (columns with ink, rows with ink).
pub(crate) fn ink(
    rgb: &[u8],
    w: u32,
    (x0, x1): (i32, i32),
    (y0, y1): (i32, i32),
) -> (Vec<i32>, Vec<i32>) {
    let dark = |x: i32, y: i32| {
        let i = (y as usize * w as usize + x as usize) * 3;
        rgb[i..i + 3].iter().all(|&c| c < 128)
    };
    let cols = (x0..x1).filter(|&x| (y0..y1).any(|y| dark(x, y))).collect();
    let rows = (y0..y1).filter(|&y| (x0..x1).any(|x| dark(x, y))).collect();
    (cols, rows)
}

/// Runs of consecutive values of sorted `v` split at gaps wider than
/// `gap`: (first, last) of each.
pub(crate) fn runs(v: &[i32], gap: i32) -> Vec<(i32, i32)> {
    let mut out: Vec<(i32, i32)> = Vec::new();
    for &x in v {
        match out.last_mut() {
            Some(r) if x - r.1 <= gap + 1 => r.1 = x,
            _ => out.push((x, x)),
        }
    }
    out
}

#[test]
fn tick_labels_grow_with_the_figure_width_to_be_read_at_half_a_page() {
    // identify --figures' 1200 x 700 figures had 12 px tick labels (8 px
    // digits): placed at half width in an A4 report, unreadable. The text
    // now scales with the width (at most with the height over 450 px).
    for (w, h) in [
        (1200, 700),
        (1200, 900),
        (1400, 900),
        (1400, 1800),
        (1600, 1000),
    ] {
        let px = tick_label_px(w, h);
        assert!(
            f64::from(px) >= 22.0 * f64::from(w) / 1200.0 - 0.5,
            "{w}x{h}: tick labels {px} px"
        );
    }
    assert_eq!(tick_label_px(1200, 700), 22);
    assert!(
        tick_label_px(3000, 400) <= 13,
        "a wide strip keeps its plot"
    );
    // the digits at 1200 px width: at least 14 px of ink high
    register_fonts();
    let px = tick_label_px(1200, 700) as i32;
    let (w, h) = (400u32, 100u32);
    let mut rgb = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        let font = ("sans-serif", px).into_font().color(&BLACK);
        root.draw(&Text::new("0123456789", (10, 20), font)).unwrap();
        root.present().unwrap();
    }
    let (_, rows) = ink(&rgb, w, (0, w as i32), (0, h as i32));
    let tall = rows.last().unwrap() - rows[0] + 1;
    assert!(tall >= 14, "digits at {px} px: {tall} px of ink high");
}

/// Fig. 1's shape: one panel, five curves, 0-0.2 s against 0-4.4 mm.
fn paper_like_figure() -> Figure {
    let series = (0..5)
        .map(|i| {
            Series::line(
                format!("point {i} (x = {} m)", 0.025 * i as f64 - 0.05),
                (0..=400)
                    .map(|k| {
                        let t = k as f64 * 0.0005;
                        (
                            t,
                            (t * 100.0).min(4.0) + 0.3 * ((t * 600.0) + i as f64).sin(),
                        )
                    })
                    .collect(),
            )
        })
        .collect();
    Figure {
        title: "Fig. 1: displacement of the contact points".into(),
        subtitle: "Paper: ring tyre, five points, sine road (identified): V = 10 m/s".into(),
        panels: vec![Panel {
            x_label: "time (s)".into(),
            y_label: "displacement u (mm), up".into(),
            series,
            ..Panel::default()
        }],
    }
}

#[test]
fn the_larger_tick_labels_of_a_paper_figure_keep_apart() {
    let (w, h) = (1200, 700);
    let (rgb, l) = render_rgb_layout(&paper_like_figure(), w, h).unwrap();
    let [left, top, right, bottom] = l[0].plot_px;
    let px = tick_label_px(w, h) as i32;
    // the x tick labels: below the tick marks (5 px), one text height
    let (_, rows) = ink(
        &rgb,
        w,
        (left - px, right + px),
        (bottom + 7, bottom + 7 + 2 * px),
    );
    let rows = runs(&rows, 2);
    let tall = rows[0].1 - rows[0].0 + 1;
    assert!(tall >= 14, "x tick labels {tall} px high ({rows:?})");
    // labels ("0.02") are runs of ink columns, at least a third of a text
    // height apart (glyphs within a label are closer)
    let (cols, _) = ink(&rgb, w, (left - px, right + px), (rows[0].0, rows[0].1 + 1));
    let labels = runs(&cols, px / 3);
    assert!(
        labels.len() >= 8,
        "{} x tick labels: {labels:?}",
        labels.len()
    );
    // the y tick labels: left of the tick marks, rows of ink a third of a
    // text height apart at least
    let (_, rows) = ink(
        &rgb,
        w,
        (left - 3 * px, left - 7),
        (top - px, bottom + px / 2),
    );
    let labels = runs(&rows, px / 3);
    assert!(
        labels.len() >= 5,
        "{} y tick labels: {labels:?}",
        labels.len()
    );
    for r in &labels {
        assert!(r.1 - r.0 < px, "y tick labels run together: {labels:?}");
    }
    if std::env::var_os("TC_DUMP_FIG").is_some() {
        render_png(
            &paper_like_figure(),
            Path::new("/tmp/p12/paper_like.png"),
            w,
            h,
        )
        .unwrap();
    }
}

#[test]
fn a_short_panel_gets_three_numeric_labels_at_least() {
    // plotters asked for three nice values on 0-6000 gave two (0, 5000);
    // on -40000-940000 one (500000). Three at least now, 1.8 label heights
    // apart where that leaves three, else 1.2 (never overlapping).
    use plotters::coord::ranged1d::{KeyPointHint, Ranged};
    let label = 24.0;
    for (range, len, want_gap) in [
        ((-240.0, 6240.0), 160.0, 1.8),
        ((-40000.0, 940000.0), 160.0, 1.2),
        ((-40000.0, 940000.0), 260.0, 1.8),
        ((0.0, 1.0), 250.0, 1.8),
        ((-72.0, 72.0), 260.0, 1.8),
    ] {
        let n = linear_label_count(range, len, 1.8 * label);
        let axis = plotters::coord::types::RangedCoordf64::from(range.0..range.1);
        let v = axis.key_points(n.max_num_points());
        assert!(v.len() >= 3, "{range:?} over {len} px: {v:?}");
        for p in v.windows(2) {
            let gap = (p[1] - p[0]) / (range.1 - range.0) * len;
            assert!(
                gap >= want_gap * label - 1e-9,
                "{range:?} over {len} px: labels {gap} px apart ({v:?})"
            );
        }
    }
}

/// Eight series in a quarter of a 1280 × 720 figure, every corner of the
/// plots taken (the legend beside them): the whole legend in its own
/// panel, its entries apart (the last two were drawn over each other at
/// the panel's bottom).
#[test]
fn eight_entries_beside_a_short_plot_stay_in_its_panel() {
    let dense = |k0: usize| -> Vec<(f64, f64)> {
        (0..400)
            .map(|k| {
                (
                    k as f64,
                    if (k + k0).is_multiple_of(2) {
                        0.0
                    } else {
                        10.0
                    },
                )
            })
            .collect()
    };
    let panel = |named: bool| Panel {
        title: "a panel".into(),
        x_label: "time t (s)".into(),
        y_label: "u (mm)".into(),
        series: (0..8)
            .map(|i| {
                let name = if named {
                    format!("point {i}")
                } else {
                    String::new()
                };
                let mut s = Series::line(name, dense(i));
                s.color = Some(i);
                s
            })
            .collect(),
        ..Panel::default()
    };
    let fig = Figure {
        title: "t".into(),
        subtitle: "s".into(),
        panels: vec![panel(true), panel(false), panel(false), panel(false)],
    };
    for (w, h) in [(1280, 720), (800, 600)] {
        let (_, l) = render_rgb_layout(&fig, w, h).unwrap();
        let legend = l[0].legend_px.expect("beside the plot");
        assert!(
            legend[3] < l[1].plot_px[1],
            "{w}x{h}: the legend {legend:?} runs into the next panel {:?}",
            l[1].plot_px
        );
        // eight rows, each at least 7 px of text and 1.6 of that apart
        assert!(legend[3] - legend[1] >= 8 * 11 + 12, "{legend:?}");
    }
}
