//! Forward-mode dual numbers over expressions: a value and its partial derivatives with
//! respect to every joint variable.
//!
//! Running the composite-rigid-body recursion on [`Dual`] gives D(q) and all ∂D/∂q_m
//! without ever expanding a polynomial: the derivative of each operation is built next to
//! the operation, shared through the same hash-consed graph. For large arms (no parallel
//! axes, full inertia tensors) this is far smaller than differentiating the normal form.

use crate::chain::JointSymbols;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::Ring;
use std::rc::Rc;

/// A value with its gradient; an empty gradient means all zeros (a constant).
#[derive(Clone, Debug)]
pub struct Dual {
    /// The value.
    pub v: E,
    /// `∂v/∂q_m` for m = 0..n, or empty.
    pub d: Rc<[E]>,
}

impl Dual {
    /// `∂v/∂q_m`.
    pub fn partial(&self, m: usize) -> E {
        self.d.get(m).cloned().unwrap_or(E::K(0.0))
    }

    fn zip(a: &Rc<[E]>, b: &Rc<[E]>, f: impl Fn(E, E) -> E) -> Rc<[E]> {
        match (a.is_empty(), b.is_empty()) {
            (true, true) => a.clone(),
            (false, true) => a.iter().map(|x| f(x.clone(), E::K(0.0))).collect(),
            (true, false) => b.iter().map(|y| f(E::K(0.0), y.clone())).collect(),
            (false, false) => a
                .iter()
                .zip(b.iter())
                .map(|(x, y)| f(x.clone(), y.clone()))
                .collect(),
        }
    }
}

impl core::ops::Add for Dual {
    type Output = Dual;
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            d: Dual::zip(&self.d, &o.d, |a, b| a + b),
        }
    }
}

impl core::ops::Sub for Dual {
    type Output = Dual;
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            d: Dual::zip(&self.d, &o.d, |a, b| a - b),
        }
    }
}

// The product rule adds inside a multiplication.
#[allow(clippy::suspicious_arithmetic_impl)]
impl core::ops::Mul for Dual {
    type Output = Dual;
    fn mul(self, o: Dual) -> Dual {
        // (uv)' = u'v + uv'
        let d = match (self.d.is_empty(), o.d.is_empty()) {
            (true, true) => self.d.clone(),
            (false, true) => self.d.iter().map(|x| x.clone() * o.v.clone()).collect(),
            (true, false) => o.d.iter().map(|y| self.v.clone() * y.clone()).collect(),
            (false, false) => self
                .d
                .iter()
                .zip(o.d.iter())
                .map(|(x, y)| x.clone() * o.v.clone() + self.v.clone() * y.clone())
                .collect(),
        };
        Dual { v: self.v * o.v, d }
    }
}

impl core::ops::Neg for Dual {
    type Output = Dual;
    fn neg(self) -> Dual {
        Dual {
            v: -self.v,
            d: self.d.iter().map(|x| -x.clone()).collect(),
        }
    }
}

impl Ring for Dual {
    fn from_f64(x: f64) -> Dual {
        Dual {
            v: E::K(x),
            d: Rc::from(Vec::new()),
        }
    }
}

/// Joint variables as duals seeded with unit tangents.
pub struct DualSymbols<'g> {
    /// The graph the values live in.
    pub graph: &'g SharedGraph,
    /// Number of joints.
    pub n: usize,
}

impl DualSymbols<'_> {
    fn seeded(&self, v: E, j: usize, dv: E) -> Dual {
        let d = (0..self.n)
            .map(|m| if m == j { dv.clone() } else { E::K(0.0) })
            .collect();
        Dual { v, d }
    }
}

impl JointSymbols<Dual> for DualSymbols<'_> {
    fn angle(&self, j: usize) -> (Dual, Dual) {
        let c = E::sym(self.graph, Sym::Cos(j));
        let s = E::sym(self.graph, Sym::Sin(j));
        (self.seeded(c.clone(), j, -s.clone()), self.seeded(s, j, c))
    }
    fn length(&self, j: usize) -> Dual {
        self.seeded(E::sym(self.graph, Sym::Len(j)), j, E::K(1.0))
    }
}

/// Joint variables as duals with one lane: the derivative along the motion `q̇`, so that a
/// recursion run on them gives a quantity and its rate of change (`D` and `Ḋ`).
pub struct RateSymbols<'g> {
    /// The graph the values live in.
    pub graph: &'g SharedGraph,
}

impl JointSymbols<Dual> for RateSymbols<'_> {
    fn angle(&self, j: usize) -> (Dual, Dual) {
        let c = E::sym(self.graph, Sym::Cos(j));
        let s = E::sym(self.graph, Sym::Sin(j));
        let qd = E::sym(self.graph, Sym::Qd(j));
        (
            Dual {
                v: c.clone(),
                d: Rc::from(vec![-(s.clone() * qd.clone())]),
            },
            Dual {
                v: s,
                d: Rc::from(vec![c * qd]),
            },
        )
    }
    fn length(&self, j: usize) -> Dual {
        Dual {
            v: E::sym(self.graph, Sym::Len(j)),
            d: Rc::from(vec![E::sym(self.graph, Sym::Qd(j))]),
        }
    }
}
