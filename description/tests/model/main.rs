//! The integration tests of `dhgen-description`, in one test binary (`cargo test -p dhgen-description
//! --test model`).
//!
//! Organisation: one module per area, each a former `model/tests/<area>.rs`, whose tests are
//! `<area>::<name>`:
//! - [`validation`]: every rule of the description format and the errors that name it;
//! - [`catalogue`]: the robots of `robots/` load with the shape they are meant to have;
//! - [`chain`]: the kinematic structure against the DH formula it factors;
//! - [`support`]: helpers the modules share (loading a catalogue robot, the DH product).

mod support;

mod catalogue;
mod chain;
mod convert;
mod urdf;
mod validation;
