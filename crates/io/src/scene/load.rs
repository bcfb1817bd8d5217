//! Scene files: RON text parsed with file, line and column in its
//! messages, bounded reads, pretty RON, atomic saves; and the road profile
//! of a scene's road.

use super::{MAX_SCENE_BYTES, Scene, SceneError, locate};
use std::path::Path;
use tirecontact_core::model::road::{Road, RoadProfile};

fn ron_options() -> ron::Options {
    ron::Options::default()
}

impl Scene {
    /// Parses RON text; `file` names the source in messages.
    pub fn from_ron_str(text: &str, file: &str) -> Result<Scene, SceneError> {
        ron_options().from_str::<Scene>(text).map_err(|e| {
            let (line, col) = skip_blanks(text, e.span.start.line, e.span.start.col);
            SceneError::Syntax {
                file: file.to_string(),
                line,
                col,
                message: format!(
                    "{}{}{}",
                    e.code,
                    syntax_hint(&e.code),
                    source_excerpt(text, line, col)
                ),
            }
        })
    }

    /// Parses and validates RON text.
    pub fn parse(text: &str, file: &str) -> Result<Scene, SceneError> {
        let scene = Self::from_ron_str(text, file)?;
        scene.validate().map_err(|errors| SceneError::Invalid {
            file: file.to_string(),
            at: locate::locate_all(text, errors.iter().map(|e| e.field.as_str())),
            errors,
        })?;
        Ok(scene)
    }

    /// Reads, parses and validates a scene file; relative road files are
    /// resolved against its folder.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        let io = |source: std::io::Error| SceneError::Io {
            path: path.to_path_buf(),
            source: source.into(),
        };
        // a regular file only (a named pipe would block, a device never
        // end), and a bounded read: a runaway file is refused
        let file = crate::fsio::read::open_regular(path).map_err(|e| {
            io(std::io::Error::new(
                e.kind(),
                format!(
                    "{e}: expected {} scene preset file (RON), e.g. presets/paper.ron",
                    if e.kind() == std::io::ErrorKind::NotFound {
                        "an existing"
                    } else {
                        "a"
                    }
                ),
            ))
        })?;
        let too_big = || {
            io(std::io::Error::other(format!(
                "more than {MAX_SCENE_BYTES} bytes: expected a scene file of at most {} MiB",
                MAX_SCENE_BYTES >> 20
            )))
        };
        // a regular file's size is known: one too big is refused unread
        if file.metadata().map_err(io)?.len() > MAX_SCENE_BYTES {
            return Err(too_big());
        }
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(file, MAX_SCENE_BYTES + 1),
            &mut bytes,
        )
        .map_err(io)?;
        if bytes.len() as u64 > MAX_SCENE_BYTES {
            // (grown while read)
            return Err(too_big());
        }
        let file = path.display().to_string();
        let text = String::from_utf8(bytes).map_err(|e| not_utf8(&file, e))?;
        let mut scene = Self::parse(&text, &file)?;
        scene.base_dir = path.parent().map(Path::to_path_buf);
        Ok(scene)
    }

    /// The scene as pretty RON text.
    pub fn to_ron_string(&self) -> String {
        let cfg = ron::ser::PrettyConfig::new()
            .struct_names(true)
            .depth_limit(4)
            .indentor("    ".to_string());
        // Serialising plain data structures cannot fail.
        ron_options()
            .to_string_pretty(self, cfg)
            .unwrap_or_else(|e| format!("// serialisation failed: {e}"))
    }

    /// Saves atomically: writes a temporary file in the same folder, flushes
    /// it to disk, then renames it over `path`. A failed write leaves the old
    /// file intact.
    pub fn save(&self, path: &Path) -> Result<(), SceneError> {
        crate::fsio::write_atomic(path, self.to_ron_string().as_bytes()).map_err(|source| {
            SceneError::Io {
                path: path.to_path_buf(),
                source: source.into(),
            }
        })
    }
}

/// RON reports some errors (a value of the wrong type) where it starts
/// reading, before the blanks that precede the offending token: move the
/// position (1-based line and column, in characters) forward over blanks to
/// that token. Unchanged when only blanks follow.
fn skip_blanks(text: &str, line: usize, col: usize) -> (usize, usize) {
    let (mut l, mut c) = (1, 1);
    let mut chars = text.chars().peekable();
    while (l, c) < (line, col) {
        match chars.next() {
            Some('\n') => (l, c) = (l + 1, 1),
            Some(_) => c += 1,
            None => return (line, col),
        }
    }
    while let Some(&ch) = chars.peek() {
        if !ch.is_whitespace() {
            return (l, c);
        }
        if ch == '\n' {
            (l, c) = (l + 1, 1);
        } else {
            c += 1;
        }
        chars.next();
    }
    (line, col)
}

/// A file that is not UTF-8 text: a syntax error at the first invalid byte
/// (1-based line and column, in characters, as RON counts them).
fn not_utf8(file: &str, e: std::string::FromUtf8Error) -> SceneError {
    let at = e.utf8_error().valid_up_to();
    let bytes = e.as_bytes();
    let before = String::from_utf8_lossy(&bytes[..at]);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    let text = String::from_utf8_lossy(bytes);
    SceneError::Syntax {
        file: file.to_string(),
        line,
        col,
        message: format!(
            "byte 0x{:02X} is not UTF-8: expected a UTF-8 text file (re-save the preset as UTF-8){}",
            // a FromUtf8Error always has an invalid byte at valid_up_to
            bytes[at],
            source_excerpt(&text, line, col)
        ),
    }
}

/// What to do about a RON error whose fix is not where it points: a missing
/// comma is reported at the next value, usually on the next line.
fn syntax_hint(code: &ron::Error) -> &'static str {
    match code {
        ron::Error::ExpectedComma => {
            ": a `,` is missing after the previous value (often at the end of the line above)"
        }
        _ => "",
    }
}

/// The source line `line` (1-based) with a caret under column `col` (1-based,
/// in characters, as RON counts them), so that a syntax or type error shows the
/// field and the value it is about. Empty when the line does not exist.
fn source_excerpt(text: &str, line: usize, col: usize) -> String {
    let Some(src) = text.lines().nth(line.wrapping_sub(1)) else {
        return String::new();
    };
    // long lines (minified files, fuzzed bytes) are cut around the column
    let chars: Vec<char> = src.chars().collect();
    let c = col.saturating_sub(1).min(chars.len());
    let from = c.saturating_sub(60);
    let to = (c + 60).min(chars.len());
    let shown: String = chars[from..to].iter().collect();
    let caret = " ".repeat(c - from);
    format!(
        "\n  {line:>4} | {}{shown}\n       | {}{caret}^",
        if from > 0 { "..." } else { "" },
        if from > 0 { "   " } else { "" }
    )
}

/// The profile of `road`, ready to be sampled: a measured or surface file
/// read relative to `base_dir`, a generated road made after its fields are
/// checked (refused as invalid values of `road`).
pub fn load_road(road: &Road, base_dir: Option<&Path>) -> Result<RoadProfile, SceneError> {
    let path = |file: &Path| match base_dir {
        Some(d) if file.is_relative() => d.join(file),
        _ => file.to_path_buf(),
    };
    match road {
        Road::Measured { file, looped } => {
            let (x_m, z_m) = crate::readers::road::read_profile_csv(&path(file))?;
            Ok(RoadProfile::Measured {
                x_m,
                z_m,
                looped: *looped,
            })
        }
        Road::Surface { file, looped } => Ok(RoadProfile::Surface(std::sync::Arc::new(
            crate::readers::road::read_surface_csv(&path(file), *looped)?,
        ))),
        Road::Crg {
            file,
            u_start_m,
            v_offset_m,
        } => {
            let crg = crate::readers::crg::read_crg(&path(file))
                .map_err(crate::readers::road::RoadFileError::from)?;
            Ok(RoadProfile::Surface(std::sync::Arc::new(
                crg.surface(u_start_m.unwrap_or(crg.u_first_m), *v_offset_m),
            )))
        }
        _ => match RoadProfile::generated(road) {
            Some(Ok(profile)) => Ok(profile),
            Some(Err(errors)) => Err(SceneError::Invalid {
                file: "road".into(),
                errors,
                at: Vec::new(),
            }),
            None => unreachable!("every road without a file is generated"),
        },
    }
}
