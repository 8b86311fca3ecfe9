//! marsden-io: writers and plots, kept out of the core.
