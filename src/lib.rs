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
//! Each folder of `src/` is a layer; a module imports from its own layer or
//! those below (`ARCHITECTURE.md`, checked by the test `layers` below).
//!
//! | layer | modules | what | method |
//! |---|---|---|---|
//! | 0 [`base`] | [`error`](base::error), [`linalg`](base::linalg), [`fsio`](base::fsio), [`modal`](base::modal), [`threads`](base::threads) | errors; checked dense decompositions (faer); atomic file writes; modes, poles for every damping ratio, `g(t)`, `G(ω)`; the kernels' worker threads | §2, §3, §6 |
//! | 1 [`model`] | [`ring`](model::ring), [`lsce`](model::lsce), [`measured`](model::measured), [`road`](model::road), [`convolution`](model::convolution) | ring tyre on an elastic foundation; LSCE identification; measured responses; road profiles and the ramp; the bounded recursive convolution with exact step weights | §3, §5, §6 |
//! | 2 [`scene`] | | RON scenes, their validation, edits by path | — |
//! | 3 [`identify`] | | ring or measured tyre -> LSCE; `ModeCache`, `PreparedModel` (what a simulation is built from) | §5-6 |
//! | 4 [`solver`] | [`simulation`](solver::simulation), [`drive`](solver::drive), [`phase`](solver::phase) | the time stepper: tables, state and scratch; the stages of a step (predict, solve, locate, commit); the run driver and its `Probe`; contact phases | §4 |
//! | 5 [`output`] | | the one run sampler, CSV writer, headless PNG figures, animation frames | — |
//! | 6 [`analysis`] | [`spectrum`](analysis::spectrum), [`metrics`](analysis::metrics), [`compare`](analysis::compare), [`fidelity`](analysis::fidelity), [`bench`](analysis::bench) | spectra and bands; run metrics; A/B compare; the error of a modal model against a reference `G(ω)`; work-precision and scaling studies | §5-6 |
//! | 7 [`studies`] | [`sweep`](studies::sweep), [`study`](studies::study) | sweeps over scene paths, multi-factor studies | — |
//! | 8 `gui` | | the visualiser (feature `gui`); the command line lives in the binary | — |

pub mod analysis;
pub mod base;
#[cfg(feature = "gui")]
pub mod gui;
pub mod identify;
pub mod model;
pub mod output;
pub mod scene;
pub mod solver;
pub mod studies;

pub use base::error::{RunError, SceneError, SolverError};
pub use identify::{ModeCache, PreparedModel};
pub use scene::Scene;
pub use solver::simulation::{IDENTIFIED_RANK_TOLERANCE, Simulation, SolverOptions, StepReport};

/// The preset opened when no file is given (embedded in the binary).
pub const DEFAULT_PRESET: &str =
    include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron"));
/// File name of the embedded default preset, for messages.
pub const DEFAULT_PRESET_NAME: &str = "presets/paper.ron";

/// The layers of `ARCHITECTURE.md`: every import of a module points to its
/// own layer or one below (tests inside a module may import anything).
#[cfg(test)]
mod layers {
    use std::collections::BTreeMap;
    use std::path::Path;

    /// Each top-level folder and its layer (0 the ground floor): a module's
    /// layer is the folder it sits in.
    const LAYERS: &[(&str, u8)] = &[
        ("base", 0),
        ("model", 1),
        ("scene", 2),
        ("identify", 3),
        ("solver", 4),
        ("output", 5),
        ("analysis", 6),
        ("studies", 7),
        ("cli", 8),
        ("gui", 8),
    ];

    /// The crate root's re-exports, by the module that defines them.
    const ROOT: &[(&str, &str)] = &[
        ("Scene", "scene"),
        ("ModeCache", "identify"),
        ("PreparedModel", "identify"),
        ("SceneError", "base"),
        ("SolverError", "base"),
        ("RunError", "base"),
        ("Simulation", "solver"),
        ("SolverOptions", "solver"),
        ("StepReport", "solver"),
        ("IDENTIFIED_RANK_TOLERANCE", "solver"),
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

    /// Every `.rs` file below `dir` (also the GUI's own layer test).
    pub(crate) fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
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
                    "{}: module `{module}` sits in no layer folder: move it into one (LAYERS, ARCHITECTURE.md)",
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
        let text = "use crate::scene::Mode;\nuse crate::{Scene, base::linalg};\n// crate::gui\nfn f() { crate::output::count(1, \"x\"); }\n#[cfg(test)]\nmod tests { use crate::cli; }";
        assert_eq!(imports(text), ["scene", "scene", "base", "output"]);
    }
}
