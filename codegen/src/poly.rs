//! The normal form: sparse polynomials in `cos θ_j`, `sin θ_j` (revolute joints) and the
//! displacement `d_j` (prismatic joints), reduced by `sin² = 1 − cos²` while multiplying.
//!
//! Every kinematic and dynamic quantity of a serial chain is such a polynomial, and with
//! every `sin` of degree at most one the representation is unique: two derivations of the
//! same quantity give the same terms, cancellations (`cos² + sin² = 1`) happen on their own,
//! and differentiation is exact. This is what egg-style rewriting cannot do at the size of
//! an inertia matrix.
//!
//! Floating-point coefficients cancel only up to rounding, so a term is dropped when its
//! coefficient is below `CANCEL` times the sum of the magnitudes that produced it: a
//! relative test that never drops a physically meaningful term.

use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::Ring;
use std::cell::Cell;
use std::rc::Rc;

/// Variables per polynomial: two per joint.
pub const MAX_VARS: usize = 32;

/// Relative size below which a cancelled coefficient is rounding noise.
const CANCEL: f64 = 64.0 * f64::EPSILON;

/// Sums of coefficients (and of their magnitudes, for the cancellation test) per monomial.
type Accumulator = crate::graph::FastMap<Mono, (f64, f64)>;

/// Exponents, indexed by variable: `2j` is `cos θ_j` (or `d_j`), `2j + 1` is `sin θ_j`.
pub type Mono = [u8; MAX_VARS];

const ONE: Mono = [0; MAX_VARS];

/// What variable `2j` stands for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Var {
    /// `2j` = cos θ_j, `2j+1` = sin θ_j.
    Angle,
    /// `2j` = d_j (prismatic); `2j+1` unused.
    Length,
}

/// A polynomial in the joint variables, in normal form.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Poly {
    /// Terms sorted by monomial; no zero coefficients, no `sin` of degree > 1.
    terms: Vec<(Mono, f64)>,
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Poly {
        Poly { terms: Vec::new() }
    }

    /// A constant.
    pub fn constant(x: f64) -> Poly {
        if x == 0.0 {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(ONE, x)],
            }
        }
    }

    /// The variable with index `v`.
    pub fn var(v: usize) -> Poly {
        let mut m = ONE;
        m[v] = 1;
        Poly {
            terms: vec![(m, 1.0)],
        }
    }

    /// `cos θ_j`
    pub fn cos(j: usize) -> Poly {
        Poly::var(2 * j)
    }

    /// `sin θ_j`
    pub fn sin(j: usize) -> Poly {
        Poly::var(2 * j + 1)
    }

    /// `d_j` of a prismatic joint.
    pub fn length(j: usize) -> Poly {
        Poly::var(2 * j)
    }

    /// The terms, sorted.
    pub fn terms(&self) -> &[(Mono, f64)] {
        &self.terms
    }

    /// True for the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// Builds a polynomial from accumulated `(value, magnitude)` per monomial.
    fn collect(acc: Accumulator) -> Poly {
        let mut terms: Vec<(Mono, f64)> = acc
            .into_iter()
            .filter(|(_, (v, mag))| v.abs() > CANCEL * mag)
            .map(|(m, (v, _))| (m, v))
            .collect();
        terms.sort_unstable_by_key(|t| t.0);
        Poly { terms }
    }

    /// `self + sign · other`, merging the two sorted term lists.
    fn combine(&self, other: &Poly, sign: f64) -> Poly {
        let (a, b) = (&self.terms, &other.terms);
        let mut terms = Vec::with_capacity(a.len() + b.len());
        let (mut i, mut j) = (0, 0);
        while i < a.len() || j < b.len() {
            match (a.get(i), b.get(j)) {
                (Some(x), Some(y)) if x.0 == y.0 => {
                    let v = x.1 + sign * y.1;
                    if v.abs() > CANCEL * (x.1.abs() + y.1.abs()) {
                        terms.push((x.0, v));
                    }
                    i += 1;
                    j += 1;
                }
                (Some(x), Some(y)) if x.0 < y.0 => {
                    terms.push(*x);
                    i += 1;
                }
                (Some(x), None) => {
                    terms.push(*x);
                    i += 1;
                }
                (_, Some(y)) => {
                    terms.push((y.0, sign * y.1));
                    j += 1;
                }
                (None, None) => unreachable!("the loop runs while a term is left"),
            }
        }
        Poly { terms }
    }

    /// `self + other`
    pub fn add(&self, other: &Poly) -> Poly {
        self.combine(other, 1.0)
    }

    /// `self - other`
    pub fn sub(&self, other: &Poly) -> Poly {
        self.combine(other, -1.0)
    }

    /// `self + x`
    pub fn add_constant(&self, x: f64) -> Poly {
        self.combine(&Poly::constant(x), 1.0)
    }

    /// `self * k`
    pub fn scale(&self, k: f64) -> Poly {
        if k == 0.0 {
            return Poly::zero();
        }
        Poly {
            terms: self.terms.iter().map(|(m, c)| (*m, c * k)).collect(),
        }
    }

    /// The product, reduced with `sin² = 1 − cos²` for angle variables (`vars[j]`).
    pub fn mul_with(&self, other: &Poly, vars: &[Var]) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        let mut acc = Accumulator::with_capacity_and_hasher(
            self.terms.len() * other.terms.len(),
            Default::default(),
        );
        let mut expanded: Vec<(Mono, f64)> = Vec::new();
        for (ma, ca) in &self.terms {
            for (mb, cb) in &other.terms {
                let mut m = *ma;
                for (x, y) in m.iter_mut().zip(mb) {
                    *x += y;
                }
                reduce(m, ca * cb, vars, &mut expanded);
                for (m, c) in expanded.drain(..) {
                    let e = acc.entry(m).or_insert((0.0, 0.0));
                    e.0 += c;
                    e.1 += c.abs();
                }
            }
        }
        Poly::collect(acc)
    }

    /// `∂/∂q_j` (for an angle: `d cos = −sin`, `d sin = cos`).
    pub fn derivative(&self, j: usize, vars: &[Var]) -> Poly {
        let mut acc = Accumulator::default();
        let push = |m: Mono, c: f64, acc: &mut Accumulator| {
            let e = acc.entry(m).or_insert((0.0, 0.0));
            e.0 += c;
            e.1 += c.abs();
        };
        let (ci, si) = (2 * j, 2 * j + 1);
        let mut expanded = Vec::new();
        for (m, c) in &self.terms {
            match vars[j] {
                Var::Length => {
                    if m[ci] > 0 {
                        let mut d = *m;
                        d[ci] -= 1;
                        push(d, c * f64::from(m[ci]), &mut acc);
                    }
                }
                Var::Angle => {
                    // d(c^a s^b) = a c^(a-1) s^b (-s) + b c^a s^(b-1) c
                    if m[ci] > 0 {
                        let mut d = *m;
                        d[ci] -= 1;
                        d[si] += 1;
                        reduce(d, -c * f64::from(m[ci]), vars, &mut expanded);
                    }
                    if m[si] > 0 {
                        let mut d = *m;
                        d[si] -= 1;
                        d[ci] += 1;
                        reduce(d, c * f64::from(m[si]), vars, &mut expanded);
                    }
                    for (m, c) in expanded.drain(..) {
                        push(m, c, &mut acc);
                    }
                }
            }
        }
        Poly::collect(acc)
    }

    /// Rewrites slot `k` from `θ_k` to the cumulative angle `φ = φ_{k−1} + θ_k`, where slot
    /// `k − 1` holds `φ_{k−1}`: `cos θ_k = cos φ cos φ_{k−1} + sin φ sin φ_{k−1}`,
    /// `sin θ_k = sin φ cos φ_{k−1} − cos φ sin φ_{k−1}`.
    pub fn to_cumulative(&self, k: usize, vars: &[Var]) -> Poly {
        let (pc, ps) = (Poly::cos(k - 1), Poly::sin(k - 1));
        let (u, v) = (Poly::cos(k), Poly::sin(k));
        let cos_k = u.mul_with(&pc, vars).add(&v.mul_with(&ps, vars));
        let sin_k = v.mul_with(&pc, vars).sub(&u.mul_with(&ps, vars));
        let mut out = Poly::zero();
        for (m, c) in &self.terms {
            let (a, b) = (m[2 * k], m[2 * k + 1]);
            let mut rest = *m;
            rest[2 * k] = 0;
            rest[2 * k + 1] = 0;
            let mut t = Poly {
                terms: vec![(rest, *c)],
            };
            for _ in 0..a {
                t = t.mul_with(&cos_k, vars);
            }
            for _ in 0..b {
                t = t.mul_with(&sin_k, vars);
            }
            out = out.add(&t);
        }
        out
    }

    /// Evaluates at numeric variable values (`values[v]`).
    #[cfg(test)]
    pub fn eval(&self, values: &[f64]) -> f64 {
        self.terms
            .iter()
            .map(|(m, c)| {
                m.iter()
                    .enumerate()
                    .filter(|(_, e)| **e > 0)
                    .fold(*c, |acc, (v, e)| acc * values[v].powi(i32::from(*e)))
            })
            .sum()
    }
}

/// Rewrites `s^b` with `b ≥ 2` as `s^(b mod 2) (1 − c²)^(b div 2)` and appends the terms.
fn reduce(m: Mono, c: f64, vars: &[Var], out: &mut Vec<(Mono, f64)>) {
    let start = out.len();
    out.push((m, c));
    for (j, var) in vars.iter().enumerate() {
        if *var != Var::Angle {
            continue;
        }
        let (ci, si) = (2 * j, 2 * j + 1);
        let mut i = start;
        while i < out.len() {
            let (mut mono, coef) = out[i];
            if mono[si] >= 2 {
                // s^2 = 1 - c^2: keep the "1" part in place, append the "-c^2" part.
                mono[si] -= 2;
                out[i] = (mono, coef);
                let mut other = mono;
                other[ci] += 2;
                out.push((other, -coef));
                // Re-examine both (a sin may still be of degree >= 2).
                continue;
            }
            i += 1;
        }
    }
}

/// How much polynomial arithmetic one normal form may cost, in term operations (a product
/// of an `a`-term and a `b`-term polynomial costs `a·b`, a sum `a + b`). The normal form
/// grows exponentially with the number of joints of an arm without structure; the budget
/// bounds the time spent before the derivation gives up on it and keeps the recursive
/// candidates, which grow polynomially.
#[derive(Debug)]
pub struct Budget {
    left: Cell<u64>,
    exhausted: Cell<bool>,
}

impl Budget {
    /// A budget of `work` term operations.
    pub fn new(work: u64) -> Rc<Budget> {
        Rc::new(Budget {
            left: Cell::new(work),
            exhausted: Cell::new(false),
        })
    }

    /// Spends `work`; false (and exhausted from then on) when it does not fit.
    fn charge(&self, work: u64) -> bool {
        if self.exhausted.get() {
            return false;
        }
        match self.left.get().checked_sub(work) {
            Some(left) => {
                self.left.set(left);
                true
            }
            None => {
                self.exhausted.set(true);
                false
            }
        }
    }

    /// Whether some operation did not fit: every result since is meaningless.
    pub fn exhausted(&self) -> bool {
        self.exhausted.get()
    }
}

/// The variable kinds and the budget of an operation's result.
type Context = (Rc<[Var]>, Option<Rc<Budget>>);

/// A polynomial paired with the variable kinds it is reduced against (and the budget its
/// arithmetic draws on), so it can implement [`Ring`] and run the model's generic formulas.
#[derive(Clone, Debug)]
pub struct P {
    /// The polynomial.
    pub poly: Poly,
    vars: Rc<[Var]>,
    budget: Option<Rc<Budget>>,
}

impl P {
    /// Wraps `poly` for the chain with variable kinds `vars`, its arithmetic drawing on
    /// `budget`.
    pub fn new(poly: Poly, vars: &Rc<[Var]>, budget: &Rc<Budget>) -> P {
        P {
            poly,
            vars: vars.clone(),
            budget: Some(budget.clone()),
        }
    }

    /// The variable kinds and budget of whichever operand has them (constants have none),
    /// after charging `work`; `None` when the budget is spent.
    fn context(a: &P, b: &P, work: u64) -> Option<Context> {
        let vars = if a.vars.len() >= b.vars.len() {
            a.vars.clone()
        } else {
            b.vars.clone()
        };
        let budget = a.budget.clone().or_else(|| b.budget.clone());
        match &budget {
            Some(budget) if !budget.charge(work) => None,
            _ => Some((vars, budget)),
        }
    }

    fn spent(vars: Rc<[Var]>, budget: Option<Rc<Budget>>) -> P {
        P {
            poly: Poly::zero(),
            vars,
            budget,
        }
    }
}

impl core::ops::Add for P {
    type Output = P;
    fn add(self, o: P) -> P {
        let work = (self.poly.terms.len() + o.poly.terms.len()) as u64;
        match P::context(&self, &o, work) {
            Some((vars, budget)) => P {
                poly: self.poly.combine(&o.poly, 1.0),
                vars,
                budget,
            },
            None => P::spent(self.vars, self.budget),
        }
    }
}

impl core::ops::Sub for P {
    type Output = P;
    fn sub(self, o: P) -> P {
        let work = (self.poly.terms.len() + o.poly.terms.len()) as u64;
        match P::context(&self, &o, work) {
            Some((vars, budget)) => P {
                poly: self.poly.combine(&o.poly, -1.0),
                vars,
                budget,
            },
            None => P::spent(self.vars, self.budget),
        }
    }
}

impl core::ops::Mul for P {
    type Output = P;
    fn mul(self, o: P) -> P {
        let work = (self.poly.terms.len() * o.poly.terms.len()) as u64;
        let Some((vars, budget)) = P::context(&self, &o, work) else {
            return P::spent(self.vars, self.budget);
        };
        // A constant factor needs no reduction.
        let poly = match (self.poly.terms.as_slice(), o.poly.terms.as_slice()) {
            ([(m, k)], _) if *m == ONE => o.poly.scale(*k),
            (_, [(m, k)]) if *m == ONE => self.poly.scale(*k),
            _ => self.poly.mul_with(&o.poly, &vars),
        };
        P { poly, vars, budget }
    }
}

impl core::ops::Neg for P {
    type Output = P;
    fn neg(self) -> P {
        P {
            poly: self.poly.scale(-1.0),
            vars: self.vars,
            budget: self.budget,
        }
    }
}

impl Ring for P {
    fn from_f64(x: f64) -> P {
        P {
            poly: Poly::constant(x),
            vars: Rc::from(Vec::new()),
            budget: None,
        }
    }
}

/// Turns a polynomial into an expression by greedy multivariate Horner factoring: the
/// variable present in the most terms is factored out, recursively. Monomials are built
/// in a fixed variable order so that equal products in different outputs are shared.
pub fn to_expr(p: &Poly, g: &SharedGraph, vars: &[Var]) -> E {
    to_expr_in(p, g, vars, &Basis::joint_angles(vars.len()))
}

/// What each angle slot of a polynomial stands for: joint j's own angle, or the
/// cumulative angle `θ_start + … + θ_j` of a run of parallel axes.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Basis {
    /// `start[j]`: the first joint of the sum held in slot j (`j` itself for a plain angle).
    pub start: Vec<usize>,
}

impl Basis {
    /// Every slot is its joint's own angle.
    pub fn joint_angles(n: usize) -> Basis {
        Basis {
            start: (0..n).collect(),
        }
    }
}

/// Like [`to_expr`], for a polynomial whose slots mean what `basis` says.
pub fn to_expr_in(p: &Poly, g: &SharedGraph, vars: &[Var], basis: &Basis) -> E {
    horner(p.terms.clone(), g, vars, basis)
}

/// The expression of slot `v`: an input, or for a cumulative angle the addition formula
/// applied to the shorter sum (built once and shared through the graph).
fn slot_expr(v: usize, g: &SharedGraph, vars: &[Var], basis: &Basis) -> E {
    let j = v / 2;
    if vars[j] == Var::Length {
        return E::sym(g, Sym::Len(j));
    }
    let start = basis.start[j];
    if start == j {
        return E::sym(
            g,
            if v.is_multiple_of(2) {
                Sym::Cos(j)
            } else {
                Sym::Sin(j)
            },
        );
    }
    let mut shorter = basis.clone();
    shorter.start[j - 1] = start;
    let (pc, ps) = (
        slot_expr(2 * (j - 1), g, vars, &shorter),
        slot_expr(2 * (j - 1) + 1, g, vars, &shorter),
    );
    let (c, s) = (E::sym(g, Sym::Cos(j)), E::sym(g, Sym::Sin(j)));
    if v.is_multiple_of(2) {
        pc * c - ps * s
    } else {
        ps * c + pc * s
    }
}

fn horner(terms: Vec<(Mono, f64)>, g: &SharedGraph, vars: &[Var], basis: &Basis) -> E {
    if terms.is_empty() {
        return E::K(0.0);
    }
    // Count, per variable, the terms containing it.
    let mut counts = [0usize; MAX_VARS];
    for (m, _) in &terms {
        for (v, e) in m.iter().enumerate() {
            if *e > 0 {
                counts[v] += 1;
            }
        }
    }
    let best = (0..MAX_VARS).max_by_key(|&v| (counts[v], std::cmp::Reverse(v)));
    match best {
        Some(v) if counts[v] >= 2 => {
            let (with, without): (Vec<_>, Vec<_>) = terms.into_iter().partition(|(m, _)| m[v] > 0);
            let reduced: Vec<(Mono, f64)> = with
                .into_iter()
                .map(|(mut m, c)| {
                    m[v] -= 1;
                    (m, c)
                })
                .collect();
            let x = slot_expr(v, g, vars, basis);
            // Pull out a common coefficient so that `k*(a + b)` is not `k*a + k*b`.
            let inner = factor_out_constant(reduced, g, vars, basis);
            let rest = horner(without, g, vars, basis);
            x * inner + rest
        }
        _ => terms
            .into_iter()
            .map(|(m, c)| monomial(&m, c, g, vars, basis))
            .fold(E::K(0.0), |a, b| a + b),
    }
}

fn factor_out_constant(terms: Vec<(Mono, f64)>, g: &SharedGraph, vars: &[Var], basis: &Basis) -> E {
    if terms.len() >= 2 {
        let k = terms[0].1;
        if terms
            .iter()
            .all(|(_, c)| (c.abs() - k.abs()).abs() <= 1e-15 * k.abs())
        {
            let normalised = terms
                .into_iter()
                .map(|(m, c)| (m, (c / k).round()))
                .collect();
            return E::K(k) * horner(normalised, g, vars, basis);
        }
    }
    horner(terms, g, vars, basis)
}

fn monomial(m: &Mono, c: f64, g: &SharedGraph, vars: &[Var], basis: &Basis) -> E {
    let mut e = E::K(1.0);
    for (v, exp) in m.iter().enumerate() {
        for _ in 0..*exp {
            e = e * slot_expr(v, g, vars, basis);
        }
    }
    E::K(c) * e
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vars(n: usize) -> Vec<Var> {
        vec![Var::Angle; n]
    }

    #[test]
    fn pythagoras_cancels() {
        let v = vars(1);
        let c = Poly::cos(0);
        let s = Poly::sin(0);
        let sum = c.mul_with(&c, &v).combine(&s.mul_with(&s, &v), 1.0);
        assert_eq!(sum, Poly::constant(1.0));
    }

    #[test]
    fn derivative_of_product() {
        let v = vars(2);
        // d/dq0 (c0 s0 c1) = (c0^2 - s0^2) c1 = (2 c0^2 - 1) c1
        let p = Poly::cos(0)
            .mul_with(&Poly::sin(0), &v)
            .mul_with(&Poly::cos(1), &v);
        let d = p.derivative(0, &v);
        let q = [0.3_f64, 0.9];
        let vals = [q[0].cos(), q[0].sin(), q[1].cos(), q[1].sin()];
        let want = (2.0 * q[0]).cos() * q[1].cos();
        assert!((d.eval(&vals) - want).abs() < 1e-15);
    }
}
