//! What changed between two versions of a scene, in words with units: the
//! visualiser shows it under a description written for the scene as it was
//! opened or saved, and adds it to the description on save, so that a saved
//! preset's text does not describe a scene it no longer is.

use super::{Contact, Mode, Scene, Tyre};
use tirecontact_core::model::road::Road;

/// `x` to four significant digits, in the shortest form (`10`, `0.025`).
fn num(x: f64) -> String {
    let r: f64 = format!("{x:.3e}").parse().unwrap_or(x);
    format!("{r}")
}

/// "label a -> b unit" of the scene field at `path` when `a != b`, in the
/// label and unit the editor shows it in (the table of fields).
fn change_of(out: &mut Vec<String>, path: &str, a: f64, b: f64) {
    let (scale, unit) = super::fields::field(path).map_or((1.0, ""), |f| f.shown);
    change(out, &super::fields::label(path), a, b, scale, unit);
}

/// "what a -> b unit" when `a != b`.
fn change(out: &mut Vec<String>, what: &str, a: f64, b: f64, scale: f64, unit: &str) {
    if a != b {
        let line = format!("{what} {} -> {} {unit}", num(a * scale), num(b * scale));
        out.push(line.trim_end().to_string());
    }
}

fn road_kind(r: &Road) -> &'static str {
    match r {
        Road::Sine { .. } => "sine",
        Road::Harmonics { .. } => "harmonics",
        Road::Measured { .. } => "measured profile",
        Road::Random { .. } => "random",
        Road::Surface { .. } => "surface",
        Road::Crg { .. } => "OpenCRG road",
        Road::Texture { .. } => "texture",
    }
}

fn tyre_kind(t: &Tyre) -> &'static str {
    match t {
        Tyre::Modal { .. } => "modal model",
        Tyre::Ring { .. } => "ring",
        Tyre::Measured { .. } => "measured responses",
        Tyre::Plate { .. } => "plate",
        Tyre::FeModes { .. } => "FE modes",
    }
}

fn contact_kind(c: &Contact) -> &'static str {
    match c {
        Contact::Rigid => "rigid",
        Contact::Compliant { .. } => "compliant",
    }
}

/// Most modes whose edits are listed one by one; more are counted.
const MODES_LISTED: usize = 3;

/// "mode k (f Hz, ξ z)" for a mode added or removed.
fn mode_named(k: usize, m: &Mode) -> String {
    format!(
        "mode {k} ({} Hz, ξ {})",
        num(m.freq_hz),
        num(m.damping_ratio)
    )
}

/// The edits of the modes `a` to `b`: per mode kept, its frequency and
/// damping from and to and whether its residues changed; the modes added
/// at the end or removed (anywhere, the others kept as they were); a count
/// beyond [`MODES_LISTED`] edits, or when the lists cannot be matched.
fn mode_edits(out: &mut Vec<String>, a: &[Mode], b: &[Mode]) {
    if a.len() > b.len() {
        // removed modes: `b` is `a` without them, in order
        let mut removed = Vec::new();
        let mut j = 0;
        for (k, m) in a.iter().enumerate() {
            if j < b.len() && b[j] == *m {
                j += 1;
            } else {
                removed.push(k);
            }
        }
        if j == b.len() && removed.len() <= MODES_LISTED {
            out.extend(
                removed
                    .iter()
                    .map(|&k| format!("{} removed", mode_named(k, &a[k]))),
            );
        } else {
            out.push(format!("{} -> {} modes", a.len(), b.len()));
        }
        return;
    }
    let common = a.len();
    let changed: Vec<usize> = (0..common).filter(|&k| a[k] != b[k]).collect();
    let added = b.len() - common;
    if changed.len() + added > MODES_LISTED {
        if !changed.is_empty() {
            out.push(format!("{} of {} modes", changed.len(), common));
        }
        if added > 0 {
            out.push(format!("{} -> {} modes", common, b.len()));
        }
        return;
    }
    for k in changed {
        let (x, y) = (&a[k], &b[k]);
        let what = format!("mode {k}");
        change(
            out,
            &format!("{what} frequency"),
            x.freq_hz,
            y.freq_hz,
            1.0,
            "Hz",
        );
        change(
            out,
            &format!("{what} damping ratio"),
            x.damping_ratio,
            y.damping_ratio,
            1.0,
            "",
        );
        if x.residue != y.residue || x.shape != y.shape {
            out.push(format!("{what} residues"));
        }
    }
    out.extend((common..b.len()).map(|k| format!("{} added", mode_named(k, &b[k]))));
}

/// The changes from `before` to `after` a reader of `before`'s description
/// would need to know, one phrase each with units ("speed V 10 -> 20 m/s");
/// empty when none. The name and the description themselves are not listed.
pub fn edits_since(before: &Scene, after: &Scene) -> Vec<String> {
    edits_since_identified(before, None, after)
}

/// [`edits_since`], where `before`'s ring tyre was identified as
/// `ring_modes`: a ring turned into a modal model ("Edit as a modal
/// model") and then edited lists the edits of those modes too (tyre ring
/// -> modal model; mode 0 frequency 40.9 -> 45 Hz; mode 13 added (…)).
pub fn edits_since_identified(
    before: &Scene,
    ring_modes: Option<&[Mode]>,
    after: &Scene,
) -> Vec<String> {
    let mut out = Vec::new();
    match (&before.tyre, &after.tyre, ring_modes) {
        (Tyre::Modal { modes: a }, Tyre::Modal { modes: b }, _) if a != b => {
            mode_edits(&mut out, a, b);
        }
        (Tyre::Ring { .. }, Tyre::Modal { modes: b }, Some(a)) => {
            out.push(format!(
                "tyre ring -> modal model of its {}",
                tirecontact_core::base::error::count(a.len(), "identified mode")
            ));
            if a != b.as_slice() {
                mode_edits(&mut out, a, b);
            }
        }
        (
            Tyre::Ring {
                ring: ra,
                identification: ia,
            },
            Tyre::Ring {
                ring: rb,
                identification: ib,
            },
            _,
        ) => {
            if ra != rb {
                out.push("ring parameters".to_string());
            }
            if ia != ib {
                out.push("identification options".to_string());
            }
        }
        (a, b, _) if std::mem::discriminant(a) != std::mem::discriminant(b) => {
            out.push(format!("tyre {} -> {}", tyre_kind(a), tyre_kind(b)));
        }
        (a @ (Tyre::Plate { .. } | Tyre::FeModes { .. } | Tyre::Measured { .. }), b, _)
            if a != b =>
        {
            out.push(format!("{} tyre parameters", tyre_kind(b)));
        }
        _ => {}
    }
    let (pa, pb) = (&before.points, &after.points);
    if let (Some(ga), Some(gb)) = (pa.grid(), pb.grid()) {
        if (ga.along, ga.across) != (gb.along, gb.across) {
            out.push(format!(
                "patch grid {} × {} -> {} × {} points (along × across)",
                ga.along, ga.across, gb.along, gb.across
            ));
        }
        change_of(
            &mut out,
            "points.spacing_m.0",
            ga.spacing_m.0,
            gb.spacing_m.0,
        );
        change_of(
            &mut out,
            "points.spacing_m.1",
            ga.spacing_m.1,
            gb.spacing_m.1,
        );
        if ga.preload != gb.preload {
            out.push("patch preload".to_string());
        }
    } else if pa.len() != pb.len() {
        out.push(format!("{} -> {} contact points", pa.len(), pb.len()));
    } else if pa != pb {
        out.push("contact point positions or heights".to_string());
    }
    match (&before.road, &after.road) {
        (
            Road::Sine {
                amplitude_m: a0,
                wavelength_m: l0,
            },
            Road::Sine {
                amplitude_m: a1,
                wavelength_m: l1,
            },
        ) => {
            change_of(&mut out, "road.amplitude_m", *a0, *a1);
            change_of(&mut out, "road.wavelength_m", *l0, *l1);
        }
        (a, b) if std::mem::discriminant(a) != std::mem::discriminant(b) => {
            out.push(format!("road {} -> {}", road_kind(a), road_kind(b)));
        }
        (a, b) if a != b => out.push(format!("{} road parameters", road_kind(b))),
        _ => {}
    }
    for (path, a, b) in [
        ("speed_mps", before.speed_mps, after.speed_mps),
        ("ramp_s", before.ramp_s, after.ramp_s),
        ("dt_s", before.dt_s, after.dt_s),
        ("duration_s", before.duration_s, after.duration_s),
    ] {
        change_of(&mut out, path, a, b);
    }
    if before.contact_scheme != after.contact_scheme {
        out.push(format!(
            "contact scheme {:?} -> {:?}",
            before.contact_scheme, after.contact_scheme
        ));
    }
    if before.contact != after.contact {
        let (a, b) = (contact_kind(&before.contact), contact_kind(&after.contact));
        if a == b {
            out.push(format!("{b} contact parameters"));
        } else {
            out.push(format!("contact {a} -> {b}"));
        }
    }
    out
}

/// `description` with a closing paragraph listing `edits` ("Edited from
/// "Paper": speed V 10 -> 20 m/s; …."); unchanged when there are none.
pub fn described_with_edits(description: &str, from_name: &str, edits: &[String]) -> String {
    if edits.is_empty() {
        return description.to_string();
    }
    let note = format!("Edited from \"{from_name}\": {}.", edits.join("; "));
    if description.trim().is_empty() {
        note
    } else {
        format!("{}\n\n{note}", description.trim_end())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{ContactScheme, Mode, Point};

    fn scene() -> Scene {
        Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/three_points.ron"
            )),
            "three_points",
        )
        .expect("shipped preset")
    }

    #[test]
    fn an_unchanged_scene_has_no_edits() {
        let s = scene();
        assert!(edits_since(&s, &s.clone()).is_empty());
        // the name and the description are the user's, not edits to report
        let mut t = s.clone();
        t.name = "renamed".into();
        t.description = "other".into();
        assert!(edits_since(&s, &t).is_empty());
    }

    #[test]
    fn numbers_are_given_with_units_from_and_to() {
        let s = scene();
        let mut t = s.clone();
        t.speed_mps = 2.0 * s.speed_mps;
        t.dt_s = 2e-5;
        t.duration_s = s.duration_s + 0.5;
        let e = edits_since(&s, &t);
        let speed = format!("speed V {} -> {} m/s", num(s.speed_mps), num(t.speed_mps));
        assert!(e.contains(&speed), "{e:?}");
        assert!(
            e.iter()
                .any(|x| x.starts_with("time step dt") && x.ends_with("-> 20 µs")),
            "{e:?}"
        );
        assert!(
            e.iter()
                .any(|x| x.starts_with("duration") && x.ends_with(" s")),
            "{e:?}"
        );
        assert_eq!(e.len(), 3, "{e:?}");
    }

    #[test]
    fn road_edits_name_the_quantity_or_the_kind() {
        let mut s = scene();
        s.road = Road::Sine {
            amplitude_m: 1e-3,
            wavelength_m: 0.1,
        };
        let mut t = s.clone();
        t.road = Road::Sine {
            amplitude_m: 2.5e-3,
            wavelength_m: 0.1,
        };
        assert_eq!(edits_since(&s, &t), ["road amplitude a 1 -> 2.5 mm"]);
        t.road = Road::Harmonics { components: vec![] };
        assert_eq!(edits_since(&s, &t), ["road sine -> harmonics"]);
    }

    #[test]
    fn tyre_points_and_contact_edits_are_listed() {
        let s = scene();
        let mut t = s.clone();
        if let Tyre::Modal { modes } = &mut t.tyre {
            modes.push(Mode {
                freq_hz: 300.0,
                damping_ratio: 0.05,
                residue: vec![],
                shape: vec![0.0; s.points.len()],
            });
        }
        t.points.push(Point {
            x_m: 1.0,
            y_m: 0.0,
            h_m: 0.0,
        });
        t.contact_scheme = ContactScheme::Paper;
        let e = edits_since(&s, &t);
        let n = s.points.len();
        let Tyre::Modal { modes } = &s.tyre else {
            panic!("three_points is a modal scene");
        };
        let k = modes.len();
        assert!(
            e.contains(&format!("mode {k} (300 Hz, ξ 0.05) added")),
            "{e:?}"
        );
        assert!(
            e.contains(&format!("{n} -> {} contact points", n + 1)),
            "{e:?}"
        );
        assert!(
            e.contains(&"contact scheme Located -> Paper".to_string()),
            "{e:?}"
        );
    }

    #[test]
    fn a_detuned_mode_is_named_with_its_values() {
        let s = scene();
        let mut t = s.clone();
        let Tyre::Modal { modes } = &mut t.tyre else {
            panic!("three_points is a modal scene");
        };
        let (f0, z0) = (modes[1].freq_hz, modes[1].damping_ratio);
        modes[1].freq_hz = 2.0 * f0;
        modes[1].damping_ratio = 0.0;
        let e = edits_since(&s, &t);
        assert_eq!(
            e,
            [
                format!("mode 1 frequency {} -> {} Hz", num(f0), num(2.0 * f0)),
                format!("mode 1 damping ratio {} -> 0", num(z0)),
            ]
        );
        // many modes: counted
        let Tyre::Modal { modes } = &mut t.tyre else {
            unreachable!()
        };
        let n = modes.len();
        for m in modes.iter_mut() {
            m.freq_hz *= 1.01;
        }
        if n > MODES_LISTED {
            assert_eq!(edits_since(&s, &t), [format!("{n} of {n} modes")]);
        } else {
            assert_eq!(edits_since(&s, &t).len(), n + 1);
        }
    }

    #[test]
    fn the_note_closes_the_description() {
        let e = vec![
            "speed V 10 -> 20 m/s".to_string(),
            "ramp 0 -> 0.1 s".to_string(),
        ];
        assert_eq!(
            described_with_edits("Five points.\n", "Paper", &e),
            "Five points.\n\nEdited from \"Paper\": speed V 10 -> 20 m/s; ramp 0 -> 0.1 s."
        );
        assert_eq!(
            described_with_edits("Five points.", "Paper", &[]),
            "Five points."
        );
        assert_eq!(
            described_with_edits("", "P", &e[..1]),
            "Edited from \"P\": speed V 10 -> 20 m/s."
        );
    }

    /// A ring made a modal model and then edited: the edits of the
    /// identified modes are listed, not only the change of kind.
    #[test]
    fn edits_of_a_ring_made_modal_are_listed_against_its_identified_modes() {
        let ring = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/paper.ron"
            )),
            "paper",
        )
        .unwrap();
        let identified: Vec<Mode> = (0..5)
            .map(|k| Mode {
                freq_hz: 40.0 + 10.0 * k as f64,
                damping_ratio: 0.05,
                residue: vec![],
                shape: vec![1.0; ring.points.len()],
            })
            .collect();
        let mut t = ring.clone();
        t.tyre = Tyre::Modal {
            modes: identified.clone(),
        };
        // converted, not yet edited
        let said = edits_since_identified(&ring, Some(&identified), &t);
        assert_eq!(said, ["tyre ring -> modal model of its 5 identified modes"]);
        let Tyre::Modal { modes } = &mut t.tyre else {
            unreachable!()
        };
        modes[0].freq_hz = 45.0;
        modes[0].damping_ratio = 0.02;
        let mut extra = identified[4].clone();
        extra.freq_hz = 600.0;
        modes.push(extra);
        t.speed_mps = 15.0;
        let said = edits_since_identified(&ring, Some(&identified), &t);
        assert_eq!(
            said,
            [
                "tyre ring -> modal model of its 5 identified modes",
                "mode 0 frequency 40 -> 45 Hz",
                "mode 0 damping ratio 0.05 -> 0.02",
                "mode 5 (600 Hz, ξ 0.05) added",
                "speed V 10 -> 15 m/s",
            ]
        );
        // without the identified modes only the kind can be said
        assert_eq!(edits_since(&ring, &t)[0], "tyre ring -> modal model");
    }

    #[test]
    fn removed_modes_are_named_wherever_they_were() {
        let s = scene();
        let Tyre::Modal { modes } = &s.tyre else {
            unreachable!()
        };
        let mut t = s.clone();
        let Tyre::Modal { modes: kept } = &mut t.tyre else {
            unreachable!()
        };
        let gone = kept.remove(1);
        assert_eq!(
            edits_since(&s, &t),
            [format!("{} removed", mode_named(1, &gone))]
        );
        // removed and another edited: the lists cannot be matched
        let Tyre::Modal { modes: kept } = &mut t.tyre else {
            unreachable!()
        };
        kept[0].freq_hz *= 2.0;
        assert_eq!(
            edits_since(&s, &t),
            [format!("{} -> {} modes", modes.len(), modes.len() - 1)]
        );
    }
}
