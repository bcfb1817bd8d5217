use super::*;
use crate::readers::fe_modes::FeDamping;
use crate::scene::{Contact, Scene, Tyre};
use std::collections::BTreeSet;
use tirecontact_core::model::road::{Harmonic, Road};

/// Every shipped preset, and each with the roads, FE dampings and contact
/// laws the presets do not all show: every kind of numeric field appears.
fn scenes() -> Vec<Scene> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
    let mut presets: Vec<Scene> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .map(|p| Scene::load(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display())))
        .collect();
    assert!(presets.len() >= 10, "{} presets", presets.len());
    let base = presets[0].clone();
    let roads = [
        Road::Harmonics {
            components: vec![Harmonic {
                amplitude_m: 1e-3,
                wavelength_m: 0.2,
                phase_rad: 0.0,
            }],
        },
        ron::from_str::<Road>("Random(class: C, seed: 1)").unwrap(),
        ron::from_str::<Road>("Texture(class: C, seed: 1)").unwrap(),
    ];
    for road in roads {
        let mut s = base.clone();
        s.road = road;
        presets.push(s);
    }
    let fe = presets
        .iter()
        .find(|s| matches!(s.tyre, Tyre::FeModes { .. }))
        .expect("an FE preset")
        .clone();
    for damping in [
        FeDamping::Ratio(0.05),
        FeDamping::Modal(vec![0.05, 0.04]),
        FeDamping::Rayleigh {
            alpha_per_s: 10.0,
            beta_s: 1e-5,
        },
    ] {
        let mut s = fe.clone();
        if let Tyre::FeModes { damping: d, .. } = &mut s.tyre {
            *d = damping;
        }
        presets.push(s);
    }
    let mut compliant = base;
    compliant.contact = Contact::Compliant {
        stiffness_n_m: vec![1e6; compliant.points.len()],
    };
    presets.push(compliant);
    presets
}

fn reached() -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for mut s in scenes() {
        out.extend(grid_fields(&s).into_iter().map(|(p, _)| p.to_string()));
        out.extend(
            numeric_fields(&mut s, true)
                .into_iter()
                .map(|(p, _)| wildcard(&p)),
        );
    }
    out
}

#[test]
fn every_field_reached_has_an_entry_and_every_entry_is_reached() {
    let reached = reached();
    let listed: BTreeSet<String> = FIELDS.iter().map(|f| f.path.to_string()).collect();
    let missing: Vec<_> = reached.difference(&listed).collect();
    assert!(missing.is_empty(), "fields without an entry: {missing:?}");
    let stale: Vec<_> = listed.difference(&reached).collect();
    assert!(stale.is_empty(), "entries no scene has: {stale:?}");
    assert_eq!(listed.len(), FIELDS.len(), "a path listed twice");
}

/// The unit of each entry is the one its path's name carries by the
/// format's naming rule (`_hz`, `_n_m2`, …): the table and the names
/// cannot drift apart.
#[test]
fn units_agree_with_the_names_suffixes() {
    let suffixes = [
        ("_n_m3", "N/m³"),
        ("_kg_m2", "kg/m²"),
        ("_n_m2", "N/m²"),
        ("_kg_m", "kg/m"),
        ("_n_m", "N/m"),
        ("_nm", "N·m"),
        ("_mps", "m/s"),
        ("_cpm", "cycles/m"),
        ("_rad", "rad"),
        ("_ratio", "-"),
        ("_hz", "Hz"),
        ("_pa", "Pa"),
        ("_per_s", "1/s"),
        ("_m", "m"),
        ("_s", "s"),
        ("_n", "N"),
    ];
    for f in FIELDS {
        // the name without its indices and a tuple's `.0`
        let name = f
            .path
            .split('.')
            .rev()
            .map(|c| c.split('[').next().unwrap_or(c))
            .find(|c| !c.is_empty() && !c.bytes().all(|b| b.is_ascii_digit()))
            .unwrap();
        let by_name = suffixes
            .iter()
            .find(|(s, _)| name.ends_with(s))
            .map(|(_, u)| *u);
        match (name, by_name) {
            // EI's unit is not the suffix's stiffness per area
            ("bending_stiffness_n_m2", _) => assert_eq!(f.unit, "N·m²"),
            (_, Some(u)) => assert_eq!(f.unit, u, "{}", f.path),
            (_, None) => assert!(
                matches!(name, "shape" | "residue" | "damping" | "along" | "across"),
                "{}: a name without a unit suffix",
                f.path
            ),
        }
    }
}

#[test]
fn labels_name_the_holder_and_the_index() {
    assert_eq!(label("speed_mps"), "speed V");
    assert_eq!(label(" dt_s "), "time step dt");
    assert_eq!(label("tyre.modes[2].damping_ratio"), "mode 2 damping ratio");
    assert_eq!(label("points[*].h_m"), "every point's height h");
    assert_eq!(
        label("contact.stiffness_n_m[1]"),
        "tread stiffness of point 1"
    );
    assert_eq!(
        label("contact.stiffness_n_m[*]"),
        "tread stiffness of every point"
    );
    // the further indices of a nested field name its points
    assert_eq!(label("tyre.modes[0].shape[1]"), "mode 0 shape at point 1");
    assert_eq!(
        label("tyre.modes[*].residue[*][*]"),
        "every mode's residue at point i of a force at point j"
    );
    // a path the format does not have
    assert_eq!(label("no.such_field"), "no.such_field");
    assert_eq!(axis_label("speed_mps"), "speed V (m/s)");
    assert_eq!(axis_label("tyre.modes[0].freq_hz"), "mode 0 frequency (Hz)");
    assert_eq!(axis_label("points.along"), "points along");
    assert_eq!(
        axis_label("tyre.modes[2].residue[0][1]"),
        "mode 2 residue at point 0 of a force at point 1 (1/kg)"
    );
}

#[test]
fn labels_are_unique_and_bounds_ordered() {
    let mut seen = BTreeSet::new();
    for f in FIELDS {
        if !f.label.is_empty() {
            assert!(
                seen.insert((f.holder, f.label)),
                "{}: label {:?} used twice",
                f.path,
                f.label
            );
        }
        if let (Some((lo, _)), Some(hi)) = (f.min_si, f.max_si) {
            assert!(lo < hi, "{}: {lo} .. {hi}", f.path);
        }
        assert!(f.shown.0 > 0.0 && !f.what.is_empty(), "{}", f.path);
    }
}

/// The shipped presets' descriptions (shown in the visualiser's panel)
/// speak in words with units: no field of the format by its key
/// (`stiffness_n_m`) and no RON value (`Compliant(stiffness_n_m: …)`).
#[test]
fn preset_descriptions_name_no_field_by_its_key() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
    let keys: BTreeSet<String> = FIELDS
        .iter()
        .map(|f| {
            let last = f.path.rsplit('.').next().unwrap_or(f.path);
            last.split('[').next().unwrap_or(last).to_string()
        })
        .filter(|k| k.contains('_'))
        .collect();
    assert!(keys.contains("stiffness_n_m") && keys.contains("speed_mps"));
    for p in std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()) {
        if p.extension().is_none_or(|x| x != "ron") {
            continue;
        }
        let d = Scene::load(&p).unwrap().description;
        for k in &keys {
            assert!(!d.contains(k.as_str()), "{}: `{k}` in {d:?}", p.display());
        }
        assert!(
            !d.split('(').skip(1).any(|rest| {
                rest.split_once(':').is_some_and(|(key, _)| {
                    key.contains('_') && key.chars().all(|c| c.is_ascii_lowercase() || c == '_')
                })
            }),
            "{}: a RON value in {d:?}",
            p.display()
        );
    }
}
