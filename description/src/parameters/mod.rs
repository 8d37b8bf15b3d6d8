//! The inertial parameters of a robot: their order, names and values, and the reduction of a
//! regressor to base parameters. One definition, read by the runtime regressor
//! (`dhgen::Robot::regressor`) and by the generated one (`robot!`'s `regressor`), so both
//! number the columns alike and regroup them by the same rule.
//!
//! # The parameters
//! Ten per link, in Pinocchio's order (`Inertia::toDynamicParameters`), in that link's frame
//! (the frame the description gives its `com` and `inertia` in: DH frame i, or the URDF link
//! frame), about the frame's origin, as identification practice writes them:
//! `m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, with `c` the centre of mass and
//! `I = I_c + m (|c|² 1 − c cᵀ)` (`Ixy` the tensor entry, `−∫xy dm`). After the 10·n link
//! columns come the joint-side terms where the description has them, joint by joint: the
//! armature `Jm·G²` (a joint with a `motor`; column `q̈_i`), then the viscous and Coulomb
//! coefficients (a joint with `friction`; columns `q̇_i` and `sign(q̇_i)`).
//!
//! # Base parameters
//! Columns of `Y` that are zero at every state, or combinations of others, leave
//! `τ = Y_b π_b` with `π_b = π_i + β π_d`: what identification can recover.
//! [`base_parameters`] finds them numerically, by Gautier's rank-revealing QR with column
//! pivoting of `Y` stacked over seeded random states: it regroups any chain (URDF frames,
//! oblique axes), where Khalil and Bennis's symbolic rules cover the parallel and perpendicular
//! axes of DH tables only. It is made exact enough to be reproducible: the states come from a
//! fixed seed (`dhgen_kernel::stream::Stream`), the columns are scaled to unit norm before pivoting
//! so the choice does not depend on units, a column counts as independent when its pivot is
//! above `1e-9` of the largest, and coefficients of `β` below `1e-10` in magnitude are exactly
//! zero.
//!
//! ```
//! use dhgen_description::parameters::{self, Column};
//! let model = dhgen_description::RobotModel::from_toml_str(r#"
//!     name = "pendulum"
//!     convention = "standard"
//!     [[links]]
//!     joint = "revolute"
//!     a = 1.0
//!     alpha = 0.0
//!     d = 0.0
//!     theta = 0.0
//!     mass = 2.0
//!     com = [-0.5, 0.0, 0.0]
//!     inertia = { xx = 0.0, yy = 0.1, zz = 0.1 }
//!     friction = { viscous = 0.1, coulomb = 0.2 }
//! "#).unwrap();
//! let columns = parameters::columns(&model);
//! assert_eq!(columns.len(), 12);
//! assert_eq!(columns[10], Column::Viscous(0));
//! assert_eq!(parameters::names(&model)[1], "mx1");
//! let pi = parameters::values(&model).unwrap();
//! assert_eq!(pi[1], -1.0); // m·cx
//! assert_eq!(pi[9], 0.1 + 2.0 * 0.25); // Izz about the frame's origin
//! ```

#[cfg(feature = "std")]
use crate::{ChainRef, RobotModel};
#[cfg(feature = "std")]
use dhgen_kernel::stream::Stream;
#[cfg(feature = "std")]
use nalgebra::{DMatrix, DVector};

pub use dhgen_kernel::parameters::{
    BODY_PARAMETER_NAMES, BODY_PARAMETERS, Column, INERTIA_ENTRIES, body_parameters, inertia_of,
};

/// The regressor's columns, in order: ten per link, then the joint-side terms the description
/// has.
#[cfg(feature = "std")]
pub fn columns(model: &RobotModel) -> Vec<Column> {
    let mut out: Vec<Column> = (0..model.dof())
        .flat_map(|link| (0..BODY_PARAMETERS).map(move |k| Column::Body { link, k }))
        .collect();
    for (i, l) in model.links.iter().enumerate() {
        if l.motor.is_some() {
            out.push(Column::Armature(i));
        }
        if l.friction.is_some() {
            out.push(Column::Viscous(i));
            out.push(Column::Coulomb(i));
        }
    }
    out
}

/// The parameters' names, in order: `m1, mx1, ..., Izz1, m2, ...`, then `Ia3` (armature of
/// joint 3), `fv3`, `fc3` (viscous and Coulomb friction of joint 3).
#[cfg(feature = "std")]
pub fn names(model: &RobotModel) -> Vec<String> {
    columns(model)
        .into_iter()
        .map(|c| match c {
            Column::Body { link, k } => format!("{}{}", BODY_PARAMETER_NAMES[k], link + 1),
            Column::Armature(i) => format!("Ia{}", i + 1),
            Column::Viscous(i) => format!("fv{}", i + 1),
            Column::Coulomb(i) => format!("fc{}", i + 1),
        })
        .collect()
}

/// The robot's own parameters `π`, in the order of [`columns`]; `None` when a link has no
/// mass properties.
#[cfg(feature = "std")]
pub fn values(model: &RobotModel) -> Option<Vec<f64>> {
    let body: Vec<[f64; BODY_PARAMETERS]> = model
        .links
        .iter()
        .map(|l| {
            l.inertial
                .map(|i| body_parameters(i.mass, &i.com, &i.inertia))
        })
        .collect::<Option<_>>()?;
    Some(
        columns(model)
            .into_iter()
            .map(|c| {
                let link = |i: usize| &model.links[i];
                match c {
                    Column::Body { link, k } => body[link][k],
                    Column::Armature(i) => link(i).motor.map_or(0.0, |m| m.armature()),
                    Column::Viscous(i) => link(i).friction.map_or(0.0, |f| f.viscous),
                    Column::Coulomb(i) => link(i).friction.map_or(0.0, |f| f.coulomb),
                }
            })
            .collect(),
    )
}

/// Why parameter values could not be taken as a robot's.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[cfg(feature = "std")]
#[non_exhaustive]
pub enum ParameterError {
    /// Another number of values than the robot (or the regrouping) has parameters.
    #[error("{given} {what} given where the robot has {expected}")]
    Count {
        /// What was counted: `"parameter values"`, `"base parameter values"`.
        what: &'static str,
        /// The values given.
        given: usize,
        /// The values expected.
        expected: usize,
    },
    /// A value, or what it implies for its link (the centre of mass `m·c / m`, the inertia
    /// about it), breaks a rule of the description format.
    #[error("parameter {name} (index {index}): {message}")]
    Value {
        /// The parameter's name ([`names`]), e.g. `mx3`, `Izz2`, `fv1`; for values given as
        /// base parameters, `base parameter 4` (from 1), or `information` for the matrix of
        /// `BaseParameters::nearest_physical`.
        name: String,
        /// Its index in `π`.
        index: usize,
        /// What is wrong.
        message: String,
    },
    /// A link of the reference model has no mass properties to take the values motion
    /// cannot tell from (`BaseParameters::expand_physical`).
    #[error("link {link} has no mass properties to take the values motion cannot tell from")]
    NoMassProperties {
        /// The link, from 1.
        link: usize,
    },
    /// No parameters with the given base parameters make every link physical
    /// (`BaseParameters::expand_physical`).
    #[error(
        "no physical robot has these base parameters: {name} cannot be made physical ({message})"
    )]
    Infeasible {
        /// What cannot be made physical: `link 3`, or a joint-side term's name (`Ia1`).
        name: String,
        /// How far from physical it stays.
        message: String,
    },
}

/// What [`with_values`] asks of each link's values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg(feature = "std")]
pub enum Links {
    /// Physical links, by the rules a description obeys (see [`with_values`]).
    Physical,
    /// Values in range only (and a massless link without first moment): links that may be no
    /// body's, a negative mass or an inertia that is not positive semi-definite, whose
    /// equations of motion are still the robot's. Base parameters expanded over a reference
    /// ([`BaseParameters::expand`]) usually need it: motion fixes only the base parameters'
    /// combinations, and the reference's values for the rest rarely leave every link physical
    /// (of the 18 robots with mass properties in dhgen's tests on 2026-12-06, base parameters
    /// of a copy 15 % heavier expanded over the original's values left 17 with an unphysical
    /// link). A model of such links is a `dhgen::Robot` (its torques, `D(q)`, forward dynamics
    /// are the identified robot's), not a description: [`RobotModel::to_toml`] writes it,
    /// validation refuses it.
    AsGiven,
}

/// The robot `model` with the parameters `pi` (in the order of [`columns`]): each link's mass,
/// centre of mass `m·c / m` and inertia about it (`I − m (|c|² 1 − c cᵀ)`, from `I` about the
/// frame's origin), each motor's rotor inertia (`Jm = Ia / G²`, its gear kept), each joint's
/// friction; everything else as it was. The inverse of [`values`]: a model built from a
/// parameter vector, identified ones say (expanded from base parameters by
/// [`BaseParameters::expand`]), for `dhgen::Robot::from_model` or a
/// description file ([`RobotModel::to_toml`]).
///
/// With [`Links::Physical`], the values must describe physical links, by the rules a
/// description obeys: finite, a mass in range and not negative (a massless link with no first
/// moment), the centre of mass within range, the inertia about it positive semi-definite and
/// obeying the triangle inequality (unless the link's inertia in `model` already broke it, as
/// `allow_nonphysical_inertia` permits), rotor inertias and friction coefficients not negative.
/// With [`Links::AsGiven`], finite values in range (and a massless link with no first moment).
///
/// # Errors
/// [`ParameterError::Count`] unless `pi` has one value per column;
/// [`ParameterError::Value`] naming the first parameter that breaks a rule (for a link's
/// inertia, its `Ixx`).
///
/// ```
/// use dhgen_description::parameters::{Links, values, with_values};
/// let model = dhgen_description::RobotModel::from_toml_file("../robots/puma560.toml").unwrap();
/// let mut pi = values(&model).unwrap();
/// pi[20] *= 1.1; // link 3's mass, its first moment and inertia about the origin kept
/// let heavier = with_values(&model, &pi, Links::Physical).unwrap();
/// assert_eq!(heavier.links[2].inertial.unwrap().mass, pi[20]);
/// assert_eq!(values(&heavier).unwrap()[20], pi[20]);
/// pi[20] = -1.0;
/// assert!(with_values(&model, &pi, Links::Physical).unwrap_err().to_string().contains("m3"));
/// // A negative mass moves by the same equations.
/// assert!(with_values(&model, &pi, Links::AsGiven).is_ok());
/// ```
#[cfg(feature = "std")]
pub fn with_values(
    model: &RobotModel,
    pi: &[f64],
    links: Links,
) -> Result<RobotModel, ParameterError> {
    use crate::validate::{
        FRICTION, INERTIA, LENGTH, MASS, ROTOR_INERTIA, check_inertia_tensor, check_mass,
    };
    let columns = columns(model);
    if pi.len() != columns.len() {
        return Err(ParameterError::Count {
            what: "parameter values",
            given: pi.len(),
            expected: columns.len(),
        });
    }
    let names = names(model);
    let fail = |index: usize, message: String| ParameterError::Value {
        name: names[index].clone(),
        index,
        message,
    };
    if let Some(index) = pi.iter().position(|x| !x.is_finite()) {
        return Err(fail(index, format!("{} is not a finite number", pi[index])));
    }
    let physical = links == Links::Physical;
    let mut out = model.clone();
    for (i, link) in out.links.iter_mut().enumerate() {
        let first = BODY_PARAMETERS * i;
        let p: [f64; BODY_PARAMETERS] = core::array::from_fn(|k| pi[first + k]);
        let mass = p[0];
        if physical {
            check_mass(mass).map_err(|message| fail(first, message))?;
        } else {
            MASS.check_value(mass.abs())
                .map_err(|message| fail(first, message))?;
        }
        let moment = [p[1], p[2], p[3]];
        let com = if mass != 0.0 {
            moment.map(|x| x / mass)
        } else if moment == [0.0; 3] {
            [0.0; 3]
        } else {
            return Err(fail(
                first + 1,
                format!("a massless link's first moment m·c = {moment:?} is not zero"),
            ));
        };
        for (k, c) in com.iter().enumerate() {
            LENGTH
                .check_value(*c)
                .map_err(|message| fail(first + 1 + k, format!("centre of mass: {message}")))?;
        }
        // I_c = I_o − m (|c|² 1 − c cᵀ): the parallel-axis term is body_parameters' own, of
        // the mass at the centre with no inertia about it.
        let (origin, shift) = (
            inertia_of(&p),
            inertia_of(&body_parameters(mass, &com, &[[0.0; 3]; 3])),
        );
        let inertia: [[f64; 3]; 3] =
            core::array::from_fn(|a| core::array::from_fn(|b| origin[a][b] - shift[a][b]));
        if physical {
            // The triangle inequality as the description had it (`allow_nonphysical_inertia`).
            let allowed = link.inertial.is_some_and(|old| {
                !crate::validate::obeys_triangle_inequality(&old.inertia, old.mass)
            });
            check_inertia_tensor(&inertia, mass, allowed).map_err(|message| {
                fail(
                    first + INERTIA_ENTRIES[0][0],
                    format!("inertia about the centre of mass: {message}"),
                )
            })?;
        } else if let Some((a, b)) = (0..3)
            .flat_map(|a| (0..3).map(move |b| (a, b)))
            .find(|&(a, b)| INERTIA.check_value(inertia[a][b]).is_err())
        {
            return Err(fail(
                first + INERTIA_ENTRIES[a][b],
                format!(
                    "inertia about the centre of mass: entry {} is out of range",
                    inertia[a][b]
                ),
            ));
        }
        link.inertial = Some(crate::Inertial { mass, com, inertia });
    }
    for (index, column) in columns
        .iter()
        .enumerate()
        .skip(BODY_PARAMETERS * model.dof())
    {
        let x = pi[index];
        if x < 0.0 && links == Links::Physical {
            return Err(fail(index, format!("{x} is negative")));
        }
        let in_range = |range: crate::validate::Range, x: f64, what: &str| {
            range
                .check_value(x.abs())
                .map(|_| x)
                .map_err(|message| fail(index, format!("{what}{message}")))
        };
        match *column {
            Column::Armature(i) => {
                if let Some(motor) = out.links[i].motor.as_mut() {
                    let jm = x / (motor.gear * motor.gear);
                    motor.inertia = in_range(ROTOR_INERTIA, jm, "rotor inertia Ia / G²: ")?;
                }
            }
            Column::Viscous(i) => {
                if let Some(f) = out.links[i].friction.as_mut() {
                    f.viscous = in_range(FRICTION, x, "")?;
                }
            }
            Column::Coulomb(i) => {
                if let Some(f) = out.links[i].friction.as_mut() {
                    f.coulomb = in_range(FRICTION, x, "")?;
                }
            }
            Column::Body { .. } => {}
        }
    }
    Ok(out)
}

/// The regrouping of a robot's parameters into base parameters (see the
/// [module](self)).
#[derive(Clone, Debug, PartialEq)]
#[cfg(feature = "std")]
pub struct BaseParameters {
    /// The independent parameters, by index into `π`, in pivot order: base parameter `k` is
    /// `π[independent[k]] + Σ_m β[k][m] π[dependent[m]]`.
    pub independent: Vec<usize>,
    /// The parameters regrouped into the independent ones (or identically without effect).
    pub dependent: Vec<usize>,
    /// `β`, `independent.len() × dependent.len()`.
    pub beta: DMatrix<f64>,
}

#[cfg(feature = "std")]
impl BaseParameters {
    /// The number of base parameters.
    pub fn count(&self) -> usize {
        self.independent.len()
    }

    /// `π_b = π_i + β π_d` for parameters `pi` in the order of [`columns`].
    pub fn reduce(&self, pi: &DVector<f64>) -> DVector<f64> {
        let dependent =
            DVector::from_iterator(self.dependent.len(), self.dependent.iter().map(|&d| pi[d]));
        DVector::from_iterator(self.count(), self.independent.iter().map(|&i| pi[i]))
            + &self.beta * dependent
    }

    /// A full parameter vector with base parameters `base`: the dependent parameters taken
    /// from `reference` (a description's, [`values`]: what motion cannot tell, left as the
    /// description has it) and each independent one set so that [`reduce`](Self::reduce)
    /// gives `base` (`π_i = π_b − β π_d`). Every such vector gives the same torques for every
    /// motion (`Y π = Y_b π_b`), so the same `D(q)`, `C`, `g` and forward dynamics; a model
    /// of it is [`with_values`]'s, usually with [`Links::AsGiven`] (see there).
    ///
    /// # Errors
    /// [`ParameterError::Count`] unless `base` has [`count`](Self::count) values and
    /// `reference` one per parameter.
    pub fn expand(&self, base: &[f64], reference: &[f64]) -> Result<DVector<f64>, ParameterError> {
        if base.len() != self.count() {
            return Err(ParameterError::Count {
                what: "base parameter values",
                given: base.len(),
                expected: self.count(),
            });
        }
        let needed = self
            .independent
            .iter()
            .chain(&self.dependent)
            .max()
            .map_or(0, |m| m + 1);
        if reference.len() != needed {
            return Err(ParameterError::Count {
                what: "reference parameter values",
                given: reference.len(),
                expected: needed,
            });
        }
        let mut pi = DVector::from_column_slice(reference);
        for (k, &i) in self.independent.iter().enumerate() {
            let regrouped: f64 = self
                .dependent
                .iter()
                .enumerate()
                .map(|(m, &d)| self.beta[(k, m)] * reference[d])
                .sum();
            pi[i] = base[k] - regrouped;
        }
        Ok(pi)
    }

    /// The base regressor: the independent columns of a regressor `y`, so that
    /// `base_regressor(y) · reduce(π) = y · π`.
    pub fn base_regressor(&self, y: &DMatrix<f64>) -> DMatrix<f64> {
        DMatrix::from_fn(y.nrows(), self.count(), |r, c| y[(r, self.independent[c])])
    }

    /// The regrouping rules as text, one per base parameter, e.g. `Izz2 + 0.25·m3 + Iyy3`
    /// (names from [`names`]).
    pub fn rules(&self, names: &[String]) -> Vec<String> {
        (0..self.count())
            .map(|k| {
                let mut s = names[self.independent[k]].clone();
                for (m, &d) in self.dependent.iter().enumerate() {
                    let b = self.beta[(k, m)];
                    if b == 0.0 {
                        continue;
                    }
                    let sign = if b < 0.0 { " − " } else { " + " };
                    if (b.abs() - 1.0).abs() < 1e-12 {
                        s += &format!("{sign}{}", names[d]);
                    } else {
                        s += &format!("{sign}{}·{}", trim(b.abs()), names[d]);
                    }
                }
                s
            })
            .collect()
    }
}

/// A coefficient to 10 significant digits, without trailing zeros.
#[cfg(feature = "std")]
fn trim(x: f64) -> String {
    let s = format!("{x:.10}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// A state `(q, q̇, q̈)`.
#[cfg(feature = "std")]
pub type State = (Vec<f64>, Vec<f64>, Vec<f64>);

/// The states the reduction samples for a chain with `parameters` columns: `max(20, 4·p/n)`
/// of them from a fixed seed, positions in the joint limits (±π without), velocities and
/// accelerations in ±2.
#[cfg(feature = "std")]
pub fn sample_states(chain: ChainRef<'_>, parameters: usize) -> Vec<State> {
    let n = chain.dof();
    let count = (4 * parameters).div_ceil(n).max(20);
    let mut rng = Stream(0x00D1_6E11);
    (0..count)
        .map(|_| {
            let q: Vec<f64> = chain
                .bodies
                .iter()
                .map(|b| match b.limits {
                    Some([lo, hi]) => rng.uniform(lo, hi),
                    None => rng.uniform(-core::f64::consts::PI, core::f64::consts::PI),
                })
                .collect();
            let qd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let qdd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
            (q, qd, qdd)
        })
        .collect()
}

/// The base parameters of the robot `model`, from its regressor `regressor(q, q̇, q̈)` (`n ×
/// columns(model).len()`) stacked over [`sample_states`] and reduced by [`reduce`].
#[cfg(feature = "std")]
pub fn base_parameters(
    model: &RobotModel,
    mut regressor: impl FnMut(&[f64], &[f64], &[f64]) -> DMatrix<f64>,
) -> BaseParameters {
    let structure = model.chain();
    let chain = structure.view();
    let (n, p) = (model.dof(), columns(model).len());
    let states = sample_states(chain, p);
    let mut stacked = DMatrix::zeros(states.len() * n, p);
    for (s, (q, qd, qdd)) in states.iter().enumerate() {
        stacked.rows_mut(s * n, n).copy_from(&regressor(q, qd, qdd));
    }
    reduce(&stacked)
}

/// Householder QR with column pivoting, `A P = Q R`: the column order `P` and `R` (its first
/// `min(rows, columns)` rows).
///
/// At each step the column with the largest remaining norm is brought forward; columns whose
/// remaining norms agree with the largest to a relative 1e-8 are ties, resolved to the lowest
/// original index. Rounding (two derivations of the same regressor differ in the last bits)
/// cannot then change the choice, so the runtime and generated regressors regroup alike, and
/// the earliest parameters (the links nearer the base, masses before inertias) are kept.
#[cfg(feature = "std")]
fn pivoted_qr(mut a: DMatrix<f64>) -> (Vec<usize>, DMatrix<f64>) {
    let (rows, p) = a.shape();
    let mut order: Vec<usize> = (0..p).collect();
    let steps = rows.min(p);
    for k in 0..steps {
        let norms: Vec<f64> = (k..p)
            .map(|j| a.column(j).rows(k, rows - k).norm())
            .collect();
        let top = norms.iter().copied().fold(0.0, f64::max);
        if top == 0.0 {
            break;
        }
        let pick = (k..p)
            .filter(|&j| norms[j - k] >= top * (1.0 - 1e-8))
            .min_by_key(|&j| order[j])
            .expect("the largest is a candidate");
        a.swap_columns(k, pick);
        order.swap(k, pick);
        // The reflection taking column k's remaining part to (α, 0, ..., 0).
        let mut v = a.column(k).rows(k, rows - k).into_owned();
        let alpha = if v[0] > 0.0 { -v.norm() } else { v.norm() };
        v[0] -= alpha;
        let vv = v.norm_squared();
        if vv > 0.0 {
            for j in k..p {
                let mut col = a.column_mut(j);
                let mut col = col.rows_mut(k, rows - k);
                let s = 2.0 * v.dot(&col) / vv;
                col.axpy(-s, &v, 1.0);
            }
        }
        a[(k, k)] = alpha;
        a.column_mut(k).rows_mut(k + 1, rows - k - 1).fill(0.0);
    }
    (order, a.rows(0, steps).upper_triangle())
}

/// Gautier's reduction of a stacked regressor: column-pivoted QR of the unit-norm columns.
#[cfg(feature = "std")]
pub fn reduce(stacked: &DMatrix<f64>) -> BaseParameters {
    let p = stacked.ncols();
    let norms: Vec<f64> = (0..p).map(|c| stacked.column(c).norm()).collect();
    let largest = norms.iter().copied().fold(0.0, f64::max);
    let mut scaled = stacked.clone();
    for (c, &norm) in norms.iter().enumerate() {
        if norm > 1e-12 * largest {
            scaled.column_mut(c).scale_mut(1.0 / norm);
        } else {
            scaled.column_mut(c).fill(0.0);
        }
    }
    let (order, r) = pivoted_qr(scaled);
    let diag = r.diagonal();
    let top = diag.iter().map(|d| d.abs()).fold(0.0, f64::max);
    let rank = diag.iter().take_while(|d| d.abs() > 1e-9 * top).count();
    let independent = order[..rank].to_vec();
    let dependent = order[rank..].to_vec();
    // β in the scaled columns: R1 β_s = R2, then back to the parameters' units.
    let r1 = r.view((0, 0), (rank, rank)).into_owned();
    let r2 = r.view((0, rank), (rank, p - rank)).into_owned();
    let beta_scaled = r1
        .solve_upper_triangular(&r2)
        .unwrap_or_else(|| DMatrix::zeros(rank, p - rank));
    let mut beta = DMatrix::zeros(rank, p - rank);
    for k in 0..rank {
        for m in 0..p - rank {
            let (i, d) = (independent[k], dependent[m]);
            // Column d = Σ_k β_s[k][m] column i (scaled): in units, β = β_s · |Y_i| / |Y_d|
            // for the parameters (π_i absorbs β π_d).
            // Zero where column i's share of column d is rounding (both unit-norm, so the
            // test is the same in any units).
            let b = if norms[d] > 1e-12 * largest && beta_scaled[(k, m)].abs() >= 1e-10 {
                beta_scaled[(k, m)] * norms[d] / norms[i]
            } else {
                0.0
            };
            beta[(k, m)] = b;
        }
    }
    BaseParameters {
        independent,
        dependent,
        beta,
    }
}
