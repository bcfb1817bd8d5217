//! Displacement coordinate systems (dataset 2420) and normal modes written
//! as complex data: the same modes written in the part system as real data
//! and in per-node rotated systems as complex data with zero imaginary
//! parts read the same; refusals by record, line and reason.

use super::uff_shapes::{self, FeFile};
use super::{FeAxes, FeAxis, FeDamping, FeModesError, FeModesSpec, FeNodes, FeShapeUnits};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::PathBuf;

type M3 = [[f64; 3]; 3];

/// Rotation by `deg` degrees about axis `a` (0 X, 1 Y, 2 Z): the rotated
/// system's X, Y, Z axes in the part system, as rows.
fn about(a: usize, deg: f64) -> M3 {
    let (s, c) = deg.to_radians().sin_cos();
    let (i, j) = ((a + 1) % 3, (a + 2) % 3);
    let mut r = [[0.0; 3]; 3];
    r[a][a] = 1.0;
    // axis i turns towards j
    r[i][i] = c;
    r[i][j] = s;
    r[j][i] = -s;
    r[j][j] = c;
    r
}

/// The system `b` given in the system `a` (rows of `b` combined over `a`'s).
fn then(a: M3, b: M3) -> M3 {
    std::array::from_fn(|i| std::array::from_fn(|c| (0..3).map(|k| b[i][k] * a[k][c]).sum()))
}

/// Components of the part-system vector `u` along the rows of `r`.
fn local(r: &M3, u: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| (0..3).map(|c| r[i][c] * u[c]).sum())
}

/// The fixtures' systems: label, kind (0 Cartesian, 1 cylindrical, 2
/// spherical), axes as rows, origin (mm).
struct System {
    label: i64,
    kind: i64,
    axes: M3,
    origin: [f64; 3],
}

/// The known rotations of the Cartesian fixture, one per node (label 0:
/// the part system).
fn cartesian_systems() -> Vec<System> {
    let sys = |label, axes, origin| System {
        label,
        kind: 0,
        axes,
        origin,
    };
    vec![
        sys(11, about(2, 30.0), [0.0; 3]),
        sys(12, about(0, 45.0), [0.0; 3]),
        sys(13, about(1, -60.0), [0.0; 3]),
        // Z 20°, then Y 35°, then X -50° about the turned axes
        sys(
            14,
            then(then(about(2, 20.0), about(1, 35.0)), about(0, -50.0)),
            [0.0; 3],
        ),
        // a quarter turn about Z with its origin away from the part's
        sys(15, about(2, 90.0), [100.0, -50.0, 20.0]),
        sys(16, about(0, 180.0), [0.0; 3]),
    ]
}

/// Node label, position (mm), displacement system.
type Node = (i64, [f64; 3], i64);

/// The fixtures' nodes: 7 nodes of a plate, z = 0, in systems 11..16 and
/// the part system.
fn plate_nodes() -> Vec<Node> {
    (0..7)
        .map(|i| {
            let x = (i as f64 - 3.0) * 10.0;
            let y = ((i % 3) as f64 - 1.0) * 30.0;
            (
                101 + i as i64,
                [x, y, 0.0],
                if i < 6 { 11 + i as i64 } else { 0 },
            )
        })
        .collect()
}

/// The fixtures' four modes in the part system: frequency (Hz) of mode
/// `k`.
fn freq_hz(k: usize) -> f64 {
    60.0 + 45.0 * k as f64
}

/// The translations of mode `k` at node index `i`, all three non-zero.
fn shape(k: usize, i: usize) -> [f64; 3] {
    let a = 0.7 * (k + 1) as f64 + 0.3 * i as f64;
    [0.2 * a.sin(), 0.3 * (1.3 * a).cos(), (0.9 * a).sin() + 0.1]
}

fn e(x: f64) -> String {
    format!("{x:25.16E}")
}

/// A UFF file: units mm/mN (164), `systems` (2420, none when empty),
/// `nodes` (2411), `modes` (2414, data type 4, or 5 with imaginary parts
/// `imag(k, i, c)`), each node's translations given in its displacement
/// system (`disp` of the node) when `in_systems`, else in the part system.
fn uff(
    systems: &[System],
    nodes: &[Node],
    in_systems: bool,
    complex: Option<&dyn Fn(usize, usize, usize) -> f64>,
) -> String {
    let mut s = String::new();
    let open = |s: &mut String, n: u32| {
        writeln!(s, "{:>6}\n{:>6}{:74}", -1, n, "").unwrap();
    };
    let close = |s: &mut String| writeln!(s, "{:>6}", -1).unwrap();
    open(&mut s, 164);
    writeln!(s, "{:>10}{:>20}{:>10}", 5, "mm mN kg", 2).unwrap();
    writeln!(s, "{}{}{}\n{}", e(1000.0), e(1000.0), e(1.0), e(273.15)).unwrap();
    close(&mut s);
    if !systems.is_empty() {
        open(&mut s, 2420);
        writeln!(s, "{:>10}\nfixture part", 1).unwrap();
        for cs in systems {
            writeln!(
                s,
                "{:>10}{:>10}{:>10}\nCS{}",
                cs.label, cs.kind, 8, cs.label
            )
            .unwrap();
            for r in cs.axes.iter().chain([&cs.origin]) {
                writeln!(s, "{}{}{}", e(r[0]), e(r[1]), e(r[2])).unwrap();
            }
        }
        close(&mut s);
    }
    open(&mut s, 2411);
    for (n, p, disp) in nodes {
        let disp = if in_systems { *disp } else { 0 };
        writeln!(s, "{n:>10}{:>10}{disp:>10}{:>10}", 0, 8).unwrap();
        writeln!(s, "{}{}{}", e(p[0]), e(p[1]), e(p[2])).unwrap();
    }
    close(&mut s);
    let by_label: BTreeMap<i64, &System> = systems.iter().map(|c| (c.label, c)).collect();
    for k in 0..4 {
        let f = &freq_hz(k);
        open(&mut s, 2414);
        let data_type = if complex.is_some() { 5 } else { 4 };
        writeln!(s, "{:>10}\nmode {}\n{:>10}", k + 1, k + 1, 1).unwrap();
        for _ in 0..5 {
            writeln!(s, "NONE").unwrap();
        }
        writeln!(
            s,
            "{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
            1, 2, 2, 8, data_type, 3
        )
        .unwrap();
        writeln!(
            s,
            "{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
            1,
            0,
            0,
            0,
            0,
            k + 1,
            0,
            0
        )
        .unwrap();
        writeln!(s, "{:>10}{:>10}", 0, 0).unwrap();
        let w = std::f64::consts::TAU * f;
        writeln!(
            s,
            "{}{}{}{}{}{}",
            e(0.0),
            e(*f),
            e(w * w),
            e(1.0),
            e(0.0),
            e(0.0)
        )
        .unwrap();
        writeln!(
            s,
            "{}{}{}{}{}{}",
            e(0.0),
            e(0.0),
            e(0.0),
            e(0.0),
            e(0.0),
            e(0.0)
        )
        .unwrap();
        for (i, (n, p, disp)) in nodes.iter().enumerate() {
            let u = shape(k, i);
            let v = match by_label.get(disp) {
                Some(cs) if in_systems => {
                    let l = local(&cs.axes, u);
                    if cs.kind == 1 {
                        // radial, tangential, axial at the node
                        let q: [f64; 3] = std::array::from_fn(|j| {
                            (0..3).map(|c| cs.axes[j][c] * (p[c] - cs.origin[c])).sum()
                        });
                        let r = q[0].hypot(q[1]);
                        let (c, sn) = (q[0] / r, q[1] / r);
                        [c * l[0] + sn * l[1], -sn * l[0] + c * l[1], l[2]]
                    } else {
                        l
                    }
                }
                _ => u,
            };
            writeln!(s, "{n:>10}").unwrap();
            match complex {
                Some(im) => writeln!(
                    s,
                    "{}{}{}{}{}{}",
                    e(v[0]),
                    e(im(k, i, 0)),
                    e(v[1]),
                    e(im(k, i, 1)),
                    e(v[2]),
                    e(im(k, i, 2))
                )
                .unwrap(),
                None => writeln!(s, "{}{}{}", e(v[0]), e(v[1]), e(v[2])).unwrap(),
            }
        }
        close(&mut s);
    }
    s
}

fn read(text: &str) -> Result<FeFile, uff_shapes::UffShapesError> {
    uff_shapes::read(text.as_bytes())
}

/// Largest difference of two files' shapes, and their largest value.
fn difference(a: &FeFile, b: &FeFile) -> (f64, f64) {
    assert_eq!(a.modes.len(), b.modes.len());
    let (mut d, mut big) = (0.0f64, 0.0f64);
    for (ma, mb) in a.modes.iter().zip(&b.modes) {
        assert_eq!(ma.mode_number, mb.mode_number);
        assert_eq!(
            ma.shape.keys().collect::<Vec<_>>(),
            mb.shape.keys().collect::<Vec<_>>()
        );
        for (n, ua) in &ma.shape {
            for c in 0..3 {
                d = d.max((ua[c] - mb.shape[n][c]).abs());
                big = big.max(ua[c].abs());
            }
        }
    }
    (d, big)
}

#[test]
fn rotated_cartesian_systems_and_complex_data_read_as_the_part_system() {
    let systems = cartesian_systems();
    let nodes = plate_nodes();
    let zero = |_: usize, _: usize, _: usize| 0.0;
    let global = read(&uff(&[], &nodes, false, None)).unwrap();
    let turned = read(&uff(&systems, &nodes, true, Some(&zero))).unwrap();
    assert_eq!(global.complex_modes, 0);
    assert_eq!(turned.complex_modes, 4);
    assert_eq!(turned.largest_imaginary_ratio, 0.0);
    assert_eq!(turned.turned.cartesian, 6);
    assert_eq!(turned.coordinate_systems.len(), 6);
    let (d, big) = difference(&global, &turned);
    assert!(big > 0.5, "{big}");
    assert!(d <= 1e-15 * big, "largest difference {d:e} of {big}");
    // read without their systems, the local components are far from the
    // part ones: the comparison above would see a dropped system
    let mut dropped = uff(&systems, &nodes, true, Some(&zero));
    for (n, _, disp) in &nodes {
        dropped = dropped.replace(
            &format!("{n:>10}{:>10}{disp:>10}{:>10}", 0, 8),
            &format!("{n:>10}{:>10}{:>10}{:>10}", 0, 0, 8),
        );
    }
    let (d_dropped, _) = difference(&global, &read(&dropped).unwrap());
    assert!(d_dropped > 0.5 * big, "{d_dropped}");
    println!(
        "rotated Cartesian systems: largest difference {d:e} of largest value {big}; {d_dropped} with the systems dropped"
    );

    // the modal models built along each axis agree
    let (ge, te) = (fe_model_all(&global), fe_model_all(&turned));
    for (a, b) in ge.iter().zip(&te) {
        for (ma, mb) in a.modes.iter().zip(&b.modes) {
            for (x, y) in ma.shape.iter().zip(&mb.shape) {
                assert!((x - y).abs() <= 1e-15 * big, "{x} {y}");
            }
        }
        assert!(
            b.notes
                .iter()
                .any(|n| n.contains("displacements of 6 nodes turned")),
            "{:?}",
            b.notes
        );
        assert!(
            b.notes
                .iter()
                .any(|n| n.contains("4 modes written as complex"))
        );
        assert_eq!(
            b.datasets_read,
            vec![
                ("dataset 164 (units)".to_string(), 1),
                ("dataset 2420 (coordinate systems)".to_string(), 1),
                ("dataset 2411 (node coordinates)".to_string(), 1),
                ("dataset 2414 (normal mode shapes)".to_string(), 4),
            ]
        );
    }
}

/// The modal models of every node along X, Y and Z.
fn fe_model_all(fe: &FeFile) -> Vec<super::FeModel> {
    let nodes: Vec<i64> = fe.nodes.keys().copied().collect();
    let points: Vec<(f64, f64)> = nodes.iter().map(|_| (0.0, 0.0)).collect();
    [FeAxis::X, FeAxis::Y, FeAxis::Z]
        .into_iter()
        .map(|direction| {
            let (along, across) = match direction {
                FeAxis::X => (FeAxis::Y, FeAxis::Z),
                FeAxis::Y => (FeAxis::Z, FeAxis::X),
                FeAxis::Z => (FeAxis::X, FeAxis::Y),
            };
            let spec = spec(
                FeNodes::List(nodes.clone()),
                direction,
                FeAxes { along, across },
            );
            super::build(&spec, fe, &points).unwrap()
        })
        .collect()
}

fn spec(nodes: FeNodes, direction: FeAxis, axes: FeAxes) -> FeModesSpec {
    FeModesSpec {
        file: PathBuf::from("fixture.unv"),
        nodes,
        direction,
        axes,
        damping: FeDamping::Ratio(0.02),
        modal_mass_kg: Vec::new(),
        band_hz: super::ALL_MODES_HZ,
        nearest_within_m: super::DEFAULT_NEAREST_WITHIN_M,
        shape_units: FeShapeUnits::Consistent,
    }
}

/// Nodes on a tread circle of radius 300 mm about the Y axis (the axle),
/// shapes given in a cylindrical system about it: radial, tangential,
/// axial.
#[test]
fn cylindrical_system_reads_as_the_part_system() {
    // its Z axis along the part's Y, its X along the part's Z
    let axle = System {
        label: 7,
        kind: 1,
        axes: [[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        origin: [5.0, 0.0, 310.0],
    };
    let nodes: Vec<Node> = (0..8)
        .map(|i| {
            let t = (200.0 + 10.0 * i as f64).to_radians();
            let y = (i % 3) as f64 * 20.0 - 20.0;
            (
                201 + i as i64,
                [5.0 + 300.0 * t.sin(), y, 310.0 + 300.0 * t.cos()],
                7,
            )
        })
        .collect();
    let global = read(&uff(&[], &nodes, false, None)).unwrap();
    let turned = read(&uff(&[axle], &nodes, true, None)).unwrap();
    assert_eq!(turned.turned.cylindrical, 8);
    let (d, big) = difference(&global, &turned);
    assert!(d <= 1e-14 * big, "largest difference {d:e} of {big}");
    println!("cylindrical system: largest difference {d:e} of largest value {big}");
}

#[test]
fn spherical_and_on_axis_refused_by_name() {
    let ball = System {
        label: 9,
        kind: 2,
        axes: about(2, 10.0),
        origin: [0.0; 3],
    };
    let nodes = vec![(301, [10.0, 20.0, 30.0], 9)];
    let e = read(&uff(&[ball], &nodes, true, None))
        .unwrap_err()
        .to_string();
    assert!(e.contains("dataset 2411") && e.contains("node 301"), "{e}");
    assert!(
        e.contains("coordinate system 9 (`CS9`) is spherical"),
        "{e}"
    );
    let axle = System {
        label: 7,
        kind: 1,
        axes: about(0, 0.0),
        origin: [0.0; 3],
    };
    let nodes = vec![(302, [0.0, 0.0, 30.0], 7)];
    // (the writer cannot give radial components on the axis: write them
    // in the part system and name the system)
    let text = uff(&[axle], &nodes, false, None).replace(
        &format!("{:>10}{:>10}{:>10}{:>10}", 302, 0, 0, 8),
        &format!("{:>10}{:>10}{:>10}{:>10}", 302, 0, 7, 8),
    );
    let e = read(&text).unwrap_err().to_string();
    assert!(e.contains("node 302: lies on the axis"), "{e}");
}

#[test]
fn undefined_system_refused_naming_node_and_system() {
    let systems = cartesian_systems();
    let nodes = plate_nodes();
    // node 105 names system 15; the file defines 11..14 and 16
    let kept: Vec<System> = systems.into_iter().filter(|c| c.label != 15).collect();
    let e = read(&uff(&kept, &nodes, true, None))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("(dataset 2411, line")
            && e.contains("node 105: displacement coordinate system 15 is not defined")
            && e.contains("the file defines 5: 11, 12, 13, 14, 16"),
        "{e}"
    );
}

#[test]
fn complex_shapes_refused_naming_the_mode_and_ratio() {
    let nodes = plate_nodes();
    // 1e-9 of the real parts: accepted; 3 % in mode 3: refused
    let tiny = |_: usize, _: usize, _: usize| 1e-10;
    let ok = read(&uff(&[], &nodes, false, Some(&tiny))).unwrap();
    assert_eq!(ok.complex_modes, 4);
    assert!(ok.largest_imaginary_ratio > 0.0 && ok.largest_imaginary_ratio < 1e-9);
    let damped = |k: usize, i: usize, _: usize| if k == 2 && i == 4 { 0.03 } else { 0.0 };
    let e = read(&uff(&[], &nodes, false, Some(&damped)))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("(dataset 2414, line")
            && e.contains("mode 3: complex shape with imaginary parts up to 3.000e-2")
            && e.contains("expected at most 1e-6"),
        "{e}"
    );
}

#[test]
fn truncated_and_bad_2420_refused_with_file_line_and_reason() {
    let systems = cartesian_systems();
    let nodes = plate_nodes();
    let text = uff(&systems, &nodes, true, None);
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| l.trim() == "2420").unwrap();
    let end = start
        + lines[start..]
            .iter()
            .position(|l| l.trim() == "-1")
            .unwrap();
    let dir = tempfile::tempdir().unwrap();
    // every cut inside the dataset: refused, by file and line, no panic
    for cut in start + 1..end {
        let mut t: Vec<&str> = lines[..cut].to_vec();
        t.extend_from_slice(&lines[end..]);
        let path = dir.path().join("cut.unv");
        std::fs::write(&path, t.join("\n") + "\n").unwrap();
        let mut sp = spec(FeNodes::List(vec![101]), FeAxis::Z, FeAxes::default());
        sp.file = path.clone();
        match super::load(&sp, &[(0.0, 0.0)]) {
            Err(FeModesError::Parse { file, source }) => {
                let m = source.to_string();
                assert!(file.ends_with("cut.unv"), "{file}");
                assert!(
                    m.contains("dataset 2") && m.contains("line"),
                    "cut {cut}: {m}"
                );
            }
            other => panic!("cut at line {cut}: {other:?}"),
        }
    }
    // a type out of range, a matrix not orthonormal, a row of two numbers
    let bad_type = text.replacen(
        &format!("{:>10}{:>10}{:>10}", 12, 0, 8),
        &format!("{:>10}{:>10}{:>10}", 12, 4, 8),
        1,
    );
    let e = read(&bad_type).unwrap_err().to_string();
    assert!(e.contains("coordinate system 12: type 4"), "{e}");
    let row = lines[start + 5];
    let skew = text.replacen(row, &format!("{}{}{}", e_(2.0), e_(0.0), e_(0.0)), 1);
    let e = read(&skew).unwrap_err().to_string();
    assert!(
        e.contains(&format!("line {}", start + 6)) && e.contains("orthonormal"),
        "{e}"
    );
    let short = text.replacen(row, &row[..50], 1);
    let e = read(&short).unwrap_err().to_string();
    assert!(
        e.contains(&format!("line {}", start + 6)) && e.contains("record 5"),
        "{e}"
    );
}

fn e_(x: f64) -> String {
    e(x)
}

/// Dataset 55 written as complex data (type 5, real and imaginary parts
/// per value, six values per node) reads as the same record written as
/// real data (type 2).
#[test]
fn dataset_55_complex_reads_as_real() {
    let record = |data_type: i64| {
        let mut s = String::new();
        writeln!(s, "{:>6}\n{:>6}", -1, 55).unwrap();
        for _ in 0..5 {
            writeln!(s, "NONE").unwrap();
        }
        writeln!(
            s,
            "{:>10}{:>10}{:>10}{:>10}{:>10}{:>10}",
            1, 2, 3, 8, data_type, 6
        )
        .unwrap();
        writeln!(s, "{:>10}{:>10}{:>10}{:>10}", 2, 4, 1, 7).unwrap();
        writeln!(s, "{:13.5E}{:13.5E}{:13.5E}{:13.5E}", 88.5, 1.0, 0.01, 0.0).unwrap();
        for (n, v) in [(1, [0.1, -0.2, 0.3]), (2, [-0.4, 0.5, 0.6])] {
            writeln!(s, "{n:>10}").unwrap();
            let mut vals: Vec<f64> = v.to_vec();
            vals.extend([0.01, 0.02, 0.03]);
            for x in vals {
                if data_type == 5 {
                    write!(s, "{:13.5E}{:13.5E}", x, 0.0).unwrap();
                } else {
                    write!(s, "{x:13.5E}").unwrap();
                }
            }
            writeln!(s).unwrap();
        }
        writeln!(s, "{:>6}", -1).unwrap();
        s
    };
    let real = read(&record(2)).unwrap();
    let complex = read(&record(5)).unwrap();
    assert_eq!(real.modes, complex.modes);
    assert_eq!(complex.modes[0].shape[&2], [-0.4, 0.5, 0.6]);
    assert_eq!((real.complex_modes, complex.complex_modes), (0, 1));
}

/// Any line of a 2420 dataset replaced by something malformed: the file is
/// read or refused with a line and a reason, never a panic.
#[test]
fn malformed_2420_lines_never_panic() {
    let text = uff(&cartesian_systems(), &plate_nodes(), true, None);
    let lines: Vec<&str> = text.lines().collect();
    let start = lines.iter().position(|l| l.trim() == "2420").unwrap();
    let end = start
        + lines[start..]
            .iter()
            .position(|l| l.trim() == "-1")
            .unwrap();
    let junk = [
        "",
        "x",
        "        11",
        "  1.0E+00  NaN  0.0",
        "  1.0E+999  0.0  0.0",
        "        11         1         8",
        "        11         2         8",
        " -9223372036854775808 0 8",
        "  1.0D+00  0.0D+00",
    ];
    for at in start + 1..end {
        for j in junk {
            let mut v = lines.clone();
            v[at] = j;
            match read(&(v.join("\n") + "\n")) {
                Ok(_) => {}
                Err(e) => {
                    let m = e.to_string();
                    assert!(m.contains("line "), "line {}, `{j}`: {m}", at + 1);
                }
            }
        }
    }
}

/// Dataset 15 gives coordinates in the node's definition system: turned
/// to the part system when it is Cartesian.
#[test]
fn dataset_15_coordinates_in_a_definition_system() {
    let systems: Vec<System> = cartesian_systems()
        .into_iter()
        .filter(|c| c.label == 15)
        .collect();
    let mut text = uff(&systems, &[], false, None);
    text.push_str(&format!(
        "{:>6}\n{:>6}\n{:>10}{:>10}{:>10}{:>10}{:13.5E}{:13.5E}{:13.5E}\n{:>6}\n",
        -1, 15, 1, 15, 0, 8, 1.0, 2.0, 3.0, -1
    ));
    let fe = read(&text).unwrap();
    // origin (100, -50, 20) mm, X along the part's Y, Y along -X
    let p = fe.nodes[&1];
    for (got, want) in p.iter().zip([98.0, -49.0, 23.0]) {
        assert!((got - want).abs() < 1e-12, "{p:?}");
    }
    assert_eq!(fe.turned.coordinates, 1);
}
