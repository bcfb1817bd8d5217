//! Problems for the solver's unit tests, written as the scene format writes
//! a modal tyre (`Scene(name: …, tyre: Modal(modes: […]), points: […], …)`),
//! so that a test reads as the presets do. Only what the solver takes is
//! read; the scene format itself, its validation and identification are
//! tested in `tirecontact-io`.

use crate::base::modal::Mode;
use crate::model::road::{Road, RoadProfile};
use crate::solver::problem::{Contact, ContactScheme, Point, Problem};
use serde::Deserialize;
use std::sync::Arc;

#[derive(Deserialize)]
#[serde(rename = "Scene")]
struct Text {
    name: String,
    #[serde(default)]
    #[allow(dead_code)]
    description: String,
    tyre: Tyre,
    points: Vec<Point>,
    road: Road,
    speed_mps: f64,
    #[serde(default)]
    ramp_s: f64,
    dt_s: f64,
    duration_s: f64,
    #[serde(default)]
    contact_scheme: ContactScheme,
    #[serde(default)]
    contact: Contact,
}

#[derive(Deserialize)]
enum Tyre {
    Modal { modes: Vec<Mode> },
}

/// The problem of a modal scene's text (a generated road; no file).
pub fn problem(text: &str) -> Problem {
    let t: Text = ron::from_str(text).unwrap_or_else(|e| panic!("test scene: {e}"));
    let Tyre::Modal { modes } = t.tyre;
    let road = RoadProfile::generated(&t.road)
        .expect("a test road without a file")
        .expect("a valid test road");
    Problem {
        name: t.name,
        points: t.points,
        modes: Arc::new(modes),
        modes_identified: false,
        road: Arc::new(road),
        contact: t.contact,
        contact_scheme: t.contact_scheme,
        dt_s: t.dt_s,
        duration_s: t.duration_s,
        speed_mps: t.speed_mps,
        ramp_s: t.ramp_s,
    }
}
