//! One attempted step: the stages of RODAS4 and of the W-method ROS34PW2 with their error
//! estimates, and what an accepted step keeps.

use super::*;

impl Rosenbrock {
    /// One step attempt from `(t, self.y)`: fills `ynew` and the error vector `u[5]`.
    pub(super) fn attempt<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        match self.method {
            RosMethod::Rodas4 => self.attempt_rodas4(sys, t, h),
            RosMethod::Ros34pw2 => self.attempt_w(sys, t, h),
        }
    }

    /// One W-method step attempt from `(t, self.y)` with the current `f0`, `J` (any
    /// approximation) and, if on, `∂f/∂t`; the LU is reused when it is for this `h`:
    ///
    /// ```text
    /// (I/(hγ) − J) u_i = f(t + c_i h, y + Σ_{j<i} a_ij u_j) + Σ_{j<i} (c_ij/h) u_j [+ h d_i ∂f/∂t]
    /// y_new = y + Σ m_i u_i,   error = Σ (m_i − m̂_i) u_i
    /// ```
    pub(super) fn attempt_w<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        let w = &self.w;
        // `!=` is also true for the NaN of "no LU".
        if self.lu_h != h {
            self.stats.lu_decomps += 1;
            if !self.solver.factor(1.0 / (h * w.gamma), &self.jac) {
                self.lu_h = f64::NAN;
                return Ok(Attempt::Singular);
            }
            self.lu_h = h;
        }
        let ih = 1.0 / h;
        let (y, ytmp, f0, dfdt) = (&self.y, &mut self.ytmp, &self.f0, &self.dfdt);
        let (stages, rest) = self.u.split_at_mut(W_STAGES);
        // The sums run over whole vectors, one stage `j` after the other (each component
        // gets its terms in the order of `j`, as a sum per component would give them).
        for i in 0..W_STAGES {
            let (done, cur) = stages.split_at_mut(i);
            let ui = &mut cur[0];
            if i == 0 {
                ui.copy_from_slice(f0);
            } else {
                ytmp.copy_from_slice(y);
                for (j, uj) in done.iter().enumerate() {
                    let a = w.a[i][j];
                    for (v, u) in ytmp.iter_mut().zip(uj) {
                        *v += a * u;
                    }
                }
                let ti = t + w.c[i] * h;
                if let Some(idx) = eval(sys, &mut self.stats, ti, ytmp, ui)? {
                    return Ok(Attempt::NonFinite(ti, idx));
                }
            }
            for (j, uj) in done.iter().enumerate() {
                let c = ih * w.cc[i][j];
                for (v, u) in ui.iter_mut().zip(uj) {
                    *v += c * u;
                }
            }
            if self.dfdt_on {
                let d = h * w.d[i];
                for (v, g) in ui.iter_mut().zip(dfdt) {
                    *v += d * g;
                }
            }
            self.solver.solve(ui);
        }
        let err = &mut rest[rest.len() - 1];
        self.ynew.copy_from_slice(y);
        err.fill(0.0);
        for (j, uj) in stages.iter().enumerate() {
            let (m, e) = (w.m[j], w.e[j]);
            for ((yn, er), u) in self.ynew.iter_mut().zip(err.iter_mut()).zip(uj) {
                *yn += m * u;
                *er += e * u;
            }
        }
        if let Some(i) = self.ynew.iter().position(|v| !v.is_finite()) {
            return Ok(Attempt::NonFinite(t + h, i));
        }
        Ok(Attempt::Done)
    }

    /// One RODAS4 step attempt from `(t, self.y)` with the current `f0`, `J`, `∂f/∂t`:
    /// fills `u[0..6]` and `ynew`.
    pub(super) fn attempt_rodas4<S: OdeSystem + ?Sized>(
        &mut self,
        sys: &mut S,
        t: f64,
        h: f64,
    ) -> Result<Attempt, SolverError> {
        let n = self.n;
        self.stats.lu_decomps += 1;
        if !self.solver.factor(1.0 / (h * GAMMA), &self.jac) {
            return Ok(Attempt::Singular);
        }
        let st = &mut self.stats;
        // Every vector cut to `n` once, so the stage loops run without bounds checks.
        let (y, ytmp, ftmp, f0, dfdt) = (
            &self.y[..n],
            &mut self.ytmp[..n],
            &mut self.ftmp[..n],
            &self.f0[..n],
            &self.dfdt[..n],
        );
        let [u1, u2, u3, u4, u5, u6] = &mut self.u;
        let (u1, u2, u3, u4, u5, u6) = (
            &mut u1[..n],
            &mut u2[..n],
            &mut u3[..n],
            &mut u4[..n],
            &mut u5[..n],
            &mut u6[..n],
        );
        let ynew = &mut self.ynew[..n];
        let solver = &mut self.solver;
        let ih = 1.0 / h;

        // stage 1
        for i in 0..n {
            u1[i] = f0[i] + h * D1 * dfdt[i];
        }
        solver.solve(u1);
        // stage 2
        for i in 0..n {
            ytmp[i] = y[i] + A21 * u1[i];
        }
        if let Some(i) = eval(sys, st, t + C2 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C2 * h, i));
        }
        for i in 0..n {
            u2[i] = ftmp[i] + h * D2 * dfdt[i] + ih * C21 * u1[i];
        }
        solver.solve(u2);
        // stage 3
        for i in 0..n {
            ytmp[i] = y[i] + A31 * u1[i] + A32 * u2[i];
        }
        if let Some(i) = eval(sys, st, t + C3 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C3 * h, i));
        }
        for i in 0..n {
            u3[i] = ftmp[i] + h * D3 * dfdt[i] + ih * (C31 * u1[i] + C32 * u2[i]);
        }
        solver.solve(u3);
        // stage 4
        for i in 0..n {
            ytmp[i] = y[i] + A41 * u1[i] + A42 * u2[i] + A43 * u3[i];
        }
        if let Some(i) = eval(sys, st, t + C4 * h, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(t + C4 * h, i));
        }
        for i in 0..n {
            u4[i] = ftmp[i] + h * D4 * dfdt[i] + ih * (C41 * u1[i] + C42 * u2[i] + C43 * u3[i]);
        }
        solver.solve(u4);
        // stage 5 (c5 = 1, d5 = 0)
        for i in 0..n {
            ytmp[i] = y[i] + A51 * u1[i] + A52 * u2[i] + A53 * u3[i] + A54 * u4[i];
        }
        let tph = t + h;
        if let Some(i) = eval(sys, st, tph, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(tph, i));
        }
        for i in 0..n {
            u5[i] = ftmp[i] + ih * (C51 * u1[i] + C52 * u2[i] + C53 * u3[i] + C54 * u4[i]);
        }
        solver.solve(u5);
        // stage 6 (stiffly accurate: its argument is the embedded solution)
        for i in 0..n {
            ytmp[i] += u5[i];
        }
        if let Some(i) = eval(sys, st, tph, ytmp, ftmp)? {
            return Ok(Attempt::NonFinite(tph, i));
        }
        for i in 0..n {
            u6[i] = ftmp[i]
                + ih * (C61 * u1[i] + C62 * u2[i] + C63 * u3[i] + C64 * u4[i] + C65 * u5[i]);
        }
        solver.solve(u6);
        for i in 0..n {
            ynew[i] = ytmp[i] + u6[i];
        }
        if let Some(i) = ynew.iter().position(|v| !v.is_finite()) {
            return Ok(Attempt::NonFinite(tph, i));
        }
        Ok(Attempt::Done)
    }

    /// Accept the attempted step `[t, t_new]`: dense output, new state.
    pub(super) fn accept(&mut self, t: f64, t_new: f64) {
        if self.method == RosMethod::Rodas4 {
            let [u1, u2, u3, u4, u5, _] = &self.u;
            for i in 0..self.n {
                self.kd1[i] = H21 * u1[i] + H22 * u2[i] + H23 * u3[i] + H24 * u4[i] + H25 * u5[i];
                self.kd2[i] = H31 * u1[i] + H32 * u2[i] + H33 * u3[i] + H34 * u4[i] + H35 * u5[i];
            }
        }
        std::mem::swap(&mut self.y_old, &mut self.y);
        self.y.copy_from_slice(&self.ynew);
        self.t_old = t;
        self.h_old = t_new - t;
        self.dense_valid = true;
        self.stats.accepted += 1;
    }
}
