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
