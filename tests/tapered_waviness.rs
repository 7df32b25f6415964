//! Cup (outer) and cone (inner) waviness on a tapered roller bearing at the ring level, per
//! lamina (docs/physics.md §R12): the raceway's deviation moves every lamina's approach along
//! the cup normal by the same amount.

use raceway::analysis::{amplitude_spectrum, Window};
use raceway::component::{variables, Component};
use raceway::contact::tapered_law::TaperedRollerLaw;
use raceway::geometry::kinematics::kinematics;
use raceway::geometry::{roller_catalogue, Bearing};
use raceway::seam::element::ElementDisplacement;

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

/// 30206 on the ring level (`dof` 2 or 5), motion-driven at 1500 rpm, the cone held at
/// `(y, z)` (m; `+z` loads it), with `effects` (empty: none).
fn scene(dof: u8, y: f64, z: f64, effects: &str) -> String {
    let fx = if effects.is_empty() {
        String::new()
    } else {
        format!("\n[effects]\n{effects}\n")
    };
    format!(
        "title = \"30206 waviness\"\nbearing = \"30206\"\n\n[model]\nlevel = \"ring\"\ncausality = \"motion\"\nring_dof = {dof}\n\n\
         [inputs]\nrule = \"velocity\"\nspeed_rpm = 1500.0\ninitial = {{ \"shaft.y\" = {y:e}, \"shaft.z\" = {z:e} }}\n{fx}\n\
         [run]\nduration_s = 0.5\nstep_s = 1e-4\n"
    )
}

/// `names` at each of `n` steps of 0.1 ms.
fn history<const N: usize>(text: &str, n: usize, names: [&str; N]) -> Vec<[f64; N]> {
    let mut c = Component::from_text(text).unwrap();
    let h = 1e-4;
    (0..n)
        .map(|i| {
            c.do_step(i as f64 * h, h).unwrap();
            names.map(|v| c.get_real(vr(v)).unwrap())
        })
        .collect()
}

fn bits<const N: usize>(h: &[[f64; N]]) -> Vec<[u64; N]> {
    h.iter().map(|r| r.map(f64::to_bits)).collect()
}

/// Cup or cone waviness of amplitude 0 takes nothing away: 1000 steps (0.1 s, 14 roller
/// passes on the cup) are the healthy run bit for bit; 0.5 µm changes them.
#[test]
fn waviness_of_zero_amplitude_reproduces_the_healthy_run_bit_for_bit() {
    let n = 1000;
    let names = ["force.x", "force.y", "force.z"];
    let healthy = bits(&history(&scene(2, -10e-6, 20e-6, ""), n, names));
    for race in ["outer", "inner"] {
        let fx = |a: f64| {
            format!(
                r#"waviness = [{{ race = "{race}", order = 5, amplitude_um = {a:?}, phase_deg = 30.0 }}]"#
            )
        };
        let zero = bits(&history(&scene(2, -10e-6, 20e-6, &fx(0.0)), n, names));
        assert_eq!(healthy, zero, "{race}");
        let wavy = bits(&history(&scene(2, -10e-6, 20e-6, &fx(0.5)), n, names));
        assert_ne!(healthy, wavy, "{race}");
    }
}

/// Least-squares amplitude of the sine at `f` (Hz) in `x` sampled at `fs`, with a constant.
fn fitted_amplitude(x: &[f64], fs: f64, f: f64) -> f64 {
    // Normal equations of [1, sin, cos].
    let mut a = [[0.0; 3]; 3];
    let mut b = [0.0; 3];
    for (i, &v) in x.iter().enumerate() {
        let w = 2.0 * std::f64::consts::PI * f * i as f64 / fs;
        let g = [1.0, w.sin(), w.cos()];
        for r in 0..3 {
            for c in 0..3 {
                a[r][c] += g[r] * g[c];
            }
            b[r] += g[r] * v;
        }
    }
    // Gaussian elimination (3×3, well conditioned over many periods).
    for c in 0..3 {
        for r in c + 1..3 {
            let m = a[r][c] / a[c][c];
            let pivot = a[c];
            for (x, p) in a[r].iter_mut().zip(pivot).skip(c) {
                *x -= m * p;
            }
            b[r] -= m * b[c];
        }
    }
    let mut s = [0.0; 3];
    for r in (0..3).rev() {
        let t: f64 = (r + 1..3).map(|k| a[r][k] * s[k]).sum();
        s[r] = (b[r] - t) / a[r][r];
    }
    s[1].hypot(s[2])
}

/// 30206 pushed 20 µm along `+z` alone (every roller loaded alike: the healthy axial force is
/// constant) at 1500 rpm, 5 DOF. A waviness of order `k = Z` (14) puts every roller on the
/// same phase of it: on the cup (`theta = psi_j`) the rollers meet `k` lobes per cage
/// revolution, so the axial force oscillates at `k FTF = Z FTF = BPFO` (143.63 Hz, the
/// roller-pass frequency on the cup, with the roller's `gamma = Dwe cos(alpha)/Dpw`); on the
/// cone (`theta = psi_j - theta_s`) at `k (f_s - FTF) = BPFI` (206.37 Hz). The line is the
/// spectrum's largest and lies within a bin of the expected frequency, and its amplitude is
/// the linear one, `Z sin(alpha) (dQ/d delta) A` (every lamina's approach along the cup normal
/// moved by `A`), within 0.1 % (measured 2e-5): `dQ/d delta` of one roller by central differences of the law.
#[test]
fn a_wavy_cup_or_cone_of_order_z_rings_at_bpfo_or_bpfi() {
    let r = roller_catalogue::lookup("30206").unwrap().build().unwrap();
    let (z, alpha) = (r.z, r.alpha);
    let law = TaperedRollerLaw::new(&r).unwrap().massless();
    let b = Bearing::from_roller(r).unwrap();
    let k = kinematics(&b, 1500.0 * std::f64::consts::PI / 30.0);
    assert_eq!(z, 14);
    let z0 = 20e-6;
    let amp = 0.1e-6;
    // dQ/d delta at the roller's approach: delta = sin(alpha) axial at zero radial play
    // shift, so d/d delta = (1/sin alpha) d/d axial.
    let ns = law.laminae().len();
    let q = |ax: f64| {
        let mut l = vec![0.0; ns];
        let u = ElementDisplacement {
            axial: ax,
            radial: 0.0,
            tilt: 0.0,
        };
        law.lamina_loads(u, &mut l)
    };
    let h = 1e-9;
    let dq = (q(z0 + h) - q(z0 - h)) / (2.0 * h) / alpha.sin();
    let want = z as f64 * alpha.sin() * dq * amp;
    let n = 4000;
    let fs = 1e4;
    let healthy = history(&scene(5, 0.0, z0, ""), n, ["force.z"]);
    let hz: Vec<f64> = healthy.iter().map(|r| r[0]).collect();
    let spread = hz.iter().fold(0.0f64, |m, v| m.max((v - hz[0]).abs()));
    assert!(
        spread < 1e-9 * hz[0].abs(),
        "healthy axial force varies by {spread} N"
    );
    for (race, f) in [("outer", k.bpfo), ("inner", k.bpfi)] {
        let fx = format!(
            r#"waviness = [{{ race = "{race}", order = {z}, amplitude_um = {:?} }}]"#,
            amp * 1e6
        );
        let x: Vec<f64> = history(&scene(5, 0.0, z0, &fx), n, ["force.z"])
            .iter()
            .map(|r| r[0])
            .collect();
        let s = amplitude_spectrum(&x, fs, Window::Hann);
        let df = s.resolution();
        let (found, a) = s.peak_in(0.5 * df, 0.5 * fs).unwrap();
        assert!(
            (found - f).abs() < df,
            "{race}: the largest line at {found:.2} Hz, expected {f:.2} Hz (bin {df} Hz), {a} N"
        );
        let got = fitted_amplitude(&x, fs, f);
        eprintln!(
            "{race}: line at {found:.2} Hz (expected {f:.2}), amplitude {got:.2} N, linear \
             {want:.2} N, relative gap {:.0e}",
            (got / want - 1.0).abs()
        );
        assert!(
            (got / want - 1.0).abs() < 1e-3,
            "{race}: amplitude {got} N, linear {want} N"
        );
    }
}
