//! Christoffel symbols `c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` (k the equation
//! index) by exact differentiation of D's normal form, and `C_kj = Σ_i c_ijk q̇_i`.

use crate::graph::{E, SharedGraph, Sym};
use crate::poly::Poly;
use dhgen_model::RobotModel;

/// `c[i][j][k]` in the normal form (motor inertia is constant and drops out).
pub fn christoffel_polys(model: &RobotModel) -> Vec<Vec<Vec<Poly>>> {
    let n = model.dof();
    let v = super::vars(model);
    let d = super::inertia::mass_matrix_polys(model);
    // dd[m][a][b] = ∂d_ab/∂q_m; D is symmetric, so only a <= b is differentiated.
    let dd: Vec<Vec<Vec<Poly>>> = (0..n)
        .map(|m| {
            let mut out = vec![vec![Poly::zero(); n]; n];
            for a in 0..n {
                for b in a..n {
                    let p = d[a][b].derivative(m, &v);
                    out[b][a] = p.clone();
                    out[a][b] = p;
                }
            }
            out
        })
        .collect();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    (0..n)
                        .map(|k| dd[i][k][j].add(&dd[j][k][i]).sub(&dd[k][i][j]).scale(0.5))
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// `c[i][j][k]` as expressions, flattened `(i·n + j)·n + k`.
pub fn christoffel(model: &RobotModel) -> (SharedGraph, Vec<E>) {
    let g = SharedGraph::default();
    let polys: Vec<Poly> = christoffel_polys(model)
        .into_iter()
        .flatten()
        .flatten()
        .collect();
    let e = super::polys_to_exprs(&polys, &g, model);
    (g, e)
}

/// `C(q, q̇)` row-major: `C_kj = Σ_i c_ijk q̇_i`.
pub fn coriolis(model: &RobotModel) -> (SharedGraph, Vec<E>) {
    let n = model.dof();
    let (g, c) = christoffel(model);
    let qd: Vec<E> = (0..n).map(|i| E::sym(&g, Sym::Qd(i))).collect();
    let mut out = Vec::with_capacity(n * n);
    for k in 0..n {
        for j in 0..n {
            let sum = (0..n).fold(E::K(0.0), |acc, i| {
                acc + c[(i * n + j) * n + k].clone() * qd[i].clone()
            });
            out.push(sum);
        }
    }
    (g, out)
}
