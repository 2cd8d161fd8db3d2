//! One module per command of the `sweep` binary.

pub mod accuracy;
pub mod plot;
pub mod query;
pub mod scene;
pub mod table;
pub mod verify;
