//! The integration methods, registered once: each row names the method as scenes spell it,
//! says whether it is meant for stiff levels and whether it has dense output, and builds
//! it. The scene's spelling list, `solver.method = "auto"`, the component's construction and
//! the straight-through check all read this table; a new method is one row here (and its
//! variant of the scene's `Method`, which a test holds to this table).

use super::{Dopri5, Integrator, LinearSolver, RosMethod, Rosenbrock};

/// Builds a method for `n` states; `linear` makes the linear solver an implicit method
/// needs (the component picks dense, block-arrowhead or reduced second-order).
pub type BuildMethod =
    fn(n: usize, linear: &mut dyn FnMut() -> Box<dyn LinearSolver>) -> Integrator;

/// One integration method.
#[derive(Clone, Copy)]
pub struct MethodEntry {
    /// Scene spelling (`solver.method`).
    pub name: &'static str,
    /// Meant for stiff levels: `auto` picks the first stiff method for a stiff level and the
    /// first non-stiff one otherwise.
    pub stiff: bool,
    /// Has dense output (needed to integrate a window straight through).
    pub dense_output: bool,
    /// Constructor.
    pub build: BuildMethod,
}

impl std::fmt::Debug for MethodEntry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("MethodEntry")
            .field("name", &self.name)
            .field("stiff", &self.stiff)
            .field("dense_output", &self.dense_output)
            .finish()
    }
}

fn dopri5(n: usize, _: &mut dyn FnMut() -> Box<dyn LinearSolver>) -> Integrator {
    Integrator::Dopri5(Dopri5::new(n))
}

fn rodas4(_: usize, linear: &mut dyn FnMut() -> Box<dyn LinearSolver>) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::with_method(RosMethod::Rodas4, linear()))
}

fn ros34pw2(_: usize, linear: &mut dyn FnMut() -> Box<dyn LinearSolver>) -> Integrator {
    Integrator::Rosenbrock(Rosenbrock::with_method(RosMethod::Ros34pw2, linear()))
}

/// Every method, in the order `auto` searches them.
#[rustfmt::skip]
pub const METHODS: &[MethodEntry] = &[
    //            name          stiff  dense output  constructor
    MethodEntry { name: "dopri5",     stiff: false, dense_output: true,  build: dopri5 },
    MethodEntry { name: "rosenbrock", stiff: true,  dense_output: true,  build: rodas4 },
    MethodEntry { name: "ros34pw2",   stiff: true,  dense_output: false, build: ros34pw2 },
];

/// The scene's spellings of `solver.method`: `auto`, then every method's name.
pub const METHOD_NAMES: [&str; METHODS.len() + 1] = {
    let mut names = ["auto"; METHODS.len() + 1];
    let mut i = 0;
    while i < METHODS.len() {
        names[i + 1] = METHODS[i].name;
        i += 1;
    }
    names
};

/// The method spelled `name` (not `auto`).
pub fn by_name(name: &str) -> Option<&'static MethodEntry> {
    METHODS.iter().find(|m| m.name == name)
}

/// What `auto` picks for a level that is stiff or not.
pub fn auto(stiff: bool) -> &'static MethodEntry {
    METHODS
        .iter()
        .find(|m| m.stiff == stiff)
        .expect("a stiff and a non-stiff method are registered")
}

/// The methods with dense output, as a list for messages (`"dopri5, rosenbrock or auto"`).
pub fn with_dense_output() -> String {
    let names: Vec<&str> = METHODS
        .iter()
        .filter(|m| m.dense_output)
        .map(|m| m.name)
        .collect();
    format!("{} or auto", names.join(", "))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_derived_and_auto_picks_by_stiffness() {
        assert_eq!(METHOD_NAMES, ["auto", "dopri5", "rosenbrock", "ros34pw2"]);
        assert_eq!(auto(false).name, "dopri5");
        assert_eq!(auto(true).name, "rosenbrock");
        assert!(by_name("auto").is_none() && by_name("rk4").is_none());
        for (i, a) in METHOD_NAMES.iter().enumerate() {
            assert!(!METHOD_NAMES[..i].contains(a), "`{a}` registered twice");
        }
        assert_eq!(with_dense_output(), "dopri5, rosenbrock or auto");
    }
}
