//! # septa-exact
//!
//! Every sign that decides Septa's combinatorics comes from this crate. It
//! knows nothing of meshes: it evaluates the **sign** of small polynomial
//! expressions of `f64` input data *exactly*, as if the inputs were real
//! numbers, in three tiers:
//!
//! 1. a floating-point **filter** with a proven error bound (derivation in
//!    the `filter` module source, after Shewchuk 1997), valid for all finite
//!    inputs: underflow is bounded as an absolute error, overflow detected;
//! 2. an allocation-free exact tier: fixed-width **integers** (`i128`, or a
//!    256-bit accumulator) when each row, scaled by a power of two, has at
//!    most 62 significant bits (exactly degenerate data such as small
//!    integers, and most near-degenerate data at any magnitude), else
//!    floating-point **expansions** (Shewchuk 1997) for inputs within an
//!    exponent window (`expansion` module source);
//! 3. exact dyadic **bignums** ([`Exact`]) for everything else (rows whose
//!    values span `1e-300 .. 1e300`, full-precision subnormals).
//!
//! [`stats`] counts, per thread, which tier decided each call.
//!
//! The barycentric predicate of Du et al. 2022 (Sec. 5.2, eq. 5-6) is
//! [`barycentric_sign_ia`] / [`barycentric_sign_mi`]; the `*_f64_naive`
//! functions are the unfiltered floating-point baseline (not exact), kept
//! for the paper's robustness comparison.
//!
//! What is exact: the returned [`Sign`]. What is not promised: any
//! floating-point value this crate may compute along the way.
//!
//! Inputs must be finite; [`check_finite`] rejects NaN and infinities with a
//! typed error before any predicate runs.
//!
//! The proofs assume the default IEEE-754 environment of Rust programs:
//! round-to-nearest-even and gradual underflow (no flush-to-zero or
//! denormals-are-zero modes, which some foreign libraries switch on).
#![warn(missing_docs)]

mod barycentric;
mod bignum;
mod bounded;
mod det;
mod double_word;
mod exact;
mod expansion;
mod expansion_det;
mod expansion_ring;
mod filter;
mod integer_det;
mod orient3d;
mod plane;
mod sign;
pub mod stats;
mod validate;

pub use barycentric::{
    barycentric_sign_ia, barycentric_sign_ia_f64_naive, barycentric_sign_mi, barycentric_sign_mi_f64_naive,
};
pub use bounded::{filtered_sign_bounded, Bounded};
pub use det::{det_sign, det_sign_diff, det_sign_diff_f64_naive, det_sign_f64_naive};
pub use double_word::DoubleWord;
pub use exact::Exact;
pub use expansion_ring::{expansion_window, Expansion};
pub use orient3d::orient3d_exact_diffs;
pub use plane::{fallback_count, filtered_sign, plane_point_sign, Interval, Ring};
pub use sign::Sign;
pub use validate::{check_finite, NonFinite};
