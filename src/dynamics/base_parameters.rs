//! Base parameters: the minimal set of combinations of the inertial parameters that the
//! dynamics determine.
//!
//! Many columns of the regressor `Y` are zero at every state (a parameter that never moves
//! anything: the first link's mass) or linear combinations of others (Ixx and Iyy of a link
//! turning about z enter only as their difference with others). `τ = Y π` is then also
//! `τ = Y_b π_b` with `Y_b` the `b` independent columns and `π_b = π_i + β π_d` regrouping the
//! dependent parameters `π_d` into the independent ones `π_i`: what identification can
//! recover, and all it needs.
//!
//! # Method
//! Numerical, by a rank-revealing QR decomposition with column pivoting (Gautier's method)
//! of `Y` stacked over random states: it finds the regrouping of any robot, where a symbolic
//! rule set (Khalil and Bennis's) covers the parallel and perpendicular axes of DH tables
//! only. It is made exact enough to be reproducible: the states come from a fixed seed
//! (`dhgen_model::random::Stream`, splitmix64), the columns are scaled to unit norm before pivoting so the choice does not
//! depend on units, a column counts as independent when its pivot is above `1e-9` of the
//! largest, and coefficients of `β` below `1e-10` in magnitude are exactly zero. The test
//! `base_parameter_count_is_the_rank` checks the count against the rank of `Y` stacked over
//! 1,000 states by a singular value decomposition, an independent computation.

use crate::robot::Robot;
use nalgebra::{DMatrix, DVector};

/// The regrouping of a robot's parameters into base parameters (see the [`dhgen::parameters`](crate::parameters)).
#[derive(Clone, Debug, PartialEq)]
pub struct BaseParameters {
    /// The independent parameters, by index into `π`, in pivot order: base parameter `k` is
    /// `π[independent[k]] + Σ_m β[k][m] π[dependent[m]]`.
    pub independent: Vec<usize>,
    /// The parameters regrouped into the independent ones (or identically without effect).
    pub dependent: Vec<usize>,
    /// `β`, `independent.len() × dependent.len()`.
    pub beta: DMatrix<f64>,
}

impl BaseParameters {
    /// The number of base parameters.
    pub fn count(&self) -> usize {
        self.independent.len()
    }

    /// `π_b = π_i + β π_d` for parameters `pi` in the order of [`Robot::parameters`].
    pub fn reduce(&self, pi: &DVector<f64>) -> DVector<f64> {
        let dependent =
            DVector::from_iterator(self.dependent.len(), self.dependent.iter().map(|&d| pi[d]));
        DVector::from_iterator(self.count(), self.independent.iter().map(|&i| pi[i]))
            + &self.beta * dependent
    }

    /// The base regressor: the independent columns of a regressor `y`, so that
    /// `base_regressor(y) · reduce(π) = y · π`.
    pub fn base_regressor(&self, y: &DMatrix<f64>) -> DMatrix<f64> {
        DMatrix::from_fn(y.nrows(), self.count(), |r, c| y[(r, self.independent[c])])
    }

    /// The regrouping rules as text, one per base parameter that regroups anything, e.g.
    /// `Izz2 + 0.25·m3 + Iyy3` (names from [`Robot::parameter_names`]).
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
fn trim(x: f64) -> String {
    let s = format!("{x:.10}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

impl Robot {
    /// The robot's base parameters (see the [`dhgen::parameters`](crate::parameters)), from its regressor stacked
    /// over `max(20, 4·p/n)` seeded random states (`p` parameters, `n` joints): positions in
    /// the joint limits (±π without), velocities and accelerations in ±2.
    ///
    /// # Panics
    /// If the robot has no mass properties.
    pub fn base_parameters(&self) -> BaseParameters {
        self.check_dynamics("base_parameters");
        let n = self.dof();
        let p = self.parameter_count();
        let states = (4 * p).div_ceil(n).max(20);
        let mut rng = dhgen_model::random::Stream(0x00D1_6E11);
        let mut stacked = DMatrix::zeros(states * n, p);
        for s in 0..states {
            let q: Vec<f64> = self
                .chain()
                .bodies
                .iter()
                .map(|b| match b.limits {
                    Some([lo, hi]) => rng.uniform(lo, hi),
                    None => rng.uniform(-core::f64::consts::PI, core::f64::consts::PI),
                })
                .collect();
            let qd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let qdd: Vec<f64> = (0..n).map(|_| rng.uniform(-2.0, 2.0)).collect();
            let y = self.regressor(&q[..], &qd[..], &qdd[..]);
            stacked.rows_mut(s * n, n).copy_from(&y);
        }
        reduce_columns(&stacked)
    }
}

/// Gautier's reduction of a stacked regressor: column-pivoted QR of the unit-norm columns.
fn reduce_columns(stacked: &DMatrix<f64>) -> BaseParameters {
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
    let qr = scaled.col_piv_qr();
    let r = qr.r();
    // The pivot order: apply the permutation to the column indices.
    let mut order = DMatrix::<f64>::from_fn(1, p, |_, c| c as f64);
    qr.p().permute_columns(&mut order);
    let order: Vec<usize> = order.iter().map(|&c| c as usize).collect();
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
            let b = if norms[d] > 1e-12 * largest {
                beta_scaled[(k, m)] * norms[d] / norms[i]
            } else {
                0.0
            };
            beta[(k, m)] = if b.abs() < 1e-10 { 0.0 } else { b };
        }
    }
    BaseParameters {
        independent,
        dependent,
        beta,
    }
}
