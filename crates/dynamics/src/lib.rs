//! surfgrav-dynamics: see the crate description.
