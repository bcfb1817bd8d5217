//! Synthetic scenes shared by tests, criterion benches and `tirecontact bench`.

use crate::road::Road;
use crate::scene::{ContactScheme, Mode, Point, Scene, Tyre};

/// `points` contact points 5 mm apart on `modes` rank-1 modes (shapes
/// `sin(kπ(i+1)/(P+1))`-like, 40 Hz to ~4 kHz, ξ = 0.05), preloaded by 1 mm
/// on a 1 mm, 0.2 m sine road at 20 m/s. Mode masses grow with order so the
/// static compliance stays that of a tyre (~1e-6 m/N per point).
pub fn many_points(points: usize, n_modes: usize) -> Scene {
    let p = points as f64;
    let modes: Vec<Mode> = (0..n_modes)
        .map(|k| {
            let kf = k as f64 + 1.0;
            let freq_hz = 40.0 * (1.0 + 0.5 * k as f64).powf(1.4);
            let amp = 0.5 / kf.sqrt();
            Mode {
                freq_hz,
                damping_ratio: 0.05,
                residue: vec![],
                shape: (0..points)
                    .map(|i| {
                        amp * (kf * std::f64::consts::PI * (i as f64 + 1.0) / (p + 1.0)).sin()
                            + if k == 0 { amp } else { 0.0 }
                    })
                    .collect(),
            }
        })
        .collect();
    Scene {
        name: format!("{points} points x {n_modes} rank-1 modes"),
        description: String::new(),
        tyre: Tyre::Modal { modes },
        points: (0..points)
            .map(|i| Point {
                x_m: 0.005 * (i as f64 - 0.5 * (p - 1.0)),
                h_m: -0.001,
            })
            .collect(),
        road: Road::Sine {
            amplitude_m: 0.001,
            wavelength_m: 0.2,
        },
        speed_mps: 20.0,
        ramp_s: 0.01,
        dt_s: 1e-5,
        duration_s: 0.1,
        contact_scheme: ContactScheme::Located,
        contact: Default::default(),
        base_dir: None,
    }
}
