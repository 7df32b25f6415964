//! Building a component from a scene: the level from the registry, the load-driven ring
//! body, the state, the static start and the integrator.

use super::inputs::motion_at;
use super::level::LevelModel;
use super::static_start::static_start;
use super::system::{JacWork, RingBody, Work};
use super::variables::SCALARS;
use super::{
    fingerprint, limits, n_variables, scene, Causality, Component, Scene, State, AUX_COMPONENT,
    I_LOAD,
};
use crate::error::Result;
use crate::geometry::Bearing;
use crate::solver::{Integrator, Options};

/// The scene's integrator and its options. `Auto` picks RODAS4 for a level its registry
/// entry marks stiff (traction slopes), DOPRI5 for the others (a massless-ball ring is a
/// few-kHz oscillator, docs/physics.md §N1.2).
/// The coordinates `model.start_hold` holds in the load-driven static start (`dofs`: the
/// ring's coordinates; none for a motion-driven scene, and `model.start = "rest"` has no
/// static start: then nothing is held, as `attached_mass_kg` is ignored there). A
/// coordinate the ring does not have (z, rx, ry of the 2-DOF ring) is refused naming the
/// field, as is a non-finite value in any scene.
fn check_start_hold(scene: &Scene, dofs: Option<&[usize]>) -> Result<[bool; 5]> {
    use crate::models::quasi_static::hold::NAMES;
    scene.model.start_hold.to_si("model.start_hold")?;
    let edge = scene.model.start_hold.edge();
    let held: [bool; 5] = std::array::from_fn(|i| edge[i].is_some());
    let Some(dofs) = dofs else {
        return Ok([false; 5]);
    };
    if scene.model.start != super::scene::Start::Equilibrium {
        return Ok([false; 5]);
    }
    for i in (0..5).filter(|&i| held[i]) {
        if !dofs.contains(&i) {
            return Err(crate::error::Error::invalid(
                format!("model.start_hold.{}", NAMES[i]),
                edge[i].unwrap_or(0.0),
                "absent: the ring has no such coordinate (model.ring_dof = 5 has z, rx, ry)",
            ));
        }
    }
    Ok(held)
}

fn make_integrator(
    scene: &Scene,
    b: &Bearing,
    level: &dyn LevelModel,
    nl: usize,
    ring: Option<&RingBody>,
) -> (Integrator, Options) {
    let n = nl + ring.map_or(0, |r| 2 * r.dofs.len());
    // A stiff level (its registry entry) gets RODAS4 by default.
    let stiff = scene.model.level.entry().stiff;
    // A level with independent blocks of states gets the block-arrowhead solver; a
    // load-driven ring (its positions and velocities after the level's states, `dq/dt =
    // v`) the reduced second-order one.
    let mut linear = || -> Box<dyn crate::solver::LinearSolver> {
        let h = level.block_head();
        match (level.blocks(), ring) {
            (Some((nb, s)), _) if h + nb * s <= nl => Box::new(
                crate::solver::BlockArrowhead::with_head(h, nb, s, n - nb * s),
            ),
            (None, Some(r)) => Box::new(crate::solver::SecondOrderLu::new(nl, r.dofs.len())),
            _ => Box::new(crate::solver::DenseLu::new(n)),
        }
    };
    let mut integrator = (scene.solver.method.resolve(stiff).build)(n, &mut linear);
    // The component reads the dense output only from the steps its system observes (a
    // window integrated straight through, `Sys::step_accepted`): a step of `do_step`
    // skips DOPRI5's coefficients.
    integrator.set_dense_output(false);
    let s = &scene.solver;
    let mut opts = Options::new(n, s.rtol, s.atol_m);
    // Angles (cage, shaft, balls): an angle error atol_m / (D/2) moves a ball surface by
    // atol_m; a level with other states gives its own scales.
    let angle = s.atol_m / (0.5 * b.d);
    if !level.state_atol(s.atol_m, &mut opts.atol[..nl]) {
        opts.atol[..nl].fill(angle);
    }
    if let Some(r) = ring {
        let nd = r.dofs.len();
        let rate = 2.0 * std::f64::consts::PI * 1e3; // velocities: atol over a 1 kHz period
        for (k, &d) in r.dofs.iter().enumerate() {
            let a = if d < 3 {
                s.atol_m
            } else {
                s.atol_m / (0.5 * b.dm)
            };
            opts.atol[nl + k] = a;
            opts.atol[nl + nd + k] = a * rate;
        }
    }
    opts.max_steps = s.max_substeps as u64;
    if s.max_substep_s > 0.0 {
        opts.h_max = s.max_substep_s;
    }
    (integrator, opts)
}

impl Component {
    /// Create from scene text (TOML or JSON).
    pub fn from_text(text: &str) -> Result<Component> {
        Component::new(Scene::from_text(text)?)
    }

    /// Create from a scene. A bad scene is refused with a message naming the field.
    pub fn new(scene: Scene) -> Result<Component> {
        let bearing = scene.validate()?;
        let mut level = scene.model.level.build(&scene, &bearing)?;
        let n = n_variables();
        let fp = fingerprint(serde_json::to_string(&scene).unwrap_or_default().as_bytes());
        let causality = scene.model.causality;
        let ring = match causality {
            Causality::Motion => None,
            Causality::Load => {
                let m = bearing.inner_ring_mass + scene.model.attached_mass_kg;
                let ro = 0.5 * (bearing.dm - bearing.d);
                let ri = 0.5 * bearing.bore;
                let it = bearing.inner_ring_mass
                    * (3.0 * (ro * ro + ri * ri) + bearing.width.powi(2))
                    / 12.0;
                Some(RingBody {
                    dofs: level.ring_dofs(),
                    inv_inertia: [1.0 / m, 1.0 / m, 1.0 / m, 1.0 / it, 1.0 / it],
                })
            }
        };
        let n_level = level.n_states();
        let n_level_aux = level.n_aux();
        let n_ring = ring.as_ref().map_or(0, |r| 2 * r.dofs.len());
        let mut state = State {
            scene_fingerprint: fp,
            x: vec![0.0; n_level + n_ring],
            aux: vec![0.0; n_level_aux + AUX_COMPONENT],
            inputs: vec![0.0; n],
            input_derivatives: vec![0.0; 3 * n],
            outputs: vec![0.0; n],
            output_derivatives: vec![0.0; n],
            outputs_stale: true,
            ..State::default()
        };
        // Every input of this causality starts at the scene's initial value (absent: 0)
        // and counts as set: an input a host never sets holds it.
        for (i, v) in SCALARS.iter().enumerate() {
            if v.is_input(causality) {
                state.inputs[i] = scene.inputs.initial_value(v.name);
                state.inputs_set |= 1 << i;
            }
        }
        let motion = motion_at(
            &state,
            scene.inputs.rule,
            0.0,
            causality,
            ring.as_ref(),
            n_level,
            &state.x,
        );
        level.init(
            &motion,
            &mut state.x[..n_level],
            &mut state.aux[..n_level_aux],
        )?;
        let hold = &scene.model.start_hold;
        let mut start_held = (
            check_start_hold(&scene, ring.as_ref().map(|r| r.dofs))?,
            [0.0; 5],
        );
        if let (Some(r), scene::Start::Equilibrium) = (&ring, scene.model.start) {
            let loads: [f64; 5] = std::array::from_fn(|k| state.inputs[I_LOAD + k]);
            let held = hold.to_si("model.start_hold")?;
            let q0 = held.map(|h| h.unwrap_or(0.0));
            let held: [Option<f64>; 5] =
                std::array::from_fn(|d| held[d].filter(|_| start_held.0[d]));
            let free: Vec<usize> = r
                .dofs
                .iter()
                .copied()
                .filter(|&d| held[d].is_none())
                .collect();
            let (q, wrench) = static_start(
                level.as_mut(),
                &free,
                q0,
                &loads,
                motion.omega,
                0.5 * bearing.dm,
                &state.x[..n_level],
                &mut state.aux[..n_level_aux],
            )?;
            for (k, &d) in r.dofs.iter().enumerate() {
                state.x[n_level + k] = q[d];
            }
            {
                // The level's position states at the equilibrium found (the balls where
                // the static start had them), not where the ring was at rest.
                let motion = motion_at(
                    &state,
                    scene.inputs.rule,
                    0.0,
                    causality,
                    Some(r),
                    n_level,
                    &state.x,
                );
                level.follow_ring(&motion, &mut state.x[..n_level])?;
            }
            for d in (0..5).filter(|&d| start_held.0[d]) {
                start_held.1[d] = -(wrench[d] + loads[d]);
            }
        }
        let dim = state.x.len();
        let (integrator, opts) =
            make_integrator(&scene, &bearing, level.as_ref(), n_level, ring.as_ref());
        let work = Work {
            k: std::array::from_fn(|_| vec![0.0; dim]),
            y: vec![0.0; dim],
            aux_save: vec![0.0; n_level_aux + AUX_COMPONENT],
            fsal_key: vec![0.0; super::N_INPUT_SLOTS + n_level_aux],
            fsal: false,
        };
        let jwork = JacWork {
            jx: vec![0.0; n_level * n_level],
            jm: vec![0.0; n_level * 10],
            wx: vec![0.0; 5 * n_level],
            wm: vec![0.0; 50],
        };
        let set_rows = scene
            .set_spec(&bearing)?
            .map(|spec| {
                spec.rows
                    .into_iter()
                    .map(|r| {
                        let rating = crate::ratings::RatingOutputs::of(&r.bearing);
                        (r.bearing, rating)
                    })
                    .collect()
            })
            .unwrap_or_default();
        let mut c = Component {
            set_rows,
            limits: limits::Limits::of(&bearing),
            rating: crate::ratings::RatingOutputs::of(&bearing),
            stages: super::Stages::default(),
            budget_gap: 1,
            state_shared: false.into(),
            start_held,
            jwork,
            scene,
            bearing,
            level,
            ring,
            n_level,
            n_level_aux,
            scratch: state.clone(),
            state,
            work,
            integrator,
            opts,
        };
        c.refresh_outputs()?;
        Ok(c)
    }
}
