//! A scene carried by a link: the URL fragment `#scene=v2.` followed by the
//! base64url (no padding) of the deflate-compressed RON of the scene and,
//! after it, the CRC-32 (big-endian, 4 bytes) of those compressed bytes.
//! The check sum makes a damaged link (a character changed, dropped or cut
//! off) refused rather than opened as another scene: a changed character
//! alters at most 6 bits in a row of the payload, which CRC-32 always
//! detects. Links of the first format, `#scene=v1.` and the payload without
//! a check sum, still open. The link holds the whole scene, so a scene that
//! needs files beside it (a measured tyre's responses, a measured road)
//! cannot travel in one and is refused, with the reason; so is a link whose
//! scene decompresses to more than [`MAX_SHARED_SCENE_BYTES`].

use super::{Scene, Tyre};
use crate::scene::SceneError;
use base64::Engine as _;
use base64::engine::general_purpose::URL_SAFE_NO_PAD;
use std::path::PathBuf;
use tirecontact_core::model::road::Road;

/// What precedes the payload in the fragment: the key and the format
/// version links are made in.
pub const FRAGMENT_KEY: &str = "scene=v2.";

/// Largest decompressed scene a link may carry (bytes): 1 MiB, a hundred
/// times the paper preset.
pub const MAX_SHARED_SCENE_BYTES: usize = 1 << 20;

/// The base URL of `tirecontact share` when none is given: the page itself,
/// relative to wherever it is served.
pub const DEFAULT_BASE_URL: &str = "index.html";

/// Bytes of the check sum that ends a `v2` payload.
const CHECK_BYTES: usize = 4;

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
    /// The link's version is a later one than this program reads.
    #[error(
        "This link was made by a newer version of the visualiser (link version v{version}; this one reads v1 and v2): open it in the page it came from."
    )]
    Newer { version: u32 },
    /// The link was damaged on its way (a character changed, dropped or
    /// added, or the link cut short): what gave it away, in words.
    #[error(
        "This link is damaged or cut short ({what}); copy the whole link again from where you got it, or use File > Share link in the visualiser to make a new one."
    )]
    Damaged { what: String },
    /// The scene of an intact link does not parse or is invalid (a link
    /// written by hand, or by a program whose scenes differ).
    #[error(transparent)]
    Scene(#[from] SceneError),
}

impl ShareError {
    fn damaged(what: impl Into<String>) -> Self {
        Self::Damaged { what: what.into() }
    }
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

/// The fragment value of `scene` (without `#`): `scene=v2.` and the
/// base64url of its deflate-compressed RON followed by the CRC-32 of the
/// compressed bytes.
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
    let mut packed = miniz_oxide::deflate::compress_to_vec(ron.as_bytes(), 9);
    let check = crc32fast::hash(&packed);
    packed.extend_from_slice(&check.to_be_bytes());
    Ok(format!("{FRAGMENT_KEY}{}", URL_SAFE_NO_PAD.encode(packed)))
}

/// The link to `scene` on the page at `base_url` (any fragment of
/// `base_url` is replaced).
pub fn link(scene: &Scene, base_url: &str) -> Result<String, ShareError> {
    let base = base_url.split('#').next().unwrap_or("");
    Ok(format!("{base}#{}", fragment(scene)?))
}

/// Keys of the fragment besides `scene` (the visualiser's `view` and
/// `speed`); a short part with another key is ignored.
const OTHER_KEYS: [&str; 2] = ["view", "speed"];

/// Longest fragment part with an unknown key that is taken for something
/// else than a damaged scene (a scene's payload is hundreds of characters).
const MAX_OTHER_PART: usize = 24;

/// The scene of a link, a fragment (`#scene=…`) or a fragment's value
/// (`scene=…`); `Ok(None)` when it has no `scene=` key (a plain page
/// link). The `view` and `speed` keys of the fragment and short parts
/// with other keys are ignored; a long part with another key (a scene
/// whose `scene=` was damaged) is refused as damaged.
pub fn scene_in(text: &str) -> Result<Option<Scene>, ShareError> {
    let fragment = match text.split_once('#') {
        Some((_, f)) => f,
        None => text,
    };
    let Some(value) = fragment.split('&').find_map(|kv| kv.strip_prefix("scene=")) else {
        let stray = fragment.split('&').find(|part| {
            let key = part.split_once('=').map_or(*part, |(k, _)| k);
            !OTHER_KEYS.contains(&key) && (part.len() > MAX_OTHER_PART || key.contains("scene"))
        });
        return match stray {
            Some(_) => Err(ShareError::damaged("its `scene=` is missing or misspelt")),
            None => Ok(None),
        };
    };
    if value.is_empty() {
        return Err(ShareError::damaged("nothing follows `scene=`"));
    }
    let Some((version, payload)) = value.split_once('.') else {
        return Err(ShareError::damaged("no version before its scene"));
    };
    let number = version
        .strip_prefix('v')
        .filter(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        .and_then(|n| n.parse::<u32>().ok());
    let checked = match number {
        Some(1) => false, // (v1: no check sum)
        Some(2) => true,
        Some(n) if n > 2 => return Err(ShareError::Newer { version: n }),
        _ => {
            return Err(ShareError::damaged(format!(
                "its version `{}` is not one of a link",
                version.chars().take(12).collect::<String>()
            )));
        }
    };
    if payload.is_empty() {
        return Err(ShareError::damaged("it ends after its version"));
    }
    // tolerate the padding some tools add back
    let mut packed = URL_SAFE_NO_PAD
        .decode(payload.trim_end_matches('='))
        .map_err(|e| {
            ShareError::damaged(match e {
                base64::DecodeError::InvalidByte(_, b) if !b.is_ascii_graphic() => {
                    "it holds a character a link does not use".to_string()
                }
                base64::DecodeError::InvalidByte(_, b) => {
                    format!("it holds `{}`, a character a link does not use", b as char)
                }
                _ => "its length or last character is not that of a whole link".to_string(),
            })
        })?;
    if checked {
        if packed.len() <= CHECK_BYTES {
            return Err(ShareError::damaged("it is too short to hold a scene"));
        }
        let at = packed.len() - CHECK_BYTES;
        let stored = u32::from_be_bytes(packed[at..].try_into().expect("4 bytes"));
        packed.truncate(at);
        if crc32fast::hash(&packed) != stored {
            return Err(ShareError::damaged(
                "its check sum does not match its contents",
            ));
        }
    }
    let ron = miniz_oxide::inflate::decompress_to_vec_with_limit(&packed, MAX_SHARED_SCENE_BYTES)
        .map_err(|e| match e.status {
        miniz_oxide::inflate::TINFLStatus::HasMoreOutput => ShareError::TooLarge {
            bytes: MAX_SHARED_SCENE_BYTES + 1,
            limit: MAX_SHARED_SCENE_BYTES,
        },
        _ => ShareError::damaged("its compressed scene does not unpack"),
    })?;
    let text = String::from_utf8(ron).map_err(|_| ShareError::damaged("its scene is not text"))?;
    let scene = match Scene::parse(&text, "(scene link)") {
        Ok(scene) => scene,
        // a v1 link has no check sum: a scene that does not read is most
        // likely a damaged one
        Err(SceneError::Syntax { .. }) if !checked => {
            return Err(ShareError::damaged("its scene does not read as a scene"));
        }
        Err(e) => return Err(e.into()),
    };
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
        link.split_once("#scene=v2.").unwrap().1
    }

    /// A `v2` link of `bytes` (any bytes, not only a scene's RON) with a
    /// right check sum: what a hand-made link or another program gives.
    fn v2_link(bytes: &[u8]) -> String {
        let mut packed = miniz_oxide::deflate::compress_to_vec(bytes, 6);
        packed.extend_from_slice(&crc32fast::hash(&packed).to_be_bytes());
        format!("#scene=v2.{}", URL_SAFE_NO_PAD.encode(packed))
    }

    /// A `v1` link (no check sum) of `bytes`.
    fn v1_link(bytes: &[u8]) -> String {
        let packed = miniz_oxide::deflate::compress_to_vec(bytes, 6);
        format!("#scene=v1.{}", URL_SAFE_NO_PAD.encode(packed))
    }

    #[test]
    fn every_shipped_preset_travels_in_a_link_and_comes_back_equal() {
        let mut carried = 0;
        for (name, scene) in shipped() {
            match link(&scene, DEFAULT_BASE_URL) {
                Ok(url) => {
                    assert!(url.starts_with("index.html#scene=v2."), "{name}: {url}");
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
        assert!(url.starts_with("https://example.org/tc/index.html#scene=v2."));
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
        for url in [v1_link(ron.as_bytes()), v2_link(ron.as_bytes())] {
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
    }

    #[test]
    fn a_scene_over_one_megabyte_is_refused_both_ways() {
        let mut scene = Scene::parse(PAPER, "paper.ron").unwrap();
        scene.description = "x".repeat(MAX_SHARED_SCENE_BYTES);
        let e = fragment(&scene).unwrap_err();
        assert!(matches!(e, ShareError::TooLarge { .. }), "{e}");
        // a small link that inflates past the limit (a compression bomb)
        let ron = scene.to_ron_string();
        for url in [v1_link(ron.as_bytes()), v2_link(ron.as_bytes())] {
            assert!(url.len() < 10_000, "{}", url.len());
            let e = scene_of(&url).unwrap_err();
            assert!(matches!(e, ShareError::TooLarge { .. }), "{e}");
            assert!(e.to_string().contains("1048576 bytes"), "{e}");
        }
        // just under the limit passes
        let rest = ron.len() - MAX_SHARED_SCENE_BYTES;
        scene.description = "x".repeat(MAX_SHARED_SCENE_BYTES - 1 - rest);
        assert_eq!(scene.to_ron_string().len(), MAX_SHARED_SCENE_BYTES - 1);
        let back = scene_of(&link(&scene, "").unwrap()).unwrap();
        assert_eq!(back.description.len(), scene.description.len());
    }

    /// The start every refusal of a damaged link has, and its advice.
    const DAMAGED: &str = "This link is damaged or cut short (";
    const ADVICE: &str = "); copy the whole link again from where you got it, or use File > Share link in the visualiser to make a new one.";

    fn damaged(link: &str) -> String {
        let e = scene_of(link).unwrap_err();
        let text = e.to_string();
        assert!(matches!(e, ShareError::Damaged { .. }), "{link}: {text}");
        assert!(
            text.starts_with(DAMAGED) && text.ends_with(ADVICE),
            "{text}"
        );
        text[DAMAGED.len()..text.len() - ADVICE.len()].to_string()
    }

    #[test]
    fn broken_links_are_refused_in_plain_words() {
        assert!(scene_in("index.html").unwrap().is_none());
        assert!(scene_in("index.html#view=scene").unwrap().is_none());
        assert!(
            scene_in("index.html#top&view=2&speed=max")
                .unwrap()
                .is_none()
        );
        assert!(matches!(scene_of("index.html"), Err(ShareError::NoScene)));
        assert_eq!(damaged("index.html#scene="), "nothing follows `scene=`");
        assert_eq!(damaged("#scene=abc"), "no version before its scene");
        assert_eq!(damaged("#scene=v2."), "it ends after its version");
        assert_eq!(
            damaged("#scene=vx.abc"),
            "its version `vx` is not one of a link"
        );
        assert_eq!(
            damaged("#scene=.abc"),
            "its version `` is not one of a link"
        );
        assert_eq!(
            damaged("#scene=v2.a*bc"),
            "it holds `*`, a character a link does not use"
        );
        assert_eq!(
            damaged("#scene=v2.AAAAA"),
            "its length or last character is not that of a whole link"
        );
        assert_eq!(damaged("#scene=v2.AAAA"), "it is too short to hold a scene");
        assert_eq!(
            damaged("#scene=v2.AAAAAAAAAAA"),
            "its check sum does not match its contents"
        );
        assert_eq!(
            damaged("#scene=v1.AAAAAAAA"),
            "its compressed scene does not unpack"
        );
        assert_eq!(
            damaged(&v1_link(&[0xff, 0xfe, 0x00])),
            "its scene is not text"
        );
        assert_eq!(
            damaged(&v2_link(&[0xff, 0xfe, 0x00])),
            "its scene is not text"
        );
        assert_eq!(
            damaged(&v1_link(b"Scene(nme: \"x\")")),
            "its scene does not read as a scene"
        );
        // the key of the scene damaged: not a plain page link
        let good = link(&Scene::parse(PAPER, "paper.ron").unwrap(), "").unwrap();
        for bad in ["#scenf=", "#scene", "#sene="] {
            let url = good.replacen("#scene=", bad, 1);
            assert_eq!(
                damaged(&url),
                "its `scene=` is missing or misspelt",
                "{url}"
            );
        }
        // a version from a later program says so
        let e = scene_of("#scene=v3.abc").unwrap_err();
        assert!(matches!(e, ShareError::Newer { version: 3 }), "{e}");
        assert!(e.to_string().contains("newer version"), "{e}");
        // an intact link whose scene does not read (hand-made, another
        // program's) keeps the exact reason
        let e = scene_of(&v2_link(b"Scene(name: \"x\")")).unwrap_err();
        assert!(e.to_string().starts_with("(scene link):"), "{e}");
        // an invalid value names the field, in either version
        let mut scene = Scene::parse(PAPER, "paper.ron").unwrap();
        scene.dt_s = -1.0;
        let ron = scene.to_ron_string();
        for url in [v1_link(ron.as_bytes()), v2_link(ron.as_bytes())] {
            let e = scene_of(&url).unwrap_err();
            assert!(e.to_string().contains("dt_s"), "{e}");
        }
        // no message speaks the decoder's language
        for url in ["#scene=", "#scene=v1.AAAAAAAA", "#scene=v2.AAAAAAAAAAA"] {
            let text = scene_of(url).unwrap_err().to_string();
            for jargon in ["Failed", "newer", "deflate", "base64", "Unexpected"] {
                assert!(!text.contains(jargon), "{url}: {text}");
            }
        }
    }

    /// Links of the first format (no check sum) still open.
    #[test]
    fn a_v1_link_still_opens_its_scene() {
        let scene = Scene::parse(PAPER, "paper.ron").unwrap();
        let url = format!(
            "index.html{}&view=2",
            v1_link(scene.to_ron_string().as_bytes())
        );
        let mut back = scene_of(&url).unwrap();
        back.base_dir = scene.base_dir.clone();
        assert_eq!(back, scene);
    }

    /// Every change of one character of the three-points link (each
    /// character replaced by each character of the link alphabet and the
    /// separators, or deleted) is refused or opens the identical scene:
    /// never another scene.
    #[test]
    fn every_one_character_change_of_a_link_is_refused_or_harmless() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../presets");
        let scene = Scene::load(&dir.join("three_points.ron")).unwrap();
        let good = link(&scene, DEFAULT_BASE_URL).unwrap();
        let alphabet: Vec<char> = ('A'..='Z')
            .chain('a'..='z')
            .chain('0'..='9')
            .chain("-_.=&#".chars())
            .collect();
        let chars: Vec<char> = good.chars().collect();
        let payload_at = good.find("v2.").unwrap() + 3;
        let (mut changes, mut refused, mut same, mut same_in_payload) = (0, 0, 0, 0);
        let mut check = |url: String, i: usize| {
            changes += 1;
            match scene_in(&url) {
                Err(_) => refused += 1,
                Ok(Some(mut back)) => {
                    back.base_dir = scene.base_dir.clone();
                    assert_eq!(back, scene, "{url} opened another scene");
                    same += 1;
                    same_in_payload += usize::from(i >= payload_at);
                }
                Ok(None) => panic!("{url} opened as a page without a scene"),
            }
        };
        for i in 0..chars.len() {
            for &c in alphabet.iter().filter(|&&c| c != chars[i]) {
                let mut changed = chars.clone();
                changed[i] = c;
                check(changed.into_iter().collect(), i);
            }
            let mut cut = chars.clone();
            cut.remove(i);
            check(cut.into_iter().collect(), i);
        }
        assert_eq!(changes, chars.len() * alphabet.len());
        assert_eq!(refused + same, changes);
        // every change of the payload is refused; only changes of the base
        // (`index.html`) and of the version's digit leave the scene as it was
        assert_eq!(same_in_payload, 0);
        assert!(same <= 11 * alphabet.len(), "{same} of {changes} opened");
        eprintln!("{changes} changes: {refused} refused, {same} open the same scene");
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
