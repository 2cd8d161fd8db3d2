//! Studies built on the engine: a user's scene ([`scene`]: bodies and impact conditions to
//! rebound curves, from a table or by simulation, with figures and measured data), the
//! figures of a table ([`figures`], `sweep plot`; some run the solver) and the solver's
//! accuracy against its cost ([`accuracy`]).

pub mod accuracy;
pub mod figures;
pub mod reference;
pub mod scene;
