//! Tests of the UFF reader: ASCII and binary datasets 58 (both byte
//! orders), units, refusals naming the record and line.

use super::*;
use crate::readers::measured::Series;

/// How a test dataset 58 is written: ASCII, or binary with a byte
/// order (1 little, 2 big endian).
#[derive(Clone, Copy)]
enum Form {
    Ascii,
    Binary { order: i64 },
}

/// A dataset 58 in the standard layout, values `vals` (real, or real
/// and imaginary in turn), units labels `units` (numerator,
/// denominator), denominator specific data type `den`.
#[allow(clippy::too_many_arguments)]
fn dataset_with(
    func: i64,
    (resp, refn): (i64, i64),
    ord: i64,
    (min, step): (f64, f64),
    (num, den): (i64, i64),
    units: (&str, &str),
    vals: &[f64],
    form: Form,
) -> Vec<u8> {
    let complex = matches!(ord, 5 | 6);
    let count = if complex { vals.len() / 2 } else { vals.len() };
    let size = if matches!(ord, 2 | 5) { 4 } else { 8 };
    let mut s = String::from("    -1\n");
    match form {
        Form::Ascii => s.push_str("    58\n"),
        // the ID line's byte count as pyuff writes it (values, not
        // components): the reader must not need it
        Form::Binary { order } => s.push_str(&format!(
            "{:>6}b{order:>6}{:>6}{:>12}{:>12}{:>6}{:>6}{:>12}{:>12}\n",
            58,
            2,
            11,
            count * size,
            0,
            0,
            0,
            0
        )),
    }
    for k in 1..=5 {
        s.push_str(&format!("ID line {k}\n"));
    }
    s.push_str(&format!(
        "{func:>5}{:>10}{:>5}{:>10} {:<10}{resp:>10}{:>4} {:<10}{refn:>10}{:>4}\n",
        1, 0, 0, "TYRE", 3, "TYRE", 3
    ));
    s.push_str(&format!(
        "{ord:>10}{count:>10}{:>10}{min:>13.5E}{step:>13.5E}{:>13.5E}\n",
        1, 0.0
    ));
    s.push_str(&format!(
        "{:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
        18, 0, 0, 0, "Time", "s"
    ));
    s.push_str(&format!(
        "{num:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
        1, 0, 0, "Response", units.0
    ));
    s.push_str(&format!(
        "{den:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
        0, 1, 0, "Force", units.1
    ));
    s.push_str(&format!(
        "{:>10}{:>5}{:>5}{:>5} {:<20} {:<20}\n",
        0, 0, 0, 0, "NONE", "NONE"
    ));
    let mut b = s.into_bytes();
    match form {
        Form::Ascii => {
            for chunk in vals.chunks(4) {
                for v in chunk {
                    b.extend(format!("{v:>20.12E}").bytes());
                }
                b.push(b'\n');
            }
        }
        Form::Binary { order } => {
            for v in vals {
                // little endian, then byte-swapped for big endian
                let mut w = if size == 4 {
                    (*v as f32).to_le_bytes().to_vec()
                } else {
                    v.to_le_bytes().to_vec()
                };
                if order == 2 {
                    w.reverse();
                }
                b.extend(w);
            }
        }
    }
    b.extend(b"    -1\n");
    b
}

/// A displacement-over-force dataset 58 in SI.
#[allow(clippy::too_many_arguments)]
pub fn dataset(
    func: i64,
    resp: i64,
    refn: i64,
    ord: i64,
    min: f64,
    step: f64,
    num: i64,
    vals: &[f64],
) -> String {
    String::from_utf8(dataset_with(
        func,
        (resp, refn),
        ord,
        (min, step),
        (num, 13),
        (
            match num {
                11 => "m/s",
                12 => "m/s^2",
                _ => "m",
            },
            "N",
        ),
        vals,
        Form::Ascii,
    ))
    .unwrap()
}

/// Values with every byte pattern's hazards: signs, magnitudes from
/// 1e-30 to 1e30, and bytes 0x0A (`\n`) and 0x0D (`\r`) inside the
/// binary numbers.
fn awkward_values(n: usize) -> Vec<f64> {
    (0..n)
        .map(|k| {
            let e = (k as i32 % 61) - 30;
            let v = (1.0 + 0.37 * k as f64).sin() * 10f64.powi(e);
            if k % 7 == 3 {
                f64::from_le_bytes([0x0A, 0x0D, 0x0A, 0x0A, 0x0D, 0x0A, 0xF0, 0x3F])
            } else {
                v
            }
        })
        .collect()
}

#[test]
fn binary_58b_reads_in_both_byte_orders_and_value_sizes() {
    let vals = awkward_values(2 * 67);
    for ord in [5, 6, 2, 4] {
        for order in [1, 2] {
            let bin = dataset_with(
                4,
                (101, 102),
                ord,
                (0.0, 0.5),
                (8, 13),
                ("m", "N"),
                &vals,
                Form::Binary { order },
            );
            // a binary record between ASCII ones
            let asc = dataset_with(
                4,
                (102, 102),
                6,
                (0.0, 0.5),
                (8, 13),
                ("m", "N"),
                &vals[..8],
                Form::Ascii,
            );
            let mut file = asc.clone();
            file.extend(&bin);
            file.extend(&asc);
            let r = records(&file).unwrap_or_else(|e| panic!("{ord} {order}: {e:?}"));
            assert_eq!(r.len(), 3);
            assert!(r[1].binary && !r[0].binary && !r[2].binary);
            assert_eq!((r[1].response_node, r[1].record), (101, 2));
            let got: Vec<f64> = if matches!(ord, 5 | 6) {
                r[1].re
                    .iter()
                    .zip(&r[1].im)
                    .flat_map(|(a, b)| [*a, *b])
                    .collect()
            } else {
                r[1].re.clone()
            };
            assert_eq!(got.len(), vals.len());
            for (g, v) in got.iter().zip(&vals) {
                let want = if matches!(ord, 2 | 5) {
                    f64::from(*v as f32)
                } else {
                    *v
                };
                assert_eq!(g.to_bits(), want.to_bits(), "{ord} {order}: {g} vs {v}");
            }
            // the wrong byte order is refused or reads other values,
            // never these
            let mut swapped = bin.clone();
            let p = swapped.iter().position(|&c| c == b'b').unwrap();
            swapped[p + 6] = if order == 1 { b'2' } else { b'1' };
            if let Ok(r) = records(&swapped) {
                assert_ne!(r[0].re, got.iter().step_by(2).copied().collect::<Vec<_>>());
            }
        }
    }
    // an end of line before the closing -1 (some exporters)
    let mut bin = dataset_with(
        4,
        (1, 1),
        6,
        (0.0, 1.0),
        (8, 13),
        ("m", "N"),
        &vals,
        Form::Binary { order: 1 },
    );
    bin.truncate(bin.len() - 7);
    bin.extend(b"\r\n    -1\n");
    assert_eq!(records(&bin).unwrap()[0].re.len(), 67);
    // truncated values
    let full = dataset_with(
        4,
        (1, 1),
        6,
        (0.0, 1.0),
        (8, 13),
        ("m", "N"),
        &vals,
        Form::Binary { order: 1 },
    );
    let e = records(&full[..full.len() - 40]).unwrap_err();
    assert!(
        e.0.contains("record 1 (dataset 58b, line 2)") && e.1.contains("expected 1072"),
        "{e:?}"
    );
    // inside the values, places are byte offsets: the first value's eight
    // bytes are where the message says the values start
    let after = "bytes left after byte ";
    let at = e.1.find(after).unwrap_or_else(|| panic!("{e:?}")) + after.len();
    let start: usize = e.1[at..]
        .split(':')
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{e:?}"));
    let first = records(&full).unwrap()[0].re[0];
    let bytes: [u8; 8] = full[start..start + 8].try_into().unwrap();
    assert_eq!(f64::from_le_bytes(bytes), first);
    let mut nan = full.clone();
    nan[start + 8..start + 16].copy_from_slice(&f64::NAN.to_le_bytes());
    let e = records(&nan).unwrap_err();
    assert!(
        e.1.contains(&format!(
            "value 1 (bytes {} to {} of the file)",
            start + 8,
            start + 15
        )),
        "{e:?}"
    );
    // a floating-point format other than IEEE
    let mut vax = full.clone();
    vax[25] = b'1';
    let e = records(&vax).unwrap_err();
    assert!(e.1.contains("floating-point format 1"), "{e:?}");
}

#[test]
fn latin1_text_fields_and_units_labels_are_read() {
    let vals: Vec<f64> = (0..8).map(f64::from).collect();
    let mut b = dataset_with(
        4,
        (7, 7),
        6,
        (0.0, 1.0),
        (8, 13),
        ("\u{b5}m", "N"),
        &vals,
        Form::Ascii,
    );
    // to Latin-1: µ (U+00B5) is C2 B5 in UTF-8, B5 in Latin-1; a ° in
    // the first ID line
    let s = String::from_utf8(b.clone())
        .unwrap()
        .replace("ID line 1", "Temp 20\u{b0}C");
    b = s
        .chars()
        .map(|c| u8::try_from(u32::from(c)).unwrap())
        .collect();
    assert!(std::str::from_utf8(&b).is_err());
    let r = records(&b).unwrap();
    assert_eq!(r[0].id1, "Temp 20°C");
    assert_eq!(r[0].numerator_units, "µm");
    let (f, how) = r[0].si_factor(None).unwrap();
    assert!((f - 1e-6).abs() < 1e-20, "{f} {how}");
    let (s, notes) = parse(&b, None).unwrap();
    let Series::Frf { re, .. } = &s[&(0, 0)] else {
        panic!()
    };
    assert!((re[3] - 6e-6).abs() < 1e-18, "{re:?}");
    assert!(notes.iter().any(|n| n.contains("`µm`")), "{notes:?}");
}

#[test]
fn units_labels_and_dataset_164_give_the_si_factor() {
    let vals: Vec<f64> = (0..8).map(f64::from).collect();
    let rec = |num, units: (&str, &str)| {
        dataset_with(
            4,
            (1, 1),
            6,
            (0.0, 1.0),
            (num, 13),
            units,
            &vals,
            Form::Ascii,
        )
    };
    let one = |b: Vec<u8>| records(&b).unwrap().remove(0);
    for (num, units, want) in [
        (12, ("g", "N"), 9.806_65),
        (12, ("m/s^2", "N"), 1.0),
        (12, ("mm/s2", "N"), 1e-3),
        (12, ("(m/s²)", "lbf"), 1.0 / 4.448_221_615_260_5),
        (11, ("in/s", "N"), 0.0254),
        (8, ("mm", "kN"), 1e-6),
        (8, ("NONE", "NONE"), 1.0),
        // a label that fills its 20 columns, as LMS exports write it
        (12, ("(1/N)*(mm/s²)", "NONE"), 1e-3),
    ] {
        let (f, how) = one(rec(num, units)).si_factor(None).unwrap();
        assert!(
            (f / want - 1.0).abs() < 1e-12,
            "{units:?}: {f} vs {want} ({how})"
        );
    }
    // dataset 164 (mm, N): labels NONE take its factors
    let u164 = b"    -1\n   164\n         5mm (milli-newton)         2\n  1.00000000000000000D+03  1.00000000000000000D+00  1.00000000000000000D+00\n  2.73150000000000000D+02\n    -1\n";
    let mut file = u164.to_vec();
    file.extend(rec(8, ("NONE", "NONE")));
    let u = read(&file).unwrap();
    let units = u.units.clone().unwrap();
    assert_eq!((units.code, units.length, units.force), (5, 1000.0, 1.0));
    let (f, how) = u.records[0].si_factor(Some(&units)).unwrap();
    assert!((f - 1e-3).abs() < 1e-15 && how.contains("164"), "{f} {how}");
    let (_, notes) = parse(&file, None).unwrap();
    assert!(
        notes.iter().any(|n| n.contains("length factor 1000")),
        "{notes:?}"
    );
    // labels that cannot be read, or of the wrong quantity
    for (num, units, want) in [
        (8, ("furlong", "N"), "unit `furlong` not known"),
        (12, ("m/s", "N"), "units `m/s` for acceleration"),
        (
            8,
            ("m", "kg"),
            "denominator units `kg`: unit `kg` not known",
        ),
    ] {
        let e = parse(&rec(num, units), None).unwrap_err();
        let msg = format!("{}{}", e.0, e.1);
        assert!(
            msg.contains(want)
                && msg.contains("record 1 (dataset 58, line 2), node 1 +Z / node 1 +Z"),
            "{msg}"
        );
    }
}

#[test]
fn coherence_is_reported_and_time_histories_are_not_used() {
    let frf: Vec<f64> = (0..16).map(|k| f64::from(k) * 1e-6).collect();
    let coh: Vec<f64> = (0..8).map(|k| 0.5 + f64::from(k) / 16.0).collect();
    let rec = |func, den, ord, vals: &[f64]| {
        dataset_with(
            func,
            (1, 2),
            ord,
            (0.0, 1.0),
            (8, den),
            ("m", "N"),
            vals,
            Form::Ascii,
        )
    };
    let mut file = rec(4, 13, 6, &frf);
    file.extend(rec(6, 0, 4, &coh));
    file.extend(rec(1, 0, 4, &coh));
    let (s, notes) = parse(&file, None).unwrap();
    assert_eq!(s.len(), 1);
    assert!(
        notes
            .iter()
            .any(|n| n.contains("record 2") && n.contains("coherence min 0.500, mean 0.719")),
        "{notes:?}"
    );
    assert!(
        notes.iter().any(|n| n.contains("record 3")
            && n.contains("a time history")
            && n.contains("not used")),
        "{notes:?}"
    );
    // time histories alone: refused, saying so
    let mut only = rec(1, 0, 4, &coh);
    only.extend(rec(2, 0, 4, &coh));
    let e = parse(&only, None).unwrap_err();
    assert!(
        e.1.contains("no FRF nor impulse response")
            && e.1
                .contains("record 1 (dataset 58, line 2), node 1 +Z / node 2 +Z: a time history")
            && e.1.contains("record 2 (dataset 58, line 18)")
            && e.1.contains("auto spectrum (function type 2)"),
        "{e:?}"
    );
}

#[test]
fn records_are_read_with_their_nodes_and_values() {
    let t = dataset(1, 101, 102, 4, 0.0, 1e-3, 8, &[0.0, 1.0, 2.0, 3.0, 4.5]);
    let r = records(t.as_bytes()).unwrap();
    assert_eq!(r.len(), 1);
    assert_eq!((r[0].response_node, r[0].reference_node), (101, 102));
    assert_eq!(r[0].re, [0.0, 1.0, 2.0, 3.0, 4.5]);
    assert_eq!(r[0].abscissa_step, 1e-3);
    // fixed-width fields that touch
    let touching = t.replace(
        "    0.000000000000E0    1.000000000000E0",
        "-1.0000000000000E+00-2.0000000000000E+00",
    );
    let r = records(touching.as_bytes()).unwrap();
    assert_eq!(r[0].re, [-1.0, -2.0, 2.0, 3.0, 4.5]);
}

#[test]
fn errors_name_the_record_the_field_and_the_expectation() {
    let good = dataset(1, 1, 1, 4, 0.0, 1e-3, 8, &[0.0, 1.0, 2.0, 3.0]);
    let cases: Vec<(String, &str)> = vec![
        (
            dataset(2, 1, 1, 4, 0.0, 1e-3, 8, &[0.0; 4]),
            "auto spectrum (function type 2)",
        ),
        (
            dataset(1, 1, 1, 4, 0.0, 1e-3, 9, &[0.0; 4]),
            "record 1 (dataset 58, line 2), node 1 +Z / node 1 +Z: ordinate specific data type 9 (record 9): expected 8",
        ),
        (
            dataset(1, 1, 1, 3, 0.0, 1e-3, 8, &[0.0; 4]),
            "record 1 (dataset 58, line 2): ordinate data type 3",
        ),
        (
            good.trim_end_matches("    -1\n").to_string(),
            "dataset 1: no closing",
        ),
        (
            good.replace("3.000000000000E0", "NaN"),
            "expected a finite number",
        ),
        (
            good.replace("3.000000000000E0", "x"),
            "line 14: value `x`: expected a number",
        ),
        (format!("junk\n{good}"), "line 1: `junk`: expected `    -1`"),
    ];
    for (text, want) in cases {
        let e = parse(text.as_bytes(), None).map(|_| ()).unwrap_err();
        let msg = format!("{}{}", e.0, e.1);
        assert!(msg.contains(want), "{msg} (wanted {want})");
    }
    // a missing value
    let short = good.replace("   3.000000000000E0", "");
    let e = parse(short.as_bytes(), None).map(|_| ()).unwrap_err();
    assert!(e.1.contains("3 values: expected 4"), "{e:?}");
}

#[test]
fn velocity_frfs_are_made_receptances() {
    // H_d(ω) = 1 / (k - m ω²): H_v = iω H_d
    let (k, m, df) = (1e6, 1.0, 1.0);
    let n = 64;
    let mut v = Vec::new();
    for q in 0..n {
        let w = std::f64::consts::TAU * q as f64 * df;
        let hd = 1.0 / (k - m * w * w);
        v.extend([0.0, w * hd]); // iω · real
    }
    let t = dataset(4, 1, 1, 6, 0.0, df, 11, &v);
    let (s, notes) = parse(t.as_bytes(), None).unwrap();
    assert!(notes.iter().any(|n| n.contains("velocity")));
    let Series::Frf { re, im, .. } = &s[&(0, 0)] else {
        panic!()
    };
    for q in 1..n {
        let w = std::f64::consts::TAU * q as f64 * df;
        let hd = 1.0 / (k - m * w * w);
        assert!(
            (re[q] - hd).abs() <= 1e-12 * hd.abs().max(1e-12),
            "{q}: {} vs {hd}",
            re[q]
        );
        assert!(im[q].abs() <= 1e-12 * hd.abs());
    }
}
