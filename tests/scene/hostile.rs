//! Hostile values, hostile list lengths and byte-level corruptions of every
//! shipped preset (and the embedded default) never panic the parser, the
//! validator, `Simulation::new` or 200 steps; an invalid scene's error names
//! the field that was changed (or the field it is checked against), and a
//! syntax error carries a line and column inside the text.
//!
//! Cases per property: `PROPTEST_CASES`, else 300 (hostile numbers, hostile
//! structure) and 400 (byte corruptions): 6-9 s in a debug build, most of
//! it identifying the mutated ring tyres (0.3 s each, cached per ring).

use crate::support::{proptest_cases, temp_dir};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use tirecontact::SceneSimulation;
use tirecontact::model::road::{Harmonic, Road};
use tirecontact::scene::{Contact, Mode, Point, Scene, Tyre};
use tirecontact::{DEFAULT_PRESET, DEFAULT_PRESET_NAME, SceneError, Simulation};

/// (file name, text) of every preset and of the embedded default.
fn presets() -> Vec<(String, String)> {
    let mut v: Vec<(String, String)> = std::fs::read_dir("presets")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    v.sort();
    v.push((DEFAULT_PRESET_NAME.to_string(), DEFAULT_PRESET.to_string()));
    v
}

fn parsed_presets() -> Vec<Scene> {
    presets()
        .iter()
        .map(|(n, t)| {
            let mut s = Scene::parse(t, n).unwrap();
            s.base_dir = Some(PathBuf::from("presets"));
            s
        })
        .collect()
}

/// Values a hand-written or generated preset may hold (all writable in RON).
/// The last ones are the edges of the accepted ranges (dt_s <= 0.1 s,
/// speed <= 1000 m/s, |h| <= 1 m, freq <= 1e6 Hz, damping <= 1e4, tread
/// stiffness <= 1e16 N/m): accepted, they must run or fail cleanly.
const HOSTILE_F64: [f64; 23] = [
    0.0,
    -0.0,
    -1.0,
    1e-300,
    -1e-300,
    1e300,
    -1e300,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    5e-324,   // smallest subnormal
    2.5e-310, // a subnormal
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    1e6,
    0.1,
    1.0,
    1000.0,
    1e4,
    1e16,
    1e-9,
    -0.999,
];

const HOSTILE_USIZE: [usize; 6] = [0, 1, 2001, 1 << 31, u32::MAX as usize, usize::MAX];

/// A place holding a number in a scene.
enum Site<'a> {
    F(&'a mut f64),
    U(&'a mut usize),
    OptU(&'a mut Option<usize>),
    U64(&'a mut u64),
}

/// Every numeric field of `s`, with its path as validation names it.
fn sites(s: &mut Scene) -> Vec<(String, Site<'_>)> {
    let mut v: Vec<(String, Site<'_>)> = vec![
        ("speed_mps".into(), Site::F(&mut s.speed_mps)),
        ("ramp_s".into(), Site::F(&mut s.ramp_s)),
        ("dt_s".into(), Site::F(&mut s.dt_s)),
        ("duration_s".into(), Site::F(&mut s.duration_s)),
    ];
    for (i, p) in s.points.iter_mut().enumerate() {
        v.push((format!("points[{i}].x_m"), Site::F(&mut p.x_m)));
        v.push((format!("points[{i}].y_m"), Site::F(&mut p.y_m)));
        v.push((format!("points[{i}].h_m"), Site::F(&mut p.h_m)));
    }
    match &mut s.tyre {
        Tyre::Modal { modes } => {
            for (k, m) in modes.iter_mut().enumerate() {
                let at = format!("tyre.modes[{k}]");
                v.push((format!("{at}.freq_hz"), Site::F(&mut m.freq_hz)));
                v.push((format!("{at}.damping_ratio"), Site::F(&mut m.damping_ratio)));
                for (i, row) in m.residue.iter_mut().enumerate() {
                    for (j, a) in row.iter_mut().enumerate() {
                        v.push((format!("{at}.residue[{i}][{j}]"), Site::F(a)));
                    }
                }
                for (i, a) in m.shape.iter_mut().enumerate() {
                    v.push((format!("{at}.shape[{i}]"), Site::F(a)));
                }
            }
        }
        Tyre::Ring {
            ring,
            identification: id,
        } => {
            let r = "tyre.ring";
            v.push((format!("{r}.radius_m"), Site::F(&mut ring.radius_m)));
            v.push((format!("{r}.belt_width_m"), Site::F(&mut ring.belt_width_m)));
            v.push((
                format!("{r}.mass_per_length_kg_m"),
                Site::F(&mut ring.mass_per_length_kg_m),
            ));
            v.push((format!("{r}.inflation_pa"), Site::F(&mut ring.inflation_pa)));
            v.push((
                format!("{r}.radial_stiffness_n_m2"),
                Site::F(&mut ring.radial_stiffness_n_m2),
            ));
            v.push((
                format!("{r}.tangential_stiffness_n_m2"),
                Site::F(&mut ring.tangential_stiffness_n_m2),
            ));
            v.push((
                format!("{r}.bending_stiffness_n_m2"),
                Site::F(&mut ring.bending_stiffness_n_m2),
            ));
            v.push((
                format!("{r}.extensional_stiffness_n"),
                Site::F(&mut ring.extensional_stiffness_n),
            ));
            v.push((
                format!("{r}.damping_ratio"),
                Site::F(&mut ring.damping_ratio),
            ));
            v.push((format!("{r}.max_order"), Site::U(&mut ring.max_order)));
            let i = "tyre.identification";
            v.push((format!("{i}.band_hz"), Site::F(&mut id.band_hz.0)));
            v.push((format!("{i}.band_hz"), Site::F(&mut id.band_hz.1)));
            v.push((
                format!("{i}.sample_rate_hz"),
                Site::F(&mut id.sample_rate_hz),
            ));
            v.push((format!("{i}.duration_s"), Site::F(&mut id.duration_s)));
            v.push((format!("{i}.model_order"), Site::OptU(&mut id.model_order)));
            v.push((
                format!("{i}.max_model_order"),
                Site::U(&mut id.max_model_order),
            ));
            v.push((
                format!("{i}.max_damping_ratio"),
                Site::F(&mut id.max_damping_ratio),
            ));
            v.push((
                format!("{i}.stable_freq_tol"),
                Site::F(&mut id.stable_freq_tol),
            ));
            v.push((
                format!("{i}.stable_damping_tol"),
                Site::F(&mut id.stable_damping_tol),
            ));
            v.push((
                format!("{i}.stable_mac_min"),
                Site::F(&mut id.stable_mac_min),
            ));
            v.push((
                format!("{i}.order_tolerance"),
                Site::F(&mut id.order_tolerance),
            ));
            v.push((
                format!("{i}.min_contribution"),
                Site::F(&mut id.min_contribution),
            ));
        }
        // (no shipped preset has measured responses: their file's
        // refusals are tested in tirecontact::readers::measured)
        Tyre::Measured { .. } => {}
        Tyre::Plate { plate } => {
            for (name, x) in [
                ("width_m", &mut plate.width_m),
                ("circumference_m", &mut plate.circumference_m),
                ("mass_per_area_kg_m2", &mut plate.mass_per_area_kg_m2),
                ("bending_along_nm", &mut plate.bending_along_nm),
                ("bending_across_nm", &mut plate.bending_across_nm),
                ("tension_along_n_m", &mut plate.tension_along_n_m),
                ("tension_across_n_m", &mut plate.tension_across_n_m),
                ("foundation_n_m3", &mut plate.foundation_n_m3),
                ("damping_ratio", &mut plate.damping_ratio),
                ("max_freq_hz", &mut plate.max_freq_hz),
            ] {
                v.push((format!("tyre.plate.{name}"), Site::F(x)));
            }
        }
        Tyre::FeModes {
            damping,
            nearest_within_m,
            ..
        } => {
            use tirecontact::readers::fe_modes::FeDamping;
            match damping {
                FeDamping::Ratio(x) => v.push(("tyre.damping.0".into(), Site::F(x))),
                FeDamping::Rayleigh {
                    alpha_per_s,
                    beta_s,
                } => {
                    v.push(("tyre.damping.alpha_per_s".into(), Site::F(alpha_per_s)));
                    v.push(("tyre.damping.beta_s".into(), Site::F(beta_s)));
                }
                FeDamping::Modal(_) | FeDamping::FromFile => {}
            }
            v.push(("tyre.nearest_within_m".into(), Site::F(nearest_within_m)));
        }
    }
    match &mut s.road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => {
            v.push(("road.amplitude_m".into(), Site::F(amplitude_m)));
            v.push(("road.wavelength_m".into(), Site::F(wavelength_m)));
        }
        Road::Harmonics { components } => {
            for (k, c) in components.iter_mut().enumerate() {
                let at = format!("road.components[{k}]");
                v.push((format!("{at}.amplitude_m"), Site::F(&mut c.amplitude_m)));
                v.push((format!("{at}.wavelength_m"), Site::F(&mut c.wavelength_m)));
                v.push((format!("{at}.phase_rad"), Site::F(&mut c.phase_rad)));
            }
        }
        Road::Measured { .. } => {}
        Road::Random {
            seed,
            length_m,
            min_wavenumber_cpm,
            max_wavenumber_cpm,
            ..
        } => {
            v.push(("road.seed".into(), Site::U64(seed)));
            v.push(("road.length_m".into(), Site::F(length_m)));
            v.push((
                "road.min_wavenumber_cpm".into(),
                Site::F(min_wavenumber_cpm),
            ));
            v.push((
                "road.max_wavenumber_cpm".into(),
                Site::F(max_wavenumber_cpm),
            ));
        }
        Road::Surface { .. } => {}
        Road::Crg {
            u_start_m,
            v_offset_m,
            ..
        } => {
            if let Some(u) = u_start_m {
                v.push(("road.u_start_m".into(), Site::F(u)));
            }
            v.push(("road.v_offset_m".into(), Site::F(v_offset_m)));
        }
        Road::Texture {
            seed,
            length_m,
            width_m,
            min_wavenumber_cpm,
            max_wavenumber_cpm,
            ..
        } => {
            v.push(("road.seed".into(), Site::U64(seed)));
            v.push(("road.length_m".into(), Site::F(length_m)));
            v.push(("road.width_m".into(), Site::F(width_m)));
            v.push((
                "road.min_wavenumber_cpm".into(),
                Site::F(min_wavenumber_cpm),
            ));
            v.push((
                "road.max_wavenumber_cpm".into(),
                Site::F(max_wavenumber_cpm),
            ));
        }
    }
    if let Contact::Compliant { stiffness_n_m } = &mut s.contact {
        for (i, k) in stiffness_n_m.iter_mut().enumerate() {
            v.push((format!("contact.stiffness_n_m[{i}]"), Site::F(k)));
        }
    }
    v
}

/// Sets site `which` (modulo their number) to hostile value `value`
/// (an index into the hostile sets); returns the path and the value set.
fn mutate_number(s: &mut Scene, which: usize, value: usize) -> (String, String) {
    let mut all = sites(s);
    let n = all.len();
    let (path, site) = &mut all[which % n];
    let shown = match site {
        Site::F(x) => {
            **x = HOSTILE_F64[value % HOSTILE_F64.len()];
            format!("{:?}", **x)
        }
        Site::U(x) => {
            **x = HOSTILE_USIZE[value % HOSTILE_USIZE.len()];
            format!("{}", **x)
        }
        Site::OptU(x) => {
            **x = Some(HOSTILE_USIZE[value % HOSTILE_USIZE.len()]);
            format!("{:?}", **x)
        }
        Site::U64(x) => {
            **x = [0, 1, u64::MAX, u64::MAX - 1][value % 4];
            format!("{}", **x)
        }
    };
    (path.clone(), shown)
}

/// A list-length or structure mutation; returns the field(s) an error about
/// it may name.
fn mutate_structure(s: &mut Scene, kind: usize, k: usize, dir: &Path) -> Vec<String> {
    let p = s.points.len();
    let modes = match &mut s.tyre {
        Tyre::Modal { modes } => Some(modes),
        Tyre::Ring { .. } | Tyre::Measured { .. } | Tyre::Plate { .. } | Tyre::FeModes { .. } => {
            None
        }
    };
    match kind % 12 {
        // no modes
        0 => {
            if let Some(m) = modes {
                m.clear();
            } else {
                s.tyre = Tyre::Modal { modes: vec![] };
            }
            vec!["tyre.modes".into()]
        }
        // no points (a measured tyre's node list then has too many)
        1 => {
            s.points.clear();
            vec![
                "points".into(),
                "shape".into(),
                "residue".into(),
                "tyre.nodes".into(),
            ]
        }
        // 1000 points (distinct positions), shapes left as they are
        2 => {
            s.points = (0..1000)
                .map(|i| Point {
                    x_m: -0.05 + 1e-4 * i as f64,
                    y_m: 0.0,
                    h_m: -0.001,
                })
                .collect();
            vec![
                "points".into(),
                "shape".into(),
                "residue".into(),
                "tyre.nodes".into(),
            ]
        }
        // a residue matrix of the wrong size (one row or column too many or few)
        3 => {
            let n = match k % 4 {
                0 => (p + 1, p),
                1 => (p, p + 1),
                2 => (p.saturating_sub(1), p),
                _ => (p, p.saturating_sub(1)),
            };
            let bad = Mode {
                freq_hz: 120.0,
                damping_ratio: 0.05,
                residue: vec![vec![0.01; n.1]; n.0],
                shape: vec![],
            };
            match modes {
                Some(m) if !m.is_empty() => {
                    let i = k % m.len();
                    m[i] = bad;
                }
                Some(m) => m.push(bad),
                None => s.tyre = Tyre::Modal { modes: vec![bad] },
            }
            vec!["residue".into()]
        }
        // a ragged residue matrix
        4 => {
            let mut r = vec![vec![0.01; p]; p];
            if let Some(row) = r.get_mut(k % p.max(1)) {
                row.push(0.0);
            }
            let bad = Mode {
                freq_hz: 120.0,
                damping_ratio: 0.05,
                residue: r,
                shape: vec![],
            };
            s.tyre = Tyre::Modal { modes: vec![bad] };
            vec!["residue".into(), "points".into()]
        }
        // a shape of the wrong length
        5 => {
            let bad = Mode {
                freq_hz: 120.0,
                damping_ratio: 0.05,
                residue: vec![],
                shape: vec![0.1; [0, p + 1, 2 * p + 3][k % 3]],
            };
            s.tyre = Tyre::Modal { modes: vec![bad] };
            vec!["shape".into(), "points".into()]
        }
        // both residue and shape, or neither
        6 => {
            let bad = Mode {
                freq_hz: 120.0,
                damping_ratio: 0.05,
                residue: if k.is_multiple_of(2) {
                    vec![vec![0.01; p]; p]
                } else {
                    vec![]
                },
                shape: if k.is_multiple_of(2) {
                    vec![0.1; p]
                } else {
                    vec![]
                },
            };
            s.tyre = Tyre::Modal { modes: vec![bad] };
            vec!["shape".into(), "residue".into(), "points".into()]
        }
        // duplicate point positions
        7 => {
            if p >= 2 {
                let (i, j) = (k % p, (k / p + 1 + k % p) % p);
                if i != j {
                    let x_m = s.points[i].x_m;
                    s.points[j].x_m = x_m;
                }
            } else if p == 1 {
                let first = s.points[0];
                s.points.push(first);
            }
            vec![
                "x_m".into(),
                "points".into(),
                "shape".into(),
                "residue".into(),
            ]
        }
        // a measured road whose samples are unsorted, duplicated, too few,
        // non-numeric or non-finite
        8 => {
            let texts = [
                "x_m,z_m\n0,0\n2,0.001\n1,0\n3,0\n",
                "0,0\n1,0\n1,0.001\n2,0\n",
                "0,0\n",
                "",
                "x_m,z_m\n",
                "0,0\n1,nan\n2,0\n",
                "0,0\n1,inf\n2,0\n",
                "0,0\n1e300,0\n",
                "a,b\nc,d\n",
                "0;0\n1;0\n",
                "3,0\n2,0\n1,0\n0,0\n",
                "0,0,0\n1,0,0\n",
            ];
            let t = texts[k % texts.len()];
            let file = dir.join(format!("road_{}.csv", k % texts.len()));
            std::fs::write(&file, t).unwrap();
            s.road = Road::Measured {
                file,
                looped: k.is_multiple_of(2),
            };
            vec!["road".into(), "ramp_s".into()]
        }
        // a measured road that does not exist, or is a folder
        9 => {
            let file = if k.is_multiple_of(3) {
                dir.join("no such dir/ünïcode road.csv")
            } else if k % 3 == 1 {
                dir.to_path_buf()
            } else {
                PathBuf::new()
            };
            s.road = Road::Measured {
                file,
                looped: false,
            };
            vec!["road".into()]
        }
        // no harmonics, or one hostile harmonic
        10 => {
            s.road = Road::Harmonics {
                components: if k.is_multiple_of(2) {
                    vec![]
                } else {
                    vec![Harmonic {
                        amplitude_m: 0.001,
                        wavelength_m: HOSTILE_F64[k % HOSTILE_F64.len()],
                        phase_rad: 0.0,
                    }]
                },
            };
            vec!["road".into(), "ramp_s".into()]
        }
        // compliant contact with a stiffness list of the wrong length
        _ => {
            s.contact = Contact::Compliant {
                stiffness_n_m: vec![1e6; [0, p + 1, 2 * p + 2][k % 3]],
            };
            vec!["contact.stiffness_n_m".into()]
        }
    }
}

/// Fields checked against one another: an error about a coupled field is a
/// fair answer to a change of this one.
fn coupled(path: &str) -> Vec<String> {
    let leaf = path.rsplit('.').next().unwrap_or(path).to_string();
    let mut v = vec![path.to_string(), leaf];
    if path.starts_with("points") || path.starts_with("road") {
        // a point lowered or a road raised may start below the road at t = 0
        v.push("ramp_s".into());
    }
    if path.starts_with("road.") {
        v.push("road.".into());
    }
    if path.starts_with("tyre.identification") {
        v.push("tyre.identification".into());
    }
    if path.starts_with("tyre.ring") {
        v.push("tyre.ring".into());
    }
    match path {
        "dt_s" => v.push("duration_s".into()),
        "duration_s" => v.push("dt_s".into()),
        _ => {}
    }
    v
}

/// Runs a valid scene for at most 200 steps; any error is fine, a panic is not.
fn run_200(scene: &Scene) -> Result<(), String> {
    let mut sim = Simulation::from_scene(scene).map_err(|e| {
        let m = e.to_string();
        assert!(!m.trim().is_empty(), "empty error from Simulation::new");
        m
    })?;
    for _ in 0..200 {
        if sim.finished() {
            break;
        }
        if let Err(e) = sim.step() {
            assert!(!e.to_string().trim().is_empty());
            break;
        }
    }
    Ok(())
}

/// Validates the scene directly and through its RON text (the hostile value
/// written as RON and read back); both must agree, and an error must name
/// one of `names`.
fn check(scene: &Scene, names: &[String], what: &str) -> Result<(), TestCaseError> {
    let direct = scene.validate();
    let text = scene.to_ron_string();
    let parsed = Scene::parse(&text, "mutated.ron");
    match (&direct, &parsed) {
        (Ok(()), Ok(_)) => {
            let _ = run_200(scene);
        }
        (Err(errors), Err(SceneError::Invalid { errors: e2, .. })) => {
            prop_assert!(!errors.is_empty());
            prop_assert_eq!(errors.len(), e2.len(), "{}\n{}", what, text);
            let shown = parsed.as_ref().unwrap_err().to_string();
            prop_assert!(
                names.iter().any(|n| shown.contains(n.as_str())),
                "{what}: error does not name any of {names:?}:\n{shown}"
            );
            for e in errors {
                prop_assert!(!e.field.is_empty() && !e.value.is_empty() && !e.expected.is_empty());
            }
        }
        (_, Err(SceneError::Syntax { .. })) => {
            prop_assert!(
                false,
                "{what}: the scene's own RON text does not read back: {}\n{text}",
                parsed.as_ref().unwrap_err()
            );
        }
        _ => prop_assert!(
            false,
            "{what}: validation {direct:?} but RON round trip {parsed:?}"
        ),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { cases: proptest_cases(300), ..ProptestConfig::default() })]

    /// One or two numeric fields set to hostile values.
    #[test]
    fn hostile_numbers(which in 0usize..13, site in 0usize..1000, value in 0usize..64,
                       site2 in proptest::option::of((0usize..1000, 0usize..64))) {
        let mut all = parsed_presets();
        let mut scene = all.swap_remove(which % all.len());
        let (path, shown) = mutate_number(&mut scene, site, value);
        let mut names = coupled(&path);
        let mut what = format!("{} = {shown}", path);
        if let Some((s2, v2)) = site2 {
            let (p2, sh2) = mutate_number(&mut scene, s2, v2);
            names.extend(coupled(&p2));
            what = format!("{what}, {p2} = {sh2}");
        }
        check(&scene, &names, &what)?;
    }

    /// Lists of the wrong length, duplicated points, broken road files.
    #[test]
    fn hostile_structure(which in 0usize..13, kind in 0usize..12, k in 0usize..1000) {
        let dir = temp_dir();
        let mut all = parsed_presets();
        let mut scene = all.swap_remove(which % all.len());
        let names = mutate_structure(&mut scene, kind, k, dir.path());
        let what = format!("preset {which}, structure mutation {kind}/{k}");
        check(&scene, &names, &what)?;
    }
}

/// A byte-level corruption of a text: flip, insert, delete, duplicate, swap.
fn corrupt(text: &[u8], ops: &[(u8, usize, u8)]) -> Vec<u8> {
    let mut b = text.to_vec();
    for &(op, pos, byte) in ops {
        let n = b.len();
        let p = if n == 0 { 0 } else { pos % n };
        match op % 6 {
            0 if n > 0 => b[p] = byte,
            1 => b.insert(p.min(n), byte),
            2 if n > 0 => {
                b.remove(p);
            }
            3 if n > 0 => b[p] ^= 1 << (byte % 8),
            4 if n > 0 => {
                let end = (p + 1 + byte as usize % 40).min(n);
                let chunk = b[p..end].to_vec();
                b.splice(p..p, chunk);
            }
            5 if n > 0 => b.truncate(p),
            _ => {}
        }
    }
    b
}

proptest! {
    #![proptest_config(ProptestConfig { cases: proptest_cases(400), ..ProptestConfig::default() })]

    /// Corrupted preset text: parsing returns a scene, or an error with a line
    /// and column inside the text (syntax) or naming fields (values); loading
    /// the same bytes from a file does the same, invalid UTF-8 included.
    #[test]
    fn corrupted_bytes(which in 0usize..13, ops in proptest::collection::vec((any::<u8>(), any::<usize>(), any::<u8>()), 1..6)) {
        let all = presets();
        let (name, text) = &all[which % all.len()];
        let bytes = corrupt(text.as_bytes(), &ops);
        let dir = temp_dir();
        let file = dir.path().join("corrupt.ron");
        std::fs::write(&file, &bytes).unwrap();
        let loaded = Scene::load(&file);
        let lossy = String::from_utf8_lossy(&bytes);
        let parsed = Scene::parse(&lossy, name);
        for r in [&parsed, &loaded] {
            match r {
                Ok(scene) => {
                    let mut s = scene.clone();
                    s.base_dir = Some(PathBuf::from("presets"));
                    let _ = run_200(&s);
                }
                Err(SceneError::Syntax { line, col, message, .. }) => {
                    let lines = lossy.lines().count().max(1);
                    prop_assert!(*line >= 1 && *line <= lines + 1, "line {line} of {lines}");
                    prop_assert!(*col >= 1);
                    prop_assert!(!message.is_empty());
                    let shown = r.as_ref().unwrap_err().to_string();
                    prop_assert!(shown.contains(&format!(":{line}:{col}:")), "{shown}");
                }
                Err(SceneError::Invalid { errors, .. }) => prop_assert!(!errors.is_empty()),
                Err(e) => prop_assert!(
                    false,
                    "a corrupted preset gave an error with no line and column: {e}"
                ),
            }
        }
    }
}
