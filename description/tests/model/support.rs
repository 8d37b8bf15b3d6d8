//! Helpers shared by the test modules.

use dhgen_description::{Frame, JointKind, JointValue, RobotModel};

/// The catalogue's directory, `robots/` of the workspace.
pub fn dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../robots")
}

/// The catalogue robot `robots/<stem>.toml`.
pub fn load(stem: &str) -> RobotModel {
    let path = dir().join(format!("{stem}.toml"));
    RobotModel::from_toml_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// base · A_1(q_1) ⋯ A_n(q_n) by the one DH formula; with the frames after each row (frames
/// 0..=n, the tool pose left out).
pub fn dh_frames(robot: &RobotModel, q: &[f64]) -> Vec<Frame<f64>> {
    let mut t = robot
        .base
        .map_or_else(Frame::identity, |p| p.frame::<f64>());
    let mut out = vec![t];
    for (link, &qi) in robot.links.iter().zip(q) {
        let value = match link.joint {
            JointKind::Revolute => JointValue::Revolute {
                cos: qi.cos(),
                sin: qi.sin(),
            },
            JointKind::Prismatic => JointValue::Prismatic(qi),
        };
        t = t.compose(&link.transform(robot.convention, value));
        out.push(t);
    }
    out
}
