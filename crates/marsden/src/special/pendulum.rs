//! Kepler problem (placeholder).
