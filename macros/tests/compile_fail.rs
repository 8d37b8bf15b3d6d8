//! Compile-fail tests of `robot!`: each bad description in tests/compile_fail/*.rs must stop
//! the build with the message committed next to it (`*.stderr`), pointing at the offending
//! token (inline form) or naming the file, line, link and field (file form).
//!
//! The cases invoke the macro as `dhgen_macros::robot!`, which `dhgen::robot!` re-exports:
//! the same macro, checked without building the rest of dhgen (nalgebra, the planning
//! stack), since a rejected description never reaches generated code.
//!
//! Regenerate the snapshots with
//! `TRYBUILD=overwrite cargo test -p dhgen-macros --test compile_fail`, then read every
//! changed `.stderr` before committing it.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Where the file-form fixtures live, relative to this crate's manifest directory; the
/// test files name them by this same relative path.
const FIXTURES: &str = "tests/compile_fail/robots";

#[test]
fn robot_macro_rejects_bad_descriptions() {
    place_file_fixtures();
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/compile_fail/*.rs");
}

/// `robot!("path")` resolves `path` against the invoking crate's `CARGO_MANIFEST_DIR`.
/// trybuild compiles each test file as a binary of a scratch crate whose manifest directory
/// is `<target dir>/tests/trybuild/<this crate's name>/`, and copies nothing into it. So that
/// the file-form tests see the same fixtures under the same relative path as this crate
/// does, the fixtures are copied there, mirroring `FIXTURES`. (The macro deliberately has no
/// fallback to other directories: a path means one file.)
fn place_file_fixtures() {
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join(FIXTURES);
    let scratch = trybuild_project_dir().join(FIXTURES);
    std::fs::create_dir_all(&scratch)
        .unwrap_or_else(|e| panic!("cannot create {}: {e}", scratch.display()));
    let entries = std::fs::read_dir(&source)
        .unwrap_or_else(|e| panic!("cannot list {}: {e}", source.display()));
    let mut copied = 0;
    for entry in entries {
        let path = entry.expect("directory entry").path();
        if path
            .extension()
            .is_some_and(|ext| ext == "toml" || ext == "urdf")
        {
            let to = scratch.join(path.file_name().expect("a file name"));
            std::fs::copy(&path, &to).unwrap_or_else(|e| {
                panic!("cannot copy {} to {}: {e}", path.display(), to.display())
            });
            copied += 1;
        }
    }
    assert!(copied > 0, "no fixtures in {}", source.display());
}

/// trybuild's scratch crate directory: `<target dir>/tests/trybuild/<crate name>/`, with the
/// target directory found the way trybuild finds it, from `cargo metadata`.
fn trybuild_project_dir() -> PathBuf {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args(["metadata", "--format-version=1", "--no-deps", "--offline"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo metadata runs");
    assert!(
        output.status.success(),
        "cargo metadata failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let metadata: serde_json::Value =
        serde_json::from_slice(&output.stdout).expect("cargo metadata prints JSON");
    let target_dir = metadata["target_directory"]
        .as_str()
        .expect("cargo metadata names the target directory");
    Path::new(target_dir)
        .join("tests")
        .join("trybuild")
        .join(env!("CARGO_PKG_NAME"))
}
