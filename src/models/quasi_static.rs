//! Jones–Harris quasi-static equilibrium (physics.md §4). Work in progress (issue 2).
