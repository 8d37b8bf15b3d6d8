//! The robot model of dhgen: the description format, its validation, the DH conventions, and
//! the kinematic structure shared by the runtime path and the code generator.
//!
//! Data flows one way: a description (a TOML file via [`RobotModel::from_toml_str`], or the
//! tokens of `robot!`) becomes a [`raw`] tree, [`validate`] turns the tree into a
//! [`RobotModel`], [`RobotModel::chain`] factors it into a [`JointChain`] once, and everything
//! downstream reads the validated model and its chain.
//!
//! ```
//! let robot = dhgen_description::RobotModel::from_toml_str(r#"
//!     name = "planar"
//!     convention = "standard"
//!     [[links]]
//!     joint = "revolute"
//!     a = 1.0
//!     alpha = 0
//!     d = 0
//!     theta = 0
//! "#).unwrap();
//! assert_eq!(robot.dof(), 1);
//! assert!(!robot.has_dynamics());
//! let chain = robot.chain();
//! assert_eq!(chain.view().tool_at(&[0.0]).p, [1.0, 0.0, 0.0]);
//! ```
//!
//! Without the default `std` feature the crate is `no_std` and holds only what generated
//! code needs at run time: the plain-data structure ([`ChainRef`]), frames and angles.
#![cfg_attr(not(feature = "std"), no_std)]

#[cfg(feature = "std")]
pub mod convert;
#[cfg(feature = "testing")]
pub mod hostile;
mod model;
pub mod parameters;
#[cfg(feature = "testing")]
pub mod random;
#[cfg(feature = "std")]
pub mod raw;
#[cfg(feature = "std")]
mod structure;
#[cfg(feature = "std")]
pub mod urdf;
#[cfg(feature = "std")]
pub mod validate;
#[cfg(feature = "std")]
mod write;

/// The linear algebra of the descriptions (the kernel's), re-exported so that every crate of
/// dhgen names the same version.
pub use dhgen_kernel::nalgebra;

#[cfg(feature = "std")]
pub use dhgen_kernel::JointChain;
/// The kernel's types a description is made of and builds: its angles, transforms, joints,
/// mass properties and chain.
pub use dhgen_kernel::{
    Angle, Axis, Body, ChainRef, Frame, Friction, Inertial, JointKind, JointValue, NotSpherical,
    Ring, SphericalWrist, Twist,
};
#[cfg(feature = "std")]
pub use model::RobotModel;
pub use model::{Collision, Convention, Link, Motor, Placement, Pose};

#[cfg(feature = "std")]
pub use load::LoadError;

#[cfg(feature = "std")]
mod load {
    use crate::{RobotModel, raw, validate};
    use std::path::Path;

    /// An error reading a description. Each variant names its `origin` (the file, or
    /// `<string>` for text in memory); a rule violation displays as
    /// `file:line:column: link N, field NAME: what is wrong`, the form editors jump to.
    #[derive(Debug, thiserror::Error)]
    #[non_exhaustive]
    pub enum LoadError {
        /// The file could not be read.
        #[error("{origin}: cannot read file: {source}")]
        Io {
            /// The file.
            origin: String,
            /// Why.
            source: std::io::Error,
        },
        /// The text is not valid TOML.
        #[error("{}:{}: invalid TOML: {}", validate::OneLine(origin), error.loc, validate::OneLine(&error.message))]
        Syntax {
            /// The file, or `<string>`.
            origin: String,
            /// Where, and the TOML parser's message.
            error: raw::SyntaxError,
        },
        /// A URDF file that is not XML, or whose robot dhgen cannot read: where, and what is
        /// wrong, naming the link or joint and the attribute.
        #[error("{}:{loc}: {}", validate::OneLine(origin), validate::OneLine(message))]
        Urdf {
            /// The file, or `<string>`.
            origin: String,
            /// Line and column in the file.
            loc: raw::Position,
            /// What is wrong.
            message: String,
        },
        /// The description breaks a rule of the format, at a line and column of the text.
        #[error("{}:{}: {error}", validate::OneLine(origin), error.loc)]
        Invalid {
            /// The file, or `<string>`.
            origin: String,
            /// The rule broken, where, and in which link and field.
            #[source]
            error: validate::Error<raw::Position>,
        },
    }

    impl LoadError {
        /// The file, or `<string>`.
        pub fn origin(&self) -> &str {
            match self {
                LoadError::Io { origin, .. }
                | LoadError::Syntax { origin, .. }
                | LoadError::Urdf { origin, .. }
                | LoadError::Invalid { origin, .. } => origin,
            }
        }
    }

    impl RobotModel {
        /// Parses and validates a TOML description.
        pub fn from_toml_str(text: &str) -> Result<RobotModel, LoadError> {
            Self::from_toml_named(text, "<string>")
        }

        /// Reads, parses and validates a TOML description file.
        pub fn from_toml_file(path: impl AsRef<Path>) -> Result<RobotModel, LoadError> {
            let path = path.as_ref();
            let origin = path.display().to_string();
            let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
                origin: origin.clone(),
                source,
            })?;
            Self::from_toml_bytes(&bytes, &origin)
        }

        /// Parses and validates a TOML description given as bytes (a file's contents);
        /// `origin` names it in error messages. Bytes that are not UTF-8 are a syntax error
        /// at the first one that is not.
        pub fn from_toml_bytes(bytes: &[u8], origin: &str) -> Result<RobotModel, LoadError> {
            match core::str::from_utf8(bytes) {
                Ok(text) => Self::from_toml_named(text, origin),
                // TOML is UTF-8: say where the text stops being that.
                Err(e) => Err(LoadError::Syntax {
                    origin: origin.to_string(),
                    error: raw::SyntaxError {
                        loc: raw::utf8_error_position(bytes, &e),
                        message: "the file is not UTF-8 text (TOML is UTF-8)".into(),
                    },
                }),
            }
        }

        /// Parses and validates TOML text; `origin` names it in error messages.
        pub fn from_toml_named(text: &str, origin: &str) -> Result<RobotModel, LoadError> {
            let table = raw::from_toml_text(text).map_err(|error| LoadError::Syntax {
                origin: origin.to_string(),
                error,
            })?;
            validate::validate(&table, None).map_err(|error| LoadError::Invalid {
                origin: origin.to_string(),
                error,
            })
        }
    }
}
