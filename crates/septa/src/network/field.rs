//! What the network asks of functions given as formulas rather than as
//! samples: values at points, and (for sparse evaluation) a proof that a box
//! holds no part of the network. The network never names a primitive; the
//! scene's primitives implement these traits (`scene/field.rs`), and so can
//! any user type.

use crate::complex::Mode;

/// `k` functions with values at points and guaranteed bounds over boxes:
/// what sparse evaluation, streaming and the distributed path need.
///
/// `value` must be a pure function of its arguments (blocks are re-run and
/// rays look at single vertices: the same point must give the same bits).
pub trait BoundedField: Sync {
    /// Number of functions `k`.
    fn functions(&self) -> usize;
    /// Value of function `f` at `p`.
    fn value(&self, f: usize, p: [f64; 3]) -> f64;
    /// The `k` values at each of `points`, row-major (`points.len() * k`;
    /// function `f` of point `i` at `i * k + f`). Equal to calling
    /// [`BoundedField::value`] at every point; override to go faster.
    fn sample(&self, points: &[[f64; 3]]) -> Vec<f64> {
        let k = self.functions();
        let mut out = Vec::with_capacity(points.len() * k);
        for &p in points {
            out.extend((0..k).map(|f| self.value(f, p)));
        }
        out
    }
    /// IA: per function, the strict sign it provably keeps on the whole box
    /// `[min, max]` (`Some(true)`: positive at every point of the box), or
    /// `None`. Such a function is active in no tet of the box, and IA reads
    /// it there only through its sign (region labels, edge tests), so the
    /// sparse path neither samples nor bounds it again inside a block. The
    /// default proves nothing.
    fn ia_signs_on_box(&self, _min: [f64; 3], _max: [f64; 3]) -> Vec<Option<bool>> {
        vec![None; self.functions()]
    }
    /// [`BoundedField::sample`] at points of a box whose
    /// [`BoundedField::ia_signs_on_box`] are `signs`: a function with a sign
    /// may be given as `1.0` or `-1.0` instead of its values (IA only). The
    /// default samples every function.
    fn sample_ia_with_signs(&self, points: &[[f64; 3]], _signs: &[Option<bool>]) -> Vec<f64> {
        self.sample(points)
    }
    /// IA [`BoundedField::may_be_active_quick`] on a sub-box of a box whose
    /// [`BoundedField::ia_signs_on_box`] are `signs` (free to skip the
    /// functions with a sign: they keep it on the sub-box).
    fn may_be_active_quick_ia_with_signs(&self, min: [f64; 3], max: [f64; 3], _signs: &[Option<bool>]) -> bool {
        self.may_be_active_quick(Mode::Ia, min, max)
    }
    /// Whether the box `[min, max]` may hold a part of the network: false
    /// only if proven empty (IA: every function keeps one strict sign on
    /// the box; MI: one function exceeds every other on it).
    fn may_be_active(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool;
    /// [`BoundedField::may_be_active`] for the small sub-boxes of a block
    /// about to be sampled (a few cubes each, dozens per block): the same
    /// guarantee (false only if proven empty), free to prove less in
    /// exchange for speed. The default is the full test.
    fn may_be_active_quick(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        self.may_be_active(mode, min, max)
    }
    /// Label volumes: when every function is an indicator (at each point
    /// one function is 1 and the others 0), appends the index of that
    /// function at each of `points` to `out` and returns true, so a block
    /// holds one label per vertex instead of `k` values. The default
    /// (and any other field) returns false and appends nothing.
    fn sample_labels(&self, _points: &[[f64; 3]], _out: &mut Vec<u32>) -> bool {
        false
    }
}

/// `k` real functions evaluable at points, without any bound (a user's
/// callable); continuation needs nothing else.
pub trait Field: Sync {
    /// Number of functions `k`.
    fn functions(&self) -> usize;
    /// Appends the values at `points` to `out`, row-major: `points.len() * k`
    /// values, function `f` of point `i` at `i * k + f`. An `Err` (a
    /// message) stops the run with [`super::NetworkError::FieldFailed`].
    fn eval(&self, points: &[[f64; 3]], out: &mut Vec<f64>) -> Result<(), String>;
}

/// A sized handle on any [`BoundedField`], so that slices can be used as
/// `&dyn BoundedField` inside the network.
pub(crate) struct ByRef<'a, F: ?Sized>(pub &'a F);

impl<F: BoundedField + ?Sized> BoundedField for ByRef<'_, F> {
    fn functions(&self) -> usize {
        self.0.functions()
    }
    fn value(&self, f: usize, p: [f64; 3]) -> f64 {
        self.0.value(f, p)
    }
    fn sample(&self, points: &[[f64; 3]]) -> Vec<f64> {
        self.0.sample(points)
    }
    fn ia_signs_on_box(&self, min: [f64; 3], max: [f64; 3]) -> Vec<Option<bool>> {
        self.0.ia_signs_on_box(min, max)
    }
    fn sample_ia_with_signs(&self, points: &[[f64; 3]], signs: &[Option<bool>]) -> Vec<f64> {
        self.0.sample_ia_with_signs(points, signs)
    }
    fn may_be_active_quick_ia_with_signs(&self, min: [f64; 3], max: [f64; 3], signs: &[Option<bool>]) -> bool {
        self.0.may_be_active_quick_ia_with_signs(min, max, signs)
    }
    fn may_be_active(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        self.0.may_be_active(mode, min, max)
    }
    fn may_be_active_quick(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        self.0.may_be_active_quick(mode, min, max)
    }
    fn sample_labels(&self, points: &[[f64; 3]], out: &mut Vec<u32>) -> bool {
        self.0.sample_labels(points, out)
    }
}
