//! Switches for the work a scene does not need ([`SolverOptions`]).

use crate::solver::problem::Problem;

/// Switches for the work a scene does not need; all on by default. Turning
/// one off gives the "before" of a benchmark; results agree to round-off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Keep one state per rank term of each residue (rank 1 for a mode
    /// shape) instead of one per (mode, source).
    pub rank_reduction: bool,
    /// Reuse the LU factorisation of the full-step contact operator while
    /// the active set is unchanged.
    pub reuse_factorisation: bool,
    /// Residual flexibility (off by default; changes results): modes above
    /// this frequency (Hz) are dropped from the convolution and replaced by
    /// their static contribution `Σ A_k / ω_k²` (their `G(0)`), applied to
    /// the contact forces as a quasi-static compliance `C`. The static term
    /// has no mass, so a landing on it takes no impulse (its velocity
    /// mismatch becomes a force rate `Δv / C`); a rigid impact on the kept
    /// modes is left only where `C` is singular on the points on the road.
    /// The model is then softer than the full one at landings: meant for
    /// scenes that stay on the road (see the bench's "Residual flexibility"
    /// table; with impacts both contact schemes agree with each other but
    /// not with the full model).
    pub residual_above_hz: Option<f64>,
    /// Relative cut of the rank reduction: the rank terms (eigen or SVD) of
    /// a mode's residue below `rank_tolerance` of the largest are dropped. `None`
    /// (default): [`IDENTIFIED_RANK_TOLERANCE`] for a model identified by
    /// LSCE (a ring tyre), [`crate::model::convolution::EXACT_RANK_TOLERANCE`]
    /// (every term, exact to round-off) for modes given in the scene, which
    /// are taken as they are. Identified residues of the ring tyre are
    /// rank 2 (its cos/sin mode pairs) plus fit noise 1e-6 to 1e-13 of
    /// σ_max; keeping the noise costs 2.5x the states (paper preset: 65
    /// instead of 26) for a change of each residue below 1e-5 of its norm,
    /// far below the identification's own error (|G| error 1.9e-2 on the
    /// paper preset). `Some(t)`: the cut `t` for any model. Ignored without
    /// `rank_reduction`. See [`SolverOptions::rank_tolerance_for`].
    pub rank_tolerance: Option<f64>,
    /// Take a step that keeps the same points on the road and locates no
    /// event without the event loop's bookkeeping (`Located` scheme with
    /// rigid contact, see `simulation/steady.rs`; compliant contact, see
    /// `simulation/compliant.rs`). Bit-identical results.
    pub steady_path: bool,
    /// Points on the road from which the contact solves take the methods
    /// of large active sets (method §4.5, "Large active sets"): the
    /// full-step inverse kept up to date as points join and leave
    /// (bordered updates, `O(|S|²)` each, checked by the backward error of
    /// the solve), and, with tread springs, sub-steps solved by GMRES
    /// through the modal states instead of filling and factorising their
    /// `2|S|` system. They agree with the direct solves to round-off
    /// (`usize::MAX`: never; smaller sets keep the direct solves, bit for
    /// bit).
    pub large_set_from: usize,
    /// With tread springs, the points on the road from which the methods
    /// of large sets apply (the smaller of this and
    /// [`SolverOptions::large_set_from`]): a step with events then borders
    /// the kept inverse of its trial (method §4.6, "Events in one solve")
    /// instead of factorising each new set, which pays from a few points
    /// on a rough road (`docs/performance.md`, "Events in one solve").
    pub compliant_large_set_from: usize,
    /// Points on the road from which a sub-step of tread springs (between
    /// events, method §4.6) is solved by GMRES through the modal states
    /// (`O(|S| K)` per product, about four products a solve) instead of
    /// filling its `2|S|` system (`|S|² K` products) and factorising it,
    /// as the large sets' sub-steps are (method §4.5). On a rough road,
    /// where a step has an event or more, that fill is most of a step.
    /// The answers agree with the direct solve to round-off (`usize::MAX`:
    /// never; the smaller of this and
    /// [`SolverOptions::large_set_from`] applies).
    pub iterative_sub_from: usize,
    /// Threads of the simulation's large kernels (1, the default: the
    /// calling thread alone, no worker started). With more, the
    /// simulation keeps `threads - 1` workers and splits a kernel over
    /// them when it has at least
    /// [`PARALLEL_FROM`](crate::base::threads::PARALLEL_FROM)
    /// multiply-adds: the projection of the points' values, the free
    /// prediction and the forces into the states, the large active sets'
    /// inverse (per step), the influence and velocity-jump tables (at
    /// set-up). Each is split into contiguous ranges of rows or states
    /// fixed by its size and the thread count, every output element
    /// computed as on one thread: results are bit-identical for any
    /// count. The projection is split from `P K` = 3·10⁴ (points times
    /// states); 2 threads gain 10-40 % per step from `P K` ≈ 6·10⁴ and
    /// 1.4-1.7x from 10⁵ (`docs/performance.md`, "Threads"); smaller
    /// scenes run as on one thread.
    pub threads: usize,
    /// Multiply-adds of a kernel call from which it is split over the
    /// [`SolverOptions::threads`] (default
    /// [`PARALLEL_FROM`](crate::base::threads::PARALLEL_FROM), where the
    /// second thread starts to save more than the hand-over costs; 1:
    /// every kernel, as the tests of the partition run them). Ignored on
    /// one thread.
    pub parallel_from_madds: usize,
    /// Solve an inelastic impact as one complementarity problem over every
    /// point at the road at that instant (method §4.4, "Several events at
    /// one instant"): a point thrown off leaves moving away from the road,
    /// points landing together take one impact, and a point thrown off a
    /// third time in a step while moving away slowly stays on ("Zeno
    /// sequences"). Off: the points on the road are thrown off one at a
    /// time, most pulling first, and a point thrown off while still moving
    /// into the road lands again as a separate event. They agree bit for
    /// bit wherever neither difference arises, and converge to the same
    /// limit as `dt` falls.
    pub joint_impacts: bool,
    /// Take the landings and releases of tread springs inside the step's
    /// one full-step solve (method §4.6, "Events in one solve"; a landing
    /// point's force on the rest of the step, a released point's trial
    /// force up to its release as a known load) instead of splitting the
    /// step into sub-steps at each event. The two agree to `O(dt²)`; off,
    /// every event splits the step as with rigid contact. It starts from
    /// the steady path's trial: without [`SolverOptions::steady_path`],
    /// events take the sub-steps.
    pub merged_events: bool,
}

/// The rank cut of identified models (see [`SolverOptions::rank_tolerance`]):
/// residue terms below 1e-5 of the largest are identification noise.
pub const IDENTIFIED_RANK_TOLERANCE: f64 = 1e-5;

/// Default of [`SolverOptions::large_set_from`]: from 24 points on the
/// road (a 48-unknown system) the updates cost less than a refactorisation
/// by a factor `n / 6` and the sub-step solve through the states less than
/// filling its blocks.
pub const LARGE_SET_FROM: usize = 24;

/// Default of [`SolverOptions::compliant_large_set_from`]: from 8 points on
/// the road, as the GMRES sub-steps ([`ITERATIVE_SUB_FROM`]).
pub const COMPLIANT_LARGE_SET_FROM: usize = 8;

/// Default of [`SolverOptions::iterative_sub_from`]: from this many points
/// on the road a compliant sub-step's GMRES solve through the states costs
/// less than filling and factorising its system
/// (`docs/performance.md`, "The shipped patch presets").
pub const ITERATIVE_SUB_FROM: usize = 8;

impl SolverOptions {
    /// The relative rank cut used for `problem` (see
    /// [`SolverOptions::rank_tolerance`]): identified modes are cut at
    /// [`IDENTIFIED_RANK_TOLERANCE`], exact ones at
    /// [`EXACT_RANK_TOLERANCE`](crate::model::convolution::EXACT_RANK_TOLERANCE).
    pub fn rank_tolerance_for(&self, problem: &Problem) -> f64 {
        self.rank_tolerance_of(problem.modes_identified)
    }

    /// The relative rank cut of modes identified from responses or given
    /// exactly (see [`SolverOptions::rank_tolerance_for`]).
    pub fn rank_tolerance_of(&self, modes_identified: bool) -> f64 {
        self.rank_tolerance.unwrap_or(if modes_identified {
            IDENTIFIED_RANK_TOLERANCE
        } else {
            crate::model::convolution::EXACT_RANK_TOLERANCE
        })
    }
}

impl Default for SolverOptions {
    fn default() -> Self {
        SolverOptions {
            rank_reduction: true,
            reuse_factorisation: true,
            residual_above_hz: None,
            rank_tolerance: None,
            steady_path: true,
            large_set_from: LARGE_SET_FROM,
            compliant_large_set_from: COMPLIANT_LARGE_SET_FROM,
            iterative_sub_from: ITERATIVE_SUB_FROM,
            threads: 1,
            parallel_from_madds: crate::base::threads::PARALLEL_FROM,
            joint_impacts: true,
            merged_events: true,
        }
    }
}
