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
