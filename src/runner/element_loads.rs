//! The rolling elements' contact loads of a run, recorded at its communication points only
//! when a caller asks ([`super::run_into_with_loads`]: `raceway run` for its ball-load
//! plot): the loads at the last point, and their envelope against azimuth (the largest and
//! smallest load an element carried in each bin of [`BIN_DEG`]) over the run's last shaft
//! revolution. Bounded memory whatever the run's length: one load per element and four
//! values per bin.

use crate::component::Scene;
use crate::seam::element::ElementLoad;
use crate::units::rpm_to_rad_s;
use std::f64::consts::TAU;

/// Width of an envelope bin, degrees: below the angular width of a 1 mm spall on the outer
/// race of a 6205 (2.4°), so the load drop there shows in the envelope.
pub const BIN_DEG: f64 = 1.0;

/// Number of envelope bins over a turn.
const BINS: usize = (360.0 / BIN_DEG) as usize;

/// The largest and smallest value seen in each azimuth bin (NaN where nothing was seen).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Envelope {
    /// Largest value per bin.
    pub max: Vec<f64>,
    /// Smallest value per bin.
    pub min: Vec<f64>,
}

impl Envelope {
    fn new() -> Envelope {
        Envelope {
            max: vec![f64::NAN; BINS],
            min: vec![f64::NAN; BINS],
        }
    }

    fn add(&mut self, k: usize, v: f64) {
        // `f64::max` of NaN and v is v: the first value seen fills the bin.
        self.max[k] = self.max[k].max(v);
        self.min[k] = self.min[k].min(v);
    }
}

/// The element loads a run recorded ([`super::run_into_with_loads`]).
#[derive(Debug, Clone, Default)]
pub struct LoadRecord {
    /// Whether the level gave element loads (`false`: nothing recorded; the level does not
    /// resolve its elements, or the run went straight through).
    pub available: bool,
    /// The loads at the last communication point, in element order (azimuths as the level
    /// has them, not reduced to one turn).
    pub last: Vec<ElementLoad>,
    /// The time of `last`, s.
    pub t_last: f64,
    /// The envelope's window `(from, to)`, s.
    pub window: (f64, f64),
    /// Whether the window is the run's last shaft revolution (`false`: the whole run, which
    /// turns the shaft less than once).
    pub last_revolution: bool,
    /// Communication points in the window.
    pub points: usize,
    /// Inner contact loads per bin of [`BIN_DEG`] from azimuth 0 (from `+x` toward `+y`).
    pub inner: Envelope,
    /// Outer contact loads per bin.
    pub outer: Envelope,
    scratch: Vec<ElementLoad>,
}

impl LoadRecord {
    /// A record for a run of `scene` (its window: the last shaft revolution of the
    /// prescribed speed, or the whole run when it turns less).
    pub fn for_scene(scene: &Scene) -> LoadRecord {
        let (from, last_revolution) = last_revolution(scene);
        LoadRecord {
            window: (from, scene.run.duration_s),
            last_revolution,
            inner: Envelope::new(),
            outer: Envelope::new(),
            ..LoadRecord::default()
        }
    }

    /// Whether a point at `t` (s) is recorded (in the window; a tolerance of a
    /// millionth of the run for the rounding of the step times).
    pub fn wants(&self, t: f64) -> bool {
        t >= self.window.0 - 1e-6 * self.window.1.abs()
    }

    /// The bin of azimuth `psi` (rad, any turn).
    pub fn bin(psi: f64) -> usize {
        let deg = psi.to_degrees().rem_euclid(360.0);
        ((deg / BIN_DEG) as usize).min(BINS - 1)
    }

    /// The centre of bin `k`, degrees.
    pub fn bin_centre_deg(k: usize) -> f64 {
        (k as f64 + 0.5) * BIN_DEG
    }

    /// Add the loads `loads` of the point at `t`: the last point's, and into the envelope.
    pub fn add(&mut self, t: f64, loads: &[ElementLoad]) {
        self.available = true;
        self.t_last = t;
        self.points += 1;
        self.last.clear();
        self.last.extend_from_slice(loads);
        for l in loads {
            let k = Self::bin(l.psi);
            self.inner.add(k, l.inner);
            self.outer.add(k, l.outer);
        }
    }

    /// Read the component's element loads at `t` (s) when the point is in the window.
    pub(super) fn take_from(&mut self, c: &crate::Component, t: f64) {
        if !self.wants(t) {
            return;
        }
        let mut s = std::mem::take(&mut self.scratch);
        if c.element_loads(&mut s) {
            self.add(t, &s);
        }
        self.scratch = s;
    }
}

/// The start of the last shaft revolution of `scene`'s run, s, under its prescribed speed
/// (the initial speed and the ramp: the shaft angle `omega0 t + ramp t² / 2`), and whether
/// the run has one (else 0: the whole run).
fn last_revolution(scene: &Scene) -> (f64, bool) {
    let end = scene.run.duration_s;
    let omega0 = scene.inputs.initial_value("shaft.omega");
    let ramp = rpm_to_rad_s(scene.run.speed_ramp_rpm_per_s);
    let angle = |t: f64| omega0 * t + 0.5 * ramp * t * t;
    let turned = |t: f64| (angle(end) - angle(t)).abs();
    let total = turned(0.0);
    if total.is_nan() || total <= TAU {
        return (0.0, false);
    }
    // The turned angle falls from above a turn at 0 to 0 at the end (monotonic while the
    // speed keeps its sign): bisection to the point one turn before the end.
    let (mut a, mut b) = (0.0, end);
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        if turned(m) > TAU {
            a = m;
        } else {
            b = m;
        }
    }
    (b, true)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The window is one shaft turn before the end: 60/1750 s at 1750 rpm held, and under
    /// a ramp from rest the `t` where `ramp (T² - t²) / 2 = 2 pi`; a run shorter than a turn
    /// keeps the whole run.
    #[test]
    fn the_window_is_the_last_shaft_revolution() {
        let scene = |speed: f64, ramp: f64, duration: f64| {
            Scene::from_text(&format!(
                "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\nspeed_rpm = \
                 {speed}\n[run]\nduration_s = {duration}\nspeed_ramp_rpm_per_s = {ramp}\n"
            ))
            .unwrap()
        };
        let (t0, rev) = last_revolution(&scene(1750.0, 0.0, 1.0));
        assert!(rev && (t0 - (1.0 - 60.0 / 1750.0)).abs() < 1e-12, "{t0}");
        let (t0, rev) = last_revolution(&scene(0.0, 60_000.0, 0.5));
        let a = rpm_to_rad_s(60_000.0);
        assert!(
            rev && (0.5 * a * (0.25 - t0 * t0) - TAU).abs() < 1e-9,
            "{t0}"
        );
        assert_eq!(last_revolution(&scene(1750.0, 0.0, 0.02)), (0.0, false));
    }

    /// Bins: azimuths of any turn fold into [0, 360) degrees; the envelope keeps each
    /// bin's extremes and leaves unvisited bins NaN.
    #[test]
    fn the_envelope_keeps_each_bins_extremes() {
        assert_eq!(LoadRecord::bin(-0.5f64.to_radians()), BINS - 1);
        assert_eq!(LoadRecord::bin((720.0f64 + 270.2).to_radians()), 270);
        let mut r = LoadRecord {
            inner: Envelope::new(),
            outer: Envelope::new(),
            ..LoadRecord::default()
        };
        let at = |deg: f64, q: f64| ElementLoad {
            psi: deg.to_radians(),
            inner: q,
            outer: q + 1.0,
        };
        r.add(0.1, &[at(10.2, 5.0), at(100.0, 7.0)]);
        r.add(0.2, &[at(10.7, 3.0), at(370.5, 9.0)]);
        assert_eq!((r.inner.max[10], r.inner.min[10]), (9.0, 3.0));
        assert_eq!((r.outer.max[10], r.outer.min[10]), (10.0, 4.0));
        assert_eq!(r.inner.max[100], 7.0);
        assert!(r.inner.max[11].is_nan() && r.inner.min[200].is_nan());
        assert_eq!((r.points, r.t_last, r.last.len()), (2, 0.2, 2));
    }
}
