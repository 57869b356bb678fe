//! The three-valued result of every predicate.

/// The sign of an exactly evaluated expression.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[repr(i8)]
pub enum Sign {
    /// Strictly below zero.
    Negative = -1,
    /// Exactly zero.
    Zero = 0,
    /// Strictly above zero.
    Positive = 1,
}

impl Sign {
    /// The sign of an `f64` taken at face value (no error analysis).
    #[inline]
    pub fn of_f64(x: f64) -> Sign {
        // Branch-free: predicates sit in hot loops with unpredictable signs.
        Sign::from_i8((x > 0.0) as i8 - (x < 0.0) as i8)
    }

    /// `-1`, `0` or `1`.
    #[inline]
    pub fn as_i8(self) -> i8 {
        self as i8
    }

    /// Inverse of [`Sign::as_i8`] on the signum of `v`.
    #[inline]
    pub fn from_i8(v: i8) -> Sign {
        match v.signum() {
            1 => Sign::Positive,
            -1 => Sign::Negative,
            _ => Sign::Zero,
        }
    }

    /// The sign of a product.
    #[inline]
    #[allow(clippy::should_implement_trait)]
    pub fn mul(self, other: Sign) -> Sign {
        Sign::from_i8(self.as_i8() * other.as_i8())
    }

    /// The opposite sign.
    #[inline]
    pub fn flip(self) -> Sign {
        Sign::from_i8(-self.as_i8())
    }

    /// True for [`Sign::Zero`].
    #[inline]
    pub fn is_zero(self) -> bool {
        self == Sign::Zero
    }
}

impl std::ops::Neg for Sign {
    type Output = Sign;
    fn neg(self) -> Sign {
        self.flip()
    }
}

impl std::ops::Mul for Sign {
    type Output = Sign;
    fn mul(self, rhs: Sign) -> Sign {
        Sign::mul(self, rhs)
    }
}
