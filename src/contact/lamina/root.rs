//! `d^(1/9)` for the lamina law: tables made at compile time and a short series
//! (docs/physics.md §R1).

/// `y^(1/9)` of `y >= 1` at compile time (Newton on `x^9 = y` from above, run to a fixed
/// point; only the arithmetic a `const fn` may do).
pub(super) const fn const_ninth_root(y: f64) -> f64 {
    let mut x = if y > 2.0 {
        y / 9.0 + 1.0
    } else {
        1.0 + (y - 1.0) / 9.0 + 1e-3
    };
    let mut k = 0;
    while k < 200 {
        let x2 = x * x;
        let x4 = x2 * x2;
        let x8 = x4 * x4;
        let next = (8.0 * x + y / x8) / 9.0;
        if next >= x {
            break;
        }
        x = next;
        k += 1;
    }
    x
}

/// Cells of the mantissa in [`ninth_root`]: 64, so `|t| < 1/128`.
pub(super) const CELLS: usize = 64;

/// `(c_i, c_i^(1/9), 1/c_i)` for the cell centres `c_i = 1 + (i + 1/2)/64` of `[1, 2)`.
pub(super) const CELL_ROOT: [(f64, f64, f64); CELLS] = {
    let mut t = [(0.0, 0.0, 0.0); CELLS];
    let mut i = 0;
    while i < CELLS {
        let c = 1.0 + (i as f64 + 0.5) / CELLS as f64;
        t[i] = (c, const_ninth_root(c), 1.0 / c);
        i += 1;
    }
    t
};

/// `2^(r/9)`, `r = 0..8`.
pub(super) const TWO_NINTHS: [f64; 9] = {
    let mut t = [0.0; 9];
    let mut r = 0;
    let mut p = 1.0;
    while r < 9 {
        t[r] = const_ninth_root(p);
        p *= 2.0;
        r += 1;
    }
    t
};

/// `2^q 2^(r/9)` for every biased exponent `E` of a positive normal `d` (`E - 1023 = 9 q +
/// r`, `r = 0..8`; index `E`, 0 unused): [`ninth_root`]'s exponent factor in one load. Each
/// entry is `TWO_NINTHS[r]` scaled by a power of two (exact), so the root's bits are those of
/// forming `2^q` and `2^(r/9)` apart.
pub(super) const EXPONENT_ROOT: [f64; 2047] = {
    let mut t = [0.0; 2047];
    let mut e = 1;
    while e < 2047 {
        let e3 = e as u64 + 3;
        let (n, r) = (e3 / 9, e3 % 9);
        t[e] = f64::from_bits((n + 909) << 52) * TWO_NINTHS[r as usize];
        e += 1;
    }
    t
};

/// Binomial coefficients of `(1 + t)^(1/9)`, `a_n = C(1/9, n)`, `n = 0..6`.
pub(super) const BINOMIAL: [f64; 7] = {
    let mut a = [0.0; 7];
    a[0] = 1.0;
    let mut n = 1;
    while n < 7 {
        a[n] = a[n - 1] * (1.0 / 9.0 - (n - 1) as f64) / n as f64;
        n += 1;
    }
    a
};

/// `d^(1/9)` for `d > 0`, the lamina law's root, in about 25 instructions against `powf`'s
/// hundred: with `d = 2^(9q + r) m`, `m` in `[1, 2)` near the cell centre `c_i`,
/// `d^(1/9) = 2^q 2^(r/9) c_i^(1/9) (1 + t)^(1/9)`, `t = (m - c_i)/c_i` (`|t| < 1/128`; the
/// binomial series to `t^6` leaves under `3e-17`); within a few units in the last place of
/// `powf(d, 1/9)` (`ninth_root_matches_powf`). Zero, subnormal, infinite or NaN `d` take
/// `powf`.
#[inline]
pub(super) fn ninth_root(d: f64) -> f64 {
    let bits = d.to_bits();
    // Positive, normal and finite exactly when the bits lie in [MIN_POSITIVE's, INFINITY's)
    // (a negative number's sign bit puts it above): one unsigned comparison.
    const MIN_NORMAL: u64 = 0x0010_0000_0000_0000;
    if bits.wrapping_sub(MIN_NORMAL) >= 0x7ff0_0000_0000_0000 - MIN_NORMAL {
        return d.powf(1.0 / 9.0);
    }
    let m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    let (c, ci9, inv_c) = CELL_ROOT[((bits >> 46) & (CELLS as u64 - 1)) as usize];
    let t = (m - c) * inv_c;
    let a = &BINOMIAL;
    let poly = a[0] + t * (a[1] + t * (a[2] + t * (a[3] + t * (a[4] + t * (a[5] + t * a[6])))));
    // The biased exponent E (1..=2046, d > 0 and normal): E - 1023 = 9 (n - 114) + r with
    // E + 3 = 9 n + r, so 2^q has the biased exponent n - 114 + 1023; `EXPONENT_ROOT[E]` is
    // `2^q 2^(r/9)`. `(2^q 2^(r/9)) c` and `2^q (2^(r/9) c)` round alike (a power of two
    // scales exactly in the normal range, and the roots of normal numbers stay far inside
    // it).
    EXPONENT_ROOT[(bits >> 52) as usize] * ci9 * poly
}
