//! Derivations: each quantity as expressions over one graph, ready for emission.
//!
//! Where two derivations exist (the expanded normal form factored by Horner's rule, or a
//! recursion over the chain kept unexpanded), both are built and the one with fewer
//! operations after common-subexpression sharing is kept.

pub mod christoffel;
pub mod energy;
pub mod gravity;
pub mod inertia;
pub mod kinematics;
pub mod newton_euler;
pub mod singularity;

use crate::chain::{JointSymbols, RingChain};
use crate::graph::{E, SharedGraph, Sym, count};
use crate::poly::{Basis, P, Poly, Var};
use dhgen_model::{ChainRef, JointKind};
use std::cell::OnceCell;
use std::rc::Rc;

/// One robot's derivations, with the expensive normal forms built at most once.
pub struct Derivation<'c> {
    /// The robot's structure.
    pub chain: ChainRef<'c>,
    mass_matrix: OnceCell<Vec<Vec<Poly>>>,
    christoffel: OnceCell<Vec<Vec<Vec<Poly>>>>,
    gravity: OnceCell<Vec<Poly>>,
}

/// Terms in D's normal form above which expanding is not worth trying: arms without
/// parallel axes and with full inertia tensors (e.g. 7-DOF) expand to many thousands.
const NORMAL_FORM_TERMS: usize = 4000;

impl<'c> Derivation<'c> {
    /// Starts the derivations of the robot with structure `chain`.
    pub fn new(chain: ChainRef<'c>) -> Self {
        Derivation {
            chain,
            mass_matrix: OnceCell::new(),
            christoffel: OnceCell::new(),
            gravity: OnceCell::new(),
        }
    }

    /// D(q) in the normal form (motor inertia included), row-major.
    pub fn mass_matrix_polys(&self) -> &Vec<Vec<Poly>> {
        self.mass_matrix
            .get_or_init(|| inertia::mass_matrix_polys(self.chain))
    }

    /// `c[i][j][k]` in the normal form.
    pub fn christoffel_polys(&self) -> &Vec<Vec<Vec<Poly>>> {
        self.christoffel
            .get_or_init(|| christoffel::christoffel_polys(self.chain, self.mass_matrix_polys()))
    }

    /// g(q) in the normal form.
    pub fn gravity_polys(&self) -> &Vec<Poly> {
        self.gravity
            .get_or_init(|| gravity::gravity_polys(self.chain))
    }

    /// D(q) as Horner-factored expressions in `graph`, flattened row-major.
    pub fn mass_matrix_exprs(&self, graph: &SharedGraph) -> Vec<E> {
        let flat: Vec<Poly> = self.mass_matrix_polys().iter().flatten().cloned().collect();
        polys_to_exprs(&flat, graph, self.chain)
    }

    /// `c[i][j][k]` as Horner-factored expressions in `graph`, flattened `(i·n + j)·n + k`.
    pub fn christoffel_exprs(&self, graph: &SharedGraph) -> Vec<E> {
        let flat: Vec<Poly> = self
            .christoffel_polys()
            .iter()
            .flatten()
            .flatten()
            .cloned()
            .collect();
        polys_to_exprs(&flat, graph, self.chain)
    }

    /// g(q) as Horner-factored expressions in `graph`.
    pub fn gravity_exprs(&self, graph: &SharedGraph) -> Vec<E> {
        polys_to_exprs(self.gravity_polys(), graph, self.chain)
    }

    /// Whether the normal form is small enough for its candidates to be worth building.
    pub fn normal_form_is_small(&self) -> bool {
        let terms: usize = self
            .mass_matrix_polys()
            .iter()
            .flatten()
            .map(|p| p.terms().len())
            .sum();
        terms <= NORMAL_FORM_TERMS
    }
}

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

/// The variable kinds of a chain's joints.
pub fn vars(chain: ChainRef<'_>) -> Rc<[Var]> {
    chain
        .bodies
        .iter()
        .map(|b| match b.joint {
            JointKind::Revolute => Var::Angle,
            JointKind::Prismatic => Var::Length,
        })
        .collect()
}

/// The chain in expression arithmetic.
pub fn graph_chain<'c>(chain: ChainRef<'c>, graph: &SharedGraph) -> RingChain<'c, E> {
    RingChain::new(chain, &GraphSymbols(graph))
}

/// The chain in normal-form arithmetic.
pub fn poly_chain(chain: ChainRef<'_>) -> RingChain<'_, P> {
    RingChain::new(chain, &PolySymbols(vars(chain)))
}

/// Of several candidate derivations of the same outputs, each in its own graph, the one
/// with the fewest operations.
pub fn cheapest(candidates: Vec<(SharedGraph, Vec<E>)>) -> (SharedGraph, Vec<E>) {
    candidates
        .into_iter()
        .min_by_key(|(graph, outs)| {
            let roots: Vec<_> = outs.iter().map(|e| e.id_in(graph)).collect();
            count(&graph.borrow(), roots).total()
        })
        .expect("at least one candidate")
}

/// Runs of consecutive revolute joints with parallel axes (no constant rotation between
/// them): their angles add up, and `cos(θ2 + θ3)` is one variable instead of four terms.
pub fn parallel_runs(chain: ChainRef<'_>) -> Basis {
    let mut start: Vec<usize> = (0..chain.dof()).collect();
    for k in 1..chain.dof() {
        if chain.parallel_to_previous(k) {
            start[k] = start[k - 1];
        }
    }
    Basis { start }
}

/// Polynomials as expressions in `graph`, Horner-factored; each polynomial is written in
/// cumulative angles of parallel axes when that gives fewer terms.
pub fn polys_to_exprs(polys: &[Poly], graph: &SharedGraph, chain: ChainRef<'_>) -> Vec<E> {
    let v = vars(chain);
    let runs = parallel_runs(chain);
    let plain = Basis::joint_angles(chain.dof());
    polys
        .iter()
        .map(|p| {
            if runs == plain {
                return crate::poly::to_expr(p, graph, &v);
            }
            let mut q = p.clone();
            for k in 1..chain.dof() {
                if runs.start[k] != k {
                    q = q.to_cumulative(k, &v);
                }
            }
            if q.terms().len() < p.terms().len() {
                crate::poly::to_expr_in(&q, graph, &v, &runs)
            } else {
                crate::poly::to_expr(p, graph, &v)
            }
        })
        .collect()
}
