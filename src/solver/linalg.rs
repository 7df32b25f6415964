//! Linear solves for the Rosenbrock matrix `W = σ·I − J` (`σ = 1/(hγ)`), in place and
//! without allocation after construction.
//!
//! - [`DenseLu`]: Gaussian elimination with partial pivoting on the whole matrix
//!   (Golub & Van Loan, *Matrix Computations*, 4th ed., Alg. 3.4.1).
//! - [`BlockArrowhead`]: the same for a block-arrowhead matrix (independent diagonal blocks
//!   coupled only through a border) by Schur-complement elimination of the blocks
//!   (Golub & Van Loan §3.2.11 block LU; docs/physics.md §N2.4 item 4).

use nalgebra::DMatrix;

/// A linear solver for `(σ·I − J)·x = b`, factored once per step attempt.
pub trait LinearSolver: Send {
    /// The dimension `n` it was built for.
    fn dim(&self) -> usize;
    /// Factor `σ·I − J` into the solver's own storage. `false`: singular (or not finite).
    fn factor(&mut self, sigma: f64, jac: &DMatrix<f64>) -> bool;
    /// Overwrite `b` with the solution `x` of `(σ·I − J)·x = b` for the last factorisation.
    fn solve(&mut self, b: &mut [f64]);
}

/// In-place LU factorisation with partial pivoting of the column-major `n × n` matrix `a`
/// (leading dimension `n`): on return `a` holds the unit lower factor `L` below the diagonal,
/// `U` above it and the reciprocals `1/u_kk` of `U`'s diagonal on it (the solve multiplies
/// by them: a division per unknown on the back substitution's critical path would cost
/// about three times the multiplication, and the reciprocal is computed here anyway to
/// scale `L`'s column); `piv[k]` is the row swapped with row `k` at step `k`.
/// `Err(k)`: the pivot in column `k` is zero or not finite (singular).
#[inline]
pub fn lu_factor(a: &mut [f64], n: usize, piv: &mut [usize]) -> Result<(), usize> {
    lu_factor_sized(a, Dynamic(n), piv)
}

/// [`lu_factor`] with the size `bs` (a compile-time constant for [`Fixed`], so that a
/// block's loops unroll; the same arithmetic in the same order either way).
#[inline(always)]
fn lu_factor_sized<B: BlockSize>(a: &mut [f64], bs: B, piv: &mut [usize]) -> Result<(), usize> {
    let n = bs.get();
    debug_assert!(a.len() >= n * n && piv.len() >= n);
    for k in 0..n {
        // pivot search in column k
        let col = k * n;
        let mut p = k;
        let mut best = a[col + k].abs();
        for i in k + 1..n {
            let v = a[col + i].abs();
            if v > best {
                best = v;
                p = i;
            }
        }
        if best == 0.0 || !best.is_finite() {
            return Err(k);
        }
        piv[k] = p;
        if p != k {
            for j in 0..n {
                a.swap(j * n + k, j * n + p);
            }
        }
        let inv = 1.0 / a[col + k];
        for i in k + 1..n {
            a[col + i] *= inv;
        }
        a[col + k] = inv;
        for j in k + 1..n {
            let akj = a[j * n + k];
            if akj != 0.0 {
                let (left, right) = a.split_at_mut(j * n);
                let lk = &left[col + k + 1..col + n];
                let cj = &mut right[k + 1..n];
                for (c, l) in cj.iter_mut().zip(lk) {
                    *c -= l * akj;
                }
            }
        }
    }
    Ok(())
}

/// Solve with the factors of [`lu_factor`]: `b` is overwritten by `x`. Up to `n = 12`
/// (a 2-DOF ring level has 5 states, a 5-DOF one 11) with the size fixed at compile time.
#[inline]
pub fn lu_solve(a: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    macro_rules! fixed {
        ($($k:literal)*) => {
            match n {
                $($k => return lu_solve_n::<$k>(&a[..$k * $k], &piv[..$k], &mut b[..$k]),)*
                _ => {}
            }
        };
    }
    fixed!(1 2 3 4 5 6 7 8 9 10 11 12);
    lu_solve_n_dyn(a, n, piv, b)
}

/// [`lu_solve`] for `n = N`, known at compile time: the row swaps in `b`, then the
/// substitutions in a local array with every index a constant (registers, no branch): a
/// zero `b_k` subtracts its zero products instead of skipping them, which differs from the
/// general loop only in the sign of a zero (the factors are finite: the Rosenbrock
/// integrators refuse a Jacobian that is not, and a non-finite pivot is singular).
#[inline(always)]
fn lu_solve_n<const N: usize>(a: &[f64], piv: &[usize], b: &mut [f64]) {
    for (k, &p) in piv.iter().enumerate() {
        if p != k {
            b.swap(k, p);
        }
    }
    let mut x = [0.0; N];
    x.copy_from_slice(b);
    for k in 0..N {
        let bk = x[k];
        for i in k + 1..N {
            x[i] -= a[k * N + i] * bk;
        }
    }
    for k in (0..N).rev() {
        x[k] *= a[k * N + k];
        let bk = x[k];
        for i in 0..k {
            x[i] -= a[k * N + i] * bk;
        }
    }
    b.copy_from_slice(&x);
}

/// [`lu_solve`] for any `n`, skipping the products of a zero `b_k`.
fn lu_solve_n_dyn(a: &[f64], n: usize, piv: &[usize], b: &mut [f64]) {
    for (k, &p) in piv.iter().enumerate().take(n) {
        if p != k {
            b.swap(k, p);
        }
    }
    // forward substitution with the unit lower factor
    for k in 0..n {
        let bk = b[k];
        if bk != 0.0 {
            let col = &a[k * n + k + 1..k * n + n];
            for (bi, l) in b[k + 1..n].iter_mut().zip(col) {
                *bi -= l * bk;
            }
        }
    }
    // back substitution with U
    for k in (0..n).rev() {
        b[k] *= a[k * n + k];
        let bk = b[k];
        if bk != 0.0 {
            let col = &a[k * n..k * n + k];
            for (bi, u) in b[..k].iter_mut().zip(col) {
                *bi -= u * bk;
            }
        }
    }
}

/// Dense LU with partial pivoting (the default solver).
#[derive(Debug, Clone)]
pub struct DenseLu {
    n: usize,
    lu: Vec<f64>,
    piv: Vec<usize>,
}

impl DenseLu {
    /// Storage for dimension `n`.
    pub fn new(n: usize) -> Self {
        DenseLu {
            n,
            lu: vec![0.0; n * n],
            piv: vec![0; n],
        }
    }
}

impl LinearSolver for DenseLu {
    fn dim(&self) -> usize {
        self.n
    }

    fn factor(&mut self, sigma: f64, jac: &DMatrix<f64>) -> bool {
        let n = self.n;
        debug_assert_eq!(jac.shape(), (n, n));
        // DMatrix storage is column-major, like ours
        for (w, j) in self.lu.iter_mut().zip(jac.as_slice()) {
            *w = -j;
        }
        for i in 0..n {
            self.lu[i * n + i] += sigma;
        }
        lu_factor(&mut self.lu, n, &mut self.piv).is_ok()
    }

    fn solve(&mut self, b: &mut [f64]) {
        lu_solve(&self.lu, self.n, &self.piv, b);
    }
}

/// Solver for states ordered `[z | q | v]` (`nz`, `nd`, `nd` of them) with `dq/dt = v`:
/// a body's positions and velocities after other states (a load-driven ring after its
/// level's). Then `J`'s `q` rows are `[0 | 0 | I]`, and with them `(σI − J) x = b` gives
/// `x_q = (b_q + x_v)/σ`; the other rows, `r = (z, v)`, reduce to
///
/// ```text
/// R x_r = b_r + G b_q,   R = σI − J_rr − G E,   G = J_rq / σ
/// ```
///
/// where `J_rr` is `J` on the rows and columns `r`, `J_rq` its `q` columns on the rows `r`,
/// and `E` picks the `v` columns (`(G E)_ij = G_ik` when column `j` is `v_k`). One
/// LU of `nz + nd` (3 for a 2-DOF ring with its cage angle, 6 with 5 DOFs) instead of
/// `nz + 2 nd` (5, 11): the same solution as the dense LU in exact arithmetic. A `J`
/// whose `q` rows are not exactly `[0 | 0 | I]` (a difference quotient of them) is
/// factored dense.
#[derive(Debug, Clone)]
pub struct SecondOrderLu {
    nz: usize,
    nd: usize,
    /// `R`'s LU (column-major, `m = nz + nd`), as [`lu_factor`] leaves it.
    red: Vec<f64>,
    piv: Vec<usize>,
    /// `G` (`m × nd`, column-major).
    g: Vec<f64>,
    /// `1/σ` of the last factorisation.
    inv_sigma: f64,
    /// The dense LU, for a `J` without the structure (allocated with the solver: no
    /// allocation when a step first meets one).
    dense: DenseLu,
    /// The last `J` did not have the structure: `dense` holds its LU.
    use_dense: bool,
    r: Vec<f64>,
}

impl SecondOrderLu {
    /// Storage for `nz` other states and `nd` positions and velocities.
    pub fn new(nz: usize, nd: usize) -> Self {
        let m = nz + nd;
        SecondOrderLu {
            nz,
            nd,
            red: vec![0.0; m * m],
            piv: vec![0; m],
            g: vec![0.0; m * nd],
            inv_sigma: f64::NAN,
            dense: DenseLu::new(nz + 2 * nd),
            use_dense: false,
            r: vec![0.0; m],
        }
    }

    /// Full index of reduced index `i` (`z` first, then `v`).
    #[inline]
    fn full(&self, i: usize) -> usize {
        if i < self.nz {
            i
        } else {
            i + self.nd
        }
    }

    /// Whether `J`'s `q` rows are exactly `[0 | 0 | I]`.
    pub fn fits(&self, jac: &DMatrix<f64>) -> bool {
        let (nz, nd) = (self.nz, self.nd);
        let n = nz + 2 * nd;
        (0..nd).all(|k| (0..n).all(|c| jac[(nz + k, c)] == f64::from(c == nz + nd + k)))
    }
}

impl LinearSolver for SecondOrderLu {
    fn dim(&self) -> usize {
        self.nz + 2 * self.nd
    }

    fn factor(&mut self, sigma: f64, jac: &DMatrix<f64>) -> bool {
        let (nz, nd) = (self.nz, self.nd);
        let n = nz + 2 * nd;
        debug_assert_eq!(jac.shape(), (n, n));
        self.use_dense = !self.fits(jac);
        if self.use_dense {
            return self.dense.factor(sigma, jac);
        }
        let m = nz + nd;
        let inv = 1.0 / sigma;
        self.inv_sigma = inv;
        for i in 0..m {
            let fi = self.full(i);
            for k in 0..nd {
                self.g[k * m + i] = jac[(fi, nz + k)] * inv;
            }
        }
        for j in 0..m {
            let fj = self.full(j);
            for i in 0..m {
                let fi = self.full(i);
                let mut v = -jac[(fi, fj)];
                if j >= nz {
                    v -= self.g[(j - nz) * m + i];
                }
                if i == j {
                    v += sigma;
                }
                self.red[j * m + i] = v;
            }
        }
        lu_factor(&mut self.red, m, &mut self.piv).is_ok()
    }

    fn solve(&mut self, b: &mut [f64]) {
        if self.use_dense {
            return self.dense.solve(b);
        }
        let (nz, nd) = (self.nz, self.nd);
        let m = nz + nd;
        for i in 0..m {
            let mut v = b[self.full(i)];
            for k in 0..nd {
                v += self.g[k * m + i] * b[nz + k];
            }
            self.r[i] = v;
        }
        lu_solve(&self.red, m, &self.piv, &mut self.r);
        for i in 0..m {
            b[self.full(i)] = self.r[i];
        }
        for k in 0..nd {
            b[nz + k] = (b[nz + k] + b[nz + nd + k]) * self.inv_sigma;
        }
    }
}

/// Block-arrowhead solver for states ordered `[block_1 … block_nb | border]`, or
/// `[head | block_1 … block_nb | tail]` ([`BlockArrowhead::with_head`]; the border is then
/// the head and the tail together, in that order): each diagonal
/// block (`s × s`, e.g. one ball's states) couples to the other blocks only through the
/// border (`m` states, e.g. rings and cage):
///
/// ```text
/// W = | D_1          B_1 |      D_i = σI − J_ii (s×s),  B_i = −J_i,border (s×m)
///     |     ⋱        ⋮   |      C_i = −J_border,i (m×s), E = σI − J_border,border (m×m)
///     |        D_nb  B_nb|
///     | C_1 … C_nb   E   |
/// ```
///
/// Factor: `D_i = L_i U_i`, `G_i = D_i⁻¹ B_i`, Schur complement `S = E − Σ C_i G_i`, `S = LU`.
/// Solve: `z_i = D_i⁻¹ b_i`, `x_b = S⁻¹ (b_b − Σ C_i z_i)`, `x_i = z_i − G_i x_b`.
/// Cost `nb·(s³ + 2 s²m + s m²) + m³` flops against `(nb·s + m)³` for dense LU.
///
/// Entries of `J` coupling two different blocks are **ignored** (assumed zero); use
/// [`BlockArrowhead::fits`] to check a Jacobian. The blocks must be non-singular by
/// themselves (partial pivoting happens within a block and within `S`), which holds for
/// `σ·I − J` when `h` is small enough; a singular block is reported like a singular matrix.
#[derive(Debug, Clone)]
pub struct BlockArrowhead {
    /// The border states before the blocks (the head); the other `m − h` follow them.
    h: usize,
    nb: usize,
    s: usize,
    m: usize,
    /// Scratch: the border's entries of a right-hand side, gathered (`m`).
    xr: Vec<f64>,
    /// Inverses of the diagonal blocks, `nb` column-major `s × s` matrices (from their LU
    /// with partial pivoting): a block solve is then an `s × s` product, with no pivot
    /// swaps or loop set-up per block (the blocks are tiny: 3 states per ball).
    d: Vec<f64>,
    /// Scratch: one block's LU and pivots.
    lu: Vec<f64>,
    dpiv: Vec<usize>,
    /// `G_i = D_i⁻¹ B_i`, `nb` column-major `s × m_g` matrices: only its columns in
    /// [`Self::g_cols`] (the others are zero).
    g: Vec<f64>,
    /// `C_i`, `nb` row-major `m_c × s` matrices (a border row's `s` entries contiguous):
    /// only its rows in [`Self::c_rows`] (the others are zero).
    c: Vec<f64>,
    /// LU of the Schur complement, column-major `m × m`.
    schur: Vec<f64>,
    spiv: Vec<usize>,
    /// The border columns `j` where some block's `B_i` is not zero (ascending): `G_i`'s
    /// other columns are zero, so they are neither stored, nor subtracted in the Schur
    /// complement `S = E − Σ C_i G_i`, nor in the back substitution `x_i = z_i − G_i x_b`
    /// (the skidding level's balls do not see the ring's velocities). Set by each
    /// factorisation from the Jacobian's pattern.
    g_cols: Vec<usize>,
    /// The border rows `r` where some `C_i` is not zero (ascending), likewise in the
    /// Schur complement and the forward elimination (`b_b − Σ C_i z_i`; the cage angle's and
    /// the ring positions' rates do not depend on the balls).
    c_rows: Vec<usize>,
    /// The state indices of [`Self::g_cols`] and of [`Self::c_rows`].
    g_idx: Vec<usize>,
    c_idx: Vec<usize>,
    /// The state index of each border state (the head's first, then the tail's).
    bidx: Vec<usize>,
    /// Scratch: which border rows have some `C` entry.
    flag: Vec<bool>,
    /// Scratch: the border entries in [`Self::c_rows`] (solve) or the Schur complement's
    /// entries in those rows and the columns of [`Self::g_cols`] (factor), gathered so
    /// that the blocks' updates run over contiguous memory.
    border: Vec<f64>,
}

impl BlockArrowhead {
    /// Storage for `nb` blocks of size `s` and a border of `m` states (`n = nb·s + m`).
    pub fn new(nb: usize, s: usize, m: usize) -> Self {
        Self::with_head(0, nb, s, m)
    }

    /// Storage for states ordered `[head | nb blocks of s | tail]`, the border (`m`
    /// states) being the `h` head states and the `m − h` tail states (`n = nb·s + m`): the
    /// full level's cage states come before its balls, the ring's after them. The same
    /// arithmetic as [`Self::new`] on the states reordered `[blocks | head | tail]`.
    pub fn with_head(h: usize, nb: usize, s: usize, m: usize) -> Self {
        assert!(h <= m, "head {h} larger than the border {m}");
        BlockArrowhead {
            h,
            nb,
            s,
            m,
            xr: vec![0.0; m],
            d: vec![0.0; nb * s * s],
            lu: vec![0.0; s * s],
            dpiv: vec![0; s],
            g: vec![0.0; nb * s * m],
            c: vec![0.0; nb * m * s],
            schur: vec![0.0; m * m],
            spiv: vec![0; m],
            g_cols: Vec::with_capacity(m),
            c_rows: Vec::with_capacity(m),
            g_idx: Vec::with_capacity(m),
            c_idx: Vec::with_capacity(m),
            bidx: (0..m).map(|r| if r < h { r } else { nb * s + r }).collect(),
            flag: vec![false; m],
            border: vec![0.0; m * m],
        }
    }

    /// Whether `jac` has the arrowhead pattern (no non-zero entry coupling two different
    /// blocks), so that the solver is exact for it.
    pub fn fits(&self, jac: &DMatrix<f64>) -> bool {
        let (h, n) = (self.h, self.nb * self.s);
        if jac.shape() != (self.dim(), self.dim()) {
            return false;
        }
        for j in 0..n {
            for i in 0..n {
                if i / self.s != j / self.s && jac[(h + i, h + j)] != 0.0 {
                    return false;
                }
            }
        }
        true
    }
}

/// A block size: a compile-time constant ([`Fixed`], so that the loops over a block unroll)
/// or a run-time one ([`Dynamic`]); the arithmetic is the same either way.
trait BlockSize: Copy {
    fn get(self) -> usize;
    /// [`lu_solve`] of a block (the same arithmetic; the fixed size skips its dispatch).
    fn lu_solve(self, a: &[f64], piv: &[usize], b: &mut [f64]);
}

#[derive(Clone, Copy)]
struct Fixed<const S: usize>;
impl<const S: usize> BlockSize for Fixed<S> {
    #[inline(always)]
    fn get(self) -> usize {
        S
    }
    #[inline(always)]
    fn lu_solve(self, a: &[f64], piv: &[usize], b: &mut [f64]) {
        if S <= 12 {
            lu_solve_n::<S>(&a[..S * S], &piv[..S], &mut b[..S]);
        } else {
            lu_solve(a, S, piv, b);
        }
    }
}

#[derive(Clone, Copy)]
struct Dynamic(usize);
impl BlockSize for Dynamic {
    #[inline(always)]
    fn get(self) -> usize {
        self.0
    }
    #[inline(always)]
    fn lu_solve(self, a: &[f64], piv: &[usize], b: &mut [f64]) {
        lu_solve(a, self.0, piv, b);
    }
}

impl LinearSolver for BlockArrowhead {
    fn dim(&self) -> usize {
        self.nb * self.s + self.m
    }

    fn factor(&mut self, sigma: f64, jac: &DMatrix<f64>) -> bool {
        // One ball's states: 3 (5 with radial mass; the full level's 5 and 9).
        match self.s {
            3 => self.factor_blocks(Fixed::<3>, sigma, jac),
            5 => self.factor_blocks(Fixed::<5>, sigma, jac),
            9 => self.factor_blocks(Fixed::<9>, sigma, jac),
            s => self.factor_blocks(Dynamic(s), sigma, jac),
        }
    }

    fn solve(&mut self, x: &mut [f64]) {
        match self.s {
            3 => self.solve_blocks(Fixed::<3>, x),
            5 => self.solve_blocks(Fixed::<5>, x),
            9 => self.solve_blocks(Fixed::<9>, x),
            s => self.solve_blocks(Dynamic(s), x),
        }
    }
}

impl BlockArrowhead {
    #[inline(always)]
    fn factor_blocks<B: BlockSize>(&mut self, bs: B, sigma: f64, jac: &DMatrix<f64>) -> bool {
        let (h, nb, s, m) = (self.h, self.nb, bs.get(), self.m);
        let nb0 = nb * s;
        debug_assert_eq!(jac.shape(), (nb0 + m, nb0 + m));
        // column-major storage: entry (i, j) at j * nn + i
        let (ja, nn) = (jac.as_slice(), nb0 + m);
        // The border's pattern: rows with some C entry (flagged column by column over the
        // blocks' columns, whose border entries are the head's and the tail's runs),
        // columns with some B entry (each a contiguous run of J's storage).
        let flag = &mut self.flag[..m];
        flag.fill(false);
        for k in h..h + nb0 {
            let col = &ja[k * nn..(k + 1) * nn];
            let (fh, ft) = flag.split_at_mut(h);
            for (f, v) in fh.iter_mut().zip(&col[..h]) {
                *f |= *v != 0.0;
            }
            for (f, v) in ft.iter_mut().zip(&col[h + nb0..]) {
                *f |= *v != 0.0;
            }
        }
        self.c_rows.clear();
        self.c_idx.clear();
        for (r, &f) in flag.iter().enumerate() {
            if f {
                self.c_rows.push(r);
                self.c_idx.push(self.bidx[r]);
            }
        }
        self.g_cols.clear();
        self.g_idx.clear();
        for (j, &bj) in self.bidx.iter().enumerate() {
            if ja[bj * nn + h..bj * nn + h + nb0].iter().any(|v| *v != 0.0) {
                self.g_cols.push(j);
                self.g_idx.push(bj);
            }
        }
        let (mc, mg) = (self.c_rows.len(), self.g_cols.len());
        // E into the Schur storage
        for (j, &bj) in self.bidx.iter().enumerate() {
            let src = &ja[bj * nn..(bj + 1) * nn];
            let dst = &mut self.schur[j * m..(j + 1) * m];
            for (dv, v) in dst[..h].iter_mut().zip(&src[..h]) {
                *dv = -v;
            }
            for (dv, v) in dst[h..].iter_mut().zip(&src[h + nb0..]) {
                *dv = -v;
            }
            dst[j] += sigma;
        }
        // The part of S the blocks update (rows `c_rows`, columns `g_cols`), gathered
        // (column-major `m_c × m_g`); each entry gets the same subtractions in the same
        // order as in place.
        let sc = &mut self.border[..mc * mg];
        for (scj, &j) in sc.chunks_exact_mut(mc.max(1)).zip(&self.g_cols) {
            let col = &self.schur[j * m..(j + 1) * m];
            for (v, &i) in scj.iter_mut().zip(&self.c_rows) {
                *v = col[i];
            }
        }
        for b in 0..nb {
            let o = h + b * s;
            let lu = &mut self.lu[..s * s];
            for j in 0..s {
                let src = &ja[(o + j) * nn + o..(o + j) * nn + o + s];
                for (l, v) in lu[j * s..(j + 1) * s].iter_mut().zip(src) {
                    *l = -v;
                }
                lu[j * s + j] += sigma;
            }
            let piv = &mut self.dpiv[..s];
            if lu_factor_sized(lu, bs, piv).is_err() {
                return false;
            }
            // D_b⁻¹, column by column from the identity.
            let d = &mut self.d[b * s * s..(b + 1) * s * s];
            for j in 0..s {
                let col = &mut d[j * s..(j + 1) * s];
                col.fill(0.0);
                col[j] = 1.0;
                bs.lu_solve(lu, piv, col);
            }
            if !d.iter().all(|v| v.is_finite()) {
                return false;
            }
            // G_b = D_b⁻¹ B_b, column by column (its non-zero columns). A zero `B` entry
            // adds products `±0` to sums that start at `+0`: the same bits as skipping it.
            let g = &mut self.g[b * s * mg..(b + 1) * s * mg];
            for (col, &sj) in g.chunks_exact_mut(s).zip(&self.g_idx) {
                let bcol = &ja[sj * nn + o..sj * nn + o + s];
                col.fill(0.0);
                for (k, bk) in bcol.iter().enumerate() {
                    let bkj = -bk;
                    for (v, dv) in col.iter_mut().zip(&d[k * s..(k + 1) * s]) {
                        *v += dv * bkj;
                    }
                }
            }
            // C_b (its non-zero rows; each row's `s` entries contiguous)
            let c = &mut self.c[b * mc * s..(b + 1) * mc * s];
            for j in 0..s {
                let src = &ja[(o + j) * nn..(o + j + 1) * nn];
                for (ii, &i) in self.c_idx.iter().enumerate() {
                    c[ii * s + j] = -src[i];
                }
            }
            // S -= C_b G_b (on the gathered part of S): each entry's subtractions in the
            // order of the block's states; a zero `G` entry subtracts `+0` (the bits of
            // skipping it, also for a `-0` entry of S).
            for (scj, gj) in sc.chunks_exact_mut(mc.max(1)).zip(g.chunks_exact(s)) {
                if gj.iter().all(|gv| *gv != 0.0) {
                    // No zero to skip (the usual column): plain products.
                    for (sv, ci) in scj.iter_mut().zip(c.chunks_exact(s)) {
                        let mut v = *sv;
                        for (cv, gv) in ci.iter().zip(gj) {
                            v -= cv * gv;
                        }
                        *sv = v;
                    }
                    continue;
                }
                for (sv, ci) in scj.iter_mut().zip(c.chunks_exact(s)) {
                    let mut v = *sv;
                    for (cv, gv) in ci.iter().zip(gj) {
                        v -= if *gv != 0.0 { cv * gv } else { 0.0 };
                    }
                    *sv = v;
                }
            }
        }
        // The updated part of S back in place.
        for (scj, &j) in sc.chunks_exact(mc.max(1)).zip(&self.g_cols) {
            let col = &mut self.schur[j * m..(j + 1) * m];
            for (v, &i) in scj.iter().zip(&self.c_rows) {
                col[i] = *v;
            }
        }
        lu_factor(&mut self.schur, m, &mut self.spiv).is_ok()
    }

    #[inline(always)]
    fn solve_blocks<B: BlockSize>(&mut self, bs: B, x: &mut [f64]) {
        let (h, nb, s, m) = (self.h, self.nb, bs.get(), self.m);
        let (mc, mg) = (self.c_rows.len(), self.g_cols.len());
        let nb0 = nb * s;
        // The border gathered: the head's entries, then the tail's.
        let (head, rest) = x.split_at_mut(h);
        let (xb, tail) = rest.split_at_mut(nb0);
        let xr = &mut self.xr[..m];
        xr[..h].copy_from_slice(head);
        xr[h..].copy_from_slice(tail);
        // The border entries the blocks update, gathered (the same subtractions in the
        // same order as in place).
        let xc = &mut self.border[..mc];
        for (v, &r) in xc.iter_mut().zip(&self.c_rows) {
            *v = xr[r];
        }
        let r = &mut self.lu[..s];
        for b in 0..nb {
            let z = &mut xb[b * s..(b + 1) * s];
            let d = &self.d[b * s * s..(b + 1) * s * s];
            // z = D_b⁻¹ z
            r.copy_from_slice(z);
            z.fill(0.0);
            for (rk, dk) in r.iter().zip(d.chunks_exact(s)) {
                for (zi, dv) in z.iter_mut().zip(dk) {
                    *zi += dv * rk;
                }
            }
            // b_border -= C_b z, each entry's terms in the order of the block's states
            let c = &self.c[b * mc * s..(b + 1) * mc * s];
            for (v, ci) in xc.iter_mut().zip(c.chunks_exact(s)) {
                let mut t = *v;
                for (cv, zk) in ci.iter().zip(z.iter()) {
                    t -= cv * zk;
                }
                *v = t;
            }
        }
        for (v, &r) in xc.iter().zip(&self.c_rows) {
            xr[r] = *v;
        }
        lu_solve(&self.schur, m, &self.spiv, xr);
        // x_b at the columns the blocks see, gathered.
        let xg = &mut self.border[..mg];
        for (v, &j) in xg.iter_mut().zip(&self.g_cols) {
            *v = xr[j];
        }
        for b in 0..nb {
            let z = &mut xb[b * s..(b + 1) * s];
            let g = &self.g[b * s * mg..(b + 1) * s * mg];
            for (&xj, gj) in xg.iter().zip(g.chunks_exact(s)) {
                for (zi, gv) in z.iter_mut().zip(gj) {
                    *zi -= gv * xj;
                }
            }
        }
        head.copy_from_slice(&xr[..h]);
        tail.copy_from_slice(&xr[h..]);
    }
}

#[cfg(test)]
mod arrowhead_reference;

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random numbers in [-1, 1] (xorshift).
    fn rng(seed: &mut u64) -> f64 {
        *seed ^= *seed << 13;
        *seed ^= *seed >> 7;
        *seed ^= *seed << 17;
        (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    #[test]
    fn dense_lu_solves_a_system_needing_pivoting() {
        // zero leading pivot: fails without row exchanges
        let j = DMatrix::from_row_slice(3, 3, &[0.0, -2.0, -1.0, -1.0, -1.0, 0.0, -3.0, 0.0, -2.0]);
        // W = 0·I − J = -J
        let mut lu = DenseLu::new(3);
        assert!(lu.factor(0.0, &j));
        let x_true = [1.0, -2.0, 0.5];
        let w = -&j;
        let mut b: Vec<f64> = (0..3)
            .map(|i| (0..3).map(|k| w[(i, k)] * x_true[k]).sum())
            .collect();
        lu.solve(&mut b);
        for i in 0..3 {
            assert!((b[i] - x_true[i]).abs() < 1e-14, "{b:?}");
        }
        // singular matrix is reported
        let s = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 4.0]);
        assert!(!DenseLu::new(2).factor(0.0, &s));
    }

    /// Every size, fixed at compile time (1 to 12) or not (13, 14), solves random systems
    /// needing row exchanges to a residual at rounding level, and the fixed-size solve gives
    /// the general loop's values (a zero may differ in sign only), zeros in `b` included.
    #[test]
    fn lu_solve_of_every_size_solves_and_matches_the_general_loop() {
        let mut seed = 0x2545_f491_4f6c_dd1d_u64;
        for n in 1..=14 {
            for trial in 0..20 {
                let mut a: Vec<f64> = (0..n * n).map(|_| rng(&mut seed)).collect();
                // Small leading diagonal: partial pivoting must swap rows.
                a[0] *= 1e-3;
                let mut b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
                if trial % 4 == 0 {
                    b[n / 2] = 0.0;
                }
                let mut f = a.clone();
                let mut piv = vec![0; n];
                lu_factor(&mut f, n, &mut piv).unwrap();
                if n > 1 && trial == 0 {
                    assert_ne!(piv[0], 0, "n = {n}: the first pivot was not exchanged");
                }
                let mut x = b.clone();
                lu_solve(&f, n, &piv, &mut x);
                let mut y = b.clone();
                lu_solve_n_dyn(&f, n, &piv, &mut y);
                assert_eq!(x, y, "n = {n}");
                let scale: f64 = a.iter().map(|v| v.abs()).sum::<f64>()
                    * x.iter().map(|v| v.abs()).fold(0.0, f64::max);
                for i in 0..n {
                    // column-major: a[j * n + i] is entry (i, j)
                    let r: f64 = (0..n).map(|j| a[j * n + i] * x[j]).sum::<f64>() - b[i];
                    assert!(r.abs() <= 1e-13 * scale, "n = {n}, row {i}: residual {r:e}");
                }
            }
        }
    }

    /// States `[z | q | v]` with `dq/dt = v`: the reduced solve gives the dense LU's
    /// solution to rounding level (1, 2 and 5 DOFs, with and without other states, rows
    /// needing exchanges), and a `J` whose position rows are not exactly `[0 | 0 | I]`
    /// (a difference quotient) is solved dense, bit for bit as [`DenseLu`].
    #[test]
    fn second_order_lu_matches_dense_lu() {
        let mut seed = 0x1234_5678_9abc_def1_u64;
        for (nz, nd) in [(0, 1), (1, 2), (0, 2), (1, 5), (3, 5)] {
            let n = nz + 2 * nd;
            for trial in 0..10 {
                let mut j = DMatrix::zeros(n, n);
                for c in 0..n {
                    for r in 0..n {
                        let q_row = r >= nz && r < nz + nd;
                        j[(r, c)] = if q_row {
                            f64::from(c == r + nd)
                        } else {
                            // Stiff entries, as contact stiffness over a mass.
                            1e6 * rng(&mut seed)
                        };
                    }
                }
                let mut so = SecondOrderLu::new(nz, nd);
                assert!(so.fits(&j));
                let sigma = [1e2, 1e3, 1e4, 3e5][trial % 4];
                let mut dense = DenseLu::new(n);
                assert!(so.factor(sigma, &j) && dense.factor(sigma, &j));
                let b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
                let (mut x, mut y) = (b.clone(), b.clone());
                so.solve(&mut x);
                dense.solve(&mut y);
                // The residual of (σI − J) x = b, against its terms' size.
                for r in 0..n {
                    let mut res = sigma * x[r] - b[r];
                    let mut size = (sigma * x[r]).abs() + b[r].abs();
                    for c in 0..n {
                        res -= j[(r, c)] * x[c];
                        size += (j[(r, c)] * x[c]).abs();
                    }
                    assert!(
                        res.abs() <= 1e-13 * size,
                        "{nz} {nd} {trial} row {r}: {res:e}"
                    );
                }
                let scale = y.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                for (a, d) in x.iter().zip(&y) {
                    assert!((a - d).abs() <= 1e-11 * scale, "{nz} {nd} {trial}: {a} {d}");
                }
                // A position row off by a rounding: dense, the same bits.
                j[(nz, nz + nd)] = 1.0 + f64::EPSILON;
                assert!(!so.fits(&j));
                assert!(so.factor(sigma, &j) && dense.factor(sigma, &j));
                let (mut x, mut y) = (b.clone(), b.clone());
                so.solve(&mut x);
                dense.solve(&mut y);
                assert_eq!(x, y);
            }
        }
    }

    #[test]
    fn block_arrowhead_matches_dense_lu() {
        let (nb, s, m) = (5, 4, 3);
        let n = nb * s + m;
        let mut seed = 0x9E37_79B9_7F4A_7C15u64;
        let mut j = DMatrix::zeros(n, n);
        for c in 0..n {
            for r in 0..n {
                let same_block = r < nb * s && c < nb * s && r / s == c / s;
                let border = r >= nb * s || c >= nb * s;
                if same_block || border {
                    j[(r, c)] = 3.0 * rng(&mut seed);
                }
            }
        }
        let mut blk = BlockArrowhead::new(nb, s, m);
        assert!(blk.fits(&j));
        let mut dense = DenseLu::new(n);
        let sigma = 2.5;
        assert!(blk.factor(sigma, &j));
        assert!(dense.factor(sigma, &j));
        let b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
        let (mut xb, mut xd) = (b.clone(), b.clone());
        blk.solve(&mut xb);
        dense.solve(&mut xd);
        // residual of the block solution against W = σI − J
        for i in 0..n {
            let mut r = sigma * xb[i] - b[i];
            for k in 0..n {
                r -= j[(i, k)] * xb[k];
            }
            assert!(r.abs() < 1e-13, "residual {r} in row {i}");
            assert!(
                (xb[i] - xd[i]).abs() < 1e-13 * (1.0 + xd[i].abs()),
                "{} vs {}",
                xb[i],
                xd[i]
            );
        }
        // a coupling between two blocks breaks the pattern
        j[(0, s)] = 1.0;
        assert!(!blk.fits(&j));
    }

    /// States `[head | blocks | tail]` (the full level's cage, its balls of 9 states, the
    /// ring): the same solution as the dense LU to rounding level, and bit for bit the
    /// solution of the blocks-first solver on the states reordered `[blocks | head | tail]`
    /// (the same arithmetic on the same numbers).
    #[test]
    fn block_arrowhead_with_a_head_is_the_blocks_first_solve_reordered() {
        let (h, nb, s, m) = (4, 5, 9, 7);
        let (nb0, n) = (nb * s, nb * s + m);
        let mut seed = 0x5DEE_CE66_D1CE_4E5Bu64;
        let mut j = DMatrix::zeros(n, n);
        let in_blocks = |i: usize| i >= h && i < h + nb0;
        for c in 0..n {
            for r in 0..n {
                let same_block = in_blocks(r) && in_blocks(c) && (r - h) / s == (c - h) / s;
                if same_block || !in_blocks(r) || !in_blocks(c) {
                    // stiff entries, as a contact over a ball mass
                    j[(r, c)] = 1e3 * rng(&mut seed);
                }
            }
        }
        // State `i` of the reordered problem is state `perm[i]` of the original.
        let perm: Vec<usize> = (h..h + nb0).chain(0..h).chain(h + nb0..n).collect();
        let jp = DMatrix::from_fn(n, n, |r, c| j[(perm[r], perm[c])]);
        let b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
        for sigma in [1e2, 3e4] {
            let mut head = BlockArrowhead::with_head(h, nb, s, m);
            let mut first = BlockArrowhead::new(nb, s, m);
            let mut dense = DenseLu::new(n);
            assert!(head.fits(&j) && first.fits(&jp));
            assert!(head.factor(sigma, &j) && first.factor(sigma, &jp) && dense.factor(sigma, &j));
            let (mut x, mut xd) = (b.clone(), b.clone());
            let mut xp: Vec<f64> = perm.iter().map(|&i| b[i]).collect();
            head.solve(&mut x);
            first.solve(&mut xp);
            dense.solve(&mut xd);
            for (k, &i) in perm.iter().enumerate() {
                assert_eq!(x[i].to_bits(), xp[k].to_bits(), "state {i}");
            }
            let scale = xd.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            for i in 0..n {
                assert!(
                    (x[i] - xd[i]).abs() <= 1e-12 * scale,
                    "{i}: {} {}",
                    x[i],
                    xd[i]
                );
            }
        }
        // a coupling between two balls breaks the pattern
        j[(h, h + s)] = 1.0;
        assert!(!BlockArrowhead::with_head(h, nb, s, m).fits(&j));
    }

    /// Border rows with no coupling to the blocks and border columns the blocks do not
    /// see (the skidding level's cage angle and ring positions, ring velocities) are
    /// skipped in the solve, and the solution is still that of the dense LU; a border
    /// column that becomes coupled is no longer skipped.
    #[test]
    fn block_arrowhead_skips_zero_border_rows_and_columns() {
        let (nb, s, m) = (6, 3, 5);
        let n = nb * s + m;
        let nb0 = nb * s;
        let mut seed = 0x2545_F491_4F6C_DD1Du64;
        let mut j = DMatrix::zeros(n, n);
        for c in 0..n {
            for r in 0..n {
                let same_block = r < nb0 && c < nb0 && r / s == c / s;
                // no C entries in border rows 0 and 2, no B entries in border column 3
                let c_zero = r >= nb0 && c < nb0 && [0, 2].contains(&(r - nb0));
                let b_zero = r < nb0 && c == nb0 + 3;
                let border = r >= nb0 || c >= nb0;
                if (same_block || border) && !c_zero && !b_zero {
                    j[(r, c)] = 3.0 * rng(&mut seed);
                }
            }
        }
        let sigma = 2.5;
        for round in 0..2 {
            let mut blk = BlockArrowhead::new(nb, s, m);
            let mut dense = DenseLu::new(n);
            assert!(blk.factor(sigma, &j) && dense.factor(sigma, &j));
            if round == 0 {
                assert_eq!(blk.c_rows, [1, 3, 4]);
                assert_eq!(blk.g_cols, [0, 1, 2, 4]);
            } else {
                assert_eq!(blk.g_cols, [0, 1, 2, 3, 4]);
            }
            let b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
            let (mut xb, mut xd) = (b.clone(), b);
            blk.solve(&mut xb);
            dense.solve(&mut xd);
            for i in 0..n {
                assert!(
                    (xb[i] - xd[i]).abs() < 1e-13 * (1.0 + xd[i].abs()),
                    "round {round}, {i}: {} vs {}",
                    xb[i],
                    xd[i]
                );
            }
            // one ball row now sees border column 3
            j[(4, nb0 + 3)] = 0.7;
        }
    }

    /// The unrolled fixed-size block path (3, 5 and 9 states per ball) gives the same bits as
    /// the run-time-size path it replaces.
    #[test]
    fn fixed_block_size_is_bit_identical_to_dynamic() {
        for s in [3usize, 5, 9] {
            let (nb, m) = (7, 4);
            let n = nb * s + m;
            let mut seed = 0x2545_F491_4F6C_DD1Du64 ^ s as u64;
            let mut j = DMatrix::zeros(n, n);
            for c in 0..n {
                for r in 0..n {
                    let same_block = r < nb * s && c < nb * s && r / s == c / s;
                    if same_block || r >= nb * s || c >= nb * s {
                        j[(r, c)] = 3.0 * rng(&mut seed);
                    }
                }
            }
            let b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
            let (mut fixed, mut dynamic) =
                (BlockArrowhead::new(nb, s, m), BlockArrowhead::new(nb, s, m));
            assert!(fixed.factor(1.7, &j));
            assert!(dynamic.factor_blocks(Dynamic(s), 1.7, &j));
            let (mut xf, mut xd) = (b.clone(), b);
            fixed.solve(&mut xf);
            dynamic.solve_blocks(Dynamic(s), &mut xd);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&fixed.d), bits(&dynamic.d));
            assert_eq!(bits(&fixed.schur), bits(&dynamic.schur));
            assert_eq!(bits(&xf), bits(&xd), "s = {s}");
        }
    }
}
