//! Identifying inertial parameters from measured motion: linear least squares on the
//! regressor, accumulated sample by sample.
//!
//! The torques are linear in the inertial parameters, `τ = Y(q, q̇, q̈) π`, and only the base
//! parameters `π_b` are determined by motion (`τ = Y_b π_b`, see `dhgen::parameters`).
//! Recording `(q, q̇, q̈, τ)` on the robot and stacking `Y_b` over the recording gives an
//! overdetermined linear system whose least-squares solution is the estimate of `π_b`.
//!
//! [`LeastSquares`] takes the rows as they come (a sample's `n × b` block of `Y_b` and its `n`
//! torques, optionally weighted joint by joint) and folds each into an upper-triangular factor
//! by Givens rotations: memory `(b + 1)²` numbers however long the recording (a minute at
//! 1 kHz of a 7-joint arm with 43 base parameters would otherwise stack 18 million entries),
//! the same estimate as a QR factorisation of the whole stacked system (never the normal
//! equations, whose condition number is the square). [`LeastSquares::estimate`] returns the
//! parameters, their covariance and standard deviations (scaled by the residual variance, as
//! for unknown noise), the residual, and the condition number of the stacked regressor; a
//! recording that does not excite every base parameter is refused, with that condition number,
//! rather than answered with arbitrary values in the directions it left free.
//!
//! Least squares knows nothing of bodies: with noise, an estimate's base parameters may belong
//! to no physical robot (a lumped inertia below what the masses beyond it carry), and a model
//! of them then has links no body has. [`Estimate::physical`] is the constrained fit instead:
//! the base parameters nearest the estimate, in the metric of its covariance, whose expansion
//! has every link physical (Wensing, Kim and Slotine's pseudo-inertia condition).
//!
//! [`PeriodAverage`] prepares a periodic recording: its periods averaged, each channel's noise
//! variance estimated from their spread (the weights below), and the positions' harmonics as a
//! [`FourierSeries`](dhgen_trajectory::FourierSeries) that gives velocities and
//! accelerations without differentiating noise.
//!
//! Weights: with each joint's torque noise `σ_j` known (or estimated from a first, unweighted
//! fit's residuals), weighting joint `j`'s rows by `1/σ_j` gives the minimum-variance estimate
//! (Gautier's weighted least squares); the residual variance is then about 1.
//!
//! ```
//! use dhgen::identification::LeastSquares;
//! use dhgen::nalgebra::{SVector, Vector2};
//! dhgen::robot!(mod elbow = "../../robots/planar_elbow.toml", regressor);
//!
//! // The "measured" torques of the arm itself at a few states.
//! let truth = elbow::base_parameters(&elbow::PARAMETER_VALUES);
//! let mut fit = LeastSquares::new(elbow::BASE_PARAMETERS);
//! for k in 0..20 {
//!     let t = k as f64 * 0.37;
//!     let q = Vector2::new(t.sin(), (1.3 * t).cos());
//!     let qd = Vector2::new(t.cos(), -1.3 * (1.3 * t).sin());
//!     let qdd = Vector2::new(-t.sin(), -1.69 * (1.3 * t).cos());
//!     let tau = elbow::inverse_dynamics(&q, &qd, &qdd);
//!     fit.add(&elbow::base_regressor(&q, &qd, &qdd), &tau)?;
//! }
//! let estimate = fit.estimate()?;
//! for (e, t) in estimate.parameters.iter().zip(truth) {
//!     assert!((e - t).abs() < 1e-9 * t.abs().max(1.0));
//! }
//! # Ok::<(), dhgen::identification::IdentificationError>(())
//! ```

use nalgebra::{DMatrix, DVector, Dim, Matrix, RawStorage, U1};

mod periodic;
mod physical;

pub use periodic::PeriodAverage;
pub use physical::PhysicalConsistency;

/// Why rows could not be added, or no estimate formed.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum IdentificationError {
    /// A block of rows does not have the shape the fit expects: `columns` regressor columns
    /// (the fit's), and as many torques (and weights) as regressor rows.
    #[error(
        "identification: a block of {rows} regressor rows × {columns} columns with {torques} torques \
         and {weights} weights, where the fit has {expected} columns (torques and weights: one per row)"
    )]
    Shape {
        /// The regressor block's rows.
        rows: usize,
        /// The regressor block's columns.
        columns: usize,
        /// The torques given.
        torques: usize,
        /// The weights given (as many as rows when none are).
        weights: usize,
        /// The fit's columns.
        expected: usize,
    },
    /// A regressor entry, a torque or a weight is not finite, or a weight is not positive; `row`
    /// counts the rows added before, from 0 (so it is the row's index in the stacked system).
    #[error(
        "identification: row {row} has a value that is not finite, or a weight that is not positive and finite"
    )]
    NotFinite {
        /// The row's index in the stacked system.
        row: usize,
    },
    /// Fewer rows than parameters, or exactly as many (no degree of freedom is left to
    /// estimate the noise).
    #[error(
        "identification: {rows} rows for {columns} parameters; more rows than parameters are needed"
    )]
    TooFewRows {
        /// The rows added.
        rows: usize,
        /// The parameters.
        columns: usize,
    },
    /// The recording does not excite every parameter: the stacked regressor is singular to
    /// working precision (its condition number is at least `1/(m ε)`, `m` the rows). Excite the
    /// robot more (other trajectories, higher velocities and accelerations), or fit the base
    /// parameters rather than all of them.
    #[error(
        "identification: the recording does not excite every parameter (the stacked regressor's \
         condition number is {condition_number:.3e})"
    )]
    NotExcited {
        /// The condition number of the stacked (weighted) regressor.
        condition_number: f64,
    },
    /// A recording given to [`PeriodAverage`] is not a positive whole number of periods of at
    /// least one sample.
    #[error(
        "identification: {samples} samples are not a positive whole number of periods of \
         {samples_per_period} samples"
    )]
    NotWholePeriods {
        /// The samples given.
        samples: usize,
        /// The samples of one period.
        samples_per_period: usize,
    },
    /// A sample of a recording has no value, or another number of values than the first.
    #[error("identification: sample {sample} has {values} values where the first has {expected}")]
    RaggedSample {
        /// The sample's index, from 0.
        sample: usize,
        /// Its values.
        values: usize,
        /// The first sample's.
        expected: usize,
    },
    /// A value of a recording is NaN or infinite.
    #[error("identification: sample {sample}, channel {channel} is not finite")]
    NonFiniteSample {
        /// The sample's index, from 0.
        sample: usize,
        /// The value's index within the sample, from 0.
        channel: usize,
    },
    /// A channel beyond a recording's.
    #[error("identification: channel {channel} of a recording with {channels} channels")]
    NoChannel {
        /// The channel asked for.
        channel: usize,
        /// The recording's channels.
        channels: usize,
    },
    /// Too few samples per period for the harmonics asked for: `N` samples resolve harmonics
    /// below `N / 2` only.
    #[error(
        "identification: {harmonics} harmonics need more than {} samples per period; the \
         recording has {samples_per_period}",
        2 * harmonics
    )]
    TooFewSamples {
        /// The samples of one period.
        samples_per_period: usize,
        /// The harmonics asked for.
        harmonics: usize,
    },
    /// The period or start time of a Fourier series fitted to a recording is refused.
    #[error("identification: {0}")]
    Series(#[from] dhgen_trajectory::TrajectoryError),
}

/// Linear least squares `min ‖W (Y π − τ)‖`, rows added as they come (see the
/// [module](self)).
#[derive(Clone, Debug, PartialEq)]
pub struct LeastSquares {
    /// `[R z; 0 ρ]`: `R` upper triangular with `RᵀR = YᵀW²Y`, `z` the rotated torques, `|ρ|`
    /// the residual norm of the least-squares solution.
    factor: DMatrix<f64>,
    rows: usize,
}

/// What [`LeastSquares::estimate`] finds.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// The least-squares parameters `π̂`.
    pub parameters: DVector<f64>,
    /// Their covariance `σ̂² (YᵀW²Y)⁻¹`, with `σ̂²` the [residual variance](Self::residual_variance).
    /// For weights `1/σ_j` of known noise, divide by `σ̂²` for the covariance the noise
    /// predicts.
    pub covariance: DMatrix<f64>,
    /// The square roots of the covariance's diagonal: each parameter's standard deviation.
    pub standard_deviations: DVector<f64>,
    /// `σ̂² = ‖W (Y π̂ − τ)‖² / (rows − parameters)`: the (weighted) residual variance.
    pub residual_variance: f64,
    /// The condition number of the stacked (weighted) regressor, the ratio of its largest to
    /// its smallest singular value: how well the recording excites the parameters (the usual
    /// measure when choosing an exciting trajectory).
    pub condition_number: f64,
    /// The rows the estimate is from.
    pub rows: usize,
}

impl Estimate {
    /// The physically consistent estimate: the full parameters `π`, every link physical,
    /// whose base parameters are nearest these in the metric of their covariance (the
    /// least-squares fit of the same rows under the constraint that the robot be one, as
    /// Wensing, Kim and Slotine identify), the directions motion cannot tell settled nearest
    /// `model`'s own values: [`BaseParameters::nearest_physical`] with the inverse covariance.
    /// `regrouping` is the one the rows were stacked by (`base_parameters()` of the robot or
    /// the generated module) and `model` the description it is of. With a zero residual (no
    /// noise) the base parameters are kept exactly ([`BaseParameters::expand_physical`]).
    /// [`BaseParameters::reduce`] gives the base parameters of the result, and
    /// `dhgen::parameters::with_values` with `Links::Physical` its model.
    ///
    /// # Errors
    /// [`ParameterError::Infeasible`] when no physical robot is near enough to be found
    /// (see [`BaseParameters::expand_physical`]), and the other errors of
    /// [`BaseParameters::nearest_physical`].
    ///
    /// [`BaseParameters::nearest_physical`]: dhgen_description::parameters::BaseParameters::nearest_physical
    /// [`BaseParameters::expand_physical`]: dhgen_description::parameters::BaseParameters::expand_physical
    /// [`BaseParameters::reduce`]: dhgen_description::parameters::BaseParameters::reduce
    /// [`ParameterError::Infeasible`]: dhgen_description::parameters::ParameterError::Infeasible
    pub fn physical(
        &self,
        regrouping: &dhgen_description::parameters::BaseParameters,
        model: &dhgen_description::RobotModel,
    ) -> Result<DVector<f64>, dhgen_description::parameters::ParameterError> {
        match self.covariance.clone().cholesky() {
            Some(factor) => {
                regrouping.nearest_physical(self.parameters.as_slice(), &factor.inverse(), model)
            }
            None => regrouping.expand_physical(self.parameters.as_slice(), model),
        }
    }
}

impl LeastSquares {
    /// An empty fit for `parameters` unknowns (the base parameters' count, or any number of
    /// regressor columns).
    pub fn new(parameters: usize) -> Self {
        LeastSquares {
            factor: DMatrix::zeros(parameters + 1, parameters + 1),
            rows: 0,
        }
    }

    /// The number of unknowns.
    pub fn parameters(&self) -> usize {
        self.factor.ncols() - 1
    }

    /// The rows added so far.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Adds the rows of `y` (one per measured torque: for a sample, the `n × b` base regressor
    /// at its `(q, q̇, q̈)`) with the torques `tau`, unweighted.
    ///
    /// # Errors
    /// [`IdentificationError::Shape`] when `y` has another number of columns than the fit has
    /// parameters or `tau` another length than `y` has rows; [`IdentificationError::NotFinite`]
    /// when an entry is not finite. Nothing is added then.
    pub fn add<R, C, S, R2, S2>(
        &mut self,
        y: &Matrix<f64, R, C, S>,
        tau: &Matrix<f64, R2, U1, S2>,
    ) -> Result<(), IdentificationError>
    where
        R: Dim,
        C: Dim,
        S: RawStorage<f64, R, C>,
        R2: Dim,
        S2: RawStorage<f64, R2, U1>,
    {
        self.add_rows(y, tau, None)
    }

    /// [`add`](Self::add) with row `i` weighted by `weights[i]` (positive): for joint `j`'s
    /// rows, `1/σ_j` of its torque noise.
    ///
    /// # Errors
    /// As [`add`](Self::add), and [`IdentificationError::Shape`] when `weights` has another
    /// length than `y` has rows, [`IdentificationError::NotFinite`] when a weight is not
    /// positive and finite.
    pub fn add_weighted<R, C, S, R2, S2>(
        &mut self,
        y: &Matrix<f64, R, C, S>,
        tau: &Matrix<f64, R2, U1, S2>,
        weights: &[f64],
    ) -> Result<(), IdentificationError>
    where
        R: Dim,
        C: Dim,
        S: RawStorage<f64, R, C>,
        R2: Dim,
        S2: RawStorage<f64, R2, U1>,
    {
        self.add_rows(y, tau, Some(weights))
    }

    fn add_rows<R, C, S, R2, S2>(
        &mut self,
        y: &Matrix<f64, R, C, S>,
        tau: &Matrix<f64, R2, U1, S2>,
        weights: Option<&[f64]>,
    ) -> Result<(), IdentificationError>
    where
        R: Dim,
        C: Dim,
        S: RawStorage<f64, R, C>,
        R2: Dim,
        S2: RawStorage<f64, R2, U1>,
    {
        let p = self.parameters();
        let (rows, columns) = y.shape();
        let weight_count = weights.map_or(rows, <[f64]>::len);
        if columns != p || tau.nrows() != rows || weight_count != rows {
            return Err(IdentificationError::Shape {
                rows,
                columns,
                torques: tau.nrows(),
                weights: weight_count,
                expected: p,
            });
        }
        let weight = |i: usize| weights.map_or(1.0, |w| w[i]);
        // Checked whole before any row is folded in, so that an error leaves the fit as it was.
        if let Some(i) = (0..rows).find(|&i| {
            let w = weight(i);
            let valid = w.is_finite()
                && w > 0.0
                && tau[i].is_finite()
                && (0..p).all(|c| y[(i, c)].is_finite());
            !valid
        }) {
            return Err(IdentificationError::NotFinite { row: self.rows + i });
        }
        let mut row = DVector::zeros(p + 1);
        for i in 0..rows {
            let w = weight(i);
            for c in 0..p {
                row[c] = w * y[(i, c)];
            }
            row[p] = w * tau[i];
            self.fold(&mut row);
        }
        self.rows += rows;
        Ok(())
    }

    /// Rotates one augmented row `[y τ]` into the factor (Givens), leaving it zero.
    fn fold(&mut self, row: &mut DVector<f64>) {
        let n = self.factor.ncols();
        for k in 0..n {
            let b = row[k];
            if b == 0.0 {
                continue;
            }
            let a = self.factor[(k, k)];
            let rho = a.hypot(b);
            let (c, s) = (a / rho, b / rho);
            self.factor[(k, k)] = rho;
            row[k] = 0.0;
            for j in k + 1..n {
                let (f, r) = (self.factor[(k, j)], row[j]);
                self.factor[(k, j)] = c * f + s * r;
                row[j] = c * r - s * f;
            }
        }
    }

    /// `R`, upper triangular with `RᵀR = YᵀW²Y`: its singular values are the stacked
    /// (weighted) regressor's (`R = Qᵀ W Y`).
    fn triangle(&self) -> DMatrix<f64> {
        let p = self.parameters();
        self.factor.view((0, 0), (p, p)).upper_triangle()
    }

    /// The condition number of the rows added so far (weighted), the ratio of the largest to
    /// the smallest singular value of the stacked regressor (∞ while it is singular): what
    /// [`Estimate::condition_number`] reports, available before an estimate, and independent of
    /// the torques. To choose an exciting trajectory, add its regressor rows with any torques
    /// (zeros) and compare.
    pub fn condition_number(&self) -> f64 {
        let singular = self.triangle().singular_values();
        let (largest, smallest) = (singular.max(), singular.min());
        if smallest > 0.0 {
            largest / smallest
        } else {
            f64::INFINITY
        }
    }

    /// The least-squares estimate from the rows added so far.
    ///
    /// # Errors
    /// [`IdentificationError::TooFewRows`] with no more rows than parameters;
    /// [`IdentificationError::NotExcited`] when the stacked regressor is singular to working
    /// precision.
    pub fn estimate(&self) -> Result<Estimate, IdentificationError> {
        let p = self.parameters();
        if self.rows <= p {
            return Err(IdentificationError::TooFewRows {
                rows: self.rows,
                columns: p,
            });
        }
        let r = self.triangle();
        let z = self.factor.view((0, p), (p, 1)).into_owned();
        let condition_number = self.condition_number();
        // Rank deficient to working precision by the usual rule (σ_min ≤ max(m, n) ε σ_max).
        if condition_number * self.rows.max(p) as f64 * f64::EPSILON >= 1.0 {
            return Err(IdentificationError::NotExcited { condition_number });
        }
        let not_excited = IdentificationError::NotExcited { condition_number };
        let parameters = r.solve_upper_triangular(&z).ok_or(not_excited)?;
        let inverse = r
            .solve_upper_triangular(&DMatrix::identity(p, p))
            .ok_or(not_excited)?;
        let residual = self.factor[(p, p)];
        let residual_variance = residual * residual / (self.rows - p) as f64;
        // (RᵀR)⁻¹ = R⁻¹ R⁻ᵀ.
        let covariance = (&inverse * inverse.transpose()) * residual_variance;
        let standard_deviations = covariance.diagonal().map(f64::sqrt);
        Ok(Estimate {
            parameters: DVector::from_iterator(p, parameters.iter().copied()),
            covariance,
            standard_deviations,
            residual_variance,
            condition_number,
            rows: self.rows,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A seeded stream in [−1, 1).
    fn stream(seed: u64) -> impl FnMut() -> f64 {
        let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        move || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        }
    }

    fn system(rows: usize, columns: usize, seed: u64) -> (DMatrix<f64>, DVector<f64>) {
        let mut r = stream(seed);
        let y = DMatrix::from_fn(rows, columns, |_, _| r());
        let t = DVector::from_fn(rows, |_, _| r());
        (y, t)
    }

    #[test]
    fn rows_added_one_by_one_give_the_stacked_systems_least_squares_solution() {
        let (y, t) = system(40, 7, 1);
        let mut fit = LeastSquares::new(7);
        for i in 0..40 {
            fit.add(&y.rows(i, 1), &t.rows(i, 1)).unwrap();
        }
        let e = fit.estimate().unwrap();
        // The stacked system solved independently, by SVD.
        let direct = y.clone().svd(true, true).solve(&t, 1e-14).unwrap();
        assert!(
            (&e.parameters - &direct).amax() < 1e-12,
            "{}",
            &e.parameters - &direct
        );
        // The covariance and residual from their definitions.
        let residual = (&y * &direct - &t).norm_squared() / (40 - 7) as f64;
        assert!((e.residual_variance - residual).abs() < 1e-12 * residual);
        let cov = (y.transpose() * &y).try_inverse().unwrap() * residual;
        assert!((&e.covariance - &cov).amax() < 1e-10 * cov.amax());
        let s = y.singular_values();
        assert!((e.condition_number / (s.max() / s.min()) - 1.0).abs() < 1e-10);
        assert_eq!(fit.condition_number(), e.condition_number);
        assert_eq!(e.rows, 40);
    }

    #[test]
    fn weights_scale_their_rows() {
        let (y, t) = system(30, 5, 2);
        let w: Vec<f64> = (0..30).map(|i| 0.5 + (i % 3) as f64).collect();
        let mut weighted = LeastSquares::new(5);
        weighted.add_weighted(&y, &t, &w).unwrap();
        let mut scaled = LeastSquares::new(5);
        let ys = DMatrix::from_fn(30, 5, |i, c| w[i] * y[(i, c)]);
        let ts = DVector::from_fn(30, |i, _| w[i] * t[i]);
        scaled.add(&ys, &ts).unwrap();
        let (a, b) = (weighted.estimate().unwrap(), scaled.estimate().unwrap());
        assert!((&a.parameters - &b.parameters).amax() < 1e-12);
        assert!((a.residual_variance - b.residual_variance).abs() < 1e-12);
        assert!((weighted.condition_number() / scaled.condition_number() - 1.0).abs() < 1e-12);
        // The torques do not enter it; an empty fit is singular.
        let mut zeros = LeastSquares::new(5);
        zeros.add(&ys, &DVector::zeros(30)).unwrap();
        assert_eq!(zeros.condition_number(), scaled.condition_number());
        assert_eq!(LeastSquares::new(5).condition_number(), f64::INFINITY);
    }

    #[test]
    fn an_exact_system_is_solved_exactly() {
        let (y, _) = system(25, 6, 3);
        let truth = DVector::from_fn(6, |i, _| (i as f64 - 2.5) * 10f64.powi(i as i32 - 3));
        let tau = &y * &truth;
        let mut fit = LeastSquares::new(6);
        fit.add(&y, &tau).unwrap();
        let e = fit.estimate().unwrap();
        assert!((&e.parameters - &truth).amax() < 1e-12 * truth.amax());
        // What is left is the rounding of τ.
        assert!(e.residual_variance.sqrt() < 1e-15 * tau.norm());
    }

    #[test]
    fn bad_rows_are_refused_and_leave_the_fit_as_it_was() {
        let (y, t) = system(10, 3, 4);
        let mut fit = LeastSquares::new(3);
        fit.add(&y.rows(0, 5), &t.rows(0, 5)).unwrap();
        let before = fit.clone();
        let mut bad = y.rows(5, 5).into_owned();
        bad[(2, 1)] = f64::NAN;
        assert_eq!(
            fit.add(&bad, &t.rows(5, 5)),
            Err(IdentificationError::NotFinite { row: 7 })
        );
        assert_eq!(
            fit.add_weighted(&y.rows(5, 5), &t.rows(5, 5), &[1.0, 1.0, 0.0, 1.0, 1.0]),
            Err(IdentificationError::NotFinite { row: 7 })
        );
        assert!(matches!(
            fit.add(&y.columns(0, 2), &t),
            Err(IdentificationError::Shape {
                columns: 2,
                expected: 3,
                ..
            })
        ));
        assert!(matches!(
            fit.add(&y, &t.rows(0, 9)),
            Err(IdentificationError::Shape { torques: 9, .. })
        ));
        assert_eq!(fit, before);
    }

    #[test]
    fn too_few_rows_and_unexcited_parameters_are_refused() {
        let (y, t) = system(12, 4, 5);
        let mut fit = LeastSquares::new(4);
        fit.add(&y.rows(0, 4), &t.rows(0, 4)).unwrap();
        assert_eq!(
            fit.estimate(),
            Err(IdentificationError::TooFewRows {
                rows: 4,
                columns: 4
            })
        );
        // A column that is never excited (the parameter of a joint that never moved) ...
        let mut idle = y.clone();
        idle.column_mut(2).fill(0.0);
        let mut fit = LeastSquares::new(4);
        fit.add(&idle, &t).unwrap();
        assert!(matches!(
            fit.estimate(),
            Err(IdentificationError::NotExcited { condition_number }) if condition_number > 1e15
        ));
        // ... and two that always move together (only their sum is determined).
        let mut tied = y.clone();
        let c0 = tied.column(0).into_owned();
        tied.column_mut(3).copy_from(&(c0 * 2.0));
        let mut fit = LeastSquares::new(4);
        fit.add(&tied, &t).unwrap();
        let e = fit.estimate();
        assert!(
            matches!(e, Err(IdentificationError::NotExcited { .. })),
            "{e:?}"
        );
    }
}
