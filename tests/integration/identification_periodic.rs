//! Periodic recordings (`dhgen::identification::PeriodAverage`): a band-limited periodic signal
//! is recovered exactly with its derivatives, the fit of L harmonics is the projection (the
//! harmonics above L leave it alone), averaging divides the noise variance by the periods and
//! the spread between periods estimates it, even on large offsets, and bad recordings are
//! refused, naming what and where. End to end: a PUMA 560's base parameters from its positions
//! and torques alone along a periodic excitation.

use super::catalogue::puma560_derivatives as puma;
use dhgen::identification::{IdentificationError, LeastSquares, PeriodAverage};
use dhgen::trajectory::{FourierSeries, Profile, Setpoint, Synchronized, TrajectoryError};
use dhgen_description::random::Stream;
use proptest::prelude::*;
use std::f64::consts::TAU;

/// `periods` periods of `n` samples of `f`, one channel.
fn sampled<const L: usize>(f: &FourierSeries<L>, n: usize, periods: usize) -> Vec<[f64; 1]> {
    let (t0, period) = (f.start_time(), f.period());
    (0..n * periods)
        .map(|i| [f.eval(t0 + i as f64 * period / n as f64).q])
        .collect()
}

/// Each coefficient's scale: |a_l| + |b_l| summed, or 1.
fn scale<const L: usize>(f: &FourierSeries<L>) -> f64 {
    let (a, b) = f.coefficients();
    a.iter().chain(b).map(|x| x.abs()).sum::<f64>().max(1.0)
}

fn series<const L: usize>() -> impl Strategy<Value = FourierSeries<L>> {
    (
        -50.0..50.0f64,
        0.1..20.0f64,
        -3.0..3.0f64,
        prop::array::uniform::<_, L>(-2.0..2.0f64),
        prop::array::uniform::<_, L>(-2.0..2.0f64),
    )
        .prop_map(|(t0, period, q0, a, b)| {
            // Four periods: the recordings take up to three.
            FourierSeries::new(t0, period, 4, q0, a, b).expect("valid input")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// A signal of at most L harmonics, sampled `n > 2L` times a period over whole periods, is
    /// its own fit: the same centre and coefficients, the same position, velocity and
    /// acceleration at every time of the recording.
    #[test]
    fn a_band_limited_signal_is_recovered_with_its_derivatives(
        f in series::<3>(),
        n in 7usize..120,
        periods in 1usize..4,
        at in 0.0..1.0f64,
    ) {
        let recording = sampled(&f, n, periods);
        let average = PeriodAverage::new(&recording, n).unwrap();
        prop_assert_eq!(average.periods(), periods);
        let fit = average.fourier_series::<3>(0, f.start_time(), f.period()).unwrap();
        let s = scale(&f);
        let (omega, amplitude) = (TAU / f.period(), s * (TAU / f.period()).max(1.0));
        prop_assert!((fit.center() - f.center()).abs() < 1e-12 * (s / omega + f.center().abs()));
        let ((a, b), (fa, fb)) = (f.coefficients(), fit.coefficients());
        for l in 0..3 {
            prop_assert!((a[l] - fa[l]).abs() < 1e-11 * s, "a_{}: {} against {}", l + 1, fa[l], a[l]);
            prop_assert!((b[l] - fb[l]).abs() < 1e-11 * s, "b_{}: {} against {}", l + 1, fb[l], b[l]);
        }
        let t = f.start_time() + at * periods as f64 * f.period();
        let (x, y) = (f.eval(t), fit.eval(t));
        prop_assert!((x.q - y.q).abs() < 1e-11 * (s / omega + f.center().abs()));
        prop_assert!((x.qd - y.qd).abs() < 1e-11 * s);
        prop_assert!((x.qdd - y.qdd).abs() < 1e-11 * amplitude * 3.0);
        // A single period has no spread to estimate noise from; more have none to find.
        match average.noise_variance() {
            None => prop_assert_eq!(periods, 1),
            Some(v) => prop_assert!(v[0] < 1e-24 * (s / omega + f.center().abs()).powi(2)),
        }
    }

    /// Harmonics above L (below n/2) are orthogonal to the first L on the samples: fitting L
    /// harmonics to a signal of six gives the first L of them.
    #[test]
    fn the_fit_of_l_harmonics_is_the_projection(f in series::<6>(), n in 13usize..100) {
        let recording = sampled(&f, n, 1);
        let average = PeriodAverage::new(&recording, n).unwrap();
        let fit = average.fourier_series::<2>(0, f.start_time(), f.period()).unwrap();
        let s = scale(&f);
        let ((a, b), (fa, fb)) = (f.coefficients(), fit.coefficients());
        for l in 0..2 {
            prop_assert!((a[l] - fa[l]).abs() < 1e-11 * s && (b[l] - fb[l]).abs() < 1e-11 * s);
        }
        prop_assert!((fit.center() - f.center()).abs() < 1e-11 * (s * f.period() + f.center().abs()));
    }
}

/// Gaussian noise of σ = 1e-3 and 4e-3 on two channels about a motion offset by 10⁶ (which
/// sums of squares would cancel to nothing): the spread between periods estimates σ² within
/// its sampling error (σ̂² N (M − 1) / σ² is χ² with N (M − 1) degrees of freedom: relative
/// standard deviation √(2 / (N (M − 1)))), and the averages are off the motion by σ² / M.
#[test]
fn averaging_divides_the_noise_by_the_periods_and_its_spread_estimates_it() {
    let (n, m) = (2_000, 5);
    let sigma = [1e-3, 4e-3];
    let mut rng = Stream(0x9E81_0D1C);
    let mut gaussian = move || {
        let (u, v) = (rng.uniform(1e-300, 1.0), rng.uniform(0.0, 1.0));
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    };
    let motion = |k: usize| {
        let x = TAU * k as f64 / n as f64;
        [1e6 + x.sin(), -2.0 + 0.3 * (3.0 * x).cos()]
    };
    let recording: Vec<Vec<f64>> = (0..n * m)
        .map(|i| {
            let truth = motion(i % n);
            (0..2).map(|c| truth[c] + sigma[c] * gaussian()).collect()
        })
        .collect();
    let average = PeriodAverage::new(&recording, n).unwrap();
    assert_eq!((average.channels(), average.periods()), (2, m));
    let variance = average.noise_variance().unwrap();
    let mean_variance = average.mean_noise_variance().unwrap();
    let spread = (2.0 / (n * (m - 1)) as f64).sqrt();
    for c in 0..2 {
        let ratio = variance[c] / (sigma[c] * sigma[c]);
        assert!(
            (ratio - 1.0).abs() < 5.0 * spread,
            "channel {c}: σ̂²/σ² = {ratio} (its standard deviation {spread:.4})"
        );
        assert!((mean_variance[c] * m as f64 / variance[c] - 1.0).abs() < 1e-15);
        // The averages' errors: N samples of variance σ² / M.
        let errors: f64 = (0..n)
            .map(|k| (average.sample(k).unwrap()[c] - motion(k)[c]).powi(2))
            .sum::<f64>()
            / n as f64;
        let ratio = errors / (sigma[c] * sigma[c] / m as f64);
        let spread = (2.0 / n as f64).sqrt();
        assert!(
            (ratio - 1.0).abs() < 5.0 * spread,
            "channel {c}: the averages' squared error is {ratio} times σ²/M"
        );
    }
    assert!(average.sample(n).is_none());
}

#[test]
fn bad_recordings_are_refused_naming_what_and_where() {
    let good = vec![[0.0, 1.0]; 12];
    assert_eq!(
        PeriodAverage::new(&good, 5),
        Err(IdentificationError::NotWholePeriods {
            samples: 12,
            samples_per_period: 5
        })
    );
    assert!(matches!(
        PeriodAverage::new(&good, 0),
        Err(IdentificationError::NotWholePeriods { .. })
    ));
    assert!(matches!(
        PeriodAverage::new::<[f64; 2]>(&[], 4),
        Err(IdentificationError::NotWholePeriods { samples: 0, .. })
    ));
    let mut ragged: Vec<Vec<f64>> = vec![vec![0.0, 1.0]; 12];
    ragged[7].push(2.0);
    assert_eq!(
        PeriodAverage::new(&ragged, 6),
        Err(IdentificationError::RaggedSample {
            sample: 7,
            values: 3,
            expected: 2
        })
    );
    let empty: Vec<Vec<f64>> = vec![Vec::new(); 4];
    assert!(matches!(
        PeriodAverage::new(&empty, 2),
        Err(IdentificationError::RaggedSample { sample: 0, .. })
    ));
    let mut nan = good.clone();
    nan[9][1] = f64::NAN;
    nan[10][0] = f64::INFINITY;
    assert_eq!(
        PeriodAverage::new(&nan, 6),
        Err(IdentificationError::NonFiniteSample {
            sample: 9,
            channel: 1
        })
    );
    let average = PeriodAverage::new(&good, 6).unwrap();
    assert_eq!(
        average.fourier_series::<1>(2, 0.0, 1.0),
        Err(IdentificationError::NoChannel {
            channel: 2,
            channels: 2
        })
    );
    // Six samples resolve two harmonics, not three.
    assert!(average.fourier_series::<2>(0, 0.0, 1.0).is_ok());
    assert_eq!(
        average.fourier_series::<3>(0, 0.0, 1.0),
        Err(IdentificationError::TooFewSamples {
            samples_per_period: 6,
            harmonics: 3
        })
    );
    for (t0, period) in [
        (0.0, 0.0),
        (0.0, -1.0),
        (0.0, f64::NAN),
        (f64::INFINITY, 1.0),
    ] {
        assert!(
            matches!(
                average.fourier_series::<1>(0, t0, period),
                Err(IdentificationError::Series(
                    TrajectoryError::NonFinite { .. } | TrajectoryError::NonPositiveLimit { .. }
                ))
            ),
            "t0 {t0}, period {period}"
        );
    }
    let message = PeriodAverage::new(&nan, 6).unwrap_err().to_string();
    assert!(message.contains("sample 9, channel 1"), "{message}");
    let one = PeriodAverage::new(&good[..6], 6).unwrap();
    assert!(one.noise_variance().is_none() && one.mean_noise_variance().is_none());
}

/// Six joints' setpoints as `(q, q̇, q̈)`.
fn split(s: &[Setpoint; 6]) -> ([f64; 6], [f64; 6], [f64; 6]) {
    (
        std::array::from_fn(|j| s[j].q),
        std::array::from_fn(|j| s[j].qd),
        std::array::from_fn(|j| s[j].qdd),
    )
}

/// The whole path of a real robot's identification on the PUMA 560: a periodic excitation
/// (three harmonics per joint), positions and torques recorded over two periods (the torques
/// of its own inverse dynamics, the velocities and accelerations not recorded), averaged, the
/// positions' harmonics fitted and differentiated, the base regressor at the fitted states:
/// its base parameters to 1e-9.
#[test]
fn a_robots_base_parameters_from_its_positions_and_torques_alone() {
    const H: usize = 3;
    let (n, m, period) = (400, 2, 4.0);
    let omega = TAU / period;
    let mid = [0.1, 0.5, -0.8, 0.2, 0.3, -0.1];
    let a: [[f64; H]; 6] =
        std::array::from_fn(|j| std::array::from_fn(|l| 0.3 * ((1.7 * j as f64 + l as f64).cos())));
    let b: [[f64; H]; 6] = std::array::from_fn(|j| {
        std::array::from_fn(|l| 0.3 * omega * ((0.9 * j as f64 - l as f64).sin()))
    });
    let excitation = Synchronized::fourier(0.0, period, m as u32, &mid, &a, &b).unwrap();
    let recording: Vec<[f64; 12]> = (0..n * m)
        .map(|i| {
            let (q, qd, qdd) = split(&excitation.eval(i as f64 * period / n as f64));
            let tau = puma::inverse_dynamics(&q, &qd, &qdd);
            std::array::from_fn(|c| if c < 6 { q[c] } else { tau[c - 6] })
        })
        .collect();
    let average = PeriodAverage::new(&recording, n).unwrap();
    let fits: Vec<FourierSeries<H>> = (0..6)
        .map(|j| average.fourier_series::<H>(j, 0.0, period).unwrap())
        .collect();
    let mut fit = LeastSquares::new(puma::BASE_PARAMETERS);
    for k in 0..n {
        let t = k as f64 * period / n as f64;
        let (q, qd, qdd) = split(&std::array::from_fn(|j| fits[j].eval(t)));
        let tau =
            dhgen::nalgebra::SVector::<f64, 6>::from_fn(|j, _| average.sample(k).unwrap()[6 + j]);
        fit.add(&puma::base_regressor(&q, &qd, &qdd), &tau).unwrap();
    }
    let estimate = fit.estimate().unwrap();
    let truth = puma::base_parameters(&puma::PARAMETER_VALUES);
    let scale = truth.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let worst = (0..puma::BASE_PARAMETERS)
        .map(|k| (estimate.parameters[k] - truth[k]).abs() / scale)
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-9,
        "worst error {worst:e} (condition number {:.1})",
        estimate.condition_number
    );
}
