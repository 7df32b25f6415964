//! TEMPORARY stand-ins for crate::lubrication::{guide_land, pocket, drag} until they land.
#![allow(missing_docs, dead_code)]
pub mod guide_land {
    #[derive(Debug, Clone)]
    pub struct GuideLand {
        pub radius: f64,
        pub width: f64,
        pub clearance: f64,
        pub viscosity: f64,
        pub outer: bool,
        pub contact_stiffness: f64,
        pub eps_max: f64,
    }
    pub struct GuideForce {
        pub f: [f64; 2],
        pub torque: f64,
        pub eps: f64,
    }
    impl GuideLand {
        pub fn force(&self, e: [f64; 2], e_dot: [f64; 2], w_c: f64, w_ring: f64) -> GuideForce {
            let em = e[0].hypot(e[1]);
            let eps = em / self.clearance;
            let pen = (em - self.eps_max * self.clearance).max(0.0);
            let k = self.contact_stiffness;
            let c = 1e-3 * k;
            let mut f = [0.0; 2];
            if em > 0.0 {
                for i in 0..2 {
                    f[i] = -k * pen * e[i] / em - c * e_dot[i] * (pen > 0.0) as u8 as f64;
                }
            }
            let t = 2.0 * std::f64::consts::PI * self.viscosity * self.radius.powi(3) * self.width
                / self.clearance
                * (w_ring - w_c);
            GuideForce { f, torque: t, eps }
        }
    }
}
pub mod pocket {
    #[derive(Debug, Clone)]
    pub struct PocketLaw {
        pub ball_radius: f64,
        pub pocket_radius: f64,
        pub width: f64,
        pub roughness: f64,
        pub viscosity: f64,
        pub e_eff: f64,
        pub friction: f64,
        pub v_s: f64,
    }
    pub struct PocketForce {
        pub normal: f64,
        pub friction: f64,
    }
    impl PocketLaw {
        pub fn force(&self, h: f64, h_dot: f64, _u: f64, vs: f64) -> PocketForce {
            let pen = (-h).max(0.0);
            let k = 1e7;
            let n = k * pen - if pen > 0.0 { 50.0 * h_dot } else { 0.0 };
            let n = n.max(0.0);
            PocketForce {
                normal: n,
                friction: -self.friction * n * (vs / self.v_s).tanh(),
            }
        }
    }
}
pub mod drag {
    #[derive(Debug, Clone, Copy)]
    pub struct Fluid {
        pub density: f64,
        pub viscosity: f64,
    }
    pub fn sphere_drag_force(f: &Fluid, d: f64, v: f64) -> f64 {
        -0.5 * 0.5 * f.density * std::f64::consts::PI * d * d / 4.0 * v * v.abs()
    }
    pub fn sphere_spin_moment(f: &Fluid, d: f64, w: f64) -> f64 {
        -std::f64::consts::PI * f.viscosity * d.powi(3) * w
    }
    pub fn disk_moment(f: &Fluid, r_in: f64, r_out: f64, w: f64) -> f64 {
        -0.5 * f.viscosity * w * (r_out.powi(4) - r_in.powi(4)) / 1e-3 * std::f64::consts::PI
    }
}
