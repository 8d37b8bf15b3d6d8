//! Derivations: each quantity as expressions over one graph, ready for emission.
//!
//! Where two derivations exist (the expanded normal form factored by Horner's rule, or a
//! recursion over the chain kept unexpanded), both are built and the one with fewer
//! operations after common-subexpression sharing is kept.

pub mod christoffel;
pub mod gravity;
pub mod inertia;
pub mod kinematics;
pub mod newton_euler;

use crate::chain::{Chain, JointSymbols};
use crate::graph::{E, SharedGraph, Sym, count};
use crate::poly::{P, Poly, Var};
use dhgen_model::{JointKind, RobotModel};
use std::rc::Rc;

/// Graph inputs for the joint variables.
pub struct GraphSymbols<'g>(pub &'g SharedGraph);

impl JointSymbols<E> for GraphSymbols<'_> {
    fn angle(&self, j: usize) -> (E, E) {
        (E::sym(self.0, Sym::Cos(j)), E::sym(self.0, Sym::Sin(j)))
    }
    fn length(&self, j: usize) -> E {
        E::sym(self.0, Sym::Len(j))
    }
}

/// Normal-form variables for the joint variables.
pub struct PolySymbols(pub Rc<[Var]>);

impl JointSymbols<P> for PolySymbols {
    fn angle(&self, j: usize) -> (P, P) {
        (P::new(Poly::cos(j), &self.0), P::new(Poly::sin(j), &self.0))
    }
    fn length(&self, j: usize) -> P {
        P::new(Poly::length(j), &self.0)
    }
}

/// The variable kinds of a model's joints.
pub fn vars(model: &RobotModel) -> Rc<[Var]> {
    model
        .links
        .iter()
        .map(|l| match l.joint {
            JointKind::Revolute => Var::Angle,
            JointKind::Prismatic => Var::Length,
        })
        .collect()
}

/// The chain in expression arithmetic.
pub fn graph_chain(model: &RobotModel, g: &SharedGraph) -> Chain<E> {
    Chain::new(model, &GraphSymbols(g))
}

/// The chain in normal-form arithmetic.
pub fn poly_chain(model: &RobotModel) -> Chain<P> {
    Chain::new(model, &PolySymbols(vars(model)))
}

/// Of several candidate derivations of the same outputs, each in its own graph, the one
/// with the fewest operations.
pub fn cheapest(candidates: Vec<(SharedGraph, Vec<E>)>) -> (SharedGraph, Vec<E>) {
    candidates
        .into_iter()
        .min_by_key(|(g, outs)| {
            let roots: Vec<_> = outs.iter().map(|e| e.id_in(g)).collect();
            count(&g.borrow(), roots).total()
        })
        .expect("at least one candidate")
}

/// Polynomials as expressions in `g`, Horner-factored.
pub fn polys_to_exprs(polys: &[Poly], g: &SharedGraph, model: &RobotModel) -> Vec<E> {
    let v = vars(model);
    polys
        .iter()
        .map(|p| crate::poly::to_expr(p, g, &v))
        .collect()
}
