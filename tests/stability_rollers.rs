//! Roller cells of the stability campaign that once failed its convergence test over the
//! long window (docs/physics.md §R9: contact damping ramped in on the mid-length approach),
//! and the contact law's damping approach behind the fix.

use raceway::contact::roller_law::CylindricalRollerLaw;
use raceway::geometry::roller_catalogue::lookup;
use raceway::models::ring::DAMPING_RAMP;
use raceway::report::stability::{self, Cell, Outcome};
use raceway::seam::element::{ElementAt, ElementDisplacement, ElementLaw, Want};

fn at0() -> ElementAt<'static> {
    ElementAt {
        index: 0,
        psi: 0.0,
        sc: (0.0, 1.0),
        q: &[0.0; 5],
    }
}

/// What contact damping ramps in with (`ElementReaction::approach`) is the most compressed
/// lamina's approach: for an edge-loaded tilted roller whose mid-length approach is
/// negative, the largest lamina approach `delta - x_k tan(tilt) - 2P(x_k)` (positive: it is
/// damped; it was left undamped); at 120 000 rpm it is zero where the inner contact closes,
/// while the mid-length approach there is the outer contact's centrifugal compression
/// (micrometres, far past the 0.1 µm ramp, which a ramp on it switched on in one step); with
/// no lamina loaded it is at most zero.
#[test]
fn the_damping_approach_starts_at_the_first_touch() {
    let b = lookup("NU206").unwrap().build().unwrap();
    let l = CylindricalRollerLaw::new(&b).unwrap();
    let lam = l.laminae().clone();
    let half_pd = 0.5 * b.pd;
    let (mid, tilt) = (-2e-6, 3e-3);
    let u = ElementDisplacement {
        axial: 0.0,
        radial: half_pd + mid,
        tilt,
    };
    let lamina_max = |delta: f64, t: f64| {
        lam.x
            .iter()
            .zip(&lam.drop2)
            .map(|(x, d)| delta - x * t - d)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let want = lamina_max(u.radial - half_pd, tilt.tan());
    assert!(want > 1e-6, "{want}");
    let massless = l.clone().massless();
    for r in [
        l.react(at0(), u, 0.0, &mut [], Want::default()).unwrap(),
        massless.react_massless(u, Want::default()),
    ] {
        assert!(r.f[1] < 0.0);
        assert!(
            (r.approach - want).abs() <= 1e-12 * want,
            "{} vs {want}",
            r.approach
        );
    }
    // Aligned: the least-dropped lamina's approach.
    let a = ElementDisplacement {
        radial: half_pd + 1e-6,
        tilt: 0.0,
        ..u
    };
    let r = massless.react_massless(a, Want::default());
    let want = lamina_max(a.radial - half_pd, 0.0);
    assert!(
        (r.approach - want).abs() <= 1e-15,
        "{} vs {want}",
        r.approach
    );
    // Unloaded: at most zero (here the gap itself).
    let gap = ElementDisplacement {
        radial: half_pd - 1e-6,
        ..a
    };
    let g = massless.react_massless(gap, Want::default()).approach;
    assert!(g < 0.0 && (g - (gap.radial - half_pd)).abs() < 1e-18, "{g}");
    // At speed: the inner contact's closing, by bisection on the radial displacement.
    let omega = 120_000.0 * std::f64::consts::PI / 30.0;
    let at = |radial: f64| {
        let u = ElementDisplacement { radial, ..a };
        l.react(at0(), u, omega, &mut [], Want::default()).unwrap()
    };
    let (mut lo, mut hi) = (half_pd, half_pd + 50e-6);
    assert!(at(hi).f[1] < 0.0 && at(lo).f[1] == 0.0);
    for _ in 0..200 {
        let m = 0.5 * (lo + hi);
        if m <= lo || m >= hi {
            break;
        }
        if at(m).f[1] < 0.0 {
            hi = m;
        } else {
            lo = m;
        }
    }
    let v0 = (l.centrifugal_force(omega) / lam.len() as f64 / lam.cs).powf(0.9);
    eprintln!(
        "mid-length approach when the inner contact closes: {:.2} µm",
        0.5 * v0 * 1e6
    );
    assert!(0.5 * v0 > 10.0 * DAMPING_RAMP, "{v0}");
    assert!((lo - half_pd - 0.5 * v0).abs() < 1e-3 * v0, "{lo} {v0}");
    let (r, r0) = (at(hi), at(lo));
    assert!(
        r.approach > 0.0 && r.approach < 1e-6 * DAMPING_RAMP,
        "{r:?}"
    );
    assert!(r0.approach <= 0.0, "{r0:?}");
}

/// The cells whose label contains `what`, run over the long campaign's 20 ms window.
fn long_cells(what: &str) -> Vec<(Cell, Outcome)> {
    let only = [what.to_string()];
    let cells: Vec<Cell> = stability::matrix(true)
        .into_iter()
        .filter(|c| stability::kept(&c.label(), &only))
        .collect();
    assert_eq!(cells.len(), 3, "{what}: one cell per roller material");
    stability::run(&cells, 0.02, false)
}

/// A tilted NU206 ring under 1 kN in 40 µm clearance, at rest: its loaded rollers are
/// edge-loaded (negative mid-length approach). Undamped, the ring rattled for the whole
/// window (rtol 1e-6/1e-7/1e-8 apart by 30-50 % pointwise); damped from each lamina's
/// touch it settles, and every refinement agrees pointwise.
#[test]
fn an_edge_loaded_ring_in_clearance_settles() {
    for (c, o) in long_cells("ring-5dof/load NU206 tilted | 0 | 1 kN | 40 µm") {
        assert!(
            matches!(o, Outcome::Converged { .. }),
            "{}: {o:?}",
            c.label()
        );
    }
}

/// A 30206 under 10 N radial and 5 N axial in 40 µm clearance, at rest: its few loaded
/// rollers sit tilted on their end laminae (a negative mid-point approach), which were left
/// undamped, so the light ring bounced all window long (Si3N4: rtol 1e-6/1e-7/1e-8 apart by
/// 0.50/0.59 pointwise, 12 % in mean/RMS); damped from each lamina's touch it settles.
#[test]
fn a_light_tapered_ring_in_clearance_settles() {
    for (c, o) in long_cells("quasi_static/load 30206 | 0 | 10 N | 40 µm") {
        assert!(
            matches!(o, Outcome::Converged { .. }),
            "{}: {o:?}",
            c.label()
        );
    }
}
