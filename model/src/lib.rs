//! The robot model of dhgen: the description format, its validation, and the DH
//! conventions shared by the runtime path and the code generator.
//!
//! Data flows one way: a description (a TOML file via [`RobotModel::from_toml_str`], or the
//! tokens of `robot!`) becomes a [`raw`] tree, [`validate`] turns the tree into a
//! [`RobotModel`], and everything downstream reads only the validated model.
//!
//! ```
//! let robot = dhgen_model::RobotModel::from_toml_str(r#"
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
//! ```

mod angle;
mod model;
pub mod raw;
pub mod validate;

pub use angle::Angle;
pub use model::{
    Collision, Convention, Frame, Friction, Inertial, JointKind, JointValue, Link, Motor, Pose,
    Ring, RobotModel,
};

use std::path::Path;

/// An error reading a description: where (the file, or `<string>`), and what.
///
/// A rule violation displays as `file:line:column: link N, field NAME: what is wrong`,
/// the form editors jump to.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadError {
    /// The file, or `<string>` for in-memory text.
    pub source: String,
    /// The TOML syntax error or validation error.
    pub kind: LoadErrorKind,
}

/// What went wrong while loading.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadErrorKind {
    /// The file could not be read.
    Io(String),
    /// The text is not valid TOML.
    Syntax(String),
    /// The description breaks a rule of the format, at a line and column of the text.
    Invalid(validate::Error<raw::Position>),
}

impl std::fmt::Display for LoadError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            LoadErrorKind::Io(e) => write!(f, "{}: cannot read file: {e}", self.source),
            LoadErrorKind::Syntax(e) => {
                write!(f, "{}: invalid TOML: {}", self.source, e.trim_end())
            }
            LoadErrorKind::Invalid(e) => write!(f, "{}:{}: {e}", self.source, e.loc),
        }
    }
}

impl std::error::Error for LoadError {}

impl RobotModel {
    /// Parses and validates a TOML description.
    pub fn from_toml_str(text: &str) -> Result<RobotModel, LoadError> {
        Self::from_toml_named(text, "<string>")
    }

    /// Reads, parses and validates a TOML description file.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<RobotModel, LoadError> {
        let path = path.as_ref();
        let source = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| LoadError {
            source: source.clone(),
            kind: LoadErrorKind::Io(e.to_string()),
        })?;
        Self::from_toml_named(&text, &source)
    }

    /// Parses and validates TOML text; `source` names it in error messages.
    pub fn from_toml_named(text: &str, source: &str) -> Result<RobotModel, LoadError> {
        let err = |kind| LoadError {
            source: source.to_string(),
            kind,
        };
        let table = raw::from_toml_text(text).map_err(|e| err(LoadErrorKind::Syntax(e)))?;
        validate::validate(&table, None).map_err(|e| err(LoadErrorKind::Invalid(e)))
    }
}
