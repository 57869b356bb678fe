//! # septa-exact
//!
//! Every sign that decides Septa's combinatorics comes from this crate. It
//! knows nothing of meshes: it evaluates the **sign** of small polynomial
//! expressions of `f64` input data *exactly*, as if the inputs were real
//! numbers, using
//!
//! 1. a floating-point **filter** with a proven error bound (stated beside
//!    each predicate), and
//! 2. exact arithmetic when the filter cannot decide.
//!
//! What is exact: the returned [`Sign`]. What is not promised: any
//! floating-point value this crate may compute along the way.
//!
//! Inputs must be finite; [`check_finite`] rejects NaN and infinities with a
//! typed error before any predicate runs.
#![warn(missing_docs)]

mod sign;
mod exact;
mod validate;
mod det;
mod plane;

pub use exact::Exact;
pub use sign::Sign;
pub use validate::{check_finite, NonFinite};
pub use det::{det_sign, det_sign_diff};
pub use plane::{fallback_count, filtered_sign, plane_point_sign, Interval, Ring};
