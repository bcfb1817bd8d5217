//! The model: the ring and plate tyres, LSCE and LSCF identification
//! numerics, roads as height functions and the bounded recursive
//! convolution.

pub mod convolution;
pub mod lsce;
pub mod lscf;
pub mod plate;
pub mod ring;
pub mod road;
pub mod stability;
