//! Tiny 3-vector helpers. The operation order of `dot` and `norm` matches
//! the reference implementation's (left to right), which the bit-exact
//! sampling test relies on.

pub(crate) type V3 = [f64; 3];

pub(crate) fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(crate) fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

pub(crate) fn scale(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

pub(crate) fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

pub(crate) fn cross(a: V3, b: V3) -> V3 {
    [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
}

/// `v / |v|` component by component (the reference's `normalize_vector`);
/// the zero vector stays zero.
pub(crate) fn normalize(v: V3) -> V3 {
    let n = norm(v);
    if n == 0.0 {
        v
    } else {
        [v[0] / n, v[1] / n, v[2] / n]
    }
}

/// `v / |v|`, or zero when `v` is zero (gradient of a distance).
pub(crate) fn unit_or_zero(v: V3) -> V3 {
    normalize(v)
}

/// Largest absolute coordinate.
pub(crate) fn mag(v: V3) -> f64 {
    v[0].abs().max(v[1].abs()).max(v[2].abs())
}

/// Centre and half-diagonal length of a box (rounded up).
pub(crate) fn box_center_radius(lo: V3, hi: V3) -> (V3, f64) {
    let c = [0, 1, 2].map(|i| 0.5 * (lo[i] + hi[i]));
    let h = [0, 1, 2].map(|i| (hi[i] - c[i]).max(c[i] - lo[i]));
    let r = norm(h);
    // Rounding of c, h and the norm is a few ulps; widen by a relative 1e-15.
    (c, r * (1.0 + 1e-15) + f64::MIN_POSITIVE)
}
