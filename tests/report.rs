//! Work-precision machinery: the errors it reports behave as the integrators' theory says
//! (convergence as rtol falls, tolerance proportionality), the two references agree, and
//! the reference cache gives back exactly what was stored.

use raceway::component::Method;
use raceway::report::work_precision::{
    self as wp, cache_path, reference_run, references, time_at_error, Case, Config,
};
use raceway::report::{force_error, Samples};
use std::path::PathBuf;

/// The study's 2-DOF ring case over a shorter window (debug builds run the tests).
fn case() -> Case {
    let mut c = wp::cases()
        .into_iter()
        .find(|c| c.name == "6205-2dof")
        .unwrap();
    c.t_end = 0.01;
    c
}

fn tmp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("raceway-report-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn config(tag: &str) -> Config {
    Config {
        cases: vec![case()],
        cache_dir: tmp(tag),
        ..Config::default()
    }
}

fn errors(cfg: &Config, method: Method, rtols: &[f64]) -> Vec<f64> {
    let c = case();
    let refs = references(cfg, &c).unwrap();
    rtols
        .iter()
        .map(|&r| {
            force_error(&c.run(method, r).unwrap().0, &refs.primary)
                .unwrap()
                .0
        })
        .collect()
}

/// DOPRI5 at 1e-12 and RODAS4 at 1e-11 are different methods with different error
/// estimators; if both are converged their forces agree far below 1e-6.
#[test]
fn the_two_references_agree_to_better_than_1e_6() {
    let cfg = config("refs");
    let r = references(&cfg, &case()).unwrap();
    assert!(r.floor_l2 < 1e-6, "L2 floor {:.3e}", r.floor_l2);
    assert!(r.floor_peak < 1e-6, "peak floor {:.3e}", r.floor_peak);
    assert!(r.floor_l2 > 0.0, "two methods cannot agree to the bit");
}

/// For each method the force error falls as rtol falls: each decade of rtol never
/// increases the error by more than a factor 3, and four decades buy at least two.
#[test]
fn error_decreases_as_rtol_decreases_for_each_method() {
    let cfg = config("mono");
    let rtols = [1e-3, 1e-4, 1e-5, 1e-6, 1e-7];
    for m in [Method::Dopri5, Method::Rosenbrock] {
        let e = errors(&cfg, m, &rtols);
        for w in e.windows(2) {
            assert!(w[1] < 3.0 * w[0], "{m:?}: {e:?}");
        }
        assert!(e[4] < 1e-2 * e[0], "{m:?}: {e:?}");
    }
}

/// Tolerance proportionality (Hairer, Nørsett & Wanner I, §II.4): the achieved error
/// follows `C rtol^p` with `p` near 1 for a well-calibrated controller; a least-squares
/// slope in log-log between 0.5 and 1.5 over four decades.
#[test]
fn tolerance_proportionality_roughly_holds() {
    let cfg = config("prop");
    let rtols = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
    for m in [Method::Dopri5, Method::Rosenbrock] {
        let e = errors(&cfg, m, &rtols);
        let xs: Vec<f64> = rtols.iter().map(|r| r.log10()).collect();
        let ys: Vec<f64> = e.iter().map(|r| r.log10()).collect();
        let (mx, my) = (xs.iter().sum::<f64>() / 5.0, ys.iter().sum::<f64>() / 5.0);
        let slope = xs
            .iter()
            .zip(&ys)
            .map(|(x, y)| (x - mx) * (y - my))
            .sum::<f64>()
            / xs.iter().map(|x| (x - mx).powi(2)).sum::<f64>();
        eprintln!("{m:?}: slope {slope:.2}, {e:?}");
        assert!(
            (0.5..=1.5).contains(&slope),
            "{m:?}: slope {slope:.2}, {e:?}"
        );
        // Calibration: the force error is within three decades above and two below the
        // tolerance asked for (forces amplify displacement errors: `Q ~ delta^1.5` with the
        // approach `delta` a fraction of the displacement, and the impact timing is sensitive).
        for (r, x) in rtols.iter().zip(&e) {
            assert!(
                *x < 1e3 * r && *x > 1e-2 * r,
                "{m:?}: rtol {r:e} gave {x:.2e}"
            );
        }
    }
}

/// The cache stores what the run computed and gives it back to the bit; its key changes
/// with the scene and the tolerance.
#[test]
fn reference_cache_round_trips_exactly() {
    let dir = tmp("cache");
    let c = case();
    let p = cache_path(&dir, &c, Method::Dopri5, 1e-9).unwrap();
    let _ = std::fs::remove_file(&p);
    let first = reference_run(&dir, &c, Method::Dopri5, 1e-9).unwrap();
    assert!(p.exists());
    let direct = c.run(Method::Dopri5, 1e-9).unwrap().0;
    let cached = reference_run(&dir, &c, Method::Dopri5, 1e-9).unwrap();
    let bits = |s: &Samples| -> Vec<u64> {
        s.t.iter()
            .chain(s.f.iter().flatten())
            .map(|v| v.to_bits())
            .collect()
    };
    assert_eq!(bits(&first), bits(&direct), "the run is deterministic");
    assert_eq!(
        bits(&cached),
        bits(&direct),
        "the cache gives back the same bits"
    );
    assert_eq!(Samples::from_csv(&direct.to_csv()).unwrap(), direct);
    // Different tolerance or scene: different file.
    assert_ne!(p, cache_path(&dir, &c, Method::Dopri5, 1e-10).unwrap());
    let mut other = c.clone();
    other.scene = other.scene.replace("3000.0", "2000.0");
    assert_ne!(p, cache_path(&dir, &other, Method::Dopri5, 1e-9).unwrap());
    // A corrupt cache file is recomputed, not trusted.
    std::fs::write(&p, "t,fx,fy,fz\n1,2,x,4\n").unwrap();
    let again = reference_run(&dir, &c, Method::Dopri5, 1e-9).unwrap();
    assert_eq!(bits(&again), bits(&direct));
}

/// The metric: zero for identical series, scale-free, and refused for mismatched times.
#[test]
fn force_error_metric_is_relative_and_checks_times() {
    let a = Samples {
        t: vec![1.0, 2.0],
        f: vec![[3.0, 4.0, 0.0], [0.0, 0.0, 5.0]],
    };
    assert_eq!(force_error(&a, &a).unwrap(), (0.0, 0.0));
    let mut b = a.clone();
    b.f[1][2] = 5.5;
    let (l2, peak) = force_error(&b, &a).unwrap();
    assert!((l2 - (0.25f64 / 50.0).sqrt()).abs() < 1e-15);
    assert!((peak - 0.1).abs() < 1e-15);
    let scaled = |s: &Samples| Samples {
        t: s.t.clone(),
        f: s.f.iter().map(|f| f.map(|x| 1e3 * x)).collect(),
    };
    let (l2s, _) = force_error(&scaled(&b), &scaled(&a)).unwrap();
    assert!((l2s - l2).abs() < 1e-15);
    let mut c = a.clone();
    c.t[1] = 2.5;
    assert!(force_error(&c, &a).is_err());
}

/// Log-log interpolation of a work-precision line: exact on a power law, `None` outside.
#[test]
fn time_at_error_interpolates_power_laws() {
    let curve: Vec<(f64, f64)> = (0..5)
        .map(|k| {
            let e = 10f64.powi(-k - 3);
            (e, 2.0 * e.powf(-0.2))
        })
        .collect();
    let t = time_at_error(&curve, 3e-5).unwrap();
    assert!((t - 2.0 * 3e-5f64.powf(-0.2)).abs() < 1e-12 * t);
    assert!(time_at_error(&curve, 1e-1).is_none());
}

/// The SciPy peer integrates the same equations: its solution converges to raceway's
/// reference (Radau and LSODA at rtol 1e-4 land within 1e-2 of it). Needs Python and
/// network for the venv: `cargo test --test report -- --ignored peer`.
#[test]
#[ignore]
fn scipy_peer_solves_the_same_model() {
    let cfg = config("peer");
    let dir = cfg.cache_dir.clone();
    wp::export_for_peer(&cfg, &case(), &dir).unwrap();
    let root = env!("CARGO_MANIFEST_DIR");
    let ok = std::process::Command::new(format!("{root}/scripts/peer-scipy"))
        .arg(&dir)
        .arg("--smoke")
        .status()
        .unwrap()
        .success();
    assert!(ok, "scripts/peer-scipy failed");
    let rows =
        wp::read_peer_csv(&std::fs::read_to_string(dir.join("6205-2dof-scipy.csv")).unwrap())
            .unwrap();
    assert_eq!(rows.len(), 2);
    for r in rows {
        assert!(r.err_l2 > 0.0 && r.err_l2 < 1e-2, "{r:?}");
    }
}
