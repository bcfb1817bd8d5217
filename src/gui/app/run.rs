//! The run: play, pause, reset, the solver steps of a frame within the time
//! budget, and scene edits (road and speed live, anything else restarts).

use super::*;
use crate::gui::jobs::prepare::{PrepareJob, Then, needs_preparing, reads_road_file, waiting_note};
use crate::gui::model::prepared::Prepared;
use crate::gui::model::time_control::step_budget_s;
use crate::model::road::RoadProfile;
use crate::solver::drive::Watch;

/// Said after an error that paused the run.
pub const PAUSED_NOTE: &str = "The run is paused: press Play (Space) to go on.";

impl App {
    /// Drops an informational message (errors stay until dismissed).
    pub(super) fn clear_info(&mut self) {
        if self.message.as_ref().is_some_and(|m| !m.error) {
            self.message = None;
        }
    }

    pub(super) fn play(&mut self) {
        self.clear_info();
        if self.sim.finished() {
            self.reset_run();
        }
        self.time.play();
    }

    pub(super) fn toggle_play(&mut self) {
        if self.time.is_playing() {
            self.time.pause();
        } else {
            self.play();
        }
    }

    pub(super) fn reset_run(&mut self) {
        self.clear_info();
        self.sim.reset();
        self.time.reset();
        self.run_start = self.doc.scene.clone();
        self.live_edits.clear();
        self.history = History::new(self.sim.num_points(), DEFAULT_BUDGET);
        self.history.record_initial(&self.sim);
        self.phases = PhaseTracker::new(self.sim.num_points(), self.phases.hold_s);
    }

    /// A freshly opened scene plays slowly enough to be watched (classroom
    /// mode keeps its slow motion).
    pub(super) fn set_watchable_speed(&mut self) {
        let speed = if self.classroom.on {
            // leaving classroom mode gives the new scene's watchable speed
            if let Some((_, before)) = &mut self.classroom.before {
                *before = Speed::watchable(self.doc.scene.duration_s);
            }
            Speed::Factor(classroom::SLOW_MOTION)
        } else {
            Speed::watchable(self.doc.scene.duration_s)
        };
        self.time.set_speed(speed);
    }

    /// Shows a field's refusal in the banner, until a good edit; a playing
    /// run pauses, so that the message is read before the run goes on.
    pub(super) fn field_refused(&mut self, text: String) {
        let noted = format!("{text} {PAUSED_NOTE}");
        // while a refusal that paused the run is still shown (not yet
        // mended, the run not played again), the next refusal keeps saying
        // why the run is paused: the same one again in the frame that paused
        // (egui may lay a frame out twice), or another field's
        let paused_by_refusal = !self.time.is_playing()
            && self
                .field_refusal
                .as_deref()
                .is_some_and(|t| t.ends_with(PAUSED_NOTE));
        let text = if paused_by_refusal {
            noted
        } else {
            self.pause_for_error(text)
        };
        self.error(text.clone());
        self.field_refusal = Some(text);
    }

    /// Pauses a playing run on a refused input, and says so after `text`.
    pub(super) fn pause_for_error(&mut self, text: String) -> String {
        if self.time.is_playing() {
            self.time.pause();
            format!("{text} {PAUSED_NOTE}")
        } else {
            text
        }
    }

    /// Field `name` shows the scene's value again: its refusal, if it is the
    /// one shown, leaves the banner.
    pub(super) fn field_restored(&mut self, name: &str) {
        if let Some(t) = &self.field_refusal
            && t.starts_with(&format!(
                "{}:",
                crate::gui::widgets::fields::banner_name(name)
            ))
        {
            if self.message.as_ref().is_some_and(|m| m.text == *t) {
                self.message = None;
            }
            self.field_refusal = None;
        }
    }

    /// Prepares what `then` waits for on a background thread (a later
    /// edit or document replaces an earlier one still waiting).
    pub(super) fn prepare(&mut self, then: Then) {
        let identifies = match &then {
            Then::Edit(s) | Then::Replace { scene: s, .. } => !self.handles.mode_cache.has_modes(s),
            Then::Road(_) | Then::Open(_) => false,
        };
        let note = waiting_note(&then, identifies);
        match PrepareJob::spawn(then, Arc::clone(&self.handles.mode_cache)) {
            Ok(job) => {
                self.info(note.clone());
                self.handles.prepare_job = Some((job, note));
            }
            Err(e) => self.error(format!("Cannot prepare the scene: {e}")),
        }
    }

    /// Applies what waited for a finished preparation.
    pub(super) fn poll_preparation(&self) -> Option<Command> {
        let r = self.handles.prepare_job.as_ref()?.0.poll()?;
        Some(Command::PreparationEnded(r))
    }

    /// Applies (or refuses) what waited for the preparation that ended.
    pub(super) fn preparation_ended(&mut self, result: Result<Prepared, String>) {
        let Some((job, note)) = self.handles.prepare_job.take() else {
            return;
        };
        // the waiting note goes; what is applied says what it says
        if self.message.as_ref().is_some_and(|m| m.text == note) {
            self.message = None;
        }
        // built on the job's thread (a large patch takes seconds)
        let ready = job.take_built();
        let built = |m: &crate::identify::PreparedModel| {
            ready.unwrap_or_else(|| {
                m.simulation(SolverOptions::default())
                    .map(|sim| (sim, m.modes().to_vec()))
            })
        };
        match (result, job.then) {
            (Ok(Prepared::Model(m)), Then::Edit(scene)) => {
                let b = built(&m);
                self.restart_with(scene, b);
            }
            (Ok(Prepared::Road(profile)), Then::Road(scene)) => {
                self.live_edit(scene, Some(profile))
            }
            (Ok(Prepared::Model(m)), Then::Replace { scene, path, what }) => {
                let b = built(&m);
                self.replace_with(scene, path, &what, b);
            }
            (Ok(Prepared::Model(m)), Then::Open(path)) => {
                let b = built(&m);
                let scene = m.scene().clone();
                self.replace_with(
                    scene,
                    Some(path.clone()),
                    &format!("opened {}", path.display()),
                    b,
                );
            }
            (Ok(_), _) => self.error("the preparation gave what was not asked for".to_string()),
            (Err(e), Then::Edit(_) | Then::Road(_)) => self.error(format!("Edit refused: {e}")),
            (Err(e), Then::Replace { .. }) => self.error(format!(
                "Cannot use this scene; the current scene is kept.\n{e}"
            )),
            (Err(e), Then::Open(_)) => self.open_failed(&e),
        }
    }

    /// Stops the preparation under way (a dropped job stops at its next
    /// stage); the current scene is kept.
    pub(super) fn cancel_preparation(&mut self) {
        if let Some((job, note)) = self.handles.prepare_job.take() {
            job.cancel();
            if self.message.as_ref().is_some_and(|m| m.text == note) {
                self.message = None;
            }
            let text = match self.saved_note.take() {
                Some(saved) => format!("{saved}; the next scene was cancelled: this one is kept."),
                None => "Cancelled: the current scene is kept.".to_string(),
            };
            self.info(text);
        }
    }

    /// What the preparation under way is doing and the fraction of it
    /// done, for its progress line.
    pub fn preparation_progress(&self) -> Option<(&'static str, f64)> {
        let (job, _) = self.handles.prepare_job.as_ref()?;
        Some((job.doing(), job.progress()))
    }

    /// Whether an edit or a new document waits for its preparation (a
    /// file read, a ring identified).
    pub fn identifying(&self) -> bool {
        self.handles.prepare_job.is_some()
    }

    /// Whether `scene`'s modes are known without an identification (given
    /// in the scene, or its ring identified at these points before).
    pub fn has_modes_for(&self, scene: &Scene) -> bool {
        self.handles.mode_cache.has_modes(scene)
    }

    /// Applies an edited scene: road and speed live, everything else restarts.
    pub(super) fn edit(&mut self, new: Scene) {
        // the latest edit or document wins over one still waiting (and the
        // note of a save made before it, if any)
        self.handles.prepare_job = None;
        self.saved_note = None;
        if let Err(errors) = new.validate() {
            let list: Vec<String> = errors.iter().map(ToString::to_string).collect();
            self.error(format!("Edit refused: {}", list.join("; ")));
            return;
        }
        // a good edit retires the banner of an earlier refused value
        if let Some(t) = self.field_refusal.take()
            && self.message.as_ref().is_some_and(|m| m.text == t)
        {
            self.message = None;
        }
        let old = &self.doc.scene;
        let restart = new.tyre != old.tyre
            || new.points != old.points
            || new.dt_s != old.dt_s
            || new.duration_s != old.duration_s
            || new.ramp_s != old.ramp_s
            || new.contact_scheme != old.contact_scheme
            || new.contact != old.contact;
        if restart {
            if needs_preparing(&new, &self.handles.mode_cache) {
                // a file read or a ring identified off the UI thread; the
                // edit waits
                self.prepare(Then::Edit(new));
                return;
            }
            let built = super::build(&new, &self.handles.mode_cache);
            self.restart_with(new, built);
            return;
        }
        if new.road != old.road && reads_road_file(&new.road) {
            self.prepare(Then::Road(new));
            return;
        }
        self.live_edit(new, None);
    }

    /// Restarts the run on the edited scene `new`, run by `built`.
    fn restart_with(&mut self, new: Scene, built: Result<(Simulation, Vec<Mode>), SceneError>) {
        let old = &self.doc.scene;
        match built {
            Ok((sim, modes)) => {
                // "Edit as a modal model" changed the panel in place and
                // said nothing: what happened, and where the modes went
                // (a mute also turns a ring into modes, some of them
                // zeroed: not the identified ones)
                let converted = matches!(
                    old.tyre,
                    crate::scene::Tyre::Ring { .. }
                        | crate::scene::Tyre::Measured { .. }
                        | crate::scene::Tyre::FeModes { .. }
                ) && matches!(&new.tyre, crate::scene::Tyre::Modal { modes } if *modes == self.modes);
                let playing = self.time.is_playing();
                // a new duration re-chooses the speed if it was the old
                // duration's own choice, or if the new run would be over in
                // a blink at it (0.002 s at 0.25x: 8 ms)
                let old_speed = self.time.speed();
                let rechoose = new.duration_s != old.duration_s
                    && !self.classroom.on
                    && (old_speed == Speed::watchable(old.duration_s)
                        || matches!(old_speed, Speed::Factor(f)
                            if new.duration_s / f < crate::gui::model::time_control::MIN_WATCH_S));
                self.sim = sim;
                self.modes = modes;
                self.edit_landed(&new);
                self.doc.scene = new;
                self.reset_run();
                if rechoose {
                    self.set_watchable_speed();
                }
                if playing {
                    self.time.play();
                }
                if converted {
                    self.info(modal_model_note(self.modes.len()));
                }
            }
            Err(e) => self.error(format!("Edit refused: {e}")),
        }
    }

    /// Applies a road or speed edit to the running simulation (`profile`:
    /// the new road's, read off the UI thread; else made here).
    fn live_edit(&mut self, new: Scene, profile: Option<RoadProfile>) {
        let old = &self.doc.scene;
        if new.road != old.road {
            let profile = match profile {
                Some(p) => Ok(p),
                None => crate::scene::load_road(&new.road, old.base_dir.as_deref()),
            };
            match profile {
                Ok(profile) => self.sim.set_road(profile),
                Err(e) => {
                    self.error(format!("Road refused: {e}"));
                    return;
                }
            }
        }
        if new.speed_mps != old.speed_mps {
            self.sim.set_speed(new.speed_mps);
        }
        if new.road != old.road || new.speed_mps != old.speed_mps {
            self.live_edits.push(LiveEdit {
                step: self.sim.steps(),
                road: new.road.clone(),
                profile: self.sim.road_profile().clone(),
                speed_mps: new.speed_mps,
            });
        }
        self.edit_landed(&new);
        self.doc.scene = new;
    }

    /// Tells the undo stacks that the edit to `new` lands (before the
    /// document takes it); an undo or redo landing gives back the mode
    /// mutes of its scene. A cancelled or failed sweep's note goes.
    fn edit_landed(&mut self, new: &Scene) {
        // notes of the scene before the edit go with it
        self.research.sweep.scene_edited();
        let mutes = self.mutes.clone();
        if let Some(back) = self
            .undo
            .landed(&self.doc.scene, mutes, new, self.handles.pointer_down)
        {
            self.mutes = back;
        }
    }

    /// Undo or redo the last scene edit: the scene it gives back is applied
    /// as an edit (which may restart the run or wait for a file), and the
    /// fields show it from the next frame. Nothing while an edit or a
    /// document is being prepared.
    pub(super) fn undo_redo(&mut self, dir: crate::gui::model::undo::Direction) {
        // (an edit or a document being prepared is not dropped for it: its
        // menu items are disabled meanwhile)
        if self.handles.prepare_job.is_some() {
            return;
        }
        // (the document's folder stays: it is where the document is saved)
        let base_dir = self.doc.scene.base_dir.clone();
        if let Some(scene) = self.undo.request(dir, base_dir.as_deref()) {
            self.edit(scene);
            self.forget_fields = true;
        }
    }

    /// Takes this frame's solver steps within the time budget, or, when
    /// the steps were taken between the frames ([`App::lend_run`]), says how
    /// they went.
    pub(super) fn advance(&mut self, frame_s: f64) {
        let dt = self.sim.dt_s();
        let want = self.time.steps_this_frame(frame_s, dt);
        let between_frames = self.handles.stepped_ahead.is_some();
        let (taken, r) = match self.handles.stepped_ahead.take() {
            Some((taken, r)) => {
                self.handles.paced_delay_s = self
                    .handles
                    .software_renderer
                    .then(|| self.handles.pacer.next_delay_s(frame_s));
                (taken, r)
            }
            None => {
                self.handles.paced_delay_s = None;
                self.handles.pacer = Default::default();
                if want == 0 {
                    return;
                }
                let before = self.sim.steps();
                let r = if self.sim.finished() {
                    Ok(0)
                } else {
                    crate::solver::drive::run(
                        &mut self.sim,
                        want,
                        &mut (&mut self.history, &mut self.phases),
                        Watch::until(
                            Instant::now() + Duration::from_secs_f64(step_budget_s(frame_s)),
                        ),
                    )
                };
                (self.sim.steps() - before, r)
            }
        };
        match r {
            // the end reached with steps still wanted: the run is complete
            Ok(_) if taken < want && self.sim.finished() => self.run_complete(),
            Ok(_) => {}
            Err(e) => {
                self.time.pause();
                self.error(format!(
                    "Solver error, run paused: {e}\nEdit the scene or reset."
                ));
            }
        }
        if between_frames {
            self.time.report_between_frames(taken, dt, frame_s);
        } else {
            self.time.report(taken, dt, frame_s);
        }
    }

    /// Pauses at the end of the run and says so.
    fn run_complete(&mut self) {
        self.time.pause();
        // (a refused field's reason stays: its field is still marked
        // "not applied", and the reason is what the user must read)
        let refusal_shown = self
            .field_refusal
            .as_ref()
            .is_some_and(|t| self.message.as_ref().is_some_and(|m| m.text == *t));
        if !refusal_shown {
            self.info(format!(
                "run complete: t = {:.4} s. Play (Space) runs it again from t = 0.",
                self.sim.time_s()
            ));
        }
    }
}

/// The banner after a ring tyre became a modal model of `n` modes.
pub fn modal_model_note(n: usize) -> String {
    format!(
        "The ring is replaced by its {n} identified modes: tune, add or remove them in the Modes table (each edit restarts the run); the Fidelity view keeps the ring as its reference. Save to keep the modal model."
    )
}

#[cfg(not(target_arch = "wasm32"))]
impl App {
    /// At the end of a frame playing "as fast as possible": lends the run
    /// to the stepping thread until the next frame
    /// ([`crate::gui::jobs::run_ahead`]), so that it steps while the frame
    /// is drawn. Elsewhere (other speeds, paused, minimised, the run at its
    /// end) the steps stay in the frame.
    pub(super) fn lend_run(&mut self, minimised: bool) {
        use crate::gui::jobs::run_ahead::{Live, RunAhead};
        if minimised
            || !self.time.is_playing()
            || self.time.speed() != Speed::Max
            || self.sim.finished()
            || self.handles.stepped_ahead.is_some()
        {
            return;
        }
        if self.handles.run_ahead.is_none() {
            // no thread (the system refused one): the steps stay in the frame
            self.handles.run_ahead = RunAhead::spawn().ok();
        }
        if self.handles.spare.is_none() {
            // what the app holds while the run is lent: never drawn, since
            // the run comes back before the frame reads it
            let Ok((sim, _)) = build(&default_scene(), &self.handles.mode_cache) else {
                return;
            };
            self.handles.spare = Some(Box::new(Live {
                history: History::new(sim.num_points(), 4096),
                phases: PhaseTracker::new(sim.num_points(), 0.0),
                sim,
            }));
        }
        let (Some(ahead), Some(spare)) =
            (self.handles.run_ahead.as_mut(), self.handles.spare.take())
        else {
            return;
        };
        let Live {
            sim,
            history,
            phases,
        } = *spare;
        let live = Box::new(Live {
            sim: std::mem::replace(&mut self.sim, sim),
            history: std::mem::replace(&mut self.history, history),
            phases: std::mem::replace(&mut self.phases, phases),
        });
        if let Err(live) = ahead.lend(live) {
            self.handles.run_ahead = None;
            self.take_back(live);
        }
    }

    /// At the start of a frame (and before reading the run between
    /// frames): takes the lent run back (the stepping thread stops after
    /// the step it is in) and leaves its steps for the next frame's
    /// [`Command::Advance`]. Nothing lent: does nothing.
    pub fn reclaim_run(&mut self) {
        let Some(ahead) = self.handles.run_ahead.as_mut() else {
            return;
        };
        if !ahead.is_lent() {
            return;
        }
        match ahead.reclaim() {
            Some(back) => {
                self.take_back(back.live);
                self.handles.stepped_ahead = Some((back.taken, back.result));
            }
            None => {
                // the thread died with the run: start it again from the scene
                self.handles.run_ahead = None;
                self.time.pause();
                match build(&self.doc.scene, &self.handles.mode_cache) {
                    Ok((sim, _)) => {
                        self.sim = sim;
                        self.reset_run();
                    }
                    Err(e) => {
                        self.error(format!("The run stopped and could not restart: {e}"));
                        return;
                    }
                }
                self.error(
                    "The solver's thread stopped unexpectedly: the run restarted from t = 0. \
                     Your scene is unchanged."
                        .to_string(),
                );
            }
        }
    }

    /// Whether the run is with the stepping thread (between two frames
    /// that play as fast as possible).
    pub fn run_is_lent(&self) -> bool {
        self.handles.run_ahead.as_ref().is_some_and(|a| a.is_lent())
    }

    /// Puts `live` back in place of the stand-in, kept for the next lease.
    fn take_back(&mut self, live: Box<crate::gui::jobs::run_ahead::Live>) {
        use crate::gui::jobs::run_ahead::Live;
        let Live {
            sim,
            history,
            phases,
        } = *live;
        self.handles.spare = Some(Box::new(Live {
            sim: std::mem::replace(&mut self.sim, sim),
            history: std::mem::replace(&mut self.history, history),
            phases: std::mem::replace(&mut self.phases, phases),
        }));
    }
}
