use thiserror::Error;

/// Why a body could not be built.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum BodyError {
    /// A size, mass, density or G that must be a positive finite number was not.
    #[error("{field} must be a positive finite number, got {value}")]
    NotPositive {
        /// The parameter's name as the user knows it (`equatorial_radius`, `mass`, ...).
        field: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A value that must be finite was NaN or infinite.
    #[error("{field} must be finite, got {value}")]
    NotFinite {
        /// The parameter's name.
        field: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A derived quantity (density, volume) overflowed or underflowed for these inputs.
    #[error("{what} is not representable for these inputs ({value}); rescale the units")]
    OutOfRange {
        /// What overflowed.
        what: &'static str,
        /// The derived value.
        value: f64,
    },
}

/// Checks that `value` is a positive finite number.
pub(crate) fn positive(field: &'static str, value: f64) -> Result<f64, BodyError> {
    if !value.is_finite() {
        Err(BodyError::NotFinite { field, value })
    } else if value <= 0.0 {
        Err(BodyError::NotPositive { field, value })
    } else {
        Ok(value)
    }
}

/// Checks that a derived quantity is a positive normal number.
pub(crate) fn representable(what: &'static str, value: f64) -> Result<f64, BodyError> {
    if value.is_normal() && value > 0.0 {
        Ok(value)
    } else {
        Err(BodyError::OutOfRange { what, value })
    }
}
