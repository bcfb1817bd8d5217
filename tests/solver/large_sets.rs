//! The methods of large active sets (bordered updates, GMRES sub-steps,
//! rows projected ahead) against the direct solves on the scaling study's
//! scenes.

use crate::support::Gap;
use tirecontact::analysis::bench::scaling::{Regime, scaling_scene};
use tirecontact::{PreparedModel, Simulation, SolverOptions};

/// The active rows a fused full step projects ahead, from its end
/// state, are the next prediction's to the bit: a run that reads them
/// and the same run made to project every step's rows afresh (its
/// rows ahead forgotten before each step) give bit-identical states,
/// forces and end values, on rough roads (landings and releases inside
/// steps, releases at once), one and two threads, while the rows
/// ahead were read on most steps.
#[test]
fn rows_projected_ahead_are_the_next_predictions_bit_for_bit() {
    for (p, k, regime, threads) in [
        (30, 10, Regime::Tread, 1),
        (60, 25, Regime::Tread, 1),
        (100, 40, Regime::Patch, 1),
        (100, 40, Regime::Patch, 2),
    ] {
        let mut scene = scaling_scene(p, k, regime);
        scene.road = tirecontact::model::road::Road::Sine {
            amplitude_m: 2e-4,
            wavelength_m: 0.05,
        };
        scene.duration_s = 0.03;
        let model = PreparedModel::of(&scene).unwrap();
        let options = SolverOptions {
            large_set_from: 2,
            threads,
            parallel_from_madds: 0,
            ..SolverOptions::default()
        };
        let mut a = Simulation::new(model.problem(), options).unwrap();
        let mut b = Simulation::new(model.problem(), options).unwrap();
        let (mut read_ahead, mut steps) = (0, 0);
        while !a.finished() {
            read_ahead += a.stages().rows_ahead_ready() as u32;
            b.stages().forget_rows_ahead();
            a.step().unwrap();
            b.step().unwrap();
            steps += 1;
            let bits = |x: &[f64]| x.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
            assert_eq!(
                bits(a.stages().modal_states().0),
                bits(b.stages().modal_states().0),
                "{p} x {k}, step {steps}"
            );
            assert_eq!(
                bits(a.stages().modal_states().1),
                bits(b.stages().modal_states().1),
                "{p} x {k}, step {steps}"
            );
            assert_eq!(
                bits(a.force_n()),
                bits(b.force_n()),
                "{p} x {k}, step {steps}"
            );
            assert_eq!(bits(a.displacement_m()), bits(b.displacement_m()));
            assert_eq!(bits(a.velocity_mps()), bits(b.velocity_mps()));
        }
        assert!(a.stats().events > 0, "{p} x {k}: no event");
        assert!(
            2 * read_ahead > steps,
            "{p} x {k}: rows ahead read on {read_ahead} of {steps} steps"
        );
    }
}

/// The same compliant scenes run with the direct solves and with the
/// methods of large sets (from 2 points on the road) agree to a
/// relative 1e-9 in displacements and step forces over every step,
/// while the updates, the GMRES solves and their checks all ran.
#[test]
fn large_set_methods_agree_with_the_direct_solves() {
    for (p, k, regime) in [
        (30, 10, Regime::Tread),
        (45, 60, Regime::Tread),
        (60, 25, Regime::Tread),
        (60, 25, Regime::Rigid),
        (90, 40, Regime::Rigid),
    ] {
        // a rough road: points land and leave inside steps
        let mut scene = scaling_scene(p, k, regime);
        scene.road = tirecontact::model::road::Road::Sine {
            amplitude_m: 5e-4,
            wavelength_m: 0.03,
        };
        // (rigid: the ramp, where the large sets are; later, repeated
        // impacts amplify round-off differences by about ten decades
        // over 0.03 s, in both solves alike)
        scene.duration_s = if regime == Regime::Rigid { 0.01 } else { 0.04 };
        let model = PreparedModel::of(&scene).unwrap();
        // (events by sub-steps in both: the merged event step is the
        // direct solves' alone)
        let sub_steps = SolverOptions {
            merged_events: false,
            ..SolverOptions::default()
        };
        let direct = SolverOptions {
            large_set_from: usize::MAX,
            compliant_large_set_from: usize::MAX,
            iterative_sub_from: usize::MAX,
            ..sub_steps
        };
        let large = SolverOptions {
            large_set_from: 2,
            ..sub_steps
        };
        let mut a = Simulation::new(model.problem(), direct).unwrap();
        let mut b = Simulation::new(model.problem(), large).unwrap();
        // differences against the largest values of the run
        let (mut u, mut q) = (Gap::default(), Gap::default());
        while !a.finished() {
            a.step().unwrap();
            b.step().unwrap();
            u.add(a.displacement_m(), b.displacement_m());
            q.add(a.force_n(), b.force_n());
        }
        let (worst_u, worst_q) = (u.relative(), q.relative());
        let (sa, sb) = (a.stats(), b.stats());
        eprintln!(
            "P {p}, K {k}: worst relative difference u {worst_u:.1e}, q {worst_q:.1e}; \
             events {} / {}, factorisations {} / {}, updates {}, refusals {}, \
             GMRES applications {}, fallbacks {}",
            sa.events,
            sb.events,
            sa.factorisations,
            sb.factorisations,
            sb.contact_updates,
            sb.update_refusals,
            sb.krylov_applications,
            sb.krylov_fallbacks
        );
        assert!(
            worst_u < 1e-9 && worst_q < 1e-9,
            "P {p}, K {k}: u {worst_u:e}, q {worst_q:e}"
        );
        assert_eq!(sa.events, sb.events, "P {p}, K {k}: events");
        assert!(sb.contact_updates > 0, "{sb:?}");
        // (GMRES serves the sub-steps of tread springs only)
        let tread = regime == Regime::Tread;
        assert_eq!(sb.krylov_applications > 0, tread, "{sb:?}");
        assert!(sb.factorisations < sa.factorisations, "{sa:?} {sb:?}");
    }
}

/// The paper's scheme (method §4.3) on a rigid patch: its active set
/// starts from every point's free prediction, so a full step whose
/// prediction leaves the projection to a large set's solve must still
/// see every point's; with the methods of large sets it agrees with the
/// direct solves as the located scheme does.
#[test]
fn the_paper_scheme_on_large_sets_agrees_with_the_direct_solves() {
    for (p, k) in [(30, 60), (45, 90)] {
        let mut scene = scaling_scene(p, k, Regime::Rigid);
        scene.contact_scheme = tirecontact::scene::ContactScheme::Paper;
        scene.road = tirecontact::model::road::Road::Sine {
            amplitude_m: 5e-4,
            wavelength_m: 0.03,
        };
        scene.duration_s = 0.01;
        let model = PreparedModel::of(&scene).unwrap();
        // (events by sub-steps in both: the merged event step is the
        // direct solves' alone)
        let sub_steps = SolverOptions {
            merged_events: false,
            ..SolverOptions::default()
        };
        let direct = SolverOptions {
            large_set_from: usize::MAX,
            compliant_large_set_from: usize::MAX,
            iterative_sub_from: usize::MAX,
            ..sub_steps
        };
        let large = SolverOptions {
            large_set_from: 2,
            ..sub_steps
        };
        let mut a = Simulation::new(model.problem(), direct).unwrap();
        let mut b = Simulation::new(model.problem(), large).unwrap();
        let (mut u, mut steps) = (Gap::default(), 0);
        while !a.finished() {
            a.step().unwrap();
            b.step().unwrap();
            steps += 1;
            u.add(a.displacement_m(), b.displacement_m());
            let on = |s: &Simulation| s.force_n().iter().filter(|&&q| q > 0.0).count();
            assert_eq!(
                on(&a),
                on(&b),
                "P {p}, K {k}, step {steps}: points pressing"
            );
        }
        assert!(b.stats().contact_updates > 0 || b.stats().factorisations > 0);
        assert!(u.relative() < 1e-9, "P {p}, K {k}: u {:e}", u.relative());
    }
}
