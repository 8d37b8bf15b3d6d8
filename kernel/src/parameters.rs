//! The layout of a body's inertial parameters: ten per link, in Pinocchio's order
//! (`Inertia::toDynamicParameters`), `m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, in
//! the link's frame, about its origin. The regressor's columns, their names and values, and
//! the base parameters are `dhgen-description`'s `parameters`.

/// The number of inertial parameters of one body.
pub const BODY_PARAMETERS: usize = 10;

/// The names of a body's ten parameters, in order (`m`, `mx` for `m·cx`, ..., `Izz`).
pub const BODY_PARAMETER_NAMES: [&str; BODY_PARAMETERS] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// The ten parameters of a body of mass `mass`, centre of mass `com` and inertia `i_com` about
/// it, all in one frame: `[m, m·c, I about the origin]` in the order of [`BODY_PARAMETER_NAMES`].
pub fn body_parameters(mass: f64, com: &[f64; 3], i_com: &[[f64; 3]; 3]) -> [f64; BODY_PARAMETERS] {
    let cc = com[0] * com[0] + com[1] * com[1] + com[2] * com[2];
    // I = I_c + m (|c|² 1 − c cᵀ)
    let i =
        |a: usize, b: usize| i_com[a][b] + mass * (if a == b { cc } else { 0.0 } - com[a] * com[b]);
    let mut out = [0.0; BODY_PARAMETERS];
    out[0] = mass;
    for a in 0..3 {
        out[1 + a] = mass * com[a];
        for b in a..3 {
            out[INERTIA_ENTRIES[a][b]] = i(a, b);
        }
    }
    out
}

/// Where each entry of the inertia tensor sits among a body's parameters: `I[a][b]` is
/// parameter `INERTIA_ENTRIES[a][b]` (`Ixx, Ixy, Iyy, Ixz, Iyz, Izz` are 4 to 9).
pub const INERTIA_ENTRIES: [[usize; 3]; 3] = [[4, 5, 7], [5, 6, 8], [7, 8, 9]];

/// The inertia tensor `[[Ixx, Ixy, Ixz], ...]` of a body's parameters `p`.
pub fn inertia_of(p: &[f64; BODY_PARAMETERS]) -> [[f64; 3]; 3] {
    INERTIA_ENTRIES.map(|row| row.map(|k| p[k]))
}

/// What one column of the regressor (one parameter) is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Column {
    /// Parameter `k` (of [`BODY_PARAMETER_NAMES`]) of link `link` (from 0).
    Body {
        /// The link, from 0.
        link: usize,
        /// The parameter, an index into [`BODY_PARAMETER_NAMES`].
        k: usize,
    },
    /// The armature `Jm·G²` of joint i (column `q̈_i`).
    Armature(usize),
    /// The viscous friction coefficient of joint i (column `q̇_i`).
    Viscous(usize),
    /// The Coulomb friction of joint i (column `sign(q̇_i)`).
    Coulomb(usize),
}
