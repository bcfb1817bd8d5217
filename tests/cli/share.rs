//! `tirecontact share`: the link printed on one line, read back by the
//! library and by an independent decoder (Python's base64 and zlib), and
//! the refusal of a scene that needs files.

use crate::support::bin;
use std::path::Path;
use tirecontact::Scene;
use tirecontact::scene::share;

fn presets() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("presets")
}

fn share_link(args: &[&str]) -> std::process::Output {
    bin().arg("share").args(args).output().unwrap()
}

#[test]
fn share_prints_one_line_that_opens_the_same_scene() {
    let path = presets().join("three_points.ron");
    let out = share_link(&[path.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    assert_eq!(text.lines().count(), 1, "{text}");
    let link = text.trim_end();
    assert!(link.starts_with("index.html#scene=v2."), "{link}");
    let mut back = share::scene_of(link).unwrap();
    let scene = Scene::load(&path).unwrap();
    back.base_dir = scene.base_dir.clone();
    assert_eq!(back, scene);

    let out = share_link(&[
        path.to_str().unwrap(),
        "--base-url",
        "https://example.org/tirecontact/",
    ]);
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(
        text.starts_with("https://example.org/tirecontact/#scene=v2."),
        "{text}"
    );
}

/// The payload is standard base64url of raw deflate and the CRC-32 of the
/// compressed bytes: Python's decoders (another implementation) check the
/// sum and give back the scene's RON text exactly.
#[test]
fn the_link_decodes_with_pythons_base64_and_zlib() {
    if std::process::Command::new("python3")
        .arg("--version")
        .output()
        .is_err()
    {
        eprintln!("python3 not installed: the independent decoding is not checked");
        return;
    }
    let path = presets().join("paper.ron");
    let out = share_link(&[path.to_str().unwrap()]);
    let link = String::from_utf8(out.stdout).unwrap();
    let payload = link
        .trim_end()
        .split_once("#scene=v2.")
        .unwrap()
        .1
        .to_string();
    let py = "import sys, base64, zlib\n\
              p = sys.argv[1]\n\
              raw = base64.urlsafe_b64decode(p + '=' * (-len(p) % 4))\n\
              packed, check = raw[:-4], int.from_bytes(raw[-4:], 'big')\n\
              assert zlib.crc32(packed) == check, 'check sum'\n\
              sys.stdout.write(zlib.decompress(packed, -15).decode('utf-8'))";
    let out = std::process::Command::new("python3")
        .args(["-c", py, &payload])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let ron = String::from_utf8(out.stdout).unwrap();
    assert_eq!(ron, Scene::load(&path).unwrap().to_ron_string());
}

#[test]
fn a_measured_tyre_is_refused_with_the_field_and_the_reason() {
    let path = presets().join("measured_example.ron");
    let out = share_link(&[path.to_str().unwrap()]);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("measured_example.ron: the scene reads its measured tyre from "),
        "{err}"
    );
    assert!(err.contains("a link carries the scene alone"), "{err}");
}
