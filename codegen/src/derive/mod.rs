//! Derivations: each quantity as expressions over one graph, ready for emission.
//!
//! Where two derivations exist (the expanded normal form factored by Horner's rule, or a
//! recursion over the chain kept unexpanded), both are built and the one with fewer
//! operations after common-subexpression sharing is kept.

pub mod center_of_mass;
pub mod christoffel;
pub mod derivatives;
pub mod energy;
pub mod gravity;
pub mod inertia;
pub mod kinematics;
pub mod newton_euler;
pub mod payload;
pub mod regressor;
pub mod singularity;

use crate::chain::{Coordinates, JointSymbols, RingChain};
use crate::graph::{E, SharedGraph, Sym, cost};
use crate::poly::{Basis, Budget, P, Poly, Var};
use dhgen_description::{ChainRef, JointKind};
use std::cell::OnceCell;
use std::rc::Rc;

/// One robot's derivations, with the expensive normal forms built at most once, or not at
/// all when they would be too large.
pub struct Derivation<'c> {
    /// The robot's structure.
    pub chain: ChainRef<'c>,
    mass_matrix: OnceCell<Option<Vec<Vec<Poly>>>>,
    christoffel: OnceCell<Option<Vec<Vec<Vec<Poly>>>>>,
    gravity: OnceCell<Option<Vec<Poly>>>,
}

/// Terms in D's normal form above which its candidates are not worth building: arms without
/// parallel axes and with full inertia tensors (e.g. 7-DOF) expand to many thousands.
const NORMAL_FORM_TERMS: usize = 4000;

/// Term operations (see [`Budget`]) D's normal form may cost before it is abandoned for the
/// recursive candidates. D's normal form wins where the arm has structure (exact quarter
/// turns, parallel axes): the PUMA 560's costs 1,300, the UR5's 7,600. Without structure it
/// grows exponentially with the number of joints (a general 10-joint arm's has 1.2 million
/// terms) and never wins; everything built from it (the Christoffel symbols by
/// differentiation, τ assembled from D, c and g) costs far more than D itself.
pub const MASS_MATRIX_WORK: u64 = 30_000;

/// The same for g(q), whose normal form is smaller and wins more often (a general 6-joint
/// arm's costs 38,000 and saves a fifth of g's operations).
pub const GRAVITY_WORK: u64 = 100_000;

/// The most joints a normal form takes: two variables per joint in a monomial.
pub const NORMAL_FORM_JOINTS: usize = crate::poly::MAX_VARS / 2;

/// Whether a chain can have a normal form at all.
fn fits_normal_form(chain: ChainRef<'_>) -> bool {
    chain.dof() <= NORMAL_FORM_JOINTS
}

/// Runs `build` on a fresh budget of `work`; `None` when the budget ran out (or the chain has
/// too many joints for the normal form).
pub fn within_budget<T>(
    chain: ChainRef<'_>,
    work: u64,
    build: impl FnOnce(&Rc<Budget>) -> T,
) -> Option<T> {
    if !fits_normal_form(chain) {
        return None;
    }
    let budget = Budget::new(work);
    let out = build(&budget);
    (!budget.exhausted()).then_some(out)
}

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

    /// D(q) in the normal form (motor inertia included), row-major; `None` when it is too
    /// large to build.
    pub fn mass_matrix_polys(&self) -> Option<&Vec<Vec<Poly>>> {
        self.mass_matrix
            .get_or_init(|| {
                within_budget(self.chain, MASS_MATRIX_WORK, |b| {
                    inertia::mass_matrix_polys(self.chain, b)
                })
            })
            .as_ref()
    }

    /// `c[i][j][k]` in the normal form, the derivatives of D's; `None` without it.
    pub fn christoffel_polys(&self) -> Option<&Vec<Vec<Vec<Poly>>>> {
        self.christoffel
            .get_or_init(|| {
                let d = self.mass_matrix_polys()?;
                Some(christoffel::christoffel_polys(self.chain, d))
            })
            .as_ref()
    }

    /// P(q) in the normal form, on g's budget; `None` when it is too large to build.
    pub fn potential_energy_poly(&self) -> Option<Poly> {
        within_budget(self.chain, GRAVITY_WORK, |b| {
            poly_chain(self.chain, b).potential_energy().poly
        })
    }

    /// g(q) in the normal form; `None` when it is too large to build.
    pub fn gravity_polys(&self) -> Option<&Vec<Poly>> {
        self.gravity
            .get_or_init(|| {
                within_budget(self.chain, GRAVITY_WORK, |b| {
                    gravity::gravity_polys(self.chain, b)
                })
            })
            .as_ref()
    }

    /// D(q) as Horner-factored expressions in `graph`, flattened row-major.
    pub fn mass_matrix_exprs(&self, graph: &SharedGraph) -> Option<Vec<E>> {
        let flat: Vec<Poly> = self
            .mass_matrix_polys()?
            .iter()
            .flatten()
            .cloned()
            .collect();
        Some(polys_to_exprs(&flat, graph, self.chain))
    }

    /// `c[i][j][k]` as Horner-factored expressions in `graph`, flattened `(i·n + j)·n + k`.
    pub fn christoffel_exprs(&self, graph: &SharedGraph) -> Option<Vec<E>> {
        let flat: Vec<Poly> = self
            .christoffel_polys()?
            .iter()
            .flatten()
            .flatten()
            .cloned()
            .collect();
        Some(polys_to_exprs(&flat, graph, self.chain))
    }

    /// g(q) as Horner-factored expressions in `graph`.
    pub fn gravity_exprs(&self, graph: &SharedGraph) -> Option<Vec<E>> {
        Some(polys_to_exprs(self.gravity_polys()?, graph, self.chain))
    }

    /// Whether D's normal form exists and is small enough for the candidates built from it
    /// (the symbols by differentiation, τ assembled from D, c and g) to be worth building.
    pub fn normal_form_is_small(&self) -> bool {
        self.mass_matrix_polys().is_some_and(|d| {
            d.iter().flatten().map(|p| p.terms().len()).sum::<usize>() <= NORMAL_FORM_TERMS
        })
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

/// Normal-form variables for the joint variables, their arithmetic drawing on a budget.
pub struct PolySymbols(pub Rc<[Var]>, pub Rc<Budget>);

impl JointSymbols<P> for PolySymbols {
    fn angle(&self, j: usize) -> (P, P) {
        (
            P::new(Poly::cos(j), &self.0, &self.1),
            P::new(Poly::sin(j), &self.0, &self.1),
        )
    }
    fn length(&self, j: usize) -> P {
        P::new(Poly::length(j), &self.0, &self.1)
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

/// The chain in normal-form arithmetic, drawing on `budget`.
pub fn poly_chain<'c>(chain: ChainRef<'c>, budget: &Rc<Budget>) -> RingChain<'c, P> {
    RingChain::new(chain, &PolySymbols(vars(chain), budget.clone()))
}

/// The coordinates the spatial candidates (C, ∂τ/∂q) are built in: the root frame and every
/// joint frame. Their outputs are dot products of spatial vectors, the same in any frame; how
/// many operations they cost depends on how many joint variables lie between the bodies and
/// the frame, so each is tried.
pub fn coordinates(chain: ChainRef<'_>) -> impl Iterator<Item = Coordinates> {
    std::iter::once(Coordinates::Root).chain((0..chain.dof()).map(Coordinates::Joint))
}

/// Every form the recursions with a spatial form (D, C, ∂τ/∂q) are built in: joint by joint in
/// joint frames (`None`, carrying vectors through each joint transform, as the CRBA does), then
/// in each frame's coordinates ([`coordinates`]).
pub fn frames(chain: ChainRef<'_>) -> impl Iterator<Item = Option<Coordinates>> {
    std::iter::once(None).chain(coordinates(chain).map(Some))
}

/// A derivative along joint m by `derivative`, or `zero` where the dynamics do not depend on
/// q_m ([`ChainRef::dynamics_ignore`]: moving joint m is a symmetry of the dynamics), which no
/// candidate need compute.
pub fn along_joint<T>(chain: ChainRef<'_>, m: usize, zero: T, derivative: impl FnOnce() -> T) -> T {
    if chain.dynamics_ignore(m) {
        zero
    } else {
        derivative()
    }
}

/// Dynamics' expressions `exprs` (in `graph`) evaluated at 0 for the joints they do not
/// depend on ([`ChainRef::dynamics_ignore`]): cos 1, sin 0, displacement 0. Exact, since the
/// value does not depend on them, and the folding drops what a recursion computes for them
/// (PUMA 560's ∂τ: 1,951 → 1,846 operations, and no sine of q6).
pub fn without_ignored_joints(chain: ChainRef<'_>, graph: &SharedGraph, exprs: &[E]) -> Vec<E> {
    without_joints(chain, graph, exprs, |j| chain.dynamics_ignore(j))
}

/// `exprs` with joint j held at its zero wherever `ignored(j)` (cosine 1, sine 0, length 0).
pub fn without_joints(
    chain: ChainRef<'_>,
    graph: &SharedGraph,
    exprs: &[E],
    ignored: impl Fn(usize) -> bool,
) -> Vec<E> {
    let ignored: Vec<bool> = (0..chain.dof()).map(ignored).collect();
    if !ignored.contains(&true) {
        return exprs.to_vec();
    }
    crate::graph::substitute(graph, exprs, |s| match s {
        Sym::Cos(j) if ignored[j] => Some(E::K(1.0)),
        Sym::Sin(j) | Sym::Len(j) if ignored[j] => Some(E::K(0.0)),
        _ => None,
    })
}

/// [`cheapest`] for a quantity of the robot's own dynamics (without payload, not the
/// regressor): each candidate first [without the joints the dynamics
/// ignore](without_ignored_joints), so the recursions compete after dropping what they
/// compute for them.
pub fn cheapest_dynamics(
    chain: ChainRef<'_>,
    candidates: Vec<(SharedGraph, Vec<E>)>,
) -> (SharedGraph, Vec<E>) {
    cheapest(
        candidates
            .into_iter()
            .map(|(graph, e)| {
                let e = without_ignored_joints(chain, &graph, &e);
                (graph, e)
            })
            .collect(),
    )
}

/// Of several candidate derivations of the same outputs, each in its own graph, the one
/// with the fewest operations.
pub fn cheapest(candidates: Vec<(SharedGraph, Vec<E>)>) -> (SharedGraph, Vec<E>) {
    candidates
        .into_iter()
        .min_by_key(|(graph, outs)| cost(graph, outs))
        .expect("at least one candidate")
}

/// For outputs in groups, each group with one or more derivations in one `graph`
/// (`options[g]`, the outputs of group g as built by each), one derivation per group: the mix
/// with the fewest operations after sharing, found greedily (from each uniform start, every
/// group on its s-th option or its last, switching any one group while that lowers the
/// total). A group without options is an error of the caller's: it panics.
pub fn cheapest_mix(graph: &SharedGraph, options: &[Vec<Vec<E>>]) -> Vec<Vec<E>> {
    let total =
        |choice: &[usize]| cost(graph, choice.iter().zip(options).flat_map(|(&c, o)| &o[c]));
    let starts = options.iter().map(Vec::len).max().unwrap_or(0);
    let mut overall: Option<(usize, Vec<usize>)> = None;
    for s in 0..starts {
        let mut choice: Vec<usize> = options.iter().map(|o| s.min(o.len() - 1)).collect();
        let mut best = total(&choice);
        let mut improved = true;
        while improved {
            improved = false;
            for g in 0..options.len() {
                for o in 0..options[g].len() {
                    let old = std::mem::replace(&mut choice[g], o);
                    let c = total(&choice);
                    if c < best {
                        best = c;
                        improved = true;
                    } else {
                        choice[g] = old;
                    }
                }
            }
        }
        if overall.as_ref().is_none_or(|(b, _)| best < *b) {
            overall = Some((best, choice));
        }
    }
    let choice = overall.map(|(_, c)| c).unwrap_or_default();
    choice
        .iter()
        .zip(options)
        .map(|(&c, o)| o[c].clone())
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Two groups whose derivations share across groups only when mixed: group 0 is `a·b` or
    /// `c·d`, group 1 `c·d + a` or `a·b + c`. Either uniform choice costs 3 operations; a mix
    /// reuses its product and costs 2.
    #[test]
    fn mix_costs_no_more_than_any_uniform_choice_and_finds_the_sharing() {
        let graph = SharedGraph::default();
        let [a, b, c, d] = [0, 1, 2, 3].map(|i| E::sym(&graph, Sym::Qd(i)));
        let ab = a.clone() * b.clone();
        let cd = c.clone() * d.clone();
        let options = vec![
            vec![vec![ab.clone()], vec![cd.clone()]],
            vec![vec![cd + a.clone()], vec![ab + c]],
        ];
        let total = |outs: &[Vec<E>]| cost(&graph, outs.iter().flatten());
        let uniform: Vec<usize> = (0..2)
            .map(|o| total(&[options[0][o].clone(), options[1][o].clone()]))
            .collect();
        assert_eq!(uniform, [3, 3]);
        assert_eq!(total(&cheapest_mix(&graph, &options)), 2);
    }
}
