//! One error type for the whole library. Every message names its cause: the field, the
//! value and the allowed range, or the call and the state it was refused in.

use std::fmt;

/// The message of a caught panic (its payload a `&str` or a `String`); `None` for another
/// payload.
pub fn panic_message(payload: &(dyn std::any::Any + Send)) -> Option<String> {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
}

/// Result alias used throughout raceway.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// What went wrong. `Display` gives a one-line message meant for people.
#[derive(Debug, Clone, PartialEq)]
pub enum Error {
    /// A value outside its allowed range (or not finite).
    Invalid {
        /// Dotted path of the field, e.g. `bearing.inner_curvature`.
        field: String,
        /// The offending value as text.
        value: String,
        /// The allowed range or rule, e.g. `> 0.5`.
        allowed: String,
    },
    /// A name that is not known (preset, material, variable, level).
    Unknown {
        /// What kind of name, e.g. `bearing preset`.
        what: &'static str,
        /// The name given.
        name: String,
        /// The names that are known.
        known: Vec<String>,
    },
    /// Text that does not parse (scene, bearing file, state bytes).
    Parse {
        /// What was being parsed.
        what: String,
        /// The parser's message (with line and column where known).
        message: String,
    },
    /// An iterative solve that did not converge: never returned as an answer.
    NotConverged {
        /// Which solve.
        what: &'static str,
        /// Iterations used.
        iterations: usize,
        /// Residual norm at the last iterate.
        residual: f64,
    },
    /// A time step that failed; the component state is unchanged.
    StepFailed {
        /// Communication time at which the step started.
        t: f64,
        /// Why.
        reason: String,
    },
    /// A step that exceeded its work budget (sub-steps or CPU time) and was stopped; the
    /// component state is unchanged. A host may retry with a shorter step (FMI: discard).
    Budget {
        /// Communication time at which the step started.
        t: f64,
        /// The scene field that sets the budget, e.g. `solver.max_step_cpu_s`.
        field: &'static str,
        /// The budget, with its unit.
        limit: String,
        /// What the step had used when it was stopped.
        used: String,
    },
    /// A call that is not allowed in the current state.
    CallOrder {
        /// The call.
        call: &'static str,
        /// Why it is refused now.
        reason: String,
    },
    /// Input/output failure (files).
    Io(String),
    /// The run was asked to stop (Ctrl-C, SIGTERM) at time `at_s` of the run; what was
    /// computed is dropped.
    Interrupted {
        /// Time reached, s.
        at_s: f64,
    },
}

impl Error {
    /// Shorthand for [`Error::Invalid`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        Error::Invalid {
            field: field.into(),
            value: short_number(value.to_string()),
            allowed: allowed.into(),
        }
    }
}

/// A number that `Display` wrote as a long decimal (`1e300` as 301 digits) in exponent form;
/// anything else as it is.
fn short_number(s: String) -> String {
    match s.parse::<f64>() {
        Ok(x) if s.len() > 24 && x.is_finite() => format!("{x:e}"),
        _ => s,
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Invalid {
                field,
                value,
                allowed,
            } => {
                write!(f, "invalid `{field}` = {value}: allowed {allowed}")
            }
            Error::Unknown { what, name, known } => {
                write!(f, "unknown {what} `{name}`; known: {}", known.join(", "))
            }
            Error::Parse { what, message } => write!(f, "cannot parse {what}: {message}"),
            Error::NotConverged {
                what,
                iterations,
                residual,
            } => write!(
                f,
                "{what} did not converge in {iterations} iterations (residual {residual:.3e})"
            ),
            Error::StepFailed { t, reason } => {
                write!(f, "step from t = {t} s failed, state unchanged: {reason}")
            }
            Error::Budget {
                t,
                field,
                limit,
                used,
            } => write!(
                f,
                "step from t = {t} s stopped, state unchanged: it exceeded the work budget \
                 `{field}` = {limit} (used {used}); raise `{field}` in the scene or shorten \
                 the communication step"
            ),
            Error::CallOrder { call, reason } => write!(f, "`{call}` refused: {reason}"),
            Error::Io(m) => write!(f, "{m}"),
            Error::Interrupted { at_s } => {
                write!(
                    f,
                    "interrupted at t = {at_s} s of the run (a stop was requested)"
                )
            }
        }
    }
}

impl std::error::Error for Error {}

/// Check that `value` is finite; the error names `field`.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "a finite number"))
    }
}

/// Check that `value` is finite and strictly positive.
pub fn positive(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "a finite number > 0"))
    }
}

/// Check that `value` is finite and in `[lo, hi]`.
pub fn in_range(field: &str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("a finite number in [{lo}, {hi}]"),
        ))
    }
}

impl From<std::io::Error> for Error {
    fn from(e: std::io::Error) -> Self {
        Error::Io(e.to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Huge and tiny values are named in exponent form (issue #38, item 9: `1e300` came out
    /// as a 301-digit decimal in FMI and `do_step` messages); ordinary ones as written.
    #[test]
    fn refused_values_are_short() {
        let e = Error::invalid("t", 1e300, "finite").to_string();
        assert!(e.contains("1e300") && !e.contains("0000000000"), "{e}");
        let e = Error::invalid("h", -2.5e-200, "positive").to_string();
        assert!(e.contains("-2.5e-200") && e.len() < 80, "{e}");
        assert!(Error::invalid("x", 1.5, "y").to_string().contains("1.5"));
        assert!(Error::invalid("x", "text value", "y")
            .to_string()
            .contains("text value"));
    }
}
