//! Layer 1, the model: the ring tyre, LSCE identification, measured responses,
//! roads and the bounded recursive convolution.

pub mod convolution;
pub mod fe_modes;
pub mod lsce;
pub mod lscf;
pub mod measured;
pub mod plate;
pub mod ring;
pub mod road;
