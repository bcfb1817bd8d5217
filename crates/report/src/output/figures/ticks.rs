//! The ticks of a log axis, chosen here rather than by plotters: plotters'
//! log key points reach each power of ten twice (once as the last multiple
//! of the decade below, `10 × 10^k`, and once as the decade itself, a
//! rounding apart), so a label such as `100` was printed twice.
//!
//! A tick is an integer mantissa times a power of ten, kept as such, so its
//! value and its text come from the same exact pair: each printed label is
//! the decimal value of its tick, and distinct ticks print distinctly.

/// The ticks of one log axis: the labelled ones (bold grid lines) and the
/// unlabelled grid lines between them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct LogTicks {
    /// Ascending tick values and their labels.
    pub labelled: Vec<(f64, String)>,
    /// Ascending values of the light grid lines (every integer multiple of
    /// a power of ten in the range, or none on axes of many decades).
    pub light: Vec<f64>,
}

impl LogTicks {
    /// The label of tick value `v` (empty where `v` is not a labelled tick).
    pub fn label(&self, v: f64) -> String {
        self.labelled
            .iter()
            .find(|(t, _)| *t == v)
            .map(|(_, s)| s.clone())
            .unwrap_or_default()
    }
}

/// `m × 10^e`, an exact decimal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Decimal {
    m: i64,
    e: i32,
}

impl Decimal {
    /// The nearest `f64` (parsed from the decimal's text: exact to the
    /// last bit, where `m as f64 * 10f64.powi(e)` is not).
    fn value(self) -> f64 {
        format!("{}e{}", self.m, self.e).parse().unwrap_or(f64::NAN)
    }

    /// Trailing zeros of the mantissa moved into the exponent.
    fn normalised(self) -> Decimal {
        let Decimal { mut m, mut e } = self;
        while m != 0 && m % 10 == 0 {
            m /= 10;
            e += 1;
        }
        Decimal { m, e }
    }

    /// Plain from 1 to 10000 (`10`, `250`, `1000`), as on every log axis
    /// of the figures ([`super::tick_label`]); exponent form below and
    /// beyond (`5e-1`, `2.5e-7`, `1e5`). Exact: the digits are those of
    /// the mantissa.
    fn text(self) -> String {
        let Decimal { m, e } = self.normalised();
        let digits = m.unsigned_abs().to_string();
        let sign = if m < 0 { "-" } else { "" };
        let v = self.value().abs();
        if (1.0..1e5).contains(&v) {
            if e >= 0 {
                return format!("{sign}{digits}{}", "0".repeat(e as usize));
            }
            let point = digits.len() as i32 + e;
            // v >= 1: at least one digit before the point
            let (int, frac) = digits.split_at(point.max(0) as usize);
            return format!("{sign}{int}.{frac}");
        }
        let exp = e + digits.len() as i32 - 1;
        let (lead, rest) = digits.split_at(1);
        if rest.is_empty() {
            format!("{sign}{lead}e{exp}")
        } else {
            format!("{sign}{lead}.{rest}e{exp}")
        }
    }
}

/// The ticks `mantissa × 10^e` in `[lo, hi]` for every decade `e` the
/// range touches, taking the decades `every` apart (counted from 10^0).
fn decade_ticks(lo: f64, hi: f64, mantissas: &[i64], every: i32) -> Vec<Decimal> {
    let (e0, e1) = (lo.log10().floor() as i32 - 1, hi.log10().ceil() as i32 + 1);
    let mut out = Vec::new();
    for e in e0..=e1 {
        if e.rem_euclid(every) != 0 {
            continue;
        }
        for &m in mantissas {
            let d = Decimal { m, e };
            let v = d.value();
            if v >= lo && v <= hi {
                out.push(d);
            }
        }
    }
    out
}

/// The multiples of `step` in `[lo, hi]` (a narrow range: less than one
/// factor of five).
fn linear_ticks(lo: f64, hi: f64, step: Decimal) -> Vec<Decimal> {
    let s = step.value();
    let (k0, k1) = ((lo / s).ceil(), (hi / s).floor());
    if !(k0.is_finite() && k1.is_finite()) || k1 - k0 > 1e4 || k0 > 1e15 {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut k = k0 as i64;
    while k as f64 <= k1 {
        let d = Decimal {
            m: k * step.m,
            e: step.e,
        };
        let v = d.value();
        if v >= lo && v <= hi {
            out.push(d);
        }
        k += 1;
    }
    out
}

/// Every second tick, until at most `max` (at least 2) are left.
fn thinned(mut ticks: Vec<Decimal>, max: usize) -> Vec<Decimal> {
    while ticks.len() > max.max(2) {
        ticks = ticks.into_iter().step_by(2).collect();
    }
    ticks
}

/// The ticks of a log axis over `[lo, hi]` (`0 < lo < hi`) with at most
/// `max_labels` labels (at least 2): 1, 2 and 5 of each decade; where
/// those are too many, the powers of ten (every one, or every second,
/// third, … decade); where they are fewer than two (a range within a
/// factor of five), every integer multiple of a power of ten, or evenly
/// spaced ticks of a 1-2-5 step. Each label is its tick's exact decimal
/// value, and no two labels are the same text.
pub fn log_axis_ticks(lo: f64, hi: f64, max_labels: usize) -> LogTicks {
    let max_labels = max_labels.max(2);
    if !(lo > 0.0 && hi > lo && lo.is_finite() && hi.is_finite()) {
        return LogTicks::default();
    }
    let one_two_five = decade_ticks(lo, hi, &[1, 2, 5], 1);
    let labelled = if one_two_five.len() > max_labels {
        // the densest of the powers of ten, every one or every second,
        // third, … decade, with two labels or more; else every second
        // tick of the last set with too many
        let mut denser = one_two_five;
        let mut every = 1;
        loop {
            let t = decade_ticks(lo, hi, &[1], every);
            if t.len() <= max_labels {
                break if t.len() >= 2 {
                    t
                } else {
                    thinned(denser, max_labels)
                };
            }
            denser = t;
            every += 1;
        }
    } else if one_two_five.len() >= 2 {
        one_two_five
    } else {
        let every_digit = decade_ticks(lo, hi, &[1, 2, 3, 4, 5, 6, 7, 8, 9], 1);
        if (2..=max_labels).contains(&every_digit.len()) {
            every_digit
        } else {
            // the largest 1-2-5 step giving two ticks or more
            let top = (hi - lo).log10().ceil() as i32;
            (0..40)
                .flat_map(|k| [5, 2, 1].map(|m| Decimal { m, e: top - k }))
                .map(|step| linear_ticks(lo, hi, step))
                .find(|t| t.len() >= 2)
                .map(|t| thinned(t, max_labels))
                .unwrap_or_default()
        }
    };
    let decades = hi.log10() - lo.log10();
    let light = if decades <= 8.0 {
        decade_ticks(lo, hi, &[1, 2, 3, 4, 5, 6, 7, 8, 9], 1)
            .into_iter()
            .map(Decimal::value)
            .collect()
    } else {
        Vec::new()
    };
    LogTicks {
        labelled: labelled
            .into_iter()
            .map(|d| (d.value(), d.text()))
            .collect(),
        light,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn texts(t: &LogTicks) -> Vec<&str> {
        t.labelled.iter().map(|(_, s)| s.as_str()).collect()
    }

    /// The modes axis of the scaling figure (10 to 400 modes, padded).
    #[test]
    fn the_modes_axis_names_each_tick_once() {
        let t = log_axis_ticks(8.62, 464.0, 12);
        assert_eq!(texts(&t), ["10", "20", "50", "100", "200"]);
        assert_eq!(t.labelled[3].0, 100.0);
    }

    #[test]
    fn labels_are_exact_decimals_in_one_style_per_range() {
        for (d, want) in [
            (Decimal { m: 5, e: -1 }, "5e-1"),
            (Decimal { m: 1, e: 5 }, "1e5"),
            (Decimal { m: 25, e: -8 }, "2.5e-7"),
            (Decimal { m: 2000, e: 0 }, "2000"),
            (Decimal { m: 325, e: -1 }, "32.5"),
            (Decimal { m: 1, e: 0 }, "1"),
            (Decimal { m: 12345, e: -4 }, "1.2345"),
        ] {
            assert_eq!(d.text(), want, "{d:?}");
        }
    }

    #[test]
    fn many_decades_keep_powers_of_ten_only() {
        let t = log_axis_ticks(1e-9, 1e9, 6);
        assert_eq!(texts(&t), ["1e-8", "1e-4", "1", "10000", "1e8"]);
        assert!(t.light.is_empty());
    }

    #[test]
    fn a_narrow_range_still_gets_two_labels() {
        let t = log_axis_ticks(31.0, 33.0, 8);
        assert!(t.labelled.len() >= 2, "{t:?}");
        let t = log_axis_ticks(3.0, 7.0, 8);
        assert_eq!(texts(&t), ["3", "4", "5", "6", "7"]);
    }

    proptest! {
        /// Over axes from 1e-12 to 1e12 and from a factor of 1.01 to
        /// twenty decades: at least two and at most `max` labels, every
        /// label distinct, read back as its tick's value, ticks ascending
        /// within the range.
        #[test]
        fn every_label_is_distinct_and_reads_as_its_tick(
            lo_exp in -12.0f64..12.0,
            span_exp in 0.005f64..20.0,
            max in 2usize..14,
        ) {
            let lo = 10f64.powf(lo_exp);
            let hi = lo * 10f64.powf(span_exp);
            let t = log_axis_ticks(lo, hi, max);
            let n = t.labelled.len();
            prop_assert!((2..=max).contains(&n), "{n} labels in {lo}..{hi} (max {max}): {t:?}");
            let mut seen = std::collections::HashSet::new();
            for (v, s) in &t.labelled {
                prop_assert!(seen.insert(s.clone()), "{s} twice: {t:?}");
                let read: f64 = s.parse().unwrap();
                prop_assert!((read - v).abs() <= 1e-12 * v.abs(), "{s} for {v}");
                prop_assert!(*v >= lo && *v <= hi, "{v} outside {lo}..{hi}");
            }
            prop_assert!(t.labelled.windows(2).all(|w| w[0].0 < w[1].0));
        }
    }
}
