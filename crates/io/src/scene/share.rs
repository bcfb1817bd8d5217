//! A scene carried by a link: the URL fragment `#scene=v1.` followed by the
//! base64url (no padding) of the deflate-compressed RON of the scene. The
//! link holds the whole scene, so a scene that needs files beside it (a
//! measured tyre's responses, a measured road) cannot travel in one and is
//! refused, with the reason; so is a link whose scene decompresses to more
//! than [`MAX_SHARED_SCENE_BYTES`].

use super::{Scene, Tyre};
use crate::scene::SceneError;
use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use std::path::PathBuf;
use tirecontact_core::model::road::Road;

/// What precedes the payload in the fragment: the key and the format version.
pub const FRAGMENT_KEY: &str = "scene=v1.";

/// Largest decompressed scene a link may carry (bytes): 1 MiB, a hundred
/// times the paper preset.
pub const MAX_SHARED_SCENE_BYTES: usize = 1 << 20;

/// The base URL of `tirecontact share` when none is given: the page itself,
/// relative to wherever it is served.
pub const DEFAULT_BASE_URL: &str = "index.html";

/// Why a scene cannot be put into a link, or a link read back.
#[derive(Debug, thiserror::Error)]
pub enum ShareError {
    /// The scene reads a file that a link cannot carry.
    #[error(
        "the scene reads its {what} from {}: a link carries the scene alone, not the files it reads; share a scene without a {what}",
        .path.display()
    )]
    NeedsFile {
        /// The field naming the file (`tyre.file`, `road.file`).
        field: &'static str,
        path: PathBuf,
        /// What the file holds, in words.
        what: &'static str,
    },
    /// The scene's RON is larger than a link may carry.
    #[error("the scene takes {bytes} bytes, more than the {limit} bytes a link may carry")]
    TooLarge { bytes: usize, limit: usize },
    /// The text has no `scene=` key in its fragment.
    #[error("no scene in the link: expected a fragment `#{FRAGMENT_KEY}…`")]
    NoScene,
    /// The `scene=` value has a version this program does not read.
    #[error("scene link version `{version}`: expected `v1` (made by a newer program?)")]
    Version { version: String },
    /// The payload is not base64url.
    #[error("the scene in the link is not base64url: {0}")]
    Base64(#[from] base64::DecodeError),
    /// The payload is not a deflate stream.
    #[error("the scene in the link is not deflate-compressed data: {reason}")]
    Deflate { reason: String },
    /// The decompressed scene is not UTF-8 text.
    #[error("the scene in the link is not UTF-8 text: {0}")]
    Utf8(#[from] std::string::FromUtf8Error),
    /// The scene in the link does not parse or is invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
}

/// The files `scene` reads, as `(field, path, what)`: a measured tyre's
/// responses, a measured road's profile, a road surface's grid.
fn needed_file(scene: &Scene) -> Option<ShareError> {
    if let Tyre::Measured { file, .. } = &scene.tyre {
        return Some(ShareError::NeedsFile {
            field: "tyre.file",
            path: file.clone(),
            what: "measured tyre",
        });
    }
    if let Tyre::FeModes { file, .. } = &scene.tyre {
        return Some(ShareError::NeedsFile {
            field: "tyre.file",
            path: file.clone(),
            what: "FE tyre",
        });
    }
    if let Road::Measured { file, .. } = &scene.road {
        return Some(ShareError::NeedsFile {
            field: "road.file",
            path: file.clone(),
            what: "measured road",
        });
    }
    if let Road::Surface { file, .. } = &scene.road {
        return Some(ShareError::NeedsFile {
            field: "road.file",
            path: file.clone(),
            what: "road surface file",
        });
    }
    if let Road::Crg { file, .. } = &scene.road {
        return Some(ShareError::NeedsFile {
            field: "road.file",
            path: file.clone(),
            what: "OpenCRG road file",
        });
    }
    None
}

/// The fragment value of `scene` (without `#`): `scene=v1.` and the
/// base64url of its deflate-compressed RON.
pub fn fragment(scene: &Scene) -> Result<String, ShareError> {
    if let Some(e) = needed_file(scene) {
        return Err(e);
    }
    let ron = scene.to_ron_string();
    if ron.len() > MAX_SHARED_SCENE_BYTES {
        return Err(ShareError::TooLarge {
            bytes: ron.len(),
            limit: MAX_SHARED_SCENE_BYTES,
        });
    }
    let packed = miniz_oxide::deflate::compress_to_vec(ron.as_bytes(), 9);
    Ok(format!("{FRAGMENT_KEY}{}", URL_SAFE_NO_PAD.encode(packed)))
}

/// The link to `scene` on the page at `base_url` (any fragment of
/// `base_url` is replaced).
pub fn link(scene: &Scene, base_url: &str) -> Result<String, ShareError> {
    let base = base_url.split('#').next().unwrap_or("");
    Ok(format!("{base}#{}", fragment(scene)?))
}

/// The scene of a link, a fragment (`#scene=…`) or a fragment's value
/// (`scene=…`); `Ok(None)` when it has no `scene=` key (a plain page
/// link). Other `&`-separated keys of the fragment are ignored.
pub fn scene_in(text: &str) -> Result<Option<Scene>, ShareError> {
    let fragment = match text.split_once('#') {
        Some((_, f)) => f,
        None => text,
    };
    let Some(value) = fragment.split('&').find_map(|kv| kv.strip_prefix("scene=")) else {
        return Ok(None);
    };
    let Some((version, payload)) = value.split_once('.') else {
        return Err(ShareError::Version {
            version: value.chars().take(12).collect(),
        });
    };
    if version != "v1" {
        return Err(ShareError::Version {
            version: version.chars().take(12).collect(),
        });
    }
    // tolerate the padding some tools add back
    let packed = URL_SAFE_NO_PAD.decode(payload.trim_end_matches('='))?;
    let ron = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_SHARED_SCENE_BYTES)
        .map_err(|e| match e.status {
        miniz_oxide::inflate::TINFLStatus::HasMoreOutput => ShareError::TooLarge {
            bytes: MAX_SHARED_SCENE_BYTES + 1,
            limit: MAX_SHARED_SCENE_BYTES,
        },
        status => ShareError::Deflate {
            reason: format!("{status:?}"),
        },
    })?;
    let text = String::from_utf8(ron)?;
    let scene = Scene::parse(&text, "(scene link)")?;
    if let Some(e) = needed_file(&scene) {
        return Err(e);
    }
    Ok(Some(scene))
}

/// [`scene_in`] for text that must hold a scene.
pub fn scene_of(text: &str) -> Result<Scene, ShareError> {
    scene_in(text)?.ok_or(ShareError::NoScene)
}

#[cfg(test)]
mod tests {
    /// The paper's preset, the visualiser's default scene.
    const PAPER: &str = include_str!(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../presets/paper.ron"
    ));

    use super::*;

    /// Every preset of the repository that reads no file.
    fn shipped() -> Vec<(String, Scene)> {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
        let mut out = Vec::new();
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "ron") {
                let name = path.file_name().unwrap().to_string_lossy().into_owned();
                out.push((name, Scene::load(&path).unwrap()));
            }
        }
        assert!(out.len() >= 10, "presets not found");
        out
    }

    fn payload(link: &str) -> &str {
        link.split_once("#scene=v1.").unwrap().1
    }

    #[test]
    fn every_shipped_preset_travels_in_a_link_and_comes_back_equal() {
        let mut carried = 0;
        for (name, scene) in shipped() {
            match link(&scene, DEFAULT_BASE_URL) {
                Ok(url) => {
                    assert!(url.starts_with("index.html#scene=v1."), "{name}: {url}");
                    let p = payload(&url);
                    assert!(
                        p.bytes()
                            .all(|b| b.is_ascii_alphanumeric() || b == b'-' || b == b'_'),
                        "{name}: not base64url without padding: {p}"
                    );
                    let mut back = scene_of(&url).unwrap();
                    // the folder a scene was read from does not travel
                    back.base_dir = scene.base_dir.clone();
                    assert_eq!(back, scene, "{name}");
                    carried += 1;
                }
                Err(ShareError::NeedsFile { field, .. }) => {
                    assert!(
                        name.starts_with("measured")
                            || matches!(scene.tyre, Tyre::FeModes { .. })
                            || matches!(scene.road, Road::Surface { .. } | Road::Crg { .. }),
                        "{name} refused: {field}"
                    );
                }
                Err(e) => panic!("{name}: {e}"),
            }
        }
        assert!(carried >= 10, "only {carried} presets carried");
    }

    #[test]
    fn a_link_keeps_its_base_and_is_much_shorter_than_the_ron() {
        let scene = Scene::parse(PAPER, "paper.ron").unwrap();
        let url = link(&scene, "https://example.org/tc/index.html#old").unwrap();
        assert!(url.starts_with("https://example.org/tc/index.html#scene=v1."));
        let ron = scene.to_ron_string();
        assert!(
            payload(&url).len() * 2 < ron.len(),
            "{} vs {}",
            payload(&url).len(),
            ron.len()
        );
        // other keys of the fragment are ignored
        let with_view = format!("{url}&view=scene");
        assert_eq!(scene_of(&with_view).unwrap().name, scene.name);
    }

    #[test]
    fn a_measured_tyre_or_road_is_refused_both_ways_with_the_field() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
        let measured = Scene::load(&dir.join("measured_example.ron")).unwrap();
        let e = link(&measured, DEFAULT_BASE_URL).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("the scene reads its measured tyre from "),
            "{e}"
        );
        assert!(e.to_string().contains("measured tyre"), "{e}");

        let mut road = Scene::parse(PAPER, "paper.ron").unwrap();
        road.road = Road::Measured {
            file: PathBuf::from("/etc/passwd"),
            looped: false,
        };
        let e = link(&road, DEFAULT_BASE_URL).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("the scene reads its measured road from /etc/passwd:"),
            "{e}"
        );
        // a hand-made link naming a file is refused too, not read
        let ron = road.to_ron_string();
        let packed = miniz_oxide::deflate::compress_to_vec(ron.as_bytes(), 6);
        let url = format!("#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed));
        let e = scene_of(&url).unwrap_err();
        assert!(
            matches!(
                e,
                ShareError::NeedsFile {
                    field: "road.file",
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn a_scene_over_one_megabyte_is_refused_both_ways() {
        let mut scene = Scene::parse(PAPER, "paper.ron").unwrap();
        scene.description = "x".repeat(MAX_SHARED_SCENE_BYTES);
        let e = fragment(&scene).unwrap_err();
        assert!(matches!(e, ShareError::TooLarge { .. }), "{e}");
        // a small link that inflates past the limit (a compression bomb)
        let ron = scene.to_ron_string();
        let packed = miniz_oxide::deflate::compress_to_vec(ron.as_bytes(), 9);
        assert!(packed.len() < 10_000, "{}", packed.len());
        let url = format!("index.html#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed));
        let e = scene_of(&url).unwrap_err();
        assert!(matches!(e, ShareError::TooLarge { .. }), "{e}");
        assert!(e.to_string().contains("1048576 bytes"), "{e}");
        // just under the limit passes
        let rest = ron.len() - MAX_SHARED_SCENE_BYTES;
        scene.description = "x".repeat(MAX_SHARED_SCENE_BYTES - 1 - rest);
        assert_eq!(scene.to_ron_string().len(), MAX_SHARED_SCENE_BYTES - 1);
        let back = scene_of(&link(&scene, "").unwrap()).unwrap();
        assert_eq!(back.description.len(), scene.description.len());
    }

    #[test]
    fn broken_links_are_refused_with_the_reason() {
        assert!(scene_in("index.html").unwrap().is_none());
        assert!(scene_in("index.html#view=scene").unwrap().is_none());
        assert!(matches!(scene_of("index.html"), Err(ShareError::NoScene)));
        let e = scene_of("#scene=v2.abc").unwrap_err();
        assert!(e.to_string().contains("`v2`"), "{e}");
        let e = scene_of("#scene=abc").unwrap_err();
        assert!(matches!(e, ShareError::Version { .. }), "{e}");
        let e = scene_of("#scene=v1.a*b").unwrap_err();
        assert!(matches!(e, ShareError::Base64(_)), "{e}");
        let e = scene_of("#scene=v1.AAAAAAAA").unwrap_err();
        assert!(matches!(e, ShareError::Deflate { .. }), "{e}");
        let packed = miniz_oxide::deflate::compress_to_vec(&[0xff, 0xfe, 0x00], 6);
        let e = scene_of(&format!("#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed))).unwrap_err();
        assert!(matches!(e, ShareError::Utf8(_)), "{e}");
        let packed = miniz_oxide::deflate::compress_to_vec(b"Scene(name: \"x\")", 6);
        let e = scene_of(&format!("#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed))).unwrap_err();
        assert!(e.to_string().starts_with("(scene link):"), "{e}");
        // an invalid value names the field
        let mut scene = Scene::parse(PAPER, "paper.ron").unwrap();
        scene.dt_s = -1.0;
        let packed = miniz_oxide::deflate::compress_to_vec(scene.to_ron_string().as_bytes(), 6);
        let e = scene_of(&format!("#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed))).unwrap_err();
        assert!(e.to_string().contains("dt_s"), "{e}");
    }

    proptest::proptest! {
        /// Any name and description (any Unicode, any length up to a few
        /// kB) and any speed travel unchanged.
        #[test]
        fn any_text_and_speed_travel_unchanged(
            name in "\\PC{1,40}",
            description in "\\PC{0,2000}",
            speed in 0.0f64..80.0,
        ) {
            let mut scene = Scene::parse(PAPER, "paper.ron").unwrap();
            scene.name = name;
            scene.description = description;
            scene.speed_mps = speed;
            proptest::prop_assume!(scene.validate().is_ok());
            let back = scene_of(&link(&scene, "p.html").unwrap()).unwrap();
            proptest::prop_assert_eq!(back, scene);
        }
    }
}
