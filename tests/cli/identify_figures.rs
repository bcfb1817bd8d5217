//! `identify --figures` draws Fig. 2 as `run --plot` draws its force panel:
//! impact spikes clipped by default, whole with `--figures-unclipped` (the
//! figures' contents are checked in `output::paper_figures`' unit test).

use crate::support::{bin, temp_dir};

#[test]
fn identify_figures_clip_by_default_and_draw_whole_on_request() {
    let tmp = temp_dir();
    let d = tmp.path();
    let mut fig2 = Vec::new();
    for (sub, extra) in [("clipped", None), ("whole", Some("--figures-unclipped"))] {
        let dir = d.join(sub);
        std::fs::create_dir_all(&dir).unwrap();
        let o = bin()
            .args(["identify", "presets/paper.ron", "--figures"])
            .arg(&dir)
            .args(extra)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8_lossy(&o.stdout);
        for f in ["paper_fig1_displacement.png", "paper_fig2_force.png"] {
            assert!(out.contains(f), "{out}");
            assert_eq!(&std::fs::read(dir.join(f)).unwrap()[1..4], b"PNG");
        }
        fig2.push(std::fs::read(dir.join("paper_fig2_force.png")).unwrap());
    }
    // the spikes are cut in one
    assert_ne!(fig2[0], fig2[1]);
}

/// `identify --data` of a UFF file takes its points from the file's nodes
/// and its band from --band-hz, and prints ξ to 6 significant digits; a
/// CSV file without --points is refused, saying why.
#[test]
fn identify_data_takes_points_from_the_file_and_the_band_from_the_flag() {
    let out = bin()
        .args([
            "identify",
            "--data",
            "tests/data/uff/time3.uff",
            "--band-hz",
            "0",
            "450",
        ])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // MODEL3: 52 Hz at ξ = 0.03, 131 Hz at 0.02, 247 Hz at 0.04
    for (f, xi) in [
        ("52.00", "xi 0.0300"),
        ("131.00", "xi 0.0200"),
        ("247.00", "xi 0.0400"),
    ] {
        let line = text
            .lines()
            .find(|l| l.contains(f) && l.contains(" Hz "))
            .unwrap_or_else(|| panic!("{f} Hz in {text}"));
        let digits = line
            .split("xi ")
            .nth(1)
            .unwrap()
            .split_whitespace()
            .next()
            .unwrap();
        assert!(line.contains(xi) && digits.len() == 9, "{line}");
    }
    assert!(
        text.contains("nodes [101, 102, 103] as points 0..3"),
        "{text}"
    );
    let dir = temp_dir();
    let csv = dir.path().join("g.csv");
    std::fs::write(&csv, "t_s,g0_0\n0,0\n0.001,1\n").unwrap();
    let out = bin()
        .args(["identify", "--data", csv.to_str().unwrap()])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("expected --points N"),
        "{err}"
    );
}

/// A driving point whose residues change sign writes no model (`-o`
/// refused, the fit shown); all negative ones point at a reversed
/// direction.
#[test]
fn identify_data_checks_the_driving_point_before_writing_a_model() {
    let dir = temp_dir();
    for (signs, want) in [
        (
            [1.0, -0.5],
            "residues change sign from mode to mode (negative at modes [1])",
        ),
        ([-1.0, -0.5], "probably reversed (--flip-direction 0)"),
    ] {
        // receptance of two modes, 52 Hz ξ 0.03 and 131 Hz ξ 0.02, residues `signs` (1/kg)
        let mut csv = String::from("freq_hz,h0_0_re,h0_0_im\n");
        for k in 0..=1000 {
            let w = std::f64::consts::TAU * f64::from(k);
            let (mut re, mut im) = (0.0, 0.0);
            for (a, (f, xi)) in signs.iter().zip([(52.0, 0.03), (131.0, 0.02)]) {
                let wn = std::f64::consts::TAU * f;
                let (dr, di) = (wn * wn - w * w, 2.0 * xi * w * wn);
                let d2 = dr * dr + di * di;
                re += a * dr / d2;
                im -= a * di / d2;
            }
            csv.push_str(&format!("{k},{re:e},{im:e}\n"));
        }
        let data = dir.path().join("h.csv");
        std::fs::write(&data, csv).unwrap();
        let model = dir.path().join("m.ron");
        let out = bin()
            .args([
                "identify",
                "--data",
                data.to_str().unwrap(),
                "--points",
                "1",
                "-o",
            ])
            .arg(&model)
            .output()
            .unwrap();
        let (text, err) = (
            String::from_utf8_lossy(&out.stdout),
            String::from_utf8_lossy(&out.stderr),
        );
        assert!(!out.status.success(), "{text}{err}");
        assert!(
            text.contains("52.00 Hz") && text.contains("131.00 Hz"),
            "{text}"
        );
        assert!(
            text.contains(want) && err.contains("not written"),
            "{text}{err}"
        );
        assert!(!model.exists());
    }
}
