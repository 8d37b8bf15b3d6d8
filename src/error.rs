//! The error type of the runtime path.

/// Why a [`Robot`](crate::Robot) could not be built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The description could not be read, parsed or validated. The message names the file
    /// (or `<string>`), and for a validation error the link and the field at fault, e.g.
    /// `robots/arm.toml: link 2, field \`mass\`: mass -1 is negative`.
    #[error(transparent)]
    Load(#[from] dhgen_description::LoadError),
}
