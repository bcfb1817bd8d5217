//! One line of scene parameters for figure subtitles, shared by every
//! figure (`run --plot`, sweeps, spectra, the visualiser's exports), with
//! numbers written as a reader expects them (`dt = 1e-7 s`, not
//! `1.0000000000000001e-7`).

use tirecontact_core::base::error::count;
use tirecontact_core::base::modal::Mode;
use tirecontact_core::model::road::Road;
use tirecontact_io::Scene;

/// Modes listed one by one in a subtitle (more are given as ranges).
const LISTED_MODES: usize = 4;

/// `x` to `digits` significant digits, trailing zeros dropped; in exponent
/// form below 1e-3 and from 1e6 on (`1e-7`, `2.5e-5`, `0.012`, `36`,
/// `1.2e6`).
pub fn short_num(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let digits = digits.max(1);
    let a = x.abs();
    if !(1e-3..1e6).contains(&a) {
        // "1.2340e-7" -> "1.234e-7"
        let s = format!("{x:.p$e}", p = digits - 1);
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        return format!("{}e{exp}", trim_zeros(mantissa));
    }
    // the rounded value's own magnitude: 9.9996 to 4 digits is "10"
    let magnitude = format!("{a:.p$e}", p = digits - 1)
        .split_once('e')
        .and_then(|(_, e)| e.parse::<i32>().ok())
        .unwrap_or(0);
    let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
    trim_zeros(&format!("{x:.decimals$}"))
}

/// A duration `t_s` (s) to `digits` significant digits in the largest of
/// s, ms, µs and ns in which it reads at least 0.1 (`0.6 µs`, `2 ms`,
/// `50 ms`, `1.5 s`): no exponents in a title.
pub fn duration_text(t_s: f64, digits: usize) -> String {
    let units = [(1.0, "s"), (1e3, "ms"), (1e6, "µs"), (1e9, "ns")];
    let (f, unit) = units
        .iter()
        .copied()
        .find(|(f, _)| (t_s * f).abs() >= 0.1)
        .unwrap_or(units[3]);
    format!("{} {unit}", short_num(t_s * f, digits))
}

fn trim_zeros(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

fn min_max(v: impl Iterator<Item = f64>) -> (f64, f64) {
    v.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

/// The modes in a few words: each one's `f Hz / ξ` when there are few,
/// the ranges of both when there are more.
fn modes_text(modes: &[Mode]) -> String {
    let n = count(modes.len(), "mode");
    if modes.is_empty() {
        return n;
    }
    if modes.len() <= LISTED_MODES {
        let each: Vec<String> = modes
            .iter()
            .map(|m| {
                format!(
                    "{} Hz/{}",
                    short_num(m.freq_hz, 4),
                    short_num(m.damping_ratio, 3)
                )
            })
            .collect();
        return format!("{n} (f/ξ: {})", each.join(", "));
    }
    let f = min_max(modes.iter().map(|m| m.freq_hz));
    let z = min_max(modes.iter().map(|m| m.damping_ratio));
    format!("{n} ({} Hz, ξ {})", range_text(f, 4), range_text(z, 3))
}

/// `lo … hi` to `digits` significant digits, or one value when both read
/// the same (`ξ 0.05`, not `ξ 0.05 … 0.05`).
fn range_text((lo, hi): (f64, f64), digits: usize) -> String {
    let (a, b) = (short_num(lo, digits), short_num(hi, digits));
    if a == b { a } else { format!("{a} … {b}") }
}

fn road_text(road: &Road) -> String {
    match road {
        Road::Sine {
            amplitude_m,
            wavelength_m,
        } => format!(
            "sine road {} mm / {} m",
            short_num(amplitude_m * 1e3, 4),
            short_num(*wavelength_m, 4)
        ),
        Road::Harmonics { components } => {
            format!("road of {}", count(components.len(), "harmonic"))
        }
        Road::Measured { file, .. } => format!(
            "measured road {}",
            file.file_name()
                .unwrap_or(file.as_os_str())
                .to_string_lossy()
        ),
        Road::Random { class, seed, .. } => format!("ISO 8608 class {class:?} road, seed {seed}"),
        Road::Surface { file, .. } => format!(
            "road surface {}",
            file.file_name()
                .unwrap_or(file.as_os_str())
                .to_string_lossy()
        ),
        Road::Crg { file, .. } => format!(
            "OpenCRG road {}",
            file.file_name()
                .unwrap_or(file.as_os_str())
                .to_string_lossy()
        ),
        Road::Texture { class, seed, .. } => {
            format!("class {class:?} texture, seed {seed}")
        }
    }
}

/// One line of `scene`'s parameters, its tyre described by `modes` (given
/// or identified): points, modes, road, speed, ramp, step and contact scheme.
pub fn scene_summary(scene: &Scene, modes: &[Mode]) -> String {
    let ramp = if scene.ramp_s > 0.0 {
        format!(", ramp {} s", short_num(scene.ramp_s, 4))
    } else {
        String::new()
    };
    format!(
        "{}, {}, {}, V = {} m/s ({} km/h){ramp}, dt = {} s, {:?} contact",
        count(scene.num_points(), "point"),
        modes_text(modes),
        road_text(&scene.road),
        short_num(scene.speed_mps, 4),
        short_num(scene.speed_mps * 3.6, 4),
        short_num(scene.dt_s, 4),
        scene.contact_scheme
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_written_by_hand() {
        // a step computed as 1/10^7 prints with 17 digits by `{:e}`
        let dt = 1.0 / 1e7 * (1.0 + f64::EPSILON);
        assert_ne!(format!("{dt:e}"), "1e-7");
        assert_eq!(short_num(dt, 4), "1e-7");
        assert_eq!(short_num(2.5e-5, 4), "2.5e-5");
        assert_eq!(short_num(0.012, 4), "0.012");
        assert_eq!(short_num(36.0, 4), "36");
        assert_eq!(short_num(-4.5678, 3), "-4.57");
        assert_eq!(short_num(9.99996, 4), "10");
        assert_eq!(short_num(1_234_567.0, 3), "1.23e6");
        assert_eq!(short_num(0.0, 4), "0");
        assert_eq!(short_num(f64::NAN, 4), "NaN");
    }

    #[test]
    fn durations_read_in_a_unit_without_exponents() {
        assert_eq!(duration_text(6e-7, 3), "0.6 µs");
        assert_eq!(duration_text(2e-3, 3), "2 ms");
        assert_eq!(duration_text(0.05, 3), "50 ms");
        assert_eq!(duration_text(1.5, 3), "1.5 s");
        assert_eq!(duration_text(2.5e-9, 3), "2.5 ns");
        assert_eq!(duration_text(1e-4, 3), "0.1 ms");
        // every duration from 1 ns to 100 s: no exponent, value read back
        let mut t = 1e-9;
        while t < 100.0 {
            let s = duration_text(t, 4);
            assert!(!s.contains('e'), "{t} -> {s}");
            let (v, unit) = s.split_once(' ').unwrap();
            let f = match unit {
                "s" => 1.0,
                "ms" => 1e-3,
                "µs" => 1e-6,
                "ns" => 1e-9,
                u => panic!("unit {u}"),
            };
            let back = v.parse::<f64>().unwrap() * f;
            assert!((back - t).abs() <= 5e-4 * t, "{t} -> {s}");
            t *= 3.7;
        }
    }

    /// Every formatted number reads back within its rounding.
    #[test]
    fn short_numbers_read_back_within_their_digits() {
        let mut x = 1.234_567e-9;
        while x < 1e9 {
            for v in [x, -x] {
                let back: f64 = short_num(v, 4).parse().unwrap();
                assert!((back - v).abs() <= 5e-4 * v.abs(), "{v} -> {back}");
            }
            x *= 7.3;
        }
    }

    #[test]
    fn the_summary_has_no_long_floats_and_lists_few_modes() {
        let mut scene = Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../presets/paper.ron"
            )),
            "paper",
        )
        .unwrap();
        scene.dt_s = 1.0 / 1e7 * (1.0 + f64::EPSILON);
        let mode = |freq_hz: f64, damping_ratio: f64| Mode {
            freq_hz,
            damping_ratio,
            residue: Vec::new(),
            shape: vec![1.0; 5],
        };
        let modes = [mode(52.34567, 0.0123456), mode(80.0, 0.03)];
        let s = scene_summary(&scene, &modes);
        assert!(s.contains("dt = 1e-7 s"), "{s}");
        assert!(s.contains("52.35 Hz/0.0123"), "{s}");
        // no number longer than a handful of digits
        let longest = s
            .split(|c: char| !(c.is_ascii_digit() || c == '.'))
            .map(str::len)
            .max()
            .unwrap();
        assert!(longest <= 8, "{s}");
        let many: Vec<Mode> = (0..13)
            .map(|k| mode(50.0 + 10.0 * k as f64, 0.02))
            .collect();
        // one damping ratio for all: said once
        let s = scene_summary(&scene, &many);
        assert!(s.contains("13 modes (50 … 170 Hz, ξ 0.02)"), "{s}");
        let mut varied = many.clone();
        varied[4].damping_ratio = 0.05;
        let s = scene_summary(&scene, &varied);
        assert!(s.contains("13 modes (50 … 170 Hz, ξ 0.02 … 0.05)"), "{s}");
    }
}
