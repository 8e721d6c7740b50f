// SPDX-License-Identifier: GPL-3.0-or-later
#include "hapticad/core/analysis/texture_fit.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unsupported/Eigen/FFT>
#include <utility>
#include <vector>

#include "hapticad/core/surfaces/viscous_texture.h"

namespace hapticad {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMaxPeriods = 1e6;  // a section longer is a period given in the wrong unit

[[noreturn]] void Fail(const std::string& what) {
  throw std::invalid_argument("texture fit: " + what);
}

std::string Text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string Mm(double metres) { return Text(metres * 1e3); }

void CheckOptions(const TextureFitOptions& o) {
  if (!(std::isfinite(o.period_m) && o.period_m > 0)) Fail("the grating period must be > 0");
  if (o.speeds_mps.empty()) Fail("give at least one target speed");
  for (double s : o.speeds_mps) {
    if (!(std::isfinite(s) && s > 0))
      Fail("every target speed must be > 0, got " + Mm(s) + " mm/s");
  }
  if (!(o.speed_tolerance > 0 && o.speed_tolerance < 0.5))
    Fail("the speed tolerance must lie in (0, 0.5)");
  std::vector<double> sorted = o.speeds_mps;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 1; k < sorted.size(); ++k) {
    if (sorted[k] - sorted[k - 1] <= o.speed_tolerance * (sorted[k] + sorted[k - 1])) {
      Fail("the speeds " + Mm(sorted[k - 1]) + " and " + Mm(sorted[k]) + " mm/s overlap within " +
           Text(o.speed_tolerance * 100) + " %: a section would count for both");
    }
  }
  if (!(std::isfinite(o.lowpass_hz) && o.lowpass_hz >= 0))
    Fail("the low-pass cut-off must be >= 0 Hz");
  if (!(std::isfinite(o.velocity_window_s) && o.velocity_window_s > 0))
    Fail("the velocity window must be > 0 s");
  if (o.min_periods < 6) {
    Fail(
        "a section needs at least 6 periods (each harmonic's main lobe spans 5 bins, and the "
        "background needs bins between them)");
  }
  if (o.harmonics < 2 || o.harmonics > 8) Fail("fit 2 to 8 harmonics");
  if (o.samples_per_period < 4 * o.harmonics || o.samples_per_period > 1024) {
    Fail("resample with 4 x harmonics (" + std::to_string(4 * o.harmonics) +
         ") to 1024 samples a period");
  }
}

void CheckRecording(const TextureRecording& r, std::size_t index) {
  const std::string name = "recording " + std::to_string(index + 1) + ": ";
  const std::size_t n = r.time_s.size();
  if (r.position_m.size() != n || r.lateral_force_n.size() != n) {
    Fail(name + "time, position and force have different lengths (" + std::to_string(n) + ", " +
         std::to_string(r.position_m.size()) + ", " + std::to_string(r.lateral_force_n.size()) +
         ")");
  }
  if (n < 3) Fail(name + "fewer than 3 samples");
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(r.time_s[k]) || !std::isfinite(r.position_m[k]) ||
        !std::isfinite(r.lateral_force_n[k])) {
      Fail(name + "sample " + std::to_string(k + 1) + " is not a finite number");
    }
    if (k > 0 && !(r.time_s[k] > r.time_s[k - 1])) {
      Fail(name + "time does not increase at sample " + std::to_string(k + 1));
    }
  }
}

// The velocity window: as asked, or four sampling periods if that is longer (a 100 Hz
// recording has one sample in 10 ms).
double VelocityWindow(const TextureRecording& r, double asked) {
  const double step =
      (r.time_s.back() - r.time_s.front()) / static_cast<double>(r.time_s.size() - 1);
  return std::max(asked, 4.0 * step);
}

// Centred-difference velocity over `window` seconds; NaN where the window does not fit.
std::vector<double> WindowVelocity(const TextureRecording& r, double window) {
  const std::vector<double>& t = r.time_s;
  const std::size_t n = t.size();
  const double half = 0.5 * window;
  std::vector<double> v(n, std::nan(""));
  std::size_t lo = 0;
  std::size_t hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (t[i] - half < t.front() || t[i] + half > t.back()) continue;
    while (t[lo] < t[i] - half) ++lo;
    if (hi < i) hi = i;
    while (hi + 1 < n && t[hi + 1] <= t[i] + half) ++hi;
    if (hi > lo) v[i] = (r.position_m[hi] - r.position_m[lo]) / (t[hi] - t[lo]);
  }
  return v;
}

// Runs [first, last] of samples at `target` speed in one direction.
std::vector<std::pair<std::size_t, std::size_t>> FindRuns(const std::vector<double>& v,
                                                          double target, double tolerance) {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  const auto at_speed = [&](std::size_t i) {
    return std::isfinite(v[i]) && std::abs(std::abs(v[i]) - target) <= tolerance * target;
  };
  std::size_t i = 0;
  while (i < v.size()) {
    if (!at_speed(i)) {
      ++i;
      continue;
    }
    const bool forward = v[i] > 0;
    std::size_t j = i;
    while (j + 1 < v.size() && at_speed(j + 1) && (v[j + 1] > 0) == forward) ++j;
    runs.emplace_back(i, j);
    i = j + 1;
  }
  return runs;
}

// The resisting force (-sign x the force along +x) at N points dx apart, the first
// half a step past x0, interpolated linearly between the samples in position order (held
// past the ends), as seed 001 §III resamples. Averaging the samples in bins instead is a
// box filter: with many samples a bin it bent the background's decay (alpha_b read 0.64
// for 0.5), and by how many samples a bin held, so alpha_b seemed to change with speed.
// False if fewer than 2 distinct positions.
bool ResampleInSpace(const TextureRecording& r, const std::vector<double>& force, double sign,
                     std::size_t first, std::size_t last, double x0, double dx, std::size_t bins,
                     std::vector<double>& out) {
  std::vector<std::pair<double, double>> samples;  // (position, resisting force)
  samples.reserve(last - first + 1);
  for (std::size_t i = first; i <= last; ++i)
    samples.emplace_back(r.position_m[i], -sign * force[i]);
  // in position order (noise or an encoder's steps may not be monotonic); equal positions
  // keep their time order, and an interpolation never spans two of them
  std::stable_sort(samples.begin(), samples.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  if (!(samples.back().first > samples.front().first)) return false;
  out.assign(bins, 0.0);
  std::size_t j = 0;  // the last sample at or before x
  for (std::size_t k = 0; k < bins; ++k) {
    const double x = x0 + (static_cast<double>(k) + 0.5) * dx;
    while (j + 1 < samples.size() && samples[j + 1].first <= x) ++j;
    if (x <= samples.front().first) {
      out[k] = samples.front().second;
    } else if (j + 1 == samples.size()) {
      out[k] = samples.back().second;
    } else {
      const auto& [xa, fa] = samples[j];
      const auto& [xb, fb] = samples[j + 1];
      out[k] = fa + (fb - fa) * (x - xa) / (xb - xa);
    }
  }
  return true;
}

// Mean kept as DC, linear trend removed, periodic Hann window, one-sided amplitudes.
// y becomes the detrended, windowed signal the spectrum is taken of.
std::vector<double> AmplitudeSpectrum(std::vector<double>& y, double& dc) {
  const std::size_t n = y.size();
  double mean = 0;
  for (double value : y) mean += value;
  mean /= static_cast<double>(n);
  const double centre = 0.5 * static_cast<double>(n - 1);
  double sxy = 0;
  double sxx = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const double u = static_cast<double>(k) - centre;
    sxy += u * (y[k] - mean);
    sxx += u * u;
  }
  const double slope = sxx > 0 ? sxy / sxx : 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double hann =
        0.5 - 0.5 * std::cos(2 * kPi * static_cast<double>(k) / static_cast<double>(n));
    y[k] = (y[k] - mean - slope * (static_cast<double>(k) - centre)) * hann;
  }
  Eigen::FFT<double> fft;
  std::vector<std::complex<double>> spectrum;
  fft.fwd(spectrum, y);
  // A sinusoid of amplitude A centred on bin k gives |X_k| = A N / 4 under the Hann window.
  std::vector<double> amplitude(n / 2 + 1);
  amplitude[0] = mean;
  for (std::size_t k = 1; k < amplitude.size(); ++k)
    amplitude[k] = 4.0 * std::abs(spectrum[k]) / static_cast<double>(n);
  dc = mean;
  return amplitude;
}

// The amplitude of a sinusoid at `bins` cycles over the windowed signal y (a fractional
// bin: the transform evaluated there, not at the FFT's integer bins).
double AmplitudeAt(const std::vector<double>& windowed, double bins) {
  std::complex<double> sum = 0;
  const double step = -2 * kPi * bins / static_cast<double>(windowed.size());
  for (std::size_t n = 0; n < windowed.size(); ++n) {
    sum += windowed[n] * std::polar(1.0, step * static_cast<double>(n));
  }
  return 4.0 * std::abs(sum) / static_cast<double>(windowed.size());
}

// Where the fundamental lies, in bins, near bin P: the highest of bins P-2..P+2, refined
// by a parabola through the logarithms of it and its neighbours (Hann's lobe is nearly
// Gaussian there).
double FindFundamental(const std::vector<double>& amplitude, std::size_t p) {
  std::size_t best = p;
  for (std::size_t k = p - 2; k <= p + 2 && k + 1 < amplitude.size(); ++k) {
    if (amplitude[k] > amplitude[best]) best = k;
  }
  if (best < 1 || best + 1 >= amplitude.size()) return static_cast<double>(best);
  const double a = std::log(std::max(amplitude[best - 1], 1e-300));
  const double b = std::log(std::max(amplitude[best], 1e-300));
  const double c = std::log(std::max(amplitude[best + 1], 1e-300));
  const double curve = a - 2 * b + c;
  const double shift = curve < 0 ? 0.5 * (a - c) / curve : 0.0;
  return static_cast<double>(best) + std::clamp(shift, -0.5, 0.5);
}

SpeedLine FitLine(const std::vector<double>& v, const std::vector<double>& y) {
  SpeedLine line;
  const double n = static_cast<double>(v.size());
  double mv = 0;
  double my = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    mv += v[k] / n;
    my += y[k] / n;
  }
  double svy = 0;
  double svv = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    svy += (v[k] - mv) * (y[k] - my);
    svv += (v[k] - mv) * (v[k] - mv);
  }
  line.slope = svv > 0 ? svy / svv : 0.0;
  line.intercept = my - line.slope * mv;
  if (v.size() >= 3 && svv > 0) {
    double residual = 0;
    for (std::size_t k = 0; k < v.size(); ++k) {
      const double e = y[k] - line.intercept - line.slope * v[k];
      residual += e * e;
    }
    const double variance = residual / (n - 2);
    line.slope_se = std::sqrt(variance / svv);
    line.intercept_se = std::sqrt(variance * (1.0 / n + mv * mv / svv));
  }
  return line;
}

std::string SpeedList(const std::vector<double>& speeds) {
  std::ostringstream out;
  for (std::size_t k = 0; k < speeds.size(); ++k) out << (k ? ", " : "") << speeds[k] * 1e3;
  return out.str();
}

}  // namespace

void LowPassFirstOrder(const std::vector<double>& time_s, double cutoff_hz,
                       std::vector<double>& signal) {
  if (signal.size() != time_s.size()) Fail("low-pass: time and signal have different lengths");
  for (std::size_t k = 1; k < signal.size(); ++k) {
    const double gain = 1.0 - std::exp(-2 * kPi * cutoff_hz * (time_s[k] - time_s[k - 1]));
    signal[k] = signal[k - 1] + gain * (signal[k] - signal[k - 1]);
  }
}

PowerFit FitPowerLaw(const std::vector<double>& x, const std::vector<double>& y) {
  PowerFit fit;
  std::vector<double> lx;
  std::vector<double> ly;
  for (std::size_t k = 0; k < std::min(x.size(), y.size()); ++k) {
    if (std::isfinite(x[k]) && std::isfinite(y[k]) && x[k] > 0 && y[k] > 0) {
      lx.push_back(std::log(x[k]));
      ly.push_back(std::log(y[k]));
    }
  }
  const auto [lo, hi] = std::minmax_element(lx.begin(), lx.end());
  if (lx.size() < 2 || *lo == *hi) return fit;
  const SpeedLine line = FitLine(lx, ly);
  fit.points = static_cast<int>(lx.size());
  fit.beta = std::exp(line.intercept);
  fit.alpha = -line.slope;
  double mean = 0;
  for (double value : ly) mean += value / static_cast<double>(ly.size());
  double residual = 0;
  double total = 0;
  for (std::size_t k = 0; k < lx.size(); ++k) {
    const double e = ly[k] - (line.intercept + line.slope * lx[k]);
    residual += e * e;
    total += (ly[k] - mean) * (ly[k] - mean);
  }
  fit.r_squared = total > 0 ? 1.0 - residual / total : 1.0;
  return fit;
}

TextureFit FitTexture(const std::vector<TextureRecording>& recordings,
                      const TextureFitOptions& options) {
  CheckOptions(options);
  if (recordings.empty()) Fail("no recording");
  for (std::size_t r = 0; r < recordings.size(); ++r) CheckRecording(recordings[r], r);

  std::vector<double> targets = options.speeds_mps;
  std::sort(targets.begin(), targets.end());
  const double lambda = options.period_m;
  const double dx = lambda / options.samples_per_period;

  TextureFit fit;
  fit.period_m = lambda;
  const double settle_s =
      options.lowpass_hz > 0 ? kLowPassSettleTimeConstants / (2 * kPi * options.lowpass_hz) : 0.0;
  bool settle_longer = false;  // the filter's start-up, not the window, cut a stroke's start
  double seen_min = INFINITY;
  double seen_max = 0;
  for (std::size_t r = 0; r < recordings.size(); ++r) {
    const TextureRecording& rec = recordings[r];
    std::vector<double> force = rec.lateral_force_n;
    if (options.lowpass_hz > 0) LowPassFirstOrder(rec.time_s, options.lowpass_hz, force);
    const double window = VelocityWindow(rec, options.velocity_window_s);
    const double half = 0.5 * window;
    const double lead = std::max(half, settle_s);
    settle_longer |= settle_s > half;
    const std::vector<double> v = WindowVelocity(rec, window);
    for (double value : v) {
      if (!std::isfinite(value)) continue;
      seen_min = std::min(seen_min, std::abs(value));
      seen_max = std::max(seen_max, std::abs(value));
    }
    for (double target : targets) {
      for (auto [a, b] : FindRuns(v, target, options.speed_tolerance)) {
        // Half a window off each end: the velocity there averages motion outside the run;
        // and the filter's start-up off the start (`lead`)
        std::size_t first = a;
        while (first <= b && rec.time_s[first] < rec.time_s[a] + lead) ++first;
        std::size_t last = b;
        while (last > first && rec.time_s[last] > rec.time_s[b] - half) --last;
        if (last <= first) continue;
        const double x_first = rec.position_m[first];
        const double x_last = rec.position_m[last];
        const double length = std::abs(x_last - x_first);
        const double whole = std::floor(length / lambda);
        if (whole > kMaxPeriods) {
          Fail("a section of " + Mm(length) + " mm holds " + std::to_string(whole) +
               " periods of " + Mm(lambda) + " mm: is the grating's period given in mm?");
        }
        const int periods = static_cast<int>(whole);
        if (periods < options.min_periods) continue;
        const double sign = x_last > x_first ? 1.0 : -1.0;
        const double x0 = std::min(x_first, x_last) + 0.5 * (length - periods * lambda);
        const std::size_t bins = static_cast<std::size_t>(periods) * options.samples_per_period;
        std::vector<double> resampled;
        if (!ResampleInSpace(rec, force, sign, first, last, x0, dx, bins, resampled)) continue;
        TextureSection section;
        section.recording = static_cast<int>(r);
        section.first_sample = first;
        section.last_sample = last;
        section.target_speed_mps = target;
        const double duration = rec.time_s[last] - rec.time_s[first];
        section.speed_mps = length / duration;
        section.samples_per_period = static_cast<double>(last - first) / (length / lambda);
        section.start_m = x0;
        section.end_m = x0 + periods * lambda;
        section.periods = periods;
        section.amplitude_n = AmplitudeSpectrum(resampled, section.dc_n);
        // the filter's known gain at a frequency of `cycles` a section (f v in time),
        // the discrete filter's (LowPassFirstOrder's) at the section's mean step: divided
        // out, so the filter removes a rig's resonance without bending the harmonics' decay
        const double dt = duration / static_cast<double>(last - first);
        const double keep = std::exp(-2 * kPi * options.lowpass_hz * dt);
        const auto gain = [&](double cycles) {
          if (options.lowpass_hz <= 0) return 1.0;
          const double theta = 2 * kPi * cycles / periods / lambda * section.speed_mps * dt;
          return (1 - keep) / std::sqrt(1 - 2 * keep * std::cos(theta) + keep * keep);
        };
        for (std::size_t k = 1; k < section.amplitude_n.size(); ++k) {
          section.amplitude_n[k] /= gain(static_cast<double>(k));
        }
        // the harmonics at whole multiples of the fundamental found near bin P: a grating
        // a little off the period given still reads right (its bin i P alone lost 15 %
        // half a bin off, and more for higher harmonics)
        const double fundamental =
            FindFundamental(section.amplitude_n, static_cast<std::size_t>(periods));
        section.period_found_m = periods * lambda / fundamental;
        for (int i = 1; i <= options.harmonics; ++i) {
          section.harmonic_n.push_back(AmplitudeAt(resampled, i * fundamental) /
                                       gain(i * fundamental));
        }
        fit.sections.push_back(std::move(section));
      }
    }
  }

  std::vector<double> speed_units;
  std::vector<double> dcs;
  std::vector<double> betas;
  std::vector<double> alphas;
  for (double target : targets) {
    SpeedFit speed;
    speed.target_speed_mps = target;
    std::vector<double> hx;
    std::vector<double> hy;
    std::vector<double> bx;
    std::vector<double> by;
    std::vector<double> section_dcs;
    for (const TextureSection& s : fit.sections) {
      if (s.target_speed_mps != target) continue;
      ++speed.sections;
      speed.speed_mps += s.speed_mps;
      section_dcs.push_back(s.dc_n);
      const std::size_t p = static_cast<std::size_t>(s.periods);
      for (int i = 1; i <= options.harmonics; ++i) {
        hx.push_back(i);
        hy.push_back(s.harmonic_n[static_cast<std::size_t>(i - 1)]);
      }
      speed.samples_per_period = speed.sections == 1
                                     ? s.samples_per_period
                                     : std::min(speed.samples_per_period, s.samples_per_period);
      for (std::size_t k = 1; k < s.amplitude_n.size(); ++k) {
        const std::size_t off = k % p;
        if (off <= 2 || off >= p - 2) continue;  // a harmonic's main lobe under the Hann window
        const double fundamentals = static_cast<double>(k) / static_cast<double>(p);
        if (options.lowpass_hz > 0 && fundamentals / lambda * s.speed_mps >= options.lowpass_hz)
          break;
        bx.push_back(fundamentals);
        by.push_back(s.amplitude_n[k]);
      }
    }
    if (speed.sections == 0) {
      fit.speeds_without_sections_mps.push_back(target);
      continue;
    }
    speed.speed_mps /= speed.sections;
    for (double dc : section_dcs) speed.dc_n += dc / speed.sections;
    if (speed.sections > 1) {
      double ss = 0;
      for (double dc : section_dcs) ss += (dc - speed.dc_n) * (dc - speed.dc_n);
      speed.dc_sd_n = std::sqrt(ss / (speed.sections - 1));
    }
    speed.harmonic = FitPowerLaw(hx, hy);
    speed.background = FitPowerLaw(bx, by);
    fit.speeds.push_back(speed);
    speed_units.push_back(speed.speed_mps / kViscousSpeedUnitMps);
    dcs.push_back(speed.dc_n);
    betas.push_back(speed.harmonic.beta);
    alphas.push_back(speed.harmonic.alpha);
  }
  if (fit.speeds.empty()) {
    std::ostringstream why;
    why << "no section of constant speed: no recording keeps within "
        << options.speed_tolerance * 100 << " % of " << SpeedList(targets)
        << " mm/s in one direction over " << options.min_periods << " periods ("
        << Mm(options.min_periods * lambda) << " mm) of the grating";
    if (settle_longer) {
      std::ostringstream settle;
      settle.precision(2);
      settle << settle_s;
      why << "; the low-pass at " << options.lowpass_hz << " Hz needs " << settle.str()
          << " s to settle, left out at the start of each stroke: give a higher cut-off (the "
             "paper's 1000 Hz)";
    }
    if (seen_max > 0) {
      why << "; its speeds range from " << seen_min * 1e3 << " to " << seen_max * 1e3 << " mm/s";
      // a thousand times off: metres for millimetres, or milliseconds for seconds
      if (seen_max * 100 < targets.front()) {
        why << ", a thousand times slower than those asked: is position_mm in metres, or time_s "
               "in milliseconds?";
      } else if (seen_max > 100 * targets.back()) {
        why << ", far faster than those asked: is position_mm in micrometres?";
      }
    }
    Fail(why.str());
  }
  fit.dc_n = FitLine(speed_units, dcs);
  fit.beta_h_n = FitLine(speed_units, betas);
  fit.alpha_h = FitLine(speed_units, alphas);
  return fit;
}

}  // namespace hapticad
