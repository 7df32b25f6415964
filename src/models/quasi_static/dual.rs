//! Forward-mode dual numbers with four derivative slots, used to get the exact Jacobian of
//! the per-ball equations (and their sensitivity to the ring position) in one pass.
//!
//! The slots are the two components of the ball centre relative to the outer groove centre
//! (`u_o = (X1, X2)`) and of the inner groove centre relative to the ball centre
//! (`u_i = (A1 - X1, A2 - X2)`); see [`super::ball`].

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to four seeds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct D4 {
    pub v: f64,
    pub d: [f64; 4],
}

impl D4 {
    /// A constant.
    #[inline]
    pub fn cst(v: f64) -> Self {
        D4 { v, d: [0.0; 4] }
    }

    /// The `i`-th independent variable.
    #[inline]
    pub fn var(v: f64, i: usize) -> Self {
        let mut d = [0.0; 4];
        d[i] = 1.0;
        D4 { v, d }
    }

    /// `f(self)` given `f` and `f'` at `self.v`.
    #[inline]
    pub fn chain(self, f: f64, df: f64) -> Self {
        D4 {
            v: f,
            d: [
                df * self.d[0],
                df * self.d[1],
                df * self.d[2],
                df * self.d[3],
            ],
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
            D4::cst(0.0)
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
    pub fn atan2(y: D4, x: D4) -> Self {
        let r2 = x.v * x.v + y.v * y.v;
        let v = y.v.atan2(x.v);
        if r2 > 0.0 {
            let mut d = [0.0; 4];
            for (k, dk) in d.iter_mut().enumerate() {
                *dk = (x.v * y.d[k] - y.v * x.d[k]) / r2;
            }
            D4 { v, d }
        } else {
            D4::cst(v)
        }
    }
}

impl Add for D4 {
    type Output = D4;
    #[inline]
    fn add(self, o: D4) -> D4 {
        D4 {
            v: self.v + o.v,
            d: [
                self.d[0] + o.d[0],
                self.d[1] + o.d[1],
                self.d[2] + o.d[2],
                self.d[3] + o.d[3],
            ],
        }
    }
}

impl Sub for D4 {
    type Output = D4;
    #[inline]
    fn sub(self, o: D4) -> D4 {
        D4 {
            v: self.v - o.v,
            d: [
                self.d[0] - o.d[0],
                self.d[1] - o.d[1],
                self.d[2] - o.d[2],
                self.d[3] - o.d[3],
            ],
        }
    }
}

impl Mul for D4 {
    type Output = D4;
    #[inline]
    fn mul(self, o: D4) -> D4 {
        let (a, b) = (self.v, o.v);
        D4 {
            v: a * b,
            d: [
                self.d[0] * b + a * o.d[0],
                self.d[1] * b + a * o.d[1],
                self.d[2] * b + a * o.d[2],
                self.d[3] * b + a * o.d[3],
            ],
        }
    }
}

impl Div for D4 {
    type Output = D4;
    #[inline]
    fn div(self, o: D4) -> D4 {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        D4 {
            v: q,
            d: [
                (self.d[0] - q * o.d[0]) * inv,
                (self.d[1] - q * o.d[1]) * inv,
                (self.d[2] - q * o.d[2]) * inv,
                (self.d[3] - q * o.d[3]) * inv,
            ],
        }
    }
}

impl Neg for D4 {
    type Output = D4;
    #[inline]
    fn neg(self) -> D4 {
        D4 {
            v: -self.v,
            d: [-self.d[0], -self.d[1], -self.d[2], -self.d[3]],
        }
    }
}

impl Add<f64> for D4 {
    type Output = D4;
    #[inline]
    fn add(self, o: f64) -> D4 {
        D4 {
            v: self.v + o,
            ..self
        }
    }
}

impl Sub<f64> for D4 {
    type Output = D4;
    #[inline]
    fn sub(self, o: f64) -> D4 {
        D4 {
            v: self.v - o,
            ..self
        }
    }
}

impl Mul<f64> for D4 {
    type Output = D4;
    #[inline]
    fn mul(self, o: f64) -> D4 {
        D4 {
            v: self.v * o,
            d: [self.d[0] * o, self.d[1] * o, self.d[2] * o, self.d[3] * o],
        }
    }
}

impl Mul<D4> for f64 {
    type Output = D4;
    #[inline]
    fn mul(self, o: D4) -> D4 {
        o * self
    }
}

impl Add<D4> for f64 {
    type Output = D4;
    #[inline]
    fn add(self, o: D4) -> D4 {
        o + self
    }
}

impl Sub<D4> for f64 {
    type Output = D4;
    #[inline]
    fn sub(self, o: D4) -> D4 {
        -o + self
    }
}

impl Div<f64> for D4 {
    type Output = D4;
    #[inline]
    fn div(self, o: f64) -> D4 {
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
        let r = f(D4::var(x0, 0), D4::var(y0, 1));
        let h = 1e-6;
        let v = |x: f64, y: f64| f(D4::cst(x), D4::cst(y)).v;
        let fx = (v(x0 + h, y0) - v(x0 - h, y0)) / (2.0 * h);
        let fy = (v(x0, y0 + h) - v(x0, y0 - h)) / (2.0 * h);
        assert!((r.d[0] - fx).abs() < 1e-8, "{} {}", r.d[0], fx);
        assert!((r.d[1] - fy).abs() < 1e-8, "{} {}", r.d[1], fy);
        assert_eq!(r.d[2], 0.0);
    }
}
