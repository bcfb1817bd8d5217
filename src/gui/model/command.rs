//! Everything a user can ask for. Panels and the keyboard push commands;
//! `App::apply` is the one place they change the app's state.

use crate::Scene;
use crate::gui::model::prepared::Prepared;
use crate::gui::model::sweep_request::{SweepEnd, SweepRequest};
use crate::gui::model::time_control::Speed;
use std::path::PathBuf;

/// A main view of the central area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum View {
    #[default]
    TimePlots,
    Scene,
    Green,
    Spectra,
    Sweep,
    Compare,
    Fidelity,
    /// The identification workbench (stabilisation diagram, picked poles).
    Workbench,
    /// The contact patch: force over the points' grid, total force, area.
    Patch,
}

impl View {
    pub const ALL: [View; 9] = [
        View::TimePlots,
        View::Scene,
        View::Green,
        View::Spectra,
        View::Sweep,
        View::Compare,
        View::Fidelity,
        View::Workbench,
        View::Patch,
    ];
    pub fn label(self) -> &'static str {
        match self {
            View::TimePlots => "Time plots",
            View::Scene => "Scene view",
            View::Green => "Green functions",
            View::Spectra => "Spectra",
            View::Sweep => "Sweep",
            View::Compare => "A/B compare",
            View::Fidelity => "Fidelity",
            View::Workbench => "Identification",
            View::Patch => "Contact patch",
        }
    }
}

/// An action that would drop unsaved edits, held until the user confirms.
#[derive(Debug, Clone, PartialEq)]
pub enum Discarding {
    New,
    OpenPath(PathBuf),
    Preset(usize),
    Quit,
    /// A guided-tour preset (index into `presets::GUIDED`).
    Guided(usize),
    /// A preset's text read by the browser's picker, with its file name.
    Text {
        name: String,
        text: String,
    },
}

/// A user request.
#[must_use = "a Command does nothing until App::apply runs it"]
#[derive(Debug, Clone, PartialEq)]
pub enum Command {
    Play,
    Pause,
    TogglePlay,
    /// Pause and take `n` solver steps.
    Step(u64),
    /// Back to t = 0 with the current scene.
    Reset,
    SetSpeed(Speed),
    /// Replace the scene by an edited, already validated one. Road and speed
    /// changes apply live; anything else restarts the run.
    EditScene(Box<Scene>),
    /// Take the last scene edit back (Ctrl+Z), or make the last one taken
    /// back again (Ctrl+Shift+Z, Ctrl+Y): each is itself a scene edit.
    Undo,
    Redo,
    /// New scene (the embedded default preset), after confirmation if dirty.
    New,
    /// Open a preset through the file dialog, after confirmation if dirty.
    OpenDialog,
    /// Open a preset file, after confirmation if dirty.
    OpenPath(PathBuf),
    /// Open a preset's text (read by the browser's picker, with its file
    /// name), after confirmation if dirty.
    OpenText {
        name: String,
        text: String,
    },
    /// Open a shipped preset (index into `presets::SHIPPED`).
    OpenPreset(usize),
    /// Save to the current file (Save As if there is none).
    Save,
    SaveAsDialog,
    SavePath(PathBuf),
    /// Show the PNG export settings.
    ExportPngDialog,
    ExportPng {
        path: PathBuf,
        width: u32,
        height: u32,
    },
    ExportCsvDialog,
    ExportCsv(PathBuf),
    /// Ask where to write the contact patch's heat map as PNG.
    ExportHeatMapDialog,
    /// Write the contact patch's heat map now as PNG.
    ExportHeatMap(PathBuf),
    /// Copy a link that carries the scene (and, in a browser, put it in
    /// the page's address).
    Share,
    /// The user confirmed dropping unsaved edits.
    ConfirmDiscard,
    CancelDiscard,
    /// Close the window (after confirmation if dirty).
    Quit,
    DismissMessage,
    ShowView(View),
    /// In a narrow window (a phone), show the editing panel in place of
    /// the views (`true`) or the views again (`false`).
    ShowEditPanel(bool),
    /// Show these points (and only these) in the time plots, and the plots.
    ShowPoints(Vec<usize>),
    /// Classroom mode on/off: large fonts, presenter layout, slow motion.
    SetClassroom(bool),
    /// Open a guided-tour preset (index into `presets::GUIDED`).
    OpenGuided(usize),
    /// Show the mode contribution bars in the normal layout.
    ShowModeBars(bool),
    /// Mute or un-mute mode `k` (residue × 0; restarts the run).
    ToggleMute(usize),
    /// Mute every mode but `k`, or un-mute all if `k` is already solo.
    SoloMode(usize),
    UnmuteAll,
    /// Switch to compliant contact and apply the mute or solo refused with
    /// rigid contact.
    MuteWithCompliantContact,
    /// Keep the modes playing: forget the refused mute or solo.
    DismissMuteRefusal,
    /// Show the animation export settings.
    ExportFramesDialog,
    ExportFrames {
        dir: PathBuf,
        settings: crate::output::animation::FrameSettings,
        /// Remove the frames of an earlier export from `dir` first.
        clear_old: bool,
    },
    CancelFrames,
    /// A researcher-tool request (spectra, sweep, A/B pin, exports).
    Research(ResearchCommand),
    /// A field refused a typed value: `text` (field, value, what is
    /// expected) goes to the message banner until a good edit.
    FieldRefused {
        field: String,
        text: String,
    },
    /// A field refused earlier shows the scene's value again: its refusal
    /// leaves the message banner.
    FieldRestored {
        field: String,
    },
    /// "Save first" in the unsaved-changes question: save (asking for a
    /// file if the scene has none), then do the held action.
    SaveFirst,
    /// After a save from the file prompt: do the held action if the scene
    /// is now saved (a failed save keeps it, and the user's edits).
    ContinueAfterSave(Discarding),
    /// Overwrite the preset shipped with the app that a save was about to
    /// replace (asked first), or keep it.
    ConfirmOverwrite,
    CancelOverwrite,
    /// Close the window showing the last Share's link.
    CloseLink,
    /// The frame's share of the run: take the solver steps the time
    /// control asks for in `frame_s` of wall time (the frame loop pushes it).
    Advance {
        frame_s: f64,
    },
    /// The CSV export job ended: its message, or why it failed.
    CsvExportEnded(Result<String, String>),
    /// The frames export job ended: the frames written, or why it stopped.
    FramesExportEnded(Result<u64, String>),
    /// A preparation (preset or road file read, ring identified) ended:
    /// what waited for it is applied (or refused with the reason).
    PreparationEnded(Result<Prepared, String>),
    /// Stop the preparation an edit or a new document waits for: the
    /// current scene is kept.
    CancelPreparation,
    /// Stop the CSV export under way (no file is written).
    CancelCsvExport,
}

/// A request of the researcher tools (wrapped in `Command::Research`).
#[derive(Debug, Clone, PartialEq)]
pub enum ResearchCommand {
    /// Recompute the spectra of the run now.
    RecomputeSpectra,
    /// Start a sweep of the current scene on a background thread.
    StartSweep(SweepRequest),
    /// Stop the running sweep (its partial results are dropped).
    CancelSweep,
    ExportSweepCsvDialog,
    /// Write the last sweep as CSV (same table as `tirecontact sweep -o`).
    ExportSweepCsv(PathBuf),
    ExportSweepPngDialog,
    /// Draw the last sweep to a PNG (same figure as `tirecontact sweep --plot`).
    ExportSweepPng(PathBuf),
    /// Pin the current run as the reference of the A/B comparison.
    PinReference,
    Unpin,
    ExportPinnedCsvDialog,
    /// Write the pinned run as CSV (`t_s, u{i}_m.., q{i}_N..`).
    ExportPinnedCsv(PathBuf),
    /// The sweep's background job ended (the frame loop pushes it).
    SweepEnded(SweepEnd),
    /// Pick the pole at (order index, pole index) of the workbench's
    /// diagram, or drop it.
    WorkbenchToggle((usize, usize)),
    /// The workbench's automatic choice of poles.
    WorkbenchAutomatic,
    /// The workbench's modes become the scene's modal tyre (the run
    /// restarts).
    WorkbenchUse,
    WorkbenchSaveDialog,
    /// Write the scene with the workbench's modes as its modal tyre.
    WorkbenchSave(PathBuf),
    /// Once a frame: follow the scene's ring reference and bring what the
    /// shown research view needs up to date (spectra, differences to the
    /// pinned run, fidelity figures), starting or picking up their jobs.
    Refresh,
}
