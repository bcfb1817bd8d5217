//! The stabilisation diagram of LSCE (method §6.3) and LSCF (method
//! §6.5.1): the poles of every model order, each classified against the
//! poles of the order below by frequency, damping and a shape MAC.
//!
//! The two methods differ in the shape they compare (LSCE the real residues
//! over the responses, LSCF the complex participation vectors), in the
//! tolerances of their options and in which pole of the order below a pole
//! is compared with ([`Matching`]); the classification itself is
//! [`Criteria::classify`].

use faer::c64;
use std::f64::consts::TAU;

/// How a pole of the stabilisation diagram compares with the order below.
/// Ordered from least to most stable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stability {
    /// Damping ratio at or above the fit's limit: drawn in the diagram,
    /// never compared with other orders, never a mode.
    Damped,
    /// No pole of the order below within the frequency tolerance.
    New,
    /// Frequency stable only.
    Frequency,
    /// Frequency and damping stable.
    FrequencyDamping,
    /// Frequency, damping and shape (residue or participation MAC) stable.
    Stable,
}

impl Stability {
    /// Every category, most stable first: the order of a diagram's legend.
    pub const ALL: [Stability; 5] = [
        Stability::Stable,
        Stability::FrequencyDamping,
        Stability::Frequency,
        Stability::New,
        Stability::Damped,
    ];
}

/// Which pole of the order below a pole is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Matching {
    /// The nearest in frequency (LSCE, method §6.3).
    Nearest,
    /// Every one; the pole takes the best category any gives it (LSCF,
    /// method §6.5.1: a polyreference model of a low-rank matrix has close
    /// twins of a physical pole, and the nearest may be the twin).
    Best,
}

/// The tolerances of a stable pole and the matching rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criteria {
    /// Largest relative frequency change between orders (-).
    pub freq_tol: f64,
    /// Largest relative damping change between orders (-).
    pub damping_tol: f64,
    /// Smallest MAC of the shapes (-).
    pub mac_min: f64,
    pub matching: Matching,
}

impl Criteria {
    /// The category of a pole of frequency `freq` (any unit, the same as
    /// `below`'s) and damping ratio `damping` against the poles `below` of
    /// the order below, `(frequency, damping ratio)` each; `mac(k)` is the
    /// MAC of the pole's shape with that of `below[k]`, evaluated only for
    /// a pole within the frequency and damping tolerances. A pole is stable
    /// in frequency when `|f_b − f| ≤ freq_tol · f`, in damping when
    /// `|ξ_b − ξ| ≤ damping_tol · ξ`, in shape when `MAC ≥ mac_min`; each
    /// test counts only when the ones before it pass. With no order below,
    /// [`Stability::New`].
    pub fn classify(
        &self,
        freq: f64,
        damping: f64,
        below: impl IntoIterator<Item = (f64, f64)>,
        mac: impl Fn(usize) -> f64,
    ) -> Stability {
        let candidates = below.into_iter().enumerate();
        match self.matching {
            Matching::Nearest => candidates
                .min_by(|a, b| (a.1.0 - freq).abs().total_cmp(&(b.1.0 - freq).abs()))
                .map_or(Stability::New, |(k, q)| {
                    self.against(freq, damping, q, || mac(k))
                }),
            Matching::Best => candidates
                .map(|(k, q)| self.against(freq, damping, q, || mac(k)))
                .max()
                .unwrap_or(Stability::New),
        }
    }

    /// The category of a pole `(freq, damping)` against one pole `q` of the
    /// order below.
    fn against(
        &self,
        freq: f64,
        damping: f64,
        q: (f64, f64),
        mac: impl FnOnce() -> f64,
    ) -> Stability {
        if (q.0 - freq).abs() > self.freq_tol * freq {
            Stability::New
        } else if (q.1 - damping).abs() > self.damping_tol * damping {
            Stability::Frequency
        } else if mac() < self.mac_min {
            Stability::FrequencyDamping
        } else {
            Stability::Stable
        }
    }
}

/// One pole of the stabilisation diagram.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramPole {
    pub freq_hz: f64,
    pub damping_ratio: f64,
    pub stability: Stability,
}

impl DiagramPole {
    /// The continuous-time pole `λ = −ξω + jω√(1−ξ²)` (rad/s), `ω = 2π f`.
    pub fn lambda(&self) -> c64 {
        let w = TAU * self.freq_hz;
        let xi = self.damping_ratio;
        c64::new(-xi * w, w * ((1.0 - xi) * (1.0 + xi)).max(0.0).sqrt())
    }
}

/// One model order of the stabilisation diagram: its poles in the band.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramOrder {
    /// Model order (LSCE: pole pairs `M`; LSCF: polynomial order `p`).
    pub order: usize,
    pub poles: Vec<DiagramPole>,
}

/// The diagram's poles of one category, as `(frequency (Hz), order)`, order
/// by order: what a drawing of the diagram marks alike.
pub fn points_of(
    diagram: &[DiagramOrder],
    stability: Stability,
) -> impl Iterator<Item = (f64, f64)> + '_ {
    diagram.iter().flat_map(move |d| {
        d.poles
            .iter()
            .filter(move |p| p.stability == stability)
            .map(move |p| (p.freq_hz, d.order as f64))
    })
}

/// The run of stable orders of the persistence rule with one reference
/// ([`PersistenceRule::persist`]'s default).
pub const PERSIST: usize = 5;

/// The persistence rule that keeps a pole of a stabilisation diagram as a
/// mode ([`keep`]; method §6.5.1): shared by the frequency-domain fit
/// (LSCF) and the workbench's automatic choice on an LSCE diagram.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PersistenceRule {
    /// Two poles within this relative frequency distance are the same
    /// physical pole (-).
    pub freq_tol: f64,
    /// The run of stable orders `P` (with one reference), and how far
    /// below the chosen order a pole may be taken.
    pub persist: usize,
}

impl PersistenceRule {
    /// Whether `a` matches `b` in frequency within the tolerance.
    fn same_frequency(&self, a: &DiagramPole, b: &DiagramPole) -> bool {
        (a.freq_hz - b.freq_hz).abs() <= self.freq_tol * a.freq_hz
    }
}

/// A pole kept as a mode by the persistence rule ([`keep`]).
#[derive(Debug, Clone, PartialEq)]
pub struct KeptPole {
    pub pole: DiagramPole,
    /// The order it was taken at.
    pub order: usize,
    /// Its place in the diagram: `diagram[at.0].poles[at.1]`.
    pub at: (usize, usize),
    /// The run of consecutive orders, `(first, last)`, at which a pole
    /// within the frequency tolerance of it is stable (frequency, damping
    /// and shape): the orders it persists over.
    pub stable_orders: (usize, usize),
    /// Frequencies (Hz) of the other poles of its order within the
    /// frequency tolerance of it (a split pole), merged into it.
    pub split_hz: Vec<f64>,
}

/// The poles [`keep`] kept, by frequency, and the chosen order.
#[derive(Debug, Clone, PartialEq)]
pub struct Selection {
    /// The chosen order (the one given, else the diagram's highest).
    pub order: usize,
    pub kept: Vec<KeptPole>,
}

/// The kept poles by persistence (method §6.5.1) of a diagram whose
/// `k`-th entry is order `k + 1`: at each order from the chosen one
/// (`order`, else the highest) down to `persist` orders below it, highest
/// first, a pole is kept when it is stable (frequency, damping, shape)
/// against the order below there and at each order down to the run's
/// start (a run of `persist` consecutive stable orders with one reference,
/// `persist / references` with several, 1 at least; each a pole within the
/// frequency tolerance of it), and a pole within the tolerance is drawn at
/// each of the `persist` orders below; a pole within the frequency
/// tolerance of one already kept is the same physical pole.
/// So a mode is kept when the top order splits it, moves it or leaves its
/// damping unsettled, as long as it persisted up to within `persist`
/// orders of the chosen one; a pole stable in frequency and damping only
/// (its shape changing from order to order) is never kept. Sorted by
/// frequency.
pub fn keep(
    diagram: &[DiagramOrder],
    order: Option<usize>,
    references: usize,
    rule: &PersistenceRule,
) -> Selection {
    if diagram.is_empty() {
        return Selection {
            order: 0,
            kept: Vec::new(),
        };
    }
    let order = order.unwrap_or(diagram.len()).clamp(1, diagram.len());
    let at = |p: usize| &diagram[p - 1].poles;
    let stable_at = |p: &DiagramPole, q: usize| {
        at(q)
            .iter()
            .any(|b| b.stability == Stability::Stable && rule.same_frequency(p, b))
    };
    // an order of a polyreference model adds N_i poles (N_i references):
    // the run is `persist` orders of one reference, persist / N_i of N_i
    let run = (rule.persist / references.max(1)).clamp(1, rule.persist.max(1));
    let drawn = |p: &DiagramPole, q: usize| {
        at(q)
            .iter()
            .any(|b| b.stability != Stability::Damped && rule.same_frequency(p, b))
    };
    let mut kept: Vec<KeptPole> = Vec::new();
    let lowest_taken = order.saturating_sub(rule.persist).max(1);
    for q in (lowest_taken..=order).rev() {
        for (index, pole) in at(q).iter().enumerate() {
            if pole.stability != Stability::Stable
                || kept.iter().any(|k| rule.same_frequency(&k.pole, pole))
            {
                continue;
            }
            let first = (1..q)
                .rev()
                .take_while(|&b| stable_at(pole, b))
                .last()
                .unwrap_or(q);
            // a run of `persist` consecutive stable orders at least (at
            // a high order, poles are so dense that one is drawn within
            // the tolerance of anything: being drawn proves nothing)
            let lowest = q.saturating_sub(rule.persist).max(1);
            if q + 1 - first < run || !(lowest..q).all(|b| drawn(pole, b)) {
                continue;
            }
            let last = (q + 1..=diagram.len())
                .take_while(|&b| stable_at(pole, b))
                .last();
            let split_hz = at(q)
                .iter()
                .filter(|b| {
                    b.stability != Stability::Damped
                        && !std::ptr::eq(*b, pole)
                        && rule.same_frequency(pole, b)
                })
                .map(|b| b.freq_hz)
                .collect();
            kept.push(KeptPole {
                pole: pole.clone(),
                order: q,
                at: (q - 1, index),
                stable_orders: (first, last.unwrap_or(q)),
                split_hz,
            });
        }
    }
    kept.sort_by(|a, b| a.pole.freq_hz.total_cmp(&b.pole.freq_hz));
    Selection { order, kept }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn criteria(matching: Matching) -> Criteria {
        Criteria {
            freq_tol: 0.01,
            damping_tol: 0.05,
            mac_min: 0.98,
            matching,
        }
    }

    #[test]
    fn each_test_counts_only_when_the_ones_before_it_pass() {
        use Stability::*;
        let c = criteria(Matching::Nearest);
        let one = |q: (f64, f64), mac: f64| c.classify(100.0, 0.02, [q], |_| mac);
        assert_eq!(one((100.5, 0.0201), 0.99), Stable);
        assert_eq!(one((100.5, 0.0201), 0.5), FrequencyDamping);
        assert_eq!(one((100.5, 0.03), 0.99), Frequency);
        assert_eq!(one((102.0, 0.02), 0.99), New);
        assert_eq!(c.classify(100.0, 0.02, [], |_| 1.0), New);
    }

    #[test]
    fn nearest_takes_the_closest_pole_and_best_the_best_category() {
        // the nearest pole differs in damping; a farther one (still within
        // the frequency tolerance) matches in everything
        let below = [(100.2, 0.03), (100.6, 0.02)];
        let mac = |_| 1.0;
        assert_eq!(
            criteria(Matching::Nearest).classify(100.0, 0.02, below, mac),
            Stability::Frequency
        );
        assert_eq!(
            criteria(Matching::Best).classify(100.0, 0.02, below, mac),
            Stability::Stable
        );
    }
}
