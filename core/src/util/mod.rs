//! Layer 0, util: float math that builds with and without `std`, the counter-
//! based RNG and its dimensions, the tolerances every backend shares, and
//! progress reporting.

pub mod math;
pub mod progress;
pub mod rng;
pub mod tolerance;
