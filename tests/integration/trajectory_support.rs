//! Checks shared by the trajectory property tests (`tests/integration/trajectory_*.rs`).

use dhgen::trajectory::{Profile, Setpoint};

/// Boundary conditions must hold to this fraction of the magnitudes involved.
pub const BOUNDARY_TOL: f64 = 1e-12;
/// Relative slack for limits (rounding of `α tb`, `Δ / (T - tb)` and the like).
pub const LIMIT_SLACK: f64 = 1e-9;

/// Asserts `|got - want| ≤ BOUNDARY_TOL * scale`.
#[track_caller]
pub fn assert_close(what: &str, got: f64, want: f64, scale: f64) {
    let tol = BOUNDARY_TOL * scale;
    assert!(
        (got - want).abs() <= tol,
        "{what}: got {got}, want {want} (difference {:e}, tolerance {tol:e})",
        (got - want).abs()
    );
}

/// Asserts a state equals `want` component-wise, each to BOUNDARY_TOL of its scale.
#[track_caller]
pub fn assert_state(what: &str, got: Setpoint, want: Setpoint, scales: Scales) {
    assert_close(&format!("{what}: q"), got.q, want.q, scales.q);
    assert_close(&format!("{what}: qd"), got.qd, want.qd, scales.qd);
    assert_close(&format!("{what}: qdd"), got.qdd, want.qdd, scales.qdd);
}

/// Magnitudes against which errors are measured, one per derivative.
#[derive(Clone, Copy, Debug)]
pub struct Scales {
    /// Position scale (e.g. max |q|).
    pub q: f64,
    /// Velocity scale.
    pub qd: f64,
    /// Acceleration scale.
    pub qdd: f64,
}

/// Bounds of the true derivatives on the whole interval, used to bound finite differences.
#[derive(Clone, Copy, Debug)]
pub struct Bounds {
    /// An upper bound of |q̇|.
    pub qd: f64,
    /// An upper bound of |q̈|.
    pub qdd: f64,
    /// An upper bound of |q⃛| if the acceleration is continuous on the whole interval, else None.
    pub jerk: Option<f64>,
}

/// Rounding error of one evaluation at magnitude `scale`, with headroom for a few operations.
/// Callers include `|t| · rate` in `scale`: a time is only known to its own rounding, so a
/// derivative `rate` turns it into that much error in the quantity.
fn rounding(scale: f64) -> f64 {
    64.0 * f64::EPSILON * scale
}

/// Checks that `p` is continuous in position and velocity at `t` (and in acceleration if
/// `bounds.jerk` is given) by comparing the two sides at `t ± eps`: a jump larger than what the
/// derivative bounds allow over `2 eps` (plus rounding) fails.
#[track_caller]
pub fn assert_continuous_at<P: Profile + ?Sized>(
    p: &P,
    t: f64,
    eps: f64,
    bounds: Bounds,
    scales: Scales,
) {
    // The actual distance between the probes: t ± eps is rounded to the grid of t.
    let (tl, tr) = (t - eps, t + eps);
    let span = tr - tl;
    let (l, m, r) = (p.eval(tl), p.eval(t), p.eval(tr));
    let dq_max = span * bounds.qd + rounding(scales.q + t.abs() * bounds.qd);
    let dv_max = span * bounds.qdd + rounding(scales.qd + t.abs() * bounds.qdd);
    assert!(
        (r.q - l.q).abs() <= dq_max,
        "position jumps at t = {t}: {} -> {} -> {}",
        l.q,
        m.q,
        r.q
    );
    assert!(
        (m.q - l.q).abs() <= dq_max && (r.q - m.q).abs() <= dq_max,
        "position at t = {t} off its sides"
    );
    assert!(
        (r.qd - l.qd).abs() <= dv_max,
        "velocity jumps at t = {t}: {} -> {} -> {}",
        l.qd,
        m.qd,
        r.qd
    );
    assert!(
        (m.qd - l.qd).abs() <= dv_max && (r.qd - m.qd).abs() <= dv_max,
        "velocity at t = {t} off its sides"
    );
    if let Some(jerk) = bounds.jerk {
        let da_max = span * jerk + rounding(scales.qdd + t.abs() * jerk);
        assert!(
            (r.qdd - l.qdd).abs() <= da_max,
            "acceleration jumps at t = {t}: {} -> {} -> {}",
            l.qdd,
            m.qdd,
            r.qdd
        );
    }
}

/// Checks that q̇ is the derivative of q (and q̈ of q̇ when the acceleration is continuous) at `t`
/// by central differences of half-width `h`, within the Taylor bound `h · max|next derivative|/2`
/// plus rounding. Valid across switching times, so `t` can be anywhere inside `[t0 + h, tf - h]`.
#[track_caller]
pub fn assert_derivatives_at<P: Profile + ?Sized>(
    p: &P,
    t: f64,
    h: f64,
    bounds: Bounds,
    scales: Scales,
) {
    // The actual probe times (t ± h rounded): the quotient and its Taylor bound use them.
    let (tl, tr) = (t - h, t + h);
    let (span, reach) = (tr - tl, (tr - t).max(t - tl));
    let (l, m, r) = (p.eval(tl), p.eval(t), p.eval(tr));
    let slope = (r.q - l.q) / span;
    let tol = 0.5 * reach * bounds.qdd + 2.0 * rounding(scales.q + t.abs() * bounds.qd) / span;
    assert!(
        (slope - m.qd).abs() <= tol,
        "q̇({t}) = {} but the difference quotient of q is {slope} (tol {tol:e})",
        m.qd
    );
    if let Some(jerk) = bounds.jerk {
        let slope = (r.qd - l.qd) / span;
        let tol = 0.5 * reach * jerk + 2.0 * rounding(scales.qd + t.abs() * bounds.qdd) / span;
        assert!(
            (slope - m.qdd).abs() <= tol,
            "q̈({t}) = {} but the difference quotient of q̇ is {slope} (tol {tol:e})",
            m.qdd
        );
    }
}

/// Asserts |q̇| ≤ vmax and |q̈| ≤ amax (each with LIMIT_SLACK) at `t`.
#[track_caller]
pub fn assert_within_limits<P: Profile + ?Sized>(p: &P, t: f64, vmax: f64, amax: f64) {
    let s = p.eval(t);
    assert!(
        s.qd.abs() <= vmax * (1.0 + LIMIT_SLACK),
        "|q̇({t})| = {} exceeds vmax = {vmax}",
        s.qd.abs()
    );
    assert!(
        s.qdd.abs() <= amax * (1.0 + LIMIT_SLACK),
        "|q̈({t})| = {} exceeds amax = {amax}",
        s.qdd.abs()
    );
}

/// `count` interior times spread over `[t0, tf]` (midpoints of equal cells, so never an end).
pub fn interior_times(t0: f64, tf: f64, count: usize) -> impl Iterator<Item = f64> {
    (0..count).map(move |i| t0 + (tf - t0) * ((i as f64 + 0.5) / count as f64))
}

/// Outside `[t0, tf]` the profile is at rest at the nearest end.
#[track_caller]
pub fn assert_held_outside<P: Profile + ?Sized>(p: &P, q0: f64, qf: f64) {
    let (t0, tf) = (p.start_time(), p.end_time());
    let span = (tf - t0).max(1.0);
    for t in [t0 - span, t0 - 1e-9 * span - 1e-9 * t0.abs()] {
        assert_eq!(p.eval(t), Setpoint::rest(q0), "before t0 = {t0} at t = {t}");
    }
    for t in [tf + 1e-9 * span + 1e-9 * tf.abs(), tf + span] {
        assert_eq!(p.eval(t), Setpoint::rest(qf), "after tf = {tf} at t = {t}");
    }
}
