//! The fidelity panel's logic (no egui here): the source Green functions of
//! a ring tyre kept as the reference, also after the scene was turned into
//! an editable modal model, and the relative L2 error (crate::analysis::fidelity) of
//! the modes in use against it, cached by the modes.

use crate::Scene;
use crate::analysis::fidelity::{Fidelity, band_frequencies, relative_l2_error, removal_costs};
use crate::base::modal::ModalModel;
use crate::model::ring::RingParams;
use crate::scene::{Mode, Tyre};

/// Frequencies (mid-points of equal slices of the band) of the error figure.
pub const FIDELITY_FREQS: usize = 500;

/// The reference of the fidelity panel: a ring tyre's Green functions (all
/// its orders) at the current points, over a band.
#[derive(Debug, Clone, PartialEq)]
pub struct FidelityRef {
    pub ring: RingParams,
    /// Band of the error figure (Hz): the ring's identification band.
    pub band_hz: (f64, f64),
    /// Name of the scene the ring came from.
    pub source: String,
}

impl FidelityRef {
    /// The reference of a ring-tyre scene; `None` for a modal one.
    pub fn of_scene(scene: &Scene) -> Option<Self> {
        match &scene.tyre {
            Tyre::Ring {
                ring,
                identification,
            } => Some(FidelityRef {
                ring: ring.clone(),
                band_hz: identification.band_hz,
                source: scene.name.clone(),
            }),
            // (a measured tyre's reference would be its data: not yet)
            Tyre::Modal { .. }
            | Tyre::Measured { .. }
            | Tyre::Plate { .. }
            | Tyre::FeModes { .. } => None,
        }
    }

    /// The ring's Green functions at the points `x_m`.
    pub fn model(&self, x_m: &[f64]) -> ModalModel {
        self.ring.modal_model(x_m)
    }

    /// The reference after the scene changed to `scene`: a ring scene
    /// brings its own; a modal scene keeps the held one (so a ring edited
    /// as a modal model is still compared with its source).
    pub fn follow(held: Option<Self>, scene: &Scene) -> Option<Self> {
        Self::of_scene(scene).or(held)
    }
}

/// The error figures of a set of modes against the reference.
#[derive(Debug, Clone, PartialEq)]
pub struct FidelityFigures {
    pub fidelity: Fidelity,
    /// Error of the model without mode `k`, per `k` (-).
    pub removal_costs: Vec<f64>,
    pub band_hz: (f64, f64),
    pub num_freqs: usize,
}

/// Relative L2 error of `modes` against `reference` at the points `x_m`
/// over the reference's band (`FIDELITY_FREQS` frequencies).
pub fn figures(
    reference: &FidelityRef,
    x_m: &[f64],
    modes: &[Mode],
) -> Result<FidelityFigures, String> {
    let freqs = band_frequencies(reference.band_hz.0, reference.band_hz.1, FIDELITY_FREQS)
        .map_err(|e| e.to_string())?;
    let src = reference.model(x_m);
    let model = ModalModel::from_modes(modes, x_m.len());
    let fidelity = relative_l2_error(&src, &model, &freqs).map_err(|e| e.to_string())?;
    let costs = removal_costs(&src, modes, &freqs).map_err(|e| e.to_string())?;
    Ok(FidelityFigures {
        fidelity,
        removal_costs: costs,
        band_hz: reference.band_hz,
        num_freqs: FIDELITY_FREQS,
    })
}

/// Cache of the figures, keyed by everything they depend on.
#[derive(Debug, Clone, Default)]
pub struct FidelityCache {
    key: Option<(FidelityRef, Vec<f64>, Vec<Mode>)>,
    value: Option<Result<FidelityFigures, String>>,
    pub computations: u64,
}

impl FidelityCache {
    /// The figures of `modes` at `x_m` against `reference`, recomputed only
    /// when one of them changed.
    pub fn get(
        &mut self,
        reference: &FidelityRef,
        x_m: &[f64],
        modes: &[Mode],
    ) -> &Result<FidelityFigures, String> {
        let same = self
            .key
            .as_ref()
            .is_some_and(|(r, x, m)| r == reference && x == x_m && m == modes);
        if !same || self.value.is_none() {
            self.key = Some((reference.clone(), x_m.to_vec(), modes.to_vec()));
            self.value = Some(figures(reference, x_m, modes));
            self.computations += 1;
        }
        self.value
            .get_or_insert_with(|| Err("no fidelity figures".into()))
    }

    /// The last figures computed, if any.
    pub fn last(&self) -> Option<&Result<FidelityFigures, String>> {
        self.value.as_ref()
    }

    /// The figures if they are those of `modes` at `x_m` against `reference`.
    pub fn current(
        &self,
        reference: &FidelityRef,
        x_m: &[f64],
        modes: &[Mode],
    ) -> Option<&Result<FidelityFigures, String>> {
        let same = self
            .key
            .as_ref()
            .is_some_and(|(r, x, m)| r == reference && x == x_m && m == modes);
        self.value.as_ref().filter(|_| same)
    }

    /// Keeps the figures computed elsewhere (a background job) for `key`.
    pub fn set(
        &mut self,
        key: (FidelityRef, Vec<f64>, Vec<Mode>),
        value: Result<FidelityFigures, String>,
    ) {
        self.key = Some(key);
        self.value = Some(value);
        self.computations += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::fidelity::without_mode;

    fn paper() -> Scene {
        Scene::parse(
            include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/presets/paper.ron")),
            "paper",
        )
        .unwrap()
    }

    #[test]
    fn the_ring_reference_survives_conversion_to_modes_and_not_a_new_scene() {
        let ring = paper();
        let r = FidelityRef::of_scene(&ring).unwrap();
        assert_eq!(r.band_hz, (0.0, 500.0));
        let mut modal = ring.clone();
        modal.tyre = Tyre::Modal {
            modes: vec![Mode {
                freq_hz: 100.0,
                damping_ratio: 0.05,
                residue: Vec::new(),
                shape: vec![0.1; 5],
            }],
        };
        assert_eq!(
            FidelityRef::follow(Some(r.clone()), &modal),
            Some(r.clone())
        );
        assert_eq!(FidelityRef::follow(None, &modal), None);
        assert_eq!(FidelityRef::follow(None, &ring), Some(r));
    }

    #[test]
    fn figures_are_cached_by_the_modes_and_grow_when_a_mode_goes() {
        // the reference's own modes against it: zero; one mode less: more
        let scene = paper();
        let r = FidelityRef::of_scene(&scene).unwrap();
        let x: Vec<f64> = scene.points.iter().map(|p| p.x_m).collect();
        let own = r.ring.modes(&x);
        let mut c = FidelityCache::default();
        let e0 = c.get(&r, &x, &own).as_ref().unwrap().fidelity.relative_l2;
        assert_eq!(e0, 0.0);
        c.get(&r, &x, &own);
        assert_eq!(c.computations, 1);
        // the lowest mode in the band carries the most
        let k = own
            .iter()
            .enumerate()
            .filter(|(_, m)| m.freq_hz > 0.0)
            .min_by(|a, b| a.1.freq_hz.total_cmp(&b.1.freq_hz))
            .unwrap()
            .0;
        let cut = without_mode(&own, k).unwrap();
        let f = c.get(&r, &x, &cut).as_ref().unwrap().clone();
        assert_eq!(c.computations, 2);
        assert!(f.fidelity.relative_l2 > 0.0);
        assert_eq!(f.removal_costs.len(), cut.len());
    }
}
