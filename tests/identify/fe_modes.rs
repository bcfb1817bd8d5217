//! FE mode shapes read directly (method §5.4): exports of the plate of
//! method §5.3 written by an independent UFF writer (pyuff, from the
//! plate's closed form computed in Python: scripts/fe_plate_fixture.py) in
//! datasets 2414 and 55, mm and m units, mass-normalised or not, read back
//! and compared with the crate's closed-form plate; the FE tyre against
//! the plate tyre at the same points (Green functions and a run); node
//! mapping, axes, damping and refusals.

use std::f64::consts::TAU;
use std::path::{Path, PathBuf};
use tirecontact::model::plate::PlateParams;
use tirecontact::readers::fe_modes::{
    self, FeAxes, FeAxis, FeDamping, FeModel, FeModesError, FeModesSpec, FeNodes, FeShapeUnits,
};
use tirecontact::scene::{Contact, Mode, PointGrid, Points, Preload, Scene, Tyre};
use tirecontact::{PreparedModel, SolverOptions};

const FILES: [&str; 3] = [
    "presets/fe_plate.uff",
    "tests/data/fe/plate_55_mm.uff",
    "tests/data/fe/plate_55_m.uff",
];

/// The plate the fixtures were written from (presets' defaults, modes up
/// to 400 Hz).
fn plate() -> PlateParams {
    PlateParams {
        max_freq_hz: 400.0,
        ..PlateParams::default()
    }
}

/// The fixtures' node grid: node `101 + 10 j + i` at `x = (i - 3) 10 mm`,
/// `y = (j - 2) 30 mm`.
fn grid_nodes() -> Vec<(i64, f64, f64)> {
    let mut v = Vec::new();
    for j in 0..5 {
        for i in 0..7 {
            v.push((
                101 + 10 * j + i,
                (i as f64 - 3.0) * 0.01,
                (j as f64 - 2.0) * 0.03,
            ));
        }
    }
    v
}

fn spec(file: &str, nodes: FeNodes) -> FeModesSpec {
    FeModesSpec {
        file: PathBuf::from(file),
        nodes,
        direction: FeAxis::Z,
        axes: FeAxes::default(),
        damping: FeDamping::Ratio(0.05),
        modal_mass_kg: Vec::new(),
        band_hz: fe_modes::ALL_MODES_HZ,
        nearest_within_m: fe_modes::DEFAULT_NEAREST_WITHIN_M,
        shape_units: FeShapeUnits::Consistent,
    }
}

fn all_nodes(file: &str) -> FeModel {
    let g = grid_nodes();
    let nodes = FeNodes::List(g.iter().map(|n| n.0).collect());
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    fe_modes::load(&spec(file, nodes), &xy).unwrap_or_else(|e| panic!("{e}"))
}

/// Largest relative difference of two lists of modes' static compliance
/// `Σ φ φᵀ / ω²` and receptance at `f_hz` (all pairs), against the
/// largest entry.
fn green_difference(a: &[Mode], b: &[Mode], p: usize) -> f64 {
    let g = |modes: &[Mode], i: usize, j: usize, f_hz: f64| -> (f64, f64) {
        let w = TAU * f_hz;
        modes.iter().fold((0.0, 0.0), |(re, im), m| {
            let wk = TAU * m.freq_hz;
            let a = m.shape[i] * m.shape[j];
            // A / (ωk² − ω² + 2i ξ ωk ω)
            let (dr, di) = (wk * wk - w * w, 2.0 * m.damping_ratio * wk * w);
            let d2 = dr * dr + di * di;
            (re + a * dr / d2, im - a * di / d2)
        })
    };
    let mut worst: f64 = 0.0;
    for f_hz in [0.0, 150.0, 260.0, 390.0] {
        let (mut diff, mut scale): (f64, f64) = (0.0, 0.0);
        for i in 0..p {
            for j in 0..p {
                let (ar, ai) = g(a, i, j, f_hz);
                let (br, bi) = g(b, i, j, f_hz);
                diff = diff.max((ar - br).hypot(ai - bi));
                scale = scale.max(ar.hypot(ai));
            }
        }
        worst = worst.max(diff / scale);
    }
    worst
}

/// Each file's 41 modes are the plate's: frequencies and mass-normalised
/// shapes at the 35 nodes as the closed form gives them (the files carry
/// six significant digits), whatever the dataset (2414, 55), units (mm-N-t
/// with shapes in 1/√t; mm-mN-kg with unit-amplitude shapes and the modal
/// mass in the record; SI with six values per node).
#[test]
fn fe_plate_files_read_the_closed_form_modes() {
    let pl = plate();
    let expected = pl.plate_modes();
    assert_eq!(expected.len(), 41);
    let g = grid_nodes();
    for file in FILES {
        let fe = all_nodes(file);
        assert_eq!(fe.modes.len(), expected.len(), "{file}");
        let (mut worst_f, mut worst_s): (f64, f64) = (0.0, 0.0);
        for (m, r) in fe.modes.iter().zip(&fe.read) {
            let (n, mm, sine) = (
                (r.mode_number / 1000) as u32,
                ((r.mode_number % 1000) / 2) as u32,
                r.mode_number % 2 == 1,
            );
            let md = expected
                .iter()
                .find(|e| e.n == n && e.m == mm && e.sine == sine)
                .unwrap_or_else(|| panic!("{file}: mode {} not a plate mode", r.mode_number));
            let f = md.omega_rad_s / TAU;
            worst_f = worst_f.max((m.freq_hz - f).abs() / f);
            let peak = 1.0 / pl.modal_mass_kg(mm).sqrt();
            for (k, &(_, x, y)) in g.iter().enumerate() {
                worst_s = worst_s.max((m.shape[k] - pl.shape(md, x, y)).abs() / peak);
            }
        }
        eprintln!(
            "{file}: frequencies within {worst_f:.2e}, shapes within {worst_s:.2e} (relative)"
        );
        assert!(worst_f < 5e-6, "{file}: frequency off by {worst_f:e}");
        assert!(worst_s < 1e-5, "{file}: shape off by {worst_s:e}");
    }
    // the factors read from dataset 164
    let fe = all_nodes(FILES[0]);
    assert_eq!(
        (fe.length_factor, fe.force_factor, fe.mass_factor),
        (1000.0, 1.0, 1e-3)
    );
    assert!(
        fe.notes.iter().any(|n| n.contains("1/√(file mass unit)")),
        "{:?}",
        fe.notes
    );
}

/// A scene of a 5 × 3 grid (10 mm along, 30 mm across: on the fixtures'
/// nodes) on a tyre `tyre`, tread springs, a sine road.
fn patch_scene(tyre: Tyre) -> Scene {
    let mut scene = Scene::load(Path::new("presets/patch_texture.ron")).unwrap();
    scene.tyre = tyre;
    scene.points = Points::from_grid(PointGrid {
        along: 5,
        across: 3,
        spacing_m: (0.01, 0.03),
        preload: Preload::Parabolic {
            depth_m: 0.0008,
            length_m: 0.06,
        },
    });
    scene.road = tirecontact::model::road::Road::Sine {
        amplitude_m: 0.0005,
        wavelength_m: 0.05,
    };
    scene.contact = Contact::Compliant {
        stiffness_n_m: vec![75_000.0],
    };
    scene.speed_mps = 10.0;
    scene.ramp_s = 0.005;
    scene.dt_s = 2e-5;
    scene.duration_s = 0.03;
    scene.base_dir = Some(PathBuf::from("."));
    scene
}

fn fe_tyre(file: &str, nodes: FeNodes, damping: FeDamping) -> Tyre {
    Tyre::FeModes {
        file: PathBuf::from(file),
        nodes,
        direction: FeAxis::Z,
        axes: FeAxes::default(),
        damping,
        modal_mass_kg: Vec::new(),
        band_hz: fe_modes::ALL_MODES_HZ,
        nearest_within_m: fe_modes::DEFAULT_NEAREST_WITHIN_M,
        shape_units: FeShapeUnits::Consistent,
    }
}

/// Two representations of the same physics: the FE tyre read at the
/// plate's nodes and the plate tyre at the same points give the same
/// modal model (static compliance and receptances up to 390 Hz within
/// 5e-5 of the largest entry: the files' six digits, frequencies among
/// them) and the same contact forces over
/// a short run on a patch (relative L2 difference below 1e-4).
#[test]
fn fe_tyre_and_plate_tyre_agree_at_the_nodes() {
    let plate_scene = patch_scene(Tyre::Plate { plate: plate() });
    let a = PreparedModel::of(&plate_scene).unwrap();
    for file in FILES {
        let fe_scene = patch_scene(fe_tyre(file, FeNodes::Nearest, FeDamping::Ratio(0.05)));
        let b = PreparedModel::of(&fe_scene).unwrap_or_else(|e| panic!("{e}"));
        let p = plate_scene.points.len();
        let d = green_difference(a.modes(), b.modes(), p);
        eprintln!("{file}: Green functions within {d:.2e} of the plate tyre's");
        assert!(d < 5e-5, "{file}: {d:e}");
        // a short run
        let mut sa = a.simulation(SolverOptions::default()).unwrap();
        let mut sb = b.simulation(SolverOptions::default()).unwrap();
        let (mut num, mut den) = (0.0, 0.0);
        while !sa.finished() {
            sa.step().unwrap();
            sb.step().unwrap();
            for (qa, qb) in sa.force_n().iter().zip(sb.force_n()) {
                num += (qa - qb) * (qa - qb);
                den += qa * qa;
            }
        }
        let rel = (num / den).sqrt();
        eprintln!("{file}: run forces within {rel:.2e} (relative L2) of the plate tyre's");
        assert!(den > 0.0 && rel < 1e-4, "{file}: {rel:e}");
    }
}

/// `Nearest` picks the node under each point (0.3 mm off the grid), says
/// how far it is, refuses a point farther than the tolerance naming it,
/// and looks on the road side: a second layer of nodes 50 mm up (higher
/// along `direction`) with other shapes is not picked.
#[test]
fn nearest_picks_the_nodes_under_the_points() {
    let file = FILES[1];
    let g = grid_nodes();
    let pts: Vec<(f64, f64)> = g.iter().map(|n| (n.1 + 0.0003, n.2 - 0.0003)).collect();
    let fe = fe_modes::load(&spec(file, FeNodes::Nearest), &pts).unwrap();
    for (k, nm) in fe.mapping.iter().enumerate() {
        assert_eq!(nm.node, g[k].0, "point {k}");
        let d = nm.distance_m.unwrap();
        assert!((d - 0.0003 * 2f64.sqrt()).abs() < 1e-9, "point {k}: {d}");
    }
    // one point 5 mm off
    let mut far = pts.clone();
    far[7].0 += 0.005;
    match fe_modes::load(&spec(file, FeNodes::Nearest), &far) {
        Err(
            e @ FeModesError::TooFar {
                point: 7,
                node: 112,
                ..
            },
        ) => {
            let s = e.to_string();
            assert!(
                s.contains("points[7]") && s.contains("nearest_within_m"),
                "{s}"
            );
        }
        other => panic!("expected points[7] refused, got {other:?}"),
    }
    // a second layer 50 mm up, its shapes doubled
    let bytes = std::fs::read(file).unwrap();
    let mut raw = fe_modes::uff_shapes::read(&bytes).unwrap();
    let low: Vec<(i64, [f64; 3])> = raw.nodes.iter().map(|(n, c)| (*n, *c)).collect();
    for (n, c) in low {
        raw.nodes.insert(n + 1000, [c[0], c[1], c[2] + 50.0]);
        for m in &mut raw.modes {
            let v = m.shape[&n];
            m.shape.insert(n + 1000, [v[0], v[1], 2.0 * v[2]]);
        }
    }
    let sp = spec(file, FeNodes::Nearest);
    let layered = fe_modes::build(&sp, &raw, &pts).unwrap();
    assert_eq!(layered.modes, fe.modes);
    assert!(layered.mapping.iter().all(|m| m.node < 1000));
}

/// The FE axes are mapped as stated: the same plate with its coordinates
/// and displacements permuted (along Y, across X; or the road normal
/// along Y) gives the same modal model under the matching `axes` and
/// `direction`, and a wrong mapping does not.
#[test]
fn axes_map_the_fe_coordinates_to_the_points() {
    let file = FILES[2];
    let g = grid_nodes();
    let pts: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let bytes = std::fs::read(file).unwrap();
    let raw = fe_modes::uff_shapes::read(&bytes).unwrap();
    let base = fe_modes::build(&spec(file, FeNodes::Nearest), &raw, &pts).unwrap();
    // permute: new[k] = old[perm[k]]
    let permuted = |perm: [usize; 3]| {
        let mut r = raw.clone();
        for c in r.nodes.values_mut() {
            *c = [c[perm[0]], c[perm[1]], c[perm[2]]];
        }
        for m in &mut r.modes {
            for v in m.shape.values_mut() {
                *v = [v[perm[0]], v[perm[1]], v[perm[2]]];
            }
        }
        r
    };
    // along Y, across X
    let swapped = permuted([1, 0, 2]);
    let mut sp = spec(file, FeNodes::Nearest);
    sp.axes = FeAxes {
        along: FeAxis::Y,
        across: FeAxis::X,
    };
    let m = fe_modes::build(&sp, &swapped, &pts).unwrap();
    assert_eq!(m.modes, base.modes);
    // the normal along Y, across along Z
    let turned = permuted([0, 2, 1]);
    let mut sp = spec(file, FeNodes::Nearest);
    sp.axes = FeAxes {
        along: FeAxis::X,
        across: FeAxis::Z,
    };
    sp.direction = FeAxis::Y;
    let m = fe_modes::build(&sp, &turned, &pts).unwrap();
    assert_eq!(m.modes, base.modes);
    // the swapped file read with the default axes: other nodes or none
    match fe_modes::build(&spec(file, FeNodes::Nearest), &swapped, &pts) {
        Ok(m) => assert_ne!(m.modes, base.modes),
        Err(FeModesError::TooFar { .. }) => {}
        Err(e) => panic!("{e}"),
    }
}

/// A file in mm (2414 in mm-N-t, 55 in mm-mN-kg) and one in m give the
/// same model at the same points; shapes scaled as displacements per √kg
/// (`LengthPerSqrtKg`) are divided by the length factor.
#[test]
fn mm_and_m_files_give_the_same_model() {
    let si = all_nodes(FILES[2]);
    let p = si.modes[0].shape.len();
    for file in &FILES[..2] {
        let d = green_difference(&all_nodes(file).modes, &si.modes, p);
        eprintln!("{file} against the SI file: {d:.2e}");
        assert!(d < 1e-5, "{file}: {d:e}");
    }
    let g = grid_nodes();
    let mut sp = spec(FILES[1], FeNodes::List(g.iter().map(|n| n.0).collect()));
    sp.shape_units = FeShapeUnits::LengthPerSqrtKg;
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let per_mm = fe_modes::load(&sp, &xy).unwrap();
    let mm = all_nodes(FILES[1]);
    for (a, b) in per_mm.modes.iter().zip(&mm.modes) {
        for (x, y) in a.shape.iter().zip(&b.shape) {
            assert!((x * 1000.0 - y).abs() <= 1e-12 * y.abs().max(1e-300));
        }
    }
}

/// Damping: Rayleigh's `ξ = α/(2ω) + βω/2` with α and β set by hand to
/// give ξ = 0.02 at the lowest mode and 0.04 at the highest (solved here
/// as a 2 × 2 system), the records' ratios (`FromFile`), one per mode
/// (`Modal`), and a `Modal` list of the wrong length refused.
#[test]
fn damping_rayleigh_from_file_and_per_mode() {
    let base = all_nodes(FILES[2]);
    let (w1, w2) = (
        TAU * base.modes[0].freq_hz,
        TAU * base.modes.last().unwrap().freq_hz,
    );
    // [1/(2w1)  w1/2; 1/(2w2)  w2/2] [α β]ᵀ = [0.02 0.04]ᵀ by Cramer's rule
    let det = w2 / (4.0 * w1) - w1 / (4.0 * w2);
    let alpha = (0.02 * w2 / 2.0 - 0.04 * w1 / 2.0) / det;
    let beta = (0.04 / (2.0 * w1) - 0.02 / (2.0 * w2)) / det;
    let g = grid_nodes();
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let mut sp = spec(FILES[2], FeNodes::Nearest);
    sp.damping = FeDamping::Rayleigh {
        alpha_per_s: alpha,
        beta_s: beta,
    };
    let r = fe_modes::load(&sp, &xy).unwrap();
    assert!((r.modes[0].damping_ratio - 0.02).abs() < 1e-12);
    assert!((r.modes.last().unwrap().damping_ratio - 0.04).abs() < 1e-12);
    // in between, the curve's minimum √(αβ) is not undershot
    let floor = (alpha * beta).sqrt();
    assert!(r.modes.iter().all(|m| m.damping_ratio >= floor - 1e-15));
    sp.damping = FeDamping::FromFile;
    let r = fe_modes::load(&sp, &xy).unwrap();
    assert!(
        r.modes
            .iter()
            .all(|m| (m.damping_ratio - 0.02).abs() < 1e-12)
    );
    let n = r.modes.len();
    sp.damping = FeDamping::Modal((0..n).map(|k| 0.001 * k as f64).collect());
    let r = fe_modes::load(&sp, &xy).unwrap();
    assert!(
        r.modes
            .iter()
            .enumerate()
            .all(|(k, m)| m.damping_ratio == 0.001 * k as f64)
    );
    sp.damping = FeDamping::Modal(vec![0.01; n - 1]);
    let e = fe_modes::load(&sp, &xy).unwrap_err().to_string();
    assert!(
        e.contains("tyre.damping") && e.contains(&format!("({n})")),
        "{e}"
    );
}

/// The 1-based line of the `nth` (0-based) line of `text` equal to `id`
/// after trimming, with the record it opens.
fn find_line(text: &str, id: &str, nth: usize) -> usize {
    text.lines()
        .enumerate()
        .filter(|(_, l)| l.trim() == id)
        .nth(nth)
        .map(|(k, _)| k + 1)
        .unwrap()
}

fn refused(text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("fe_modes_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(format!(
        "bad_{:x}.uff",
        text.len() ^ text.as_bytes()[text.len() / 2] as usize
    ));
    std::fs::write(&path, text).unwrap();
    let g = grid_nodes();
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let r = fe_modes::load(&spec(path.to_str().unwrap(), FeNodes::Nearest), &xy);
    std::fs::remove_file(&path).ok();
    match r {
        Ok(_) => panic!("a malformed file was accepted"),
        Err(e) => e.to_string(),
    }
}

/// Malformed files are refused naming the record (its place in the file),
/// the dataset, the line and the reason; a file without normal modes says
/// what it holds.
#[test]
fn malformed_records_are_refused_by_record_number() {
    let text = std::fs::read_to_string(FILES[1]).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let edit = |at: usize, new: &str| {
        let mut v = lines.clone();
        v[at - 1] = new;
        v.join("\n") + "\n"
    };
    // the third mode (record 5: 164 and 15 come first): a value unreadable
    let id = find_line(&text, "55", 2);
    let bad = id + 10; // record 10 of the first node
    let e = refused(&edit(bad, "  0.00000E+00  0.00000E+00  x.1E+00"));
    assert!(
        e.contains(&format!("record 5 (dataset 55, line {bad})")) && e.contains("`x.1E+00`"),
        "{e}"
    );
    // complex data in record 4's data definition: each value then has a
    // real and an imaginary part, and the record's real values are too few
    let id = find_line(&text, "55", 1);
    let e = refused(&edit(
        id + 6,
        "         1         2         2         8         5         3",
    ));
    assert!(
        e.contains("record 4 (dataset 55, line")
            && e.contains("node 101: 7 numbers: expected 6")
            && e.contains("each a real and an imaginary part"),
        "{e}"
    );
    // a data type that is neither real nor complex
    let e = refused(&edit(
        id + 6,
        "         1         2         2         8         3         3",
    ));
    assert!(
        e.contains(&format!("record 4 (dataset 55, line {})", id + 6)) && e.contains("data type 3"),
        "{e}"
    );
    // no modal mass in record 3
    let id = find_line(&text, "55", 0);
    let e = refused(&edit(
        id + 8,
        "  1.23321E+02  0.00000E+00  0.00000E+00  0.00000E+00",
    ));
    assert!(e.contains("record 3") && e.contains("modal_mass_kg"), "{e}");
    // a node missing from record 6
    let id = find_line(&text, "55", 3);
    let mut v = lines.clone();
    v.drain(id + 8..id + 10);
    let e = refused(&(v.join("\n") + "\n"));
    assert!(e.contains("record 6") && e.contains("node 101"), "{e}");
    // truncated
    let cut = &text[..text.len() - 200];
    let e = refused(cut);
    assert!(e.contains("no closing") && e.contains("record 43"), "{e}");
    // frequency responses only
    let fr = text.replace(
        "         1         2         2         8         2         3",
        "         1         5         2         8         2         3",
    );
    let e = refused(&fr);
    assert!(
        e.contains("no normal modes")
            && e.contains("41 × dataset 55 of frequency response (analysis type 5)")
            && e.contains("1 × dataset 15 (node coordinates)"),
        "{e}"
    );
    // 2414: record 12 unreadable
    let text = std::fs::read_to_string(FILES[0]).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let id = find_line(&text, "2414", 1);
    let mut v = lines.clone();
    v[id + 11] = "  0.00000e+00  abc";
    let e = refused(&(v.join("\n") + "\n"));
    assert!(
        e.contains(&format!("record 4 (dataset 2414, line {})", id + 12))
            && e.contains("record 12"),
        "{e}"
    );
}

/// The preset syntax: `nodes: [..]` or `Nearest`, `Rayleigh(alpha: ..,
/// beta: ..)`, `modal_mass: 1.0`; saved and read back unchanged.
#[test]
fn fe_tyre_preset_syntax_reads_and_saves() {
    let text = r#"Scene(
        name: "fe",
        tyre: FeModes(file: "plate.uff", nodes: Nearest, direction: Z,
            axes: (along: X, across: Y), damping: Rayleigh(alpha: 10.0, beta: 1e-5),
            modal_mass: 1.0),
        points: [Point(x_m: 0.0, h_m: -0.001), Point(x_m: 0.01, h_m: -0.001)],
        road: Sine(amplitude_m: 0.0, wavelength_m: 1.0),
        speed_mps: 10.0, dt_s: 1e-5, duration_s: 0.01,
    )"#;
    let s = Scene::from_ron_str(text, "fe.ron").unwrap_or_else(|e| panic!("{e}"));
    let sp = s.tyre.fe_spec(None).unwrap();
    assert_eq!(sp.nodes, FeNodes::Nearest);
    assert_eq!(sp.modal_mass_kg, vec![1.0]);
    assert_eq!(
        sp.damping,
        FeDamping::Rayleigh {
            alpha_per_s: 10.0,
            beta_s: 1e-5
        }
    );
    let listed = text.replace("nodes: Nearest", "nodes: [101, 102]");
    let s2 = Scene::from_ron_str(&listed, "fe.ron").unwrap();
    assert_eq!(
        s2.tyre.fe_spec(None).unwrap().nodes,
        FeNodes::List(vec![101, 102])
    );
    for sc in [s, s2] {
        let saved = sc.to_ron_string();
        let back =
            Scene::from_ron_str(&saved, "saved.ron").unwrap_or_else(|e| panic!("{e}\n{saved}"));
        assert_eq!(back.tyre, sc.tyre, "{saved}");
    }
    // nodes listed: one per point
    let three = listed.replace("nodes: [101, 102]", "nodes: [101, 102, 103]");
    let e = Scene::from_ron_str(&three, "fe.ron")
        .unwrap()
        .validate()
        .unwrap_err();
    assert!(e.iter().any(|f| f.field == "tyre.nodes"), "{e:?}");
}

/// Files as other programs write them read alike: CRLF line ends, a
/// Latin-1 byte (`µ`) in an ID line, `D` exponents in the 2411
/// coordinates, and a 2414 record that gives the eigenvalue `ω²` but no
/// frequency.
#[test]
fn crlf_latin1_d_exponents_and_eigenvalues_read_alike() {
    let g = grid_nodes();
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let base = all_nodes(FILES[0]);
    let text = std::fs::read_to_string(FILES[0]).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut out: Vec<u8> = Vec::new();
    let mut in2411 = false;
    let mut k = 0;
    while k < lines.len() {
        let l = lines[k];
        if l.trim() == "2411" {
            in2411 = true;
        } else if l.trim() == "-1" {
            in2411 = false;
        }
        let mut line = l.as_bytes().to_vec();
        if in2411 && (l.contains("e+") || l.contains("e-")) {
            line = l.replace('e', "D").into_bytes();
        }
        if l.starts_with("normal mode") {
            line = b"normal mode, shapes in \xb5m? no: 1/sqrt(t)".to_vec();
        }
        // record 12 of a 2414: frequency 0, the eigenvalue kept
        if k >= 12 && lines[k - 12].trim() == "2414" {
            let mut f: Vec<String> = l.split_whitespace().map(String::from).collect();
            f[1] = "0.00000e+00".into();
            line = format!("  {}", f.join("  ")).into_bytes();
        }
        out.extend_from_slice(&line);
        out.extend_from_slice(b"\r\n");
        k += 1;
    }
    let dir = std::env::temp_dir().join(format!("fe_modes_crlf_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("crlf.uff");
    std::fs::write(&path, &out).unwrap();
    let r = fe_modes::load(&spec(path.to_str().unwrap(), FeNodes::Nearest), &xy);
    std::fs::remove_dir_all(&dir).ok();
    let r = r.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.modes.len(), base.modes.len());
    for (a, b) in r.modes.iter().zip(&base.modes) {
        // f and ω² each written with six digits: within 4e-6 + 2e-6
        assert!(
            (a.freq_hz - b.freq_hz).abs() < 6e-6 * b.freq_hz,
            "{} vs {}",
            a.freq_hz,
            b.freq_hz
        );
        assert_eq!(a.shape, b.shape);
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: crate::support::proptest_cases(200),
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// Hostile bytes: a fixture cut anywhere, with up to four bytes
    /// overwritten anywhere, is read or refused, never a panic; a refusal
    /// names a line, and a refusal inside a dataset its record.
    #[test]
    fn damaged_files_are_read_or_refused_never_a_panic(
        which in 0usize..3,
        cut in 0.0f64..1.0,
        edits in proptest::collection::vec((0.0f64..1.0, proptest::prelude::any::<u8>()), 0..4),
    ) {
        let mut bytes = std::fs::read(FILES[which]).unwrap();
        let n = ((bytes.len() as f64) * (0.05 + 0.95 * cut)) as usize;
        bytes.truncate(n.max(1));
        for (at, b) in edits {
            let k = ((bytes.len() - 1) as f64 * at) as usize;
            bytes[k] = b;
        }
        match fe_modes::uff_shapes::read(&bytes) {
            Ok(fe) => {
                let g = grid_nodes();
                let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
                let _ = fe_modes::build(&spec("damaged.uff", FeNodes::Nearest), &fe, &xy);
            }
            Err(e) => {
                let s = e.to_string();
                proptest::prop_assert!(s.contains("line "), "{}", s);
            }
        }
    }
}

/// Rigid contact needs at most as many points as modes (the contact
/// system is a sum of rank-one terms): 15 points on the 5 modes below
/// 160 Hz are refused, saying so, and accepted with tread springs.
#[test]
fn rigid_contact_with_more_points_than_modes_is_refused() {
    let mut scene = patch_scene(fe_tyre(FILES[0], FeNodes::Nearest, FeDamping::Ratio(0.05)));
    if let Tyre::FeModes { band_hz, .. } = &mut scene.tyre {
        *band_hz = (0.0, 160.0);
    }
    PreparedModel::of(&scene).unwrap();
    scene.contact = Contact::Rigid;
    let e = PreparedModel::of(&scene).unwrap_err().to_string();
    assert!(
        e.contains("rigid contact of 15 points on 5 modes") && e.contains("Compliant"),
        "{e}"
    );
}

/// A modal analysis exports more than displacements: normal-mode records
/// of stresses (result type 2) beside the displacements are skipped, the
/// model unchanged; a file of stresses alone says what it holds.
#[test]
fn other_results_of_the_modes_are_skipped() {
    let text = std::fs::read_to_string(FILES[0]).unwrap();
    let blocks: Vec<&str> = text.split("    -1\n    -1\n").collect();
    // each mode again as a stress record (result type 2): the mode's block
    // with its record 9 changed
    let def = "         1         2         2         8         4         3";
    let stress_def = "         1         2         2         2         4         3";
    let stresses: Vec<String> = blocks[2..]
        .iter()
        .map(|b| {
            b.replace(def, stress_def)
                .trim_end_matches("    -1\n")
                .to_string()
        })
        .collect();
    let both = format!(
        "{}    -1\n    -1\n{}    -1\n",
        text,
        stresses.join("\n    -1\n    -1\n")
    );
    let dir = std::env::temp_dir().join(format!("fe_modes_stress_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("both.uff");
    std::fs::write(&path, &both).unwrap();
    let g = grid_nodes();
    let xy: Vec<(f64, f64)> = g.iter().map(|n| (n.1, n.2)).collect();
    let r = fe_modes::load(&spec(path.to_str().unwrap(), FeNodes::Nearest), &xy);
    let only = text.replace(def, stress_def);
    std::fs::write(&path, &only).unwrap();
    let e = fe_modes::load(&spec(path.to_str().unwrap(), FeNodes::Nearest), &xy);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(
        r.unwrap_or_else(|e| panic!("{e}")).modes,
        all_nodes(FILES[0]).modes
    );
    let e = e.unwrap_err().to_string();
    assert!(
        e.contains("41 × dataset 2414 of normal mode stress (result type 2)"),
        "{e}"
    );
}
