//! Damped Newton for the small nonlinear systems of the bearing models (a ball's two
//! equilibrium equations, a ring's five), and a safeguarded scalar Newton on a bracket.
//!
//! [`solve`] is Newton's method with a back-tracking line search on the residual norm
//! (Dennis & Schnabel, *Numerical Methods for Unconstrained Optimization and Nonlinear
//! Equations*, SIAM 1996, §6.3, Algorithm A6.3.1 with step halving): from `x`, the step
//! `dx` solves `J dx = -r`; the trial `x + t dx` (`t = 1, 1/2, 1/4, …`) is accepted when
//! its residual norm is at most `(1 - armijo t)` times the current one (Armijo's sufficient
//! decrease; `armijo = 0` accepts any decrease). Options are plain data ([`Options`]):
//! iteration and halving limits, the sufficient-decrease constant, a cap on the step, the
//! unknowns' scales, the dead-zone bisection and Jacobian reuse.
//!
//! What is left to the system ([`NewtonSystem`]):
//!
//! - **The norm and its tolerance, per point.** Each evaluation returns a [`Check`]: the
//!   residual norm and the tolerance on it at that point. A relative tolerance times a force
//!   scale, plus a rounding floor (the contact stiffness times the rounding of the positions
//!   it differences), is how a nearly unloaded ball is not asked for a residual below what
//!   its forces can resolve (the rounding-aware acceptance of the full level).
//! - **The linear solve**, from the Jacobian of its last [`NewtonSystem::linearise`]: a
//!   closed-form 2×2 ([`solve2`]) for a ball, a Levenberg–Marquardt-regularised LU
//!   ([`solve_regularised`]) for a ring whose directions may carry no stiffness.
//! - **Transactional state**: a trial evaluation may touch the system's warm-start state
//!   (the balls' positions inside a ring solve); [`NewtonSystem::accept`] commits it.
//!
//! Warm start: `x` on entry is the start (the caller's previous answer or a prediction);
//! with [`Options::warm_start`] it is first checked with a residual evaluation alone, and
//! a start that already passes costs no Jacobian.
//! Jacobian reuse ([`Options::reuse_jacobian`], the modified or simplified Newton method,
//! Dennis & Schnabel §6.5 / Kelley, *Solving Nonlinear Equations with Newton's Method*, SIAM
//! 2003, §2.3 "the chord method"): after a full step that contracted the residual by at
//! least [`REUSE_CONTRACTION`] the next step reuses the Jacobian; a step that then fails the
//! line search is retried with a fresh Jacobian, so reuse changes the cost, never the
//! answer's tolerance.
//!
//! [`solve_to_rounding`] is the same damped Newton with the other stopping rule: it ends
//! when the *update* is below what the system can resolve ([`Linearised::resolution`]),
//! not on a residual tolerance (Kelley 2003, §1.5: the step is the error estimate of a
//! quadratically converging iteration; Dennis & Schnabel §7.2, the step-size test). The
//! answer then depends on the start only through rounding, which is what a right-hand
//! side needs (the quasi-static ball: the integrator's error estimate and its
//! finite-difference Jacobian must not see the warm start). A residual tolerance remains
//! only as the fallback acceptance when the update stagnates at the rounding floor.

/// Contraction `|r_new| / |r_old|` below which a reused Jacobian is kept for the next step
/// (a chord iteration converging at least linearly with rate 1/4).
pub const REUSE_CONTRACTION: f64 = 0.25;

/// Settings of one [`solve`], plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options<const N: usize> {
    /// Newton steps allowed (a solve that reaches it without convergence reports
    /// [`Outcome::MaxIterations`]).
    pub max_iterations: usize,
    /// Step halvings per line search before it gives up ([`Outcome::LineSearch`]).
    pub max_halvings: usize,
    /// Sufficient-decrease constant `c` of the line search: accept `|r(x + t dx)| <= (1 - c
    /// t) |r(x)|` (`0`: any strict decrease).
    pub armijo: f64,
    /// Largest component of a step in scaled units (the whole step is shortened to it);
    /// `f64::INFINITY`: no cap.
    pub max_step: f64,
    /// Scale of each unknown: the linear solve works in `x_i scale_i` (the step `dx_i` it
    /// returns is applied as `x_i += t dx_i / scale_i`).
    pub scale: [f64; N],
    /// Bisections allowed in a dead zone (0: none). When a trial's residual equals the
    /// current one exactly (nothing engaged along the step, e.g. a ring crossing its
    /// clearance before the contacts rise), the band where the residual starts to fall lies
    /// between this step and the last one that overshot, narrower than a halving: it is
    /// bisected (residual unchanged: further, larger: back) and the line search ends there.
    /// When the full step itself ends in the dead zone, the step is doubled (as many times)
    /// until the residual changes, then bisected the same way.
    pub dead_zone_bisections: usize,
    /// Reuse the Jacobian after a well-contracting full step (modified Newton).
    pub reuse_jacobian: bool,
    /// The start is likely the answer already (the previous step's solution, or a
    /// prediction from it): check it with a residual evaluation before paying for a
    /// Jacobian, and return it when it passes (no [`NewtonSystem::linearise`] at all).
    pub warm_start: bool,
}

impl<const N: usize> Default for Options<N> {
    fn default() -> Self {
        Options {
            max_iterations: 60,
            max_halvings: 30,
            armijo: 1e-4,
            max_step: f64::INFINITY,
            scale: [1.0; N],
            dead_zone_bisections: 0,
            reuse_jacobian: false,
            warm_start: false,
        }
    }
}

/// The residual norm at a point and the tolerance on it there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Check {
    /// Residual norm (`f64::INFINITY` when the residual is not finite).
    pub norm: f64,
    /// Converged when `norm <= tol`.
    pub tol: f64,
}

impl Check {
    /// A non-finite residual never converges, even against a tolerance that overflowed
    /// with it (`inf <= inf`).
    fn converged(&self) -> bool {
        self.norm.is_finite() && self.norm <= self.tol
    }
}

/// A nonlinear system `r(x) = 0` in `N` unknowns, as [`solve`] drives it.
pub trait NewtonSystem<const N: usize> {
    /// Error of an evaluation.
    type Error;

    /// Evaluate the residual at a trial point. An error refuses the point (the line search
    /// halves the step).
    fn residual(&mut self, x: &[f64; N]) -> Result<Check, Self::Error>;

    /// Evaluate the residual and the Jacobian at the current point `x` (the start or the
    /// last accepted trial; the system may return what it kept from that trial). An error
    /// ends the solve with it.
    fn linearise(&mut self, x: &[f64; N]) -> Result<Check, Self::Error>;

    /// The Newton step `dx` (scaled, [`Options::scale`]) solving `J dx = -r` with the
    /// Jacobian of the last [`Self::linearise`] and the residual at the current point;
    /// `false` when singular.
    fn step(&mut self, dx: &mut [f64; N]) -> bool;

    /// The last trial point became the current point (commit what its evaluation left).
    fn accept(&mut self) {}
}

/// How a solve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The residual norm is within the tolerance.
    Converged,
    /// The linear solve failed (singular Jacobian).
    Singular,
    /// No step length decreased the residual enough.
    LineSearch,
    /// [`Options::max_iterations`] steps without convergence.
    MaxIterations,
}

/// What a solve did: how it ended, where (the residual at the final `x`) and its work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Report {
    /// How it ended.
    pub outcome: Outcome,
    /// Newton steps taken (accepted).
    pub iterations: usize,
    /// Residual norm and tolerance at the final `x`.
    pub check: Check,
    /// Residual evaluations at trial points.
    pub residuals: usize,
    /// Jacobian evaluations ([`NewtonSystem::linearise`]).
    pub jacobians: usize,
}

impl Report {
    /// Converged?
    pub fn converged(&self) -> bool {
        self.outcome == Outcome::Converged
    }
}

/// Damped Newton from `x` (the warm start) towards `r(x) = 0`. On return `x` is the last
/// accepted point (the answer when [`Report::outcome`] is [`Outcome::Converged`]). Only an
/// error of [`NewtonSystem::linearise`] is an `Err`; a solve that does not converge reports
/// why in [`Report::outcome`] and leaves the caller to restart or refuse.
pub fn solve<const N: usize, S: NewtonSystem<N> + ?Sized>(
    sys: &mut S,
    x: &mut [f64; N],
    opts: &Options<N>,
) -> Result<Report, S::Error> {
    if opts.warm_start {
        if let Ok(c) = sys.residual(x) {
            if c.converged() {
                sys.accept();
                return Ok(Report {
                    outcome: Outcome::Converged,
                    iterations: 0,
                    check: c,
                    residuals: 1,
                    jacobians: 0,
                });
            }
        }
    }
    let mut rep = Report {
        outcome: Outcome::Converged,
        iterations: 0,
        check: sys.linearise(x)?,
        residuals: 0,
        jacobians: 1,
    };
    // The Jacobian is from an earlier point than `x` (modified Newton).
    let mut stale = false;
    let mut dx = [0.0; N];
    loop {
        if rep.check.converged() {
            rep.outcome = Outcome::Converged;
            return Ok(rep);
        }
        if rep.iterations >= opts.max_iterations {
            rep.outcome = Outcome::MaxIterations;
            return Ok(rep);
        }
        if !sys.step(&mut dx) {
            if stale {
                rep.check = sys.linearise(x)?;
                rep.jacobians += 1;
                stale = false;
                continue;
            }
            rep.outcome = Outcome::Singular;
            return Ok(rep);
        }
        let big = dx.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if big > opts.max_step {
            let f = opts.max_step / big;
            dx.iter_mut().for_each(|v| *v *= f);
        }
        let trial_at =
            |t: f64| -> [f64; N] { std::array::from_fn(|i| x[i] + t * dx[i] / opts.scale[i]) };
        let r0 = rep.check.norm;
        let mut t = 1.0;
        // The last step length that overshot (residual up), for the dead-zone bisection.
        let mut over = None;
        let mut accepted = None;
        for _ in 0..opts.max_halvings {
            let trial = trial_at(t);
            rep.residuals += 1;
            if let Ok(c) = sys.residual(&trial) {
                // From a non-finite start (`r0 = inf`) a non-finite trial is no decrease
                // (`inf <= inf`); from a finite one nothing below changes.
                if opts.dead_zone_bisections > 0 && c.norm == r0 && r0.is_finite() {
                    // The full step ends inside the dead zone (nothing overshot yet: a
                    // small residual's step shorter than the clearance): the band lies
                    // beyond it. Double the step until the residual changes: lower is
                    // accepted, higher (or refused) is the overshoot the bisection needs.
                    if over.is_none() {
                        for _ in 0..opts.dead_zone_bisections {
                            let far = 2.0 * t;
                            let trial = trial_at(far);
                            rep.residuals += 1;
                            match sys.residual(&trial) {
                                Ok(c) if c.norm < r0 => {
                                    accepted = Some((trial, c, far));
                                    break;
                                }
                                Ok(c) if c.norm == r0 => t = far,
                                _ => {
                                    over = Some(far);
                                    break;
                                }
                            }
                        }
                    }
                    if let (None, Some(mut hi)) = (accepted, over) {
                        let mut lo = t;
                        for _ in 0..opts.dead_zone_bisections {
                            let mid = 0.5 * (lo + hi);
                            let trial = trial_at(mid);
                            rep.residuals += 1;
                            match sys.residual(&trial) {
                                Ok(c) if c.norm < r0 => {
                                    accepted = Some((trial, c, mid));
                                    break;
                                }
                                Ok(c) if c.norm == r0 => lo = mid,
                                _ => hi = mid,
                            }
                        }
                    }
                    break;
                }
                if c.norm.is_finite() && c.norm <= (1.0 - opts.armijo * t) * r0 {
                    accepted = Some((trial, c, t));
                    break;
                }
                over = Some(t);
            }
            t *= 0.5;
        }
        let Some((trial, c, t)) = accepted else {
            if stale {
                rep.check = sys.linearise(x)?;
                rep.jacobians += 1;
                stale = false;
                continue;
            }
            rep.outcome = Outcome::LineSearch;
            return Ok(rep);
        };
        sys.accept();
        *x = trial;
        rep.iterations += 1;
        if c.converged() {
            rep.check = c;
            rep.outcome = Outcome::Converged;
            return Ok(rep);
        }
        if opts.reuse_jacobian && t == 1.0 && c.norm <= REUSE_CONTRACTION * r0 {
            rep.check = c;
            stale = true;
        } else {
            rep.check = sys.linearise(x)?;
            rep.jacobians += 1;
            stale = false;
        }
    }
}

/// An evaluation of a system at a point, as [`solve_to_rounding`] reads it: the residual
/// norm, the Newton step from its Jacobian and the update size it can resolve.
pub trait Linearised<const N: usize> {
    /// Residual norm (`f64::INFINITY` when not finite: the solve fails there).
    fn norm(&self) -> f64;
    /// The scale the fallback tolerance is relative to ([`RoundingOptions::rtol`]).
    fn scale(&self) -> f64;
    /// The Newton step `dx` solving `J dx = -r` here; `None` when singular.
    fn step(&self) -> Option<[f64; N]>;
    /// Update below which `x + dx` is the root to rounding (`x`: this evaluation's point).
    fn resolution(&self, x: &[f64; N]) -> f64;
}

/// A system `r(x) = 0` solved to rounding by [`solve_to_rounding`]: the evaluations are
/// values (no state), and an optional richer evaluation (`Final`) serves a step predicted
/// to land on the root, so the caller gets what it wants at the answer (e.g. more
/// derivatives) without evaluating there again.
pub trait RoundingSystem<const N: usize> {
    /// The evaluation the iteration runs on.
    type Eval: Linearised<N>;
    /// The richer evaluation of a step predicted final.
    type Final: Linearised<N>;
    /// Evaluate at `x`.
    fn eval(&self, x: &[f64; N]) -> Self::Eval;
    /// Evaluate at `x` with everything the caller wants at the answer.
    fn eval_final(&self, x: &[f64; N]) -> Self::Final;
    /// Is the full step of size `step` from `e` predicted to land within `resolution` of
    /// the root (then it is evaluated with [`Self::eval_final`])? `false`: never.
    fn predicts_root(&self, e: &Self::Eval, step: f64, resolution: f64) -> bool;
}

/// Settings of one [`solve_to_rounding`], plain data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoundingOptions {
    /// Newton steps allowed.
    pub max_iterations: usize,
    /// Step halvings per line search.
    pub max_halvings: usize,
    /// Sufficient-decrease constant of the line search (as [`Options::armijo`]).
    pub armijo: f64,
    /// Fallback acceptance: a point whose residual is at most `rtol` times its
    /// [`Linearised::scale`] plus `atol` is accepted when the update stagnates (it no
    /// longer halves), the line search fails, the Jacobian is singular or the iterations
    /// run out.
    pub rtol: f64,
    /// Absolute part of the fallback tolerance.
    pub atol: f64,
}

/// The evaluation a [`solve_to_rounding`] ended on.
#[derive(Debug, Clone, Copy)]
pub enum Last<E, F> {
    /// The iteration's own evaluation.
    Plain(E),
    /// The richer evaluation of a step predicted final (and confirmed).
    Final(F),
}

/// What a [`solve_to_rounding`] found: the last point, the update there (the root is their
/// sum to rounding) and the evaluation at the last point.
pub type Answer<const N: usize, S> = (
    [f64; N],
    [f64; N],
    Last<<S as RoundingSystem<N>>::Eval, <S as RoundingSystem<N>>::Final>,
);

/// A [`solve_to_rounding`] that found no answer: Newton steps taken and the residual norm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Failure {
    /// Newton steps taken.
    pub iterations: usize,
    /// Residual norm where it stopped.
    pub residual: f64,
}

/// Damped Newton from `x` that stops on the size of its update (see the module notes):
/// returns the last point `x`, the update `dx` there (the root is `x + dx` to rounding;
/// zero when the fallback tolerance accepted `x` itself) and the evaluation at `x`.
///
/// Each iteration: the step from the evaluation at `x`; if it is at most the evaluation's
/// [`Linearised::resolution`], the answer is `x + dx`. Otherwise, when the system
/// [predicts](RoundingSystem::predicts_root) the full step lands on the root, that point is
/// evaluated with [`RoundingSystem::eval_final`]: if it decreases the residual and its own
/// update is within its resolution, the solve ends there; if it only decreases the
/// residual, the iteration goes on from it. Otherwise a back-tracking line search (`t = 1,
/// 1/2, …`, Armijo) on the residual norm.
#[inline]
pub fn solve_to_rounding<const N: usize, S: RoundingSystem<N>>(
    sys: &S,
    mut x: [f64; N],
    opts: &RoundingOptions,
) -> Result<Answer<N, S>, Failure> {
    let mut e = sys.eval(&x);
    // The last accepted update's size (for the stagnation test).
    let mut last = f64::INFINITY;
    let mut it = 0;
    let fail = |iterations, residual| Failure {
        iterations,
        residual,
    };
    let big = |d: &[f64; N]| d.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    loop {
        let norm = e.norm();
        if !norm.is_finite() {
            return Err(fail(it, norm));
        }
        let ok = norm <= opts.rtol * e.scale() + opts.atol;
        // Accept `x` itself on the fallback tolerance (the update is not applied: it may
        // be the step the line search refused), or fail.
        let fallback = move |e| {
            if ok {
                Ok((x, [0.0; N], Last::Plain(e)))
            } else {
                Err(fail(it, norm))
            }
        };
        let Some(dx) = e.step() else {
            return fallback(e);
        };
        let step = big(&dx);
        if !step.is_finite() {
            return Err(fail(it, norm));
        }
        let tiny = e.resolution(&x);
        if step <= tiny {
            return Ok((x, dx, Last::Plain(e)));
        }
        if (ok && step > 0.5 * last) || it >= opts.max_iterations {
            return fallback(e);
        }
        let full: [f64; N] = std::array::from_fn(|i| x[i] + dx[i]);
        if sys.predicts_root(&e, step, tiny) {
            let ef = sys.eval_final(&full);
            if ef.norm() <= (1.0 - opts.armijo) * norm {
                if let Some(df) = ef.step() {
                    if big(&df) <= ef.resolution(&full) {
                        return Ok((full, df, Last::Final(ef)));
                    }
                }
                // Not there yet after all: go on from the accepted step.
                x = full;
                e = sys.eval(&x);
                last = step;
                it += 1;
                continue;
            }
        }
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..opts.max_halvings {
            let xt: [f64; N] = std::array::from_fn(|i| x[i] + t * dx[i]);
            let et = sys.eval(&xt);
            if et.norm() <= (1.0 - opts.armijo * t) * norm {
                x = xt;
                e = et;
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        if !accepted {
            return fallback(e);
        }
        last = t * step;
        it += 1;
    }
}

/// Solve the 2×2 system `j x = r` in closed form; `None` when the determinant is not finite
/// or not above `rel` times the product of the rows' 1-norms (`rel = 0`: any non-zero
/// determinant).
#[inline]
pub fn solve2(j: &[[f64; 2]; 2], r: [f64; 2], rel: f64) -> Option<[f64; 2]> {
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let scale = (j[0][0].abs() + j[0][1].abs()) * (j[1][0].abs() + j[1][1].abs());
    if !(det.is_finite() && det.abs() > rel * scale && scale > 0.0) {
        return None;
    }
    Some([
        (j[1][1] * r[0] - j[0][1] * r[1]) / det,
        (j[0][0] * r[1] - j[1][0] * r[0]) / det,
    ])
}

/// Solve `(k + mu I) x = r` for a stiffness-like `k` (symmetric positive semi-definite up
/// to the gyroscopic and friction terms), regularised Levenberg–Marquardt fashion where a
/// direction has no stiffness: `mu = rel max|k_ii| + f64::MIN_POSITIVE`, raised (×1e3, at
/// least `1e-9 max|k_ii|`) up to `tries` times while the LU fails or gives a non-finite
/// answer. A direction with neither stiffness nor residual stays where it is.
pub fn solve_regularised<const N: usize>(
    k: &[[f64; N]; N],
    r: &[f64; N],
    rel: f64,
    tries: usize,
) -> Option<[f64; N]>
where
    nalgebra::Const<N>: nalgebra::DimMin<nalgebra::Const<N>, Output = nalgebra::Const<N>>,
{
    let ks = nalgebra::SMatrix::<f64, N, N>::from_fn(|i, j| k[i][j]);
    let dmax = (0..N).map(|i| ks[(i, i)].abs()).fold(0.0, f64::max);
    let mut mu = rel * dmax + f64::MIN_POSITIVE;
    let rv = nalgebra::SVector::<f64, N>::from_column_slice(r);
    for _ in 0..tries {
        let a = ks + nalgebra::SMatrix::<f64, N, N>::identity() * mu;
        if let Some(x) = a.lu().solve(&rv) {
            if x.iter().all(|v| v.is_finite()) {
                return Some(std::array::from_fn(|i| x[i]));
            }
        }
        mu = (mu * 1e3).max(1e-9 * dmax);
    }
    None
}

/// Safeguarded Newton for a scalar `g(x) = 0` with `g` increasing on the bracket `[lo, hi]`
/// (`g(lo) <= 0 <= g(hi)`), from `x` (Press et al., *Numerical Recipes* 3rd ed., §9.4,
/// `rtsafe`): `g` returns `(g(x), g'(x))`; each evaluation narrows the bracket; a Newton
/// step that leaves the bracket (or a non-positive slope) is replaced by bisection. Stops
/// when the step or the bracket is at most `tol`, or a Newton step is at most `tol_newton`
/// (quadratic convergence: the error left is of order its square over the scale), or after
/// `max_iterations`; returns the last point.
#[inline]
pub fn bracketed(
    mut g: impl FnMut(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    mut x: f64,
    tol: f64,
    tol_newton: f64,
    max_iterations: usize,
) -> f64 {
    for _ in 0..max_iterations {
        let (r, dr) = g(x);
        if r > 0.0 {
            hi = x;
        } else {
            lo = x;
        }
        let mut newton = dr > 0.0;
        let mut xn = if newton { x - r / dr } else { 0.5 * (lo + hi) };
        if !(xn > lo && xn < hi) {
            xn = 0.5 * (lo + hi);
            newton = false;
        }
        let step = (xn - x).abs();
        if step <= tol || hi - lo <= tol || (newton && step <= tol_newton) {
            return xn;
        }
        x = xn;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A two-equation test system from its residual and Jacobian functions.
    struct Sys {
        f: fn(&[f64; 2]) -> [f64; 2],
        jac: fn(&[f64; 2]) -> [[f64; 2]; 2],
        x: [f64; 2],
        trial: [f64; 2],
        j: [[f64; 2]; 2],
        linearisations: usize,
    }

    fn sys(f: fn(&[f64; 2]) -> [f64; 2], jac: fn(&[f64; 2]) -> [[f64; 2]; 2]) -> Sys {
        Sys {
            f,
            jac,
            x: [0.0; 2],
            trial: [0.0; 2],
            j: [[0.0; 2]; 2],
            linearisations: 0,
        }
    }

    impl Sys {
        fn check(&self, x: &[f64; 2]) -> Check {
            let v = (self.f)(x);
            Check {
                norm: v[0].hypot(v[1]),
                tol: 1e-12,
            }
        }
    }

    impl NewtonSystem<2> for Sys {
        type Error = ();
        fn residual(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
            self.trial = *x;
            Ok(self.check(x))
        }
        fn linearise(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
            self.linearisations += 1;
            self.x = *x;
            self.j = (self.jac)(x);
            Ok(self.check(x))
        }
        fn step(&mut self, dx: &mut [f64; 2]) -> bool {
            let v = (self.f)(&self.x);
            match solve2(&self.j, [-v[0], -v[1]], 0.0) {
                Some(d) => {
                    *dx = d;
                    true
                }
                None => false,
            }
        }
        fn accept(&mut self) {
            self.x = self.trial;
        }
    }

    /// Dennis & Schnabel's scaled Rosenbrock system `r = (10 (x1 - x0²), 1 - x0)`, root
    /// (1, 1): from the classic start (-1.2, 1) a full step overshoots and the line search
    /// must damp it.
    fn rosenbrock() -> Sys {
        sys(
            |x| [10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]],
            |x| [[-20.0 * x[0], 10.0], [-1.0, 0.0]],
        )
    }

    /// A circle and a line, `x0² + x1² = 4`, `x0 = x1`: root (√2, √2).
    fn circle() -> Sys {
        sys(
            |x| [x[0] * x[0] + x[1] * x[1] - 4.0, x[0] - x[1]],
            |x| [[2.0 * x[0], 2.0 * x[1]], [1.0, -1.0]],
        )
    }

    /// `x = (1, 1)` whose residual and tolerance both overflow for `|x0| > 1e3` (a
    /// tolerance scaled by a force that overflowed with the residual).
    struct Overflowing {
        x: [f64; 2],
    }

    impl Overflowing {
        fn check(x: &[f64; 2]) -> Check {
            if x[0].abs() > 1e3 {
                Check {
                    norm: f64::INFINITY,
                    tol: f64::INFINITY,
                }
            } else {
                Check {
                    norm: (x[0] - 1.0).hypot(x[1] - 1.0),
                    tol: 1e-12,
                }
            }
        }
    }

    impl NewtonSystem<2> for Overflowing {
        type Error = ();
        fn residual(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
            Ok(Self::check(x))
        }
        fn linearise(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
            self.x = *x;
            Ok(Self::check(x))
        }
        fn step(&mut self, dx: &mut [f64; 2]) -> bool {
            *dx = [1.0 - self.x[0], 1.0 - self.x[1]];
            true
        }
        fn accept(&mut self) {}
    }

    /// An overflowing start is not an answer (`inf <= inf` is no convergence), and an
    /// overflowing trial is no decrease from it: the solve leaves the start for the root.
    #[test]
    fn an_overflowing_point_is_neither_converged_nor_accepted() {
        let opts = Options {
            max_step: f64::INFINITY,
            ..Options::default()
        };
        let mut x = [1e6, 0.0];
        let rep = solve(&mut Overflowing { x }, &mut x, &opts).unwrap();
        assert!(rep.converged(), "{rep:?}");
        assert_eq!(x, [1.0, 1.0]);
        // From the same start, a step that lands on another overflowing point is refused.
        struct Stuck(Overflowing);
        impl NewtonSystem<2> for Stuck {
            type Error = ();
            fn residual(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
                self.0.residual(x)
            }
            fn linearise(&mut self, x: &[f64; 2]) -> Result<Check, ()> {
                self.0.linearise(x)
            }
            fn step(&mut self, dx: &mut [f64; 2]) -> bool {
                *dx = [1e6, 0.0];
                true
            }
            fn accept(&mut self) {}
        }
        let mut x = [1e6, 0.0];
        let rep = solve(&mut Stuck(Overflowing { x }), &mut x, &opts).unwrap();
        assert!(!rep.converged(), "{rep:?}");
        assert_eq!(x, [1e6, 0.0]);
    }

    #[test]
    fn damped_newton_finds_the_root_and_counts_its_work() {
        let mut s = rosenbrock();
        let mut x = [-1.2, 1.0];
        let rep = solve(&mut s, &mut x, &Options::default()).unwrap();
        assert!(rep.converged(), "{rep:?}");
        assert!(
            (x[0] - 1.0).abs() < 1e-12 && (x[1] - 1.0).abs() < 1e-12,
            "{x:?}"
        );
        assert_eq!(rep.jacobians, s.linearisations);
        assert!(rep.residuals >= rep.iterations);
    }

    #[test]
    fn jacobian_reuse_reaches_the_same_root_with_fewer_jacobians() {
        let opts = Options::default();
        let mut full = circle();
        let mut x_full = [3.0, 1.0];
        let a = solve(&mut full, &mut x_full, &opts).unwrap();
        let mut chord = circle();
        let mut x_chord = [3.0, 1.0];
        let reuse = Options {
            reuse_jacobian: true,
            ..opts
        };
        let b = solve(&mut chord, &mut x_chord, &reuse).unwrap();
        assert!(a.converged() && b.converged(), "{a:?} {b:?}");
        let r2 = 2f64.sqrt();
        for x in [x_full, x_chord] {
            assert!(
                (x[0] - r2).abs() < 1e-12 && (x[1] - r2).abs() < 1e-12,
                "{x:?}"
            );
        }
        assert!(b.jacobians < a.jacobians, "{a:?} {b:?}");
    }

    #[test]
    fn a_converged_warm_start_costs_one_residual_and_no_jacobian() {
        let r2 = 2f64.sqrt();
        let warm = Options {
            warm_start: true,
            ..Options::default()
        };
        let mut c = circle();
        let mut x = [r2, r2];
        let rep = solve(&mut c, &mut x, &warm).unwrap();
        assert!(rep.converged() && x == [r2, r2], "{rep:?}");
        assert_eq!((rep.residuals, rep.jacobians, c.linearisations), (1, 0, 0));
        // A start that does not pass goes on as a plain solve.
        let mut x = [3.0, 1.0];
        let rep = solve(&mut c, &mut x, &warm).unwrap();
        assert!(rep.converged() && rep.jacobians > 0 && (x[0] - r2).abs() < 1e-12);
    }

    #[test]
    fn iteration_limit_and_singular_jacobian_are_reported() {
        let mut s = rosenbrock();
        let mut x = [-1.2, 1.0];
        let few = Options {
            max_iterations: 1,
            ..Options::default()
        };
        let rep = solve(&mut s, &mut x, &few).unwrap();
        assert_eq!((rep.outcome, rep.iterations), (Outcome::MaxIterations, 1));
        // At the circle's centre the Jacobian [[0, 0], [1, -1]] is singular.
        let mut c = circle();
        let rep = solve(&mut c, &mut [0.0, 0.0], &Options::default()).unwrap();
        assert_eq!((rep.outcome, rep.iterations), (Outcome::Singular, 0));
        // No stiffness and no residual along x0: it stays; x1 = 8 / 4 (to the
        // regularisation mu = 1e-12 max k_ii, relative).
        let k = [[0.0, 0.0], [0.0, 4.0]];
        let d = solve_regularised(&k, &[0.0, 8.0], 1e-12, 8).unwrap();
        assert!(d[0] == 0.0 && (d[1] - 2.0).abs() < 1e-11, "{d:?}");
    }

    #[test]
    fn bracketed_newton_finds_a_cube_root_inside_its_bracket() {
        let x = bracketed(
            |x| (x * x * x - 2.0, 3.0 * x * x),
            0.0,
            2.0,
            0.1,
            1e-15,
            1e-9,
            60,
        );
        assert!((x - 2f64.cbrt()).abs() < 1e-14, "{x}");
    }

    /// `r(x) = (x0² - 2, x1 - x0)`, root `(√2, √2)`, evaluated as a value; `rich` marks
    /// the final evaluation, `wide` counts how many were made.
    #[derive(Debug, Clone, Copy)]
    struct Sq {
        x: [f64; 2],
        rich: bool,
    }

    impl Linearised<2> for Sq {
        fn norm(&self) -> f64 {
            let r = [self.x[0] * self.x[0] - 2.0, self.x[1] - self.x[0]];
            r[0].hypot(r[1])
        }
        fn scale(&self) -> f64 {
            2.0
        }
        fn step(&self) -> Option<[f64; 2]> {
            let [a, b] = self.x;
            let j = [[2.0 * a, 0.0], [-1.0, 1.0]];
            solve2(&j, [-(a * a - 2.0), -(b - a)], 0.0)
        }
        fn resolution(&self, x: &[f64; 2]) -> f64 {
            f64::EPSILON.sqrt() * 0.125 * x[0].abs().max(x[1].abs())
        }
    }

    struct SqSystem {
        predict: bool,
        wide: std::cell::Cell<usize>,
    }

    impl RoundingSystem<2> for SqSystem {
        type Eval = Sq;
        type Final = Sq;
        fn eval(&self, x: &[f64; 2]) -> Sq {
            Sq { x: *x, rich: false }
        }
        fn eval_final(&self, x: &[f64; 2]) -> Sq {
            self.wide.set(self.wide.get() + 1);
            Sq { x: *x, rich: true }
        }
        fn predicts_root(&self, _: &Sq, step: f64, resolution: f64) -> bool {
            self.predict && step * step <= resolution
        }
    }

    #[test]
    fn newton_to_rounding_gives_the_root_to_rounding_from_any_start() {
        let opts = RoundingOptions {
            max_iterations: 60,
            max_halvings: 40,
            armijo: 1e-4,
            rtol: 1e-12,
            atol: 0.0,
        };
        let root = 2f64.sqrt();
        for predict in [false, true] {
            let mut answers = Vec::new();
            for start in [[1.0, 0.0], [3.0, 5.0], [40.0, -7.0], [root, root]] {
                let sys = SqSystem {
                    predict,
                    wide: std::cell::Cell::new(0),
                };
                let (x, dx, last) = solve_to_rounding(&sys, start, &opts).unwrap();
                let ans = [x[0] + dx[0], x[1] + dx[1]];
                // The root to rounding (1 ulp of √2 is 2.2e-16), whatever the start.
                for v in ans {
                    assert!(
                        (v - root).abs() <= 2.0 * f64::EPSILON * root,
                        "{start:?} {ans:?}"
                    );
                }
                answers.push(ans);
                // The update it stopped on is within the resolution.
                assert!(dx[0].abs().max(dx[1].abs()) <= 1.5e-9 * root, "{dx:?}");
                // A step predicted final ends on the rich evaluation, and one rich
                // evaluation served it; without prediction none is made.
                match last {
                    Last::Final(e) => assert!(predict && e.rich && sys.wide.get() == 1),
                    Last::Plain(e) => assert!(!e.rich && (!predict || start == [root, root])),
                }
                if !predict {
                    assert_eq!(sys.wide.get(), 0);
                }
            }
            assert!(answers
                .windows(2)
                .all(|w| (w[0][0] - w[1][0]).abs() <= 4.5e-16));
        }
        // A residual that overflows fails with its iteration count, never an answer.
        let sys = SqSystem {
            predict: false,
            wide: std::cell::Cell::new(0),
        };
        let f = solve_to_rounding(&sys, [1e200, 0.0], &opts).unwrap_err();
        assert_eq!(f.iterations, 0);
        assert!(f.residual.is_infinite());
    }
}
