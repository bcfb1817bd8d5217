//! Undo and redo of scene edits, without egui: two bounded stacks of whole
//! scenes, each with the words of the change it undoes ("speed V 8 -> 16
//! m/s"). An undo or redo is a scene edit like any other (it may restart
//! the run, wait for a file or a ring's identification, or be refused), so
//! the stacks move only when the edit lands: [`EditHistory::request`] says
//! which scene is wanted, [`EditHistory::landed`] is told of every edit
//! that took effect and recognises the requested one, giving back what the
//! app kept beside that scene (`S`: the visualiser's mode mutes). The edits
//! of one drag of a control (the pointer held down over one quantity) make
//! one step.

use crate::Scene;

/// Edits kept to undo (the oldest are dropped first).
pub const MAX_UNDO: usize = 100;

/// Which way an undo-stack move goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    Undo,
    Redo,
}

/// A scene to go back (or forward) to and what changed from it.
#[derive(Debug, Clone)]
struct Step<S> {
    scene: Scene,
    /// What the app kept beside the scene then, given back with it.
    side: S,
    /// The change, in words with units (empty when only the name or the
    /// description changed).
    what: String,
    /// What the change touched, its numbers left out ("speed V -> m/s"):
    /// the edits of one drag over the same quantity merge.
    key: String,
}

/// The undo and redo stacks of a document; `S`: what the app keeps beside
/// each scene and gets back with it.
#[derive(Debug, Clone)]
pub struct EditHistory<S = ()> {
    undo: Vec<Step<S>>,
    redo: Vec<Step<S>>,
    /// The undo or redo asked for and not landed yet: the scene it edits
    /// to.
    requested: Option<(Direction, Scene)>,
    /// The top undo step was made while the pointer was held down (a drag
    /// still going on may add to it).
    dragging: bool,
}

impl<S> Default for EditHistory<S> {
    fn default() -> Self {
        EditHistory {
            undo: Vec::new(),
            redo: Vec::new(),
            requested: None,
            dragging: false,
        }
    }
}

/// The words of a change from `before` to `after`.
fn describe(before: &Scene, after: &Scene) -> String {
    let edits = crate::scene::edits_since(before, after);
    if edits.is_empty() {
        let what = match (
            before.name != after.name,
            before.description != after.description,
        ) {
            (true, true) => "name and description",
            (true, false) => "name",
            (false, true) => "description",
            (false, false) => "",
        };
        return what.to_string();
    }
    edits.join("; ")
}

/// Whether a word of a change's words is a number ("12", "-5", ".5").
fn is_number(w: &str) -> bool {
    let digits = w.strip_prefix('-').unwrap_or(w);
    digits
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_digit() || c == '.')
}

/// `what` without its numbers: the quantities a change touched.
fn key_of(what: &str) -> String {
    what.split_whitespace()
        .filter(|w| !is_number(w))
        .collect::<Vec<_>>()
        .join(" ")
}

impl<S: Clone> EditHistory<S> {
    /// The words of the change the next undo takes back.
    pub fn undo_label(&self) -> Option<&str> {
        self.undo.last().map(|s| s.what.as_str())
    }

    /// The words of the change the next redo makes again.
    pub fn redo_label(&self) -> Option<&str> {
        self.redo.last().map(|s| s.what.as_str())
    }

    /// The scene an undo or redo edits to (to be applied as an edit), and
    /// noted as requested; `None` when there is nothing to undo or redo.
    /// Its `base_dir` is `base_dir`, the document's: the folder relative
    /// files are read from goes with where the document is saved (a Save
    /// As between the edits moved it), not with the edits.
    pub fn request(&mut self, dir: Direction, base_dir: Option<&std::path::Path>) -> Option<Scene> {
        let stack = match dir {
            Direction::Undo => &self.undo,
            Direction::Redo => &self.redo,
        };
        let mut scene = stack.last()?.scene.clone();
        scene.base_dir = base_dir.map(std::path::Path::to_path_buf);
        self.requested = Some((dir, scene.clone()));
        self.dragging = false;
        Some(scene)
    }

    /// An edit from `before` (with `side` kept beside it) to `after` took
    /// effect. The requested undo or redo when `after` is its scene: the
    /// stacks move by one and what was kept beside `after` is given back.
    /// Otherwise a new edit: it goes on the undo stack (merged with the one
    /// before while `dragging`, the pointer held down since that one, over
    /// the same quantity; a drag back to where it began is no step) and the
    /// redo stack is emptied.
    pub fn landed(&mut self, before: &Scene, side: S, after: &Scene, dragging: bool) -> Option<S> {
        if before == after {
            return None;
        }
        if let Some((dir, wanted)) = self.requested.take()
            && wanted == *after
        {
            let (from, to) = match dir {
                Direction::Undo => (&mut self.undo, &mut self.redo),
                Direction::Redo => (&mut self.redo, &mut self.undo),
            };
            self.dragging = false;
            let step = from.pop()?;
            let back = step.side.clone();
            to.push(Step {
                scene: before.clone(),
                side,
                ..step
            });
            return Some(back);
        }
        let what = describe(before, after);
        let key = key_of(&what);
        self.redo.clear();
        if dragging
            && self.dragging
            && let Some(top) = self.undo.last_mut()
            && top.key == key
        {
            if top.scene == *after {
                // dragged back to where it began: nothing to undo
                self.undo.pop();
                self.dragging = false;
            } else {
                // the same drag: the step still goes back to where it began
                top.what = describe(&top.scene, after);
            }
            return None;
        }
        self.undo.push(Step {
            scene: before.clone(),
            side,
            what,
            key,
        });
        if self.undo.len() > MAX_UNDO {
            self.undo.remove(0);
        }
        self.dragging = dragging;
        None
    }

    /// A save wrote the description `before` as `after` (with the edits
    /// since the scene was opened or saved added): every scene to go back
    /// or forward to with the description `before` takes `after`. An undo
    /// or redo past the save keeps the text the save wrote; it gave back
    /// the description of before the save, the saved lines gone from the
    /// document without a word. A scene with another description (an edit
    /// of it) keeps its own.
    pub fn described(&mut self, before: &str, after: &str) {
        if before == after {
            return;
        }
        for step in self.undo.iter_mut().chain(self.redo.iter_mut()) {
            if step.scene.description == before {
                step.scene.description = after.to_string();
            }
        }
    }

    /// The pointer was let go: the next edit starts a new step.
    pub fn end_drag(&mut self) {
        self.dragging = false;
    }

    /// A new document: nothing to undo or redo.
    pub fn clear(&mut self) {
        *self = EditHistory::default();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene() -> Scene {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/presets/three_points.ron");
        Scene::parse(&std::fs::read_to_string(path).unwrap(), path).unwrap()
    }

    fn with_speed(s: &Scene, v: f64) -> Scene {
        Scene {
            speed_mps: v,
            ..s.clone()
        }
    }

    /// Applies an undo or redo the way the app does: the requested scene
    /// lands as an edit.
    fn go(h: &mut EditHistory, current: &mut Scene, dir: Direction) -> bool {
        let Some(next) = h.request(dir, current.base_dir.as_deref()) else {
            return false;
        };
        h.landed(current, (), &next, false);
        *current = next;
        true
    }

    #[test]
    fn undo_and_redo_walk_the_edits_back_and_forth() {
        let s0 = scene();
        let mut h = EditHistory::default();
        let mut cur = s0.clone();
        let speeds = [2.0, 3.0, 4.0];
        for &v in &speeds {
            let next = with_speed(&cur, v);
            h.landed(&cur, (), &next, false);
            cur = next;
        }
        assert_eq!(h.undo_label(), Some("speed V 3 -> 4 m/s"));
        assert!(h.redo_label().is_none());
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur.speed_mps, 3.0);
        assert_eq!(h.redo_label(), Some("speed V 3 -> 4 m/s"));
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur, s0, "three undos give the scene as opened back");
        assert!(!go(&mut h, &mut cur, Direction::Undo), "nothing left");
        assert!(go(&mut h, &mut cur, Direction::Redo));
        assert!(go(&mut h, &mut cur, Direction::Redo));
        assert_eq!(cur.speed_mps, 3.0);
        // a new edit drops what could be redone
        let next = with_speed(&cur, 9.0);
        h.landed(&cur, (), &next, false);
        cur = next;
        assert!(h.redo_label().is_none());
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur.speed_mps, 3.0);
    }

    #[test]
    fn a_requested_undo_that_never_lands_moves_nothing() {
        let s0 = scene();
        let mut h = EditHistory::default();
        let s1 = with_speed(&s0, 5.0);
        h.landed(&s0, (), &s1, false);
        // the undo is asked for, but the user's next edit lands instead
        // (the undo was refused or waited for a file and was replaced)
        let _ = h.request(Direction::Undo, s0.base_dir.as_deref());
        let s2 = with_speed(&s1, 6.0);
        h.landed(&s1, (), &s2, false);
        assert_eq!(h.undo_label(), Some("speed V 5 -> 6 m/s"));
        let mut cur = s2;
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur, s0);
    }

    #[test]
    fn one_drag_over_one_quantity_is_one_step() {
        let s0 = scene();
        let mut h = EditHistory::default();
        let mut cur = s0.clone();
        for k in 1..=30 {
            let next = with_speed(&cur, 1.0 + 0.1 * k as f64);
            h.landed(&cur, (), &next, true);
            cur = next;
        }
        h.end_drag();
        let whole = format!("speed V {} -> 4 m/s", s0.speed_mps);
        assert_eq!(
            h.undo_label(),
            Some(whole.as_str()),
            "the drag from its start"
        );
        // a second drag is a second step
        let next = with_speed(&cur, 7.0);
        h.landed(&cur, (), &next, true);
        cur = next;
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur.speed_mps, 4.0);
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur, s0);
        // a drag over another quantity does not merge into the speed's
        let mut h = EditHistory::default();
        let a = with_speed(&s0, 2.0);
        h.landed(&s0, (), &a, true);
        let b = Scene {
            dt_s: a.dt_s / 2.0,
            ..a.clone()
        };
        h.landed(&a, (), &b, true);
        let mut cur = b;
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert_eq!(cur, a);
    }

    #[test]
    fn a_drag_back_to_where_it_began_is_no_step() {
        let s0 = scene();
        let mut h = EditHistory::default();
        let s1 = with_speed(&s0, 30.0);
        h.landed(&s0, (), &s1, false);
        h.end_drag();
        let mut cur = s1.clone();
        for v in [31.0, 32.0, 31.0, 30.0] {
            let next = with_speed(&cur, v);
            h.landed(&cur, (), &next, true);
            cur = next;
        }
        h.end_drag();
        assert_eq!(
            h.undo_label(),
            Some(format!("speed V {} -> 30 m/s", s0.speed_mps).as_str())
        );
        assert!(
            go(&mut h, &mut cur, Direction::Undo),
            "the edit before the drag"
        );
        assert_eq!(cur, s0);
    }

    #[test]
    fn what_was_kept_beside_a_scene_comes_back_with_it() {
        let s0 = scene();
        let mut h: EditHistory<u32> = EditHistory::default();
        let s1 = with_speed(&s0, 5.0);
        assert_eq!(h.landed(&s0, 7, &s1, false), None);
        let back = h.request(Direction::Undo, s0.base_dir.as_deref()).unwrap();
        assert_eq!(
            h.landed(&s1, 9, &back, false),
            Some(7),
            "the undo gives 7 back"
        );
        let fwd = h.request(Direction::Redo, s0.base_dir.as_deref()).unwrap();
        assert_eq!(
            h.landed(&back, 7, &fwd, false),
            Some(9),
            "the redo gives 9 back"
        );
    }

    #[test]
    fn numbers_leave_a_change_s_key() {
        assert_eq!(key_of("speed V -5 -> 12.5 m/s"), "speed V -> m/s");
        assert_eq!(
            key_of("mode 0 frequency .5 -> -0.25 Hz"),
            "mode frequency -> Hz"
        );
    }

    #[test]
    fn the_stack_keeps_the_latest_edits_and_a_new_document_empties_it() {
        let s0 = scene();
        let mut h = EditHistory::default();
        let mut cur = s0.clone();
        for k in 0..MAX_UNDO + 20 {
            let next = with_speed(&cur, 1.0 + k as f64);
            h.landed(&cur, (), &next, false);
            cur = next;
        }
        let mut undone = 0;
        while go(&mut h, &mut cur, Direction::Undo) {
            undone += 1;
        }
        assert_eq!(undone, MAX_UNDO);
        assert_eq!(cur.speed_mps, 20.0, "the oldest edits were dropped");
        h.clear();
        assert!(h.undo_label().is_none() && h.redo_label().is_none());
    }

    #[test]
    fn a_change_of_the_text_alone_is_named() {
        let s0 = scene();
        let renamed = Scene {
            name: "mine".into(),
            ..s0.clone()
        };
        let mut h = EditHistory::default();
        h.landed(&s0, (), &renamed, false);
        assert_eq!(h.undo_label(), Some("name"));
        // an edit that changes nothing is not a step
        h.landed(&renamed, (), &renamed.clone(), false);
        let mut cur = renamed;
        assert!(go(&mut h, &mut cur, Direction::Undo));
        assert!(!go(&mut h, &mut cur, Direction::Undo));
    }
}
