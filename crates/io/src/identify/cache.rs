//! The identified modes kept by their caller ([`ModeCache`], method §6.4):
//! keyed on the tyre, its identification options and the points.

use super::{
    IdentifyError, PreparedModel, data_path, fe_model, identify_measured, identify_ring, points_xy,
    positions,
};
use crate::scene::{Scene, SceneError, Tyre};
use std::sync::{Arc, Mutex};
use tirecontact_core::base::modal::Mode;
use tirecontact_core::model::lsce::{IdentifyOptions, LsceError};
use tirecontact_core::model::ring::RingParams;

type CacheEntry = (String, Arc<Vec<Mode>>);

/// Identified ring modes kept by whoever runs several scenes of one tyre
/// (the visualiser, a sweep), keyed on the exact ring, identification options
/// and point positions; the 8 most recent are kept. A value the caller owns
/// and passes where modes are needed: nothing is cached behind its back.
/// Shared between threads by reference (the identification itself runs
/// outside the lock).
#[derive(Debug, Default)]
pub struct ModeCache {
    entries: Mutex<Vec<CacheEntry>>,
}

/// How many identifications a [`ModeCache`] keeps.
const CACHE_LEN: usize = 8;

/// The cache key of a ring, its identification options and the points.
pub(super) fn cache_key(ring: &RingParams, x_m: &[f64], opts: &IdentifyOptions) -> String {
    format!("{ring:?}|{opts:?}|{x_m:?}")
}

/// The cache key of a scene's identified tyre (`None`: a modal tyre). A
/// measured tyre's is its data file's path, options, nodes and point
/// count: the file is read once per key ([`ModeCache::forget`] drops it).
fn tyre_key(scene: &Scene) -> Option<String> {
    match &scene.tyre {
        Tyre::Modal { .. } | Tyre::Plate { .. } => None,
        Tyre::FeModes { .. } => Some(format!(
            "fe|{:?}|{:?}",
            scene.tyre.fe_spec(scene.base_dir.as_deref()),
            points_xy(scene)
        )),
        Tyre::Ring {
            ring,
            identification,
        } => Some(cache_key(ring, &positions(scene), identification)),
        Tyre::Measured {
            file,
            identification,
            nodes,
        } => Some(format!(
            "measured|{}|{identification:?}|{nodes:?}|{}",
            data_path(scene, file).display(),
            scene.num_points()
        )),
    }
}

impl ModeCache {
    pub fn new() -> Self {
        Self::default()
    }

    pub(super) fn lookup(&self, key: &str) -> Option<Arc<Vec<Mode>>> {
        let entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        entries
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, m)| Arc::clone(m))
    }

    pub(super) fn store(&self, key: String, modes: Arc<Vec<Mode>>) {
        let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        if entries.iter().any(|(k, _)| *k == key) {
            return;
        }
        if entries.len() >= CACHE_LEN {
            entries.remove(0);
        }
        entries.push((key, modes));
    }

    /// The identified modes of a ring at the points `x_m`: from the cache
    /// when this ring, these options and positions were identified before,
    /// else identified now ([`identify_ring`]) and kept.
    pub fn ring_modes(
        &self,
        ring: &RingParams,
        x_m: &[f64],
        opts: &IdentifyOptions,
    ) -> Result<Arc<Vec<Mode>>, LsceError> {
        let key = cache_key(ring, x_m, opts);
        if let Some(modes) = self.lookup(&key) {
            return Ok(modes);
        }
        let modes = Arc::new(identify_ring(ring, x_m, opts)?.identification.modes);
        self.store(key, Arc::clone(&modes));
        Ok(modes)
    }

    /// The modes of a scene's tyre: those written in the preset
    /// (`Tyre::Modal`), the ring identified at the points' positions
    /// (`Tyre::Ring`, method §5-6) through [`ModeCache::ring_modes`], or
    /// the measured responses identified (`Tyre::Measured`).
    pub fn modes(&self, scene: &Scene) -> Result<Arc<Vec<Mode>>, SceneError> {
        let fail = |e: IdentifyError| SceneError::Identification {
            scene: scene.name.clone(),
            message: e.to_string(),
        };
        match &scene.tyre {
            Tyre::Modal { modes } => Ok(Arc::new(modes.clone())),
            Tyre::Plate { plate } => Ok(Arc::new(plate.modes(&points_xy(scene)))),
            Tyre::FeModes { .. } => {
                let key = tyre_key(scene).unwrap_or_default();
                if let Some(m) = self.lookup(&key) {
                    return Ok(m);
                }
                let modes = Arc::new(fe_model(scene)?.modes);
                self.store(key, Arc::clone(&modes));
                Ok(modes)
            }
            Tyre::Ring {
                ring,
                identification,
            } => self
                .ring_modes(ring, &positions(scene), identification)
                .map_err(|e| fail(e.into())),
            Tyre::Measured {
                file,
                identification,
                nodes,
            } => {
                let key = tyre_key(scene).unwrap_or_default();
                if let Some(m) = self.lookup(&key) {
                    return Ok(m);
                }
                let id = identify_measured(
                    &data_path(scene, file),
                    (!nodes.is_empty()).then_some(nodes.as_slice()),
                    scene.num_points(),
                    identification,
                )
                .map_err(fail)?;
                let modes = Arc::new(id.identification.modes);
                self.store(key, Arc::clone(&modes));
                Ok(modes)
            }
        }
    }

    /// Whether [`ModeCache::modes`] answers at once: modes written in the
    /// preset, or a tyre already identified with these points and options
    /// (else it runs the identification, a tenth of a second or more).
    pub fn has_modes(&self, scene: &Scene) -> bool {
        matches!(scene.tyre, Tyre::Modal { .. } | Tyre::Plate { .. })
            || self.identified(scene).is_some()
    }

    /// The modes identified from `scene`'s ring or measured tyre, if this
    /// cache holds them (never identifies); `None` for a modal tyre.
    pub fn identified(&self, scene: &Scene) -> Option<Arc<Vec<Mode>>> {
        self.lookup(&tyre_key(scene)?)
    }

    /// Drops `scene`'s identified tyre, so that the next use identifies it
    /// again (a measured tyre's file opened anew may have changed).
    pub fn forget(&self, scene: &Scene) {
        if let Some(key) = tyre_key(scene) {
            let mut entries = self.entries.lock().unwrap_or_else(|e| e.into_inner());
            entries.retain(|(k, _)| *k != key);
        }
    }

    /// Keeps the modes of a model prepared elsewhere (a background job
    /// with its own cache), so that the scene is not identified again.
    pub fn remember(&self, model: &PreparedModel) {
        if let Some(key) = tyre_key(model.scene()) {
            self.store(key, Arc::clone(&model.problem().modes));
        }
    }
}
