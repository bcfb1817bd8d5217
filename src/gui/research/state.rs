//! What the app keeps for the researcher tools.

use super::fidelity::{FidelityCache, FidelityRef};
use super::spectra::{HistoryCache, HistorySpectra};
use super::sweep_job::SweepState;
use crate::analysis::compare::{PinnedRun, RunDifference};

/// Presentation options of the spectra view.
#[derive(Debug, Clone, PartialEq)]
pub struct SpectraOptions {
    pub log_x: bool,
    /// Points drawn.
    pub shown: Vec<bool>,
    /// Draw the spectrum of the summed force of all points.
    pub total: bool,
    /// Highest frequency drawn (Hz).
    pub max_hz: f64,
    /// Recompute while the run plays (else only on the button or a pause).
    pub auto: bool,
}

impl Default for SpectraOptions {
    fn default() -> Self {
        SpectraOptions {
            log_x: true,
            shown: Vec::new(),
            total: true,
            max_hz: 2000.0,
            auto: true,
        }
    }
}

/// Form of the sweep panel (view-local until Run is pressed).
#[derive(Debug, Clone, PartialEq)]
pub struct SweepForm {
    pub param: String,
    pub from: f64,
    pub to: f64,
    pub steps: usize,
}

impl Default for SweepForm {
    fn default() -> Self {
        SweepForm {
            param: "speed_mps".into(),
            from: 8.0,
            to: 36.0,
            steps: 8,
        }
    }
}

/// Presentation options of the A/B view.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    pub shown: Vec<bool>,
    pub difference: bool,
    /// Fit the force plot to the force without impacts, as the time plots
    /// do (impacts clipped and marked ▼).
    pub clip_impacts: bool,
}

impl Default for CompareOptions {
    fn default() -> Self {
        CompareOptions {
            shown: Vec::new(),
            difference: true,
            clip_impacts: true,
        }
    }
}

/// Presentation options of the fidelity view.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FidelityOptions {
    /// Receiving point i and loaded point j of the curves.
    pub i: usize,
    pub j: usize,
    pub log_x: bool,
}

/// The researcher tools' state held by the app.
#[derive(Debug, Default)]
pub struct ResearchState {
    pub(crate) spectra: HistoryCache<Result<HistorySpectra, String>>,
    pub(crate) spectra_now: bool,
    pub(crate) spectra_opts: SpectraOptions,
    pub(crate) sweep: SweepState,
    pub(crate) sweep_form: SweepForm,
    pub(crate) pinned: Option<PinnedRun>,
    pub(crate) difference: HistoryCache<RunDifference>,
    pub(crate) compare_opts: CompareOptions,
    pub(crate) fidelity_ref: Option<FidelityRef>,
    pub(crate) fidelity: FidelityCache,
    pub(crate) fidelity_opts: FidelityOptions,
    /// The pinned run with its force without impacts as `q` (sets the
    /// compare view's clipped force axes), and its difference.
    pub(crate) pinned_without_impacts: Option<PinnedRun>,
    pub(crate) difference_without_impacts: HistoryCache<RunDifference>,
    /// The spectra being computed on a background thread, if any.
    pub(crate) spectra_job: Option<super::spectra_job::SpectraJob>,
    /// Background spectra computations started so far.
    pub(crate) spectra_jobs: u64,
    /// The fidelity figures being computed on a background thread, if any.
    pub(crate) fidelity_job: Option<super::fidelity_job::FidelityJob>,
    /// Background fidelity computations started so far.
    pub(crate) fidelity_jobs: u64,
    /// The identification workbench of the scene's tyre (its key), or why
    /// there is none.
    pub(crate) workbench: Option<(
        super::workbench_job::WorkbenchKey,
        Result<crate::identify::workbench::Workbench, String>,
    )>,
    pub(crate) workbench_job: Option<super::workbench_job::WorkbenchJob>,
    /// The scene's modal tyre and points as "Use these modes" made them:
    /// while the scene keeps them, the workbench they came from stays
    /// shown, its picks ready to refine.
    pub(crate) workbench_used: Option<super::workbench_job::WorkbenchKey>,
    /// The frequency-domain fit of a measured file of FRFs, or why there is
    /// none (with the workbench, same key).
    pub(crate) frf_fit: Option<Result<crate::identify::frequency::FrfIdentification, String>>,
}

impl ResearchState {
    /// The spectra last computed (or why there are none).
    pub fn spectra(&self) -> Option<&Result<HistorySpectra, String>> {
        self.spectra.get()
    }
    /// Times the spectra were computed.
    pub fn spectra_computations(&self) -> u64 {
        self.spectra.computations
    }
    /// Spectra computations started on a background thread so far.
    pub fn spectra_jobs(&self) -> u64 {
        self.spectra_jobs
    }
    /// Progress (0..=1) of the spectra being computed in the background.
    pub fn spectra_computing(&self) -> Option<f64> {
        self.spectra_job.as_ref().map(|j| j.progress())
    }
    pub fn sweep(&self) -> &SweepState {
        &self.sweep
    }
    pub fn pinned(&self) -> Option<&PinnedRun> {
        self.pinned.as_ref()
    }
    /// Current − pinned, as last computed for the A/B view.
    pub fn difference(&self) -> Option<&RunDifference> {
        self.difference.get()
    }
    pub fn fidelity_reference(&self) -> Option<&FidelityRef> {
        self.fidelity_ref.as_ref()
    }
    /// The fidelity figures last computed for the panel.
    pub fn fidelity(&self) -> Option<&Result<super::fidelity::FidelityFigures, String>> {
        self.fidelity.last()
    }
    /// Progress (0..=1) of the fidelity figures being computed in the
    /// background.
    pub fn fidelity_computing(&self) -> Option<f64> {
        self.fidelity_job.as_ref().map(|j| j.progress())
    }
    /// Fidelity computations started on a background thread so far.
    pub fn fidelity_jobs(&self) -> u64 {
        self.fidelity_jobs
    }
    /// The identification workbench shown, or why there is none.
    pub fn workbench(&self) -> Option<&Result<crate::identify::workbench::Workbench, String>> {
        self.workbench.as_ref().map(|w| &w.1)
    }
    /// Whether the scene's tyre is the modes picked on the workbench shown.
    pub fn workbench_in_use(&self) -> bool {
        self.workbench.is_some() && self.workbench_used.is_some()
    }
    /// The frequency-domain fit of the measured file's FRFs shown, or why
    /// there is none (`None`: not a file of FRFs).
    pub fn frf_fit(
        &self,
    ) -> Option<&Result<crate::identify::frequency::FrfIdentification, String>> {
        self.frf_fit.as_ref()
    }
    /// Whether the workbench's identification is running.
    pub fn workbench_computing(&self) -> bool {
        self.workbench_job.is_some()
    }
}
