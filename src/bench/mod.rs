//! Measurements: the work-precision study behind `tirecontact bench`, and the
//! baselines it compares against (method §3 α/β form, direct convolution).

pub mod baselines;
pub mod peers;
pub mod residual;
pub mod scaling;
pub mod scenes;
pub mod work_precision;
