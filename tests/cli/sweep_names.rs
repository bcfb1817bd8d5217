//! `sweep`: a parameter path with spaces around it (`--param " speed_mps "`,
//! a quoted name) is the path; the sweep table names its columns as `run -o`
//! names the same quantities (`q{i}_N` → `q{i}_smooth_max_N`,
//! `q{i}_smooth_rms_N`, `q{i}_1ms_max_N`; `contact{i}` →
//! `contact{i}_fraction`), not `max_force_n_q{i}`.

use crate::support::{bin, temp_dir};

fn header(path: &std::path::Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let first = text.lines().next().unwrap_or_default();
    first.split(',').map(String::from).collect()
}

#[test]
fn a_padded_param_is_trimmed_and_columns_follow_the_run_csv() {
    let tmp = temp_dir();
    let dir = tmp.path();
    let (table, run_csv) = (dir.join("sweep.csv"), dir.join("run.csv"));
    let o = bin()
        .args([
            "sweep",
            "presets/three_points.ron",
            "--param",
            " speed_mps ",
            "--from",
            "10",
            "--to",
            "12",
            "--steps",
            "2",
            "--duration",
            "0.05",
            "-o",
        ])
        .arg(&table)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("of speed_mps from 10 to 12"), "{out}");
    let sweep = header(&table);
    assert_eq!(sweep[0], "speed_mps");
    let o = bin()
        .args([
            "run",
            "presets/three_points.ron",
            "--duration",
            "0.001",
            "-o",
        ])
        .arg(&run_csv)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let run = header(&run_csv);
    // each point's force and contact columns of the run, renamed as the
    // sweep's statistics of them: the suffix after the point's name
    let renamed = |prefix: &str, stats: &[&str]| -> Vec<String> {
        let mut want = Vec::new();
        for stat in stats {
            for c in &run {
                let Some(rest) = c.strip_prefix(prefix) else {
                    continue;
                };
                let (index, unit) = rest.split_once('_').unwrap_or((rest, ""));
                if index.is_empty() || !index.bytes().all(|b| b.is_ascii_digit()) {
                    continue;
                }
                want.push(if unit.is_empty() {
                    format!("{prefix}{index}_{stat}")
                } else {
                    format!("{prefix}{index}_{stat}_{unit}")
                });
            }
        }
        want
    };
    let forces = renamed("q", &["smooth_max", "smooth_rms", "1ms_max"]);
    assert_eq!(forces.len(), 9, "three points, three statistics: {run:?}");
    assert_eq!(&sweep[1..10], &forces[..], "sweep {sweep:?}\nrun {run:?}");
    // then impacts per second, mean and largest impulse: 9 columns
    let contact = renamed("contact", &["fraction"]);
    assert_eq!(contact.len(), 3, "{run:?}");
    assert_eq!(&sweep[19..22], &contact[..], "sweep {sweep:?}\nrun {run:?}");
}
