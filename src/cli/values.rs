//! Parsers of command-line numbers whose refusal says what was expected, in
//! which unit (clap's own said `invalid digit found in string`).

/// A whole count (`--every`, `--steps`, `--threads`); 0 passes, so that the
/// command's own check names the option and the least value.
pub fn parse_count(s: &str) -> Result<u64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a whole number >= 1 (1, 2, 10, ...)".to_string())
}

/// [`parse_count`] as a `usize`.
pub fn parse_count_usize(s: &str) -> Result<usize, String> {
    parse_count(s).and_then(|n| usize::try_from(n).map_err(|_| "too large".to_string()))
}

/// A time in seconds (`--dt`, `--duration`); its range is checked by the
/// scene's validation, which names the field.
pub fn parse_seconds(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a time in seconds, e.g. 1e-5 or 0.5".to_string())
}

/// A number in the unit of a swept parameter (`--from`, `--to`).
pub fn parse_value(s: &str) -> Result<f64, String> {
    s.trim().parse().map_err(|_| {
        "expected a number in the unit of --param (m/s for speed_mps, Hz for freq_hz), e.g. 8 or 1.5e-3".to_string()
    })
}

/// A size in decimal GB (`--max-output-gb`); its range is checked by the command.
pub fn parse_gb(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a size in GB, e.g. 20 or 0.5".to_string())
}

/// A frequency in Hz (`--spectrum-max-hz`); its range is checked by the command.
pub fn parse_hz(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a frequency in Hz, e.g. 5000".to_string())
}

/// A frame rate in Hz (`--fps`); its range is checked by the command.
pub fn parse_frame_rate(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a frame rate in Hz, e.g. 25".to_string())
}

/// A dimensionless factor (`--slow-motion`); its range is checked by the command.
pub fn parse_factor(s: &str) -> Result<f64, String> {
    s.trim()
        .parse()
        .map_err(|_| "expected a number, e.g. 20 or 0.5".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_parse_and_refusals_say_what_was_expected() {
        assert_eq!(parse_count("10"), Ok(10));
        assert_eq!(parse_count("0"), Ok(0));
        assert!(
            parse_count("ten")
                .unwrap_err()
                .contains("whole number >= 1")
        );
        assert!(parse_count("-3").is_err());
        assert!(parse_count("2.5").is_err());
        assert_eq!(parse_count_usize("4"), Ok(4));
        assert_eq!(parse_seconds("1e-5"), Ok(1e-5));
        assert_eq!(parse_seconds("-1"), Ok(-1.0));
        assert!(
            parse_seconds("abc")
                .unwrap_err()
                .contains("time in seconds")
        );
        assert_eq!(parse_value("-5"), Ok(-5.0));
        assert!(parse_value("fast").unwrap_err().contains("unit of --param"));
    }
}
