//! Set cells of the stability campaign (a block of its own, mounted by
//! [`super`]): the 7008CE DB pair as one component under a heavy preload, with one row
//! lifting off under axial load, and at high speed, on the quasi-static and the 5-DOF ring
//! levels. Each must give finite outputs that converge under refinement (rtol 1e-6 against
//! 1e-7, [`super::CONVERGENCE_LIMIT`]) or end in a clean error.

use super::{drive_checked, panic_text, pointwise, Outcome, CONVERGENCE_LIMIT};
use crate::component::variables::by_name;
use crate::component::Component;
use std::fmt::Write as _;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// One set cell.
#[derive(Debug, Clone, PartialEq)]
pub struct SetCell {
    /// Label.
    pub name: &'static str,
    /// `[set]` and `[model]` lines.
    pub lines: &'static str,
    /// Inputs at the start (SI, by variable name).
    pub inputs: &'static [(&'static str, f64)],
    /// Macro step, s.
    pub h: f64,
    /// On the 5-DOF ring load-driven (`false`: the quasi-static level motion-driven).
    pub ring: bool,
}

const MOTION0: [(&str, f64); 10] = [
    ("shaft.x", 0.0),
    ("shaft.y", 0.0),
    ("shaft.z", 0.0),
    ("shaft.rx", 0.0),
    ("shaft.ry", 0.0),
    ("shaft.vx", 0.0),
    ("shaft.vy", 0.0),
    ("shaft.vz", 0.0),
    ("shaft.wx", 0.0),
    ("shaft.wy", 0.0),
];

/// The set cells: heavy preload (3 kN, a quarter of the 7008CE's C0, rigid), lift-off
/// (a 300 N pair pushed 60 µm axially, or under a 3 kN thrust: the row facing `-z` unloads), high speed (30 000 rpm,
/// rigid and constant-force preload), each on the quasi-static level motion-driven and on
/// the 5-DOF ring load-driven.
pub fn cells() -> Vec<SetCell> {
    const W12: f64 = 1256.637061;
    const W30: f64 = 3141.592654;
    vec![
        SetCell {
            name: "heavy preload 3 kN, qs motion",
            lines: "[set]\narrangement = \"db\"\npreload_n = 3000\n",
            inputs: &[("shaft.y", -5e-6), ("shaft.ry", 1e-4), ("shaft.omega", W12)],
            h: 1e-4,
            ring: false,
        },
        SetCell {
            name: "heavy preload 3 kN, ring load",
            lines: "[set]\narrangement = \"db\"\npreload_n = 3000\n",
            inputs: &[("load.y", -2000.0), ("load.z", 500.0), ("shaft.omega", W12)],
            h: 1e-4,
            ring: true,
        },
        SetCell {
            name: "lift-off under thrust (60 µm axial), qs motion",
            lines: "[set]\narrangement = \"db\"\npreload_n = 300\n",
            inputs: &[("shaft.z", 60e-6), ("shaft.omega", W12)],
            h: 1e-4,
            ring: false,
        },
        SetCell {
            name: "lift-off under 3 kN thrust, ring load",
            lines: "[set]\narrangement = \"db\"\npreload_n = 300\n",
            inputs: &[("load.z", 3000.0), ("load.y", -300.0), ("shaft.omega", W12)],
            h: 1e-4,
            ring: true,
        },
        SetCell {
            name: "30 000 rpm rigid, qs motion",
            lines: "[set]\narrangement = \"db\"\npreload_n = 300\n",
            inputs: &[("shaft.y", -4e-6), ("shaft.z", 2e-6), ("shaft.omega", W30)],
            h: 1e-4,
            ring: false,
        },
        SetCell {
            name: "30 000 rpm spring, qs motion",
            lines: "[set]\narrangement = \"db\"\npreload_n = 300\nspring_n_per_um = 2\n",
            inputs: &[("shaft.y", -4e-6), ("shaft.z", 2e-6), ("shaft.omega", W30)],
            h: 1e-4,
            ring: false,
        },
        SetCell {
            name: "30 000 rpm rigid, ring load",
            lines: "[set]\narrangement = \"db\"\npreload_n = 300\n",
            inputs: &[("load.y", -500.0), ("load.z", 200.0), ("shaft.omega", W30)],
            h: 1e-4,
            ring: true,
        },
    ]
}

impl SetCell {
    /// The cell's scene at `rtol` (the 7008CE pair, its inputs at the start).
    pub fn scene(&self, rtol: f64) -> String {
        let load = self.ring;
        let mut initial: Vec<(&str, f64)> = if load {
            ["load.x", "load.y", "load.z", "load.mx", "load.my"]
                .iter()
                .map(|n| (*n, 0.0))
                .collect()
        } else {
            MOTION0.to_vec()
        };
        for &(n, v) in self.inputs {
            match initial.iter_mut().find(|(m, _)| *m == n) {
                Some(e) => e.1 = v,
                None => initial.push((n, v)),
            }
        }
        // The speed is a scene field in rpm (`[inputs] speed_rpm`), the rest initial values.
        let rpm = initial
            .iter()
            .find(|(n, _)| *n == "shaft.omega")
            .map_or(0.0, |(_, w)| w * 30.0 / std::f64::consts::PI);
        let initial: Vec<String> = initial
            .iter()
            .filter(|(n, _)| *n != "shaft.omega")
            .map(|(n, x)| format!("\"{n}\" = {x:e}"))
            .collect();
        format!(
            "bearing = \"7008CE\"\n{}{}[solver]\nrtol = {rtol:e}\n[inputs]\nrule = \"hold\"\nspeed_rpm = {rpm:?}\ninitial = {{ {} }}\n",
            self.lines,
            self.lines_model(),
            initial.join(", ")
        )
    }

    fn lines_model(&self) -> &'static str {
        if self.ring {
            "[model]\nlevel = \"ring\"\nring_dof = 5\ncausality = \"load\"\n"
        } else {
            "[model]\nlevel = \"quasi_static\"\ncausality = \"motion\"\n"
        }
    }

    fn run_once(
        &self,
        rtol: f64,
        t_end: f64,
    ) -> crate::Result<(super::super::Samples, f64, Option<String>)> {
        let mut c = Component::from_text(&self.scene(rtol))?;
        let (s, bad) = drive_checked(&mut c, t_end, self.h, &[], None)?;
        let p = c.get_real(by_name("contact.max_pressure").expect("in table").vr)?;
        Ok((s, p, bad))
    }

    /// Run at rtol 1e-6 and 1e-7 over `t_end` (s).
    pub fn run(&self, t_end: f64) -> Outcome {
        let r = catch_unwind(AssertUnwindSafe(|| {
            Ok::<_, crate::Error>((self.run_once(1e-6, t_end)?, self.run_once(1e-7, t_end)?))
        }));
        let ((sa, pa, na), (sb, pb, nb)) = match r {
            Err(p) => return Outcome::Failed(format!("panic: {}", panic_text(&*p))),
            Ok(Err(e)) => return Outcome::CleanError(e.to_string()),
            Ok(Ok(v)) => v,
        };
        if let Some(what) = na.or(nb) {
            return Outcome::Failed(format!("non-finite output: {what}"));
        }
        let diff = pointwise(&sa, &sb);
        if diff <= CONVERGENCE_LIMIT && pa.is_finite() && pb.is_finite() {
            Outcome::Converged {
                diff,
                max_pressure: pa.max(pb),
            }
        } else {
            Outcome::Failed(format!("refinement difference {diff:.3e}"))
        }
    }
}

/// Run every set cell over `t_end` (s).
pub fn run(t_end: f64, verbose: bool) -> Vec<(SetCell, Outcome)> {
    run_of(t_end, &[], verbose)
}

/// Run the set cells whose label `set: NAME` passes the developer filter `only`
/// ([`super::kept`]) over `t_end` (s).
pub fn run_of(t_end: f64, only: &[String], verbose: bool) -> Vec<(SetCell, Outcome)> {
    cells()
        .into_iter()
        .filter(|c| super::kept(&format!("set: {}", c.name), only))
        .map(|c| {
            let o = c.run(t_end);
            if verbose {
                println!("set: {} -> {o:?}", c.name);
            }
            (c, o)
        })
        .collect()
}

/// The set cells' section of the campaign page.
pub fn markdown(res: &[(SetCell, Outcome)], t_end: f64) -> String {
    let mut s = format!(
        "\n## Bearing sets\n\nThe 7008CE DB pair as one component (`[set]`), {} ms windows at 0.1 ms \
         steps, rtol 1e-6 against 1e-7.\n\n| cell | outcome | refinement diff | peak contact pressure at the end (GPa) |\n|---|---|---|---|\n",
        t_end * 1e3
    );
    for (c, o) in res {
        let (what, diff, p) = match o {
            Outcome::Converged { diff, max_pressure } => (
                "converged",
                format!("{diff:.1e}"),
                format!("{:.2}", max_pressure * 1e-9),
            ),
            Outcome::Statistical {
                diff, max_pressure, ..
            } => (
                "statistical",
                format!("{diff:.1e}"),
                format!("{:.2}", max_pressure * 1e-9),
            ),
            Outcome::CleanError(e) => ("clean error", e.clone(), "-".into()),
            Outcome::Failed(e) => ("FAILED", e.clone(), "-".into()),
        };
        let _ = writeln!(s, "| {} | {what} | {diff} | {p} |", c.name);
    }
    s
}
