//! The kinematic chain in joint frames, generic over the arithmetic.
//!
//! The structure comes from [`dhgen_description::ChainRef`]: `T(q) = P_0 Z_1 P_1 ⋯ Z_n P_n`. In
//! joint frame k every joint axis is the local z axis through the origin and every link's
//! inertia is constant, and consecutive frames differ by `T_k = P_k · Z_k(q_k)`. The
//! algorithms below (composite inertia, gravity, Newton-Euler, J̇q̇) are written once for any
//! [`Ring`]: polynomials (the normal form), expression nodes and dual numbers alike. They run
//! in the root frame that `P_0` places in the world, with gravity rotated into it; the
//! spatial ones (C, ∂τ/∂q) in any frame's coordinates ([`Coordinates`]).

use dhgen_description::parameters::INERTIA_ENTRIES;
use dhgen_description::{ChainRef, Frame, Inertial, JointKind, JointValue, Ring};

/// A 3-vector over a ring.
pub type V3<R> = [R; 3];

/// A mass and its first moment `m c` about a frame's origin, in its axes.
pub type FirstMoment<R> = (R, V3<R>);

fn k<R: Ring>(x: f64) -> R {
    R::from_f64(x)
}

/// `a × b`
pub fn cross<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    [
        a[1].clone() * b[2].clone() - a[2].clone() * b[1].clone(),
        a[2].clone() * b[0].clone() - a[0].clone() * b[2].clone(),
        a[0].clone() * b[1].clone() - a[1].clone() * b[0].clone(),
    ]
}

fn add3<R: Ring>(a: &V3<R>, b: &V3<R>) -> V3<R> {
    core::array::from_fn(|i| a[i].clone() + b[i].clone())
}

/// The acceleration of the point `p` of a frame whose origin accelerates by `a` and which
/// turns with `w` and `wd` (all in the frame's axes): `a + ω̇ × p + ω × (ω × p)`.
fn point_acceleration<R: Ring>(a: &V3<R>, wd: &V3<R>, w: &V3<R>, p: &V3<R>) -> V3<R> {
    add3(&add3(a, &cross(wd, p)), &cross(w, &cross(w, p)))
}

fn scale3<R: Ring>(s: &R, a: &V3<R>) -> V3<R> {
    core::array::from_fn(|i| s.clone() * a[i].clone())
}

/// `R v`
pub fn rot<R: Ring>(f: &Frame<R>, v: &V3<R>) -> V3<R> {
    mat_vec(&f.r, v)
}

/// `Rᵀ v`
pub fn rot_t<R: Ring>(f: &Frame<R>, v: &V3<R>) -> V3<R> {
    mat_t_vec(&f.r, v)
}

/// Mass properties about a frame's origin: mass, first moment `h = m c`, and the
/// rotational inertia about the origin `Ī`.
#[derive(Clone, Debug)]
pub struct MassMoments<R> {
    /// Mass.
    pub m: R,
    /// First moment of mass.
    pub h: V3<R>,
    /// Rotational inertia about the frame origin.
    pub i: [[R; 3]; 3],
}

impl<R: Ring> MassMoments<R> {
    /// The moments about the origin of the frame `inertial` is given in.
    pub fn about_origin(inertial: &Inertial) -> MassMoments<R> {
        let (m, c) = (inertial.mass, inertial.com);
        let cc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        MassMoments {
            m: k(m),
            h: c.map(|x| k(m * x)),
            i: core::array::from_fn(|a| {
                core::array::from_fn(|b| {
                    let parallel = if a == b { m * cc } else { 0.0 } - m * c[a] * c[b];
                    k(inertial.inertia[a][b] + parallel)
                })
            }),
        }
    }

    /// The body seen from the parent frame of `f` (`f` maps child coordinates to parent).
    ///
    /// `Ī' = R Ī Rᵀ + 2(p·w)1 − w pᵀ − p wᵀ + m(|p|² 1 − p pᵀ)` with `w = R h`.
    pub fn transformed(&self, f: &Frame<R>) -> MassMoments<R> {
        let w = rot(f, &self.h);
        let p = &f.p;
        let h = add3(&w, &scale3(&self.m, p));
        // R Ī Rᵀ
        let ri: [[R; 3]; 3] = core::array::from_fn(|a| {
            core::array::from_fn(|b| {
                f.r[a][0].clone() * self.i[0][b].clone()
                    + f.r[a][1].clone() * self.i[1][b].clone()
                    + f.r[a][2].clone() * self.i[2][b].clone()
            })
        });
        let pw = dot(p, &w);
        let pp = dot(p, p);
        // Symmetric: the upper triangle, mirrored.
        let upper: [[Option<R>; 3]; 3] = core::array::from_fn(|a| {
            core::array::from_fn(|b| {
                (a <= b).then(|| {
                    let rir = ri[a][0].clone() * f.r[b][0].clone()
                        + ri[a][1].clone() * f.r[b][1].clone()
                        + ri[a][2].clone() * f.r[b][2].clone();
                    let mut v = rir
                        - w[a].clone() * p[b].clone()
                        - p[a].clone() * w[b].clone()
                        - self.m.clone() * p[a].clone() * p[b].clone();
                    if a == b {
                        v = v + k::<R>(2.0) * pw.clone() + self.m.clone() * pp.clone();
                    }
                    v
                })
            })
        });
        let i = core::array::from_fn(|a| {
            core::array::from_fn(|b| {
                let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
                upper[lo][hi]
                    .clone()
                    .expect("the upper triangle is computed")
            })
        });
        MassMoments {
            m: self.m.clone(),
            h,
            i,
        }
    }

    /// The body whose parameters (in the order of `dhgen_description::parameters`) are all zero
    /// but parameter `p`, which is one.
    pub fn unit(p: usize) -> MassMoments<R> {
        MassMoments::of(|k| R::from_f64(if k == p { 1.0 } else { 0.0 }))
    }

    /// The body whose parameter k (in the order of `dhgen_description::parameters`) is `value(k)`.
    pub fn of(value: impl Fn(usize) -> R) -> MassMoments<R> {
        MassMoments {
            m: value(0),
            h: [value(1), value(2), value(3)],
            i: INERTIA_ENTRIES.map(|row| row.map(&value)),
        }
    }

    /// The ten parameters (`m, h, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`).
    pub fn parameters(&self) -> [R; 10] {
        let mut out: [R; 10] = core::array::from_fn(|_| R::from_f64(0.0));
        out[0] = self.m.clone();
        for a in 0..3 {
            out[1 + a] = self.h[a].clone();
            for b in a..3 {
                out[INERTIA_ENTRIES[a][b]] = self.i[a][b].clone();
            }
        }
        out
    }

    /// The wrench `(f, n)` (moment about the frame origin) that gives the body the motion
    /// `(ω, ω̇, a)` of its frame (`a` the origin's acceleration, gravity included):
    /// `f = m a + ω̇ × h + ω × (ω × h)`, `n = Ī ω̇ + ω × Ī ω + h × a`.
    pub fn wrench(&self, (w, wd, a): &(V3<R>, V3<R>, V3<R>)) -> (V3<R>, V3<R>) {
        let f = add3(
            &add3(&scale3(&self.m, a), &cross(wd, &self.h)),
            &cross(w, &cross(w, &self.h)),
        );
        let iw = mat_vec(&self.i, w);
        let nn = add3(
            &add3(&mat_vec(&self.i, wd), &cross(w, &iw)),
            &cross(&self.h, a),
        );
        (f, nn)
    }

    /// The momentum `I v` of the body moving with the motion `(ω, u)` (`u` the velocity of
    /// the origin): angular about the origin `Ī ω + h × u`, linear `m u + ω × h`.
    pub fn momentum(&self, (w, u): &(V3<R>, V3<R>)) -> (V3<R>, V3<R>) {
        (
            add3(&mat_vec(&self.i, w), &cross(&self.h, u)),
            add3(&scale3(&self.m, u), &cross(w, &self.h)),
        )
    }

    /// The block `P` of the body's Coriolis factor `B = [[P, 0], [−l×, 0]]` (Echeandia and
    /// Wensing's `½((v ×*) I − I (v ×) + (I v) ×̄)`) moving with the motion `(ω, u)`:
    /// `P = ½(İ_ωω − n̂)`, with `İ_ωω = ω̂Ī − Īω̂ + 2(h·u)1 − u hᵀ − h uᵀ` the ωω block of the
    /// rate of its spatial inertia and `(n, l)` its [`momentum`](Self::momentum). Computed
    /// as `(h·u)1 − u hᵀ − ω̂Σ`, `Σ = ½ tr(Ī)1 − Ī` the second moment of its mass: for a
    /// symmetric `Ī`, `ω̂Ī + Īω̂ = ((tr Ī)ω − Īω)^`, so the inertia's share
    /// `½(ω̂Ī − Īω̂ − (Īω)^)` is `ω̂Ī − ½(tr Ī)ω̂ = −ω̂Σ`, and the first moment's
    /// `½(2(h·u)1 − u hᵀ − h uᵀ − (h × u)^)` is `(h·u)1 − u hᵀ`, since `(h × u)^ = u hᵀ − h uᵀ`
    /// (Panda's C in joint frames: 1,790 operations from the first form, 1,602 from this).
    pub fn coriolis_factor(&self, (w, u): &(V3<R>, V3<R>)) -> [[R; 3]; 3] {
        let half_trace =
            k::<R>(0.5) * (self.i[0][0].clone() + self.i[1][1].clone() + self.i[2][2].clone());
        // Columns of −ω̂Σ: Σ_col c × ω.
        let sw: [V3<R>; 3] = core::array::from_fn(|c| {
            let column: V3<R> = core::array::from_fn(|r| {
                if r == c {
                    half_trace.clone() - self.i[r][c].clone()
                } else {
                    k::<R>(0.0) - self.i[r][c].clone()
                }
            });
            cross(&column, w)
        });
        let hu = dot(&self.h, u);
        core::array::from_fn(|r| {
            core::array::from_fn(|c| {
                let x = sw[c][r].clone() - u[r].clone() * self.h[c].clone();
                if r == c { x + hu.clone() } else { x }
            })
        })
    }

    /// Two bodies' moments about the same origin, combined.
    pub fn plus(&self, o: &MassMoments<R>) -> MassMoments<R> {
        MassMoments {
            m: self.m.clone() + o.m.clone(),
            h: add3(&self.h, &o.h),
            i: core::array::from_fn(|a| {
                core::array::from_fn(|b| self.i[a][b].clone() + o.i[a][b].clone())
            }),
        }
    }
}

/// The links' mass moments in their joint frames with the inertial parameters grouped
/// (Khalil and Kleinfinger, 1987), in spatial form: from the tip down, the part of link j's
/// moments that joint j can neither move nor load is moved onto link j − 1 (onto the fixed
/// base, where it acts on no joint, for j = 1). For a revolute joint (axis z through the
/// origin of its frame) that part is the mass, the first moment along the axis and
/// `Ī_yy (1 − z zᵀ)`: its momentum does not depend on q̇_j and it exerts no torque about the
/// axis. For a prismatic joint it is the rotational inertia `Ī` (no mass, so no force along
/// the axis, and the same at any displacement). τ, D(q), C(q, q̇), g(q), the kinetic energy
/// are unchanged (each moved part stays where it is, on the parent; link 1 keeps only what
/// loads joint 1, so per-link sums such as the centre of mass are not);
/// the links keep fewer non-zero parameters, so every recursion costs fewer operations
/// (PUMA 560: τ by Newton–Euler 427 → 345 operations, C by Echeandia and Wensing 1,388 → 936;
/// UR5 485 → 332 and 1,094 → 531; Panda 818 → 703 and 2,317 → 2,090). Empty for a
/// kinematics-only chain. (The runtime path keeps the links as described: the two check each
/// other.)
pub fn grouped(chain: ChainRef<'_>) -> Vec<MassMoments<f64>> {
    let n = chain.dof();
    if !chain.has_dynamics() {
        return Vec::new();
    }
    let mut b: Vec<MassMoments<f64>> = chain
        .bodies
        .iter()
        .filter_map(|b| b.inertial.map(|i| MassMoments::about_origin(&i)))
        .collect();
    for j in (0..n).rev() {
        let moved = match chain.bodies[j].joint {
            JointKind::Revolute => {
                let l = b[j].i[1][1];
                let moved = MassMoments {
                    m: b[j].m,
                    h: [0.0, 0.0, b[j].h[2]],
                    i: [[l, 0.0, 0.0], [0.0, l, 0.0], [0.0, 0.0, 0.0]],
                };
                b[j].m = 0.0;
                b[j].h[2] = 0.0;
                b[j].i[0][0] -= l;
                b[j].i[1][1] = 0.0;
                moved
            }
            JointKind::Prismatic => {
                let moved = MassMoments {
                    m: 0.0,
                    h: [0.0; 3],
                    i: b[j].i,
                };
                b[j].i = [[0.0; 3]; 3];
                moved
            }
        };
        if j > 0 {
            b[j - 1] = b[j - 1].plus(&moved.transformed(&chain.placements[j]));
        }
    }
    // Link 1 moves about (along) a fixed axis: of its own moments only the inertia about the
    // axis loads a revolute joint 1 (with the first moment across it, under gravity across
    // the axis), only the mass a prismatic one.
    let first = &mut b[0];
    match chain.bodies[0].joint {
        JointKind::Revolute => {
            let h = if chain.gravity_along_first_axis() {
                [0.0; 3]
            } else {
                [first.h[0], first.h[1], 0.0]
            };
            *first = MassMoments {
                m: 0.0,
                h,
                i: [[0.0; 3], [0.0; 3], [0.0, 0.0, first.i[2][2]]],
            };
        }
        JointKind::Prismatic => {
            *first = MassMoments {
                m: first.m,
                h: [0.0; 3],
                i: [[0.0; 3]; 3],
            };
        }
    }
    b
}

fn dot<R: Ring>(a: &V3<R>, b: &V3<R>) -> R {
    a[0].clone() * b[0].clone() + a[1].clone() * b[1].clone() + a[2].clone() * b[2].clone()
}

/// How a caller supplies each joint's variables in its own arithmetic.
pub trait JointSymbols<R> {
    /// `(cos θ_j, sin θ_j)` of revolute joint j (full angle, offset included).
    fn angle(&self, j: usize) -> (R, R);
    /// `d_j` of prismatic joint j (full displacement, offset included).
    fn length(&self, j: usize) -> R;
}

/// Joint values as numbers (`q`, offsets applied, the model's exact quarter turns), to run
/// the recursions in `f64`: what the generator evaluates at compile time (the base
/// parameters), and how tests check a recursion against the runtime path.
pub struct Numbers<'a>(pub ChainRef<'a>, pub &'a [f64]);

impl JointSymbols<f64> for Numbers<'_> {
    fn angle(&self, j: usize) -> (f64, f64) {
        match self.0.bodies[j].value(self.1[j]) {
            JointValue::Revolute { cos, sin } => (cos, sin),
            JointValue::Prismatic(_) => unreachable!("joint {j} is revolute"),
        }
    }
    fn length(&self, j: usize) -> f64 {
        self.1[j] + self.0.bodies[j].offset
    }
}

/// Each link as described (not [`grouped`]): its mass and first moment `m c` in its joint
/// frame; zeros for a kinematics-only chain. Grouping keeps the dynamics, not per-link sums
/// such as the centre of mass, which read these.
pub fn described<R: Ring>(
    chain: ChainRef<'_>,
) -> impl DoubleEndedIterator<Item = FirstMoment<R>> + ExactSizeIterator + '_ {
    chain.bodies.iter().map(|b| {
        b.inertial.map_or((k(0.0), [k(0.0), k(0.0), k(0.0)]), |i| {
            (k(i.mass), i.com.map(|c| k(i.mass * c)))
        })
    })
}

/// What grouping the links' parameters ([`grouped`]) takes off their potential energy: the
/// mass it moves onto the base, which no joint lifts. A constant, since grouping leaves g(q) =
/// ∂P/∂q unchanged; taken at q = 0 (offsets applied) as the links as described less the
/// grouped bodies.
pub fn grouping_shift(chain: ChainRef<'_>) -> f64 {
    let zeros = vec![0.0; chain.dof()];
    let at_zero = RingChain::<f64>::new(chain, &Numbers(chain, &zeros));
    let grouped = at_zero.bodies.iter().map(|b| (b.m, b.h));
    at_zero.potential_of(described(chain)) - at_zero.potential_of(grouped)
}

/// The chain of one robot in one arithmetic, in joint frames (see
/// [`ChainRef`]): the recursions run in the root frame, the frame
/// that `P_0` places in the world.
pub struct RingChain<'c, R> {
    /// The structure.
    pub chain: ChainRef<'c>,
    /// Joint kinds.
    pub kinds: Vec<JointKind>,
    /// `Z_k`: joint k's motion.
    pub motions: Vec<Frame<R>>,
    /// `T_k`: joint frame k in joint frame k − 1 (joint frame 0 in the root frame).
    pub t: Vec<Frame<R>>,
    /// Link frame k in joint frame k (constant).
    pub link_in_k: Vec<Frame<R>>,
    /// Each link's mass properties in its joint frame (when the model has dynamics).
    pub bodies: Vec<MassMoments<R>>,
    /// Gravity in the root frame.
    pub gravity: V3<R>,
}

impl<'c, R: Ring> RingChain<'c, R> {
    /// The chain of `chain` with joint variables `sym`.
    pub fn new(chain: ChainRef<'c>, sym: &impl JointSymbols<R>) -> RingChain<'c, R> {
        let motion = |j: usize| -> Frame<R> {
            match chain.bodies[j].joint {
                JointKind::Revolute => {
                    let (cos, sin) = sym.angle(j);
                    JointValue::Revolute { cos, sin }.motion()
                }
                JointKind::Prismatic => JointValue::Prismatic(sym.length(j)).motion(),
            }
        };
        let bodies = grouped(chain)
            .iter()
            .map(|b| MassMoments {
                m: k(b.m),
                h: b.h.map(k),
                i: b.i.map(|row| row.map(k)),
            })
            .collect();
        let motions: Vec<Frame<R>> = (0..chain.dof()).map(motion).collect();
        RingChain {
            chain,
            kinds: chain.bodies.iter().map(|b| b.joint).collect(),
            t: (0..chain.dof())
                .map(|j| chain.step(j, motions[j].clone()))
                .collect(),
            motions,
            link_in_k: chain.bodies.iter().map(|b| b.link.to_ring()).collect(),
            bodies,
            gravity: chain.gravity_in_root().map(k),
        }
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.kinds.len()
    }

    /// Composite bodies: `Ic_k` = links k..n, in K_k.
    pub fn composites(&self) -> Vec<MassMoments<R>> {
        let n = self.dof();
        let mut out: Vec<MassMoments<R>> = Vec::with_capacity(n);
        for j in (0..n).rev() {
            let own = self.bodies[j].clone();
            let c = match out.last() {
                Some(child) => own.plus(&child.transformed(&self.t[j + 1])),
                None => own,
            };
            out.push(c);
        }
        out.reverse();
        out
    }

    /// The joint-space inertia matrix by the composite-rigid-body algorithm (upper
    /// triangle computed, mirrored).
    pub fn mass_matrix(&self) -> Vec<Vec<R>> {
        let n = self.dof();
        let ic = self.composites();
        let mut d = vec![vec![k::<R>(0.0); n]; n];
        for j in 0..n {
            let b = &ic[j];
            // Wrench (n, f) that gives composite j a unit acceleration of joint j, in K_j.
            let (mut nn, mut f) = match self.kinds[j] {
                JointKind::Revolute => (
                    [b.i[0][2].clone(), b.i[1][2].clone(), b.i[2][2].clone()],
                    [-b.h[1].clone(), b.h[0].clone(), k(0.0)],
                ),
                JointKind::Prismatic => (
                    [b.h[1].clone(), -b.h[0].clone(), k(0.0)],
                    [k(0.0), k(0.0), b.m.clone()],
                ),
            };
            d[j][j] = self.component(j, &nn, &f);
            for i in (0..j).rev() {
                (nn, f) = force_into_parent(&self.t[i + 1], &(nn, f));
                let v = self.component(i, &nn, &f);
                d[i][j] = v.clone();
                d[j][i] = v;
            }
        }
        d
    }

    /// Joint i's axis `S_i` in its own frame, as a motion (angular, linear): the z axis.
    fn local_axis(&self, i: usize) -> Sv<R> {
        let (z, axis) = ([k(0.0), k(0.0), k(0.0)], [k(0.0), k(0.0), k(1.0)]);
        match self.kinds[i] {
            JointKind::Revolute => (axis, z),
            JointKind::Prismatic => (z, axis),
        }
    }

    fn component(&self, i: usize, n: &V3<R>, f: &V3<R>) -> R {
        match self.kinds[i] {
            JointKind::Revolute => n[2].clone(),
            JointKind::Prismatic => f[2].clone(),
        }
    }

    /// Gravity in each K_k.
    fn gravity_in_frames(&self) -> Vec<V3<R>> {
        let mut g = Vec::with_capacity(self.dof());
        let mut cur = self.gravity.clone();
        for t in &self.t {
            cur = rot_t(t, &cur);
            g.push(cur.clone());
        }
        g
    }

    /// The torques that hold the arm still against gravity, from the composite bodies.
    pub fn gravity_torques(&self) -> Vec<R> {
        let ic = self.composites();
        self.gravity_in_frames()
            .iter()
            .zip(&ic)
            .zip(&self.kinds)
            .map(|((g, b), kind)| match kind {
                JointKind::Revolute => -(cross(&b.h, g)[2].clone()),
                JointKind::Prismatic => -(b.m.clone() * g[2].clone()),
            })
            .collect()
    }

    /// The potential energy `P(q) = −Σ_k m_k gravity · c_k` of the links, centres of mass in
    /// the world frame (zero at the world origin): that of the grouped bodies (with whatever
    /// was added to them, such as a payload), plus the constant grouping takes off
    /// ([`grouping_shift`]).
    pub fn potential_energy(&self) -> R {
        let grouped = self.bodies.iter().map(|b| (b.m.clone(), b.h.clone()));
        self.potential_of(grouped) + k(grouping_shift(self.chain))
    }

    /// `−gravity · H` for bodies given as (mass, first moment) in their joint frames: their
    /// total mass and first moment about the root frame's origin, carried tip to base, then
    /// paired with gravity; the placement of the root frame in the world (`P_0`'s translation)
    /// adds `−M gravity · p_0`.
    fn potential_of(
        &self,
        bodies: impl DoubleEndedIterator<Item = FirstMoment<R>> + ExactSizeIterator,
    ) -> R {
        let (_, (mass, h)) = self.first_moments(bodies);
        let (g, p0) = (&self.chain.gravity, &self.chain.placements[0].p);
        let lift = g[0] * p0[0] + g[1] * p0[1] + g[2] * p0[2];
        -(dot(&self.gravity, &h) + mass * k(lift))
    }

    /// For bodies given as (mass, first moment) in their joint frames, carried tip to base:
    /// per joint k the mass of links k.. and their first moment about joint frame k's origin
    /// in its axes, and the total mass and first moment about the root frame's origin in its
    /// axes.
    pub fn first_moments(
        &self,
        bodies: impl DoubleEndedIterator<Item = FirstMoment<R>> + ExactSizeIterator,
    ) -> (Vec<FirstMoment<R>>, FirstMoment<R>) {
        let mut mass = k::<R>(0.0);
        let mut h: V3<R> = [k(0.0), k(0.0), k(0.0)];
        let mut per_joint = Vec::with_capacity(self.dof());
        for (t, (m, hj)) in self.t.iter().zip(bodies).rev() {
            // Links j.. in K_j, then seen from K_{j−1} (the root frame for j = 0).
            mass = mass + m;
            let own = add3(&h, &hj);
            h = add3(&rot(t, &own), &scale3(&mass, &t.p));
            per_joint.push((mass.clone(), own));
        }
        per_joint.reverse();
        (per_joint, (mass, h))
    }

    /// The velocity pass: each joint frame's angular velocity ω and its origin's linear
    /// velocity v, in local coordinates.
    pub fn velocities(&self, qd: &[R]) -> Vec<(V3<R>, V3<R>)> {
        let z = || k::<R>(0.0);
        let (mut w, mut v): (V3<R>, V3<R>) = ([z(), z(), z()], [z(), z(), z()]);
        let mut out = Vec::with_capacity(self.dof());
        for ((t, kind), rate) in self.t.iter().zip(&self.kinds).zip(qd) {
            // The parent's motion seen from frame j, then joint j's own rate.
            (w, v) = motion_into_child(t, &(w, v));
            let rate = [z(), z(), rate.clone()];
            match kind {
                JointKind::Revolute => w = add3(&w, &rate),
                JointKind::Prismatic => v = add3(&v, &rate),
            }
            out.push((w.clone(), v.clone()));
        }
        out
    }

    /// The kinetic energy `½ Σ_k (m v·v + 2 v·(ω × h) + ω·Ī ω)` of the links, from the
    /// velocities of the joint frames and each link's moments about its joint frame's origin.
    pub fn kinetic_energy(&self, qd: &[R]) -> R {
        let twice =
            self.velocities(qd)
                .iter()
                .zip(&self.bodies)
                .fold(k::<R>(0.0), |acc, ((w, v), b)| {
                    let iw = mat_vec(&b.i, w);
                    acc + b.m.clone() * dot(v, v)
                        + k::<R>(2.0) * dot(v, &cross(w, &b.h))
                        + dot(w, &iw)
                });
        k::<R>(0.5) * twice
    }

    /// The generalised momentum `D(q) q̇` (armature not included): each link's momentum
    /// about its joint frame's origin, linear `m v + ω × h` and angular `Ī ω + h × v`, summed
    /// tip to base by the inward pass.
    pub fn momentum(&self, qd: &[R]) -> Vec<R> {
        let momenta = self
            .velocities(qd)
            .into_iter()
            .zip(&self.bodies)
            .map(|(motion, b)| {
                let (angular, linear) = b.momentum(&motion);
                (linear, angular)
            })
            .collect();
        self.inward(momenta)
    }

    /// The outward pass of Newton-Euler: for each joint frame K_j, its angular velocity,
    /// angular acceleration and the linear acceleration of its origin (local coordinates),
    /// given the base's linear acceleration `a0`.
    pub fn outward(&self, qd: &[R], qdd: &[R], a0: V3<R>) -> Vec<(V3<R>, V3<R>, V3<R>)> {
        let z = || k::<R>(0.0);
        let mut w: V3<R> = [z(), z(), z()];
        let mut wd: V3<R> = [z(), z(), z()];
        let mut a = a0;
        let mut out = Vec::with_capacity(self.dof());
        for j in 0..self.dof() {
            let t = &self.t[j];
            let wr = rot_t(t, &w);
            let wdr = rot_t(t, &wd);
            // Acceleration of K_j's origin from the parent's motion.
            let ap = point_acceleration(&a, &wd, &w, &t.p);
            let mut aj = rot_t(t, &ap);
            let axis_rate = [z(), z(), qd[j].clone()];
            match self.kinds[j] {
                JointKind::Revolute => {
                    w = add3(&wr, &axis_rate);
                    wd = add3(
                        &add3(&wdr, &[z(), z(), qdd[j].clone()]),
                        &cross(&wr, &axis_rate),
                    );
                }
                JointKind::Prismatic => {
                    w = wr.clone();
                    wd = wdr;
                    let cor = cross(&wr, &axis_rate);
                    aj = add3(
                        &add3(&aj, &scale3(&k(2.0), &cor)),
                        &[z(), z(), qdd[j].clone()],
                    );
                }
            }
            a = aj;
            out.push((w.clone(), wd.clone(), a.clone()));
        }
        out
    }

    /// `J̇(q, q̇) q̇` of the point `tip` (given in the last joint frame K_n): the tool's
    /// acceleration `[v̇; ω̇]` at `q̈ = 0`, in the axes of DH frame 0.
    pub fn jdot_qdot(&self, qd: &[R], tip: &V3<R>) -> [R; 6] {
        let n = self.dof();
        let z = || k::<R>(0.0);
        let zeros: Vec<R> = (0..n).map(|_| z()).collect();
        let (w, wd, a) = self
            .outward(qd, &zeros, [z(), z(), z()])
            .pop()
            .expect("validated models have links");
        let at = point_acceleration(&a, &wd, &w, tip);
        let frame = self
            .joint_frames()
            .pop()
            .expect("validated models have links");
        let (v, o) = (rot(&frame, &at), rot(&frame, &wd));
        [
            v[0].clone(),
            v[1].clone(),
            v[2].clone(),
            o[0].clone(),
            o[1].clone(),
            o[2].clone(),
        ]
    }

    /// `J̇_b(q, q̇) q̇` of the frame `tip` (placed in the last joint frame): the rate of that
    /// frame's velocity in its own axes at `q̈ = 0`, `[Rᵀ a − ω_b × v_b; Rᵀ ω̇]`, where `a`
    /// and `ω̇` are the tip's classical and angular accelerations, `v_b` and `ω_b` its
    /// velocities in its own axes and `R` its rotation. Everything stays in the joint frames
    /// of the outward pass; no frame is carried to the root.
    pub fn body_jdot_qdot(&self, qd: &[R], tip: &Frame<R>) -> [R; 6] {
        let z = || k::<R>(0.0);
        let zeros: Vec<R> = (0..self.dof()).map(|_| z()).collect();
        let (w, wd, a) = self
            .outward(qd, &zeros, [z(), z(), z()])
            .pop()
            .expect("validated models have links");
        // The last joint frame's origin's velocity (its ω is the outward pass's, the same
        // nodes in a shared graph).
        let (_, v) = self
            .velocities(qd)
            .pop()
            .expect("validated models have links");
        let p = &tip.p;
        let a_tip = point_acceleration(&a, &wd, &w, p);
        let v_tip = add3(&v, &cross(&w, p));
        let (w_b, v_b) = (rot_t(tip, &w), rot_t(tip, &v_tip));
        let turning = cross(&w_b, &v_b);
        let linear = rot_t(tip, &a_tip);
        let angular = rot_t(tip, &wd);
        [
            linear[0].clone() - turning[0].clone(),
            linear[1].clone() - turning[1].clone(),
            linear[2].clone() - turning[2].clone(),
            angular[0].clone(),
            angular[1].clone(),
            angular[2].clone(),
        ]
    }

    /// Recursive Newton-Euler: `τ = D q̈ + C q̇ + g`.
    pub fn rnea(&self, qd: &[R], qdd: &[R]) -> Vec<R> {
        let forces = self
            .outward(qd, qdd, self.base_acceleration())
            .iter()
            .zip(&self.bodies)
            .map(|(motion, b)| b.wrench(motion))
            .collect();
        self.inward(forces)
    }

    /// The terms of Echeandia and Wensing's Coriolis algorithm at `qd`, in the coordinates
    /// `at`: every joint axis and body carried into that frame once, the velocities, the
    /// axes' rates, and the composites (inertias, the Coriolis factors' `P`, linear momenta) summed
    /// tip to base.
    fn spatial_terms(&self, at: Coordinates, qd: &[R]) -> SpatialTerms<R> {
        let n = self.dof();
        let z = || k::<R>(0.0);
        let (axes, bodies) = self.axes_and_bodies_in(at);
        let mut velocity: Sv<R> = ([z(), z(), z()], [z(), z(), z()]);
        let mut velocities = Vec::with_capacity(n);
        let mut rates = Vec::with_capacity(n);
        let mut momenta = Vec::with_capacity(n);
        let mut p: Vec<[[R; 3]; 3]> = Vec::with_capacity(n);
        for ((axis, b), rate) in axes.iter().zip(&bodies).zip(qd) {
            velocity = (
                add3(&velocity.0, &scale3(rate, &axis.0)),
                add3(&velocity.1, &scale3(rate, &axis.1)),
            );
            rates.push(motion_cross(&velocity, axis));
            p.push(b.coriolis_factor(&velocity));
            momenta.push(b.momentum(&velocity));
            velocities.push(velocity.clone());
        }
        // Composites, tip to base: inertias, Coriolis factors' P and linear momenta.
        let composite = summed_tip_to_base(&bodies);
        let mut linear: Vec<V3<R>> = momenta.iter().map(|m| m.1.clone()).collect();
        for i in (1..n).rev() {
            let pi = p[i].clone();
            p[i - 1] = core::array::from_fn(|r| {
                core::array::from_fn(|c| p[i - 1][r][c].clone() + pi[r][c].clone())
            });
            let li = linear[i].clone();
            linear[i - 1] = add3(&linear[i - 1], &li);
        }
        SpatialTerms {
            axes,
            velocities,
            rates,
            bodies,
            momenta,
            composite,
            p,
            linear,
        }
    }

    /// Every joint's spatial axis `S_j` (angular, linear at the origin) and every body, in
    /// the coordinates `at`: each carried there once.
    fn axes_and_bodies_in(&self, at: Coordinates) -> (Vec<Sv<R>>, Vec<MassMoments<R>>) {
        let z = || k::<R>(0.0);
        let frames = self.joint_frames_in(at);
        let axes = frames
            .iter()
            .zip(&self.kinds)
            .map(|(f, kind)| {
                let dir = [f.r[0][2].clone(), f.r[1][2].clone(), f.r[2][2].clone()];
                match kind {
                    JointKind::Revolute => (dir.clone(), cross(&f.p, &dir)),
                    JointKind::Prismatic => ([z(), z(), z()], dir),
                }
            })
            .collect();
        let bodies = self
            .bodies
            .iter()
            .zip(&frames)
            .map(|(b, f)| b.transformed(f))
            .collect();
        (axes, bodies)
    }

    /// The joint-space inertia matrix (armature not included) by the composite-rigid-body
    /// algorithm in the coordinates `at`, the runtime path's algorithm when `at` is the root:
    /// every axis and body carried into one frame, the composites summed tip to base, and
    /// `D_ij = S_i·(I^C_j S_j)` for `i ≤ j` (mirrored). A pair costs one dot product, where
    /// [`mass_matrix`](RingChain::mass_matrix) carries a wrench through a joint transform;
    /// carrying the bodies costs more per joint, so this wins on long chains without
    /// structure.
    pub fn mass_matrix_in(&self, at: Coordinates) -> Vec<Vec<R>> {
        let n = self.dof();
        let (axes, bodies) = self.axes_and_bodies_in(at);
        let composite = summed_tip_to_base(&bodies);
        let mut d = vec![vec![k::<R>(0.0); n]; n];
        for j in 0..n {
            let f = composite[j].momentum(&axes[j]);
            for i in 0..=j {
                let v = motion_dot(&axes[i], &f);
                d[i][j] = v.clone();
                d[j][i] = v;
            }
        }
        d
    }

    /// C(q, q̇) row by row, the Christoffel-consistent Coriolis matrix, by Echeandia and
    /// Wensing's O(n²) algorithm (the runtime path's, written here over any ring): in root-frame
    /// coordinates, each body's `B = ½(v×* I − I v× + (I v)×̄)`, held as the 3×3 `P = ½(İ_ωω −
    /// n̂)` ([`MassMoments::coriolis_factor`]) and the linear momentum `l`, summed tip to base with the inertias; then
    /// `C_kj = S_k·(I^C_j Ṡ_j + B^C_j S_j)` for `k ≤ j` and `C_jk = Ṡ_k·I^C_j S_j +
    /// S_k·B^C_jᵀ S_j` for `k < j`, with `Ṡ_j = v_j × S_j`. Every joint axis and body is
    /// carried into the root frame once, so a pair (k, j) costs a few dot products: the
    /// candidate without structure to exploit (general arms), where it costs no more
    /// operations than the runtime path does.
    pub fn coriolis_matrix(&self, qd: &[R]) -> Vec<Vec<R>> {
        self.coriolis_matrix_in(Coordinates::Root, qd)
    }

    /// [`coriolis_matrix`](RingChain::coriolis_matrix) computed in the coordinates `at`.
    pub fn coriolis_matrix_in(&self, at: Coordinates, qd: &[R]) -> Vec<Vec<R>> {
        let t = self.spatial_terms(at, qd);
        self.coriolis_from_terms(&t, &t.coriolis_vectors())
    }

    /// C(q, q̇) row by row by Echeandia and Wensing's O(n²) recursion in joint frames (as
    /// [`mass_matrix`](RingChain::mass_matrix) runs the composite-rigid-body algorithm):
    /// each body's velocity, momentum and Coriolis factor `B = [[P, 0], [−l×, 0]]` in its own
    /// frame, the composites `I^C_j` and `B^C_j` carried tip to base through the joint
    /// transforms (`l' = R l`, `P' = R P Rᵀ + (p·l') 1 − l' pᵀ`: `B` transforms as `X* B X⁻¹`
    /// and keeps its form), then per joint j the forces `I^C_j Ṡ_j + B^C_j S_j`, `I^C_j S_j`
    /// and the moment `B^C_jᵀ S_j` carried down the chain, where `S_k` is the local z axis and
    /// `Ṡ_k = v_k × S_k` has four non-zero entries: `C_kj = S_k·(I^C_j Ṡ_j + B^C_j S_j)` for
    /// `k ≤ j`, `C_jk = Ṡ_k·(I^C_j S_j) + S_k·(B^C_jᵀ S_j)` for `k < j`. In joint frames the
    /// axes and the bodies' constant inertias are sparse, which the root frame's
    /// [`coriolis_matrix`](RingChain::coriolis_matrix) gives up to avoid carrying vectors.
    pub fn coriolis_matrix_local(&self, qd: &[R]) -> Vec<Vec<R>> {
        self.coriolis_local(qd, None).0
    }

    /// [`inverse_dynamics_derivatives`](RingChain::inverse_dynamics_derivatives) (`[∂τ/∂q,
    /// C]`) in joint frames, beside [`coriolis_matrix_local`](RingChain::coriolis_matrix_local):
    /// the vectors `I^C_i S_i` and `B^C_iᵀ S_i` it carries down the chain for C are those
    /// `∂τ_i/∂q_j = (I^C_i S_i)·Ψ̈_j + 2 (B^C_iᵀ S_i)·Ψ̇_j` (`i ≥ j`) needs in frame j, and
    /// for `i < j` one more force, `S_j ×* F_j + I^C_j Ψ̈_j + 2 B^C_j Ψ̇_j`, is carried down
    /// from frame j. The accelerations start from the base's, upwards, instead of gravity.
    pub fn inverse_dynamics_derivatives_local(&self, qd: &[R], qdd: &[R]) -> [Vec<Vec<R>>; 2] {
        let (c, dq) = self.coriolis_local(qd, Some(qdd));
        [dq.expect("asked for with the accelerations"), c]
    }

    /// C(q, q̇) in joint frames, and with `qdd`, ∂τ/∂q too.
    fn coriolis_local(&self, qd: &[R], qdd: Option<&[R]>) -> (Vec<Vec<R>>, Option<Vec<Vec<R>>>) {
        let n = self.dof();
        let z = || k::<R>(0.0);
        // Into frame j from frame j − 1 (the root for j = 0), into frame i from frame i + 1.
        let outward = |j: usize, m: &Sv<R>| motion_into_child(&self.t[j], m);
        let carry = |i: usize, f: &Sv<R>| force_into_parent(&self.t[i + 1], f);
        // Outward: velocities, Ṡ_j, each body's P and l in its own frame, and with the
        // accelerations, Ψ̈_j and each body's force.
        let mut v: Sv<R> = ([z(), z(), z()], [z(), z(), z()]);
        let mut a: Sv<R> = ([z(), z(), z()], self.gravity.clone().map(|x| -x));
        let mut rates = Vec::with_capacity(n);
        let mut factors: Vec<([[R; 3]; 3], V3<R>)> = Vec::with_capacity(n);
        let mut psi_dd = Vec::with_capacity(n);
        let mut forces = Vec::with_capacity(n);
        for j in 0..n {
            let s = self.local_axis(j);
            let before = outward(j, &v);
            v = add_sv(&before, &scale_sv(&qd[j], &s));
            let rate = motion_cross(&v, &s);
            let b = &self.bodies[j];
            let momentum = b.momentum(&v);
            if let Some(qdd) = qdd {
                a = outward(j, &a);
                psi_dd.push(joint_acceleration(
                    &mut a, &before, &s, &rate, &qd[j], &qdd[j],
                ));
                forces.push(add_sv(&b.momentum(&a), &force_cross(&v, &momentum)));
            }
            rates.push(rate);
            factors.push((b.coriolis_factor(&v), momentum.1));
        }
        // Inward: composite inertias, Coriolis factors and forces, each in its joint's frame.
        let inertias = self.composites();
        for j in (0..n.saturating_sub(1)).rev() {
            let t = &self.t[j + 1];
            let (pc, lc) = factors[j + 1].clone();
            let l = rot(t, &lc);
            // R P Rᵀ, by columns of P Rᵀ: (P Rᵀ)_{:,c} = P (row c of R).
            let prt: [V3<R>; 3] = core::array::from_fn(|c| mat_vec(&pc, &t.r[c]));
            let pl = dot(&t.p, &l);
            let carried: [[R; 3]; 3] = core::array::from_fn(|r| {
                core::array::from_fn(|c| {
                    let rpr = t.r[r][0].clone() * prt[c][0].clone()
                        + t.r[r][1].clone() * prt[c][1].clone()
                        + t.r[r][2].clone() * prt[c][2].clone();
                    let mut x = rpr - l[r].clone() * t.p[c].clone();
                    if r == c {
                        x = x + pl.clone();
                    }
                    x
                })
            });
            let (p, own) = &mut factors[j];
            *p = core::array::from_fn(|r| {
                core::array::from_fn(|c| p[r][c].clone() + carried[r][c].clone())
            });
            *own = add3(own, &l);
            if qdd.is_some() {
                let fc = carry(j, &forces[j + 1]);
                forces[j] = add_sv(&forces[j], &fc);
            }
        }
        let mut c = vec![vec![z(); n]; n];
        let mut dq = qdd.map(|_| vec![vec![z(); n]; n]);
        let two = || k::<R>(2.0);
        for j in 0..n {
            let s = self.local_axis(j);
            let (p, l) = &factors[j];
            let ic = &inertias[j];
            // B^C S = (P ω, ω × l), the moment of Bᵀ S = Pᵀ ω + l × u; B^C Ψ̇ likewise.
            let b_times = |(w, _): &Sv<R>| (mat_vec(p, w), cross(w, l));
            let pt = mat_t_vec(p, &s.0);
            let mut f1 = add_sv(&ic.momentum(&rates[j]), &b_times(&s));
            let mut f2 = ic.momentum(&s);
            let mut f3 = add3(&pt, &cross(l, &s.1));
            // For ∂τ_i/∂q_j, i < j: y_j = S_j ×* F_j + I^C_j Ψ̈_j + 2 B^C_j Ψ̇_j.
            let mut y = dq.as_ref().map(|_| {
                let bp = b_times(&rates[j]);
                add_sv(
                    &add_sv(&force_cross(&s, &forces[j]), &ic.momentum(&psi_dd[j])),
                    &scale_sv(&two(), &bp),
                )
            });
            c[j][j] = motion_dot(&s, &f1);
            let derivative = |f2: &Sv<R>, f3: &V3<R>, m: usize| {
                motion_dot(&psi_dd[m], f2) + two() * dot(&rates[m].0, f3)
            };
            if let Some(dq) = &mut dq {
                dq[j][j] = derivative(&f2, &f3, j);
            }
            for kk in (0..j).rev() {
                f1 = carry(kk, &f1);
                f2 = carry(kk, &f2);
                f3 = rot(&self.t[kk + 1], &f3);
                let sk = self.local_axis(kk);
                c[kk][j] = motion_dot(&sk, &f1);
                c[j][kk] = motion_dot(&rates[kk], &f2) + dot(&sk.0, &f3);
                if let (Some(dq), Some(yv)) = (&mut dq, &mut y) {
                    *yv = carry(kk, yv);
                    dq[j][kk] = derivative(&f2, &f3, kk);
                    dq[kk][j] = motion_dot(&sk, yv);
                }
            }
        }
        (c, dq)
    }

    /// Every joint frame in the coordinates `at` (joint m moves about their z axis through
    /// their origin).
    pub fn joint_frames_in(&self, at: Coordinates) -> Vec<Frame<R>> {
        match at {
            Coordinates::Root => self.joint_frames(),
            Coordinates::Joint(m) => {
                let n = self.dof();
                let mut out = vec![Frame::identity(); n];
                for j in m + 1..n {
                    out[j] = out[j - 1].compose(&self.t[j]);
                }
                for j in (0..m).rev() {
                    out[j] = out[j + 1].compose(&self.t[j + 1].inverse());
                }
                out
            }
        }
    }

    /// Gravity in the coordinates `at`.
    fn gravity_in(&self, at: Coordinates) -> V3<R> {
        match at {
            Coordinates::Root => self.gravity.clone(),
            Coordinates::Joint(m) => self.gravity_in_frames().swap_remove(m),
        }
    }

    /// C from the terms, by the dot products with each joint's vectors
    /// ([`SpatialTerms::coriolis_vectors`]).
    fn coriolis_from_terms(
        &self,
        t: &SpatialTerms<R>,
        vectors: &[CoriolisVectors<R>],
    ) -> Vec<Vec<R>> {
        let n = self.dof();
        let mut c = vec![vec![k::<R>(0.0); n]; n];
        for (j, (s, (f1, f2, f3))) in t.axes.iter().zip(vectors).enumerate() {
            c[j][j] = motion_dot(s, f1);
            for (kk, (sk, rk)) in t.axes.iter().zip(&t.rates).take(j).enumerate() {
                c[kk][j] = motion_dot(sk, f1);
                c[j][kk] = motion_dot(rk, f2) + dot(&sk.0, f3);
            }
        }
        c
    }

    /// `∂τ/∂q` row by row (entry `[i][j]` = ∂τ_i/∂q_j, gravity included) and C(q, q̇), in
    /// closed form from the spatial terms C already has (the analytic derivatives of
    /// Carpentier and Mansard, RSS 2018, in the form of Singh, Russell and Wensing, 2022).
    ///
    /// Moving joint j turns every body after it rigidly about the screw `S_j`; in world
    /// coordinates, with `Ψ̇_j = Ṡ_j = v_j × S_j`, `Ψ̈_j = a_{j−1} × S_j + v_{j−1} × Ψ̇_j`,
    /// each body's force `f_k = I_k a_k + v_k ×* I_k v_k` (k ≥ j) changes by `S_j ×* f_k +
    /// I_k Ψ̈_j + 2 B_k Ψ̇_j`. Summed over the bodies a joint carries, and with `S_i·(S_j ×*
    /// F) = −(S_j × S_i)·F` cancelling the turn of the axis itself:
    /// - `∂τ_i/∂q_j = (I^C_i S_i)·Ψ̈_j + 2 (B^C_iᵀ S_i)·Ψ̇_j` for `i ≥ j`;
    /// - `∂τ_i/∂q_j = S_i·(S_j ×* F_j + I^C_j Ψ̈_j + 2 B^C_j Ψ̇_j)` for `i < j`,
    ///
    /// `F_j` the force joint j transmits. O(n) 6-vectors and O(n²) dot products.
    ///
    /// Every output is a dot product of spatial vectors, the same in any coordinates: `at`
    /// chooses them (the root frame, or a joint frame nearer the middle of the chain, where
    /// fewer joint variables separate the bodies from the coordinates).
    pub fn inverse_dynamics_derivatives(
        &self,
        at: Coordinates,
        qd: &[R],
        qdd: &[R],
    ) -> [Vec<Vec<R>>; 2] {
        let n = self.dof();
        let z = || k::<R>(0.0);
        let t = self.spatial_terms(at, qd);
        let vectors = t.coriolis_vectors();
        let c = self.coriolis_from_terms(&t, &vectors);
        // Accelerations (the base's upwards instead of gravity), Ψ̈, and the bodies' forces.
        let mut a: Sv<R> = ([z(), z(), z()], self.gravity_in(at).map(|x| -x));
        let mut v: Sv<R> = ([z(), z(), z()], [z(), z(), z()]);
        let mut psi_dd = Vec::with_capacity(n);
        let mut forces = Vec::with_capacity(n);
        for j in 0..n {
            let s = &t.axes[j];
            psi_dd.push(joint_acceleration(
                &mut a,
                &v,
                s,
                &t.rates[j],
                &qd[j],
                &qdd[j],
            ));
            v = t.velocities[j].clone();
            forces.push(add_sv(
                &t.bodies[j].momentum(&a),
                &force_cross(&v, &t.momenta[j]),
            ));
        }
        for j in (1..n).rev() {
            let fj = forces[j].clone();
            forces[j - 1] = add_sv(&forces[j - 1], &fj);
        }
        let mut dq = vec![vec![z(); n]; n];
        for j in 0..n {
            let s = &t.axes[j];
            let (pd, pdd) = (&t.rates[j], &psi_dd[j]);
            // i ≥ j: (I^C_i S_i)·Ψ̈_j + 2 (B^C_iᵀ S_i)·Ψ̇_j.
            for (row, (_, f2, f3)) in dq.iter_mut().zip(&vectors).skip(j) {
                row[j] = motion_dot(pdd, f2) + k::<R>(2.0) * dot(&pd.0, f3);
            }
            // i < j: S_i·y_j.
            let y = add_sv(
                &add_sv(&force_cross(s, &forces[j]), &t.composite[j].momentum(pdd)),
                &t.coriolis_action(j, pd, 2.0),
            );
            for (i, row) in dq.iter_mut().enumerate().take(j) {
                row[j] = motion_dot(&t.axes[i], &y);
            }
        }
        [dq, c]
    }

    /// The acceleration the outward pass starts from: the base accelerates upwards instead of
    /// gravity pulling down.
    fn base_acceleration(&self) -> V3<R> {
        self.gravity.clone().map(|x| -x)
    }

    /// The joint torque regressor's link columns, row by row: `out[i][10·k + p]` is the torque
    /// of joint i per unit of parameter p of link k (`dhgen_description::parameters`: `m, m·c, I`
    /// about link frame k's origin, in its axes), gravity included.
    ///
    /// Linear in each body's parameters: the outward pass once, then per link the ten unit
    /// wrenches in its joint frame (constants fold the unused terms away), turned from the
    /// joint frame's parameters to the link frame's by the constant map `MassMoments::
    /// transformed` is, and per joint i ≤ k the dot product with joint i's axis carried out
    /// to frame k as a motion vector (`ang·n + lin·f`): O(n²) 6-vectors, where transporting
    /// each of the 10·k wrenches back would cost ten times as much.
    pub fn regressor(&self, qd: &[R], qdd: &[R]) -> Vec<Vec<R>> {
        const P: usize = dhgen_description::parameters::BODY_PARAMETERS;
        let n = self.dof();
        let z = || k::<R>(0.0);
        let motion = self.outward(qd, qdd, self.base_acceleration());
        // Per link, the wrench (f, n) of each link-frame parameter, in the joint frame.
        let wrenches: Vec<Vec<(V3<R>, V3<R>)>> = (0..n)
            .map(|j| {
                let joint_frame: Vec<(V3<R>, V3<R>)> = (0..P)
                    .map(|l| MassMoments::<R>::unit(l).wrench(&motion[j]))
                    .collect();
                let link = &self.chain.bodies[j].link;
                (0..P)
                    .map(|p| {
                        let map = MassMoments::<f64>::unit(p).transformed(link).parameters();
                        let mut f = [z(), z(), z()];
                        let mut nn = [z(), z(), z()];
                        for (l, &c) in map.iter().enumerate() {
                            if c != 0.0 {
                                let (fl, nl) = &joint_frame[l];
                                f = add3(&f, &scale3(&k(c), fl));
                                nn = add3(&nn, &scale3(&k(c), nl));
                            }
                        }
                        (f, nn)
                    })
                    .collect()
            })
            .collect();
        let mut out = vec![vec![z(); P * n]; n];
        for (i, row) in out.iter_mut().enumerate() {
            // Joint i's axis as a motion vector (direction, and its moment arm), in frame k.
            let (mut ang, mut lin) = self.local_axis(i);
            for kk in i..n {
                if kk > i {
                    (ang, lin) = motion_into_child(&self.t[kk], &(ang, lin));
                }
                for (p, (f, nn)) in wrenches[kk].iter().enumerate() {
                    row[P * kk + p] = dot(&ang, nn) + dot(&lin, f);
                }
            }
        }
        out
    }

    /// The inward pass: wrenches (force, moment about the frame origin) given per joint frame,
    /// summed tip to base, each joint taking its component (the moment about its axis, or
    /// the force along it).
    fn inward(&self, wrenches: Vec<(V3<R>, V3<R>)>) -> Vec<R> {
        let n = self.dof();
        let mut out = vec![k::<R>(0.0); n];
        let mut carry: Option<(V3<R>, V3<R>)> = None;
        for (j, (mut f, mut nn)) in wrenches.into_iter().enumerate().rev() {
            if let Some((fc, nc)) = carry {
                let t = &self.t[j + 1];
                let fr = rot(t, &fc);
                nn = add3(&add3(&nn, &rot(t, &nc)), &cross(&t.p, &fr));
                f = add3(&f, &fr);
            }
            out[j] = self.component(j, &nn, &f);
            carry = Some((f, nn));
        }
        out
    }

    /// The joint frames, starting from `start` (the root frame's pose: the identity, or
    /// `P_0` for the world frame), by the model's one walk of the chain.
    pub fn joint_frames_from(&self, start: Frame<R>) -> Vec<Frame<R>> {
        let mut out = Vec::with_capacity(self.dof());
        self.chain.walk(
            start,
            |k| self.motions[k].clone(),
            |_, f| out.push(f.clone()),
        );
        out
    }

    /// Joint frames in the root frame: joint k moves about their z axis through their
    /// origin.
    pub fn joint_frames(&self) -> Vec<Frame<R>> {
        self.joint_frames_from(Frame::identity())
    }
}

/// A motion (angular, linear at the origin) in a parent frame seen in the child frame `t`
/// places in it: `(Rᵀ ω, Rᵀ (u + ω × p))`.
fn motion_into_child<R: Ring>(t: &Frame<R>, (w, u): &Sv<R>) -> Sv<R> {
    let lin = rot_t(t, &add3(u, &cross(w, &t.p)));
    (rot_t(t, w), lin)
}

/// A force (moment about the origin, force) in the child frame `t` places in its parent, seen
/// in the parent: `(R n + p × R f, R f)`.
fn force_into_parent<R: Ring>(t: &Frame<R>, (nn, f): &Sv<R>) -> Sv<R> {
    let f = rot(t, f);
    (add3(&rot(t, nn), &cross(&t.p, &f)), f)
}

/// One joint's step of the closed-form ∂τ/∂q's outward pass, all in one frame's coordinates:
/// from the parent's acceleration `a` and velocity `parent`, joint j's axis `s` and
/// `Ψ̇_j = v_j × S_j` (`rate`), returns `Ψ̈_j = a × S_j + v_parent × Ψ̇_j` and makes `a` the
/// body's, `a + S_j q̈_j + Ψ̇_j q̇_j`.
fn joint_acceleration<R: Ring>(
    a: &mut Sv<R>,
    parent: &Sv<R>,
    s: &Sv<R>,
    rate: &Sv<R>,
    qd: &R,
    qdd: &R,
) -> Sv<R> {
    let psi_dd = add_sv(&motion_cross(a, s), &motion_cross(parent, rate));
    *a = add_sv(&add_sv(a, &scale_sv(qdd, s)), &scale_sv(qd, rate));
    psi_dd
}

/// `M v`
fn mat_vec<R: Ring>(m: &[[R; 3]; 3], v: &V3<R>) -> V3<R> {
    core::array::from_fn(|i| {
        m[i][0].clone() * v[0].clone()
            + m[i][1].clone() * v[1].clone()
            + m[i][2].clone() * v[2].clone()
    })
}

/// `Mᵀ v`
fn mat_t_vec<R: Ring>(m: &[[R; 3]; 3], v: &V3<R>) -> V3<R> {
    core::array::from_fn(|i| {
        m[0][i].clone() * v[0].clone()
            + m[1][i].clone() * v[1].clone()
            + m[2][i].clone() * v[2].clone()
    })
}

/// The coordinates a spatial algorithm works in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Coordinates {
    /// The root frame (what `P_0` places in the world).
    Root,
    /// Joint frame m, moving with link m.
    Joint(usize),
}

/// A spatial vector in one frame's coordinates: `(angular, linear at the origin)` for a
/// motion, `(moment about the origin, force)` for a force.
type Sv<R> = (V3<R>, V3<R>);

fn add_sv<R: Ring>(a: &Sv<R>, b: &Sv<R>) -> Sv<R> {
    (add3(&a.0, &b.0), add3(&a.1, &b.1))
}

fn scale_sv<R: Ring>(s: &R, a: &Sv<R>) -> Sv<R> {
    (scale3(s, &a.0), scale3(s, &a.1))
}

/// `m × x` of motions: `(ω × a, ω × b + u × a)`.
fn motion_cross<R: Ring>((w, u): &Sv<R>, (a, b): &Sv<R>) -> Sv<R> {
    (cross(w, a), add3(&cross(w, b), &cross(u, a)))
}

/// `m ×* f` of a motion on a force: `(ω × n + u × f, ω × f)`.
fn force_cross<R: Ring>((w, u): &Sv<R>, (nn, f): &Sv<R>) -> Sv<R> {
    (add3(&cross(w, nn), &cross(u, f)), cross(w, f))
}

/// The composite bodies `Σ_{k ≥ j} bodies[k]` of bodies all in one frame's coordinates,
/// summed tip to base.
fn summed_tip_to_base<R: Ring>(bodies: &[MassMoments<R>]) -> Vec<MassMoments<R>> {
    let mut composite = bodies.to_vec();
    for i in (1..composite.len()).rev() {
        composite[i - 1] = composite[i - 1].plus(&composite[i]);
    }
    composite
}

/// A motion applied to a force: `ω·n + u·f`.
fn motion_dot<R: Ring>(m: &Sv<R>, f: &Sv<R>) -> R {
    dot(&m.0, &f.0) + dot(&m.1, &f.1)
}

/// What [`RingChain::coriolis_matrix`] and [`RingChain::inverse_dynamics_derivatives`] share,
/// per joint j, all in one frame's coordinates ([`Coordinates`]).
struct SpatialTerms<R> {
    /// `S_j`.
    axes: Vec<Sv<R>>,
    /// `v_j`, the velocity of body j.
    velocities: Vec<Sv<R>>,
    /// `Ṡ_j = v_j × S_j`.
    rates: Vec<Sv<R>>,
    /// Body j.
    bodies: Vec<MassMoments<R>>,
    /// `I_j v_j`.
    momenta: Vec<Sv<R>>,
    /// `I^C_j`, bodies j..n.
    composite: Vec<MassMoments<R>>,
    /// The composite Coriolis factor's `P^C_j = Σ_{k ≥ j} P_k`
    /// ([`MassMoments::coriolis_factor`]).
    p: Vec<[[R; 3]; 3]>,
    /// The composite linear momentum `l^C_j = Σ_{k ≥ j} l_k`.
    linear: Vec<V3<R>>,
}

/// Per joint j, `(I^C_j Ṡ_j + B^C_j S_j, I^C_j S_j, B^C_jᵀ S_j)` (the last's angular part;
/// its linear part is zero): what row and column j of C are dot products with.
type CoriolisVectors<R> = (Sv<R>, Sv<R>, V3<R>);

impl<R: Ring> SpatialTerms<R> {
    /// Every joint's [`CoriolisVectors`], computed once for C and for ∂τ/∂q.
    fn coriolis_vectors(&self) -> Vec<CoriolisVectors<R>> {
        self.axes
            .iter()
            .enumerate()
            .map(|(j, s)| {
                (
                    add_sv(
                        &self.composite[j].momentum(&self.rates[j]),
                        &self.coriolis_action(j, s, 1.0),
                    ),
                    self.composite[j].momentum(s),
                    self.coriolis_transpose_action(j, s),
                )
            })
            .collect()
    }

    /// `x B^C_j u` with `B = [[P, 0], [−l×, 0]]` (`P^C_j` and `l^C_j` the composites):
    /// `(x P ω, x ω × l)`.
    fn coriolis_action(&self, j: usize, (w, _): &Sv<R>, x: f64) -> Sv<R> {
        let x = k::<R>(x);
        (
            scale3(&x, &mat_vec(&self.p[j], w)),
            scale3(&x, &cross(w, &self.linear[j])),
        )
    }

    /// The angular part of `B^C_jᵀ s` (its linear part is zero): `Pᵀ ω + l × u`.
    fn coriolis_transpose_action(&self, j: usize, (w, u): &Sv<R>) -> V3<R> {
        add3(&mat_t_vec(&self.p[j], w), &cross(&self.linear[j], u))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `MassMoments::coriolis_factor` is `½(İ_ωω − n̂)` as defined (the ωω block of the rate
    /// `v ×* I − I v ×` of the spatial inertia, and the angular momentum `n = Īω + h × u`),
    /// written here entry by entry, for bodies with full inertia tensors (symmetric, not
    /// necessarily physical: the identity needs only symmetry) and arbitrary motions.
    #[test]
    fn coriolis_factor_is_half_the_inertia_rate_less_the_angular_momentum() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        let mut worst: f64 = 0.0;
        for _ in 0..200 {
            // A symmetric Ī from its six entries.
            let upper: [f64; 6] = core::array::from_fn(|_| next());
            let at = |a: usize, b: usize| match (a.min(b), a.max(b)) {
                (0, 0) => 0,
                (0, 1) => 1,
                (0, _) => 2,
                (1, 1) => 3,
                (1, _) => 4,
                _ => 5,
            };
            let i: [[f64; 3]; 3] =
                core::array::from_fn(|a| core::array::from_fn(|b| upper[at(a, b)]));
            let body = MassMoments {
                m: next().abs(),
                h: [next(), next(), next()],
                i,
            };
            let (w, u) = ([next(), next(), next()], [next(), next(), next()]);
            let p = body.coriolis_factor(&(w, u));
            let h = body.h;
            let skew = |a: [f64; 3]| [[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]];
            let product = |x: [[f64; 3]; 3], y: [[f64; 3]; 3]| -> [[f64; 3]; 3] {
                core::array::from_fn(|r| {
                    core::array::from_fn(|c| (0..3).map(|k| x[r][k] * y[k][c]).sum())
                })
            };
            let (wi, iw) = (product(skew(w), i), product(i, skew(w)));
            let hu: f64 = (0..3).map(|k| h[k] * u[k]).sum();
            let n: [f64; 3] = core::array::from_fn(|r| {
                (0..3).map(|k| i[r][k] * w[k]).sum::<f64>() + cross(&h, &u)[r]
            });
            let nhat = skew(n);
            for r in 0..3 {
                for c in 0..3 {
                    let rate = wi[r][c] - iw[r][c] + if r == c { 2.0 * hu } else { 0.0 }
                        - u[r] * h[c]
                        - h[r] * u[c];
                    let expected = 0.5 * (rate - nhat[r][c]);
                    worst = worst.max((p[r][c] - expected).abs());
                }
            }
        }
        assert!(worst < 1e-13, "largest difference {worst:e}");
    }
}
