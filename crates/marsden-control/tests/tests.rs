//! The tests of marsden-control, one binary; a file per area.

// Tests may unwrap (helpers too, not only the `#[test]` functions).
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod cases;
