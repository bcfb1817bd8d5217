//! Impact spikes in force plots: a rigid landing is an impulse, drawn as
//! impulse / dt, tens of kN against a rolling force of about 1 kN. Plots
//! fit their force axis to the force *without* impacts and clip the spikes
//! a margin above it, marking them (the visualiser's "clip impact spikes",
//! the exported and command-line figures).

/// The level at which a force plot clips impact spikes: a margin above the
/// range `(lo, hi)` of the force without impacts (N).
pub fn clip_level((lo, hi): (f64, f64)) -> f64 {
    hi + 0.1 * (hi - lo).max(1.0)
}

/// The impact part (N, impulse / dt) of point `i`'s step-mean force `q[i]`
/// under the paper's contact scheme, which locates no impacts: the first
/// step of a contact absorbs the landing point's momentum as one huge
/// step-mean force, and the points already in contact feel it through the
/// tyre in the same step.
///
/// Rule: a step is a *landing step* when some point's force turns positive
/// after a step without force (`q[k] > 0`, `q_prev[k] <= 0`). In a landing
/// step, each point's rise over its previous step's force,
/// `max(q[i] - q_prev[i], 0)`, is the impact's impulse / dt (so the force
/// without impacts holds its previous value, `min(q[i], q_prev[i])`); in
/// other steps the impact part is zero.
pub fn paper_impact_n(q: &[f64], q_prev: &[f64], i: usize) -> f64 {
    if is_landing_step(q, q_prev) {
        rise_n(q, q_prev, i)
    } else {
        0.0
    }
}

/// Whether some point's force turns positive after a step without force
/// (the landing step of [`paper_impact_n`]).
pub fn is_landing_step(q: &[f64], q_prev: &[f64]) -> bool {
    q.iter().zip(q_prev).any(|(&a, &b)| a > 0.0 && b <= 0.0)
}

/// `max(q[i] - q_prev[i], 0)` (N); 0 for a point out of range.
pub fn rise_n(q: &[f64], q_prev: &[f64], i: usize) -> f64 {
    match (q.get(i), q_prev.get(i)) {
        (Some(&a), Some(&b)) => (a - b).max(0.0),
        _ => 0.0,
    }
}

/// Per step, the impact part of every point's step-mean force (N): the
/// located impacts' impulses / dt, or under the paper's rigid scheme the
/// landing rule of [`paper_impact_n`]; zero for compliant contact.
#[derive(Debug, Clone, Default)]
pub struct ImpactTracker {
    q_prev: Vec<f64>,
}

impl ImpactTracker {
    /// A tracker starting from `sim`'s current forces (the step before the
    /// next one recorded).
    pub fn start(sim: &tirecontact_core::Simulation) -> Self {
        ImpactTracker {
            q_prev: sim.force_n().to_vec(),
        }
    }

    /// A tracker of `p` points whose step before the next one had no force.
    pub fn zeros(p: usize) -> Self {
        ImpactTracker {
            q_prev: vec![0.0; p],
        }
    }

    /// Starts again from `sim`'s current forces, in the tracker's own buffer.
    pub fn restart(&mut self, sim: &tirecontact_core::Simulation) {
        self.q_prev.clear();
        self.q_prev.extend_from_slice(sim.force_n());
    }

    /// Each point's impact part of the step just taken into `parts`: what
    /// [`ImpactTracker::add_step`] adds to zeros, the same numbers, without
    /// clearing `parts` first or dividing where there is no impulse.
    pub fn step_parts(&mut self, sim: &tirecontact_core::Simulation, parts: &mut [f64]) {
        let scene = sim.problem();
        if scene.contact_scheme == tirecontact_io::scene::ContactScheme::Paper
            && scene.contact.is_rigid()
        {
            parts.fill(0.0);
            return self.add_step(sim, parts);
        }
        let dt = sim.dt_s();
        let impulses = sim.impact_impulse_ns();
        for (i, s) in parts.iter_mut().enumerate() {
            // (`0 + j / dt` as `add_step` adds it: the same sign of zero)
            *s = match impulses.get(i) {
                Some(&j) if j != 0.0 => 0.0 + j / dt,
                _ => 0.0,
            };
        }
    }

    /// Adds each point's impact part of the step just taken to `sums`.
    pub fn add_step(&mut self, sim: &tirecontact_core::Simulation, sums: &mut [f64]) {
        let scene = sim.problem();
        let q = sim.force_n();
        if scene.contact_scheme == tirecontact_io::scene::ContactScheme::Paper
            && scene.contact.is_rigid()
        {
            self.q_prev.resize(q.len(), 0.0);
            if is_landing_step(q, &self.q_prev) {
                for (i, s) in sums.iter_mut().enumerate() {
                    *s += rise_n(q, &self.q_prev, i);
                }
            }
            self.q_prev.copy_from_slice(q);
        } else {
            let dt = sim.dt_s();
            for (s, j) in sums.iter_mut().zip(sim.impact_impulse_ns()) {
                *s += j / dt;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clip_level_is_a_margin_above_the_rolling_force() {
        assert_eq!(clip_level((0.0, 1000.0)), 1100.0);
        // a flat force still gets a margin of at least 0.1 N
        assert_eq!(clip_level((5.0, 5.0)), 5.1);
    }

    #[test]
    fn a_landing_step_counts_each_rise_as_impact() {
        // no point lands: no impact, whatever the rises
        assert_eq!(paper_impact_n(&[5.0, 9.0], &[4.0, 1.0], 1), 0.0);
        // point 0 lands: its whole force and point 1's rise are impact
        assert_eq!(paper_impact_n(&[300.0, 90.0], &[0.0, 40.0], 0), 300.0);
        assert_eq!(paper_impact_n(&[300.0, 90.0], &[0.0, 40.0], 1), 50.0);
        // a point whose force fell keeps it
        assert_eq!(paper_impact_n(&[300.0, 30.0], &[0.0, 40.0], 1), 0.0);
        assert_eq!(paper_impact_n(&[300.0], &[0.0], 3), 0.0);
    }

    /// `step_parts` writes what `add_step` adds to zeros, bit for bit, on
    /// the paper's scheme and on the located one with impacts.
    #[test]
    fn step_parts_are_what_add_step_adds_to_zeros() {
        for preset in ["three_points.ron", "paper.ron"] {
            let scene = tirecontact_io::scene::Scene::load(
                &std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../presets"))
                    .join(preset),
            )
            .unwrap();
            use tirecontact_io::SceneSimulation as _;
            let mut sim = tirecontact_core::Simulation::from_scene(&scene).unwrap();
            let p = sim.num_points();
            let (mut a, mut b) = (ImpactTracker::default(), ImpactTracker::default());
            let (mut added, mut set) = (vec![0.0; p], vec![7.0; p]);
            let mut impacts = 0;
            for _ in 0..20_000 {
                sim.step().unwrap();
                added.fill(0.0);
                a.add_step(&sim, &mut added);
                b.step_parts(&sim, &mut set);
                for i in 0..p {
                    assert_eq!(added[i].to_bits(), set[i].to_bits(), "{preset}, point {i}");
                }
                impacts += added.iter().filter(|&&x| x > 0.0).count();
            }
            assert!(impacts > 0, "{preset}: the run has impacts");
        }
    }
}
