//! The tyre of a scene: the sources of its Green functions as the preset
//! writes them.

use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use tirecontact_core::base::modal::Mode;
use tirecontact_core::model::lsce::IdentifyOptions;
use tirecontact_core::model::ring::RingParams;

/// Source of the tyre's Green functions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Tyre {
    /// A modal model given mode by mode (method §2).
    Modal { modes: Vec<Mode> },
    /// The ring tyre (method §5), its radial Green functions at the contact
    /// points identified by LSCE (method §6) into a modal model. Both fields
    /// default (the reference passenger tyre, the default options).
    Ring {
        #[serde(default)]
        ring: RingParams,
        #[serde(default)]
        identification: IdentifyOptions,
    },
    /// Responses measured on a real tyre (hammer or shaker tests) or
    /// computed elsewhere (finite elements, waveguides), identified by LSCE
    /// (method §6) as the ring's are. The file (relative to the preset's
    /// folder) is UFF 58 (`.uff`, `.unv`), CSV impulse responses
    /// (`t_s, g{i}_{j}`, m/(N·s)) or CSV receptances (`freq_hz,
    /// h{i}_{j}_re, h{i}_{j}_im`, m/N): see [`crate::readers::measured`]. The data's
    /// sampling is used (`identification.sample_rate_hz` is not); its
    /// first `identification.duration_s` seconds are identified.
    Measured {
        file: PathBuf,
        #[serde(default)]
        identification: IdentifyOptions,
        /// The file's node numbers of the scene's points, in order (UFF);
        /// empty (the default): the file's points in order.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        nodes: Vec<i64>,
    },
    /// A tyre with a width (method §5.3): the belt as a tensioned
    /// orthotropic plate on an elastic foundation, its modes in closed form
    /// at the points `(x_m, y_m)` (`y_m` within `±width_m/2`). Defaults: a
    /// passenger car tyre's belt.
    Plate {
        #[serde(default)]
        plate: tirecontact_core::model::plate::PlateParams,
    },
    /// A tyre computed elsewhere (method §5.4): the normal modes of a
    /// finite-element model exported as UFF 55 or 2414 (node coordinates in
    /// 15 or 2411, units in 164), read into a modal model at the points
    /// without identification. See [`crate::readers::fe_modes`].
    FeModes {
        /// The UFF file, relative to the preset's folder.
        file: PathBuf,
        /// The file's node of each point, in order, or `Nearest`: the node
        /// nearest each point (within `nearest_within_m`).
        nodes: crate::readers::fe_modes::FeNodes,
        /// The FE axis normal to the road, pointing away from it; default Z.
        #[serde(default = "default_fe_direction")]
        direction: crate::readers::fe_modes::FeAxis,
        /// The FE axes of the points' `x_m` (along) and `y_m` (across);
        /// default `(along: X, across: Y)`.
        #[serde(default)]
        axes: crate::readers::fe_modes::FeAxes,
        /// `Ratio(ξ)`, `Modal([ξ, ...])`, `Rayleigh(alpha_per_s, beta_s)` or
        /// `FromFile`.
        damping: crate::readers::fe_modes::FeDamping,
        /// Modal masses (kg) replacing the records': one number, or one per
        /// mode kept; empty (the default): the records'.
        #[serde(
            default,
            alias = "modal_mass",
            deserialize_with = "crate::readers::fe_modes::de_masses",
            skip_serializing_if = "Vec::is_empty"
        )]
        modal_mass_kg: Vec<f64>,
        /// Modes kept, `lo <= f <= hi` (Hz); default every mode.
        #[serde(
            default = "all_fe_modes",
            skip_serializing_if = "crate::readers::fe_modes::is_all_modes"
        )]
        band_hz: (f64, f64),
        /// `Nearest`: largest distance (m) from a point to its node;
        /// default 0.001.
        #[serde(
            default = "default_nearest_within",
            skip_serializing_if = "crate::readers::fe_modes::is_default_within"
        )]
        nearest_within_m: f64,
        /// How the file scales its shapes: `Consistent` (default, 1/√ of
        /// the file's mass unit) or `LengthPerSqrtKg`.
        #[serde(
            default,
            skip_serializing_if = "crate::readers::fe_modes::FeShapeUnits::is_consistent"
        )]
        shape_units: crate::readers::fe_modes::FeShapeUnits,
    },
}

fn default_fe_direction() -> crate::readers::fe_modes::FeAxis {
    crate::readers::fe_modes::FeAxis::Z
}

fn all_fe_modes() -> (f64, f64) {
    crate::readers::fe_modes::ALL_MODES_HZ
}

fn default_nearest_within() -> f64 {
    crate::readers::fe_modes::DEFAULT_NEAREST_WITHIN_M
}

impl Tyre {
    /// An FE tyre's fields, its file resolved against `base_dir`.
    pub fn fe_spec(
        &self,
        base_dir: Option<&Path>,
    ) -> Option<crate::readers::fe_modes::FeModesSpec> {
        let Tyre::FeModes {
            file,
            nodes,
            direction,
            axes,
            damping,
            modal_mass_kg,
            band_hz,
            nearest_within_m,
            shape_units,
        } = self
        else {
            return None;
        };
        Some(crate::readers::fe_modes::FeModesSpec {
            file: crate::readers::fe_modes::resolve(base_dir, file),
            nodes: nodes.clone(),
            direction: *direction,
            axes: *axes,
            damping: damping.clone(),
            modal_mass_kg: modal_mass_kg.clone(),
            band_hz: *band_hz,
            nearest_within_m: *nearest_within_m,
            shape_units: *shape_units,
        })
    }
}
