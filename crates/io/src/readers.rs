//! The file readers: measured tyre responses (UFF 58, CSV impulse
//! responses and FRFs), FE normal modes (UFF 55/2414 with 15/2411, 164,
//! 2420), road profiles and surfaces (CSV).

pub mod crg;
pub mod fe_modes;
pub mod measured;
pub mod road;

/// A two-point model of two modes (60 Hz, ξ 0.03, shape (1, 0.5); 170 Hz,
/// ξ 0.02, shape (0.4, −0.8)), for the unit tests of what reads or
/// identifies responses.
#[cfg(test)]
pub(crate) fn two_mode_test_model() -> tirecontact_core::base::modal::ModalModel {
    let mode =
        |freq_hz: f64, damping_ratio: f64, shape: [f64; 2]| tirecontact_core::base::modal::Mode {
            freq_hz,
            damping_ratio,
            residue: vec![],
            shape: shape.to_vec(),
        };
    tirecontact_core::base::modal::ModalModel::from_modes(
        &[mode(60.0, 0.03, [1.0, 0.5]), mode(170.0, 0.02, [0.4, -0.8])],
        2,
    )
}
