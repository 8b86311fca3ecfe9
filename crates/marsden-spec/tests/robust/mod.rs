//! Hostile inputs (issue "no input crashes, hangs, exhausts memory or gets a made-up
//! result"): each test is named after the promise it guards.

// Nothing untrue on success: time overflow, step counts, resolution, non-finite energy.
mod honest;
// Automatic differentiation that does not invent NaN.
mod ad;
// Limits checked before anything is allocated.
mod limits;
// Output directories: sanitised names, a lock, whole summaries.
mod outputs;
// Generated problem files: no panic, statuses that tell the truth.
mod fuzz;
