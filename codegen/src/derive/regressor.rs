//! The joint torque regressor `Y(q, q̇, q̈)` (`τ = Y π`) and the base parameters, in the
//! order and frames of [`dhgen_description::parameters`].
//!
//! `Y` is the chain's regressor recursion ([`RingChain::regressor`]: the outward pass once,
//! then each link's unit wrenches against the joint axes carried out to it) plus the
//! joint-side columns. The base parameters are found by the one rule of
//! `dhgen_description::parameters` (Gautier's pivoted QR over seeded states) applied to this same
//! recursion evaluated in `f64` when the module is generated; the base regressor is then the
//! independent columns, whose derivation is a subset of `Y`'s graph (nothing else is emitted).

use crate::chain::{Numbers, RingChain};
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::nalgebra::DMatrix;
use dhgen_description::parameters::{BODY_PARAMETERS, BaseParameters, Column};
use dhgen_description::{ChainRef, Ring, RobotModel};

/// `Y` row by row from the link columns `links` of [`RingChain::regressor`]: the joint-side
/// columns `q̈_i` (armature), `q̇_i` (viscous) and `coulomb(i)` (Coulomb) in their rows.
fn assemble<R: Ring>(
    columns: &[Column],
    links: &[Vec<R>],
    qd: &[R],
    qdd: &[R],
    coulomb: impl Fn(usize) -> R,
) -> Vec<Vec<R>> {
    links
        .iter()
        .enumerate()
        .map(|(i, row)| {
            columns
                .iter()
                .map(|c| match *c {
                    Column::Body { link, k } => row[BODY_PARAMETERS * link + k].clone(),
                    Column::Armature(j) if j == i => qdd[i].clone(),
                    Column::Viscous(j) if j == i => qd[i].clone(),
                    Column::Coulomb(j) if j == i => coulomb(i),
                    _ => R::from_f64(0.0),
                })
                .collect()
        })
        .collect()
}

/// `Y` without its Coulomb columns (zero there: `sign` is not arithmetic, the module adds it),
/// row-major, `n × columns.len()`.
pub fn regressor(chain: ChainRef<'_>, columns: &[Column], graph: &SharedGraph) -> Vec<E> {
    let n = chain.dof();
    let qd: Vec<E> = (0..n).map(|i| E::sym(graph, Sym::Qd(i))).collect();
    let qdd: Vec<E> = (0..n).map(|i| E::sym(graph, Sym::Qdd(i))).collect();
    let links = super::graph_chain(chain, graph).regressor(&qd, &qdd);
    assemble(columns, &links, &qd, &qdd, |_| E::K(0.0))
        .into_iter()
        .flatten()
        .collect()
}

/// The robot's base parameters, by `dhgen_description::parameters::base_parameters` on this
/// module's regressor evaluated in `f64` (`sign(0) = 0` in the Coulomb columns).
pub fn base_parameters(model: &RobotModel) -> BaseParameters {
    let structure = model.chain();
    let chain = structure.view();
    let columns = dhgen_description::parameters::columns(model);
    dhgen_description::parameters::base_parameters(model, |q, qd, qdd| {
        let links = RingChain::new(chain, &Numbers(chain, q)).regressor(qd, qdd);
        let sign = |i: usize| {
            if qd[i] > 0.0 {
                1.0
            } else if qd[i] < 0.0 {
                -1.0
            } else {
                0.0
            }
        };
        let y = assemble(&columns, &links, qd, qdd, sign);
        DMatrix::from_fn(chain.dof(), columns.len(), |r, c| y[r][c])
    })
}
