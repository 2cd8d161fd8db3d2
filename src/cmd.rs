//! One module per command of the `sweep` binary.

pub mod accuracy;
pub mod export;
pub mod gamma;
pub mod impact;
pub mod inspect;
pub mod kinks;
pub mod merge;
pub mod plot;
pub mod query;
pub mod reference;
pub mod run;
pub mod scene;
pub mod verify;
