//! Stand-alone runs of a scene: the component stepped at the scene's `[run]` step with the
//! prescribed shaft motion (motion-driven) or loads (load-driven), every output recorded.
//! What `raceway run` does; usable from Rust too.

use crate::component::{variables, Causality, Component, Scene};
use crate::error::Result;
use crate::units::rpm_to_rad_s;
use std::f64::consts::PI;

/// A recorded run: time and one column per variable of the table (inputs and outputs).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Variable names, in column order.
    pub names: Vec<&'static str>,
    /// Units, in column order.
    pub units: Vec<&'static str>,
    /// Communication times, s.
    pub t: Vec<f64>,
    /// Values, `columns[k][i]` at `t[i]`.
    pub columns: Vec<Vec<f64>>,
}

impl Series {
    /// The column of a variable.
    pub fn column(&self, name: &str) -> Option<&[f64]> {
        self.names
            .iter()
            .position(|n| *n == name)
            .map(|k| self.columns[k].as_slice())
    }

    /// CSV text: a header `t,<name> [unit],...` and one row per time.
    pub fn to_csv(&self) -> String {
        let mut s = String::from("t [s]");
        for (n, u) in self.names.iter().zip(&self.units) {
            s += &format!(",{n} [{u}]");
        }
        s.push('\n');
        for i in 0..self.t.len() {
            s += &format!("{:e}", self.t[i]);
            for c in &self.columns {
                s += &format!(",{:e}", c[i]);
            }
            s.push('\n');
        }
        s
    }
}

fn vr(name: &str) -> u32 {
    variables::by_name(name).expect("a contract variable").vr
}

/// Set the inputs `scene`'s `[run]` prescribes at time `t`: the shaft speed (with its
/// ramp) and, motion-driven, the shaft motion with the orbit, or, load-driven, the loads
/// with the rotating load.
fn set_inputs(c: &mut Component, scene: &Scene, t: f64) -> Result<()> {
    let r = &scene.run;
    let init = |name: &str| scene.inputs.initial.get(name).copied().unwrap_or(0.0);
    let omega0 = init("shaft.omega");
    let ramp = rpm_to_rad_s(r.speed_ramp_rpm_per_s);
    // Shaft angle at time t under the ramp.
    let shaft_angle = omega0 * t + 0.5 * ramp * t * t;
    let omega = omega0 + ramp * t;
    c.set_real(vr("shaft.omega"), omega)?;
    if ramp != 0.0 {
        c.set_input_derivative(vr("shaft.omega"), 1, ramp)?;
    }
    match scene.model.causality {
        Causality::Motion => {
            let (w, ph) = if r.orbit_hz > 0.0 {
                (2.0 * PI * r.orbit_hz, 2.0 * PI * r.orbit_hz * t)
            } else {
                (omega, shaft_angle)
            };
            let a = r.orbit_um * 1e-6;
            let (s, co) = ph.sin_cos();
            for (name, v) in [
                ("shaft.x", init("shaft.x") + a * co),
                ("shaft.y", init("shaft.y") + a * s),
                ("shaft.vx", init("shaft.vx") - a * w * s),
                ("shaft.vy", init("shaft.vy") + a * w * co),
            ] {
                c.set_real(vr(name), v)?;
            }
            for name in [
                "shaft.z", "shaft.rx", "shaft.ry", "shaft.vz", "shaft.wx", "shaft.wy",
            ] {
                c.set_real(vr(name), init(name))?;
            }
        }
        Causality::Load => {
            let (s, co) = shaft_angle.sin_cos();
            let f = r.rotating_load_n;
            c.set_real(vr("load.x"), init("load.x") + f * co)?;
            c.set_real(vr("load.y"), init("load.y") + f * s)?;
            for name in ["load.z", "load.mx", "load.my"] {
                c.set_real(vr(name), init(name))?;
            }
        }
    }
    Ok(())
}

/// The component of `scene` ready to run: built; the inputs the run prescribes at its end
/// (the speed after the ramp) accepted and the outputs there computed, on a separate
/// component so nothing of it carries over; the inputs of the start set and the outputs
/// computed. This is the last check of `raceway scene --check` too, so a scene that
/// passes it starts running.
pub fn prepare(scene: &Scene) -> Result<Component> {
    let at_end = |e: crate::Error| match e {
        crate::Error::Invalid {
            field,
            value,
            allowed,
        } => crate::Error::Invalid {
            field: format!(
                "{field} (prescribed by [run] at t = {} s)",
                scene.run.duration_s
            ),
            value,
            allowed,
        },
        other => other,
    };
    let mut end = Component::new(scene.clone())?;
    set_inputs(&mut end, scene, scene.run.duration_s)
        .and_then(|_| end.refresh_outputs())
        .map_err(at_end)?;
    let mut c = Component::new(scene.clone())?;
    set_inputs(&mut c, scene, 0.0)?;
    c.refresh_outputs()?;
    Ok(c)
}

/// What a run records besides the scalar inputs and outputs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Record {
    /// The stiffness `K.i.j` and damping `C.i.j` matrices (50 columns more).
    pub stiffness_damping: bool,
}

/// Run `scene` for its `[run]` duration. `progress` receives the completed fraction now
/// and then. The component's state after the run is returned too.
pub fn run(scene: &Scene, progress: &mut dyn FnMut(f64)) -> Result<(Series, Component)> {
    run_recording(scene, Record::default(), progress)
}

/// [`run`], recording what `record` asks for too.
pub fn run_recording(
    scene: &Scene,
    record: Record,
    progress: &mut dyn FnMut(f64),
) -> Result<(Series, Component)> {
    run_with(scene, record, false, progress)
}

/// [`run_recording`]; `through`: the whole duration in one
/// [`Component::step_through`] (the integrator takes its own steps, the series at the
/// communication points from its dense output) instead of a `do_step` per point. Straight
/// through holds the inputs of the start, so it is refused, naming the field, for a run
/// that moves them (`speed_ramp_rpm_per_s`, `orbit_um`, `rotating_load_n`), and for what
/// `step_through` refuses.
pub fn run_with(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
) -> Result<(Series, Component)> {
    run_until(scene, record, through, progress, &mut || false)
}

/// [`run_with`], asking `stop` before every communication step: when it answers true the
/// run ends with [`crate::Error::Interrupted`] (Ctrl-C in the command line and in Python).
/// `stop` is called once per step, so it should be cheap (check a flag, or the clock).
pub fn run_until(
    scene: &Scene,
    record: Record,
    through: bool,
    progress: &mut dyn FnMut(f64),
    stop: &mut dyn FnMut() -> bool,
) -> Result<(Series, Component)> {
    if through {
        let r = &scene.run;
        let moving = match scene.model.causality {
            Causality::Motion => ("run.orbit_um", r.orbit_um),
            Causality::Load => ("run.rotating_load_n", r.rotating_load_n),
        };
        for (field, v) in [("run.speed_ramp_rpm_per_s", r.speed_ramp_rpm_per_s), moving] {
            if v != 0.0 {
                return Err(crate::Error::invalid(
                    field,
                    v,
                    "0 for a run straight through (--through holds the inputs of the start)",
                ));
            }
        }
    }
    let mut c = prepare(scene)?;
    let r = &scene.run;
    let causality = scene.model.causality;
    let n = (r.duration_s / r.step_s).round().max(1.0) as usize;
    let h = r.duration_s / n as f64;
    let matrices = variables::STIFFNESS
        .iter()
        .chain(&variables::DAMPING)
        .flatten()
        .filter(|_| record.stiffness_damping);
    let vars: Vec<&variables::Variable> = variables::SCALARS
        .iter()
        .filter(|v| v.is_input(causality) || v.is_output(causality))
        .chain(matrices)
        .collect();
    let mut series = Series {
        names: vars.iter().map(|v| v.name).collect(),
        units: vars.iter().map(|v| v.unit).collect(),
        t: Vec::with_capacity(n + 1),
        columns: vec![Vec::with_capacity(n + 1); vars.len()],
    };

    let record = |c: &mut Component, series: &mut Series, t: f64| {
        series.t.push(t);
        for (col, v) in series.columns.iter_mut().zip(&vars) {
            col.push(c.get_real(v.vr).unwrap_or(0.0));
        }
    };
    record(&mut c, &mut series, 0.0);
    if through {
        let vrs: Vec<u32> = vars.iter().map(|v| v.vr).collect();
        let mut out = Vec::new();
        c.step_through(0.0, h, n, &vrs, &mut out)?;
        for (k, row) in out.chunks_exact(vrs.len().max(1)).enumerate() {
            series.t.push((k + 1) as f64 * h);
            for (col, v) in series.columns.iter_mut().zip(row) {
                col.push(*v);
            }
        }
        progress(1.0);
        return Ok((series, c));
    }
    let every = (n / 100).max(1);
    for i in 0..n {
        let t = i as f64 * h;
        if stop() {
            return Err(crate::Error::Interrupted { at_s: t });
        }
        set_inputs(&mut c, scene, t)?;
        c.do_step(t, h)?;
        record(&mut c, &mut series, (i + 1) as f64 * h);
        if i % every == 0 {
            progress((i + 1) as f64 / n as f64);
        }
    }
    progress(1.0);
    Ok((series, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The skidding level's own ball loads: their inner-contact vector sum carries the
    /// 500 N radial load of study \[2\]'s 6012 (small contact angles under a radial load, so
    /// within 5 %) pointing down like the load; the quasi-static level has none of its own.
    #[test]
    fn skidding_ball_loads_carry_the_load() {
        let text = include_str!("../examples/scenes/6012-skidding.toml");
        let mut scene = Scene::from_text(text).unwrap();
        scene.run.duration_s = 0.02;
        let (_, c) = run(&scene, &mut |_| {}).unwrap();
        let loads = c
            .ball_loads()
            .expect("the skidding level resolves its balls");
        assert_eq!(loads.len(), c.bearing().z);
        let (sx, sy) = loads.iter().fold((0.0, 0.0), |(x, y), (psi, qi, _)| {
            (x + qi * psi.cos(), y + qi * psi.sin())
        });
        assert!((sy + 500.0).abs() < 25.0 && sx.abs() < 25.0, "{sx} {sy}");
        let qs = Component::new(Scene::default_scene()).unwrap();
        assert!(qs.ball_loads().is_none());
    }

    /// A motion-driven ring run with a synchronous orbit: the recorded inputs follow the
    /// prescribed circle exactly and the force opposes the displacement.
    #[test]
    fn prescribed_orbit_is_followed_and_resisted() {
        let scene = Scene::from_text(
            "bearing = \"6205\"\n[model]\nlevel = \"ring\"\n[inputs]\ninitial = { \"shaft.omega\" = 100.0 }\n[run]\nduration_s = 0.02\nstep_s = 1e-4\norbit_um = 12.0\n",
        )
        .unwrap();
        let (s, _) = run(&scene, &mut |_| {}).unwrap();
        assert_eq!(s.t.len(), 201);
        let (x, y, fx, fy) = (
            s.column("shaft.x").unwrap(),
            s.column("shaft.y").unwrap(),
            s.column("force.x").unwrap(),
            s.column("force.y").unwrap(),
        );
        for i in 0..s.t.len() {
            assert!(((x[i] * x[i] + y[i] * y[i]).sqrt() - 12e-6).abs() < 1e-12);
            assert!(
                fx[i] * x[i] + fy[i] * y[i] < 0.0,
                "the bearing pushes back at t = {}",
                s.t[i]
            );
        }
        assert!(s.to_csv().starts_with("t [s],shaft.x [m]"));
        // K and C when asked: the same run with 50 columns more; K.x.x, the radial
        // stiffness of the loaded ring, is positive and of the order of 1e7..1e9 N/m.
        let (k, _) = run_recording(
            &scene,
            Record {
                stiffness_damping: true,
            },
            &mut |_| {},
        )
        .unwrap();
        assert_eq!(k.names.len(), s.names.len() + 50);
        assert_eq!(k.column("force.x").unwrap(), s.column("force.x").unwrap());
        let kxx = k.column("K.x.x").unwrap();
        assert!(kxx.iter().all(|v| *v > 1e6), "{:?}", &kxx[..3]);
        assert_eq!(
            k.units[k.names.iter().position(|n| *n == "C.y.y").unwrap()],
            "N.s/m"
        );
    }
}
