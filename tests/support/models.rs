//! Reference models built in code, shared by several tests: modal tyres given
//! by their mode shapes at the contact points, on a road, and a seeded
//! random number generator for reproducible inputs.

use tirecontact::model::road::Road;
use tirecontact::scene::{ContactScheme, Mode, Point, Scene, Tyre};

/// A mode given by its shape at the contact points (no residue matrix).
pub fn shape_mode(freq_hz: f64, damping_ratio: f64, shape: &[f64]) -> Mode {
    Mode {
        freq_hz,
        damping_ratio,
        residue: vec![],
        shape: shape.to_vec(),
    }
}

/// A sine road.
pub fn sine(amplitude_m: f64, wavelength_m: f64) -> Road {
    Road::Sine {
        amplitude_m,
        wavelength_m,
    }
}

/// Contact points from `(x_m, h_m)` pairs.
pub fn points(xh: &[(f64, f64)]) -> Vec<Point> {
    xh.iter()
        .map(|&(x_m, h_m)| Point { x_m, y_m: 0.0, h_m })
        .collect()
}

/// A modal tyre's scene: `modes` at `points` on `road`, default contact, no
/// folder for road files.
#[allow(clippy::too_many_arguments)]
pub fn modal_scene(
    modes: Vec<Mode>,
    points: Vec<Point>,
    road: Road,
    speed_mps: f64,
    ramp_s: f64,
    dt_s: f64,
    duration_s: f64,
    scheme: ContactScheme,
) -> Scene {
    Scene {
        name: "test scene".into(),
        description: String::new(),
        tyre: Tyre::Modal { modes },
        points: points.into(),
        road,
        speed_mps,
        ramp_s,
        dt_s,
        duration_s,
        contact_scheme: scheme,
        contact: Default::default(),
        base_dir: None,
    }
}

/// Seeded splitmix64: the same numbers on every machine and run.
pub struct SplitMix(pub u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [-1, 1).
    pub fn signed(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}
