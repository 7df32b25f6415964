//! The keys of `raceway quasi-static --json` (and Python's `quasi_static`): a ball bearing
//! (its `solution` and the design check `calculator`), a roller bearing and a set
//! (`--scene`), all in one table (docs/columns.md says which keys belong to which).

use super::{k, Key};

/// A ball's equilibrium (`solution.balls[]`, a set row's `balls[]`).
macro_rules! balls {
    ($p:literal, $what:literal) => {
        [
            k($p, "balls", "", $what),
            k(concat!($p, "[].psi"), "psi", "rad", "azimuth"),
            k(concat!($p, "[].q_i"), "q_i", "N", "inner contact load"),
            k(concat!($p, "[].q_o"), "q_o", "N", "outer contact load"),
            k(
                concat!($p, "[].alpha_i"),
                "alpha_i",
                "rad",
                "inner contact angle",
            ),
            k(
                concat!($p, "[].alpha_o"),
                "alpha_o",
                "rad",
                "outer contact angle",
            ),
            k(
                concat!($p, "[].delta_i"),
                "delta_i",
                "m",
                "inner approach (negative: gap)",
            ),
            k(
                concat!($p, "[].delta_o"),
                "delta_o",
                "m",
                "outer approach (negative: gap)",
            ),
            k(
                concat!($p, "[].a_i"),
                "a_i",
                "m",
                "inner contact semi-axis across the rolling direction",
            ),
            k(
                concat!($p, "[].b_i"),
                "b_i",
                "m",
                "inner contact semi-axis along the rolling direction",
            ),
            k(
                concat!($p, "[].p_i"),
                "p_i",
                "Pa",
                "inner peak (Hertz) pressure",
            ),
            k(
                concat!($p, "[].a_o"),
                "a_o",
                "m",
                "outer contact semi-axis across the rolling direction",
            ),
            k(
                concat!($p, "[].b_o"),
                "b_o",
                "m",
                "outer contact semi-axis along the rolling direction",
            ),
            k(concat!($p, "[].p_o"), "p_o", "Pa", "outer peak pressure"),
            k(concat!($p, "[].fc"), "fc", "N", "centrifugal force"),
            k(concat!($p, "[].mg"), "mg", "N.m", "gyroscopic moment"),
            k(
                concat!($p, "[].omega_m"),
                "omega_m",
                "rad/s",
                "orbital (cage) speed",
            ),
            k(
                concat!($p, "[].omega_r"),
                "omega_r",
                "rad/s",
                "spin speed relative to the cage",
            ),
            k(concat!($p, "[].beta"), "beta", "rad", "spin-axis attitude"),
            k(
                concat!($p, "[].spin_roll_i"),
                "spin_roll_i",
                "1",
                "spin-to-roll ratio at the inner contact",
            ),
            k(
                concat!($p, "[].spin_roll_o"),
                "spin_roll_o",
                "1",
                "spin-to-roll ratio at the outer contact",
            ),
            k(
                concat!($p, "[].x"),
                "centre",
                "m",
                "ball centre relative to the outer groove centre (X1, X2)",
            ),
        ]
    };
}

/// A displacement `(x, y, z, rx, ry)` split into its five keys.
macro_rules! displacement {
    ($from:expr, $name:literal, $what:literal) => {
        k(
            $from,
            concat!($name, ".x|", $name, ".y|", $name, ".z|", $name, ".rx|", $name, ".ry"),
            "m|m|m|rad|rad",
            $what,
        )
    };
}

/// Forces and moments `(Fx, Fy, Fz, Mx, My)` split into their five keys.
macro_rules! force {
    ($from:expr, $name:literal, $what:literal) => {
        k(
            $from,
            concat!($name, ".x|", $name, ".y|", $name, ".z|", $name, ".rx|", $name, ".ry"),
            "N|N|N|N.m|N.m",
            $what,
        )
    };
}

/// ISO/TS 16281 lamina life (`ratings::lamina_life::LaminaLife`), under a prefix: the
/// roller quasi-static report's and a ring-level roller run's.
macro_rules! lamina_life {
    ($p:literal, $n:literal, $what:literal) => {
        [
            k($p, $n, "", $what),
            k(
                concat!($p, ".l10r_mrev"),
                "L10r",
                "Mrev",
                "reference rating life L10r (null: nothing loaded)",
            ),
            k(
                concat!($p, ".inner_mrev"),
                "life_inner",
                "Mrev",
                "the inner raceway's life alone",
            ),
            k(
                concat!($p, ".outer_mrev"),
                "life_outer",
                "Mrev",
                "the outer raceway's life alone",
            ),
            k(
                concat!($p, ".p_ref"),
                "P_ref",
                "N",
                "dynamic equivalent reference load C / L10r^(3/10)",
            ),
            k(concat!($p, ".options"), "options", "", "the steps applied"),
            k(
                concat!($p, ".options.edge_factor"),
                "edge_factor",
                "",
                "each lamina load multiplied by the edge-stress factor",
            ),
            k(
                concat!($p, ".options.remove_lambda_nu"),
                "remove_lambda_nu",
                "",
                "the laminae rated from C / (lambda nu)",
            ),
            k(
                concat!($p, ".ratings"),
                "ratings",
                "",
                "the raceway ratings used",
            ),
            k(
                concat!($p, ".ratings.q_ci"),
                "Q_ci",
                "N",
                "roller load of the inner raceway's basic dynamic rating",
            ),
            k(
                concat!($p, ".ratings.q_ce"),
                "Q_ce",
                "N",
                "roller load of the outer raceway's basic dynamic rating",
            ),
            k(
                concat!($p, ".ratings.qk_ci"),
                "q_ci",
                "N",
                "a lamina's inner rating Q_ci ns^(-7/9)",
            ),
            k(
                concat!($p, ".ratings.qk_ce"),
                "q_ce",
                "N",
                "a lamina's outer rating",
            ),
        ]
    };
}
pub(super) use lamina_life;

/// A set's own keys under its solution's path `$p` (`solution` of `quasi-static --scene`,
/// `locations[].set` of `raceway shaft`): the spring's shift, the system life and every
/// row.
macro_rules! set_rows {
    ($p:literal) => {
        [
        k(concat!($p, ".spring_shift"), "spring_shift", "m", "the preload spring's shift (set)"),
        k(concat!($p, ".life_mrev"), "system_life", "Mrev", "system life of the rows (set; null: no row loaded)"),
        k(concat!($p, ".rows"), "rows", "", "one entry per row (set)"),
        k(concat!($p, ".rows[].bearing"), "bearing", "", "the row's bearing"),
        k(concat!($p, ".rows[].position"), "position", "m", "axial position from the reference point"),
        k(concat!($p, ".rows[].orientation"), "orientation", "1", "+1: contact angle opens toward +z; -1: toward -z"),
        displacement!(concat!($p, ".rows[].displacement"), "displacement", "the row's own displacement (its frame)"),
        force!(concat!($p, ".rows[].force"), "force", "forces and moments of the row on the shaft at the row (shaft frame)"),
        k(concat!($p, ".rows[].radial_load"), "radial_load", "N", "radial load"),
        k(concat!($p, ".rows[].axial_load"), "axial_load", "N", "axial load toward the row's loading direction"),
        k(concat!($p, ".rows[].element_loads"), "element_loads", "N", "per-element inner contact loads"),
        k(concat!($p, ".rows[].contact_angles"), "contact_angles", "rad", "per-element inner and outer contact angles"),
        k(concat!($p, ".rows[].loaded_elements"), "loaded_elements", "1", "elements with a positive inner contact load"),
        k(concat!($p, ".rows[].lifted_off"), "lifted_off", "", "no element loaded"),
        k(concat!($p, ".rows[].axial_stiffness"), "axial_stiffness", "N/m", "the row's axial stiffness in its own frame"),
        k(concat!($p, ".rows[].life_mrev"), "life", "Mrev", "rating life (ball rows: ISO/TS 16281 reference life; roller rows: ISO 281 basic life; null: unloaded)"),
        k(concat!($p, ".rows[].weibull_slope"), "weibull_slope", "1", "Weibull slope of the row's life distribution"),
        k(concat!($p, ".rows[].s0"), "S0", "1", "static safety C0/P0 (null: unloaded)"),
        k(concat!($p, ".rows[].peak_pressure"), "peak_pressure", "Pa", "peak contact pressure (ball rows; 0 for roller rows)"),
        ]
    };
}

/// The top level and `solution` of every quasi-static document.
const OWN: &[Key] = &[
    k("bearing", "bearing", "", "bearing designation (ball, roller)"),
    k("scene", "scene", "", "the scene file (set)"),
    k("element", "element", "", "`roller` or `set` (absent: a ball bearing)"),
    k("speed_rpm", "speed", "rpm", "shaft speed"),
    force!("load", "load", "external load on the shaft (roller; set: at the reference point)"),
    k("race_control", "race_control", "", "race control assumption (ball)"),
    k("rating_error", "rating_error", "", "why the ratings are not available (ball)"),
    k("calculator_error", "calculator_error", "", "why the design check is not available (ball)"),
    k("solution", "solution", "", "the equilibrium (SI)"),
    k("solution.omega", "omega", "rad/s", "shaft speed (ball, set)"),
    force!("solution.load", "load", "external load on the inner ring (ball)"),
    displacement!("solution.q", "displacement", "inner-ring (set: shaft at the reference point) displacement"),
    force!("solution.forces", "force", "forces and moments of the bearing on the shaft (ball; = -load to the tolerance)"),
    force!("solution.rollers_force", "force", "forces and moments of the rollers on the shaft (roller)"),
    force!("solution.force", "force", "forces and moments of the set on the shaft at the reference point (set)"),
    k("solution.stiffness", "stiffness", "SI", "stiffness K = -dF/dq, 5 x 5, row i: force i of (Fx, Fy, Fz, Mx, My), column j: coordinate j of (x, y, z, rx, ry); N/m, N/rad, N.m/m, N.m/rad by block (ball, set)"),
    k("solution.k", "stiffness", "SI", "stiffness K = -dF/dq as for a ball bearing (roller)"),
    k("solution.psi", "psi", "rad", "ball azimuths (ball)"),
    k("solution.states", "states", "", "per-ball solver states, to warm-start a motion-driven run (ball)"),
    k("solution.states[].x", "centre", "m", "ball centre relative to the outer groove curvature centre (X1, X2)"),
    k("solution.states[].a", "groove_offset", "m", "groove offset (A1, A2) at which the centre was solved"),
    k("solution.states[].dxda", "dcentre_doffset", "1", "sensitivity dX/dA (row r: X_r)"),
    k("solution.states[].warm", "warm", "", "false: no previous solution"),
    k("solution.iterations", "iterations", "1", "Newton iterations (ball, roller)"),
    k("solution.held", "held", "", "which of (x, y, z, rx, ry) were held at a given value (ball)"),
    force!("solution.reaction", "reaction", "what the support adds on each held coordinate (ball; zero on the solved ones)"),
    k("solution.rollers", "rollers", "", "every roller (roller)"),
    k("solution.rollers[].psi", "psi", "rad", "azimuth"),
    k("solution.rollers[].load", "q_i|q_o", "N", "inner and outer (cone and cup) contact loads"),
    k("solution.rollers[].pressure", "p_i|p_o", "Pa", "inner and outer peak pressures"),
    k("solution.rollers[].flange_load", "flange_load", "N", "flange load (tapered: the cone back flange; zero otherwise)"),
    k("solution.rollers[].lamina_load", "lamina_load_outer", "N", "outer-contact load of each lamina (first lamina first)"),
    k("solution.rollers[].lamina_load_inner", "lamina_load_inner", "N", "inner-contact (cone) load of each lamina"),
    k("solution.rollers[].lamina_pressure", "lamina_pressure", "Pa", "inner-contact peak pressure of each lamina"),
    k("solution.rollers[].edge_pressure", "edge_pressure", "Pa", "the larger inner-contact pressure of the two end laminae"),
    k("cr", "C", "N", "ISO 281 basic dynamic load rating Cr (roller)"),
    k("c0r", "C0", "N", "ISO 76 basic static load rating C0r (roller)"),
    k("p", "P", "N", "ISO 281 dynamic equivalent load (roller)"),
    k("p0", "P0", "N", "ISO 76 static equivalent load (roller)"),
    k("l10_mrev", "L10", "Mrev", "basic rating life (Cr/P)^(10/3) (roller; null at zero load)"),
    k("max_pressure", "max_pressure", "Pa", "largest lamina pressure, inner contact (roller)"),
    k("max_edge_pressure", "max_edge_pressure", "Pa", "largest edge (end-lamina) pressure (roller)"),
    k("s0_lamina", "S0_lamina", "1", "static safety of the most loaded lamina (4000 MPa / max_pressure)^2 (roller)"),
    k("notes", "notes", "", "what in these figures is not sourced (roller)"),
];

/// The design check (`calculator`) of a ball bearing.
const CALCULATOR: &[Key] = &[
    k("calculator", "calculator", "", "the design check (ball; null when it failed, then calculator_error says why)"),
    k("calculator.oil", "oil", "", "the oil, when given"),
    k("calculator.oil.name", "name", "", "how the oil was named"),
    k("calculator.oil.nu40", "nu40", "m2/s", "kinematic viscosity at 40 °C"),
    k("calculator.oil.nu100", "nu100", "m2/s", "kinematic viscosity at 100 °C"),
    k("calculator.oil.viscosity_index", "viscosity_index", "1", "ASTM D2270 viscosity index"),
    k("calculator.lubrication", "lubrication", "", "the oil's viscosity, nu1 and kappa at the operating temperature"),
    k("calculator.lubrication.temperature_c", "temperature", "°C", "operating temperature"),
    k("calculator.lubrication.nu", "nu", "m2/s", "kinematic viscosity at that temperature"),
    k("calculator.lubrication.nu1", "nu1", "m2/s", "ISO 281 reference viscosity (null at standstill)"),
    k("calculator.lubrication.kappa", "kappa", "1", "viscosity ratio nu / nu1 (null at standstill)"),
    k("calculator.friction_model", "friction_model", "", "the model of `friction`: palmgren"),
    k("calculator.friction", "friction", "", "Palmgren's friction moment (ISO/TR 14179-2), with the oil and the ratings"),
    k("calculator.friction.m0", "M0", "N.m", "load-independent (viscous) moment"),
    k("calculator.friction.m1", "M1", "N.m", "load-dependent moment"),
    k("calculator.friction.total", "moment", "N.m", "friction moment M0 + M1"),
    k("calculator.friction.f1", "f1", "1", "load factor f1"),
    k("calculator.friction.p1", "P1", "N", "friction load"),
    k("calculator.friction.power", "power", "W", "power loss M omega"),
    k("calculator.subsurface", "subsurface", "", "subsurface stresses below the most loaded ball (null: no ball loaded)"),
    k("calculator.subsurface.ball", "ball", "1", "index of the ball"),
    k("calculator.subsurface.inner", "inner", "", "inner contact"),
    k("calculator.subsurface.inner.tau_max", "tau_max", "Pa", "largest principal shear stress"),
    k("calculator.subsurface.inner.z_tau_max", "z_tau_max", "m", "its depth"),
    k("calculator.subsurface.inner.von_mises", "von_mises", "Pa", "largest von Mises stress"),
    k("calculator.subsurface.inner.z_von_mises", "z_von_mises", "m", "its depth"),
    k("calculator.subsurface.inner.tau_orth", "tau_orth", "Pa", "largest orthogonal shear stress"),
    k("calculator.subsurface.inner.z_tau_orth", "z_tau_orth", "m", "its depth"),
    k("calculator.subsurface.outer", "outer", "", "outer contact"),
    k("calculator.subsurface.outer.tau_max", "tau_max", "Pa", "largest principal shear stress"),
    k("calculator.subsurface.outer.z_tau_max", "z_tau_max", "m", "its depth"),
    k("calculator.subsurface.outer.von_mises", "von_mises", "Pa", "largest von Mises stress"),
    k("calculator.subsurface.outer.z_von_mises", "z_von_mises", "m", "its depth"),
    k("calculator.subsurface.outer.tau_orth", "tau_orth", "Pa", "largest orthogonal shear stress"),
    k("calculator.subsurface.outer.z_tau_orth", "z_tau_orth", "m", "its depth"),
    k("calculator.clearance", "clearance", "", "the operating clearance chain, with fits or temperatures"),
    k("calculator.clearance.unmounted", "unmounted", "m", "unmounted diametral clearance Pd0"),
    k("calculator.clearance.shaft_pressure", "shaft_pressure", "Pa", "shaft-fit pressure"),
    k("calculator.clearance.from_shaft_fit", "from_shaft_fit", "m", "change of Pd from the shaft fit"),
    k("calculator.clearance.housing_pressure", "housing_pressure", "Pa", "housing-fit pressure"),
    k("calculator.clearance.from_housing_fit", "from_housing_fit", "m", "change of Pd from the housing fit"),
    k("calculator.clearance.from_temperatures", "from_temperatures", "m", "change of Pd from the temperatures"),
    k("calculator.clearance.from_speed", "from_speed", "m", "change of Pd from the inner ring's centrifugal growth"),
    k("calculator.clearance.operating", "operating", "m", "operating diametral clearance (negative: preload)"),
    k("calculator.clearance.inner_bore_hoop_stress", "inner_bore_hoop_stress", "Pa", "hoop stress at the inner ring's bore from the shaft fit"),
    k("calculator.equilibrium_clearance", "equilibrium_clearance|equilibrium_contact_angle", "m|rad", "the clearance and free contact angle the equilibrium was solved with (with the operating clearance)"),
    k("calculator.duty", "duty", "", "the life under the load spectrum, when one is given"),
    k("calculator.duty.mean_load", "mean_load", "N", "mean equivalent load P_m"),
    k("calculator.duty.mean_speed_rpm", "mean_speed", "rpm", "mean speed n_m"),
    k("calculator.duty.l10_mrev", "L10", "Mrev", "basic life (C/P_m)^p"),
    k("calculator.duty.miner_mrev", "miner_life", "Mrev", "Palmgren-Miner life with the rows' factors"),
    k("calculator.duty.miner_hours", "miner_life", "h", "the same in hours at the mean speed"),
    k("calculator.thermal_speed", "thermal_speed", "", "ISO 15312 thermal reference speed and the thermally safe speed"),
    k("calculator.thermal_speed.surface", "surface", "m2", "heat-emitting reference surface A_r"),
    k("calculator.thermal_speed.heat_flow_density", "heat_flow_density", "W/m2", "reference heat-flow density q_r (unsourced law)"),
    k("calculator.thermal_speed.heat_flow", "heat_flow", "W", "reference heat flow q_r A_r"),
    k("calculator.thermal_speed.reference_load", "reference_load", "N", "reference load 0.05 C0"),
    k("calculator.thermal_speed.reference_speed_rpm", "reference_speed", "rpm", "thermal reference speed"),
    k("calculator.thermal_speed.safe_speed_rpm", "safe_speed", "rpm", "thermally safe operating speed (null: permitted temperature not above the ambient)"),
    k("calculator.thermal_speed.safe_temperatures_c", "safe_temperature|safe_ambient", "°C", "the bearing temperature and the ambient of the safe speed"),
    k("calculator.thermal_speed.unsourced", "unsourced", "", "what is not sourced"),
    k("calculator.skf_friction", "skf_friction", "", "SKF four-term friction model (constants unconfirmed)"),
    k("calculator.skf_friction.series", "series", "", "the bearing series of its constants"),
    k("calculator.skf_friction.lubrication", "lubrication", "", "lubrication method"),
    k("calculator.skf_friction.rolling", "rolling_moment", "N.m", "rolling moment M_rr"),
    k("calculator.skf_friction.sliding", "sliding_moment", "N.m", "sliding moment M_sl"),
    k("calculator.skf_friction.seals", "seal_moment", "N.m", "seal moment (null: no seal constants)"),
    k("calculator.skf_friction.drag", "drag_moment", "N.m", "drag moment (null: not an oil bath, or no drag inputs)"),
    k("calculator.skf_friction.total", "moment", "N.m", "the sum of the terms computed"),
    k("calculator.skf_friction.power", "power", "W", "power loss M omega"),
    k("calculator.skf_friction.g_rr", "G_rr", "SKF", "rolling variable G_rr in SKF's units (N and mm)"),
    k("calculator.skf_friction.g_sl", "G_sl", "SKF", "sliding variable G_sl in SKF's units (N and mm)"),
    k("calculator.skf_friction.phi_ish", "phi_ish", "1", "inlet shear heating factor"),
    k("calculator.skf_friction.phi_rs", "phi_rs", "1", "replenishment/starvation factor"),
    k("calculator.skf_friction.phi_bl", "phi_bl", "1", "sliding weighting factor"),
    k("calculator.skf_friction.mu_sl", "mu_sl", "1", "sliding friction coefficient"),
    k("calculator.skf_friction.alpha_f", "alpha_F", "rad", "deep-groove axial-load angle (null without axial load)"),
    k("calculator.skf_friction.centrifugal_load", "centrifugal_load", "N", "angular-contact centrifugal load of the rolling term"),
    k("calculator.skf_friction.unconfirmed", "unconfirmed", "", "what is not confirmed against SKF's own text"),
    k("calculator.skf_friction.warnings", "warnings", "", "conditions of the source the operating point does not meet"),
    k("calculator.skf_note", "skf_note", "", "why there is no SKF friction"),
    k("calculator.held_moment", "held_moment", "", "the moment the support holds on held tilts, and the lives with and without it"),
    k("calculator.held_moment.moment", "moment", "N.m", "magnitude of the moment the bearing carries"),
    k("calculator.held_moment.reaction", "reaction.rx|reaction.ry", "N.m", "the reaction moment on the held tilts"),
    k("calculator.held_moment.l10_mrev", "L10", "Mrev", "ISO 281 L10 (no moment)"),
    k("calculator.held_moment.l10r_mrev", "L10r", "Mrev", "per-ball L10r (with the moment)"),
];

const BALLS: [Key; 22] = balls!("solution.balls", "per-ball results (ball)");
const SET_ROWS: [Key; NSET] = set_rows!("solution");
/// The number of keys of [`set_rows!`].
const NSET: usize = 19;
const ROW_BALLS: [Key; 22] = balls!(
    "solution.rows[].balls",
    "every ball's equilibrium (ball rows)"
);
const LAMINA: [Key; 13] = lamina_life!(
    "lamina_life",
    "lamina_life",
    "ISO/TS 16281 reference rating life from the lamina loads with the edge-stress factor, inner ring rotating (roller)"
);
const LAMINA_PLAIN: [Key; 13] = lamina_life!(
    "lamina_life_without_edge_factor",
    "lamina_life_without_edge_factor",
    "the same without the edge-stress factor (roller)"
);

/// Every key of the quasi-static documents but the rating's.
pub fn keys() -> Vec<Key> {
    let mut v = OWN.to_vec();
    v.extend_from_slice(&BALLS);
    v.extend_from_slice(&SET_ROWS);
    v.extend_from_slice(&ROW_BALLS);
    v.extend_from_slice(&LAMINA);
    v.extend_from_slice(&LAMINA_PLAIN);
    v.extend_from_slice(CALCULATOR);
    v
}

/// `raceway shaft --json` (and Python's `shaft`): the shaft's equilibrium, each location and
/// its set (the same keys as a set's `solution` under `locations[].set`).
const SHAFT: &[Key] = &[
    k("omega", "omega", "rad/s", "shaft speed"),
    force!("load", "load", "external load on the shaft at its origin"),
    displacement!("q", "displacement", "shaft displacement at its origin"),
    k("stiffness", "stiffness", "SI", "the shaft's stiffness K = -dF/dq at its origin, 5 x 5 (N/m, N/rad, N.m/m, N.m/rad by block)"),
    k("locations", "locations", "", "one entry per bearing location"),
    k("locations[].name", "name", "", "the location's name"),
    k("locations[].position", "position", "m", "axial position on the shaft"),
    k("locations[].lifted_off", "lifted_off", "", "no element of the location loaded"),
    k("locations[].floating", "floating", "", "the location floats axially (carries no axial load)"),
    k("locations[].set", "set", "", "the location's bearing or set at its equilibrium (SI)"),
    k("locations[].set.omega", "omega", "rad/s", "shaft speed"),
    displacement!("locations[].set.q", "displacement", "the set's displacement at its reference point"),
    force!("locations[].set.force", "force", "forces and moments of the set on the shaft at its reference point"),
    k("locations[].set.stiffness", "stiffness", "SI", "the set's stiffness at its reference point, 5 x 5"),
    k("life_mrev", "system_life", "Mrev", "system life of every row of every location (null: none loaded)"),
    k("warnings", "warnings", "", "what the solve warns of"),
];
const SHAFT_SET_ROWS: [Key; NSET] = set_rows!("locations[].set");
const SHAFT_ROW_BALLS: [Key; 22] = balls!(
    "locations[].set.rows[].balls",
    "every ball's equilibrium (ball rows)"
);

/// Every key of `raceway shaft --json`.
pub fn shaft_keys() -> Vec<Key> {
    let mut v = SHAFT.to_vec();
    v.extend_from_slice(&SHAFT_SET_ROWS);
    v.extend_from_slice(&SHAFT_ROW_BALLS);
    v
}
