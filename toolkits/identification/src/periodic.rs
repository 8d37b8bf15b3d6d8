//! Periodic recordings: averaged period by period, their noise estimated from the spread
//! between periods, their derivatives taken from their harmonics.
//!
//! A robot measures its joint positions (encoders) and torques (motor currents), not its
//! velocities and accelerations, and differentiating noisy positions twice amplifies the noise
//! by the square of the frequency. An exciting trajectory that repeats (a
//! [`FourierSeries`]) avoids both problems (Swevers et al. 1997):
//!
//! - averaging `M` periods sample by sample divides the variance of independent noise by `M`,
//!   and the spread of the periods about their average estimates that variance, channel by
//!   channel, without a model: the weights of [`LeastSquares::add_weighted`](super::LeastSquares::add_weighted);
//! - the averaged period's harmonics up to the excitation's bandwidth hold the motion and
//!   leave out the noise beyond it, and a Fourier series is differentiated exactly: q, q̇ and
//!   q̈ at every sample from the positions alone.

use super::IdentificationError;
use dhgen_trajectory::FourierSeries;

/// A recording of whole periods of a periodic motion, averaged period by period.
///
/// The recording is `M` periods of `N` samples each, every sample `c` values (channels: the
/// joints' positions and torques, say), taken at times `t0 + (p N + k) T / N` for period `p` and
/// sample `k` of a period of `T` seconds. The average of sample `k` over the periods is
/// `x̄_k = Σ_p x_pk / M`; with `M ≥ 2`, each channel's noise variance is estimated by
///
/// ```text
/// σ̂² = Σ_p Σ_k (x_pk − x̄_k)² / (N (M − 1))
/// ```
///
/// unbiased for noise independent from sample to sample and a motion that repeats exactly
/// (a transient not yet decayed, or a drift, adds to it: leave the first periods out). The
/// averages' own variance is `σ̂² / M` ([`mean_noise_variance`](Self::mean_noise_variance)).
///
/// ```
/// use dhgen::identification::PeriodAverage;
/// use dhgen::trajectory::Profile;
///
/// // Three periods of 1 s at 100 Hz of q(t) = 0.3 + 0.5 sin(2πt), with ±1e-3 of noise.
/// let sample = |i: usize| {
///     let t = i as f64 / 100.0;
///     let noise = if i % 2 == 0 { 1e-3 } else { -1e-3 };
///     [0.3 + 0.5 * (std::f64::consts::TAU * t).sin() + noise]
/// };
/// let recording: Vec<[f64; 1]> = (0..300).map(sample).collect();
/// let average = PeriodAverage::new(&recording, 100)?;
/// assert_eq!((average.periods(), average.samples_per_period()), (3, 100));
/// // The first harmonic holds the motion: q, q̇ and q̈ at any time.
/// let q = average.fourier_series::<1>(0, 0.0, 1.0)?;
/// let at = q.eval(0.25);
/// assert!((at.q - 0.8).abs() < 1e-12 && at.qd.abs() < 1e-12);
/// assert!((at.qdd + 0.5 * std::f64::consts::TAU.powi(2)).abs() < 1e-10);
/// # Ok::<(), dhgen::identification::IdentificationError>(())
/// ```
#[derive(Clone, Debug, PartialEq)]
pub struct PeriodAverage {
    samples_per_period: usize,
    channels: usize,
    periods: usize,
    /// `N × c`, sample by sample.
    mean: Vec<f64>,
    /// `c` entries; `None` with one period.
    variance: Option<Vec<f64>>,
}

impl PeriodAverage {
    /// Averages `samples` (one slice of channel values per sample, in time order, every one of
    /// the same length) period by period, `samples_per_period` samples to a period.
    ///
    /// # Errors
    /// [`IdentificationError::NotWholePeriods`] unless the samples are a positive whole number
    /// of periods of at least one sample; [`IdentificationError::RaggedSample`] for a sample
    /// with no channel or another number of channels than the first;
    /// [`IdentificationError::NonFiniteSample`] naming the first value that is not finite.
    pub fn new<S: AsRef<[f64]>>(
        samples: &[S],
        samples_per_period: usize,
    ) -> Result<Self, IdentificationError> {
        let n = samples_per_period;
        if n == 0 || samples.is_empty() || !samples.len().is_multiple_of(n) {
            return Err(IdentificationError::NotWholePeriods {
                samples: samples.len(),
                samples_per_period,
            });
        }
        let channels = samples[0].as_ref().len();
        for (sample, s) in samples.iter().enumerate() {
            let values = s.as_ref();
            if values.len() != channels || channels == 0 {
                return Err(IdentificationError::RaggedSample {
                    sample,
                    values: values.len(),
                    expected: channels,
                });
            }
            if let Some(channel) = values.iter().position(|x| !x.is_finite()) {
                return Err(IdentificationError::NonFiniteSample { sample, channel });
            }
        }
        let periods = samples.len() / n;
        let mut mean = vec![0.0; n * channels];
        for period in samples.chunks(n) {
            for (row, s) in mean.chunks_mut(channels).zip(period) {
                for (m, x) in row.iter_mut().zip(s.as_ref()) {
                    *m += x;
                }
            }
        }
        let m = periods as f64;
        for x in &mut mean {
            *x /= m;
        }
        // Two passes (deviations from the finished averages), not sums of squares, which
        // cancel catastrophically for small noise on large values.
        let variance = (periods > 1).then(|| {
            let mut sum = vec![0.0; channels];
            for period in samples.chunks(n) {
                for (row, s) in mean.chunks(channels).zip(period) {
                    for ((total, x), m) in sum.iter_mut().zip(s.as_ref()).zip(row) {
                        *total += (x - m) * (x - m);
                    }
                }
            }
            let dof = (n * (periods - 1)) as f64;
            sum.into_iter().map(|s| s / dof).collect()
        });
        Ok(PeriodAverage {
            samples_per_period: n,
            channels,
            periods,
            mean,
            variance,
        })
    }

    /// The periods averaged, `M`.
    pub fn periods(&self) -> usize {
        self.periods
    }

    /// The samples of one period, `N`.
    pub fn samples_per_period(&self) -> usize {
        self.samples_per_period
    }

    /// The values of each sample, `c`.
    pub fn channels(&self) -> usize {
        self.channels
    }

    /// Sample `k` of the period (`k < N`), averaged over the periods: one value per channel.
    pub fn sample(&self, k: usize) -> Option<&[f64]> {
        let c = self.channels;
        self.mean.get(k * c..(k + 1) * c)
    }

    /// Each channel's noise variance `σ̂²` (see the [type](Self)), estimated from the spread of
    /// the periods about their average; `None` for a recording of one period.
    pub fn noise_variance(&self) -> Option<&[f64]> {
        self.variance.as_deref()
    }

    /// The variance of each channel's averaged samples, `σ̂² / M`: for a torque channel, the
    /// square of the `1/w` that weights its rows in
    /// [`LeastSquares::add_weighted`](super::LeastSquares::add_weighted); `None` for one
    /// period.
    pub fn mean_noise_variance(&self) -> Option<Vec<f64>> {
        let m = self.periods as f64;
        self.noise_variance()
            .map(|v| v.iter().map(|s| s / m).collect())
    }

    /// The averaged period of `channel` as a Fourier series of its first `L` harmonics (and
    /// its mean): the least-squares fit of `L` harmonics of `2π / period` to the `N` averaged
    /// samples, which for samples evenly spread over a whole period is their discrete Fourier
    /// transform (the harmonics are orthogonal on them while `2L < N`). Sample `k` is at
    /// `t0 + k · period / N`; the series runs for the recording's `M` periods from `t0`.
    ///
    /// Its [`eval`](dhgen_trajectory::Profile::eval) gives the position, velocity and
    /// acceleration at any time of the recording: the motion's up to harmonic `L`, without
    /// the noise above it (and with what the motion holds above it left out: choose `L` to
    /// cover the motion's bandwidth, not only the excitation's). A signal of at most `L`
    /// harmonics is recovered exactly, up to rounding.
    ///
    /// # Errors
    /// [`IdentificationError::NoChannel`] for a channel beyond the samples';
    /// [`IdentificationError::TooFewSamples`] unless `2L < N`;
    /// [`IdentificationError::Series`] for a period or `t0` that is not finite or a period that
    /// is not positive.
    pub fn fourier_series<const L: usize>(
        &self,
        channel: usize,
        t0: f64,
        period: f64,
    ) -> Result<FourierSeries<L>, IdentificationError> {
        let (n, c) = (self.samples_per_period, self.channels);
        if channel >= c {
            return Err(IdentificationError::NoChannel {
                channel,
                channels: c,
            });
        }
        if 2 * L >= n {
            return Err(IdentificationError::TooFewSamples {
                samples_per_period: n,
                harmonics: L,
            });
        }
        let values = || self.mean.iter().skip(channel).step_by(c);
        let mean = values().sum::<f64>() / n as f64;
        // x(τ) ≈ mean + Σ_l α_l cos(l ω τ) + β_l sin(l ω τ), α_l and β_l by the DFT. Harmonic
        // l at sample k turns (l k mod N) / N: one table of the N sines and cosines serves
        // every harmonic, each angle exact in turns before it is scaled.
        let turns: Vec<(f64, f64)> = (0..n)
            .map(|m| (core::f64::consts::TAU * (m as f64 / n as f64)).sin_cos())
            .collect();
        let mut alpha = [0.0; L];
        let mut beta = [0.0; L];
        for l in 1..=L {
            let (mut sum_cos, mut sum_sin, mut turn) = (0.0, 0.0, 0);
            for x in values() {
                let (s, co) = turns[turn];
                sum_cos += (x - mean) * co;
                sum_sin += (x - mean) * s;
                // (l k) mod N, k advancing; l < N / 2.
                turn += l;
                if turn >= n {
                    turn -= n;
                }
            }
            alpha[l - 1] = 2.0 * sum_cos / n as f64;
            beta[l - 1] = 2.0 * sum_sin / n as f64;
        }
        // FourierSeries: q = q0 + Σ (a_l sin − b_l cos) / (l ω), so a_l = l ω β_l and
        // b_l = −l ω α_l.
        let omega = core::f64::consts::TAU / period;
        let a = core::array::from_fn(|i| (i + 1) as f64 * omega * beta[i]);
        let b = core::array::from_fn(|i| -((i + 1) as f64) * omega * alpha[i]);
        // More than u32::MAX periods (tens of gigabytes of samples): the series runs that many.
        let cycles = u32::try_from(self.periods).unwrap_or(u32::MAX);
        Ok(FourierSeries::new(t0, period, cycles, mean, a, b)?)
    }
}
