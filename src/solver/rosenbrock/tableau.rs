//! Tableaux as data: RODAS4's coefficients (Hairer & Wanner's code RODAS, `METH = 1`) and
//! ROS34PW2's (Rang & Angermann 2005) with its W-method constants and their transformation
//! to the stage form the stepper runs (docs/physics.md §N2.4).

pub(super) const GAMMA: f64 = 0.25;
pub(super) const C2: f64 = 0.386;
pub(super) const C3: f64 = 0.21;
pub(super) const C4: f64 = 0.63;
pub(super) const D1: f64 = 0.25;
pub(super) const D2: f64 = -0.1043;
pub(super) const D3: f64 = 0.1035;
pub(super) const D4: f64 = -0.362_000_000_000_002_3e-1;
pub(super) const A21: f64 = 1.544;
pub(super) const A31: f64 = 0.946_678_528_081_582_6;
pub(super) const A32: f64 = 0.255_701_169_898_328_4;
pub(super) const A41: f64 = 3.314_825_187_068_521;
pub(super) const A42: f64 = 2.896_124_015_972_201;
pub(super) const A43: f64 = 0.998_641_913_997_781_7;
pub(super) const A51: f64 = 1.221_224_509_226_641;
pub(super) const A52: f64 = 6.019_134_481_288_629;
pub(super) const A53: f64 = 12.537_083_329_320_87;
pub(super) const A54: f64 = -0.687_886_036_105_895;
pub(super) const C21: f64 = -5.6688;
pub(super) const C31: f64 = -2.430_093_356_833_875;
pub(super) const C32: f64 = -0.206_359_915_709_191_5;
pub(super) const C41: f64 = -0.107_352_905_815_137_5;
pub(super) const C42: f64 = -9.594_562_251_023_355;
pub(super) const C43: f64 = -20.470_286_148_096_16;
pub(super) const C51: f64 = 7.496_443_313_967_647;
pub(super) const C52: f64 = -10.246_804_314_643_52;
pub(super) const C53: f64 = -33.999_903_528_199_05;
pub(super) const C54: f64 = 11.708_908_932_061_6;
pub(super) const C61: f64 = 8.083_246_795_921_522;
pub(super) const C62: f64 = -7.981_132_988_064_893;
pub(super) const C63: f64 = -31.521_594_328_743_71;
pub(super) const C64: f64 = 16.319_305_431_231_36;
pub(super) const C65: f64 = -6.058_818_238_834_054;
// dense output (3rd order), same source
pub(super) const H21: f64 = 10.126_235_083_445_86;
pub(super) const H22: f64 = -7.487_995_877_610_167;
pub(super) const H23: f64 = -34.800_918_615_557_47;
pub(super) const H24: f64 = -7.992_771_707_568_823;
pub(super) const H25: f64 = 1.025_137_723_295_662;
pub(super) const H31: f64 = -0.676_280_339_280_125_3;
pub(super) const H32: f64 = 6.087_714_651_680_015;
pub(super) const H33: f64 = 16.430_843_208_924_78;
pub(super) const H34: f64 = 24.767_225_114_183_86;
pub(super) const H35: f64 = -6.594_389_125_716_872;

/// Stages of ROS34PW2.
pub(super) const W_STAGES: usize = 4;
/// W-method: most accepted steps on one Jacobian (a rejection refreshes it sooner).
pub const W_JAC_MAX_AGE: u32 = 10;
/// W-method: a proposed step growth up to this factor keeps the step and its LU.
pub(super) const W_HOLD: f64 = 1.2;
/// W-method: a rejected step refreshes `J` only when `J` has carried more than this many
/// accepted steps. Skidding 7008CE at 24 000 rpm, 0.01 s in 0.1 ms communication steps,
/// with [`W_SPLIT`]: 313 Jacobians to 174, 322.5 M to 278.4 M instructions (callgrind).
pub const W_REJECT_KEEP: u32 = 2;
/// W-method: when the rest of a call is under this many proposed steps (and more than
/// one), it is taken in two equal steps.
pub const W_SPLIT: f64 = 2.0;

/// ROS34PW2 as published (Rang & Angermann 2005, the W-method "ROS34PW2" of their
/// Table 3.2): `γ`, the strictly lower `α`, the full lower `Γ` (diagonal `γ`), weights `b`
/// and embedded weights `b̂`. Stiffly accurate: `b_j = α_4j + Γ_4j`. (The digits as
/// published, some beyond `f64`.)
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_GAMMA: f64 = 4.358_665_215_084_590e-1;
/// `α_ij`, `j < i`.
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_ALPHA: [[f64; 4]; 4] = [
    [0.0; 4],
    [8.717_330_430_169_180_1e-1, 0.0, 0.0, 0.0],
    [
        8.445_706_001_536_942_3e-1,
        -1.129_906_423_648_418_5e-1,
        0.0,
        0.0,
    ],
    [0.0, 0.0, 1.0, 0.0],
];
/// `Γ_ij`, `j <= i`.
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_GAMMA_MATRIX: [[f64; 4]; 4] = [
    [ROS34PW2_GAMMA, 0.0, 0.0, 0.0],
    [-8.717_330_430_169_180_1e-1, ROS34PW2_GAMMA, 0.0, 0.0],
    [
        -9.033_805_701_304_408_2e-1,
        5.418_067_238_809_532_6e-2,
        ROS34PW2_GAMMA,
        0.0,
    ],
    [
        2.421_238_070_609_534_6e-1,
        -1.223_250_583_904_514_7,
        5.452_602_553_351_021_4e-1,
        ROS34PW2_GAMMA,
    ],
];
/// Weights `b` (order 3).
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_B: [f64; 4] = [
    2.421_238_070_609_534_6e-1,
    -1.223_250_583_904_514_7,
    1.545_260_255_335_102_0,
    ROS34PW2_GAMMA,
];
/// Embedded weights `b̂` (order 2).
#[allow(clippy::excessive_precision)]
pub const ROS34PW2_BHAT: [f64; 4] = [
    3.781_090_314_581_936_9e-1,
    -9.604_229_221_242_317_8e-2,
    0.5,
    2.179_332_607_542_295e-1,
];

/// A 4-stage W-method in the transformed variables `u_i = Σ_j Γ_ij k_j` (Hairer &
/// Wanner II, §IV.7, Eq. 7.16–7.19, as for RODAS4 above).
#[derive(Debug, Clone, PartialEq)]
pub struct WCoeffs {
    /// `γ`.
    pub gamma: f64,
    /// `A = α Γ⁻¹` (strictly lower).
    pub a: [[f64; 4]; 4],
    /// `C = diag(1/γ) − Γ⁻¹` (strictly lower).
    pub cc: [[f64; 4]; 4],
    /// Stage times `c_i = Σ_j α_ij`.
    pub c: [f64; 4],
    /// `d_i = Σ_j Γ_ij` (the `∂f/∂t` weights).
    pub d: [f64; 4],
    /// `m = b Γ⁻¹`.
    pub m: [f64; 4],
    /// Error weights `m − m̂`, `m̂ = b̂ Γ⁻¹`.
    pub e: [f64; 4],
}

impl WCoeffs {
    /// Transformed coefficients of a method given as published (`α`, `Γ`, `b`, `b̂`).
    #[allow(clippy::needless_range_loop)] // the index formulas of the definitions
    pub fn from_published(
        alpha: &[[f64; 4]; 4],
        gam: &[[f64; 4]; 4],
        b: &[f64; 4],
        bhat: &[f64; 4],
    ) -> Self {
        // Γ⁻¹ by forward substitution (lower triangular).
        let mut gi = [[0.0; 4]; 4];
        for col in 0..4 {
            for i in 0..4 {
                let mut v = if i == col { 1.0 } else { 0.0 };
                for k in 0..i {
                    v -= gam[i][k] * gi[k][col];
                }
                gi[i][col] = v / gam[i][i];
            }
        }
        let mut r = WCoeffs {
            gamma: gam[0][0],
            a: [[0.0; 4]; 4],
            cc: [[0.0; 4]; 4],
            c: [0.0; 4],
            d: [0.0; 4],
            m: [0.0; 4],
            e: [0.0; 4],
        };
        for i in 0..4 {
            for j in 0..i {
                r.a[i][j] = (0..4).map(|k| alpha[i][k] * gi[k][j]).sum();
                r.cc[i][j] = -gi[i][j];
            }
            r.c[i] = alpha[i].iter().sum();
            r.d[i] = gam[i].iter().sum();
            let m: f64 = (0..4).map(|k| b[k] * gi[k][i]).sum();
            let mh: f64 = (0..4).map(|k| bhat[k] * gi[k][i]).sum();
            r.m[i] = m;
            r.e[i] = m - mh;
        }
        r
    }

    /// ROS34PW2.
    pub fn ros34pw2() -> Self {
        Self::from_published(
            &ROS34PW2_ALPHA,
            &ROS34PW2_GAMMA_MATRIX,
            &ROS34PW2_B,
            &ROS34PW2_BHAT,
        )
    }
}
