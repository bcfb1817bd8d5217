//! The automatic model order of LSCE (method §6: "chosen with a
//! stabilisation diagram").

use super::{EXACT_FIT, IdentifyOptions, OrderErrors};
use crate::model::stability::{DiagramOrder, Stability};

/// The automatic model order (method §6: chosen with the stabilisation
/// diagram): among the orders whose in-band fit error is near the best
/// (within `order_tolerance`, plus [`EXACT_FIT`]), the smallest whose kept
/// poles (`kept_at[k]`: indices into `diagram[k].poles`; `errors[k]` the
/// order's fit errors) all persist, each
/// stable against the order below or found stable at the order above; if
/// no near-best order has only persistent poles, the smallest near-best
/// order. `None` without any in-band pole.
pub(super) fn choose_order(
    diagram: &[DiagramOrder],
    errors: &[OrderErrors],
    kept_at: &[Vec<usize>],
    opts: &IdentifyOptions,
) -> Option<usize> {
    let best = (0..diagram.len())
        .filter(|&k| !diagram[k].poles.is_empty())
        .map(|k| errors[k].band_time_error)
        .fold(f64::INFINITY, f64::min);
    let near_best = |k: usize| {
        !diagram[k].poles.is_empty()
            && errors[k].band_time_error <= (1.0 + opts.order_tolerance) * best + EXACT_FIT
    };
    let persists = |k: usize| {
        let d = &diagram[k];
        kept_at.get(k).is_some_and(|kept| {
            kept.iter().all(|&c| {
                let pl = &d.poles[c];
                pl.stability == Stability::Stable
                    || diagram.get(k + 1).is_some_and(|up| {
                        up.poles.iter().any(|q| {
                            q.stability == Stability::Stable
                                && (q.freq_hz - pl.freq_hz).abs()
                                    <= opts.stable_freq_tol * pl.freq_hz
                        })
                    })
            })
        })
    };
    (0..diagram.len())
        .find(|&k| near_best(k) && persists(k))
        .or_else(|| (0..diagram.len()).find(|&k| near_best(k)))
        .map(|k| diagram[k].order)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::stability::DiagramPole;

    fn pole(freq_hz: f64, stability: Stability) -> DiagramPole {
        DiagramPole {
            freq_hz,
            damping_ratio: 0.05,
            stability,
        }
    }

    fn order(
        order: usize,
        poles: Vec<DiagramPole>,
        band_time_error: f64,
    ) -> (DiagramOrder, OrderErrors) {
        (
            DiagramOrder { order, poles },
            OrderErrors {
                order,
                time_error: band_time_error,
                band_time_error,
            },
        )
    }

    /// The smallest near-best order keeps a pole that appears there only
    /// (new at order 3, gone at order 4: a fit to noise); the order chosen
    /// is the next near-best one whose kept poles persist. Without the
    /// persistence rule it would be 3.
    #[test]
    fn a_near_best_order_with_a_passing_pole_is_skipped() {
        use Stability::*;
        let (d, e): (Vec<DiagramOrder>, Vec<OrderErrors>) = [
            order(1, vec![pole(100.0, New)], 0.5),
            order(2, vec![pole(100.0, Stable), pole(200.0, New)], 0.2),
            order(
                3,
                vec![pole(100.0, Stable), pole(200.0, Stable), pole(333.0, New)],
                0.010,
            ),
            order(
                4,
                vec![pole(100.0, Stable), pole(200.0, Stable), pole(410.0, New)],
                0.0101,
            ),
            order(
                5,
                vec![
                    pole(100.0, Stable),
                    pole(200.0, Stable),
                    pole(410.0, Stable),
                ],
                0.0102,
            ),
        ]
        .into_iter()
        .unzip();
        let all: Vec<Vec<usize>> = d.iter().map(|o| (0..o.poles.len()).collect()).collect();
        let opts = IdentifyOptions::default();
        // order 4's new pole persists, stable, at order 5: order 4
        assert_eq!(choose_order(&d, &e, &all, &opts), Some(4));
        // the passing pole carries no share (not kept): order 3
        let mut kept = all.clone();
        kept[2] = vec![0, 1];
        assert_eq!(choose_order(&d, &e, &kept, &opts), Some(3));
        // nothing near the best persists: the smallest near-best order
        let mut d2 = d.clone();
        d2[4].poles[2].stability = New;
        d2[3].poles[2].stability = New;
        assert_eq!(choose_order(&d2[..4], &e[..4], &all[..4], &opts), Some(3));
        // no in-band pole at all
        let (empty, empty_errors) = order(1, vec![], 0.1);
        assert_eq!(
            choose_order(&[empty], &[empty_errors], &[vec![]], &opts),
            None
        );
    }
}
