//! Solo and mute of modes (classroom mode bars): a muted mode's
//! residue (or shape) is scaled by 0 in the scene, which restarts the run;
//! un-muting every mode gives the original tyre back exactly.

use crate::base::linalg;
use crate::model::convolution::ModalBasis;
use crate::scene::{Contact, Mode, Tyre};

/// Which modes are muted, and the tyre to give back when none is.
#[derive(Debug, Clone, PartialEq)]
pub struct Mutes {
    /// The tyre before the first mute (modal or ring).
    pub original: Tyre,
    /// The modes of `original` (identified for a ring tyre).
    pub base: Vec<Mode>,
    pub muted: Vec<bool>,
    /// The tyre the mutes produced (to notice other edits of the tyre).
    pub tyre: Tyre,
}

/// A modal tyre of `base` with the modes flagged in `muted` scaled by 0.
pub fn muted_tyre(base: &[Mode], muted: &[bool]) -> Tyre {
    let modes = base
        .iter()
        .zip(muted.iter().chain(std::iter::repeat(&false)))
        .map(|(m, &off)| {
            let mut m = m.clone();
            if off {
                m.residue.iter_mut().flatten().for_each(|a| *a = 0.0);
                m.shape.iter_mut().for_each(|a| *a = 0.0);
            }
            m
        })
        .collect();
    Tyre::Modal { modes }
}

/// The muted flags after toggling mode `k` (`solo`: mute all others, or
/// un-mute all when `k` is already the only one playing).
pub fn toggled(current: &[bool], n: usize, k: usize, solo: bool) -> Vec<bool> {
    let mut m: Vec<bool> = (0..n)
        .map(|i| current.get(i).copied().unwrap_or(false))
        .collect();
    if k >= n {
        return m;
    }
    if solo {
        let is_solo = (0..n).all(|i| m[i] == (i != k));
        for (i, x) in m.iter_mut().enumerate() {
            *x = !is_solo && i != k;
        }
    } else {
        m[k] = !m[k];
    }
    m
}

/// Why these mutes cannot be simulated, if they cannot: every mode muted, or
/// (rigid contact) the playing modes cannot move the points independently,
/// which makes the contact system singular.
pub fn refusal(base: &[Mode], muted: &[bool], p: usize, contact: &Contact) -> Option<String> {
    let playing = muted.iter().filter(|m| !**m).count();
    if playing == 0 {
        return Some("at least one mode must play".to_string());
    }
    if !contact.is_rigid() || p == 0 {
        return None;
    }
    let modes: Vec<Mode> = base
        .iter()
        .zip(muted)
        .filter(|(_, m)| !**m)
        .map(|(m, _)| m.clone())
        .collect();
    // Σ A_k of the playing modes: symmetric positive semi-definite, so
    // full rank means every active set's contact system is regular
    let j = match ModalBasis::new(&modes, p) {
        Ok(basis) => basis.velocity_jump(),
        Err(e) => return Some(e.to_string()),
    };
    let scale = j.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let rank = match linalg::rank(
        linalg::from_row_major(p, &j).as_ref(),
        1e-10 * scale.max(f64::MIN_POSITIVE),
    ) {
        Ok(rank) => rank,
        Err(e) => return Some(format!("the playing modes' contact system: {e}")),
    };
    (rank < p).then(|| refusal_text(p, playing, rank))
}

/// Why rigid contact refuses `playing` modes that move `p` points in only
/// `rank` independent shapes, and the ways out, in plain words.
fn refusal_text(p: usize, playing: usize, rank: usize) -> String {
    let who = if playing == 1 {
        "the one mode playing gives".to_string()
    } else {
        format!("the {playing} modes playing give")
    };
    format!(
        "with rigid contact the road sets the height of every point touching it, so \
         the playing modes must be able to move each of the {p} points on its own \
         ({p} independent shapes of motion); {who} only {rank}, and the contact \
         forces would have no unique solution. Use compliant contact (a spring in \
         the tread takes up what the modes cannot follow), or keep more modes playing."
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Scene;

    fn three() -> Scene {
        Scene::parse(
            include_str!(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/presets/three_points.ron"
            )),
            "three",
        )
        .unwrap()
    }

    #[test]
    fn solo_mutes_the_others_and_toggles_back() {
        let m = toggled(&[], 3, 1, true);
        assert_eq!(m, [true, false, true]);
        assert_eq!(toggled(&m, 3, 1, true), [false, false, false]);
        assert_eq!(toggled(&m, 3, 0, false), [false, false, true]);
        assert_eq!(toggled(&m, 3, 7, false), m);
    }

    #[test]
    fn muted_modes_have_zero_residue_and_the_rest_is_unchanged() {
        let s = three();
        let base = crate::ModeCache::new().modes(&s).unwrap();
        let Tyre::Modal { modes } = muted_tyre(&base, &[false, true, false]) else {
            panic!()
        };
        assert_eq!(modes[0], base[0]);
        assert_eq!(modes[2], base[2]);
        assert!(
            modes[1]
                .residue_matrix()
                .iter()
                .flatten()
                .all(|a| *a == 0.0)
        );
        assert_eq!(modes[1].freq_hz, base[1].freq_hz);
    }

    #[test]
    fn rigid_contact_refuses_fewer_independent_modes_than_points() {
        let s = three();
        let base = crate::ModeCache::new().modes(&s).unwrap();
        assert!(refusal(&base, &[false; 3], 3, &s.contact).is_none());
        let r = refusal(&base, &[false, true, false], 3, &s.contact).unwrap();
        assert!(
            r.contains("move each of the 3 points on its own")
                && r.contains("the 2 modes playing give only 2,")
                && r.contains("keep more modes playing")
                && !r.contains("mode(s)"),
            "{r}"
        );
        // a solo: one mode, said so
        let r = refusal(&base, &[true, false, true], 3, &s.contact).unwrap();
        assert!(r.contains("the one mode playing gives only 1,"), "{r}");
        let soft = Contact::Compliant {
            stiffness_n_m: vec![2e6],
        };
        assert!(refusal(&base, &[false, true, false], 3, &soft).is_none());
        assert!(refusal(&base, &[true; 3], 3, &soft).is_some());
    }
}
