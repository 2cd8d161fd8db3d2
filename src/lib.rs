//! Reference engine for oblique elastic impacts with friction.
pub mod physics;
