//! Synthetic scenes shared by tests, criterion benches and `tirecontact bench`.

use tirecontact_core::model::road::Road;
use tirecontact_io::scene::{ContactScheme, Mode, Point, Scene, Tyre};

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
                y_m: 0.0,
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

/// [`many_points`]`(3, 12)` (40 Hz to 527 Hz) with damping `xi`, each point
/// preloaded so that the static force is `force_n` at every point (through
/// the full static compliance `Σ φ_k φ_kᵀ / ω_k²`), on a 0.2 m sine road of
/// `amplitude_m` at `speed_mps`. With a large preload, a small amplitude
/// and a slow ramp the points never leave the road: a smooth scene.
pub fn preloaded_three_points(
    xi: f64,
    force_n: f64,
    amplitude_m: f64,
    speed_mps: f64,
    ramp_s: f64,
    dt_s: f64,
    duration_s: f64,
) -> Scene {
    let mut s = many_points(3, 12);
    s.name = "3 points x 12 modes, always in contact".into();
    let p = s.num_points();
    let mut compliance = vec![0.0; p * p];
    if let Tyre::Modal { modes } = &mut s.tyre {
        for m in modes {
            m.damping_ratio = xi;
            let w2 = (std::f64::consts::TAU * m.freq_hz).powi(2);
            for i in 0..p {
                for j in 0..p {
                    compliance[i * p + j] += m.shape[i] * m.shape[j] / w2;
                }
            }
        }
    }
    for (i, pt) in s.points.iter_mut().enumerate() {
        pt.h_m = -(0..p).map(|j| compliance[i * p + j] * force_n).sum::<f64>();
    }
    s.road = Road::Sine {
        amplitude_m,
        wavelength_m: 0.2,
    };
    s.speed_mps = speed_mps;
    s.ramp_s = ramp_s;
    s.dt_s = dt_s;
    s.duration_s = duration_s;
    s
}
