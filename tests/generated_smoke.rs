dhgen::robot!(pub mod puma = "robots/puma560.toml");

#[test]
fn smoke() {
    let q = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6];
    let d = puma::mass_matrix(&q);
    println!("{d}");
}
