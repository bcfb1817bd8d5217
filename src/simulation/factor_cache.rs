//! Full-step factorisations kept by active set (method §4, "Events inside the
//! step"): the full-step Gauss-point operator of a rigid contact depends
//! only on the active set (in its order) and `dt`, and a rolling tyre's
//! active sets come back on every road period. The factorisation of each
//! set that was left is kept in a small cache of buffers sized once (no
//! allocation per step), and taken back instead of factorising again:
//! the same LU, inverse and packed rows, bit for bit. Like the current
//! factorisation, the kept ones stay valid across `reset` (the set and `dt`
//! are all they depend on; `dt`, the modes and the options are fixed for a
//! simulation's life).

use crate::contact::DenseSolver;

/// Most factorisations kept.
const MAX_ENTRIES: usize = 16;

/// Memory the kept factorisations may take (bytes): large scenes keep
/// fewer, or none.
const BUDGET_BYTES: usize = 16 << 20;

/// One kept full-step factorisation: what [`super::Simulation`] holds in
/// `full_solver`, `full_set`, `full_free`, `full_free_rows`.
pub(super) struct FullFactor {
    pub solver: DenseSolver,
    pub set: Vec<usize>,
    pub free: Vec<usize>,
    pub free_rows: Vec<f64>,
    /// Tick of the last store or take; 0: empty.
    pub used: u64,
}

/// The kept factorisations, least recently used replaced first.
pub(super) struct FactorCache {
    pub entries: Vec<FullFactor>,
    clock: u64,
}

impl FactorCache {
    /// Buffers for `p` points; `enabled: false` (no reuse of the full-step
    /// factorisation, or compliant contact) keeps none.
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
            .map(|_| FullFactor {
                solver: DenseSolver::new(m),
                set: Vec::with_capacity(p),
                free: Vec::with_capacity(p),
                free_rows: Vec::with_capacity(4 * p * p),
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
            .position(|e| e.used != 0 && e.set.as_slice() == set)
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

    /// A new tick for [`FullFactor::used`].
    pub fn tick(&mut self) -> u64 {
        self.clock += 1;
        self.clock
    }
}
