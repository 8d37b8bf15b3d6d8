//! Base parameters expanded to physical links: [`PhysicalConsistency`], for
//! [`BaseParameters`].
//!
//! Motion fixes only the base parameters; the other directions of `π` are free. Over them this
//! finds the vector nearest the description's own values whose every link is a body: its
//! pseudo-inertia `J = [[Σ, h], [hᵀ, m]]` (`Σ = ½ tr(I) 1 − I` the second moment of its mass
//! about the frame's origin, `h = m c`) positive definite, which holds exactly when some
//! density has the link's mass, centre and inertia (Wensing, Kim and Slotine, "Linear matrix
//! inequalities for physically consistent inertial parameter identification", 2017) and
//! implies the triangle inequality. For a link whose description already broke that
//! inequality (`allow_nonphysical_inertia`) the weaker `[[I, S(h)], [S(h)ᵀ, m 1]] ≻ 0` is
//! asked (`S(h)` the cross-product matrix): a positive mass and, by the Schur complement,
//! `I − S(h) S(h)ᵀ / m` (the inertia about the centre of mass) positive definite. Rotor
//! inertias and friction coefficients must stay positive.
//!
//! Each constraint is a symmetric matrix affine in the free values. The search is a barrier
//! method (Boyd and Vandenberghe, chapter 11): Newton's method on the distance to the
//! reference plus `−log det` of every constraint divided by a growing weight, after a first
//! phase that finds a strictly physical start (or shows there is none) by minimizing how
//! far the constraints are from holding.

use dhgen_description::RobotModel;
use dhgen_description::parameters::{
    self as parameters, BODY_PARAMETERS, BaseParameters, Column, ParameterError, columns,
    inertia_of, names,
};
use nalgebra::{Cholesky, DMatrix, DVector};

/// The barrier's last weight leaves the distance within this of its least value (the
/// distance is in units of each parameter's scale, see [`scales`]).
const GAP: f64 = 1e-10;
/// Newton steps per weight, at the most.
const NEWTON_STEPS: usize = 100;
/// How fast the barrier's weight grows.
const GROWTH: f64 = 10.0;
/// The first phase's pull toward its start, in each variable's scale: small, so that it
/// cannot hide a margin.
const PHASE_ONE_PULL: f64 = 1e-8;
/// The weight of the distance from the description in [`BaseParameters::nearest_physical`],
/// against the fit's `(π_b − π̂)ᵀ Λ (π_b − π̂)` (of order the number of base parameters).
const PULL: f64 = 1e-6;
/// How far below zero a constraint's least eigenvalue may be, in its own units (a link's
/// mass and the robot's length, a joint-side term's scale): positive semi-definite to
/// rounding, as a description's links are, so that a link may be a point mass, a rod or a
/// plane (its pseudo-inertia singular), which no strictly positive definite search reaches.
const MARGIN: f64 = 1e-13;

/// One constraint: `F(y) = f0 + Σ_a y_a f_a`, to be kept positive definite.
struct Constraint {
    /// What it keeps physical, for errors: `link 3`, `Ia2`.
    name: String,
    /// How far below zero its least eigenvalue may go, included in `f0`.
    margin: f64,
    f0: DMatrix<f64>,
    /// The non-zero `f_a`, with the index `a` of their variable.
    terms: Vec<(usize, DMatrix<f64>)>,
}

impl Constraint {
    fn at(&self, y: &DVector<f64>) -> DMatrix<f64> {
        let mut f = self.f0.clone();
        for (a, fa) in &self.terms {
            let ya = y[*a];
            f.zip_apply(fa, |x, b| *x += b * ya);
        }
        f
    }

    /// The least eigenvalue of `F(y)`.
    fn least(&self, y: &DVector<f64>) -> f64 {
        self.at(y).symmetric_eigenvalues().min()
    }
}

/// `½ yᵀ Q y + cᵀ y` plus `−log det F(y)` of every constraint over `1/t`.
struct Barrier<'a> {
    constraints: &'a [Constraint],
    q: DMatrix<f64>,
    c: DVector<f64>,
}

impl Barrier<'_> {
    /// `t` times the objective plus the barrier, or `None` outside the constraints.
    fn value(&self, t: f64, y: &DVector<f64>) -> Option<f64> {
        let mut v = t * (0.5 * y.dot(&(&self.q * y)) + self.c.dot(y));
        for k in self.constraints {
            let l = Cholesky::new(k.at(y))?;
            v -= 2.0 * l.l_dirty().diagonal().map(f64::ln).sum();
        }
        Some(v)
    }

    /// Newton's method on [`value`](Self::value) from the strictly feasible `y`, until the
    /// Newton decrement is rounding or `stop(y)`; `false` if a step could not be made.
    fn centre(&self, t: f64, y: &mut DVector<f64>, stop: &dyn Fn(&DVector<f64>) -> bool) -> bool {
        let n = y.len();
        for _ in 0..NEWTON_STEPS {
            if stop(y) {
                return true;
            }
            let mut g = (&self.q * &*y + &self.c) * t;
            let mut h = &self.q * t;
            for k in self.constraints {
                let Some(inverse) = Cholesky::new(k.at(y)).map(|l| l.inverse()) else {
                    return false;
                };
                // ∂(−log det F)/∂y_a = −tr(F⁻¹ f_a); ∂² = tr(F⁻¹ f_a F⁻¹ f_b).
                let p: Vec<DMatrix<f64>> = k.terms.iter().map(|(_, fa)| &inverse * fa).collect();
                for (i, (a, _)) in k.terms.iter().enumerate() {
                    g[*a] -= p[i].trace();
                    for (j, (b, _)) in k.terms.iter().enumerate().skip(i) {
                        // tr(A B) without forming the product: nalgebra's `tr_dot`.
                        let hab = p[i].tr_dot(&p[j]);
                        h[(*a, *b)] += hab;
                        if i != j {
                            h[(*b, *a)] += hab;
                        }
                    }
                }
            }
            let Some(step) = Cholesky::new(h).map(|l| l.solve(&-&g)) else {
                return false;
            };
            let decrement = -g.dot(&step);
            if decrement.is_nan() || decrement <= 1e-14 * n as f64 {
                return true;
            }
            let Some(before) = self.value(t, y) else {
                return false;
            };
            let mut alpha = 1.0;
            loop {
                let trial = &*y + &step * alpha;
                if self
                    .value(t, &trial)
                    .is_some_and(|v| v <= before - 0.25 * alpha * decrement)
                {
                    *y = trial;
                    break;
                }
                alpha *= 0.5;
                if alpha < 1e-14 {
                    // No descent left within rounding: as centred as this weight allows.
                    return true;
                }
            }
        }
        true
    }

    /// Centres for growing weights from `t = 1` until `size / t` (the gap to the least
    /// objective) is below [`GAP`], or `stop(y)`, or `settled(y, gap)` at a centre (where the
    /// objective is within `gap = size / t` of its least).
    fn minimize(
        &self,
        y: &mut DVector<f64>,
        size: usize,
        stop: &dyn Fn(&DVector<f64>) -> bool,
        settled: &dyn Fn(&DVector<f64>, f64) -> bool,
    ) {
        let mut t = 1.0;
        loop {
            let gap = size as f64 / t;
            if !self.centre(t, y, stop) || stop(y) || settled(y, gap) || gap < GAP {
                return;
            }
            t *= GROWTH;
        }
    }
}

/// The scale of each parameter, in which the distance to the reference is measured: the
/// robot's mean link mass `M` for a mass, `M L` for a first moment, `M L²` for an inertia,
/// with `L` the root mean square distance of the mass from its frame's origin
/// (`L² = Σ ∫|r|² dm / Σ m`); a joint-side term's own value (1 where it is zero).
fn scales(model: &RobotModel, reference: &[f64]) -> (Vec<f64>, f64, f64) {
    let n = model.dof();
    let mass: f64 = (0..n).map(|i| reference[BODY_PARAMETERS * i]).sum();
    let second: f64 = (0..n)
        .map(|i| {
            let p = &reference[BODY_PARAMETERS * i..BODY_PARAMETERS * (i + 1)];
            0.5 * (p[4] + p[6] + p[9])
        })
        .sum();
    let big_m = (mass / n as f64).max(f64::MIN_POSITIVE);
    let big_l = if mass > 0.0 && second > 0.0 {
        (second / mass).sqrt()
    } else {
        1.0
    };
    let s = columns(model)
        .iter()
        .zip(reference)
        .map(|(column, r)| match *column {
            Column::Body { k: 0, .. } => big_m,
            Column::Body { k: 1..=3, .. } => big_m * big_l,
            Column::Body { .. } => big_m * big_l * big_l,
            _ if *r != 0.0 => r.abs(),
            _ => 1.0,
        })
        .collect();
    (s, big_m, big_l)
}

/// The constraint matrix of a link's parameters `p` (or of a direction in them: the map is
/// linear), scaled by a mass `big_m` (the link's own) and the robot's length `L` to be of
/// order one: the pseudo-inertia, or with
/// `triangle = false` the inertia-and-mass matrix; for a link whose mass is fixed at zero,
/// only the second moment (or the inertia).
fn link_matrix(p: &[f64], triangle: bool, massless: bool, big_m: f64, big_l: f64) -> DMatrix<f64> {
    let p: [f64; BODY_PARAMETERS] = core::array::from_fn(|k| p[k]);
    let i = inertia_of(&p);
    let (m, h) = (
        p[0] / big_m,
        [p[1], p[2], p[3]].map(|x| x / (big_m * big_l)),
    );
    let inertia = |a: usize, b: usize| i[a][b] / (big_m * big_l * big_l);
    if triangle {
        let half_trace = 0.5 * (inertia(0, 0) + inertia(1, 1) + inertia(2, 2));
        let sigma = |a: usize, b: usize| {
            if a == b {
                half_trace - inertia(a, a)
            } else {
                -inertia(a, b)
            }
        };
        if massless {
            return DMatrix::from_fn(3, 3, sigma);
        }
        DMatrix::from_fn(4, 4, |a, b| match (a, b) {
            (3, 3) => m,
            (3, b) => h[b],
            (a, 3) => h[a],
            (a, b) => sigma(a, b),
        })
    } else {
        if massless {
            return DMatrix::from_fn(3, 3, inertia);
        }
        // S(h), the cross-product matrix: S(h) v = h × v.
        let s = [[0.0, -h[2], h[1]], [h[2], 0.0, -h[0]], [-h[1], h[0], 0.0]];
        DMatrix::from_fn(6, 6, |a, b| match (a < 3, b < 3) {
            (true, true) => inertia(a, b),
            (true, false) => s[a][b - 3],
            (false, true) => s[b][a - 3],
            (false, false) => {
                if a == b {
                    m
                } else {
                    0.0
                }
            }
        })
    }
}

/// The physical consistency of base parameters: the full parameter vectors whose every link is
/// a body (its pseudo-inertia positive semi-definite), nearest a description's own values or
/// a least-squares estimate. Implemented for [`BaseParameters`].
pub trait PhysicalConsistency {
    /// A full parameter vector with base parameters `base` whose every link is physical: of
    /// all such vectors (each gives the same torques for every motion, as
    /// [`expand`](BaseParameters::expand)'s does), the one nearest `model`'s own values
    /// ([`parameters::values`]). It is [`with_values`](parameters::with_values)'s with
    /// [`Links::Physical`](parameters::Links::Physical).
    ///
    /// Physical is the rule of a description, to rounding: a link's pseudo-inertia positive
    /// semi-definite (a mass not negative, an inertia about the centre of mass positive
    /// semi-definite and obeying the triangle inequality, or, where `model`'s link broke that
    /// inequality, positive semi-definite only); rotor inertias and friction coefficients not
    /// negative. The distance is measured in each parameter's scale: the robot's mean link
    /// mass `M` for masses, `M L` for first moments, `M L²` for inertias (`L` the root mean
    /// square distance of the robot's mass from its links' frames), a joint-side term's own
    /// value; its square is found to about `1e-10` of the least. Where [`expand`](BaseParameters::expand)'s
    /// vector is physical it is the one returned. Where the links can be physical only as
    /// limits of bodies (a point mass, a rod, a plane or a massless link, as descriptions
    /// often have them), the search keeps a margin of `1e-13` of each link's mass and may end
    /// short of the nearest; the vector is still physical. A link whose mass `base` fixes at
    /// zero must have its first moment fixed at zero too.
    ///
    /// Base parameters identified from noisy measurements may have no physical expansion (a
    /// lumped inertia estimated below what the masses beyond it already carry); the error
    /// names the link furthest from physical at the best point found.
    ///
    /// # Errors
    /// [`ParameterError::Count`] as for [`expand`](BaseParameters::expand);
    /// [`ParameterError::NoMassProperties`] for a link of `model` without mass properties;
    /// [`ParameterError::Infeasible`] naming the link or term that cannot be made physical.
    fn expand_physical(
        &self,
        base: &[f64],
        model: &RobotModel,
    ) -> Result<DVector<f64>, ParameterError>;

    /// Identified base parameters made physical: the base parameters `π_b` and their
    /// expansion `π` with every link physical (as [`expand_physical`](PhysicalConsistency::expand_physical)
    /// asks) that minimize `(π_b − π̂)ᵀ Λ (π_b − π̂)`, with `π̂` the least-squares `estimate`
    /// and `Λ` its `information` (the inverse of its covariance: the minimum is then the
    /// constrained least-squares fit of the same rows, Wensing, Kim and Slotine's
    /// physically consistent identification), plus `1e-6` times
    /// [`expand_physical`](PhysicalConsistency::expand_physical)'s distance of `π` from `model`'s values,
    /// which settles the directions motion cannot tell. Returns `π` ([`reduce`](parameters::reduce)
    /// gives its base parameters). Where the estimate's own expansion over `model`'s values
    /// is physical, that is returned.
    ///
    /// # Errors
    /// As [`expand_physical`](PhysicalConsistency::expand_physical); [`ParameterError::Count`] also when
    /// `information` is not square of the base parameters' count.
    fn nearest_physical(
        &self,
        estimate: &[f64],
        information: &DMatrix<f64>,
        model: &RobotModel,
    ) -> Result<DVector<f64>, ParameterError>;
}

impl PhysicalConsistency for BaseParameters {
    fn expand_physical(
        &self,
        base: &[f64],
        model: &RobotModel,
    ) -> Result<DVector<f64>, ParameterError> {
        let reference = reference_values(model)?;
        finite_base(base)?;
        // The reference's own values, where they leave every link physical: the nearest
        // (expand checks the counts).
        let plain = self.expand(base, &reference)?;
        if parameters::with_values(model, plain.as_slice(), parameters::Links::Physical).is_ok() {
            return Ok(plain);
        }
        let scales = scales(model, &reference);
        // π(x) = π0 + A x over the dependent parameters x, through π(r) = plain.
        let a = self.dependent_directions(reference.len());
        // The distance Σ ((x − r)/s)², as ½ xᵀ Q x + cᵀ x.
        let (q, c, r) = self.distance(&scales.0, &reference);
        let pi0 = plain - &a * &r;
        let units = self.dependent.iter().map(|&dep| scales.0[dep]).collect();
        search(model, &scales, pi0, a, (q, c), r, units)
    }

    fn nearest_physical(
        &self,
        estimate: &[f64],
        information: &DMatrix<f64>,
        model: &RobotModel,
    ) -> Result<DVector<f64>, ParameterError> {
        let reference = reference_values(model)?;
        finite_base(estimate)?;
        if let Some(index) = information.iter().position(|x| !x.is_finite()) {
            return Err(ParameterError::Value {
                name: "information".into(),
                index,
                message: format!("entry {} is not a finite number", information[index]),
            });
        }
        let plain = self.expand(estimate, &reference)?;
        let b = self.count();
        if information.shape() != (b, b) {
            return Err(ParameterError::Count {
                what: "rows and columns of the information matrix",
                given: information.nrows().max(information.ncols()),
                expected: b,
            });
        }
        if parameters::with_values(model, plain.as_slice(), parameters::Links::Physical).is_ok() {
            return Ok(plain);
        }
        // Variables v = (π_b, x), π = E π_b + A x with E placing π_b at the independent
        // parameters.
        let p = reference.len();
        let d = self.dependent.len();
        let mut g = DMatrix::zeros(p, b + d);
        for (k, &i) in self.independent.iter().enumerate() {
            g[(i, k)] = 1.0;
        }
        g.columns_mut(b, d).copy_from(&self.dependent_directions(p));
        let scales = scales(model, &reference);
        let (qx, cx, r) = self.distance(&scales.0, &reference);
        let symmetric = (information + information.transpose()) * 0.5;
        let pi_hat = DVector::from_column_slice(estimate);
        let mut q = DMatrix::zeros(b + d, b + d);
        q.view_mut((0, 0), (b, b)).copy_from(&(&symmetric * 2.0));
        q.view_mut((b, b), (d, d)).copy_from(&(qx * PULL));
        let mut c = DVector::zeros(b + d);
        c.rows_mut(0, b).copy_from(&(&symmetric * &pi_hat * -2.0));
        c.rows_mut(b, d).copy_from(&(cx * PULL));
        let mut start = DVector::zeros(b + d);
        start.rows_mut(0, b).copy_from(&pi_hat);
        start.rows_mut(b, d).copy_from(&r);
        let units = self
            .independent
            .iter()
            .chain(&self.dependent)
            .map(|&i| scales.0[i])
            .collect();
        search(model, &scales, DVector::zeros(p), g, (q, c), start, units)
    }
}

/// A quadratic `½ xᵀ Q x + cᵀ x` and the point `r` it is centred on: `(Q, c, r)`.
type Quadratic = (DMatrix<f64>, DVector<f64>, DVector<f64>);

/// The pieces of the search made from the regrouping.
trait Directions {
    fn dependent_directions(&self, p: usize) -> DMatrix<f64>;
    fn distance(&self, scale: &[f64], reference: &[f64]) -> Quadratic;
}

impl Directions for BaseParameters {
    /// `A`, `p × d`: how `π` moves with the dependent parameters `x` at fixed base
    /// parameters (`π_d = x`, `π_i = π_b − β x`).
    fn dependent_directions(&self, p: usize) -> DMatrix<f64> {
        let d = self.dependent.len();
        let mut a = DMatrix::zeros(p, d);
        for (m, &dep) in self.dependent.iter().enumerate() {
            a[(dep, m)] = 1.0;
            for (k, &i) in self.independent.iter().enumerate() {
                a[(i, m)] = -self.beta[(k, m)];
            }
        }
        a
    }

    /// The distance of the dependent parameters `x` from the reference's `r`,
    /// `Σ ((x − r)/s)²` in the parameters' scales `scale` ([`scales`]), as `½ xᵀ Q x + cᵀ x`
    /// (plus a constant): `(Q, c, r)`.
    fn distance(&self, scale: &[f64], reference: &[f64]) -> Quadratic {
        let d = self.dependent.len();
        let weights = DVector::from_iterator(
            d,
            self.dependent
                .iter()
                .map(|&dep| 2.0 / (scale[dep] * scale[dep])),
        );
        let r = DVector::from_iterator(d, self.dependent.iter().map(|&dep| reference[dep]));
        let c = -weights.component_mul(&r);
        (DMatrix::from_diagonal(&weights), c, r)
    }
}

/// `model`'s own parameter values, or the error naming its first link without mass
/// properties.
fn reference_values(model: &RobotModel) -> Result<Vec<f64>, ParameterError> {
    parameters::values(model).ok_or_else(|| ParameterError::NoMassProperties {
        link: model
            .links
            .iter()
            .position(|l| l.inertial.is_none())
            .map_or(0, |i| i + 1),
    })
}

/// `Ok` if every base parameter value is finite, else the error naming the first that is not.
fn finite_base(base: &[f64]) -> Result<(), ParameterError> {
    match base.iter().position(|x| !x.is_finite()) {
        Some(index) => Err(ParameterError::Value {
            name: format!("base parameter {}", index + 1),
            index,
            message: format!("{} is not a finite number", base[index]),
        }),
        None => Ok(()),
    }
}

/// The search: over variables `v` with `π = π0 + G v`, the least `½ vᵀ Q v + cᵀ v` whose `π`
/// has physical links, from `start`; `π` of the best. `units` holds each variable's scale,
/// in which the first phase keeps near the start.
fn search(
    model: &RobotModel,
    (scale, big_m, big_l): &(Vec<f64>, f64, f64),
    pi0: DVector<f64>,
    a: DMatrix<f64>,
    (q, c): (DMatrix<f64>, DVector<f64>),
    start: DVector<f64>,
    units: Vec<f64>,
) -> Result<DVector<f64>, ParameterError> {
    let d = a.ncols();
    let (big_m, big_l) = (*big_m, *big_l);
    let names = names(model);
    let infeasible = |name: String, message: String| ParameterError::Infeasible { name, message };
    let mut constraints = Vec::new();
    for (link, l) in model.links.iter().enumerate() {
        let rows = BODY_PARAMETERS * link..BODY_PARAMETERS * (link + 1);
        let varies = |row: usize| a.row(row).iter().any(|x| *x != 0.0);
        let triangle = l.inertial.is_some_and(|i| {
            dhgen_description::validate::obeys_triangle_inequality(&i.inertia, i.mass)
        });
        let first = rows.start;
        let massless = !varies(first) && pi0[first] == 0.0;
        if massless && (first + 1..first + 4).any(|r| varies(r) || pi0[r] != 0.0) {
            return Err(infeasible(
                format!("link {}", link + 1),
                "its mass is fixed at zero but not its first moment".into(),
            ));
        }
        let own = l.inertial.map_or(0.0, |i| i.mass);
        let mass = if own > 0.0 { own } else { big_m };
        let matrix = |v: &[f64]| link_matrix(v, triangle, massless, mass, big_l);
        let f0 = matrix(&pi0.as_slice()[rows.clone()]);
        let size = f0.nrows();
        let terms: Vec<(usize, DMatrix<f64>)> = (0..d)
            .filter(|&m| rows.clone().any(|r| a[(r, m)] != 0.0))
            .map(|m| {
                let column: Vec<f64> = rows.clone().map(|r| a[(r, m)]).collect();
                (m, matrix(&column))
            })
            .collect();
        constraints.push(Constraint {
            name: format!("link {}", link + 1),
            margin: MARGIN,
            f0: f0 + DMatrix::identity(size, size) * MARGIN,
            terms,
        });
    }
    for (index, column) in columns(model).iter().enumerate() {
        if matches!(column, Column::Body { .. }) {
            continue;
        }
        let unit = DMatrix::from_element(1, 1, 1.0 / scale[index]);
        constraints.push(Constraint {
            name: names[index].clone(),
            margin: 0.0,
            f0: &unit * pi0[index],
            terms: (0..d)
                .filter(|&m| a[(index, m)] != 0.0)
                .map(|m| (m, &unit * a[(index, m)]))
                .collect(),
        });
    }
    // Constraints the free values cannot move are checked as they stand; the others go
    // to the barrier.
    let (fixed, free): (Vec<Constraint>, Vec<Constraint>) =
        constraints.into_iter().partition(|k| k.terms.is_empty());
    let none = DVector::zeros(d);
    for k in &fixed {
        let least = k.least(&none);
        if least < 0.0 {
            return Err(infeasible(
                k.name.clone(),
                format!(
                    "base parameters alone fix it, {:.3e} below physical",
                    least - k.margin
                ),
            ));
        }
    }
    let size: usize = free.iter().map(|k| k.f0.nrows()).sum();
    let mut x = start.clone();
    let worst = |x: &DVector<f64>| {
        free.iter()
            .map(|k| (k.least(x), k))
            .min_by(|a, b| a.0.total_cmp(&b.0))
    };
    if let Some((least, _)) = worst(&x).filter(|(least, _)| *least <= 0.0) {
        // Phase one: the least s with every F(x) + s 1 positive definite, from the start; a
        // negative s is a strictly physical start.
        let shifted: Vec<Constraint> = free
            .iter()
            .map(|k| Constraint {
                name: k.name.clone(),
                margin: k.margin,
                f0: k.f0.clone(),
                terms: k
                    .terms
                    .iter()
                    .cloned()
                    .chain(core::iter::once((
                        d,
                        DMatrix::identity(k.f0.nrows(), k.f0.nrows()),
                    )))
                    .collect(),
            })
            .collect();
        // s plus PHASE_ONE_PULL Σ ((v − start)/unit)², which keeps the Hessian positive
        // definite along directions no constraint sees, whatever the objective's units.
        let mut qs = DMatrix::zeros(d + 1, d + 1);
        let mut cs = DVector::zeros(d + 1);
        for (k, unit) in units.iter().enumerate() {
            let w = 2.0 * PHASE_ONE_PULL / (unit * unit);
            qs[(k, k)] = w;
            cs[k] = -w * start[k];
        }
        cs[d] = 1.0;
        let phase_one = Barrier {
            constraints: &shifted,
            q: qs,
            c: cs,
        };
        let mut y = DVector::zeros(d + 1);
        y.rows_mut(0, d).copy_from(&start);
        y[d] = 1.0 - least;
        let found = |y: &DVector<f64>| y[d] < 0.0;
        // At a centre the least s is within the gap of s itself (to the pull's share, at most
        // PHASE_ONE_PULL times the distance moved): when s less the gap stays well above zero
        // no physical start exists, and the rest of the first phase is spared.
        let hopeless = |y: &DVector<f64>, gap: f64| y[d] - gap > 1e-6;
        phase_one.minimize(&mut y, size, &found, &hopeless);
        x = y.rows(0, d).into_owned();
    }
    let physical = |x: &DVector<f64>| {
        let pi = &pi0 + &a * x;
        parameters::with_values(model, pi.as_slice(), parameters::Links::Physical)
            .is_ok()
            .then_some(pi)
    };
    // Phase two from a start inside every constraint. Where the links can be physical
    // only as limits of bodies (a point mass, a rod, a plane, a massless link: a singular
    // pseudo-inertia), that inside is as thin as the margin and the first phase may not
    // reach it; its best point is then returned if the description's rules (semi-definite
    // to rounding) accept it.
    if worst(&x).is_none_or(|(least, _)| least > 0.0) {
        let mut nearest = x.clone();
        Barrier {
            constraints: &free,
            q,
            c,
        }
        .minimize(&mut nearest, size, &|_| false, &|_, _| false);
        if let Some(pi) = physical(&nearest) {
            return Ok(pi);
        }
        // Within the margin but not by the description's rules (a friction coefficient or
        // a massless link's mass a rounding below zero): the nearest point toward the start
        // that is, by bisection on the segment (the rules are convex).
        if physical(&x).is_some() {
            let (mut outside, mut inside) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (outside + inside);
                if physical(&(&nearest + (&x - &nearest) * mid)).is_some() {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            if let Some(pi) = physical(&(&nearest + (&x - &nearest) * inside)) {
                return Ok(pi);
            }
        }
    }
    physical(&x).ok_or_else(|| match worst(&x) {
        Some((least, k)) => infeasible(
            k.name.clone(),
            format!(
                "at best {:.3e} below physical, in units of its mass and the robot's \
                     length {big_l:.4} m",
                least - k.margin
            ),
        ),
        None => infeasible(
            "a link".into(),
            "the base parameters fix every link, and one breaks a rule of the description".into(),
        ),
    })
}
