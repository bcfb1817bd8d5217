//! The three parts of a [`Simulation`](super::Simulation):
//!
//! - [`SimTables`]: built once from the problem, the options and
//!   `dt` (method §3-4), never changed;
//! - [`SimState`]: the run at the current time, what a snapshot or a
//!   restart needs;
//! - [`Scratch`]: the buffers a step works in, sized once so that the step
//!   allocates nothing (method §4.5, "Memory"): those every scheme shares,
//!   and a part per scheme's own solves ([`DenseScratch`], [`EventScratch`],
//!   [`LargeSetScratch`], [`RowsAhead`]).
//!
//! The full-step factorisations kept by active set (`factor_cache.rs`) are
//! a fourth, derived part: a function of the tables and the active set
//! alone, rebuilt bit for bit when missing.

use super::columns::{add_set_response, column_response};
use super::merged::MergedScratch;
use super::residual::{add_residual, split_residual};
use super::{RunStats, SolverOptions};
use crate::base::threads::Threads;
use crate::model::convolution::{Influence, ModalBasis, ModalState, StepTable, TauInterp};
use crate::solver::error::BuildError;
use crate::solver::problem::Problem;
use crate::solver::simulation::contact::DenseSolver;
use crate::solver::simulation::contact::krylov::Gmres;
use std::ops::Range;

/// Krylov vectors kept between GMRES restarts.
const GMRES_RESTART: usize = 30;

/// The most values (f64) the interpolated influence columns of the merged
/// event step may hold (`4 P² (M − 1)`, 32 MB): about 390 points at `M` = 8.
const TAU_COLUMN_BUDGET: usize = 1 << 22;

/// What a simulation builds once from the problem, the options and
/// `dt`, and never changes: the modal basis and its exact step (method
/// §3.3-3.4), the full-step influence of the Gauss-point forces (§4.3), the
/// velocity jump of an impulse (§4.4), the residual and tread compliances
/// (§4.6-4.7). Every stage of a step reads them; none writes them.
pub(super) struct SimTables {
    /// Rank terms of the kept modes (method §3.4).
    pub basis: ModalBasis,
    /// Exact step weights over `dt_s` (method §3.3).
    pub full: StepTable,
    /// Influence of the Gauss-point forces on the end values over `dt_s`
    /// (method §4.3 step 3), the residual compliance included.
    pub full_inf: Influence,
    /// The same influence by source column: for point `j`, the columns `j`
    /// of `gx1`, `gx2`, `gv1`, `gv2` one after the other (`4P` values), so
    /// that the end values run over contiguous memory.
    pub full_inf_cols: Vec<f64>,
    /// Velocity jump per unit impulse, `g'(0+) = Σ_k A_k` (m/s per N·s,
    /// P x P row-major, method §4.4 "Impact").
    pub jump: Vec<f64>,
    /// Its transpose (`jump_t[j * P + i] = jump[i * P + j]`): the velocity
    /// change of every point from an impulse at `j` in contiguous memory.
    pub jump_t: Vec<f64>,
    /// Residual compliance of the dropped modes (m/N, P x P row-major,
    /// method §4.7); empty: all modes in the convolution.
    pub residual: Vec<f64>,
    /// Tread stiffness per point (N/m) of compliant contact (method §4.6);
    /// empty: rigid.
    pub tread_k_n_m: Vec<f64>,
    /// `a_s[i] b_s[i]` per point and state (`P x ns`, point-major) of
    /// compliant contact: the terms of a point's own influence block, whose
    /// weighted sums precondition the iterative sub-step solves
    /// (`large.rs`); empty: rigid.
    pub own_terms: Vec<f64>,
    /// The Gauss-point weights of a step of any `τ ≤ dt` and their
    /// influence columns, interpolated in `τ` (method §4.6, "Events in one
    /// solve"); `None` unless tread-spring events are merged, or when no
    /// interpolant meets its tolerance.
    pub tau_interp: Option<TauInterp>,
    /// Heights `h_i` of the points above the road (m, `problem.points[i].h_m`).
    pub h_m: Vec<f64>,
    /// Number of contact points `P`.
    pub p: usize,
    /// The time step (s).
    pub dt_s: f64,
    /// Events in one step after which the rest of the step takes the
    /// step-end rule (`4P + 16`, method §4.4 "Cascades").
    pub max_events: u32,
    /// `problem.num_steps()` (duration and `dt` are fixed for the
    /// simulation's life).
    pub num_steps: u64,
    pub options: SolverOptions,
}

impl SimTables {
    /// The tables of `problem` with its modes, the `P x P` ones computed
    /// on `threads` (the same values for any number). Fails only if a
    /// mode's residue cannot be split into rank terms (method §3.4) or the
    /// residual compliance does not apply (method §4.7).
    pub fn new(
        problem: &Problem,
        options: SolverOptions,
        threads: &Threads,
    ) -> Result<Self, BuildError> {
        let p = problem.num_points();
        let (basis, residual) = tables_basis(problem, problem.modes.to_vec(), options)?;
        let full = StepTable::new(&basis, problem.dt_s);
        let mut full_inf = Influence::new_on(&basis, &full, threads);
        if !residual.is_empty() {
            add_residual(&mut full_inf, &residual, problem.dt_s);
        }
        let jump = basis.velocity_jump_on(threads);
        let jump_t = transposed(&jump, p);
        let mut full_inf_cols = Vec::with_capacity(4 * p * p);
        influence_columns(&full_inf, p, 0..p, &mut full_inf_cols);
        let tau_interp = if tau_interp_used(problem, options, &residual) {
            TauInterp::new(&basis, problem.dt_s, TAU_COLUMN_BUDGET)
        } else {
            None
        };
        Ok(Self::assemble(
            problem,
            options,
            (basis, residual, full, tau_interp),
            full_inf,
            full_inf_cols,
            jump,
            jump_t,
        ))
    }

    fn assemble(
        problem: &Problem,
        options: SolverOptions,
        (basis, residual, full, tau_interp): (ModalBasis, Vec<f64>, StepTable, Option<TauInterp>),
        full_inf: Influence,
        full_inf_cols: Vec<f64>,
        jump: Vec<f64>,
        jump_t: Vec<f64>,
    ) -> Self {
        let p = problem.num_points();
        let tread_k_n_m = problem.contact.stiffness_per_point(p);
        let own_terms = if tread_k_n_m.is_empty() {
            Vec::new()
        } else {
            basis
                .out
                .iter()
                .zip(&basis.inp_t)
                .map(|(o, b)| o * b)
                .collect()
        };
        SimTables {
            jump,
            jump_t,
            full_inf_cols,
            full_inf,
            full,
            basis,
            residual,
            tread_k_n_m,
            own_terms,
            tau_interp,
            h_m: problem.points.iter().map(|pt| pt.h_m).collect(),
            p,
            dt_s: problem.dt_s,
            max_events: 4 * p as u32 + 16,
            num_steps: problem.num_steps(),
            options,
        }
    }

    /// The fewest points on the road that take the methods of large sets
    /// (`large.rs`): [`SolverOptions::large_set_from`], with tread springs
    /// at most [`SolverOptions::compliant_large_set_from`].
    #[inline]
    pub fn large_set_from(&self) -> usize {
        if self.compliant() {
            self.options
                .large_set_from
                .min(self.options.compliant_large_set_from)
        } else {
            self.options.large_set_from
        }
    }

    /// Whether a large active set can occur and takes the methods of
    /// `large.rs`: at least [`SimTables::large_set_from`] points.
    #[inline]
    pub fn large_sets(&self) -> bool {
        self.p >= self.large_set_from()
    }

    /// The fewest points on the road whose compliant sub-steps are solved
    /// by GMRES through the states (`large.rs`,
    /// [`SolverOptions::iterative_sub_from`]); `usize::MAX` for rigid
    /// contact, which keeps the direct sub-step solve.
    #[inline]
    pub fn iterative_sub_from(&self) -> usize {
        if self.compliant() {
            self.options.iterative_sub_from.min(self.large_set_from())
        } else {
            usize::MAX
        }
    }

    /// Whether the contact is compliant (tread springs, method §4.6).
    #[inline]
    pub fn compliant(&self) -> bool {
        !self.tread_k_n_m.is_empty()
    }

    /// The Gauss-point weights of a step of `tau_s ≤ dt` from rest into
    /// `table`: interpolated when [`SimTables::tau_interp`] is there, else
    /// exact (method §4.6, "Events in one solve").
    pub fn short_table(&self, tau_s: f64, table: &mut StepTable) {
        match &self.tau_interp {
            Some(ti) => ti.fill_gauss(&self.basis, tau_s, table),
            None => table.fill(&self.basis, tau_s),
        }
    }

    /// Adds to every point's end displacement `u` (m) and velocity `v`
    /// (m/s) the response to point `j`'s full-step Gauss-point forces
    /// `q1`, `q2` (N, method §4.3 step 3), down its contiguous influence
    /// columns (`full_inf_cols`).
    /// Four lanes through an AVX2 build where the CPU has it (no FMA: the
    /// same operations, bit-identical).
    #[inline]
    pub fn add_full_step_response(&self, j: usize, q1: f64, q2: f64, u: &mut [f64], v: &mut [f64]) {
        let p = self.p;
        let cols = &self.full_inf_cols[4 * p * j..4 * p * (j + 1)];
        #[cfg(target_arch = "x86_64")]
        {
            if std::arch::is_x86_feature_detected!("avx2") {
                #[target_feature(enable = "avx2")]
                fn wide(cols: &[f64], p: usize, q1: f64, q2: f64, u: &mut [f64], v: &mut [f64]) {
                    column_response(cols, p, 0..p, q1, q2, u, v)
                }
                // SAFETY: the CPU supports AVX2 (checked just above).
                return unsafe { wide(cols, p, q1, q2, u, v) };
            }
        }
        column_response(cols, p, 0..p, q1, q2, u, v)
    }

    /// [`SimTables::add_full_step_response`] of every point of `set` in
    /// turn, with the forces `q1[j]`, `q2[j]` indexed by point: the same
    /// values to the bit, each point's sums kept in registers over the
    /// whole set ([`add_set_response`]).
    #[inline]
    pub fn add_set_full_step_response(
        &self,
        set: &[usize],
        q1: &[f64],
        q2: &[f64],
        u: &mut [f64],
        v: &mut [f64],
    ) {
        add_set_response(&self.full_inf_cols, self.p, set, q1, q2, u, v);
    }
}

/// The modal basis of `modes` (rank terms, method §3.4) and the residual
/// compliance of the modes left out of it (method §4.7).
fn tables_basis(
    problem: &Problem,
    modes: Vec<crate::base::modal::Mode>,
    options: SolverOptions,
) -> Result<(ModalBasis, Vec<f64>), BuildError> {
    let p = problem.num_points();
    let (modes, residual) = split_residual(problem, modes, options.residual_above_hz)?;
    let basis = if options.rank_reduction {
        ModalBasis::with_rank_tolerance(&modes, p, options.rank_tolerance_for(problem)).map_err(
            |source| BuildError::Basis {
                problem: problem.name.clone(),
                source,
            },
        )?
    } else {
        ModalBasis::per_source(&modes, p)
    };
    Ok((basis, residual))
}

/// The transpose of the `P × P` row-major `m`.
fn transposed(m: &[f64], p: usize) -> Vec<f64> {
    (0..p * p).map(|k| m[(k % p) * p + k / p]).collect()
}

/// The points `js` of [`SimTables::full_inf_cols`] of an influence,
/// appended to `cols`.
fn influence_columns(g: &Influence, p: usize, js: Range<usize>, cols: &mut Vec<f64>) {
    for j in js {
        for m in [&g.gx1, &g.gx2, &g.gv1, &g.gv2] {
            cols.extend((0..p).map(|i| m[i * p + j]));
        }
    }
}

/// Multiply-adds per block of [`SimTablesBuild`]'s `P × P` tables
/// (about a millisecond of a desktop core).
const BLOCK_MADDS: usize = 1 << 21;

/// [`SimTables::new`] a stage at a time, for a caller that must return
/// between stages (a page in the browser has one thread): the basis, then
/// the step table, the influence and the velocity jump a block of rows at
/// a time, then the columns a block of points at a time. Every entry is
/// the same sum in the same order as [`SimTables::new`]'s on any number
/// of threads: the same tables to the bit.
pub(super) struct SimTablesBuild {
    options: SolverOptions,
    parts: Option<(ModalBasis, Vec<f64>, StepTable)>,
    inf: Influence,
    jump: Vec<f64>,
    jump_t: Vec<f64>,
    cols: Vec<f64>,
    /// The short-step interpolant once its weights are (a stage), and the
    /// stages of its columns done (the last one checks them).
    tau: Option<Option<TauInterp>>,
    tau_stages: usize,
    /// Rows of the influence, rows of the jump and points of the columns
    /// done so far.
    inf_rows: usize,
    jump_rows: usize,
    col_points: usize,
    /// Rows (or points) per block.
    block: usize,
}

impl SimTablesBuild {
    pub fn new(options: SolverOptions) -> Self {
        SimTablesBuild {
            options,
            parts: None,
            inf: Influence::default(),
            jump: Vec::new(),
            jump_t: Vec::new(),
            cols: Vec::new(),
            tau: None,
            tau_stages: 0,
            inf_rows: 0,
            jump_rows: 0,
            col_points: 0,
            block: 1,
        }
    }

    /// Stages left before the tables are complete (known once the basis
    /// is: until then, an estimate from the modes).
    pub fn stages_left(&self, problem: &Problem) -> usize {
        let p = problem.num_points();
        let blocks = |done: usize| (p - done).div_ceil(self.block);
        match &self.parts {
            None if self.col_points == p && p > 0 => 0,
            None => {
                let block = block_rows(p, problem.modes.len().max(1));
                let tau = if tau_interp_used(problem, self.options, &[]) {
                    self.tau_stages_left()
                } else {
                    0
                };
                1 + 3 * p.div_ceil(block) + 2 + tau
            }
            Some(_) => {
                blocks(self.inf_rows)
                    + blocks(self.jump_rows)
                    + blocks(self.col_points)
                    + self.tau_stages_left()
                    + 2
            }
        }
    }

    /// Stages left of [`SimTables::tau_interp`] (an estimate of 24 column
    /// stages before its weights are known).
    fn tau_stages_left(&self) -> usize {
        match &self.tau {
            None => 1 + 25,
            Some(Some(ti)) if ti.columns_fit(TAU_COLUMN_BUDGET) => {
                (ti.column_stages() + 1).saturating_sub(self.tau_stages)
            }
            Some(_) => 0,
        }
    }

    /// Runs the next stage; the tables once the last one ran.
    pub fn stage(&mut self, problem: &Problem) -> Result<Option<SimTables>, BuildError> {
        let (p, dt_s) = (problem.num_points(), problem.dt_s);
        let Some((basis, residual, full)) = &self.parts else {
            let (basis, residual) = tables_basis(problem, problem.modes.to_vec(), self.options)?;
            let full = StepTable::new(&basis, dt_s);
            self.block = block_rows(p, basis.stored_states());
            self.inf.zeroed(p);
            self.jump = vec![0.0; p * p];
            self.cols = Vec::with_capacity(4 * p * p);
            self.parts = Some((basis, residual, full));
            return Ok(None);
        };
        if self.inf_rows < p {
            let r = self.inf_rows..(self.inf_rows + self.block).min(p);
            self.inf_rows = r.end;
            self.inf.add_rows(basis, full, r);
            if self.inf_rows == p && !residual.is_empty() {
                add_residual(&mut self.inf, residual, dt_s);
            }
            return Ok(None);
        }
        if self.jump_rows < p {
            let r = self.jump_rows..(self.jump_rows + self.block).min(p);
            self.jump_rows = r.end;
            basis.velocity_jump_rows(r.clone(), &mut self.jump[r.start * p..r.end * p]);
            return Ok(None);
        }
        if self.jump_t.is_empty() && p > 0 {
            self.jump_t = transposed(&self.jump, p);
            return Ok(None);
        }
        if self.col_points < p {
            let js = self.col_points..(self.col_points + self.block).min(p);
            self.col_points = js.end;
            influence_columns(&self.inf, p, js, &mut self.cols);
            return Ok(None);
        }
        match &mut self.tau {
            None => {
                let used = tau_interp_used(problem, self.options, residual);
                self.tau = Some(used.then(|| TauInterp::weights(basis, dt_s)).flatten());
                return Ok(None);
            }
            Some(Some(ti)) if ti.columns_fit(TAU_COLUMN_BUDGET) => {
                let n = ti.column_stages();
                if self.tau_stages < n {
                    ti.add_node_column(basis, self.tau_stages);
                    self.tau_stages += 1;
                    return Ok(None);
                }
                if self.tau_stages == n {
                    ti.finish_columns(basis);
                    self.tau_stages += 1;
                    return Ok(None);
                }
            }
            Some(_) => {}
        }
        let Some((basis, residual, full)) = self.parts.take() else {
            unreachable!("the basis is the first stage");
        };
        Ok(Some(SimTables::assemble(
            problem,
            self.options,
            (basis, residual, full, self.tau.take().flatten()),
            std::mem::take(&mut self.inf),
            std::mem::take(&mut self.cols),
            std::mem::take(&mut self.jump),
            std::mem::take(&mut self.jump_t),
        )))
    }
}

/// Whether [`SimTables::tau_interp`] is built: when the merged event step
/// can use it (tread springs, no residual compliance, merged events on).
fn tau_interp_used(problem: &Problem, options: SolverOptions, residual: &[f64]) -> bool {
    options.merged_events
        && residual.is_empty()
        && !problem
            .contact
            .stiffness_per_point(problem.num_points())
            .is_empty()
}

/// Rows of a `P × P` table over `states` states per block of about
/// [`BLOCK_MADDS`] multiply-adds (at least one).
fn block_rows(p: usize, states: usize) -> usize {
    (BLOCK_MADDS / (4 * p * states).max(1)).max(1)
}

/// The run at the current time: what a snapshot or a restart needs. The
/// modal states (method §3.2), the points' outputs and the road they see,
/// the contact and active sets (method §4.2-4.4) and the statistics.
pub(super) struct SimState {
    /// Modal states at `t_s` (method §3.2).
    pub modal: Box<ModalState>,
    /// Time (s).
    pub t_s: f64,
    /// Steps taken.
    pub steps: u64,
    /// Added to `V t` so that the distance rolled stays continuous when the
    /// speed changes (m).
    pub x_offset_m: f64,
    /// Displacements `u_i` (m, up).
    pub u: Vec<f64>,
    /// Velocities `v_i` (m/s).
    pub v: Vec<f64>,
    /// Road heights `r_i` seen by the points (m).
    pub r: Vec<f64>,
    /// Road rates `r_i'` (m/s).
    pub rd: Vec<f64>,
    /// Step-mean contact forces of the last step (N).
    pub q_mean: Vec<f64>,
    /// Impulses of the impacts located in the last step (N·s).
    pub impact_impulse: Vec<f64>,
    /// Contact per point.
    pub contact: Vec<bool>,
    /// The active set `S`, the points the contact solve holds on the road
    /// (method §4.3), carried over to the next step.
    pub active: Vec<usize>,
    /// Points released in the last step (not re-added in it).
    pub released: Vec<bool>,
    /// Times each point was thrown off the road by an impact in the last
    /// step (method §4.4, "Zeno sequences").
    pub thrown_off: Vec<u32>,
    /// A spring freed at the instant it landed lands again only after it
    /// (s); NaN: no hold.
    pub held_at_s: Vec<f64>,
    /// The last step located events or released points: `impact_impulse`
    /// and `released` need clearing, and the next step rebuilds its active
    /// set from `contact`.
    pub had_event: bool,
    /// Statistics of the run so far.
    pub stats: RunStats,
}

impl SimState {
    /// At rest at `t = 0`, for `p` points on `basis` (the road seen at
    /// `t = 0` is the caller's to set).
    pub fn new(basis: &ModalBasis, p: usize) -> Self {
        SimState {
            modal: Box::new(ModalState::zeros(basis)),
            t_s: 0.0,
            steps: 0,
            x_offset_m: 0.0,
            u: vec![0.0; p],
            v: vec![0.0; p],
            r: vec![0.0; p],
            rd: vec![0.0; p],
            q_mean: vec![0.0; p],
            impact_impulse: vec![0.0; p],
            thrown_off: vec![0; p],
            contact: vec![false; p],
            active: Vec::with_capacity(p),
            released: vec![false; p],
            held_at_s: vec![f64::NAN; p],
            had_event: true,
            stats: RunStats::default(),
        }
    }
}

/// The buffers a step works in, sized once (method §4.5, "Memory"): those
/// every contact scheme's step shares (the prediction, the end values, the
/// Gauss-point forces, the sub-step table) and one part per scheme's own
/// solves. Nothing they hold is carried from one step to the next but the
/// next step's active rows ([`RowsAhead`], read only while its `ready`
/// says they are of the committed state): `impulse` is cleared at the step
/// start, every other buffer is written before it is read, and the
/// sub-step table is refilled whenever its length changes.
pub(super) struct Scratch {
    /// The free prediction of the modal states (method §4.3 step 1).
    pub free: Box<ModalState>,
    /// Free end displacements (m) and velocities (m/s).
    pub uh: Vec<f64>,
    pub vh: Vec<f64>,
    /// End displacements (m) and velocities (m/s) under the solved forces.
    pub ue: Vec<f64>,
    pub ve: Vec<f64>,
    /// Road heights (m) and rates (m/s) at the end of the (sub-)step.
    pub re: Vec<f64>,
    pub rde: Vec<f64>,
    /// Road samples `z`, `dz/dx` before the ramp (m, m/m).
    pub zbuf: Vec<f64>,
    pub dzbuf: Vec<f64>,
    /// Gauss-point forces of the active points (N, method §3.3).
    pub q1: Vec<f64>,
    pub q2: Vec<f64>,
    /// Impulse of the step so far per point (N·s).
    pub impulse: Vec<f64>,
    /// Whether `impulse` is all zeros: the last step that finished read
    /// and cleared it (a step that failed half-way leaves it to be zeroed
    /// by the next).
    pub impulse_clear: bool,
    /// Steps since the last step with an event, counted at the current
    /// step's start (saturating; `0` after a step with one): with merged
    /// tread-spring events, a large set's full step fuses its projection
    /// into its solve only after a few
    /// ([`Simulation::fused_full_step`](super::Simulation)).
    pub quiet_steps: u32,
    /// Right-hand side and solution of a contact system (`2P`).
    pub rhs: Vec<f64>,
    /// Exact step weights over the current sub-step (method §3.3).
    pub sub: StepTable,
    /// State increment of the solved sub-step forces, and its projection
    /// (m, m/s; also the active rows' free values, in the set's order, on
    /// their way to `uh`, `vh` in a threaded projection of those rows).
    pub delta: Box<ModalState>,
    pub du: Vec<f64>,
    pub dv: Vec<f64>,
    /// `delta` holds the end state of the (sub-)step solved last (its
    /// prediction plus the solved forces: a large compliant set's full
    /// step, or a sub-step whose prediction projected only the active
    /// points, `large.rs`), which `commit` takes as it is.
    pub fused_end: bool,
    /// The last prediction projected every point's free end values
    /// (`uh`, `vh`), not only the active points'.
    pub projected_all: bool,
    /// The direct solves of sub-steps and impacts (rigid and compliant
    /// contact, the step-end rules over a sub-step).
    pub dense: DenseScratch,
    /// The located scheme's events: restricted forces and joint impacts.
    pub events: EventScratch,
    /// Large active sets and compliant sub-steps by GMRES (`large.rs`).
    pub large: LargeSetScratch,
    /// The next step's active rows, projected by a large compliant set's
    /// full step (`large.rs`).
    pub ahead: RowsAhead,
    /// The merged event step of tread springs (`merged.rs`).
    pub merged: MergedScratch,
}

impl Scratch {
    /// Buffers for the tables' points and states.
    pub fn new(tables: &SimTables) -> Self {
        let p = tables.p;
        let zero = ModalState::zeros(&tables.basis);
        Scratch {
            free: Box::new(zero.clone()),
            uh: vec![0.0; p],
            vh: vec![0.0; p],
            ue: vec![0.0; p],
            ve: vec![0.0; p],
            re: vec![0.0; p],
            rde: vec![0.0; p],
            zbuf: vec![0.0; p],
            dzbuf: vec![0.0; p],
            q1: vec![0.0; p],
            q2: vec![0.0; p],
            impulse: vec![0.0; p],
            impulse_clear: true,
            rhs: vec![0.0; 2 * p],
            sub: tables.full.clone(),
            delta: Box::new(zero),
            du: vec![0.0; p],
            dv: vec![0.0; p],
            fused_end: false,
            quiet_steps: u32::MAX,
            projected_all: false,
            dense: DenseScratch::new(tables),
            events: EventScratch::new(p),
            large: LargeSetScratch::new(tables),
            ahead: RowsAhead::new(tables),
            merged: MergedScratch::new(tables),
        }
    }
}

/// The direct (factorised) solves of a sub-step's Gauss-point system
/// (method §4.5) and of an impact's impulses (method §4.4, "Impact"), and
/// the residual compliance's factor on the points on the road (§4.7).
pub(super) struct DenseScratch {
    /// `|S| x |S|` blocks of the sub-step influence (4 |S|² used); the
    /// factor of the residual compliance at an impact (`|S|²` used).
    pub gss: Vec<f64>,
    /// One point's output vector times each of the sub-step's four
    /// weights (`4 ns`).
    pub sub_out_weighted: Vec<f64>,
    /// The sub-step and impulse systems' solver.
    pub solver: DenseSolver,
}

impl DenseScratch {
    fn new(tables: &SimTables) -> Self {
        let p = tables.p;
        DenseScratch {
            gss: vec![0.0; 4 * p * p],
            sub_out_weighted: vec![0.0; 4 * tables.basis.stored_states()],
            solver: DenseSolver::new(2 * p),
        }
    }
}

/// The located scheme's events (method §4.4): the trial forces restricted
/// to the interval before an event, and the candidates of a joint impact.
pub(super) struct EventScratch {
    /// Trial Gauss-point forces restricted to the interval before an event
    /// (N).
    pub rq1: Vec<f64>,
    pub rq2: Vec<f64>,
    /// The candidates of a joint impact and a point's mark of being in its
    /// set (method §4.4, "Several events at one instant").
    pub impact_candidates: Vec<usize>,
    pub impact_in_set: Vec<bool>,
}

impl EventScratch {
    fn new(p: usize) -> Self {
        EventScratch {
            rq1: vec![0.0; p],
            rq2: vec![0.0; p],
            impact_candidates: Vec::with_capacity(p),
            impact_in_set: vec![false; p],
        }
    }
}

/// Large active sets (method §4.5, "Large active sets"): the kept
/// inverse's right-hand side and marks, and the iterative sub-step solve
/// of compliant sets. Empty but for `mark` unless
/// [`SimTables::large_sets`] or [`SimTables::iterative_sub_from`] points
/// can be on the road.
pub(super) struct LargeSetScratch {
    /// GMRES of the sub-step system (`contact/krylov.rs`).
    pub gmres: Gmres,
    /// The 2 × 2 block-diagonal preconditioner's inverses per active point.
    pub jacobi: Vec<[f64; 4]>,
    /// The Gauss-point forces of a GMRES product by point (its input
    /// vector scattered for the force kernel, N).
    pub gq1: Vec<f64>,
    pub gq2: Vec<f64>,
    /// The right-hand side in slot order, and a point's slot mark.
    pub rhs_slots: Vec<f64>,
    pub mark: Vec<bool>,
}

impl LargeSetScratch {
    fn new(tables: &SimTables) -> Self {
        let p = tables.p;
        let large = tables.large_sets() || p >= tables.iterative_sub_from();
        let n = |len: usize| if large { len } else { 0 };
        LargeSetScratch {
            gmres: Gmres::new(n(2 * p), GMRES_RESTART),
            jacobi: vec![[0.0; 4]; n(p)],
            gq1: vec![0.0; n(p)],
            gq2: vec![0.0; n(p)],
            rhs_slots: vec![0.0; n(2 * p)],
            mark: vec![false; p],
        }
    }
}

/// The next step's free prediction from the end state a large compliant
/// set's full step formed (method §4.5, "One pass over the outputs";
/// `large.rs`): its active points' free end values by point, the points
/// they were projected for, and whether the next step may read them.
/// Empty unless large compliant sets can occur.
pub(super) struct RowsAhead {
    /// The next step's free prediction of the modal states.
    pub free: Box<ModalState>,
    /// Its active points' free end displacements (m) and velocities (m/s),
    /// by point.
    pub uh: Vec<f64>,
    pub vh: Vec<f64>,
    /// The points projected ahead: a mark per point, and the list.
    pub row: Vec<bool>,
    pub points: Vec<usize>,
    /// The other points (those off the set, or active without a row).
    pub others: Vec<usize>,
    /// The last solve formed `free` (set by the solve, taken by `commit`).
    pub pending: bool,
    /// `free` is the prediction of the committed state (set by `commit`
    /// after a fused full step, taken by the next `predict`).
    pub ready: bool,
    /// The current prediction is `free`'s: its active rows are read from
    /// `uh`, `vh` (taken by the solve's projection of the active rows).
    pub in_use: bool,
}

impl RowsAhead {
    fn new(tables: &SimTables) -> Self {
        let p = tables.p;
        let ahead = tables.large_sets() && tables.compliant();
        let n = |len: usize| if ahead { len } else { 0 };
        RowsAhead {
            free: Box::new(if ahead {
                ModalState::zeros(&tables.basis)
            } else {
                ModalState {
                    x: Vec::new(),
                    v: Vec::new(),
                }
            }),
            uh: vec![0.0; n(p)],
            vh: vec![0.0; n(p)],
            row: vec![false; n(p)],
            points: Vec::with_capacity(n(p)),
            others: Vec::with_capacity(n(p)),
            pending: false,
            ready: false,
            in_use: false,
        }
    }
}
