//! Contact phases per point for on-screen labels (classroom mode):
//! free flight, impact, in contact, release.
//!
//! The phase of a step comes from the contact flag at its start and end and
//! from whether the point carried force during it (`Simulation::force_n`, the
//! step-mean force: an impact and release inside one step leave the flag
//! unchanged but carry an impulse):
//!
//! | start | end | force in step | phase |
//! |---|---|---|---|
//! | free | free | no | free flight |
//! | free | contact | - | impact |
//! | free | free | yes | impact (a bounce inside the step) |
//! | contact | contact | - | in contact |
//! | contact | free | - | release |
//!
//! Impacts and releases last one step, too short to read; a [`PhaseTracker`]
//! keeps each event on screen for a hold time (simulated seconds) unless a
//! newer event of the same point replaces it.

/// The phase of one contact point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactPhase {
    FreeFlight,
    Impact,
    InContact,
    Release,
}

impl ContactPhase {
    /// Plain words for the screen.
    pub fn label(self) -> &'static str {
        match self {
            ContactPhase::FreeFlight => "free flight",
            ContactPhase::Impact => "impact",
            ContactPhase::InContact => "in contact",
            ContactPhase::Release => "release",
        }
    }

    /// Whether the phase is an instantaneous event (impact, release).
    pub fn is_event(self) -> bool {
        matches!(self, ContactPhase::Impact | ContactPhase::Release)
    }
}

/// The phase of one step from the contact flags at its start and end and
/// whether the point carried force during it.
pub fn classify(was_contact: bool, is_contact: bool, had_force: bool) -> ContactPhase {
    match (was_contact, is_contact) {
        (false, true) => ContactPhase::Impact,
        (true, false) => ContactPhase::Release,
        (true, true) => ContactPhase::InContact,
        (false, false) if had_force => ContactPhase::Impact,
        (false, false) => ContactPhase::FreeFlight,
    }
}

/// Share of the phase an event starts (contact after an impact, flight
/// after a release) for which the event stays shown at most: the steady
/// phase is then seen for the rest, however fast events follow each other.
pub const EVENT_SHARE: f64 = 0.5;

/// Phases of every point over a run, with events held on screen.
#[derive(Debug, Clone, PartialEq)]
pub struct PhaseTracker {
    /// How long an impact or release stays shown at most (simulated s).
    pub hold_s: f64,
    contact: Vec<bool>,
    steady: Vec<ContactPhase>,
    /// Last event per point and its time (s).
    event: Vec<Option<(ContactPhase, f64)>>,
    impacts: Vec<u64>,
    releases: Vec<u64>,
    /// Time of each point's last impact and last release (s).
    last_impact_s: Vec<Option<f64>>,
    last_release_s: Vec<Option<f64>>,
    /// Length of each point's last whole contact and last whole flight (s).
    contact_s: Vec<Option<f64>>,
    flight_s: Vec<Option<f64>>,
}

impl PhaseTracker {
    /// A tracker of `p` points, all in free flight, events held `hold_s`.
    pub fn new(p: usize, hold_s: f64) -> Self {
        PhaseTracker {
            hold_s,
            contact: vec![false; p],
            steady: vec![ContactPhase::FreeFlight; p],
            event: vec![None; p],
            impacts: vec![0; p],
            releases: vec![0; p],
            last_impact_s: vec![None; p],
            last_release_s: vec![None; p],
            contact_s: vec![None; p],
            flight_s: vec![None; p],
        }
    }

    pub fn num_points(&self) -> usize {
        self.contact.len()
    }

    /// Back to the start of a run (same points and hold time).
    pub fn reset(&mut self) {
        *self = PhaseTracker::new(self.contact.len(), self.hold_s);
    }

    /// Records one step ending at `t_s` with the contact flags and step-mean
    /// forces (N) at its end. Extra or missing points are ignored.
    pub fn after_step(&mut self, t_s: f64, in_contact: &[bool], force_n: &[f64]) {
        for i in 0..self.contact.len().min(in_contact.len()) {
            let had_force = force_n.get(i).is_some_and(|q| *q > 0.0);
            let phase = classify(self.contact[i], in_contact[i], had_force);
            match phase {
                ContactPhase::Impact => {
                    self.impacts[i] += 1;
                    self.event[i] = Some((phase, t_s));
                    self.flight_s[i] = self.last_release_s[i].map(|r| t_s - r);
                    self.last_impact_s[i] = Some(t_s);
                }
                ContactPhase::Release => {
                    self.releases[i] += 1;
                    self.event[i] = Some((phase, t_s));
                    self.contact_s[i] = self.last_impact_s[i].map(|a| t_s - a);
                    self.last_release_s[i] = Some(t_s);
                }
                _ => {}
            }
            // a bounce inside a step ends in flight
            self.steady[i] = if in_contact[i] {
                ContactPhase::InContact
            } else {
                ContactPhase::FreeFlight
            };
            self.contact[i] = in_contact[i];
        }
    }

    /// How long the event `e` of point `i` stays shown (s): `hold_s`, and at
    /// most [`EVENT_SHARE`] of the last whole phase of the kind it starts.
    pub fn held_s(&self, i: usize, e: ContactPhase) -> f64 {
        let follows = match e {
            ContactPhase::Impact => self.contact_s.get(i).copied().flatten(),
            ContactPhase::Release => self.flight_s.get(i).copied().flatten(),
            _ => None,
        };
        follows.map_or(self.hold_s, |d| self.hold_s.min(EVENT_SHARE * d))
    }

    /// The phase of point `i` to show at time `t_s`: a held event, else the
    /// steady phase.
    pub fn phase(&self, i: usize, t_s: f64) -> ContactPhase {
        match self.event.get(i).copied().flatten() {
            Some((e, at)) if t_s - at <= self.held_s(i, e) => e,
            _ => self
                .steady
                .get(i)
                .copied()
                .unwrap_or(ContactPhase::FreeFlight),
        }
    }

    /// Impacts counted so far for point `i`.
    pub fn impacts(&self, i: usize) -> u64 {
        self.impacts.get(i).copied().unwrap_or(0)
    }
    /// Releases counted so far for point `i`.
    pub fn releases(&self, i: usize) -> u64 {
        self.releases.get(i).copied().unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Scene, Simulation};

    #[test]
    fn the_table_of_phases() {
        use ContactPhase::*;
        assert_eq!(classify(false, false, false), FreeFlight);
        assert_eq!(classify(false, true, false), Impact);
        assert_eq!(classify(false, true, true), Impact);
        assert_eq!(classify(false, false, true), Impact);
        assert_eq!(classify(true, true, true), InContact);
        assert_eq!(classify(true, false, false), Release);
    }

    #[test]
    fn events_are_held_then_the_steady_phase_shows() {
        let mut t = PhaseTracker::new(2, 0.01);
        t.after_step(0.001, &[false, false], &[0.0, 0.0]);
        assert_eq!(t.phase(0, 0.001), ContactPhase::FreeFlight);
        t.after_step(0.002, &[true, false], &[5.0, 0.0]);
        assert_eq!(t.phase(0, 0.002), ContactPhase::Impact);
        assert_eq!(t.phase(1, 0.002), ContactPhase::FreeFlight);
        t.after_step(0.003, &[true, false], &[5.0, 0.0]);
        assert_eq!(t.phase(0, 0.011), ContactPhase::Impact);
        assert_eq!(t.phase(0, 0.0125), ContactPhase::InContact);
        t.after_step(0.02, &[false, false], &[0.0, 0.0]);
        assert_eq!(t.phase(0, 0.02), ContactPhase::Release);
        assert_eq!(t.phase(0, 0.031), ContactPhase::FreeFlight);
        assert_eq!((t.impacts(0), t.releases(0)), (1, 1));
        // out-of-range point: free flight, no panic
        assert_eq!(t.phase(9, 0.0), ContactPhase::FreeFlight);
    }

    /// Played at the classroom's slow motion, the paper preset's points
    /// land and leave every few milliseconds: the four phases must each be
    /// shown a visible share of the run, not only IMPACT and RELEASE.
    #[test]
    fn every_phase_is_shown_for_a_share_of_a_fast_bouncing_run() {
        for (preset, text) in [
            (
                "paper",
                include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            ),
            (
                "three_points",
                include_str!(concat!(
                    env!("CARGO_MANIFEST_DIR"),
                    "/presets/three_points.ron"
                )),
            ),
        ] {
            let mut scene = Scene::parse(text, preset).unwrap();
            scene.duration_s = scene.duration_s.min(0.15);
            let p = scene.num_points();
            // 0.6 s of wall time at 0.05x and at 0.01x
            for hold_s in [0.6 * 0.05, 0.6 * 0.01] {
                let mut sim = Simulation::from_scene(&scene).unwrap();
                let mut tr = PhaseTracker::new(p, hold_s);
                let mut shown = [0u64; 4];
                let mut total = 0u64;
                while !sim.finished() {
                    sim.step().unwrap();
                    tr.after_step(sim.time_s(), sim.in_contact(), sim.force_n());
                    if sim.time_s() < scene.ramp_s {
                        continue;
                    }
                    for i in 0..p {
                        let k = match tr.phase(i, sim.time_s()) {
                            ContactPhase::FreeFlight => 0,
                            ContactPhase::Impact => 1,
                            ContactPhase::InContact => 2,
                            ContactPhase::Release => 3,
                        };
                        shown[k] += 1;
                        total += 1;
                    }
                }
                let share: Vec<f64> = shown.iter().map(|&n| n as f64 / total as f64).collect();
                for (k, name) in ["free flight", "impact", "in contact", "release"]
                    .iter()
                    .enumerate()
                {
                    assert!(
                        share[k] >= 0.05,
                        "{preset}, hold {hold_s} s: {name} shown {:.3} of the run ({share:?})",
                        share[k]
                    );
                }
            }
        }
    }

    /// Over a run, impacts and releases alternate per point, and counting
    /// the contact flag's rising edges independently gives the same impacts
    /// (bounces inside a step excepted, counted separately).
    #[test]
    fn impacts_match_rising_edges_of_the_contact_flag() {
        let scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three",
        )
        .unwrap();
        let mut sim = Simulation::from_scene(&scene).unwrap();
        let mut tr = PhaseTracker::new(3, 0.0);
        let mut prev = [false; 3];
        let mut rising = [0u64; 3];
        let mut bounces = [0u64; 3];
        for _ in 0..20_000 {
            sim.step().unwrap();
            for i in 0..3 {
                let c = sim.in_contact()[i];
                rising[i] += u64::from(!prev[i] && c);
                bounces[i] += u64::from(!prev[i] && !c && sim.force_n()[i] > 0.0);
                prev[i] = c;
            }
            tr.after_step(sim.time_s(), sim.in_contact(), sim.force_n());
        }
        for i in 0..3 {
            assert!(rising[i] > 0, "point {i} never landed");
            assert_eq!(tr.impacts(i), rising[i] + bounces[i]);
            let open = u64::from(prev[i]);
            assert_eq!(tr.releases(i) + open, rising[i]);
        }
    }
}
