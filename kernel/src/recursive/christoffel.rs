//! The Christoffel symbols from the analytic derivatives of `D(q)`.

use super::*;

/// The Christoffel symbols `c_ijk` (k the equation index) into `out`, row-major
/// (`out[(i·n + j)·n + k]`, n = `states.len()`), from body states whose composites are
/// accumulated, with `moved` and `screw` scratch of n² entries each. With `S_i` the joint
/// screws, `I^C_l` the composite inertias and `×` the spatial cross product, for `a ≤ b`:
/// `∂D_ab/∂q_l` is 0 for `l ≤ a`, `(S_a × S_l)·I^C_b S_b` for `a < l < b`, and
/// `(S_a × S_l)·I^C_l S_b + (S_b × S_l)·I^C_l S_a` for `l ≥ b`; these derivatives are written
/// into `out` first, then each triple of indices is turned into its symbols in place
/// (`c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` reads three derivatives and gives three
/// symbols, each at the places its symmetries put it), so no third array of n³ is needed.
/// Slices shorter than that are left as they are (callers size them; no panic either way).
pub fn christoffel_into<T: Real>(
    states: &[BodyState<T>],
    moved: &mut [Force<T>],
    screw: &mut [Motion<T>],
    out: &mut [T],
) {
    let n = states.len();
    if moved.len() < n * n || screw.len() < n * n || out.len() < n * n * n {
        return;
    }
    // moved[l·n + j] = I^C_l S_j for j ≤ l; screw[a·n + l] = S_a × S_l for a < l.
    for (l, sl) in states.iter().enumerate() {
        for (j, sj) in states.iter().enumerate().take(l + 1) {
            moved[l * n + j] = sl.composite.apply(&sj.axis);
        }
        for (a, sa) in states.iter().enumerate().take(l) {
            screw[a * n + l] = sa.axis.cross(&sl.axis);
        }
    }
    // out[(l·n + a)·n + b] = ∂D_ab/∂q_l.
    out.fill(T::zero());
    for a in 0..n {
        for b in a..n {
            for l in a + 1..n {
                let mut v = screw[a * n + l].dot(&moved[l.max(b) * n + b]);
                if l > b {
                    v += screw[b * n + l].dot(&moved[l * n + a]);
                }
                out[(l * n + a) * n + b] = v;
                out[(l * n + b) * n + a] = v;
            }
        }
    }
    // Per triple x ≤ y ≤ z: the derivatives d_x = ∂D_yz/∂q_x, d_y = ∂D_xz/∂q_y,
    // d_z = ∂D_xy/∂q_z, and the symbols c_xyz = c_yxz = ½(d_x + d_y − d_z),
    // c_xzy = c_zxy = ½(d_x + d_z − d_y), c_yzx = c_zyx = ½(d_y + d_z − d_x).
    let half: T = k(0.5);
    let at = |i: usize, j: usize, k: usize| (i * n + j) * n + k;
    for x in 0..n {
        for y in x..n {
            for z in y..n {
                let (dx, dy, dz) = (out[at(x, y, z)], out[at(y, x, z)], out[at(z, x, y)]);
                let c_xyz = half * ((dx + dy) - dz);
                let c_xzy = half * ((dx + dz) - dy);
                let c_yzx = half * ((dy + dz) - dx);
                out[at(x, y, z)] = c_xyz;
                out[at(y, x, z)] = c_xyz;
                out[at(x, z, y)] = c_xzy;
                out[at(z, x, y)] = c_xzy;
                out[at(y, z, x)] = c_yzx;
                out[at(z, y, x)] = c_yzx;
            }
        }
    }
}

/// The Christoffel symbols of `chain`'s `D(q)`, `[i][j][k]` = `c_ijk` (k the equation index),
/// at the configuration given as for [`mass_matrix`]: the runtime path's algorithm
/// (`dhgen::Robot::christoffel`), O(n³), from the analytic derivatives
/// of D. Motor inertias are constant and do not enter.
#[must_use]
pub fn christoffel<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
) -> [[[T; N]; N]; N] {
    let mut states = states_at(chain, cos, sin, d);
    accumulate_composites(&mut states);
    let mut moved = [[Force::zero(); N]; N];
    let mut screw = [[Motion::zero(); N]; N];
    let mut out = [[[T::zero(); N]; N]; N];
    christoffel_into(
        &states,
        moved.as_flattened_mut(),
        screw.as_flattened_mut(),
        out.as_flattened_mut().as_flattened_mut(),
    );
    out
}
