//! Ball–race contacts of the skidding level: the quasi-static radial split of a ball's load
//! between the races, contact states, the penetration law, the ball's geometry at its azimuth,
//! the contact loads and the spin moment (docs/physics.md §5.2).

use super::*;

impl SkiddingModel {
    /// Ball position along the contact line: solve `Q_o(d_o) - Q_i(delta - d_o) = f` for
    /// the outer approach `d_o` (monotone; safeguarded Newton). Returns the loads, their
    /// stiffnesses `dQ/d(approach)` and the square roots of the approaches.
    pub(super) fn split(&self, delta: f64, f: f64) -> Split {
        let (ki, ko) = (self.inner.kc, self.outer.kc);
        if f <= 0.0 && delta <= 0.0 {
            return Split::default();
        }
        let f = f.max(0.0);
        // Bracket [lo, hi] with g(lo) <= 0 <= g(hi): when the outer contact alone carries
        // at least f at the whole approach (the usual case), hi = delta; otherwise the ball
        // may leave the inner race and hi = max(delta, 0) + (f/ko)^(2/3) (one cube root).
        let lo = 0.0;
        let outer_alone = if delta > 0.0 {
            ko * delta * delta.sqrt()
        } else {
            0.0
        };
        let hi = if delta > 0.0 && outer_alone >= f {
            delta
        } else {
            let t = f / ko;
            delta.max(0.0) + (t * t).cbrt()
        };
        // Start from the f = 0 split (equal loads).
        let x = if delta > 0.0 {
            (delta * self.kratio / (1.0 + self.kratio)).min(hi)
        } else {
            hi
        };
        let g = |x: f64| {
            let (qo, so) = crate::contact::hertz_load_and_stiffness(ko, x);
            let (qi, si) = crate::contact::hertz_load_and_stiffness(ki, delta - x);
            (qo - qi - f, so + si)
        };
        let tol = 1e-13 * hi.max(1e-9);
        // A Newton step below 1e-8 of the bracket leaves an error of order its square
        // over the approach (quadratic convergence): accept it without another pass.
        let tol_newton = 1e-8 * hi.max(1e-9);
        let x = crate::solver::newton::bracketed(g, lo, hi, x, tol, tol_newton, 60);
        let (r_o, r_i) = (x.max(0.0).sqrt(), (delta - x).max(0.0).sqrt());
        Split {
            q_i: ki * r_i * r_i * r_i,
            q_o: ko * r_o * r_o * r_o,
            s_i: 1.5 * ki * r_i,
            s_o: 1.5 * ko * r_o,
            r_i,
            r_o,
        }
    }

    /// Contact data for the traction law from the load and the square root of the
    /// approach (`Q^(1/3) = Kc^(1/3) sqrt(delta)`: no cube root on the hot path).
    pub(super) fn contact_state(&self, inner: bool, q: f64, r: f64) -> ContactState {
        let (pc, ca, cb) = if inner {
            (&self.inner, self.ax_i[0], self.ax_i[1])
        } else {
            (&self.outer, self.ax_o[0], self.ax_o[1])
        };
        ContactState {
            q,
            a: ca * r,
            b: cb * r,
            rx: pc.curvature.rx,
            kappa: pc.ellipse.kappa,
            e_eff: pc.e_eff,
        }
    }

    /// C¹ positive part with smoothing width `w`, and its slope.
    pub(super) fn pen(x: f64, w: f64) -> (f64, f64) {
        if x <= 0.0 {
            (0.0, 0.0)
        } else if x < w {
            (0.5 * x * x / w, x / w)
        } else {
            (x - 0.5 * w, 1.0)
        }
    }

    /// Integral of [`Self::pen`]: the pocket spring's energy per unit stiffness.
    pub(super) fn pen_energy(x: f64, w: f64) -> f64 {
        if x <= 0.0 {
            0.0
        } else if x < w {
            x * x * x / (6.0 * w)
        } else {
            0.5 * x * x - 0.5 * w * x + w * w / 6.0
        }
    }

    /// Geometry of ball `j` at azimuth `psi` for ring displacement `q` (Jones geometry of
    /// the ring level).
    pub(super) fn geo(&self, q: &[f64; 5], psi: f64) -> Geo {
        let (s, c) = psi.sin_cos();
        let a1 = self.a10 + q[2] + self.ri * (q[3] * s - q[4] * c);
        let a2 = self.a20 + q[0] * c + q[1] * s;
        // Millimetre-sized: no overflow, so the plain root (hypot is several times slower).
        let l = (a1 * a1 + a2 * a2).sqrt();
        let n = [a1 / l, a2 / l];
        Geo {
            s,
            c,
            n,
            l,
            delta: if self.p.outer_wear.is_empty() {
                l - self.a
            } else {
                l - self.a - crate::models::wear::sample(&self.p.outer_wear, psi)
            },
            g: [
                n[1] * c,
                n[1] * s,
                n[0],
                n[0] * self.ri * s,
                -n[0] * self.ri * c,
            ],
        }
    }

    /// Normal loads of a ball at geometry `geo` and orbital speed `w_b` (centrifugal
    /// force `m (dm/2) w_b²` along the contact line's radial component).
    /// With radial mass the ball's outer approach `u` is given (`Some`) and the loads
    /// follow from it and the total approach.
    pub(super) fn loads(&self, geo: &Geo, w_b: f64, u: Option<f64>) -> Loads {
        let fc = self.m * 0.5 * self.dm * w_b * w_b;
        let f = fc * geo.n[1];
        let sp = match u {
            None => self.split(geo.delta, f),
            Some(u) => {
                let (r_o, r_i) = (u.max(0.0).sqrt(), (geo.delta - u).max(0.0).sqrt());
                let (ki, ko) = (self.inner.kc, self.outer.kc);
                Split {
                    q_i: ki * r_i * r_i * r_i,
                    q_o: ko * r_o * r_o * r_o,
                    s_i: 1.5 * ki * r_i,
                    s_o: 1.5 * ko * r_o,
                    r_i,
                    r_o,
                }
            }
        };
        Loads {
            sp,
            fc,
            f_active: f > 0.0,
            radial: u.is_some(),
        }
    }

    /// Spinning moment of a contact in full spin sliding, `M = (3/8) mu Q a E(k)`
    /// (Harris & Kotzalas Vol. 2 ch. 2, the spinning friction moment of an elliptical
    /// contact; `3 pi/16 mu Q a` for a circle), regularised by `tanh(w a / v_s)` so that it
    /// is continuous through zero spin. Returns `(M, dM/dQ, dM/dw)` at spin `w` (rad/s).
    pub(super) fn spin_moment(&self, inner: bool, q: f64, r: f64, w: f64) -> (f64, f64, f64) {
        let mu = self.p.spin_friction;
        if mu <= 0.0 || q <= 0.0 {
            return (0.0, 0.0, 0.0);
        }
        let (ca, e) = if inner {
            (self.ax_i[0], self.inner.ellipse.e)
        } else {
            (self.ax_o[0], self.outer.ellipse.e)
        };
        let a = ca * r;
        let ms = 0.375 * mu * q * a * e;
        let z = w * a / self.p.friction_v_s;
        let th = crate::contact::traction::tanh(z);
        let sech2 = 1.0 - th * th;
        // ms ~ Q^(4/3), z ~ Q^(1/3).
        let m_q = (4.0 / 3.0) * ms * th / q + ms * sech2 * z / (3.0 * q);
        (ms * th, m_q, ms * sech2 * a / self.p.friction_v_s)
    }

    /// Ball `j`'s outer-race contact at the last evaluation: the contact data of the
    /// traction law, the slip `dv_o` and the rolling speed `u_o` (m/s).
    pub fn outer_contact(&self, j: usize) -> (ContactState, f64, f64) {
        let b = &self.balls[j];
        let r = (b.q_o.max(0.0) / self.outer.kc).cbrt().sqrt();
        let u_o = 0.5 * (0.5 * self.do_ * b.w_b + 0.5 * self.d * b.w_s);
        (self.contact_state(false, b.q_o.max(0.0), r), b.dv_o, u_o)
    }

    /// Hertz approach of the outer contact under load `q`, m.
    pub fn outer_approach(&self, q: f64) -> f64 {
        (q.max(0.0) / self.outer.kc).powf(2.0 / 3.0)
    }

    /// Peak Hertz pressure at the larger of a ball's two loads, Pa.
    pub fn peak_pressure(&self, q_i: f64, q_o: f64) -> f64 {
        // p0 = 3Q/(2 pi a b) with a b = ca cb Q^(2/3) (coefficients per sqrt(delta) here).
        let p0 = |q: f64, ax: [f64; 2], k3: f64| {
            if q > 0.0 {
                let q3 = q.cbrt();
                1.5 * q3 * k3 * k3 / (PI * ax[0] * ax[1])
            } else {
                0.0
            }
        };
        p0(q_i, self.ax_i, self.kc3_i).max(p0(q_o, self.ax_o, self.kc3_o))
    }
}
