// SPDX-License-Identifier: GPL-3.0-or-later
// FitTexture: a viscous grating texture (seed 001, eq. 2) fitted to recordings of a
// finger, or a probe, stroked over a grating, by the procedure of seed 001 §III:
//
//  1. The lateral force is low-pass filtered (first order, Butterworth's response:
//     -3 dB at `lowpass_hz`; 0 leaves it as recorded).
//  2. The recording is cut into sections of constant velocity: runs where the speed,
//     a centred difference over `velocity_window_s`, stays within `speed_tolerance`
//     (2.5 % in the paper) of one of the target speeds and the direction does not
//     change. Turnarounds and other non-steady parts fall outside every run; half a
//     window is dropped at each end, and at the start at least kLowPassSettleTimeConstants
//     of the filter's time constant 1 / (2 pi lowpass_hz) (the filter still holds the force
//     from before the run: the paper's 1000 Hz settles within the half window, a 1 Hz one
//     would drag a short section's mean towards the pause before it); runs shorter than
//     `min_periods` periods are dropped.
//  3. Each section is resampled in space (the force interpolated linearly between the
//     samples at steps of period / samples_per_period), trimmed to a whole number P of
//     periods, detrended (its mean kept) and Hann-windowed, and its spatial
//     FFT taken. Harmonic i of the grating falls in bin i P. Each bin's amplitude is
//     divided by the (discrete) filter's gain at its frequency in time, f v (so the filter removes
//     a rig's resonance without bending the harmonics' decay: the paper's 1000 Hz
//     filter lowered its fourth harmonic at high speeds).
//  4. Per speed: f_DC is the mean resisting force; the first `harmonics` harmonic
//     amplitudes of all sections (read at whole multiples of the fundamental found
//     within 2 bins of bin P, so a grating a little off the period given reads right)
//     are fitted with A_i = beta_h i^-alpha_h, and the non-harmonic bins (each harmonic's
//     Hann main lobe, bins i P - 2 .. i P + 2, excluded; and only those below the filter's cut-off
//     in time, f v < lowpass_hz) with B(f) = beta_b f^-alpha_b. Both are least squares on
//     logarithms, as the paper's "best fit power model". Frequencies are in multiples of the
//     grating's fundamental 1/lambda, so beta_h is the fundamental's amplitude (eq. 2's beta_h) and
//     beta_b the noise at the fundamental's frequency (eq. 1's f_k = i / lambda, rescaled). beta_b
//     is an amplitude per bin, so a random background's beta_b falls as 1 / sqrt(section length):
//     compare it only between fits of like sections; alpha_b does not depend on the length.
//  5. Across speeds, with v in units of 400 mm/s as in eq. 2: f_DC + v f_vis,
//     beta_h + v beta_vis and alpha_h + v alpha_vis are straight lines fitted through the
//     per-speed values (one speed: the viscous terms are 0).
//
// Units: SI. Input force is the lateral force on the finger along +x (N): a resisting
// force is negative while x increases. Output forces are newtons of resisting force;
// dividing f_dc_n, f_vis_n, beta_h_n and beta_vis_n by the device's full range gives
// eq. 2's normalised levels. Throws std::invalid_argument, saying what is wrong, for
// input that cannot be fitted (sizes, non-finite samples, time not increasing, bad
// options, no section at any speed). Allocates; not for the servo thread.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace hapticad {

// One recording: sample k at time_s[k] (strictly increasing), finger position along the
// stroke position_m[k], lateral force on the finger lateral_force_n[k].
struct TextureRecording {
  std::vector<double> time_s;
  std::vector<double> position_m;
  std::vector<double> lateral_force_n;
};

// The low-pass's start-up left out of each section's start, in time constants: what is left
// of the force before the run is at most e^-7 (0.09 %) of the step from it.
inline constexpr double kLowPassSettleTimeConstants = 7.0;

struct TextureFitOptions {
  double period_m = 2.5e-3;                                         // the grating's lambda, > 0
  std::vector<double> speeds_mps = {0.05, 0.08, 0.12, 0.18, 0.27};  // the paper's five
  double speed_tolerance = 0.025;                                   // relative, in (0, 0.5)
  double lowpass_hz = 1000.0;                                       // 0: no filter
  double velocity_window_s = 0.01;                                  // > 0
  int min_periods = 6;          // >= 6: each harmonic's Hann lobe spans 5 bins
  int harmonics = 3;            // fitted; the paper used the first three, 2..8
  int samples_per_period = 64;  // spatial resampling, 4 x harmonics .. 1024
};

// One section of constant velocity and its one-sided amplitude spectrum.
struct TextureSection {
  int recording = 0;             // index into the recordings
  std::size_t first_sample = 0;  // the section's samples in its recording, inclusive
  std::size_t last_sample = 0;
  double target_speed_mps = 0;
  double speed_mps = 0;  // measured: distance / time over the section
  double start_m = 0;    // the section's extent along x
  double end_m = 0;
  int periods = 0;  // P
  double dc_n = 0;  // mean resisting force
  // recorded samples a period: below some 8 a harmonic, interpolating between them
  // lowers the higher harmonics (and bends alpha_h)
  double samples_per_period = 0;
  // amplitude_n[k] at frequency k / P fundamentals, k = 0 .. N/2 (amplitude_n[0] = dc_n)
  std::vector<double> amplitude_n;
  // harmonic i's amplitude at [i - 1], i = 1..harmonics, read at i times the fundamental
  // found near bin P
  std::vector<double> harmonic_n;
  // the grating's period as the section shows it: the fundamental found near bin P (a
  // period given wrong by more than 2 / P of itself is not found: see the fit's r^2)
  double period_found_m = 0;
};

// A power law y = beta x^-alpha fitted by least squares on logarithms.
struct PowerFit {
  double beta = 0;
  double alpha = 0;
  int points = 0;
  double r_squared = 0;  // on the logarithms; 1 when the points lie on the law
};

struct SpeedFit {
  double target_speed_mps = 0;
  double speed_mps = 0;  // mean measured speed of its sections
  int sections = 0;
  double samples_per_period = 0;  // the fewest recorded samples a period of its sections
  double dc_n = 0;                // mean of the sections' DC
  double dc_sd_n = 0;             // their standard deviation (0 for one section)
  PowerFit harmonic;              // A_i = beta i^-alpha, beta in N
  PowerFit background;            // B(f) = beta f^-alpha, f in fundamentals, beta in N
};

// A straight line y = intercept + slope v, v in units of 400 mm/s, least squares through
// the per-speed values, with the standard errors of its two coefficients (from the
// residuals: NaN with fewer than 3 speeds, where a line leaves none).
struct SpeedLine {
  double intercept = 0;
  double slope = 0;
  double intercept_se = std::numeric_limits<double>::quiet_NaN();
  double slope_se = std::numeric_limits<double>::quiet_NaN();
};

struct TextureFit {
  double period_m = 0;
  std::vector<TextureSection> sections;
  std::vector<SpeedFit> speeds;  // the target speeds that had sections, ascending
  std::vector<double> speeds_without_sections_mps;
  SpeedLine dc_n;      // f_DC (N) + v f_vis (N per 400 mm/s)
  SpeedLine beta_h_n;  // beta_h (N) + v beta_vis
  SpeedLine alpha_h;   // alpha_h + v alpha_vis
};

// Runs steps 1-5 over every recording. Expensive: filters, differentiates and
// transforms every sample.
TextureFit FitTexture(const std::vector<TextureRecording>& recordings,
                      const TextureFitOptions& options);

// Step 1 alone, in place: y[k] = y[k-1] + (1 - exp(-2 pi f_c dt)) (x[k] - y[k-1]), the
// first-order low-pass's response, exact for an input held over each step (so a
// jittered sampling period is honoured).
void LowPassFirstOrder(const std::vector<double>& time_s, double cutoff_hz,
                       std::vector<double>& signal);

// A power law through (x, y) pairs with x, y > 0 (others skipped); needs two distinct x.
PowerFit FitPowerLaw(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace hapticad
