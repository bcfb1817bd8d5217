//! Numbers as the fields and plot axes show them.

/// Formats a value compactly with up to 6 significant digits.
pub fn format_number(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return if x == 0.0 {
            "0".to_string()
        } else {
            x.to_string()
        };
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let digits = (5 - a.log10().floor() as i32).max(0) as usize;
        let s = format!("{x:.digits$}");
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    } else {
        let s = format!("{x:.5e}");
        match s.split_once('e') {
            Some((m, e)) => {
                let m = if m.contains('.') {
                    m.trim_end_matches('0').trim_end_matches('.')
                } else {
                    m
                };
                format!("{m}e{e}")
            }
            None => s,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_format_compactly() {
        assert_eq!(format_number(100.0), "100");
        assert_eq!(format_number(0.05), "0.05");
        assert_eq!(format_number(-1.0), "-1");
        assert_eq!(format_number(1e-5), "1e-5");
        assert_eq!(format_number(72.0), "72");
        assert_eq!(format_number(0.123456789), "0.123457");
        assert_eq!(format_number(2.5e7), "2.5e7");
    }
}
