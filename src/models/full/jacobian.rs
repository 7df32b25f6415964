//! The full level's Jacobian: analytic per-ball and cage columns with the difference quotients
//! where the evaluation is not differentiated by hand.

use super::*;
use crate::seam::{Jacobians, Motion};

impl FullModel {
    /// Jacobians at the shaft's motion `m` by block-wise forward differences, into `jac`, all
    /// row-major: `jx = d(rates)/d(states)` (`n × n`), and when load-driven (non-empty
    /// slices) `jm = d(rates)/d(q, v)` (`n × 10`), `wx = d(wrench)/d(states)` (`5 × n`),
    /// `wm = d(wrench)/d(q, v)` (`5 × 10`). A ball's column costs one ball evaluation (its rates, its share of the
    /// cage's and of the wrench, differenced against the ball's terms kept from the
    /// evaluation at `x`; a spin column keeps the ball's position, and with dynamic ball
    /// contacts a velocity column keeps its contacts), a cage column
    /// the pockets of every ball on the race parts kept from the evaluation at `x` (the
    /// cage reaches a ball only through its pocket), a ring column the race contacts'
    /// tractions of every ball (the inner contacts evaluated again when
    /// `q` moved, the pockets kept where the positions are; quasi-static ball positions
    /// are solved again for a displacement column).
    /// The cage columns equal whole-evaluation differences bit for bit. `scratch` holds
    /// `3 n + n_aux` values. Allocation-free.
    pub fn jacobian(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &[f64],
        jac: Jacobians<'_>,
        scratch: &mut [f64],
    ) -> Result<()> {
        self.jacobian_from(m, x, aux, jac, scratch, None, true)
    }

    /// [`Self::jacobian`]; `kept`: the rates and totals of an evaluation with
    /// [`Races::Keep`] at this motion, these states and with `aux` as it left it (its
    /// positions are then those a solve from `aux` returns, bit for bit), which stands in
    /// for the evaluation at `x`. `clear`: zero the entries of `jx` that couple two
    /// balls' blocks (zero by [`Self::blocks`]; never written here), which a caller that
    /// reads only the blocks and the border leaves as they are (`false`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn jacobian_from(
        &mut self,
        m: &Motion,
        x: &[f64],
        aux: &[f64],
        jac: Jacobians<'_>,
        scratch: &mut [f64],
        kept: Option<(&[f64], &Totals)>,
        clear: bool,
    ) -> Result<()> {
        let Jacobians { jx, jm, wx, wm } = jac;
        let n = self.n_states();
        let na = self.n_aux();
        let (xs, rest) = scratch.split_at_mut(n);
        let (d0, rest) = rest.split_at_mut(n);
        let (col, rest) = rest.split_at_mut(n);
        let auxs = &mut rest[..na];
        let load = !jm.is_empty() && !wx.is_empty() && !wm.is_empty();
        // Written below: every row of the cage's and ring's columns, a ball's block and
        // the cage's rows in the ball's columns (the rest is zero only with ball blocks).
        if clear || self.blocks().is_none() {
            jx.fill(0.0);
        }
        jm.fill(0.0);
        wx.fill(0.0);
        wm.fill(0.0);
        auxs.copy_from_slice(aux);
        // The balls' race parts at `x` are kept for the cage and ball columns.
        let tot0 = match kept {
            Some((dk, tk)) => {
                d0.copy_from_slice(dk);
                *tk
            }
            None => self.eval_with(m, x, auxs, d0, Races::Keep)?,
        };
        let step = |xv: f64| 1.5e-8 * xv.abs().max(1.0);
        if load {
            // Ring columns: displacements and velocities (steps as the outputs' K and C).
            for c in 0..10 {
                let mut mp = *m;
                let h = match c {
                    0..=2 => 1e-10,
                    3 | 4 => 1e-8,
                    5..=7 => 1e-6,
                    _ => 1e-4,
                };
                if c < 5 {
                    mp.q[c] += h;
                } else {
                    mp.v[c - 5] += h;
                }
                auxs.copy_from_slice(aux);
                let t = self.eval_with(&mp, x, auxs, col, Races::Ring { moved: c < 5 })?;
                for r in 0..n {
                    jm[r * 10 + c] = (col[r] - d0[r]) / h;
                }
                for r in 0..5 {
                    wm[r * 10 + c] = (t.wrench[r] - tot0.wrench[r]) / h;
                }
            }
        }
        // Cage columns: the cage reaches the balls only through the pockets (the race
        // parts, with the positions solved, are the kept ones).
        xs.copy_from_slice(x);
        for c in 0..self.nc {
            let h = step(x[c]);
            xs[c] = x[c] + h;
            let t = self.eval_with(m, xs, auxs, col, Races::Kept)?;
            for r in 0..n {
                jx[r * n + c] = (col[r] - d0[r]) / h;
            }
            if load {
                for r in 0..5 {
                    wx[r * n + c] = (t.wrench[r] - tot0.wrench[r]) / h;
                }
            }
            xs[c] = x[c];
        }
        // Ball columns: ball j's rates and the cage's.
        // The base: the terms of the evaluation at `x`, kept with its race parts.
        let ck = self.cage_kin(x);
        self.pocket_trig(ck.theta);
        let nb = self.nb;
        let qs = self.p.ball_contacts == BallContacts::QuasiStatic;
        for j in 0..self.z {
            let k = self.nc + nb * j;
            let xrel = self.races[j].xrel;
            let base = self.terms[j];
            let mut r0 = [0.0; 9];
            self.ball_rates(&base, &x[k..k + nb], &mut r0[..nb]);
            for c in 0..nb {
                let h = step(x[k + c]);
                let mut xb = [0.0; 9];
                xb[..nb].copy_from_slice(&x[k..k + nb]);
                xb[c] += h;
                if qs {
                    // Warm start: the position at `x`.
                    auxs[3 * j..3 * j + 3].copy_from_slice(&[xrel[0], xrel[1], 1.0]);
                }
                // The quasi-static position depends on the orbital angle and speed
                // (states 0 and 1), not on the spin: the spin columns keep it.
                // They keep its frame, contacts and contact states too. A dynamic ball's
                // velocity columns (3 to 5) keep its contacts (its position and orbital
                // angle are held), its spin columns (6 to 8) its frame too.
                let race = if c >= if qs { 2 } else { 3 } {
                    let (bk, xrel, _) = self.ball_kin_at(j, &m.q, &xb[..nb], auxs, false)?;
                    let kr = &self.races[j];
                    let known = if !qs && c < 6 {
                        Known::Contacts(kr)
                    } else {
                        Known::Kept(kr)
                    };
                    self.ball_race(m, &bk, xrel, known)
                } else {
                    self.ball_race_at(j, m, &xb[..nb], auxs, true)?
                };
                let bt = self.ball_cage(&ck, self.pocket_sc[j], &race);
                let mut r1 = [0.0; 9];
                self.ball_rates(&bt, &xb[..nb], &mut r1[..nb]);
                for r in 0..nb {
                    jx[(k + r) * n + k + c] = (r1[r] - r0[r]) / h;
                }
                let mut dc = [0.0; 12];
                self.cage_rates_from(
                    sub(bt.cage_f, base.cage_f),
                    sub(bt.cage_m, base.cage_m),
                    &mut dc[..self.nc],
                );
                for (r, dcr) in dc.iter().enumerate().take(self.nc) {
                    jx[r * n + k + c] = dcr / h;
                }
                if load {
                    for r in 0..5 {
                        wx[r * n + k + c] = (bt.wrench[r] - base.wrench[r]) / h;
                    }
                }
            }
        }
        Ok(())
    }
}
