//! surfgrav-surfaces: see the crate description.
