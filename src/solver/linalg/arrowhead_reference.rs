//! The block-arrowhead factor and solve as they were before their loops were reordered
//! (each border entry's updates running over one block's states, contiguous), kept to
//! check that the reordered path gives the same bits.

use super::*;

/// The old storage: `c` holds each block's `C_i` column-major `m_c × s`.
struct OldArrowhead {
    h: usize,
    nb: usize,
    m: usize,
    xr: Vec<f64>,
    d: Vec<f64>,
    lu: Vec<f64>,
    dpiv: Vec<usize>,
    g: Vec<f64>,
    c: Vec<f64>,
    schur: Vec<f64>,
    spiv: Vec<usize>,
    g_cols: Vec<usize>,
    c_rows: Vec<usize>,
    border: Vec<f64>,
}

impl OldArrowhead {
    fn with_head(h: usize, nb: usize, s: usize, m: usize) -> Self {
        OldArrowhead {
            h,
            nb,
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
            border: vec![0.0; m * m],
        }
    }
}

impl OldArrowhead {
    #[inline(always)]
    fn factor_blocks<B: BlockSize>(&mut self, bs: B, sigma: f64, jac: &DMatrix<f64>) -> bool {
        let (h, nb, s, m) = (self.h, self.nb, bs.get(), self.m);
        let nb0 = nb * s;
        debug_assert_eq!(jac.shape(), (nb0 + m, nb0 + m));
        // column-major storage: entry (i, j) at j * nn + i
        let (ja, nn) = (jac.as_slice(), nb0 + m);
        // The state index of border state `r`: the head's first, then the tail's.
        let bi = |r: usize| if r < h { r } else { nb0 + r };
        // The border's pattern: rows with some C entry, columns with some B entry (each a
        // contiguous run of J's storage).
        self.c_rows.clear();
        self.g_cols.clear();
        for r in 0..m {
            if (h..h + nb0).any(|k| ja[k * nn + bi(r)] != 0.0) {
                self.c_rows.push(r);
            }
        }
        for j in 0..m {
            if ja[bi(j) * nn + h..bi(j) * nn + h + nb0]
                .iter()
                .any(|v| *v != 0.0)
            {
                self.g_cols.push(j);
            }
        }
        let (mc, mg) = (self.c_rows.len(), self.g_cols.len());
        // E into the Schur storage
        for j in 0..m {
            for i in 0..m {
                let v = -ja[bi(j) * nn + bi(i)];
                self.schur[j * m + i] = if i == j { v + sigma } else { v };
            }
        }
        // The part of S the blocks update (rows `c_rows`, columns `g_cols`), gathered
        // (column-major `m_c × m_g`); each entry gets the same subtractions in the same
        // order as in place.
        let sc = &mut self.border[..mc * mg];
        for (jj, &j) in self.g_cols.iter().enumerate() {
            for (ii, &i) in self.c_rows.iter().enumerate() {
                sc[jj * mc + ii] = self.schur[j * m + i];
            }
        }
        for b in 0..nb {
            let o = h + b * s;
            let lu = &mut self.lu[..s * s];
            for j in 0..s {
                for i in 0..s {
                    let v = -ja[(o + j) * nn + o + i];
                    lu[j * s + i] = if i == j { v + sigma } else { v };
                }
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
                lu_solve(lu, s, piv, col);
            }
            if !d.iter().all(|v| v.is_finite()) {
                return false;
            }
            // G_b = D_b⁻¹ B_b, column by column (its non-zero columns)
            let g = &mut self.g[b * s * mg..(b + 1) * s * mg];
            for (jj, &j) in self.g_cols.iter().enumerate() {
                let col = &mut g[jj * s..(jj + 1) * s];
                col.fill(0.0);
                for k in 0..s {
                    let bkj = -ja[bi(j) * nn + o + k];
                    if bkj != 0.0 {
                        for (v, dv) in col.iter_mut().zip(&d[k * s..(k + 1) * s]) {
                            *v += dv * bkj;
                        }
                    }
                }
            }
            // C_b (its non-zero rows) and S -= C_b G_b (on the gathered part of S)
            let c = &mut self.c[b * mc * s..(b + 1) * mc * s];
            for j in 0..s {
                for (ii, &i) in self.c_rows.iter().enumerate() {
                    c[j * mc + ii] = -ja[(o + j) * nn + bi(i)];
                }
            }
            for jj in 0..mg {
                let sj = &mut sc[jj * mc..(jj + 1) * mc];
                for k in 0..s {
                    let gkj = g[jj * s + k];
                    if gkj != 0.0 {
                        let ck = &c[k * mc..(k + 1) * mc];
                        for (sv, cv) in sj.iter_mut().zip(ck) {
                            *sv -= cv * gkj;
                        }
                    }
                }
            }
        }
        // The updated part of S back in place.
        for (jj, &j) in self.g_cols.iter().enumerate() {
            for (ii, &i) in self.c_rows.iter().enumerate() {
                self.schur[j * m + i] = sc[jj * mc + ii];
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
        for b in 0..nb {
            let z = &mut xb[b * s..(b + 1) * s];
            let d = &self.d[b * s * s..(b + 1) * s * s];
            // z = D_b⁻¹ z
            let r = &mut self.lu[..s];
            r.copy_from_slice(z);
            z.fill(0.0);
            for (k, &rk) in r.iter().enumerate() {
                for (zi, dv) in z.iter_mut().zip(&d[k * s..(k + 1) * s]) {
                    *zi += dv * rk;
                }
            }
            let c = &self.c[b * mc * s..(b + 1) * mc * s];
            for (k, zk) in z.iter().enumerate() {
                let ck = &c[k * mc..(k + 1) * mc];
                for (v, cv) in xc.iter_mut().zip(ck) {
                    *v -= cv * zk;
                }
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
            for (jj, &xj) in xg.iter().enumerate() {
                for (zi, gv) in z.iter_mut().zip(&g[jj * s..(jj + 1) * s]) {
                    *zi -= gv * xj;
                }
            }
        }
        head.copy_from_slice(&xr[..h]);
        tail.copy_from_slice(&xr[h..]);
    }
}

/// Deterministic pseudo-random numbers in [-1, 1] (xorshift).
fn rng(seed: &mut u64) -> f64 {
    *seed ^= *seed << 13;
    *seed ^= *seed >> 7;
    *seed ^= *seed << 17;
    (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

/// The reordered factor and solve give the old path's bits: the Schur complement's LU, the
/// blocks' inverses and the solutions of several right-hand sides (zeros among them), for
/// every block size the solver unrolls (3, 5, 9) and a run-time one (4), with and without
/// a head, on Jacobians with the skidding level's pattern: zero border rows and columns,
/// zeros (`+0`, whose `W` entry is `-0`) inside the blocks and their borders, a block
/// that does not see a border column the others see.
#[test]
fn reordered_block_arrowhead_is_the_old_path_bit_for_bit() {
    let mut seed = 0x0DDB_1A5E_5BAD_5EEDu64;
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    for (h, s) in [(0, 3), (0, 5), (2, 9), (0, 4), (3, 3)] {
        let (nb, m) = (6, 7);
        let (nb0, n) = (nb * s, nb * s + m);
        let in_blocks = |i: usize| i >= h && i < h + nb0;
        let mut j = DMatrix::zeros(n, n);
        for c in 0..n {
            for r in 0..n {
                let same_block = in_blocks(r) && in_blocks(c) && (r - h) / s == (c - h) / s;
                let border = !in_blocks(r) || !in_blocks(c);
                // border row 1 and border column 2 do not couple to the blocks
                let br = |i: usize| if i < h { i } else { i - nb0 };
                let zero_row = !in_blocks(r) && in_blocks(c) && br(r) == 1;
                let zero_col = in_blocks(r) && !in_blocks(c) && br(c) == 2;
                // the first block does not see border column 3 (its G column is zero: the
                // Schur update skips it)
                let zero_first = in_blocks(r) && (r - h) / s == 0 && !in_blocks(c) && br(c) == 3;
                let v = 1e3 * rng(&mut seed);
                // about one entry in five exactly zero
                if (same_block || border)
                    && !zero_row
                    && !zero_col
                    && !zero_first
                    && v.abs() > 200.0
                {
                    j[(r, c)] = v;
                }
            }
        }
        for sigma in [1e2, 3e4] {
            let mut new = BlockArrowhead::with_head(h, nb, s, m);
            let mut old = OldArrowhead::with_head(h, nb, s, m);
            let ok_new = new.factor(sigma, &j);
            let ok_old = match s {
                3 => old.factor_blocks(Fixed::<3>, sigma, &j),
                5 => old.factor_blocks(Fixed::<5>, sigma, &j),
                9 => old.factor_blocks(Fixed::<9>, sigma, &j),
                _ => old.factor_blocks(Dynamic(s), sigma, &j),
            };
            assert!(ok_new && ok_old, "h {h}, s {s}");
            assert_eq!((&new.c_rows, &new.g_cols), (&old.c_rows, &old.g_cols));
            assert!(
                new.c_rows.len() < m && new.g_cols.len() < m,
                "skipped border"
            );
            assert_eq!(bits(&new.d), bits(&old.d), "h {h}, s {s}");
            assert_eq!(bits(&new.schur), bits(&old.schur), "h {h}, s {s}");
            for trial in 0..4 {
                let mut b: Vec<f64> = (0..n).map(|_| rng(&mut seed)).collect();
                if trial % 2 == 1 {
                    for v in b.iter_mut().step_by(3) {
                        *v = 0.0;
                    }
                }
                let (mut xn, mut xo) = (b.clone(), b);
                new.solve(&mut xn);
                match s {
                    3 => old.solve_blocks(Fixed::<3>, &mut xo),
                    5 => old.solve_blocks(Fixed::<5>, &mut xo),
                    9 => old.solve_blocks(Fixed::<9>, &mut xo),
                    _ => old.solve_blocks(Dynamic(s), &mut xo),
                }
                assert_eq!(bits(&xn), bits(&xo), "h {h}, s {s}, trial {trial}");
            }
        }
    }
}
