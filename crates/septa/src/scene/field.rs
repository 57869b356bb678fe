//! Scene primitives as the network's fields (`network::field`): values
//! by [`Primitive::eval`], sampling in parallel by [`sample_grid`], empty
//! boxes proven by the primitives' conservative bounds (`sample.rs`).

use super::sample::{
    box_may_be_active_ia, box_may_be_active_ia_with_signs, box_may_be_active_mi, ia_signs_on_box,
    sample_grid_ia_with_signs,
};
use super::{block_may_be_active_ia, block_may_be_active_mi, sample_grid, Primitive};
use crate::complex::Mode;
use crate::network::{BoundedField, Field};

impl BoundedField for [Primitive] {
    fn functions(&self) -> usize {
        self.len()
    }

    fn value(&self, f: usize, p: [f64; 3]) -> f64 {
        self[f].eval(p)
    }

    fn sample(&self, points: &[[f64; 3]]) -> Vec<f64> {
        sample_grid(self, points)
    }

    fn ia_signs_on_box(&self, min: [f64; 3], max: [f64; 3]) -> Vec<Option<bool>> {
        ia_signs_on_box(self, min, max)
    }

    fn sample_ia_with_signs(&self, points: &[[f64; 3]], signs: &[Option<bool>]) -> Vec<f64> {
        sample_grid_ia_with_signs(self, points, signs)
    }

    fn may_be_active_quick_ia_with_signs(&self, min: [f64; 3], max: [f64; 3], signs: &[Option<bool>]) -> bool {
        box_may_be_active_ia_with_signs(self, min, max, signs)
    }

    fn may_be_active(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        match mode {
            Mode::Ia => block_may_be_active_ia(self, min, max),
            Mode::Mi => block_may_be_active_mi(self, min, max),
        }
    }

    fn may_be_active_quick(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        match mode {
            Mode::Ia => box_may_be_active_ia(self, min, max),
            Mode::Mi => box_may_be_active_mi(self, min, max),
        }
    }
}

impl BoundedField for Vec<Primitive> {
    fn functions(&self) -> usize {
        self.as_slice().functions()
    }

    fn value(&self, f: usize, p: [f64; 3]) -> f64 {
        self.as_slice().value(f, p)
    }

    fn sample(&self, points: &[[f64; 3]]) -> Vec<f64> {
        self.as_slice().sample(points)
    }

    fn ia_signs_on_box(&self, min: [f64; 3], max: [f64; 3]) -> Vec<Option<bool>> {
        self.as_slice().ia_signs_on_box(min, max)
    }

    fn sample_ia_with_signs(&self, points: &[[f64; 3]], signs: &[Option<bool>]) -> Vec<f64> {
        self.as_slice().sample_ia_with_signs(points, signs)
    }

    fn may_be_active_quick_ia_with_signs(&self, min: [f64; 3], max: [f64; 3], signs: &[Option<bool>]) -> bool {
        self.as_slice().may_be_active_quick_ia_with_signs(min, max, signs)
    }

    fn may_be_active(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        self.as_slice().may_be_active(mode, min, max)
    }

    fn may_be_active_quick(&self, mode: Mode, min: [f64; 3], max: [f64; 3]) -> bool {
        self.as_slice().may_be_active_quick(mode, min, max)
    }
}

/// Scene primitives as a [`Field`] for continuation (their bounds unused).
pub struct Primitives<'a>(pub &'a [Primitive]);

impl Field for Primitives<'_> {
    fn functions(&self) -> usize {
        self.0.len()
    }

    fn eval(&self, points: &[[f64; 3]], out: &mut Vec<f64>) -> Result<(), String> {
        for &p in points {
            out.extend(self.0.iter().map(|f| f.eval(p)));
        }
        Ok(())
    }
}
