//! Every numeric field of the editing panel says on hover what it is, its
//! unit and the values it accepts (tooltips used to name only the preset
//! field: "ramp_s (changing this restarts the run)"),
//! and the accepted range it states is the one the scene's validation
//! applies.

use crate::support::preset;
use egui::accesskit::Role;
use egui_kittest::kittest::{NodeT, Queryable};
use tirecontact::Scene;
use tirecontact::gui::App;
use tirecontact::gui::widgets::field_help::help;
use tirecontact::model::road::{Harmonic, Road};
use tirecontact::scene::Contact;

/// Three points (mode shapes) on a two-harmonic road with compliant contact.
fn harmonics_compliant() -> Scene {
    let mut s = preset("three_points");
    s.road = Road::Harmonics {
        components: vec![
            Harmonic {
                amplitude_m: 0.001,
                wavelength_m: 0.2,
                phase_rad: 0.0,
            },
            Harmonic {
                amplitude_m: 0.0005,
                wavelength_m: 0.05,
                phase_rad: 1.0,
            },
        ],
    };
    s.contact = Contact::Compliant {
        stiffness_n_m: vec![2e5],
    };
    s.validate().unwrap();
    s
}

/// Hovers every text field of the side panel (mode details opened) and
/// returns each field's name with its tooltip, if it has one.
fn tooltips(scene: Scene) -> Vec<(String, Option<String>)> {
    let app = App::new(scene, None).unwrap();
    // tall enough for the whole panel, so that every field can be hovered
    let mut h = crate::harness::harness_sized(app, [1500.0, 4000.0]);
    h.run();
    let headers: Vec<String> = h
        .query_all_by_label_contains("mode ")
        .filter_map(|n| n.accesskit_node().label())
        .filter(|l| l.contains("residue matrix") || l.contains("shape φ"))
        .collect();
    for l in headers {
        h.get_by_label(&l).click();
        h.run();
        h.run();
    }
    let names: Vec<String> = h
        .query_all_by_role(Role::TextInput)
        .filter_map(|n| n.accesskit_node().label())
        .filter(|l| !l.starts_with("scene."))
        .collect();
    assert!(names.len() >= 3, "fields found: {names:?}");
    let mut out = Vec::new();
    for name in names {
        h.get_by_label(&name).hover();
        h.run_steps(40);
        // a label's text is its accesskit value
        let tip = h
            .query_all_by_label_contains("accepts:")
            .filter_map(|n| n.accesskit_node().label().or(n.accesskit_node().value()))
            .find(|t| t.contains(&format!("`{name}`")));
        out.push((name, tip));
        // away from every field, so that the next tooltip is the next field's
        h.hover_at(egui::pos2(1400.0, 3990.0));
        h.run_steps(5);
    }
    out
}

#[test]
fn every_numeric_field_says_what_it_is_its_unit_and_its_range_on_hover() {
    let mut seen = Vec::new();
    for scene in [
        preset("single_mode"),
        harmonics_compliant(),
        preset("random_road"),
    ] {
        for (name, tip) in tooltips(scene) {
            let tip = tip.unwrap_or_else(|| panic!("{name}: no tooltip with its range"));
            let h = help(&name).unwrap_or_else(|| panic!("{name}: no help"));
            assert!(tip.starts_with(h.what), "{name}: {tip}");
            let unit_line = tip.lines().nth(1).unwrap_or("");
            assert!(
                unit_line.starts_with("unit: ") && unit_line.len() > "unit:  · accepts: ".len(),
                "{name}: {tip}"
            );
            assert!(
                !unit_line.starts_with("unit:  "),
                "{name}: the unit is missing: {tip}"
            );
            assert!(
                tip.contains("restarts the run") || tip.contains("applied live"),
                "{name}: {tip}"
            );
            seen.push(name);
        }
    }
    // the fields of every kind were met
    for kind in [
        "road.amplitude_m",
        "road.wavelength_m",
        "speed_kmh",
        "speed_mps",
        "ramp_s",
        "dt_s",
        "duration_s",
        "tyre.modes[0].freq_hz",
        "tyre.modes[0].damping_ratio",
        "tyre.modes[0].residue[0][0]",
        "tyre.modes[0].shape[0]",
        "points[0].x_m",
        "points[0].y_m",
        "points[0].h_m",
        "road.components[1].amplitude_m",
        "road.components[1].wavelength_m",
        "road.components[1].phase_rad",
        "contact.stiffness_n_m[0]",
        "road.length_m",
        "road.min_wavenumber_cpm",
        "road.max_wavenumber_cpm",
    ] {
        assert!(seen.iter().any(|s| s == kind), "{kind} not met: {seen:?}");
    }
}

/// Sets the field `name` (its SI value) of a scene that has it.
fn set(s: &mut Scene, name: &str, v: f64) {
    use tirecontact::scene::Tyre;
    match name {
        "road.amplitude_m" | "road.wavelength_m" => {
            if let Road::Sine {
                amplitude_m,
                wavelength_m,
            } = &mut s.road
            {
                if name == "road.amplitude_m" {
                    *amplitude_m = v
                } else {
                    *wavelength_m = v
                }
            }
        }
        "speed_mps" => s.speed_mps = v,
        "ramp_s" => s.ramp_s = v,
        "dt_s" => s.dt_s = v,
        "duration_s" => s.duration_s = v,
        "points[0].h_m" => s.points[0].h_m = v,
        "contact.stiffness_n_m[0]" => {
            s.contact = Contact::Compliant {
                stiffness_n_m: vec![v],
            }
        }
        _ => {
            let Tyre::Modal { modes } = &mut s.tyre else {
                panic!("a modal scene")
            };
            match name {
                "tyre.modes[0].freq_hz" => modes[0].freq_hz = v,
                "tyre.modes[0].damping_ratio" => modes[0].damping_ratio = v,
                _ => panic!("{name}"),
            }
        }
    }
}

fn refused(s: &Scene, field: &str) -> bool {
    s.validate()
        .err()
        .is_some_and(|e| e.iter().any(|e| e.field == field))
}

/// Each stated bound is accepted (or not, as stated) and the values just
/// past it are refused, by `Scene::validate`.
#[test]
fn the_stated_ranges_are_the_validated_ones() {
    for name in [
        "road.amplitude_m",
        "road.wavelength_m",
        "speed_mps",
        "ramp_s",
        "dt_s",
        "duration_s",
        "points[0].h_m",
        "contact.stiffness_n_m[0]",
        "tyre.modes[0].freq_hz",
        "tyre.modes[0].damping_ratio",
    ] {
        let h = help(name).unwrap();
        // a scene whose other fields leave room at the bounds: no point
        // below the road (ramp 0 allowed), a long duration (dt up to 0.1 s)
        let mut base = preset("single_mode");
        base.points[0].h_m = 0.1;
        base.duration_s = 10.0;
        base.validate().unwrap();
        let at = |v: f64| {
            let mut s = base.clone();
            set(&mut s, name, v);
            s
        };
        let tiny = |x: f64| x.abs().max(1.0) * 1e-9;
        if let Some(hi) = h.max_si {
            assert!(!refused(&at(hi), name), "{name}: {hi} refused");
            assert!(
                refused(&at(hi + tiny(hi)), name),
                "{name}: above {hi} accepted"
            );
        }
        match h.min_si {
            Some((lo, inclusive)) => {
                assert_eq!(refused(&at(lo), name), !inclusive, "{name} at {lo}");
                assert!(
                    refused(&at(lo - tiny(lo)), name),
                    "{name}: below {lo} accepted"
                );
                assert!(
                    !refused(&at(lo + tiny(lo)), name),
                    "{name}: just above {lo}"
                );
            }
            None => assert!(!refused(&at(-1e3), name), "{name}: no lower bound stated"),
        }
    }
}
