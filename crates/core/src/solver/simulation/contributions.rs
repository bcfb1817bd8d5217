//! Per-mode contributions to a point's displacement (classroom
//! "mode bars"): `u_i = Σ_k u_ik`, `u_ik = Σ_{s of mode k} a_s[i] x_s`.
//! The displacement has no static or road part: the tyre starts at rest and
//! `u` is the modal response to the contact forces alone.

use super::Simulation;

impl Simulation {
    /// Number of modes of the modal model in use.
    pub fn num_modes(&self) -> usize {
        self.tables.basis.modes.len()
    }

    /// Writes into `out` (length >= `num_modes()`) how much each mode adds
    /// to the displacement of point `i` now (m). Allocation-free. Entries past
    /// `num_modes()` are left alone; a point index out of range writes zeros.
    pub fn mode_displacement_m(&self, i: usize, out: &mut [f64]) {
        let nm = self.tables.basis.modes.len().min(out.len());
        out[..nm].fill(0.0);
        if i >= self.tables.p {
            return;
        }
        let ns = self.tables.basis.stored_states();
        let a = &self.tables.basis.out[i * ns..(i + 1) * ns];
        for ((&k, &a_s), &x_s) in self
            .tables
            .basis
            .mode_of_state
            .iter()
            .zip(a)
            .zip(&self.state.modal.x)
        {
            if k < nm {
                out[k] += a_s * x_s;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::Simulation;

    fn check_sum(text: &str, steps: usize) {
        let scene = crate::solver::test_problem::problem(text);
        let mut sim = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        let nm = sim.num_modes();
        assert_eq!(nm, scene.modes.len());
        let mut c = vec![0.0; nm];
        let mut worst = 0.0f64;
        let mut largest = 0.0f64;
        for _ in 0..steps {
            sim.step().unwrap();
            for i in 0..sim.num_points() {
                sim.mode_displacement_m(i, &mut c);
                let sum: f64 = c.iter().sum();
                let u = sim.displacement_m()[i];
                worst = worst.max((sum - u).abs());
                largest = largest.max(u.abs());
            }
        }
        assert!(largest > 1e-5, "the run never moved: {largest}");
        assert!(
            worst <= 1e-12 * largest.max(1e-6),
            "sum differs by {worst} m"
        );
    }

    #[test]
    fn contributions_sum_to_the_displacement() {
        check_sum(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/single_mode.ron"
            )),
            3000,
        );
        check_sum(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/three_points.ron"
            )),
            3000,
        );
    }

    #[test]
    fn a_mode_with_zero_shape_contributes_nothing() {
        let text = include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/three_points.ron"
        ))
        .replace("shape: [0.3, 0.0, -0.3]", "shape: [0.0, 0.0, 0.0]")
        // two modes cannot hold three points rigidly: use tread springs
        .replace(
            "contact_scheme: Located,",
            "contact: Compliant(stiffness_n_m: [2e6]),",
        );
        let scene = crate::solver::test_problem::problem(&text);
        let mut sim = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        let mut c = vec![0.0; 3];
        let mut other = 0.0f64;
        for _ in 0..3000 {
            sim.step().unwrap();
            for i in 0..3 {
                sim.mode_displacement_m(i, &mut c);
                assert_eq!(c[1], 0.0);
                other = other.max(c[0].abs());
            }
        }
        assert!(other > 1e-5);
    }

    #[test]
    fn single_mode_contribution_is_the_modal_coordinate_times_residue() {
        // one point, one mode, residue 0.1: the basis term is a = 0.1 (shape
        // of a 1x1 residue by SVD: a b = 0.1), so u = contribution exactly
        let scene = crate::solver::test_problem::problem(include_str!(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../presets/single_mode.ron"
        )));
        let sim = Simulation::new(&scene, crate::SolverOptions::default()).unwrap();
        let mut c = [7.0, 7.0];
        sim.mode_displacement_m(0, &mut c);
        assert_eq!(c, [0.0, 7.0]);
        sim.mode_displacement_m(5, &mut c);
        assert_eq!(c, [0.0, 7.0]);
    }
}
