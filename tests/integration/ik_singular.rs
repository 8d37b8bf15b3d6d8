//! Closed-form inverse kinematics **at** singular poses, not near them: random arms of every
//! family the solver takes (intersecting, parallel and skew shoulders with a revolute or
//! prismatic joint 3, the cylindrical arm, three parallel axes; oblique wrists; standard and
//! modified DH; random base and tool), each posed exactly at each singularity it has:
//! - the wrist (axes 4 and 6 aligned; for three parallel axes, axis 6 along them),
//! - the wrist centre (or, for three parallel axes, the point where axes 5 and 6 meet) on axis 1,
//! - the boundary of the workspace (the elbow stretched or folded, a skew shoulder's double
//!   root): every zero of the Jacobian's determinant along a line in q2 or q3,
//! - a prismatic joint 3 at either limit.
//!
//! The singular configurations are found from the arm's own forward kinematics and Jacobian
//! (the runtime path's, or a generated module's), never from the solver. At each, every solution
//! must reproduce the pose to `VERIFY_TOLERANCE`, and the generating configuration must be among
//! them — or, where the pose leaves a joint free, its representative in the solver's documented
//! choice (q4 = 0 at the wrist singularity, q6 = 0 for three parallel axes, q1 = 0 on axis 1) —
//! on the runtime path (`DecoupledIk::from_model`), `DecoupledIk::from_chain` and the generated
//! `ik()` alike.
//!
//! At a double root a joint is determined only to about the square root of the rounding
//! (`√ε ≈ 1.5e-8` rad): the generating joints are compared to 1e-6 there.

use crate::catalogue;
use dhgen::ik::{DecoupledIk, Solutions, VERIFY_TOLERANCE, pose_error};
use dhgen::model::{Convention, convert};
use dhgen::nalgebra::{DVector, Isometry3, Matrix6, SVector, Vector3};
use dhgen::rotation::wrap_angle;
use dhgen::{Arm, Robot};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::collections::BTreeMap;
use std::f64::consts::PI;

type Q = SVector<f64, 6>;

/// A solver under test: every solution of a pose.
type Solver<'a> = &'a dyn Fn(&Isometry3<f64>) -> Solutions;

/// The families of arms drawn here.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Family {
    Intersecting { prismatic3: bool },
    Parallel { prismatic3: bool },
    Skew { prismatic3: bool },
    Cylindrical,
    ThreeParallel,
}

/// What makes a pose singular.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
enum Singularity {
    /// Axes 4 and 6 aligned (spherical wrist), or axis 6 along axes 2–4 (three parallel).
    Wrist,
    /// The wrist centre (three parallel axes: where axes 5 and 6 meet) on axis 1.
    OnAxis1,
    /// The Jacobian's determinant vanishes on a line in joint 2 or 3: the workspace boundary.
    Boundary,
    /// A prismatic joint 3 at one of its limits.
    PrismaticLimit,
}

/// An arm under test: its forward kinematics and Jacobian, and the solvers to compare.
struct Subject<'a> {
    fk: &'a dyn Fn(&Q) -> Isometry3<f64>,
    jacobian: &'a dyn Fn(&Q) -> Matrix6<f64>,
    prismatic: [bool; 6],
    limits: [Option<[f64; 2]>; 6],
    three_parallel: bool,
    /// Each solver's answer for a pose; they must agree.
    solvers: &'a [Solver<'a>],
    /// The arm's description, for messages.
    description: String,
}

/// Tally of poses tried and branches lost, by family and singularity, with the first few
/// losses spelled out.
#[derive(Default)]
struct Tally {
    counts: BTreeMap<(String, Singularity), (usize, usize)>,
    examples: Vec<String>,
}

impl Tally {
    fn add(&mut self, family: &str, s: Singularity, lost: Option<String>) {
        let e = self.counts.entry((family.to_string(), s)).or_default();
        e.0 += 1;
        if let Some(what) = lost {
            e.1 += 1;
            if self.examples.len() < 3 {
                self.examples.push(format!("{family}, {s:?}: {what}"));
            }
        }
    }

    /// Prints the table (`--nocapture` shows it) and fails on any loss.
    fn assert_none_lost(&self) {
        let mut lost = 0;
        for ((family, s), (tried, l)) in &self.counts {
            println!("{family:<32} {s:<15?} {tried:>5} poses, {l:>3} lost");
            lost += l;
        }
        assert_eq!(
            lost,
            0,
            "branches lost at singular poses:\n{}",
            self.examples.join("\n\n")
        );
    }
}

fn joint_distance(prismatic: bool, a: f64, b: f64) -> f64 {
    if prismatic {
        (a - b).abs()
    } else {
        wrap_angle(a - b).abs()
    }
}

fn axis(j: &Matrix6<f64>, i: usize) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
    // Column i of [v; ω] at the tool point p: ω along the axis, v = ω × (p − o).
    let v = j.fixed_view::<3, 1>(0, i).into_owned();
    let w = j.fixed_view::<3, 1>(3, i).into_owned();
    (w, v, v.cross(&w))
}

/// The point nearest to both lines (o1 + t d1, o2 + s d2).
fn meeting_point(
    o1: Vector3<f64>,
    d1: Vector3<f64>,
    o2: Vector3<f64>,
    d2: Vector3<f64>,
) -> Vector3<f64> {
    let w0 = o1 - o2;
    let (a, b, c) = (d1.dot(&d1), d1.dot(&d2), d2.dot(&d2));
    let (d, e) = (d1.dot(&w0), d2.dot(&w0));
    let den = a * c - b * b;
    let t = (b * e - c * d) / den;
    let s = (a * e - b * d) / den;
    0.5 * (o1 + d1 * t + o2 + d2 * s)
}

impl Subject<'_> {
    /// The distance of the wrist centre (axes 4 and 5 meeting) or, for three parallel axes,
    /// of the point where axes 5 and 6 meet, from the axis of joint `k + 1`.
    fn centre_off_axis(&self, q: &Q, k: usize) -> f64 {
        let j = (self.jacobian)(q);
        let p = (self.fk)(q).translation.vector;
        let line = |i: usize| {
            let (w, _, v_cross_w) = axis(&j, i);
            let n = w.norm();
            // (p − o)⊥ = v × ω for a unit ω: a point on the axis is p − v × ω.
            (p - v_cross_w / (n * n), w / n)
        };
        let (a, b) = if self.three_parallel { (4, 5) } else { (3, 4) };
        let (oa, da) = line(a);
        let (ob, db) = line(b);
        let c = meeting_point(oa, da, ob, db);
        let (o1, d1) = line(k);
        let r = c - o1;
        (r - d1 * d1.dot(&r)).norm()
    }

    /// The cosine of the angle between axis 6 and axis 4 (axis 2 for three parallel axes).
    fn wrist_cosine(&self, q: &Q) -> f64 {
        let j = (self.jacobian)(q);
        let k = if self.three_parallel { 1 } else { 3 };
        let (a, _, _) = axis(&j, k);
        let (b, _, _) = axis(&j, 5);
        a.dot(&b) / (a.norm() * b.norm())
    }

    /// q5 values putting the wrist at its singularity, with the other joints of `q`: the
    /// cosine of the angle between the axes is `c0 + a cos q5 + b sin q5`, aligned at its
    /// extrema `±√(a² + b²) + c0 = ±1`.
    fn wrist_singular_q5(&self, q: &Q) -> Vec<f64> {
        let at = |x: f64| {
            let mut q = *q;
            q[4] = x;
            self.wrist_cosine(&q)
        };
        let (f0, f90, f180) = (at(0.0), at(PI / 2.0), at(PI));
        let c0 = 0.5 * (f0 + f180);
        let (a, b) = (0.5 * (f0 - f180), f90 - c0);
        let phi = b.atan2(a);
        [phi, phi + PI]
            .into_iter()
            .filter(|&x| (at(x).abs() - 1.0).abs() < 1e-12)
            .map(wrap_angle)
            .collect()
    }

    fn det(&self, q: &Q) -> f64 {
        (self.jacobian)(q).determinant()
    }

    /// Configurations where det J vanishes along joint `j`'s line through `q`: sign changes
    /// on a grid, bisected to adjacent floating-point values.
    fn det_zeros(&self, q: &Q, j: usize) -> Vec<Q> {
        let (lo, hi) = if self.prismatic[j] {
            let [lo, hi] = self.limits[j].unwrap_or([0.05, 0.8]);
            (lo, hi)
        } else {
            (-PI, PI)
        };
        let at = |x: f64| {
            let mut q = *q;
            q[j] = x;
            q
        };
        let n = 48;
        let xs: Vec<f64> = (0..=n)
            .map(|k| lo + (hi - lo) * k as f64 / n as f64)
            .collect();
        let mut out = Vec::new();
        for w in xs.windows(2) {
            let (mut a, mut b) = (w[0], w[1]);
            let (fa, fb) = (self.det(&at(a)), self.det(&at(b)));
            if fa == 0.0 || fa.signum() == fb.signum() {
                continue;
            }
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                if self.det(&at(m)).signum() == fa.signum() {
                    a = m;
                } else {
                    b = m;
                }
            }
            out.push(at(0.5 * (a + b)));
        }
        out
    }

    /// `q` with joints 2 and 3 moved (Newton's method, differences for the derivatives) so
    /// that the wrist centre lies on axis 1, if it can.
    fn onto_axis1(&self, q: &Q) -> Option<Q> {
        // The residual: the centre's offset from axis 1 in two fixed directions across it.
        let j0 = (self.jacobian)(q);
        let (w, _, _) = axis(&j0, 0);
        let w = w.normalize();
        let e1 = w
            .cross(&Vector3::x())
            .try_normalize(1e-6)
            .unwrap_or_else(|| w.cross(&Vector3::y()).normalize());
        let e2 = w.cross(&e1);
        let residual = |q: &Q| -> [f64; 2] {
            let j = (self.jacobian)(q);
            let p = (self.fk)(q).translation.vector;
            let line = |i: usize| {
                let (w, _, vxw) = axis(&j, i);
                let n = w.norm();
                (p - vxw / (n * n), w / n)
            };
            let (a, b) = if self.three_parallel { (4, 5) } else { (3, 4) };
            let (oa, da) = line(a);
            let (ob, db) = line(b);
            let r = meeting_point(oa, da, ob, db) - line(0).0;
            [r.dot(&e1), r.dot(&e2)]
        };
        let mut q = *q;
        for _ in 0..40 {
            let r = residual(&q);
            if r[0].hypot(r[1]) < 1e-15 {
                return Some(q);
            }
            let h = 1e-7;
            let mut jac = [[0.0; 2]; 2];
            for (c, k) in [1usize, 2].into_iter().enumerate() {
                let (mut qp, mut qm) = (q, q);
                qp[k] += h;
                qm[k] -= h;
                let (rp, rm) = (residual(&qp), residual(&qm));
                jac[0][c] = (rp[0] - rm[0]) / (2.0 * h);
                jac[1][c] = (rp[1] - rm[1]) / (2.0 * h);
            }
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det.abs() < 1e-12 {
                return None;
            }
            let d1 = (r[0] * jac[1][1] - r[1] * jac[0][1]) / det;
            let d2 = (jac[0][0] * r[1] - jac[1][0] * r[0]) / det;
            q[1] -= d1;
            q[2] -= d2;
            if !q.iter().all(|x| x.is_finite()) || q[1].abs() > 10.0 || q[2].abs() > 10.0 {
                return None;
            }
        }
        let r = residual(&q);
        (r[0].hypot(r[1]) < 1e-14).then_some(q)
    }

    /// Solves the pose of `q` with every solver; every solution must reproduce the pose, and
    /// `found` must hold for one of them. Returns what was lost, if the branch was.
    fn check(&self, q: &Q, within_limits: bool, found: &dyn Fn(&Q) -> bool) -> Option<String> {
        let pose = (self.fk)(q);
        let first = (self.solvers[0])(&pose);
        for solver in &self.solvers[1..] {
            assert_eq!(first, solver(&pose), "the solvers disagree at q = {q}");
        }
        for s in &first {
            let (dp, dr) = pose_error(&(self.fk)(s), &pose);
            assert!(
                dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE,
                "solution {s} misses the pose of {q} by {dp:e} m, {dr:e} rad"
            );
        }
        let inside = |s: &Q| {
            (0..6).all(|j| {
                self.limits[j].is_none_or(|[lo, hi]| s[j] >= lo - 1e-12 && s[j] <= hi + 1e-12)
            })
        };
        let kept = first
            .iter()
            .filter(|s| !within_limits || inside(s))
            .any(found);
        (!kept).then(|| {
            let solutions: Vec<_> = first.iter().map(|s| s.as_slice().to_vec()).collect();
            format!(
                "q = {:?} is not among {solutions:?}\n{}",
                q.as_slice(),
                self.description
            )
        })
    }

    fn near(&self, a: &Q, b: &Q, joints: &[usize], tol: f64) -> bool {
        joints
            .iter()
            .all(|&j| joint_distance(self.prismatic[j], a[j], b[j]) < tol)
    }

    /// Poses the arm at each of its singularities from `count` random configurations and
    /// tallies the branches lost.
    fn run(&self, name: &str, count: usize, rng: &mut StdRng, tally: &mut Tally) {
        let random_q = |rng: &mut StdRng| -> Q {
            SVector::from_fn(|j, _| match (self.prismatic[j], self.limits[j]) {
                (_, Some([lo, hi])) => rng.random_range(lo..hi),
                (true, None) => rng.random_range(0.1..0.5),
                (false, None) => rng.random_range(-PI..PI),
            })
        };
        let all = [0, 1, 2, 3, 4, 5];
        for _ in 0..count {
            let q0 = random_q(rng);
            // The wrist.
            for q5 in self.wrist_singular_q5(&q0) {
                let mut q = q0;
                q[4] = q5;
                let lost = if self.three_parallel {
                    // q6 = 0 where the arm reaches the pose with it, else nearer 0 than the
                    // generating q6 (which reaches it).
                    self.check(&q, false, &|s| {
                        self.near(s, &q, &[0, 4], 1e-6)
                            && (s[5].abs() < 1e-9 || s[5].abs() <= wrap_angle(q[5]).abs() + 1e-9)
                    })
                } else {
                    self.check(&q, false, &|s| {
                        self.near(s, &q, &[0, 1, 2, 4], 1e-6) && s[3].abs() < 1e-9
                    })
                };
                tally.add(name, Singularity::Wrist, lost);
            }
            // The wrist centre on axis 1.
            // q1 is free for the position: the solver takes the value nearest 0 with which the
            // wrist completes the pose, no further from 0 than the generating q1.
            if let Some(q) = self.onto_axis1(&q0) {
                let q1_rep = |s: &Q| s[0].abs() <= wrap_angle(q[0]).abs() + 1e-9;
                let lost = if self.three_parallel {
                    self.check(&q, false, &|s| q1_rep(s))
                } else if self.centre_off_axis(&q, 1) < 1e-9 {
                    // On axis 2 as well (the elbow folded onto the shoulder): q2 is free too.
                    self.check(&q, false, &|s| {
                        q1_rep(s)
                            && s[1].abs() <= wrap_angle(q[1]).abs() + 1e-9
                            && self.near(s, &q, &[2], 1e-6)
                    })
                } else {
                    self.check(&q, false, &|s| q1_rep(s) && self.near(s, &q, &[1, 2], 1e-6))
                };
                tally.add(name, Singularity::OnAxis1, lost);
            }
            // The boundary of the workspace, away from the wrist singularity.
            if (self.wrist_cosine(&q0).abs() - 1.0).abs() > 1e-3 {
                for j in [1, 2] {
                    for q in self.det_zeros(&q0, j) {
                        if self.centre_off_axis(&q, 0) < 1e-9 {
                            continue;
                        }
                        let lost = self.check(&q, false, &|s| self.near(s, &q, &all, 1e-6));
                        tally.add(name, Singularity::Boundary, lost);
                    }
                }
            }
            // A prismatic joint 3 at its limits.
            if let (true, Some(limits)) = (self.prismatic[2], self.limits[2]) {
                for x in limits {
                    let mut q = q0;
                    q[2] = x;
                    let lost = self.check(&q, true, &|s| self.near(s, &q, &all, 1e-7));
                    tally.add(name, Singularity::PrismaticLimit, lost);
                }
            }
        }
    }
}

/// A twist in (−π, π) at least 0.2 rad from 0 and ±π, or a quarter turn.
fn twist(rng: &mut StdRng) -> f64 {
    let x: f64 = if rng.random_bool(0.3) {
        PI / 2.0
    } else {
        rng.random_range(0.2..PI - 0.2)
    };
    if rng.random_bool(0.5) { x } else { -x }
}

fn row(joint: &str, a: f64, alpha: f64, d: f64, theta: f64, limits: Option<[f64; 2]>) -> String {
    let limits = limits.map_or(String::new(), |[lo, hi]| {
        format!("limits = [{lo:?}, {hi:?}]\n")
    });
    format!(
        "[[links]]\njoint = \"{joint}\"\na = {a:?}\nalpha = {alpha:?}\nd = {d:?}\ntheta = {theta:?}\n{limits}"
    )
}

fn pose_table(rng: &mut StdRng) -> String {
    let mut r = |s: f64| rng.random_range(-s..s);
    format!(
        "{{ xyz = [{:?}, {:?}, {:?}], rpy = [{:?}, {:?}, {:?}] }}",
        r(0.3),
        r(0.3),
        r(0.3),
        r(PI),
        r(PI),
        r(PI)
    )
}

/// An arm of `family` whose wrist can reach its singularity: the twists of axes 4–5 and 5–6
/// equal in size (α5 = ±α4), so that q5 can align axes 4 and 6 (or axis 6 with axes 2–4).
/// Offsets are zero or random, so that the wrist centre reaches axis 1 on some arms.
fn arm(family: Family, rng: &mut StdRng) -> String {
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    let mut s = StdRng::seed_from_u64(r(0.0, 1e18) as u64);
    let maybe_zero = |s: &mut StdRng, lo: f64, hi: f64| {
        if s.random_bool(0.4) {
            0.0
        } else {
            s.random_range(lo..hi)
        }
    };
    let alpha4 = twist(&mut s);
    let alpha5 = if s.random_bool(0.5) { alpha4 } else { -alpha4 };
    let p3 = Some([0.1, 0.5]);
    let theta = |s: &mut StdRng| s.random_range(-PI..PI);
    let rows = match family {
        Family::ThreeParallel => vec![
            row(
                "revolute",
                maybe_zero(&mut s, 0.0, 0.1),
                twist(&mut s),
                r(0.05, 0.2),
                theta(&mut s),
                None,
            ),
            row(
                "revolute",
                r(-0.6, -0.2),
                0.0,
                r(-0.1, 0.1),
                theta(&mut s),
                None,
            ),
            row(
                "revolute",
                r(-0.5, -0.2),
                0.0,
                r(-0.1, 0.1),
                theta(&mut s),
                None,
            ),
            row(
                "revolute",
                maybe_zero(&mut s, 0.0, 0.1),
                alpha4,
                r(0.05, 0.2),
                theta(&mut s),
                None,
            ),
            row("revolute", 0.0, alpha5, r(0.05, 0.15), theta(&mut s), None),
            row(
                "revolute",
                r(0.0, 0.05),
                r(-PI, PI),
                r(0.05, 0.15),
                theta(&mut s),
                None,
            ),
        ],
        Family::Cylindrical => vec![
            row(
                "revolute",
                maybe_zero(&mut s, 0.0, 0.2),
                if s.random_bool(0.5) { 0.0 } else { PI },
                r(0.2, 0.5),
                theta(&mut s),
                None,
            ),
            row(
                "prismatic",
                maybe_zero(&mut s, 0.0, 0.1),
                twist(&mut s),
                0.2,
                theta(&mut s),
                Some([0.0, 0.6]),
            ),
            row(
                "prismatic",
                maybe_zero(&mut s, 0.0, 0.1),
                twist(&mut s),
                0.2,
                theta(&mut s),
                Some([0.1, 0.8]),
            ),
            row(
                "revolute",
                0.0,
                alpha4,
                maybe_zero(&mut s, 0.05, 0.2),
                theta(&mut s),
                None,
            ),
            row("revolute", 0.0, alpha5, 0.0, theta(&mut s), None),
            row(
                "revolute",
                r(0.0, 0.1),
                r(-PI, PI),
                r(0.05, 0.2),
                theta(&mut s),
                None,
            ),
        ],
        Family::Intersecting { prismatic3 }
        | Family::Parallel { prismatic3 }
        | Family::Skew { prismatic3 } => {
            let (a1, alpha1) = match family {
                Family::Intersecting { .. } => (0.0, twist(&mut s)),
                Family::Parallel { .. } => (r(0.1, 0.4), if s.random_bool(0.5) { 0.0 } else { PI }),
                _ => (r(0.1, 0.4), twist(&mut s)),
            };
            let (joint3, limits3) = if prismatic3 {
                ("prismatic", p3)
            } else {
                ("revolute", None)
            };
            vec![
                row(
                    "revolute",
                    a1,
                    alpha1,
                    maybe_zero(&mut s, 0.2, 0.5),
                    theta(&mut s),
                    None,
                ),
                row(
                    "revolute",
                    r(0.2, 0.6),
                    twist(&mut s),
                    maybe_zero(&mut s, -0.2, 0.2),
                    theta(&mut s),
                    None,
                ),
                row(
                    joint3,
                    maybe_zero(&mut s, 0.0, 0.1),
                    twist(&mut s),
                    r(0.1, 0.3),
                    theta(&mut s),
                    limits3,
                ),
                row("revolute", 0.0, alpha4, r(0.2, 0.5), theta(&mut s), None),
                row("revolute", 0.0, alpha5, 0.0, theta(&mut s), None),
                row(
                    "revolute",
                    r(0.0, 0.1),
                    r(-PI, PI),
                    r(0.05, 0.2),
                    theta(&mut s),
                    None,
                ),
            ]
        }
    };
    let base = if s.random_bool(0.5) {
        format!("base = {}\n", pose_table(&mut s))
    } else {
        String::new()
    };
    let tool = if s.random_bool(0.5) {
        format!("tool = {}\n", pose_table(&mut s))
    } else {
        String::new()
    };
    format!(
        "name = \"singular\"\nconvention = \"standard\"\n{base}{tool}{}",
        rows.concat()
    )
}

fn subject_of_runtime(
    robot: &Robot,
    tally: &mut Tally,
    name: &str,
    count: usize,
    rng: &mut StdRng,
) {
    let model_ik = DecoupledIk::from_model(robot.model()).unwrap();
    let chain_ik = DecoupledIk::from_chain(robot.chain()).unwrap();
    let fk = |q: &Q| robot.fk(&DVector::from_column_slice(q.as_slice()));
    let jacobian = |q: &Q| -> Matrix6<f64> {
        robot
            .jacobian(&DVector::from_column_slice(q.as_slice()))
            .fixed_view::<6, 6>(0, 0)
            .into_owned()
    };
    let solve_model = |p: &Isometry3<f64>| model_ik.solve(p);
    let solve_chain = |p: &Isometry3<f64>| chain_ik.solve(p);
    let subject = Subject {
        fk: &fk,
        jacobian: &jacobian,
        prismatic: chain_ik.prismatic(),
        limits: core::array::from_fn(|j| robot.limits(j)),
        three_parallel: chain_ik.arm_kind() == dhgen::ik::ArmKind::ThreeParallel,
        solvers: &[&solve_model, &solve_chain],
        description: robot.model().to_toml(),
    };
    subject.run(name, count, rng, tally);
}

#[test]
fn every_family_at_every_singularity_keeps_the_generating_branch() {
    let mut rng = StdRng::seed_from_u64(20_261_208);
    let mut tally = Tally::default();
    let families = [
        Family::Intersecting { prismatic3: false },
        Family::Intersecting { prismatic3: true },
        Family::Parallel { prismatic3: false },
        Family::Parallel { prismatic3: true },
        Family::Skew { prismatic3: false },
        Family::Skew { prismatic3: true },
        Family::Cylindrical,
        Family::ThreeParallel,
    ];
    for family in families {
        for k in 0..12 {
            // Zero offsets can make a degenerate arm, which the solver refuses: draw again.
            let standard = loop {
                let robot = Robot::from_toml_str(&arm(family, &mut rng)).unwrap();
                if DecoupledIk::from_chain(robot.chain()).is_ok() {
                    break robot;
                }
            };
            // Every other arm as its modified-DH table (the same joint values, the same poses).
            let (robot, convention) = if k % 2 == 1 {
                let m = convert::to_dh(standard.model(), Convention::Modified).unwrap();
                (Robot::from_model(m), "modified")
            } else {
                (standard, "standard")
            };
            let name = format!("{family:?}").replace(" ", "") + " " + convention;
            subject_of_runtime(&robot, &mut tally, &name, 6, &mut rng);
        }
    }
    tally.assert_none_lost();
}

/// The generated `ik()` of every catalogue robot and fixture with a closed form, against
/// its constant `IK` and the runtime path built from the same description.
#[test]
fn generated_ik_at_singular_poses() {
    macro_rules! generated {
        ($($m:ident: $file:expr),* $(,)?) => {{
            let mut rng = StdRng::seed_from_u64(62);
            let mut tally = Tally::default();
            $({
                use catalogue::$m as m;
                let runtime = Robot::from_toml_file(format!("{}/{}", env!("CARGO_MANIFEST_DIR"), $file)).unwrap();
                let runtime_ik = DecoupledIk::from_model(runtime.model()).unwrap();
                let fk = |q: &Q| m::fk(q);
                let jacobian = |q: &Q| m::Robot.jacobian(q);
                let generated = |p: &Isometry3<f64>| m::ik(p);
                let constant = |p: &Isometry3<f64>| m::IK.solve(p);
                let from_runtime = |p: &Isometry3<f64>| runtime_ik.solve(p);
                let subject = Subject {
                    fk: &fk,
                    jacobian: &jacobian,
                    prismatic: m::IK.prismatic(),
                    limits: core::array::from_fn(|j| m::Robot.limits(j)),
                    three_parallel: m::IK.arm_kind() == dhgen::ik::ArmKind::ThreeParallel,
                    solvers: &[&generated, &constant, &from_runtime],
                    description: $file.to_string(),
                };
                subject.run(stringify!($m), 40, &mut rng, &mut tally);
            })*
            tally
        }};
    }
    let tally = generated!(
        puma560: "robots/puma560.toml",
        stanford: "robots/stanford.toml",
        ur5: "robots/ur5.toml",
        cylindrical: "robots/cylindrical.toml",
        craig: "tests/fixtures/craig.toml",
        elbow: "tests/fixtures/elbow.toml",
        offset_elbow: "tests/fixtures/offset_elbow.toml",
        puma_offsets: "tests/fixtures/puma_offsets.toml",
        shoulder_singular_elbow: "tests/fixtures/shoulder_singular_elbow.toml",
    );
    tally.assert_none_lost();
}
