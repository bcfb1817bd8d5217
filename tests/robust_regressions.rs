//! Inputs found by the robust_* property tests to panic, hang or give an
//! unclear error, kept as plain tests (each fixed in its own commit).

use tirecontact::scene::{Point, Scene};
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME};

fn paper() -> Scene {
    Scene::parse(DEFAULT_PRESET, DEFAULT_PRESET_NAME).unwrap()
}

/// A ring tyre at 1000 points passed validation; its identification then
/// sampled P(P+1)/2 = 500 500 responses of 1000 samples (4 GB) and ran for
/// an hour. It is refused, naming `points`, the count and the limit.
#[test]
fn ring_tyre_with_a_thousand_points_is_refused_up_front() {
    let mut s = paper();
    s.points = (0..1000)
        .map(|i| Point {
            x_m: -0.05 + 1e-4 * i as f64,
            h_m: -0.003,
        })
        .collect();
    let errors = s.validate().unwrap_err();
    let e = errors
        .iter()
        .find(|e| e.field == "points")
        .unwrap_or_else(|| panic!("no error about points: {errors:?}"));
    assert!(e.value.contains("1000"), "{e}");
    assert!(e.expected.contains("at most"), "{e}");
    // the shipped ring scene (5 points) and 50 points stay accepted
    assert!(paper().validate().is_ok());
    s.points.truncate(50);
    assert!(s.validate().is_ok(), "{:?}", s.validate());
}

/// `max_model_order: 18446744073709551615` (usize::MAX) panicked the
/// validator ("attempt to multiply with overflow" in lsce/options.rs, debug
/// builds; release builds wrapped and asked for 4 samples). It is an error
/// naming the field, and the duration check stays sensible.
#[test]
fn huge_max_model_order_is_an_error_not_an_overflow() {
    let text = DEFAULT_PRESET.replace(
        "max_model_order: 40",
        "max_model_order: 18446744073709551615",
    );
    assert_ne!(text, DEFAULT_PRESET);
    let err = Scene::parse(&text, "huge.ron").unwrap_err().to_string();
    assert!(
        err.contains("tyre.identification.max_model_order = 18446744073709551615"),
        "{err}"
    );
    assert!(!err.contains("tyre.identification.duration_s"), "{err}");
}
