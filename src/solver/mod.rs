//! Integrators and nonlinear solvers written for the bearing problem.
