//! The CPU backend's tests, one binary: the conformance suite and the packet twins.

mod conformance;
mod twins;
