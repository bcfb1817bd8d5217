//! # tirecontact
//!
//! Dynamic tyre/road contact by fast modal convolution (see `docs/method.md`, from
//! Meftah & Duhamel, CFM 2011).
//!
//! ## Conventions (method §1)
//!
//! * `P` contact points on the contact line, indices `i, j = 0..P-1`; point `i`
//!   sits at `x_i` (m) with undeformed height `h_i` (m) above the mean road
//!   plane (`h_i < 0` means preload).
//! * `u_i` is the vertical displacement of point `i`, positive **up**, from the
//!   undeformed tyre; `v_i = du_i/dt`.
//! * `q_i >= 0` is the contact force of the road on the tyre, positive up.
//! * SI units everywhere; names carry their unit (`dt_s`, `freq_hz`, ...).
//!
//! ## Module map
//!
//! | module | what | method |
//! |---|---|---|
//! | [`modal`] | modes, poles for every damping ratio, `g(t)`, `g'(t)`, `G(ω)` | §2 |
//! | [`convolution`] | bounded recursive convolution, exact step weights; α/β baseline and direct control | §3 |
//! | [`road`] | road profiles and the preload/road ramp | §4 |
//! | [`simulation`] | the time stepper: tables, state and scratch; the stages of a step (predict, solve, locate, commit); events inside the step; the scaled dense solves of the contact systems (`simulation::contact`) | §4 |
//! | [`drive`] | the run driver and the `Probe` observer every output implements | — |
//! | [`ring`] | ring tyre on an elastic foundation: orders, modes, radial Green functions | §5 |
//! | [`linalg`] | checked dense decompositions (faer): rank terms, least squares, eigenvalues | §3, §6 |
//! | [`lsce`] | LSCE identification, stabilisation diagram, fit report | §6 |
//! | [`identify`] | ring -> sampled responses -> LSCE; `ModeCache`, `PreparedModel` (what a simulation is built from) | §5-6 |
//! | [`scene`] | RON scenes and their validation | — |
//! | [`fsio`] | atomic file writes, temporaries removed on Ctrl-C | — |
//! | [`output`] | CSV writer, headless PNG figures | — |
//! | [`spectrum`] | amplitude/PSD spectra, third-octave bands, run spectra | — |
//! | [`sweep`] | scene parameters by path, multi-threaded sweeps | — |
//! | [`fidelity`] | relative L2 error of a modal model against a reference `G(ω)` | §5-6 |
//! | [`compare`] | a pinned reference run and the difference to it | — |
//! | `gui` | the visualiser (feature `gui`) | — |

pub mod bench;
pub mod compare;
pub mod convolution;
pub mod drive;
pub mod error;
pub mod fidelity;
pub mod fsio;
#[cfg(feature = "gui")]
pub mod gui;
pub mod identify;
pub mod linalg;
pub mod lsce;
pub mod measured;
pub mod metrics;
pub mod modal;
pub mod output;
pub mod phase;
pub mod ring;
pub mod road;
pub mod scene;
pub mod simulation;
pub mod spectrum;
pub mod study;
pub mod sweep;

pub use error::{RunError, SceneError, SolverError};
pub use identify::{ModeCache, PreparedModel};
pub use scene::Scene;
pub use simulation::{IDENTIFIED_RANK_TOLERANCE, Simulation, SolverOptions, StepReport};

/// The preset opened when no file is given (embedded in the binary).
pub const DEFAULT_PRESET: &str = include_str!("../presets/paper.ron");
/// File name of the embedded default preset, for messages.
pub const DEFAULT_PRESET_NAME: &str = "presets/paper.ron";

/// The layers of `ARCHITECTURE.md`: every import of a module points to its
/// own layer or one below (tests inside a module may import anything).
#[cfg(test)]
mod layers {
    use std::collections::BTreeMap;
    use std::path::Path;

    /// Each top-level module and its layer (0 the ground floor).
    const LAYERS: &[(&str, u8)] = &[
        ("error", 0),
        ("linalg", 0),
        ("fsio", 0),
        ("modal", 0),
        ("phase", 0),
        ("ring", 1),
        ("lsce", 1),
        ("measured", 1),
        ("road", 1),
        ("convolution", 1),
        ("fidelity", 1),
        ("scene", 2),
        ("identify", 3),
        ("simulation", 4),
        ("drive", 4),
        ("output", 5),
        ("compare", 6),
        ("spectrum", 6),
        ("metrics", 6),
        ("bench", 6),
        ("sweep", 7),
        ("study", 7),
        ("cli", 8),
        ("gui", 8),
    ];

    /// The crate root's re-exports, by the module that defines them.
    const ROOT: &[(&str, &str)] = &[
        ("Scene", "scene"),
        ("ModeCache", "identify"),
        ("PreparedModel", "identify"),
        ("SceneError", "error"),
        ("SolverError", "error"),
        ("RunError", "error"),
        ("Simulation", "simulation"),
        ("SolverOptions", "simulation"),
        ("StepReport", "simulation"),
        ("IDENTIFIED_RANK_TOLERANCE", "simulation"),
    ];

    fn layer(module: &str) -> Option<u8> {
        LAYERS.iter().find(|(m, _)| *m == module).map(|(_, l)| *l)
    }

    /// The modules a source text imports through `crate::`, its test
    /// module left out.
    fn imports(text: &str) -> Vec<String> {
        let code = text.split("#[cfg(test)]").next().unwrap_or("");
        let mut out = Vec::new();
        for line in code.lines().filter(|l| !l.trim_start().starts_with("//")) {
            for (k, _) in line.match_indices("crate::") {
                let rest = &line[k + "crate::".len()..];
                if let Some(list) = rest.strip_prefix('{') {
                    let list = list.split('}').next().unwrap_or("");
                    for name in list.split(',').map(str::trim) {
                        let head = name.split("::").next().unwrap_or("");
                        match ROOT.iter().find(|(n, _)| *n == head) {
                            Some((_, m)) => out.push(m.to_string()),
                            None => out.push(head.to_string()),
                        }
                    }
                } else {
                    let head: String = rest
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    match ROOT.iter().find(|(n, _)| *n == head) {
                        Some((_, m)) => out.push(m.to_string()),
                        None => out.push(head),
                    }
                }
            }
        }
        out
    }

    fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                sources(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }

    #[test]
    fn every_import_points_down_or_sideways() {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = Vec::new();
        sources(&src, &mut files);
        let mut upward: BTreeMap<String, Vec<String>> = BTreeMap::new();
        let mut seen = 0;
        for file in &files {
            let rel = file.strip_prefix(&src).unwrap();
            let first = rel
                .components()
                .next()
                .unwrap()
                .as_os_str()
                .to_string_lossy();
            let module = first.trim_end_matches(".rs").to_string();
            let Some(own) = layer(&module) else {
                // the crate root and the binary
                assert!(
                    module == "lib" || module == "main",
                    "{}: module `{module}` has no layer: add it to LAYERS and ARCHITECTURE.md",
                    rel.display()
                );
                continue;
            };
            let text = std::fs::read_to_string(file).unwrap();
            for target in imports(&text) {
                seen += 1;
                if let Some(l) = layer(&target)
                    && l > own
                {
                    upward
                        .entry(rel.display().to_string())
                        .or_default()
                        .push(format!("{target} (layer {l} > {own})"));
                }
            }
        }
        assert!(seen > 100, "only {seen} imports read: the scan is broken");
        assert!(upward.is_empty(), "imports pointing up: {upward:#?}");
    }

    #[test]
    fn the_scan_sees_every_import_form() {
        let text = "use crate::scene::Mode;\nuse crate::{Scene, linalg};\n// crate::gui\nfn f() { crate::output::count(1, \"x\"); }\n#[cfg(test)]\nmod tests { use crate::cli; }";
        assert_eq!(imports(text), ["scene", "scene", "linalg", "output"]);
    }
}
