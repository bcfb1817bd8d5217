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
    /// Every phase, the events first: the order in which counts of points
    /// per phase are shown.
    pub const ALL: [ContactPhase; 4] = [
        ContactPhase::Impact,
        ContactPhase::Release,
        ContactPhase::InContact,
        ContactPhase::FreeFlight,
    ];

    /// [`ContactPhase::label`] as shown beside a point or a count: the
    /// events (impact, release) in capitals.
    pub fn shown(self) -> String {
        if self.is_event() {
            self.label().to_uppercase()
        } else {
            self.label().to_string()
        }
    }

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
