//! Identifying a PUMA 560's inertial parameters from motion, as on a real robot.
//!
//! ```sh
//! cargo run --release --example identify [plot.svg]
//! cargo run --release --example identify -- --write-plant   # rewrite the plant's description
//! ```
//!
//! The "real" robot (the plant) is the PUMA 560 of `robots/puma560.toml` with every mass,
//! centre of mass and inertia changed by up to ±20 % (`examples/puma560_identify_plant.toml`,
//! written from a fixed seed by `--write-plant`; the example checks that it is current) and a
//! 2.5 kg payload in its hand, which the controller knows only roughly (it assumes 2 kg at 6 cm
//! instead of 8). A computed-torque controller on the *nominal* generated model drives the plant
//! along an exciting trajectory (a finite Fourier series per joint,
//! `dhgen::trajectory::FourierSeries`: three periods of 10 s, its phases those of 16 candidates
//! whose reference gives the stacked base regressor the smallest condition number, its bounds
//! checked against the joint limits) at 1 kHz, the plant integrated by RK4 on its generated
//! forward dynamics with the payload (`forward_dynamics_with_payload`).
//!
//! Identification: the generated base regressor `Y_b(q, q̇, q̈)` of the nominal structure
//! (`robot!(..., regressor)`: the geometry is known, the inertial parameters are not), folded
//! sample by sample into `dhgen::identification::LeastSquares` (least squares by Givens
//! rotations). First from the plant's exact states and torques (exact up to rounding); then as a
//! robot measures: positions from encoders of 2¹⁸ counts a turn and torques with 1 % noise,
//! nothing else. The last two periods (the first holds the start's transient) are averaged
//! (`dhgen::identification::PeriodAverage`), which halves the torque noise's variance and
//! estimates it from the periods' spread; each position's first 40 harmonics give q, q̇ and q̈;
//! each joint's rows are weighted by its estimated noise. Reported: the condition numbers, the
//! recovered base parameters against the plant's with the error in standard deviations least
//! squares predicts, the torque prediction error on a second trajectory, the identified arm as a
//! model (the estimate expanded over the nominal values, and the physically consistent estimate
//! of `Estimate::physical`, every link a body) with its accelerations against the plant's, and
//! the payload alone
//! (10 parameters) identified from 3 s of motion with the arm's own parameters known. The SVG
//! (`target/identify.svg` unless a path is given) shows measured and predicted torques on the
//! validation trajectory.

use dhgen::identification::{LeastSquares, PeriodAverage};
use dhgen::nalgebra::{DMatrix, DVector, SMatrix, SVector};
use dhgen::parameters::{Links, PhysicalConsistency};
use dhgen::payload::Payload;
use dhgen::trajectory::{FourierSeries, MultiProfile, Profile, Setpoint, Synchronized};
use dhgen::{Robot, RobotModel};
use plotters::prelude::*;
use std::error::Error;
use std::path::PathBuf;

dhgen::robot!(mod puma560 = "robots/puma560.toml", regressor);
dhgen::robot!(mod plant = "examples/puma560_identify_plant.toml");

/// Where the plant's description is checked in.
const PLANT: &str = "examples/puma560_identify_plant.toml";

type V6 = SVector<f64, 6>;

const DT: f64 = 1e-3;

/// A small deterministic generator (xorshift64*), uniform in [0, 1) and Gaussian.
struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn gaussian(&mut self) -> f64 {
        // Box–Muller.
        let (u, v) = (self.uniform().max(1e-300), self.uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

/// The real arm: every link's mass, centre of mass and inertia scaled by factors in
/// [0.8, 1.2] (a scaled inertia tensor stays physical).
fn perturbed(nominal: &RobotModel, rng: &mut Rng) -> RobotModel {
    let mut m = nominal.clone();
    let mut factor = || 0.8 + 0.4 * rng.uniform();
    for link in &mut m.links {
        let i = link
            .inertial
            .as_mut()
            .expect("the PUMA has mass properties");
        i.mass *= factor();
        let c = factor();
        i.com = i.com.map(|x| x * c);
        let s = factor();
        i.inertia = i.inertia.map(|row| row.map(|x| x * s));
    }
    m
}

/// A 10 cm cube of `mass` kg, `z` m beyond the flange.
fn cube(mass: f64, z: f64) -> dhgen::model::Inertial {
    let moment = mass * 0.1 * 0.1 / 6.0;
    dhgen::model::Inertial {
        mass,
        com: [0.0, 0.0, z],
        inertia: [[moment, 0.0, 0.0], [0.0, moment, 0.0], [0.0, 0.0, moment]],
    }
}

/// The payload: 2.5 kg, 8 cm beyond the flange.
fn payload() -> dhgen::model::Inertial {
    cube(2.5, 0.08)
}

/// A body's ten parameters, as `*_with_payload` take them.
fn parameters(body: &dhgen::model::Inertial) -> [f64; 10] {
    Payload::new(body.mass, body.com, body.inertia)
        .expect("a physical payload")
        .parameters()
}

/// The arm with the payload merged into its last link by the parallel-axis theorem, the
/// description form of what the plant's `forward_dynamics_with_payload` takes at run time: the
/// truth the identified parameters are compared with, computed independently of it.
fn with_payload(arm: &RobotModel) -> RobotModel {
    let mut m = arm.clone();
    let last = m.links.last_mut().unwrap();
    last.inertial = Some(last.inertial.unwrap().combined(&payload()));
    m
}

/// Whether the checked-in plant is the arm `expected` (its mass properties and structure).
fn plant_is_current(expected: &RobotModel) -> Result<bool, Box<dyn Error>> {
    let mut checked_in = RobotModel::from_toml_file(PLANT)?;
    checked_in.name.clone_from(&expected.name);
    checked_in.description.clone_from(&expected.description);
    Ok(&checked_in == expected)
}

/// Harmonics of the exciting trajectory.
const HARMONICS: usize = 4;

/// Its period, s, and the samples of one period.
const PERIOD: f64 = 10.0;
const PER_PERIOD: usize = 10_000;

/// Harmonics of the fit of each measured position: the motion's bandwidth (the plant, unlike
/// the reference, is not band-limited to the excitation's four: its tracking error has more).
const FIT: usize = 40;

/// The exciting trajectory (`dhgen::trajectory::FourierSeries`, Swevers et al.'s finite
/// Fourier series): per joint, four harmonics of a `period` about a mid pose, harmonic `l` of
/// amplitude 0.35/l rad and a phase from `seed`, run for `cycles` periods (a periodic
/// recording, whose torques hold the harmonics only once the start's transient has decayed).
fn exciting(period: f64, cycles: u32, seed: f64) -> Synchronized<FourierSeries<HARMONICS>, 6> {
    let mid = [0.0, 0.8, -1.0, 0.0, 0.4, 0.0];
    let omega = std::f64::consts::TAU / period;
    // Harmonic l's position p sin(l ω τ + φ) is (a_l sin − b_l cos)/(l ω) with
    // a_l = p l ω cos φ and b_l = −p l ω sin φ.
    let coefficient = |j: usize, l: usize, part: fn(f64) -> f64| {
        let (p, rate) = (0.35 / l as f64, l as f64 * omega);
        let phase = 1.7 * j as f64 + 0.9 * l as f64 + seed;
        p * rate * part(phase)
    };
    let a = core::array::from_fn(|j| core::array::from_fn(|l| coefficient(j, l + 1, f64::cos)));
    let b = core::array::from_fn(|j| core::array::from_fn(|l| -coefficient(j, l + 1, f64::sin)));
    Synchronized::fourier(0.0, period, cycles, &mid, &a, &b).expect("finite coefficients")
}

/// Six joints' setpoints as `(q, q̇, q̈)`.
fn split(s: &[Setpoint; 6]) -> (V6, V6, V6) {
    (
        V6::from_fn(|j, _| s[j].q),
        V6::from_fn(|j, _| s[j].qd),
        V6::from_fn(|j, _| s[j].qdd),
    )
}

/// One recorded sample.
struct Record {
    t: f64,
    q: V6,
    qd: V6,
    qdd: V6,
    tau: V6,
}

/// What the controller assumes the hand holds: 2 kg, 6 cm beyond the flange (the true payload
/// is 2.5 kg at 8 cm). Computed torque scales its gains by the model's inertia, and without
/// a payload the model's wrist (about 0.002 kg·m²) gets a stiffness of under 1 N·m/rad, which
/// the payload's weight turns over.
fn guessed_payload() -> dhgen::model::Inertial {
    cube(2.0, 0.06)
}

/// Computed torque on the nominal generated model with a guessed payload drives the generated
/// plant holding the true one; RK4 at 1 kHz.
fn record(reference: &Synchronized<FourierSeries<HARMONICS>, 6>) -> Vec<Record> {
    let held = parameters(&payload());
    let seconds = reference.duration();
    let (mut q, mut qd, _) = split(&reference.eval(0.0));
    let mut out = Vec::new();
    let steps = (seconds / DT).round() as usize;
    let guess = parameters(&guessed_payload());
    for i in 0..steps {
        let t = i as f64 * DT;
        let r = reference.eval(t);
        let qa: [f64; 6] = core::array::from_fn(|j| q[j]);
        let qda: [f64; 6] = core::array::from_fn(|j| qd[j]);
        let v: [f64; 6] = core::array::from_fn(|j| {
            r[j].qdd + 400.0 * (r[j].q - qa[j]) + 40.0 * (r[j].qd - qda[j])
        });
        let tau = puma560::inverse_dynamics_with_payload(&qa, &qda, &v, &guess);
        // The plant's D is positive definite everywhere: its accelerations always exist.
        let f = |q: &V6, qd: &V6| plant::forward_dynamics_with_payload(q, qd, &tau, &held);
        let qdd = f(&q, &qd).expect("the plant's D is positive definite");
        out.push(Record { t, q, qd, qdd, tau });
        (q, qd) = dhgen::simulate::rk4_step_with(f, &q, &qd, DT)
            .expect("the plant's D is positive definite");
    }
    out
}

/// Every `every`-th sample's regressor rows (`rows(q, q̇, q̈)`, `6 × C`) and torques,
/// stacked.
fn stack<const C: usize>(
    records: &[Record],
    every: usize,
    rows: impl Fn(&V6, &V6, &V6) -> SMatrix<f64, 6, C>,
) -> (DMatrix<f64>, DVector<f64>) {
    let picked: Vec<&Record> = records.iter().step_by(every).collect();
    let n = 6;
    let mut y = DMatrix::zeros(n * picked.len(), C);
    let mut tau = DVector::zeros(n * picked.len());
    for (s, r) in picked.iter().enumerate() {
        y.rows_mut(s * n, n).copy_from(&rows(&r.q, &r.qd, &r.qdd));
        tau.rows_mut(s * n, n).copy_from(&r.tau);
    }
    (y, tau)
}

fn main() -> Result<(), Box<dyn Error>> {
    let arg = std::env::args().nth(1);
    let nominal_model = RobotModel::from_toml_file("robots/puma560.toml")?;
    let mut rng = Rng(0x1D_E471_F1ED);
    let mut arm_model = perturbed(&nominal_model, &mut rng);
    arm_model.name = "puma560_identify_plant".into();
    arm_model.description = Some(
        "Unimation PUMA 560, every mass, centre of mass and inertia scaled by a factor in \
         [0.8, 1.2] (examples/identify.rs)"
            .into(),
    );
    if arg.as_deref() == Some("--write-plant") {
        let header = "# The plant of examples/identify.rs: robots/puma560.toml with every mass, centre of\n\
                      # mass and inertia scaled by factors in [0.8, 1.2] from a fixed seed. Written by\n\
                      # `cargo run --release --example identify -- --write-plant`.\n";
        std::fs::write(PLANT, format!("{header}{}", arm_model.to_toml()))?;
        println!("wrote {PLANT}");
        return Ok(());
    }
    if !plant_is_current(&arm_model)? {
        return Err(format!(
            "{PLANT} is not the perturbation of robots/puma560.toml this example makes: \
             rewrite it with `cargo run --release --example identify -- --write-plant`"
        )
        .into());
    }
    let svg = arg.map_or_else(|| PathBuf::from("target/identify.svg"), PathBuf::from);

    // The plant's parameters with the payload, reduced by the generated regrouping.
    let pi_plant: [f64; puma560::PARAMETERS] = Robot::from_model(with_payload(&arm_model))
        .parameters()
        .as_slice()
        .try_into()?;
    let truth = DVector::from_row_slice(&puma560::base_parameters(&pi_plant));
    println!(
        "PUMA 560: {} parameters, {} base parameters",
        puma560::PARAMETERS,
        puma560::BASE_PARAMETERS
    );
    let base_rows = |q: &V6, qd: &V6, qdd: &V6| puma560::base_regressor(q, qd, qdd);

    // The excitation's phases: of 16 candidates, those whose reference trajectory gives the
    // stacked base regressor the smallest condition number (the measure identification
    // experiments minimise), from the reference alone (its rows with zero torques: the
    // condition number does not read them), before anything is run.
    let condition = |seed: f64| -> Result<f64, Box<dyn Error>> {
        let reference = exciting(PERIOD, 1, seed);
        let mut fit = LeastSquares::new(puma560::BASE_PARAMETERS);
        for i in (0..PER_PERIOD).step_by(10) {
            let (q, qd, qdd) = split(&reference.eval(i as f64 * DT));
            fit.add(&base_rows(&q, &qd, &qdd), &V6::zeros())?;
        }
        Ok(fit.condition_number())
    };
    let mut candidates = Vec::new();
    for k in 0..16 {
        let seed = 0.7 * f64::from(k);
        candidates.push((condition(seed)?, seed));
    }
    let (best, seed) = candidates
        .iter()
        .copied()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .expect("16 candidates");
    let worst_candidate = candidates.iter().map(|c| c.0).fold(0.0, f64::max);
    println!(
        "excitation phases: of 16 candidates, condition number {best:.0} along the reference \
         (the worst {worst_candidate:.0})"
    );

    // The exciting trajectory's bounds, checked against the joint limits before it is run.
    let training = exciting(PERIOD, 3, seed);
    let mut worst = Setpoint::default();
    for (j, series) in training.joints().iter().enumerate() {
        let b = series.bounds();
        let (low, high) = (series.center() - b.q, series.center() + b.q);
        if let Some([min, max]) = nominal_model.links[j].limits
            && (low < min || high > max)
        {
            return Err(format!("joint {}: the excitation reaches [{low}, {high}]", j + 1).into());
        }
        worst = Setpoint::new(worst.q.max(b.q), worst.qd.max(b.qd), worst.qdd.max(b.qdd));
    }
    println!(
        "exciting trajectory: {HARMONICS} harmonics of a {PERIOD} s period, three times; \
         |q − q_mid| ≤ {:.2} rad, |q̇| ≤ {:.2} rad/s, |q̈| ≤ {:.2} rad/s² (worst joint), within the \
         joint limits",
        worst.q, worst.qd, worst.qdd
    );

    // The first period holds the transient of the start (the plant is not the model the
    // controller inverts); the last two repeat.
    let train = record(&training);
    let steady = &train[PER_PERIOD..];
    let picked: Vec<&Record> = steady.iter().step_by(10).collect();
    let mut exact = LeastSquares::new(puma560::BASE_PARAMETERS);
    for r in &picked {
        exact.add(&base_rows(&r.q, &r.qd, &r.qdd), &r.tau)?;
    }
    let estimate = exact.estimate()?;
    println!(
        "stacked base regressor: {} × {}, condition number {:.1}",
        estimate.rows,
        puma560::BASE_PARAMETERS,
        estimate.condition_number
    );
    let rel = |a: &DVector<f64>| {
        (a - &truth)
            .iter()
            .zip(truth.iter())
            .map(|(e, t)| e.abs() / t.abs().max(1e-3))
            .fold(0.0, f64::max)
    };
    println!(
        "without noise: worst error of the {} base parameters {:.1e} (relative, to max(|π_b|, 1e-3))",
        puma560::BASE_PARAMETERS,
        rel(&estimate.parameters)
    );

    // As measured: positions from encoders of 2¹⁸ counts a turn, torques with Gaussian noise of
    // 1 % of each joint's RMS torque; nothing else. The two periods averaged (the torque noise's
    // variance halved, and estimated from the periods' spread), each joint's position fitted by
    // its first FIT harmonics and differentiated: q, q̇ and q̈ without differentiating noise;
    // each joint's rows weighted by 1/σ̂ of its averaged torque (Gautier's weighted least
    // squares), whose estimate's covariance the noise predicts: (YᵀW²Y)⁻¹, the library's
    // covariance divided by the residual variance.
    let n = puma560::DOF;
    let rms: Vec<f64> = (0..n)
        .map(|j| {
            let sum: f64 = picked.iter().map(|r| r.tau[j] * r.tau[j]).sum();
            (sum / picked.len() as f64).sqrt()
        })
        .collect();
    let sigma: Vec<f64> = rms.iter().map(|r| 0.01 * r).collect();
    let count = std::f64::consts::TAU / f64::from(1u32 << 18);
    let measured: Vec<[f64; 12]> = steady
        .iter()
        .map(|r| {
            core::array::from_fn(|c| {
                if c < n {
                    (r.q[c] / count).round() * count
                } else {
                    r.tau[c - n] + sigma[c - n] * rng.gaussian()
                }
            })
        })
        .collect();
    let average = PeriodAverage::new(&measured, PER_PERIOD)?;
    let t0 = steady[0].t;
    let fits = (0..n)
        .map(|j| average.fourier_series::<FIT>(j, t0, PERIOD))
        .collect::<Result<Vec<_>, _>>()?;
    let noise = average.noise_variance().ok_or("two periods")?;
    let show = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.2e}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mean_noise = average.mean_noise_variance().ok_or("two periods")?;
    println!(
        "measured: encoder counts of {count:.2e} rad, torques with noise σ = [{}] N·m; two \
         periods averaged",
        show(&sigma)
    );
    println!(
        "  noise σ̂ from the periods' spread: torques [{}] N·m, positions {:.2e} rad at most \
         (the motion repeats, and so do its counts)",
        show(&(0..n).map(|j| noise[n + j].sqrt()).collect::<Vec<_>>()),
        (0..n).map(|j| noise[j].sqrt()).fold(0.0, f64::max),
    );
    // The fitted states against the plant's own, which the identification never reads.
    let mut worst_state = [0.0f64; 3];
    let mut size = [0.0f64; 3];
    for r in &steady[PER_PERIOD..] {
        for (j, fit) in fits.iter().enumerate() {
            let s = fit.eval(r.t);
            for (k, (x, y)) in [(s.q, r.q[j]), (s.qd, r.qd[j]), (s.qdd, r.qdd[j])]
                .into_iter()
                .enumerate()
            {
                worst_state[k] = worst_state[k].max((x - y).abs());
                size[k] = size[k].max(y.abs());
            }
        }
    }
    // The plant's q̈ at a sample is its acceleration as the new torque applies; the wrist's
    // changes within the 1 ms step, and the positions show the step's: their second
    // differences (q_{k+1} − 2 q_k + q_{k−1}) / Δt², unquantized, differ from it as much.
    let second_difference = steady[PER_PERIOD..]
        .windows(3)
        .flat_map(|w| {
            (0..n).map(move |j| (w[2].q[j] - 2.0 * w[1].q[j] + w[0].q[j]) / (DT * DT) - w[1].qdd[j])
        })
        .fold(0.0, |m: f64, e| m.max(e.abs()));
    println!(
        "  {FIT} harmonics of each position: worst error of q {:.1e} rad, q̇ {:.1e} rad/s, q̈ {:.1e} \
         rad/s² (of {:.2}, {:.2}, {:.2} at most) against the plant's own; the exact positions' \
         second differences differ from its q̈ by {second_difference:.1e}",
        worst_state[0], worst_state[1], worst_state[2], size[0], size[1], size[2]
    );
    let weights: Vec<f64> = (0..n).map(|j| 1.0 / mean_noise[n + j].sqrt()).collect();
    let mut weighted = LeastSquares::new(puma560::BASE_PARAMETERS);
    for k in (0..PER_PERIOD).step_by(5) {
        let t = t0 + k as f64 * DT;
        let (q, qd, qdd) = split(&core::array::from_fn(|j| fits[j].eval(t)));
        let torques = average.sample(k).ok_or("a sample of the period")?;
        let tau = V6::from_fn(|j, _| torques[n + j]);
        weighted.add_weighted(&base_rows(&q, &qd, &qdd), &tau, &weights)?;
    }
    let fit = weighted.estimate()?;
    let estimate = &fit.parameters;
    println!(
        "  base parameters from {} rows, condition number {:.1}, residual variance {:.3} (1 for \
         weights of the true noise):",
        fit.rows, fit.condition_number, fit.residual_variance
    );
    println!("  k   truth         estimate      error      predicted σ   |error|/σ");
    // The standard deviation least squares predicts for each base parameter.
    let predicted_sd: Vec<f64> = (0..puma560::BASE_PARAMETERS)
        .map(|k| (fit.covariance[(k, k)] / fit.residual_variance).sqrt())
        .collect();
    let mut worst_z = 0.0f64;
    for (k, &sd) in predicted_sd.iter().enumerate() {
        let z = (estimate[k] - truth[k]).abs() / sd;
        worst_z = worst_z.max(z);
        println!(
            "  {:<3} {:>12.6} {:>12.6} {:>10.2e} {:>12.2e} {:>8.2}",
            k + 1,
            truth[k],
            estimate[k],
            estimate[k] - truth[k],
            sd,
            z
        );
    }
    println!(
        "  largest |error| / predicted σ over {} parameters: {worst_z:.2}",
        puma560::BASE_PARAMETERS
    );

    // Validation on another trajectory.
    let validation = record(&exciting(8.0, 1, 2.3));
    let (yv, tv) = stack::<{ puma560::BASE_PARAMETERS }>(&validation, 1, base_rows);
    let predicted = &yv * estimate;
    let err = &predicted - &tv;
    for j in 0..n {
        let e: f64 = err.iter().skip(j).step_by(n).map(|x| x * x).sum::<f64>();
        let m: f64 = tv.iter().skip(j).step_by(n).map(|x| x * x).sum::<f64>();
        println!(
            "validation joint {}: torque prediction error {:.3} N·m RMS ({:.2} % of the torque)",
            j + 1,
            (e / (tv.len() / n) as f64).sqrt(),
            100.0 * (e / m).sqrt()
        );
    }

    // The identified arm as a model, two ways: the base parameters expanded over the nominal
    // values (what motion cannot tell kept as the description has it; the links need not
    // each be physical, `Links::AsGiven`), and the nearest expansion whose every link is
    // physical (`expand_physical`). Each is a `dhgen::Robot` whose forward dynamics are the
    // identified robot's. Their accelerations under the validation run's torques against the
    // plant's: the wrist's inertia is so small (no motors in this description) that errors
    // too small to show in the torques show in D⁻¹.
    let regrouping = Robot::from_model(nominal_model.clone()).base_parameters();
    let reference = dhgen::parameters::values(&nominal_model).ok_or("mass properties")?;
    let expanded = regrouping.expand(estimate.as_slice(), &reference)?;
    let over_nominal =
        dhgen::parameters::with_values(&nominal_model, expanded.as_slice(), Links::Physical);
    let model_of = |expanded: &[f64], links: Links| -> Result<Robot, Box<dyn Error>> {
        let model = dhgen::parameters::with_values(&nominal_model, expanded, links)?;
        Ok(Robot::from_model(model))
    };
    let physical = regrouping.expand_physical(estimate.as_slice(), &nominal_model);
    // Identification constrained to physical links: the fit's own estimate moved, in the
    // metric of its covariance, to the nearest base parameters a physical robot has.
    let consistent = fit.physical(&regrouping, &nominal_model);
    if let Ok(pi) = &consistent {
        let base = regrouping.reduce(pi);
        let worst = predicted_sd
            .iter()
            .enumerate()
            .map(|(k, sd)| (base[k] - truth[k]).abs() / sd)
            .fold(0.0, f64::max);
        println!(
            "physically consistent estimate: largest |error| / predicted σ {worst:.2} (unconstrained \
             {worst_z:.2})"
        );
    }
    let mut models = vec![(
        match &over_nominal {
            Ok(_) => "over the nominal values (every link physical)".to_string(),
            Err(e) => format!("over the nominal values (not every link physical: {e})"),
        },
        model_of(expanded.as_slice(), Links::AsGiven)?,
    )];
    match &physical {
        Ok(pi) => models.push((
            "the nearest with every link physical".to_string(),
            model_of(pi.as_slice(), Links::Physical)?,
        )),
        Err(e) => println!("no expansion of the estimate has physical links: {e}"),
    }
    match consistent {
        Ok(pi) => models.push((
            "physically consistent estimate".to_string(),
            model_of(pi.as_slice(), Links::Physical)?,
        )),
        Err(e) => println!("no physically consistent estimate: {e}"),
    }
    // The same from the plant's own base parameters: its accelerations exactly.
    models.push((
        "from the plant's own base parameters".to_string(),
        model_of(
            regrouping.expand(truth.as_slice(), &reference)?.as_slice(),
            Links::AsGiven,
        )?,
    ));
    let mut size = [0.0f64; 6];
    for r in &validation {
        for (s, x) in size.iter_mut().zip(r.qdd.iter()) {
            *s += x * x;
        }
    }
    println!(
        "the identified arm as a model, forward dynamics on the validation run, RMS error of q̈ \
         joint by joint:"
    );
    for (what, robot) in &models {
        let mut error = [0.0f64; 6];
        for r in &validation {
            let qdd = robot
                .forward_dynamics(&r.q, &r.qd, &r.tau)
                .ok_or("the identified D(q) is singular")?;
            for j in 0..n {
                error[j] += (qdd[j] - r.qdd[j]).powi(2);
            }
        }
        let relative: Vec<String> = (0..n)
            .map(|j| format!("{:.1e}", (error[j] / size[j]).sqrt()))
            .collect();
        println!("  {what}: [{}]", relative.join(", "));
    }

    // The payload alone, the arm's own parameters known: τ − Y π_arm = Y_6 π_payload with Y_6
    // the last link's ten columns (the payload's parameters in link 6's frame, the tool's).
    let own = DVector::from_vec(
        dhgen::parameters::values(&arm_model).ok_or("the arm has mass properties")?,
    );
    let short = record(&exciting(3.0, 1, 4.1));
    let first = 10 * (n - 1);
    let mut alone = LeastSquares::new(10);
    for r in short.iter().step_by(5) {
        let y = puma560::regressor(&r.q, &r.qd, &r.qdd);
        let residual = r.tau - y * &own;
        alone.add(&y.fixed_columns::<10>(first), &residual)?;
    }
    let payload = alone.estimate()?.parameters;
    let m = payload[0];
    println!(
        "payload from 3 s of motion: mass {:.6} kg (true 2.5), centre of mass [{:.6}, {:.6}, {:.6}] m (true [0, 0, 0.08])",
        m,
        payload[1] / m,
        payload[2] / m,
        payload[3] / m
    );

    plot(&svg, &validation, &predicted)?;
    println!("wrote {}", svg.display());
    Ok(())
}

/// Measured and predicted torques of joints 1–3 on the validation trajectory.
fn plot(
    path: &PathBuf,
    records: &[Record],
    predicted: &DVector<f64>,
) -> Result<(), Box<dyn Error>> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let root = SVGBackend::new(path, (1000, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "PUMA 560, validation trajectory: measured torque (solid) and predicted from identified base parameters (dashed)",
        ("sans-serif", 16),
    )?;
    let panels = root.split_evenly((3, 1));
    let tf = records.last().map_or(1.0, |r| r.t);
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
    ];
    for (j, panel) in panels.iter().enumerate() {
        let lo = records
            .iter()
            .map(|r| r.tau[j])
            .fold(f64::INFINITY, f64::min);
        let hi = records
            .iter()
            .map(|r| r.tau[j])
            .fold(f64::NEG_INFINITY, f64::max);
        let pad = 0.1 * (hi - lo).max(1e-3);
        let mut chart = ChartBuilder::on(panel)
            .caption(format!("joint {}", j + 1), ("sans-serif", 14))
            .margin(8)
            .x_label_area_size(28)
            .y_label_area_size(50)
            .build_cartesian_2d(0.0..tf, (lo - pad)..(hi + pad))?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc("τ [N·m]")
            .draw()?;
        chart.draw_series(LineSeries::new(
            records.iter().map(|r| (r.t, r.tau[j])),
            colors[j].stroke_width(2),
        ))?;
        let n = records[0].q.len();
        chart.draw_series(DashedLineSeries::new(
            records
                .iter()
                .enumerate()
                .map(|(s, r)| (r.t, predicted[s * n + j])),
            6,
            4,
            BLACK.stroke_width(1),
        ))?;
    }
    root.present()?;
    Ok(())
}
