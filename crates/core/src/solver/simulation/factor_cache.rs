//! Full-step factorisations kept by active set (method §4.5, "Reuse"): the
//! full-step Gauss-point operator of a rigid contact depends only on the
//! active set (in its order) and `dt`, and a rolling tyre's active sets
//! come back on every road period. The factorisation of each set that was
//! left is kept in a small cache of buffers sized once (no allocation per
//! step), and taken back instead of factorising again: the same LU, inverse
//! and packed rows, bit for bit. Like the current factorisation, the kept
//! ones stay valid across `reset` (the set and `dt` are all they depend on;
//! `dt`, the modes and the options are fixed for a simulation's life).

use crate::solver::simulation::contact::DenseSolver;
use crate::solver::simulation::contact::bordered::BorderedInverse;

/// Most factorisations kept.
const MAX_ENTRIES: usize = 16;

/// Memory the kept factorisations may take (bytes): large scenes keep
/// fewer, or none.
const BUDGET_BYTES: usize = 16 << 20;

/// The full-step factorisation of one active set.
pub(super) struct FullFactor {
    pub solver: DenseSolver,
    /// The active set factorised, in its order.
    pub set: Vec<usize>,
    /// The points outside `set`, in order.
    pub free: Vec<usize>,
    /// Per point of `free`, the full-step influence of the Gauss-point
    /// forces of `set` on its end displacement and velocity, packed as two
    /// rows of `2|S|` against the solved `q1 | q2` (`4|S|` values).
    pub free_rows: Vec<f64>,
}

impl FullFactor {
    /// Buffers for `p` points (capacities `P` and `4P²`).
    fn new(p: usize) -> Self {
        FullFactor {
            solver: DenseSolver::new(2 * p),
            set: Vec::with_capacity(p),
            free: Vec::with_capacity(p),
            free_rows: Vec::with_capacity(4 * p * p),
        }
    }
}

/// The full-step factorisations of a simulation: the current one and those
/// kept for sets left earlier. A function of the tables and the active set
/// alone: neither the run's state (a restart rebuilds them, bit for bit) nor
/// per-step scratch (they outlive steps and `reset`).
pub(super) struct FullFactors {
    /// The factorisation of `current.set`, valid if `factored`.
    pub current: FullFactor,
    pub factored: bool,
    pub cache: FactorCache,
    /// The full-step inverse of a large compliant active set, kept up to
    /// date as points join and leave (`large.rs`; empty buffers
    /// otherwise), valid if `updated_valid`.
    pub updated: BorderedInverse,
    pub updated_valid: bool,
}

impl FullFactors {
    /// Buffers for `p` points; `keep: false` (no reuse of the full-step
    /// factorisation, or compliant contact) keeps none for sets left.
    pub fn new(p: usize, keep: bool, large: bool) -> Self {
        FullFactors {
            current: FullFactor::new(p),
            factored: false,
            cache: FactorCache::new(p, keep),
            updated: BorderedInverse::new(if large { p } else { 0 }),
            updated_valid: false,
        }
    }

    /// Whether the current factorisation is valid and of `active`.
    #[inline]
    pub fn holds(&self, active: &[usize]) -> bool {
        let set = &self.current.set;
        self.factored && set.len() == active.len() && set.iter().zip(active).all(|(a, b)| a == b)
    }
}

/// One kept full-step factorisation.
pub(super) struct Kept {
    pub factor: FullFactor,
    /// Tick of the last store or take; 0: empty.
    pub used: u64,
}

/// The kept factorisations, least recently used replaced first.
pub(super) struct FactorCache {
    pub entries: Vec<Kept>,
    clock: u64,
}

impl FactorCache {
    /// Buffers for `p` points; `enabled: false` keeps none.
    pub fn new(p: usize, enabled: bool) -> Self {
        let m = 2 * p;
        // LU and inverse (`m²` each), packed rows (`4p²`)
        let bytes = 8 * (2 * m * m + 4 * p * p + 4 * m + 2 * p).max(1);
        let cap = if enabled {
            (BUDGET_BYTES / bytes).min(MAX_ENTRIES)
        } else {
            0
        };
        let entries = (0..cap)
            .map(|_| Kept {
                factor: FullFactor::new(p),
                used: 0,
            })
            .collect();
        FactorCache { entries, clock: 0 }
    }

    pub fn is_enabled(&self) -> bool {
        !self.entries.is_empty()
    }

    /// The entry holding the factorisation of `set` (same points, same order).
    pub fn find(&self, set: &[usize]) -> Option<usize> {
        self.entries
            .iter()
            .position(|e| e.used != 0 && e.factor.set.as_slice() == set)
    }

    /// The entry to store into: an empty one, else the least recently used.
    pub fn victim(&self) -> usize {
        let mut best = 0;
        for (k, e) in self.entries.iter().enumerate() {
            if e.used < self.entries[best].used {
                best = k;
            }
        }
        best
    }

    /// A new tick for [`Kept::used`].
    pub fn tick(&mut self) -> u64 {
        self.clock += 1;
        self.clock
    }
}
