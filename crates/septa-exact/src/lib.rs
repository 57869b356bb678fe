//! # septa-exact
//!
//! Every sign that decides Septa's combinatorics comes from this crate. It
//! knows nothing of meshes: it evaluates the **sign** of small polynomial
//! expressions of `f64` input data *exactly*, as if the inputs were real
//! numbers, in three tiers:
//!
//! 1. a floating-point **filter** with a proven error bound (derivation in
//!    the `filter` module source, after Shewchuk 1997);
//! 2. an allocation-free exact tier on floating-point **expansions** for
//!    inputs within an exponent window (`expansion` module source);
//! 3. exact dyadic **bignums** ([`Exact`]) for everything else (values
//!    spanning `1e-300 .. 1e300`, subnormals).
//!
//! [`stats`] counts, per thread, which tier decided each call.
//!
//! What is exact: the returned [`Sign`]. What is not promised: any
//! floating-point value this crate may compute along the way.
//!
//! Inputs must be finite; [`check_finite`] rejects NaN and infinities with a
//! typed error before any predicate runs.
#![warn(missing_docs)]

mod barycentric;
mod bignum;
mod det;
mod exact;
mod expansion;
mod expansion_det;
mod filter;
mod plane;
mod sign;
pub mod stats;
mod validate;

pub use barycentric::{barycentric_sign_ia, barycentric_sign_mi};
pub use det::{det_sign, det_sign_diff, det_sign_diff_f64_naive, det_sign_f64_naive};
pub use exact::Exact;
pub use plane::{fallback_count, filtered_sign, plane_point_sign, Interval, Ring};
pub use sign::Sign;
pub use validate::{check_finite, NonFinite};
