//! # tirecontact
//!
//! Dynamic tyre/road contact by fast modal convolution (see `SPEC.md`, from
//! Meftah & Duhamel, CFM 2011).
//!
//! ## Conventions (SPEC §1)
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
//! | module | what | SPEC |
//! |---|---|---|
//! | [`modal`] | modes, poles for every damping ratio, `g(t)`, `g'(t)`, `G(ω)` | §2 |
//! | [`convolution`] | bounded recursive convolution, exact step weights; α/β baseline and direct control | §3 |
//! | [`road`] | road profiles and the preload/road ramp | §4 |
//! | [`contact`] | scaled dense solves for the Gauss-point and impulse systems | §4 |
//! | [`simulation`] | the time stepper: active set, complementarity, events inside the step | §4 |
//! | [`ring`] | ring tyre on an elastic foundation: orders, modes, radial Green functions | §5 |
//! | [`linalg`] | checked dense decompositions (faer): rank terms, least squares, eigenvalues | §3, §6 |
//! | [`lsce`] | LSCE identification, stabilisation diagram, fit report | §6 |
//! | [`identify`] | ring -> sampled responses -> LSCE, cached per scene | §5-6 |
//! | [`scene`] | RON scenes and their validation | — |
//! | [`output`] | CSV writer, headless PNG figures | — |
//! | [`spectrum`] | amplitude/PSD spectra, third-octave bands, run spectra | — |
//! | [`sweep`] | scene parameters by path, multi-threaded sweeps | — |
//! | [`fidelity`] | relative L2 error of a modal model against a reference `G(ω)` | §5-6 |
//! | [`compare`] | a pinned reference run and the difference to it | — |
//! | `gui` | the visualiser (feature `gui`) | — |

pub mod bench;
pub mod compare;
pub mod contact;
pub mod convolution;
pub mod error;
pub mod fidelity;
#[cfg(feature = "gui")]
pub mod gui;
pub mod identify;
pub mod linalg;
pub mod lsce;
pub mod modal;
pub mod output;
pub mod phase;
pub mod ring;
pub mod road;
pub mod scene;
pub mod simulation;
pub mod spectrum;
pub mod sweep;

pub use error::{SceneError, SolverError};
pub use scene::Scene;
pub use simulation::{IDENTIFIED_RANK_TOLERANCE, Simulation, SolverOptions, StepReport};

/// The preset opened when no file is given (embedded in the binary).
pub const DEFAULT_PRESET: &str = include_str!("../presets/paper.ron");
/// File name of the embedded default preset, for messages.
pub const DEFAULT_PRESET_NAME: &str = "presets/paper.ron";
