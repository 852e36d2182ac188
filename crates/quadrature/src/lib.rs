//! surfgrav-quadrature: see the crate description.
