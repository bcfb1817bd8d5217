use super::round_125;

#[test]
fn height_labels_are_a_label_and_a_half_apart_in_true_mm() {
    use super::height_marks;
    // a 185 px high plot over ±20 mm of exaggerated height at ×10 (true
    // ±2 mm); labels 36 px apart at least
    let (frame_px, label_px, e) = (185.0, 36.0, 10.0);
    let bounds = (-0.02, 0.02);
    let per_px = (bounds.1 - bounds.0) / frame_px;
    let g = egui_plot::GridInput {
        bounds,
        base_step_size: 8.0 * per_px,
    };
    let marks = height_marks(g, 1e3 / e, label_px);
    // one step, at least a label and a half apart, and not needlessly
    // coarse: the next finer 1-2-5 step would be closer
    let major = marks[0].step_size;
    assert!(marks.iter().all(|m| m.step_size == major));
    assert!(major / per_px >= label_px, "{} px", major / per_px);
    assert!(major / per_px < 2.5 * label_px, "{} px", major / per_px);
    // in true mm a 1-2-5 step
    let mm = major * 1e3 / e;
    let mant = mm / 10f64.powf(mm.log10().floor());
    assert!(
        [1.0, 2.0, 5.0].iter().any(|m| (mant - m).abs() < 1e-9),
        "{mm} mm"
    );
    let labelled: Vec<f64> = marks
        .iter()
        .filter(|m| m.step_size >= major)
        .map(|m| m.value)
        .collect();
    assert!(labelled.len() >= 2, "{labelled:?}");
    assert!(labelled.iter().all(|v| *v >= bounds.0 && *v <= bounds.1));
    // a tall plot: about eight steps over its height, as before (steps
    // only a label and a half apart would put 20 labels on 800 px)
    let g = egui_plot::GridInput {
        bounds,
        base_step_size: 8.0 * (bounds.1 - bounds.0) / 800.0,
    };
    let marks = height_marks(g, 1e3 / e, 21.0);
    assert!((4..=9).contains(&marks.len()), "{} marks", marks.len());
}

#[test]
fn exaggeration_rounds_to_1_2_5() {
    assert_eq!(round_125(1.0), 1.0);
    assert_eq!(round_125(3.0), 2.0);
    assert_eq!(round_125(4.0), 5.0);
    assert_eq!(round_125(80.0), 100.0);
    assert_eq!(round_125(f64::NAN), 1.0);
    use super::floor_125;
    for (x, want) in [
        (1.0, 1.0),
        (1.99, 1.0),
        (2.0, 2.0),
        (4.9, 2.0),
        (5.0, 5.0),
        (9.99, 5.0),
        (10.0, 10.0),
        (73.0, 50.0),
        (0.3, 1.0),
        (f64::NAN, 1.0),
    ] {
        assert_eq!(floor_125(x), want, "{x}");
    }
    use super::ceil_125;
    for (x, want) in [
        (1.0, 1.0),
        (1.2, 2.0),
        (2.0, 2.0),
        (3.3, 5.0),
        (5.0, 5.0),
        (6.0, 10.0),
        (10.0, 10.0),
        (73.0, 100.0),
        (0.3, 1.0),
        (f64::NAN, 1.0),
    ] {
        assert_eq!(ceil_125(x), want, "{x}");
    }
}
