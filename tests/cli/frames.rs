//! `run PRESET --frames DIR`: (t1 - t0) × slow motion × fps PNG frames of the
//! requested size (read from the PNG header, no image decoder needed), not
//! blank; bad settings are refused naming the option.

use crate::support::{bin, temp_dir};

/// Width and height from a PNG's IHDR chunk.
fn png_size(bytes: &[u8]) -> (u32, u32) {
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "not a PNG");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    (be(&bytes[16..20]), be(&bytes[20..24]))
}

#[test]
fn frames_count_size_and_content() {
    let tmp = temp_dir();
    let dir = tmp.path().join("frames");
    let o = bin()
        .args([
            "run",
            "presets/three_points.ron",
            "--duration",
            "0.06",
            "--fps",
            "30",
            "--slow-motion",
            "10",
            "--frames-from",
            "0.04",
            "--frame-size",
            "480x270",
            "--frames",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // (0.06 - 0.04) s × 10 × 30 fps = 6 frames
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert_eq!(files.len(), 6, "{files:?}");
    assert!(files[0].ends_with("frame_00000.png"));
    assert!(files[5].ends_with("frame_00005.png"));
    let mut sizes = Vec::new();
    for f in &files {
        let bytes = std::fs::read(f).unwrap();
        assert_eq!(png_size(&bytes), (480, 270));
        sizes.push(bytes.len());
    }
    // a blank 480x270 PNG compresses to well under 2 kB; a drawn frame does not
    assert!(sizes.iter().all(|s| *s > 8000), "{sizes:?}");

    let o = bin()
        .args(["run", "presets/three_points.ron", "--fps", "0", "--frames"])
        .arg(tmp.path().join("never"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("fps = 0") && err.contains("expected"), "{err}");
}

/// A second, shorter export into the same folder is refused (the first
/// one's last frames would stay behind and join the new ones in a video)
/// unless `--frames-clear` removes the old frames first.
#[test]
fn old_frames_are_refused_unless_cleared() {
    let tmp = temp_dir();
    let dir = tmp.path().join("frames");
    let export = |from: &str, clear: bool| {
        let mut c = bin();
        c.args([
            "run",
            "presets/three_points.ron",
            "--duration",
            "0.06",
            "--fps",
            "30",
            "--slow-motion",
            "10",
            "--frame-size",
            "320x200",
            "--frames-from",
            from,
            "--frames",
        ])
        .arg(&dir);
        if clear {
            c.arg("--frames-clear");
        }
        c.output().unwrap()
    };
    let count = || std::fs::read_dir(&dir).unwrap().count();
    let o = export("0.04", false);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(count(), 6);
    let o = export("0.05", false);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("already holds 6 frames of an earlier export"),
        "{err}"
    );
    assert_eq!(count(), 6, "the refused export wrote or removed frames");
    let o = export("0.05", true);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(count(), 3, "old frames left behind");
}
