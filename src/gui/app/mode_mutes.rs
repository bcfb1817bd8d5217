//! Mode mute and solo (classroom mode bars): a mute is a scene edit of the
//! tyre, remembered so that un-muting every mode gives the original back.

use super::*;
use crate::gui::model::mute_set::{muted_tyre, refusal, toggled};
use crate::scene::Contact;

impl App {
    /// Mutes (or solos) mode `k` through a scene edit, refused with the
    /// reason when the muted model cannot be simulated.
    pub(super) fn set_mutes(&mut self, k: usize, solo: bool) {
        self.set_mutes_with(k, solo, None);
    }

    /// [`Self::set_mutes`], with the scene's contact law replaced by
    /// `contact` in the same edit when given.
    pub(super) fn set_mutes_with(&mut self, k: usize, solo: bool, contact: Option<Contact>) {
        let refused = self.classroom.mute_refused.take();
        self.clear_refusal(refused);
        let contact = contact.unwrap_or_else(|| self.doc.scene.contact.clone());
        let (original, base, current) = match &self.mutes {
            Some(m) => (m.original.clone(), m.base.clone(), m.muted.clone()),
            None => (self.doc.scene.tyre.clone(), self.modes.clone(), Vec::new()),
        };
        let muted = toggled(&current, base.len(), k, solo);
        if muted.iter().all(|m| !m) {
            self.apply(Command::UnmuteAll);
            return;
        }
        if let Some(why) = refusal(&base, &muted, self.doc.scene.num_points(), &contact) {
            let what = if solo { "Solo" } else { "Mute" };
            let text = format!("{what} of mode {k} not applied: {why}");
            self.error(text.clone());
            // the ways out, offered beside the mode bars
            self.classroom.mute_refused = Some(crate::gui::classroom::MuteRefusal {
                mode: k,
                solo,
                text,
                rigid: contact.is_rigid(),
            });
            return;
        }
        let tyre = muted_tyre(&base, &muted);
        let mut s = self.doc.scene.clone();
        s.tyre = tyre.clone();
        s.contact = contact;
        self.edit(s);
        if self.doc.scene.tyre == tyre {
            self.mutes = Some(Mutes {
                original,
                base,
                muted,
                tyre,
            });
        }
    }

    /// Takes down the banner of the refusal `refused` (its cause is gone:
    /// another mute, the solo applied with compliant contact, or the modes
    /// kept playing); a message shown since is left.
    pub(super) fn clear_refusal(&mut self, refused: Option<crate::gui::classroom::MuteRefusal>) {
        if let Some(r) = refused
            && self.message.as_ref().is_some_and(|m| m.text == r.text)
        {
            self.message = None;
        }
    }

    /// Gives the original tyre back (if the edit is accepted).
    pub(super) fn unmute_all(&mut self) {
        if let Some(m) = self.mutes.take() {
            let mut s = self.doc.scene.clone();
            s.tyre = m.original.clone();
            self.edit(s);
            if self.doc.scene.tyre != m.original {
                self.mutes = Some(m);
            }
        }
    }

    /// An edit of the tyre other than by the mutes ends them (after every
    /// command).
    pub(super) fn end_mutes_on_other_edits(&mut self) {
        if self
            .mutes
            .as_ref()
            .is_some_and(|m| m.tyre != self.doc.scene.tyre)
        {
            self.mutes = None;
        }
    }
}
