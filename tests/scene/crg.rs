//! OpenCRG roads in a scene: the shipped Belgian block preset, the run
//! refused where it would leave the file or cross cells without height
//! (each named), the heights at the nodes those of the standard less the
//! mean height, and the scene's `y` to the left as OpenCRG's `v`.

use std::path::Path;
use tirecontact::model::road::Road;
use tirecontact::readers::crg::read_crg;
use tirecontact::{PreparedModel, Scene, SceneError};

fn belgian() -> Scene {
    Scene::load(Path::new("presets/patch_belgian_block.ron")).unwrap()
}

fn refused(scene: &Scene) -> Vec<tirecontact::base::error::FieldError> {
    match PreparedModel::of(scene) {
        Err(SceneError::Invalid { errors, .. }) => errors,
        Err(e) => panic!("refused otherwise: {e}"),
        Ok(_) => panic!("accepted"),
    }
}

fn set_road(scene: &mut Scene, u_start: Option<f64>, v_offset: f64) {
    let Road::Crg {
        u_start_m,
        v_offset_m,
        ..
    } = &mut scene.road
    else {
        panic!("not an OpenCRG road");
    };
    (*u_start_m, *v_offset_m) = (u_start, v_offset);
}

/// A run that would leave the file is refused naming the last time that
/// fits: the patch's front point (x = 45 mm) starts 1 m into the 10 m
/// file, at 8 m/s it reaches the end after (9 - 0.045) / 8 s.
#[test]
fn a_run_past_the_end_of_the_file_names_the_last_time_that_fits() {
    let mut s = belgian();
    s.duration_s = 2.0;
    let e = refused(&s);
    assert_eq!(e.len(), 1, "{e:?}");
    assert_eq!(e[0].field, "duration_s");
    let x_front = s.points.iter().map(|p| p.x_m).fold(f64::MIN, f64::max);
    let t_last = (9.0 - x_front) / 8.0;
    assert!(
        e[0].expected.contains(&format!(
            "a duration <= {}",
            tirecontact::base::error::fmt_num(t_last)
        )),
        "{}",
        e[0].expected
    );
    // within it: accepted
    s.duration_s = t_last - 1e-3;
    PreparedModel::of(&s).unwrap();
    // starting before the file
    let mut s = belgian();
    set_road(&mut s, Some(729.0), 0.0);
    let e = refused(&s);
    assert!(
        e.iter()
            .all(|e| e.field.starts_with("points[") && e.field.ends_with("].x_m")),
        "{e:?}"
    );
}

/// The Belgian block has no heights near its right edge (v < -1.37 m):
/// a patch rolling there is refused, each point over a gap named; a patch
/// beyond the edge is refused by its points' `y`.
#[test]
fn points_over_cells_without_height_are_named() {
    let mut s = belgian();
    set_road(&mut s, Some(731.0), -1.5);
    let e = refused(&s);
    assert!(!e.is_empty());
    for e in &e {
        assert!(
            e.field.starts_with("points[") && e.field.ends_with(']'),
            "{e:?}"
        );
        assert!(e.expected.contains("no height at u = "), "{}", e.expected);
    }
    set_road(&mut s, Some(731.0), -1.7);
    let e = refused(&s);
    assert!(e.iter().any(|e| e.field.ends_with("].y_m")), "{e:?}");
}

/// At the grid's nodes the road a run samples is the standard's
/// evaluation less the file's mean height; `u_start_m` defaults to the
/// file's first cross section.
#[test]
fn node_heights_are_the_standards_less_the_mean() {
    let s = belgian();
    let model = PreparedModel::of(&s).unwrap();
    let crg = read_crg(Path::new("presets/roads/belgian_block.crg")).unwrap();
    let g = model.road().surface().unwrap();
    assert!((g.datum_m - crg.mean_height_m()).abs() == 0.0);
    assert!((g.datum_m - 2.1135).abs() < 1e-3, "{}", g.datum_m);
    for (k, j) in [(100, 170), (101, 171), (555, 200), (1000, 340), (250, 33)] {
        let (u, v) = (crg.u_at(k), crg.v_m[j]);
        let want = crg.evaluate_m(u, v).unwrap();
        let (z, _) = model.road().sample_at(u - 731.0, v).unwrap();
        assert!(
            (z - (want - g.datum_m)).abs() < 1e-12,
            "({k}, {j}): {z} vs {want}"
        );
    }
    // `u_start_m` defaults to the first cross section: the patch's rear
    // half (x < 0) then starts before the file, each point named
    let mut s = belgian();
    set_road(&mut s, None, 0.0);
    let e = refused(&s);
    assert_eq!(e.len(), 48, "{e:?}");
    assert!(
        e[0].expected.contains("u = 730 m under x = 0"),
        "{}",
        e[0].expected
    );
}

/// The scene's `y` points to the left, as OpenCRG's `v`: on the banked
/// handmade road (banking 0.011 at u = 2 m), a point at y = +1 m is
/// 0.022 m higher than one at y = -1 m where the grid is flat.
#[test]
fn y_points_to_the_left_as_v() {
    let text = r#"Scene(
    name: "banked",
    tyre: Modal(modes: [(freq_hz: 100.0, damping_ratio: 0.05, residue: [[1e-3, 0.0], [0.0, 1e-3]])]),
    points: [(x_m: 0.0, y_m: 1.0, h_m: -0.5), (x_m: 0.0, y_m: -1.0, h_m: -0.5)],
    road: Crg(file: "handmade_banked.crg", u_start_m: Some(2.0)),
    speed_mps: 1.0,
    ramp_s: 0.1,
    dt_s: 1e-4,
    duration_s: 0.5,
)"#;
    let mut s = Scene::parse(text, "banked").unwrap();
    s.base_dir = Some(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/crg"));
    let model = PreparedModel::of(&s).unwrap();
    let crg = read_crg(Path::new("tests/data/crg/handmade_banked.crg")).unwrap();
    let left = model.road().sample_at(0.0, 1.0).unwrap().0;
    let right = model.road().sample_at(0.0, -1.0).unwrap().0;
    let (gl, gr) = (
        crg.z_m[4 * crg.nu + 2] as f64,
        crg.z_m[2 * crg.nu + 2] as f64,
    );
    assert!(
        ((left - right) - (gl - gr + 0.022)).abs() < 1e-9,
        "{left} {right}"
    );
    assert!(left - right > 0.0);
}
