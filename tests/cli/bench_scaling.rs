//! `bench --scaling --quick`: every size measured in its own process, the
//! table, the fitted exponents and the figure written.

use crate::support::{bin, temp_dir};

#[test]
fn the_scaling_study_writes_its_table_and_figure() {
    let tmp = temp_dir();
    let out = tmp.path().join("scaling");
    let o = bin()
        .args(["bench", "--scaling", "--quick", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(out.join("scaling.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    // four sizes, each with rigid contact and with tread springs, and two
    // of the contact patch
    assert_eq!(rows.len(), 10, "{csv}");
    assert_eq!(rows.iter().filter(|r| r[0] == "patch").count(), 2, "{csv}");
    for r in &rows {
        let step_s: f64 = r[4].parse().unwrap();
        let free_s: f64 = r[5].parse().unwrap();
        assert!(step_s > 0.0 && free_s > 0.0, "{r:?}");
        // each child reports its own peak memory (Linux)
        if cfg!(target_os = "linux") {
            let kb: f64 = r[13].parse().unwrap();
            assert!(kb > 1000.0, "{r:?}");
        }
        // 20 points: the tread holds the pressed third (6) on the road,
        // rigid contact about one point
        if r[1] == "20" {
            let on: f64 = r[7].parse::<f64>().unwrap() * 20.0;
            match r[0] {
                "tread" => assert!((5.5..=7.0).contains(&on), "{r:?}"),
                "rigid" => assert!(on < 3.0, "{r:?}"),
                other => panic!("contact `{other}`"),
            }
        }
        // the patch (20 points across): its pressed third on the road
        if r[0] == "patch" {
            let share: f64 = r[7].parse().unwrap();
            assert!((0.25..=0.42).contains(&share), "{r:?}");
        }
    }
    let md = std::fs::read_to_string(out.join("scaling.md")).unwrap();
    assert!(md.contains("Fitted exponents"), "{md}");
    assert!(out.join("scaling.png").metadata().unwrap().len() > 10_000);
    // a bad size is refused with what was expected
    let o = bin()
        .args(["bench", "--scaling-one", "5"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected P,K,CONTACT"));
}
