//! Stability sweeps.
