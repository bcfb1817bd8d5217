use super::*;
use tirecontact_core::model::road::RoadProfile;
use tirecontact_io::Scene;
use tirecontact_io::SceneSimulation;

/// The three-points preset (a line of points on a ring tyre).
fn three_points() -> Scene {
    Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        )),
        "three_points",
    )
    .unwrap()
}

fn settings() -> FrameSettings {
    FrameSettings {
        t0_s: 0.0,
        t1_s: 0.1,
        fps: 25.0,
        slow_motion: 2.0,
        width: 320,
        height: 240,
    }
}

/// Before the ramp the tyre sees its own point heights (interpolated,
/// held beyond the end points); after it, the road profile itself.
#[test]
fn road_in_tyre_frame_blends_point_heights_into_the_road() {
    let scene = three_points();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let at_start = road_in_tyre_frame(&sim, -0.1, 0.1, 8);
    assert_eq!(at_start.len(), 9);
    for [x, y] in &at_start {
        // h = -1.5 mm at every point of this preset
        assert!((y + 0.0015).abs() < 1e-15, "x = {x}: {y}");
    }
    while sim.time_s() < scene.ramp_s + 1e-3 {
        sim.step().unwrap();
    }
    for [x, y] in road_in_tyre_frame(&sim, -0.1, 0.1, 8) {
        let z = sim.road_profile().sample(x + sim.rolled_m()).unwrap().0;
        assert!((y - z).abs() < 1e-15, "x = {x}: {y} vs {z}");
    }
}

/// Under a row across the tread of a patch on a road surface, the road
/// is the surface at that row's `y`, and before the ramp the heights
/// of that row's points.
#[test]
fn road_under_a_row_is_the_surface_at_its_y() {
    let mut scene = Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/patch_texture.ron"
        )),
        "patch_texture",
    )
    .unwrap();
    let y_row = scene
        .points
        .iter()
        .map(|p| p.y_m)
        .fold(f64::INFINITY, f64::min);
    let row: Vec<(f64, f64)> = scene
        .points
        .iter()
        .filter(|p| p.y_m == y_row)
        .map(|p| (p.x_m, p.h_m))
        .collect();
    assert!(row.len() > 2 && y_row < 0.0);
    // before the ramp: the row's own heights at its points
    let sim = Simulation::from_scene(&scene).unwrap();
    for &(x, h) in &row {
        let at = road_in_tyre_frame_at(&sim, x, x, 1, Some(y_row));
        assert!((at[0][1] - h).abs() < 1e-15, "x = {x}: {:?} vs {h}", at[0]);
    }
    // after a short ramp: the surface at the row's y, not the
    // centreline's
    scene.ramp_s = 1e-4;
    let mut sim = Simulation::from_scene(&scene).unwrap();
    while sim.time_s() < scene.ramp_s + 1e-9 {
        sim.step().unwrap();
    }
    let mut differs = false;
    for [x, z] in road_in_tyre_frame_at(&sim, -0.05, 0.05, 20, Some(y_row)) {
        let want = sim
            .road_profile()
            .sample_at(x + sim.rolled_m(), y_row)
            .unwrap()
            .0;
        assert!((z - want).abs() < 1e-15, "x = {x}: {z} vs {want}");
        let centre = sim.road_profile().sample(x + sim.rolled_m()).unwrap().0;
        differs |= (z - centre).abs() > 1e-6;
    }
    assert!(differs, "the texture is the same across the tread");
}

#[test]
fn frame_count_is_interval_times_rate() {
    assert_eq!(settings().frame_count(), 5);
    let s = FrameSettings {
        slow_motion: 20.0,
        ..settings()
    };
    assert_eq!(s.frame_count(), 50);
    assert!((s.frame_time_s(10) - 0.02).abs() < 1e-15);
}

#[test]
fn bad_settings_name_field_value_and_expectation() {
    let e = FrameSettings {
        fps: 0.0,
        ..settings()
    }
    .check(1.0)
    .unwrap_err();
    assert!(
        matches!(e, FramesError::Setting { field: "fps", value, .. } if value == 0.0),
        "{e:?}"
    );
    let e = e.to_string();
    assert!(e.contains("fps = 0") && e.contains("expected"), "{e}");
    let e = FrameSettings {
        t1_s: 2.0,
        ..settings()
    }
    .check(1.0)
    .unwrap_err()
    .to_string();
    assert!(e.contains("t1_s = 2") && e.contains("duration"), "{e}");
    let e = FrameSettings {
        width: 10,
        ..settings()
    }
    .check(1.0)
    .unwrap_err()
    .to_string();
    assert!(e.contains("width = 10"), "{e}");
}

#[test]
fn cancel_stops_before_writing() {
    let scene = Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/single_mode.ron"
        )),
        "s",
    )
    .unwrap();
    let sim = Simulation::from_scene(&scene).unwrap();
    let dir = std::env::temp_dir().join(format!("tc-anim-cancel-{}", std::process::id()));
    let cancel = AtomicBool::new(true);
    let progress = AtomicU64::new(0);
    let r = export_frames(
        sim,
        &scene.road,
        &dir,
        &settings(),
        false,
        &progress,
        &cancel,
    );
    let e = r.unwrap_err();
    assert!(
        matches!(e, FramesError::Cancelled { done: 0, total: 5 }),
        "{e:?}"
    );
    assert_eq!(e.to_string(), "cancelled after 0 of 5 frames");
    assert!(!frame_path(&dir, 0).exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Pixels of `rgb` (rows of `w`) that blend the road's colour with the
/// white above it by 35 % to 85 %: the road line's antialiased edge
/// (the fill under it is a 25 % blend, its line 100 %).
fn road_edge_pixels(img: &image::RgbImage) -> usize {
    let road = [f64::from(ROAD.0), f64::from(ROAD.1), f64::from(ROAD.2)];
    img.pixels()
        .filter(|p| {
            let a = (255.0 - f64::from(p.0[0])) / (255.0 - road[0]);
            (0.35..0.85).contains(&a)
                && (0..3).all(|c| {
                    let want = a * road[c] + (1.0 - a) * 255.0;
                    (f64::from(p.0[c]) - want).abs() <= 6.0
                })
        })
        .count()
}

/// The frames are antialiased: the sloped road line has an edge of
/// partial blends along its length (a line drawn without antialiasing
/// has almost none), and the frame has the size asked for.
#[test]
fn frames_draw_the_road_antialiased() {
    let scene = Scene::parse(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/paper.ron"
        )),
        "paper",
    )
    .unwrap();
    let mut sim = Simulation::from_scene(&scene).unwrap();
    for _ in 0..6000 {
        sim.step().unwrap();
    }
    let phases = PhaseTracker::new(sim.num_points(), 0.01);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("f.png");
    let (w, h) = (640, 360);
    draw_frame(
        &sim,
        &phases,
        &extents(&sim, &scene.road, (0.0, scene.duration_s), &[]),
        &path,
        w,
        h,
    )
    .unwrap();
    let img = image::open(&path).unwrap().to_rgb8();
    assert_eq!(img.dimensions(), (w, h));
    let edge = road_edge_pixels(&img);
    // the same scene drawn at its size without supersampling
    let mut rgb = vec![0u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
        draw_frame_on(
            &root,
            &sim,
            &phases,
            &extents(&sim, &scene.road, (0.0, scene.duration_s), &[]),
            w,
            h,
        )
        .unwrap();
        root.present().unwrap();
    }
    let aliased = road_edge_pixels(&image::RgbImage::from_raw(w, h, rgb).unwrap());
    assert!(
        edge >= 200 && edge >= 5 * aliased.max(1),
        "{edge} blended road-edge pixels antialiased, {aliased} without"
    );
}

/// A patch's frames draw one row in full, the one nearest the centreline;
/// a single row is drawn whole.
#[test]
fn a_patch_is_drawn_by_its_centre_row() {
    let load = |text: &str, name: &str| Scene::parse(text, name).unwrap();
    let patch = load(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/patch_texture.ron"
        )),
        "patch_texture",
    );
    let sim = Simulation::from_scene(&patch).unwrap();
    let points = &sim.problem().points;
    let y = drawn_row_y_m(points).expect("a patch has rows");
    let nearest = points
        .iter()
        .map(|p| p.y_m.abs())
        .fold(f64::INFINITY, f64::min);
    assert_eq!(y.abs(), nearest);
    let in_row = points.iter().filter(|p| p.y_m == y).count();
    assert!(
        in_row > 1 && in_row < points.len(),
        "{in_row} of {}",
        points.len()
    );
    let paper = load(
        include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/paper.ron"
        )),
        "paper",
    );
    let sim = Simulation::from_scene(&paper).unwrap();
    assert_eq!(drawn_row_y_m(&sim.problem().points), None);
}

/// The counts line says how many points are in each phase, events first
/// and in capitals, without the empty ones.
#[test]
fn phase_counts_name_each_phase_once() {
    use tirecontact_core::solver::phase::ContactPhase as P;
    let phases = [
        P::InContact,
        P::FreeFlight,
        P::InContact,
        P::Impact,
        P::InContact,
    ];
    assert_eq!(
        phase_counts(phases.into_iter()),
        "1 IMPACT · 3 in contact · 1 free flight"
    );
    assert_eq!(phase_counts(std::iter::empty()), "");
}

/// Every frame's road, drawn at `sim`'s time, inside `ext`'s heights:
/// the lowest and highest drawn (mm).
fn drawn_road_mm(sim: &Simulation, ext: &Extents) -> (f64, f64) {
    let mut range = (f64::INFINITY, f64::NEG_INFINITY);
    for [_, y] in road_in_tyre_frame(sim, ext.x0, ext.x1, 600) {
        let y_mm = 1e3 * y;
        assert!(
            ext.y0_mm < y_mm && y_mm < ext.y1_mm,
            "t = {} s: road at {y_mm} mm outside {} to {} mm",
            sim.time_s(),
            ext.y0_mm,
            ext.y1_mm
        );
        range = (range.0.min(y_mm), range.1.max(y_mm));
    }
    range
}

fn harmonic(amplitude_m: f64, wavelength_m: f64) -> tirecontact_core::model::road::Harmonic {
    tirecontact_core::model::road::Harmonic {
        amplitude_m,
        wavelength_m,
        phase_rad: 0.0,
    }
}

/// The frames' height range is set by the road the run rolls over: on a
/// road of a 0.1 m swell 20 m long, rolled over from its trough to its
/// crest (10 m at 100 m/s), it spans the heights drawn over the run (the
/// window's road at the start, around the trough, is not enough), every
/// frame's road inside it.
#[test]
fn the_height_range_fits_the_road_rolled_over() {
    let mut scene = three_points();
    let swell = tirecontact_core::model::road::Harmonic {
        phase_rad: -0.5 * std::f64::consts::PI,
        ..harmonic(0.1, 20.0)
    };
    scene.road = Road::Harmonics {
        components: vec![swell, harmonic(0.001, 0.05)],
    };
    (scene.speed_mps, scene.duration_s, scene.dt_s) = (100.0, 0.11, 1e-4);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let ext = extents(&sim, &scene.road, (0.0, scene.duration_s), &[]);
    // the drawn heights: the road over the run, the points' heights, zero
    let (mut lo, mut hi) = scene.points.iter().fold((0.0f64, 0.0f64), |(a, b), p| {
        (a.min(1e3 * p.h_m), b.max(1e3 * p.h_m))
    });
    let first = drawn_road_mm(&sim, &ext);
    loop {
        let (a, b) = drawn_road_mm(&sim, &ext);
        (lo, hi) = (lo.min(a), hi.max(b));
        if sim.time_s() >= scene.duration_s - 1e-9 {
            break;
        }
        for _ in 0..50 {
            sim.step().unwrap();
        }
    }
    assert!(
        hi - first.1 > 50.0,
        "the road rises by {} mm over the run only",
        hi - first.1
    );
    assert!(
        ext.y1_mm - ext.y0_mm <= 2.5 * (hi - lo),
        "{} to {} mm for heights from {lo} to {hi} mm",
        ext.y0_mm,
        ext.y1_mm
    );
}

/// A road and speed changed during the run (a live edit replayed) are in
/// the frames' height range from their time on: after a change to a road
/// ten times higher and a faster speed, every frame's road is inside it.
#[test]
fn the_height_range_spans_the_roads_of_changes() {
    let mut scene = three_points();
    scene.road = Road::Harmonics {
        components: vec![harmonic(0.001, 0.05)],
    };
    scene.duration_s = 0.04;
    let high = RoadProfile::Harmonics(vec![harmonic(0.01, 0.3)]);
    let (t_change, speed) = (0.02, 2.0 * scene.speed_mps);
    let mut sim = Simulation::from_scene(&scene).unwrap();
    let change = RoadChange {
        t_s: t_change,
        profile: &high,
        speed_mps: speed,
    };
    let ext = extents(&sim, &scene.road, (0.0, scene.duration_s), &[change]);
    let without = extents(&sim, &scene.road, (0.0, scene.duration_s), &[]);
    assert!(
        ext.y1_mm > 5.0 * without.y1_mm,
        "{} vs {} mm",
        ext.y1_mm,
        without.y1_mm
    );
    let mut changed = false;
    while sim.time_s() < scene.duration_s - 1e-9 {
        if !changed && sim.time_s() >= t_change - 1e-9 {
            sim.set_road(high.clone());
            sim.set_speed(speed);
            changed = true;
        }
        drawn_road_mm(&sim, &ext);
        for _ in 0..20 {
            sim.step().unwrap();
        }
    }
    assert!(changed);
    drawn_road_mm(&sim, &ext);
}
