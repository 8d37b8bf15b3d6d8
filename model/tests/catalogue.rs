//! Every robot of the catalogue loads and validates.

use dhgen_model::RobotModel;

#[test]
fn catalogue_loads() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots");
    let mut count = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let robot = RobotModel::from_toml_file(&path).unwrap_or_else(|e| panic!("{e}"));
            assert!(robot.dof() > 0);
            count += 1;
        }
    }
    assert!(count >= 4);
}
