//! Forward-mode dual numbers with four derivative slots, used to get the exact Jacobian of
//! the per-ball equations (and their sensitivity to the ring position) in one pass.
//!
//! The slots are the two components of the ball centre relative to the outer groove centre
//! (`u_o = (X1, X2)`) and of the inner groove centre relative to the ball centre
//! (`u_i = (A1 - X1, A2 - X2)`); see [`super::ball`].

#![allow(clippy::needless_range_loop)] // the slot loops read as the formulas

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to `N` seeds (`N = 0`: plain values).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Dual<const N: usize> {
    pub v: f64,
    pub d: [f64; N],
}

/// Four slots: d/d(u_o1, u_o2, u_i1, u_i2).
pub(crate) type D4 = Dual<4>;

impl<const N: usize> Dual<N> {
    /// A constant.
    #[inline]
    pub fn cst(v: f64) -> Self {
        Dual { v, d: [0.0; N] }
    }

    /// `f(self)` given `f` and `f'` at `self.v`.
    #[inline]
    pub fn chain(self, f: f64, df: f64) -> Self {
        Dual {
            v: f,
            d: self.d.map(|x| df * x),
        }
    }

    #[inline]
    pub fn sqrt(self) -> Self {
        let s = self.v.max(0.0).sqrt();
        let ds = if s > 0.0 { 0.5 / s } else { 0.0 };
        self.chain(s, ds)
    }

    /// `max(self, 0)^1.5`: the Hertz law, C¹ at zero.
    #[inline]
    pub fn pos_pow15(self) -> Self {
        if self.v > 0.0 {
            let s = self.v.sqrt();
            self.chain(self.v * s, 1.5 * s)
        } else {
            Dual::cst(0.0)
        }
    }

    #[inline]
    pub fn sin(self) -> Self {
        self.chain(self.v.sin(), self.v.cos())
    }

    #[inline]
    pub fn cos(self) -> Self {
        self.chain(self.v.cos(), -self.v.sin())
    }

    #[inline]
    pub fn abs(self) -> Self {
        if self.v < 0.0 {
            -self
        } else {
            self
        }
    }

    /// `atan2(y, x)`.
    #[inline]
    pub fn atan2(y: Self, x: Self) -> Self {
        let r2 = x.v * x.v + y.v * y.v;
        let v = y.v.atan2(x.v);
        if r2 > 0.0 {
            let mut d = [0.0; N];
            for (k, dk) in d.iter_mut().enumerate() {
                *dk = (x.v * y.d[k] - y.v * x.d[k]) / r2;
            }
            Dual { v, d }
        } else {
            Dual::cst(v)
        }
    }
}

impl<const N: usize> Add for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: Self) -> Self {
        let mut d = self.d;
        for k in 0..N {
            d[k] += o.d[k];
        }
        Dual { v: self.v + o.v, d }
    }
}

impl<const N: usize> Sub for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: Self) -> Self {
        let mut d = self.d;
        for k in 0..N {
            d[k] -= o.d[k];
        }
        Dual { v: self.v - o.v, d }
    }
}

impl<const N: usize> Mul for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let (a, b) = (self.v, o.v);
        let mut d = [0.0; N];
        for k in 0..N {
            d[k] = self.d[k] * b + a * o.d[k];
        }
        Dual { v: a * b, d }
    }
}

impl<const N: usize> Div for Dual<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        let mut d = [0.0; N];
        for k in 0..N {
            d[k] = (self.d[k] - q * o.d[k]) * inv;
        }
        Dual { v: q, d }
    }
}

impl<const N: usize> Neg for Dual<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Dual {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}

impl<const N: usize> Add<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn add(self, o: f64) -> Self {
        Dual {
            v: self.v + o,
            d: self.d,
        }
    }
}

impl<const N: usize> Sub<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn sub(self, o: f64) -> Self {
        Dual {
            v: self.v - o,
            d: self.d,
        }
    }
}

impl<const N: usize> Mul<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: f64) -> Self {
        Dual {
            v: self.v * o,
            d: self.d.map(|x| x * o),
        }
    }
}

impl<const N: usize> Mul<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn mul(self, o: Dual<N>) -> Dual<N> {
        o * self
    }
}

impl<const N: usize> Add<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn add(self, o: Dual<N>) -> Dual<N> {
        o + self
    }
}

impl<const N: usize> Sub<Dual<N>> for f64 {
    type Output = Dual<N>;
    #[inline]
    fn sub(self, o: Dual<N>) -> Dual<N> {
        -o + self
    }
}

impl<const N: usize> Div<f64> for Dual<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: f64) -> Self {
        self * (1.0 / o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        // f(x, y) = atan2(y, x) sqrt(x y) / (1 + x) + max(y - x, 0)^1.5 cos(x) + sin(y)
        let f = |x: D4, y: D4| {
            D4::atan2(y, x) * (x * y).sqrt() / (1.0 + x) + (y - x).pos_pow15() * x.cos() + y.sin()
        };
        let (x0, y0) = (0.7, 1.3);
        let var = |v: f64, i: usize| {
            let mut x = D4::cst(v);
            x.d[i] = 1.0;
            x
        };
        let r = f(var(x0, 0), var(y0, 1));
        let h = 1e-6;
        let v = |x: f64, y: f64| f(D4::cst(x), D4::cst(y)).v;
        let fx = (v(x0 + h, y0) - v(x0 - h, y0)) / (2.0 * h);
        let fy = (v(x0, y0 + h) - v(x0, y0 - h)) / (2.0 * h);
        assert!((r.d[0] - fx).abs() < 1e-8, "{} {}", r.d[0], fx);
        assert!((r.d[1] - fy).abs() < 1e-8, "{} {}", r.d[1], fy);
        assert_eq!(r.d[2], 0.0);
    }
}
