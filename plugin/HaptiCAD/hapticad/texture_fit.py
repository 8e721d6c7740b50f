# SPDX-License-Identifier: GPL-3.0-or-later
"""Fit a surface's viscous grating texture to force recordings (seed 001, §III).

The fit itself is the core's (``_core.fit_texture``: low-pass, sections of constant
speed, spatial FFT, power fits, lines in speed). This module reads recordings, turns the
fit's newtons into a surface's texture levels and sets them. No GUI.

Recordings are CSV files with a header, in one of two forms:

* a rig's: ``time_s``, ``position_mm`` (the finger along the stroke), ``lateral_force_n``
  (the lateral force on the finger along +position: negative while it moves to +),
  optionally ``normal_force_n``;
* HaptiCAD's own trace (``hapticad feel``'s ``trace.csv``): the contact rows, position
  along the direction the proxy travelled most, force on the device along it.
"""
import csv
import io
import math
import os
import re
import warnings
from dataclasses import dataclass, field

import numpy as np

from . import _core
from .texture_fit_options import (DEFAULT_HARMONICS, DEFAULT_LOWPASS_HZ, DEFAULT_MIN_PERIODS,
                                  DEFAULT_TOLERANCE_PERCENT)

MM = 1e-3
PAPER_SPEEDS_MM_S = (50.0, 80.0, 120.0, 180.0, 270.0)  # seed 001 §III
RIG_COLUMNS = ("time_s", "position_mm", "lateral_force_n")
TRACE_COLUMNS = ("time_s", "proxy_x_mm", "proxy_y_mm", "proxy_z_mm", "force_x_n", "force_y_n",
                 "force_z_n", "normal_force_n", "contact")
FIELDS = ("TextureDC", "TextureViscosity", "TextureBeta", "TextureBetaViscosity", "TextureAlpha",
          "TextureAlphaViscosity")


@dataclass
class Recording:
    path: str
    kind: str  # "rig" or "trace"
    data: object  # _core.TextureRecording
    normal_n: np.ndarray = None  # the normal force at each sample, when recorded


@dataclass
class FitReport:
    fit: object  # _core.TextureFit
    recordings: list
    options: object  # _core.TextureFitOptions
    notes: list = field(default_factory=list)

    @property
    def normal_force_n(self):
        """The mean normal force over the fitted sections' samples (N), when recorded:
        what the finger pressed with while the texture was measured, not while idle."""
        values = [self.recordings[s.recording].normal_n[s.first_sample:s.last_sample + 1]
                  for s in self.fit.sections if self.recordings[s.recording].normal_n is not None]
        return float(np.mean(np.concatenate(values))) if values else None

    def normal_force_by_speed_n(self):
        """{target speed mm/s: mean normal force over its sections' samples, N}, when recorded."""
        by_speed = {}
        for s in self.fit.sections:
            normal = self.recordings[s.recording].normal_n
            if normal is not None:
                by_speed.setdefault(round(s.target_speed_mps / MM), []).append(
                    normal[s.first_sample:s.last_sample + 1])
        return {speed: float(np.mean(np.concatenate(v))) for speed, v in sorted(by_speed.items())}


# the press may wander this much between speeds before it is said (seed 001 strokes at
# one press: a force that grows with the press would read as a viscosity)
PRESS_DRIFT = 0.1


def press_note(report):
    """A sentence when the recorded normal force differs between the speeds by more than
    PRESS_DRIFT of its mean, else "": friction that grows with the press then reads as
    viscosity (f_vis), which the fit cannot tell apart."""
    by_speed = report.normal_force_by_speed_n()
    if len(by_speed) < 2:
        return ""
    values = list(by_speed.values())
    mean = float(np.mean(values))
    if mean <= 0 or (max(values) - min(values)) <= PRESS_DRIFT * mean:
        return ""
    each = ", ".join(f"{n:.2f} N at {v} mm/s" for v, n in by_speed.items())
    return (f"the finger pressed differently at different speeds ({each}): seed 001 strokes at one press, and "
            "friction that grows with the press reads as viscosity (f_vis) here; record at an even press, or "
            "compare the speeds' force over their press")


SPEED_MAX_MM_S = 1e4  # 10 m/s: no finger or rig scans a texture faster


def parse_speeds(text):
    """The scanning speeds in ``text``, mm/s: numbers separated by commas or semicolons
    (blanks ignored), each > 0 and below SPEED_MAX_MM_S; with semicolons, a comma between
    digits is a decimal comma ("50;80;120,5"). ValueError saying so otherwise."""
    if ";" in text:
        text = re.sub(r"(?<=\d),(?=\d)", ".", text)
    try:
        values = [float(v) for v in text.replace(";", ",").split(",") if v.strip()]
    except ValueError:
        values = []
    if not values or not all(0 < v < SPEED_MAX_MM_S for v in values):  # NaN fails both
        raise ValueError(f"{text!r} is not a list of speeds in mm/s (each > 0 and < {SPEED_MAX_MM_S:g}), "
                         "like 50, 80, 120")
    return values


def _column_name(text):
    """A header cell as a column name: "Time (s)" and "time_s" are one, so are
    "Lateral force [N]" and "lateral_force_n"."""
    name = re.sub(r"\s*[(\[]\s*([^)\]]*?)\s*[)\]]\s*$", r"_\1", text.strip()).lower()
    return re.sub(r"[\s-]+", "_", name)


def _read_columns(path):
    name = path  # as the user gave it: `hapticad feel` names every trace trace.csv
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:  # a spreadsheet's BOM too
            first = handle.readline()
    except (UnicodeDecodeError, csv.Error):
        raise ValueError(f"{name}: not a text CSV file") from None
    except OSError as exc:
        raise ValueError(_unreadable(path, exc)) from None
    # a spreadsheet's export: commas, or semicolons or tabs with decimal commas
    headers = {sep: [_column_name(h) for h in next(csv.reader([first], delimiter=sep), [])] for sep in ",;\t"}
    separator = next((sep for sep, header in headers.items() if set(RIG_COLUMNS) <= set(header)), ",")
    header = headers[separator]
    if not any(header):
        raise ValueError(f"{name}: empty file")
    if set(TRACE_COLUMNS) <= set(header):
        kind, wanted = "trace", TRACE_COLUMNS
    elif set(RIG_COLUMNS) <= set(header):
        kind = "rig"
        wanted = RIG_COLUMNS + (("normal_force_n",) if "normal_force_n" in header else ())
    else:
        raise ValueError(f"{name}: needs the columns {', '.join(RIG_COLUMNS)} (a rig's recording; \"Time (s)\" "
                         "reads as time_s) or a HaptiCAD trace.csv; its header is " + first.strip())
    index = [header.index(c) for c in wanted]
    source = path
    if separator != ",":
        with open(path, encoding="utf-8-sig") as handle:
            source = io.StringIO(handle.read().replace(",", "."))  # decimal commas
    try:  # numpy's C reader: a rig's 20 s at 125 kHz in half a second
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # "input contained no data": the fit says so, by file
            table = np.loadtxt(source, delimiter=separator, skiprows=1, usecols=index, ndmin=2, dtype=float)
        if not np.isfinite(table).all():  # "nan" or "inf" in a cell: _read_rows names its line
            raise ValueError("not finite")
    except (ValueError, UnicodeDecodeError):
        table = _read_rows(path, name, wanted, index, separator)  # slow, and says which line is wrong
    return kind, {c: table[:, k] for k, c in enumerate(wanted)}


def _unreadable(path, exc):
    """Why ``path`` could not be opened, as a sentence naming it (not Python's "[Errno 2]")."""
    if isinstance(exc, IsADirectoryError) or os.path.isdir(path):
        trace = os.path.join(path, "trace.csv")  # `hapticad feel`'s folder
        return (f"{path} is a folder, not a recording: give the CSV files in it"
                + (f", like {trace}" if os.path.isfile(trace) else ""))
    if isinstance(exc, FileNotFoundError):
        folder = os.path.dirname(path)
        return f"{path}: there is no {f'folder {folder}' if folder and not os.path.isdir(folder) else 'such file'}"
    return f"{path}: cannot be read ({(exc.strerror or str(exc)).lower()})"


def _read_rows(path, name, wanted, index, separator=","):
    try:
        with open(path, newline="", encoding="utf-8-sig") as handle:
            rows = list(csv.reader(handle, delimiter=separator))[1:]
    except (UnicodeDecodeError, csv.Error) as exc:
        raise ValueError(f"{name}: not a readable CSV file ({exc})") from None
    table = np.empty((len(rows), len(wanted)))
    kept = 0
    for line, row in enumerate(rows, start=2):
        if not any(cell.strip() for cell in row):  # a spreadsheet's rows of empty cells
            continue
        for k, (c, i) in enumerate(zip(wanted, index)):
            try:
                cell = row[i].strip()
                table[kept, k] = float(cell.replace(",", ".") if separator != "," else cell)
            except (ValueError, IndexError):
                raise ValueError(f"{name}, line {line}: {c} is not a number") from None
            if not math.isfinite(table[kept, k]):  # float() reads "nan" and "inf"
                raise ValueError(f"{name}, line {line}: {c} is not a number ({cell})")
        kept += 1
    return table[:kept]


def load_recording(path):
    """A Recording from a CSV file. Raises ValueError naming the file (as ``path`` gives it)
    and line."""
    kind, c = _read_columns(path)
    name = path
    if kind == "rig":
        t, x, f = c["time_s"], c["position_mm"] * MM, c["lateral_force_n"]
        normal = c.get("normal_force_n")
    else:
        touching = c["contact"] != 0
        if touching.sum() < 3:
            raise ValueError(f"{name}: the trace has no contact to fit")
        p = np.column_stack([c["proxy_x_mm"], c["proxy_y_mm"], c["proxy_z_mm"]])[touching] * MM
        force = np.column_stack([c["force_x_n"], c["force_y_n"], c["force_z_n"]])[touching]
        # the stroke's direction: the axis along which the proxy travelled most
        _, _, axes = np.linalg.svd(p - p.mean(axis=0), full_matrices=False)
        direction = axes[0]
        t, x, f = c["time_s"][touching], (p - p.mean(axis=0)) @ direction, force @ direction
        normal = c["normal_force_n"][touching]
    try:
        data = _core.TextureRecording(np.ascontiguousarray(t), np.ascontiguousarray(x), np.ascontiguousarray(f))
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from None
    return Recording(os.path.abspath(path), kind, data, normal)


def fit_files(paths, period_mm, speeds_mm_s=PAPER_SPEEDS_MM_S, tolerance_percent=DEFAULT_TOLERANCE_PERCENT,
              lowpass_hz=DEFAULT_LOWPASS_HZ, harmonics=DEFAULT_HARMONICS, min_periods=DEFAULT_MIN_PERIODS):
    """Fits the recordings in ``paths``. Raises ValueError for unreadable files, bad options,
    or recordings that hold no section of constant speed; messages and notes name each file
    as ``paths`` gives it."""
    if not paths:
        raise ValueError("give at least one recording")
    recordings = [load_recording(p) for p in paths]
    options = _core.TextureFitOptions()
    options.period_m = float(period_mm) * MM
    options.speeds_mps = sorted({float(s) * MM for s in speeds_mm_s})  # "50, 50" is one speed
    options.speed_tolerance = float(tolerance_percent) / 100.0
    options.lowpass_hz = float(lowpass_hz)
    options.harmonics = int(harmonics)
    options.min_periods = int(min_periods)
    try:
        fit = _core.fit_texture([r.data for r in recordings], options)
    except ValueError as exc:  # the core counts recordings and samples; the designer knows files and lines
        raise ValueError(re.sub(r"recording (\d+): (.*?)sample (\d+)|recording (\d+):",
                                lambda m: _where(recordings, paths, m), str(exc))) from None
    # a grating's friction resists the finger at every speed: a section whose mean force
    # runs with the motion is a sign slip in its file (one trial logged the other way round
    # was fitted into a viscosity of -2 N per 400 mm/s and set)
    backwards = {}
    for section in fit.sections:
        if section.dc_n < 0:
            backwards.setdefault(section.recording, []).append(section)
    if backwards:
        said = []
        for index, sections in backwards.items():
            at = {}
            for section in sections:
                at.setdefault(round(section.target_speed_mps / MM), []).append(section.dc_n)
            speeds = ", ".join(f"{np.mean(v):.3g} N at {k} mm/s" for k, v in sorted(at.items()))
            said.append(f"{paths[index]} ({speeds})")
        raise ValueError(
            f"the lateral force runs with the motion, not against it, in {'; '.join(said)}: the fit needs the "
            "force resisting the finger, as eq. 2 gives it; change the sign of lateral_force_n in "
            f"{'that file' if len(backwards) == 1 else 'those files'}")
    notes = []
    if fit.speeds_without_sections_mps:
        missing = ", ".join(f"{s / MM:g}" for s in fit.speeds_without_sections_mps)
        notes.append(f"no section at {missing} mm/s: those speeds are not in the fit" + _settling(options))
    if len(fit.speeds) == 1:
        notes.append("one speed only: the viscous terms (f_vis, beta_vis, alpha_vis) are 0")
    unused = [p for i, p in enumerate(paths) if not any(s.recording == i for s in fit.sections)]
    if unused:
        notes.append(f"{', '.join(unused)} gave no section (no stroke held within {options.speed_tolerance:.1%} of a "
                     f"speed for {options.min_periods} periods): not in the fit")
    notes += _quality_notes(fit, options)
    report = FitReport(fit, recordings, options, notes)
    pressed = report.normal_force_by_speed_n()
    if pressed and min(pressed.values()) <= 0:
        # a finger stroking presses with more than 0 N: -1 was taken, and a friction level
        # made of it failed as "the full range must be > 0 N, got -0.48", naming no file
        at = ", ".join(f"{n:.3g} N at {v} mm/s" for v, n in pressed.items())
        files = ", ".join(p for i, p in enumerate(paths) if recordings[i].normal_n is not None)
        raise ValueError(f"the normal force (normal_force_n) while stroking is {at} in {files}: a finger pressing "
                         "gives more than 0 N; was it logged with the other sign, or is it another column?")
    notes += [n for n in [press_note(report), slope_notes(fit)] if n]
    return report


def _settling(options):
    """", the low-pass ... leaves out ..." when the filter's start-up, left out of each
    stroke's start (the core's kLowPassSettleTimeConstants), is longer than the half velocity
    window left out anyway, else "": a slow cut-off is why short, fast strokes give no section."""
    if options.lowpass_hz <= 0:
        return ""
    settle_s = _core.LOWPASS_SETTLE_TIME_CONSTANTS / (2 * math.pi * options.lowpass_hz)
    if settle_s <= 0.5 * options.velocity_window_s:
        return ""
    return (f" (the low-pass at {options.lowpass_hz:g} Hz leaves out the first {settle_s:.2g} s of each stroke, "
            "while it settles: a higher cut-off keeps more, the paper's is 1000 Hz)")


def _where(recordings, paths, match):
    """A core message's "recording N: ... sample K" as the file (as given) and, for a rig's
    CSV, its line."""
    if match.group(4):
        return f"{paths[int(match.group(4)) - 1]}:"
    index, what, sample = int(match.group(1)) - 1, match.group(2), int(match.group(3))
    name = paths[index]
    if index < len(recordings) and recordings[index].kind == "rig":
        return f"{name}: {what}line {sample + 1}"
    return f"{name}: {what}contact row {sample}"


# two-sided 95 % Student t for n - 2 degrees of freedom (a line through n speeds)
_T95 = {1: 12.706, 2: 4.303, 3: 3.182, 4: 2.776, 5: 2.571, 6: 2.447, 7: 2.365, 8: 2.306, 9: 2.262, 10: 2.228}


def _slope_interval(line, speeds):
    """(low, high) of a line's slope at 95 %, or None with fewer than 3 speeds."""
    if line.slope_se is None or speeds < 3:
        return None
    half = _T95.get(speeds - 2, 1.96) * line.slope_se
    return (line.slope - half, line.slope + half)


def slope_notes(fit):
    """A sentence naming the speed terms (f_vis, beta_vis, alpha_vis) whose 95 % interval
    holds 0: within the noise of the speeds' values, so not shown to change with speed
    (seed 001 found no significant speed dependence in the harmonics and set such terms
    to 0); they are set as fitted, and the sentence says how loose they are."""
    loose = []
    for name, line, unit in (("f_vis", fit.dc_n, " N"), ("beta_vis", fit.beta_h_n, " N"),
                             ("alpha_vis", fit.alpha_h, "")):
        interval = _slope_interval(line, len(fit.speeds))
        if interval is not None and interval[0] <= 0 <= interval[1]:
            loose.append(f"{name} {line.slope:.3g}{unit} (95 %: {interval[0]:.3g} to {interval[1]:.3g})")
    if not loose:
        return ""
    return (f"not shown to change with speed over these {len(fit.speeds)} speeds: {', '.join(loose)} per 400 mm/s; "
            "seed 001 set such terms to 0; they are set as fitted: set them to 0 on the surface to follow the paper")


def _quality_notes(fit, options):
    """What a designer should know before trusting the fit."""
    notes = []
    for s in fit.speeds:
        wanted = 8 * options.harmonics
        if s.samples_per_period < wanted:
            rate = s.speed_mps / fit.period_m * wanted
            notes.append(f"at {s.speed_mps / MM:.0f} mm/s the recording has {s.samples_per_period:.1f} samples a "
                         f"period (fewer than {wanted}): interpolating between them lowers the higher harmonics "
                         f"and bends alpha_h; record at {rate:.0f} Hz or more")
    if is_flat(fit):  # its harmonics' law and period mean nothing: said once, plainly
        notes.append(f"the recordings hold no ripple at all (under {FLAT_RIPPLE_N * 1e6:g} uN at every speed): the "
                     "force is flat, so no grating is felt in it and only the DC force means anything")
        return notes
    wrong = wrong_period(fit)
    crooked = [s for s in fit.speeds if s.harmonic.r_squared < 0.9]
    if crooked:  # one sentence for every speed it happens at
        at = ", ".join(f"{s.speed_mps / MM:.0f} mm/s (r^2 {s.harmonic.r_squared:.2f})" for s in crooked)
        # the recordings' strongest ripple at the period given: the period is not the cause
        why = ("is the grating's period right?" if wrong else
               "alpha_h is loosely fitted there (its higher harmonics near the noise; the period is right)")
        notes.append(f"at {at} the harmonics do not follow a power law: {why}")
    if wrong:
        notes.append(wrong)
        return notes  # the period found near the given one means nothing then
    found = period_found_m(fit)
    if found != fit.period_m:
        notes.append(f"the recordings show a grating period of {found / MM:.4g} mm, not the "
                     f"{fit.period_m / MM:g} mm given: the harmonics were read at the period found, "
                     "and it is the period set")
    return notes


PERIOD_MISMATCH = 0.15  # of the given period: more than the fit's own search (2 bins) can correct
FLAT_RIPPLE_N = 1e-6  # a ripple under a micronewton: below any rig's resolution, rounding left in a flat force


def is_flat(fit):
    """Whether no section's spectrum holds a ripple (FLAT_RIPPLE_N): a constant force, in
    which the strongest "ripple" was rounding, read as a period of 11.5 mm."""
    return all(float(np.max(np.abs(np.asarray(s.amplitude_n, float)[1:]), initial=0.0)) < FLAT_RIPPLE_N
               for s in fit.sections)


def wrong_period(fit):
    """A sentence when the recordings' strongest ripple is not at the period the fit was
    given (a fit at the wrong period must not be set), else ""."""
    strongest = dominant_period_m(fit)
    if strongest is None or abs(strongest - fit.period_m) <= PERIOD_MISMATCH * fit.period_m:
        return ""
    return (f"the grating period looks wrong: the recordings ripple most strongly every {strongest / MM:.3g} mm, "
            f"not every {fit.period_m / MM:g} mm as given; fit again with that period")


def dominant_period_m(fit):
    """The period (m) of the strongest ripple the sections show between a quarter and
    four times the given period (the median over sections), or None without sections.
    The fit reads the grating only near the period it is given; a period given wrong by
    a factor (half, double) is found here. None too for a flat force (is_flat)."""
    if is_flat(fit):
        return None
    periods = []
    for s in fit.sections:
        amplitude = np.asarray(s.amplitude_n, float)
        low, high = max(1, s.periods // 4), min(len(amplitude) - 1, 4 * s.periods)
        if high <= low:
            continue
        k = low + int(np.argmax(amplitude[low:high + 1]))
        periods.append(fit.period_m * s.periods / _refined_peak(amplitude, k))
    return float(np.median(periods)) if periods else None


def _refined_peak(amplitude, k):
    """Bin k of a Hann-windowed spectrum's peak refined between its neighbours: the
    parabola through the three log amplitudes (a peak between two bins read 2.47 or
    2.55 mm for 2.5)."""
    if not 0 < k < len(amplitude) - 1 or min(amplitude[k - 1:k + 2]) <= 0:
        return float(k)
    a, b, c = np.log(amplitude[k - 1:k + 2])
    bend = a - 2 * b + c
    return float(k) + (0.5 * (a - c) / bend if bend < 0 else 0.0)


def eq2_newtons(fit):
    """The fit as eq. 2's parameters in newtons (level 1 = 1 N): _core.ViscousTextureParams."""
    params = _core.ViscousTextureParams()
    params.f_dc, params.f_vis = fit.dc_n.intercept, fit.dc_n.slope
    params.beta_h, params.beta_vis = fit.beta_h_n.intercept, fit.beta_h_n.slope
    params.alpha_h, params.alpha_vis = fit.alpha_h.intercept, fit.alpha_h.slope
    params.period_m = fit.period_m
    return params


def peak_force_n(fit, samples=256):
    """The largest force eq. 2 (the core's) gives with the fit over a period, at the
    fitted speeds (N)."""
    params = eq2_newtons(fit)
    xs = np.arange(samples) * fit.period_m / samples
    return max((_core.viscous_texture_level(params, x, s.speed_mps) for s in fit.speeds for x in xs), default=0.0)


def trough_force_n(fit, samples=256):
    """The smallest force eq. 2 (the core's) gives with the fit over a period, at the
    fitted speeds (N); below 0 the renderer clips it."""
    params = eq2_newtons(fit)
    xs = np.arange(samples) * fit.period_m / samples
    return min((_core.viscous_texture_level(params, x, s.speed_mps) for s in fit.speeds for x in xs), default=0.0)


def period_found_m(fit):
    """The grating's period the sections show (the median of each one's fundamental) when
    it is more than 1 % off the period given, else the period given (m)."""
    found = [s.period_found_m for s in fit.sections]
    median = float(np.median(found)) if found else fit.period_m
    return median if abs(median - fit.period_m) > 0.01 * fit.period_m else fit.period_m


def levels(fit, full_range_n):
    """The surface properties eq. 2 needs to render the fit with ``full_range_n`` N as level 1."""
    if not (math.isfinite(full_range_n) and full_range_n > 0):
        raise ValueError(f"the full range must be > 0 N, got {full_range_n}")
    return {
        "TextureDC": fit.dc_n.intercept / full_range_n,
        "TextureViscosity": fit.dc_n.slope / full_range_n,
        "TextureBeta": fit.beta_h_n.intercept / full_range_n,
        "TextureBetaViscosity": fit.beta_h_n.slope / full_range_n,
        "TextureAlpha": fit.alpha_h.intercept,
        "TextureAlphaViscosity": fit.alpha_h.slope,
        # the harmonics were read at the period the recordings show: rendered at it too
        "TexturePeriod": period_found_m(fit) / MM,
    }


def full_range_for(surface, report):
    """(newtons that level 1 stands for on ``surface``, what to set, notes).

    Device force with a Full range: that. Device force with the device's full range (0):
    a number of newtons no device knows in advance, so the fit sets Full range to its own
    peak force rounded up to 0.1 N, and the recorded newtons are felt as recorded.
    Friction level: static friction times the recordings' normal force.

    Whatever the surface's setting, a fit beyond the newtons a full range can stand for is
    refused: the recorded forces are implausible as newtons (mN logged as N), and on a
    surface with a Full range they were set as levels of hundreds, clipped to level 1."""
    peak = peak_force_n(report.fit)
    most = _full_range_limit()
    if peak > most:
        raise ValueError(f"the fitted lateral force reaches {peak:.4g} N, more than the {most:g} N a texture's full "
                         "range can stand for (a finger's lateral force is a few newtons): are the forces recorded "
                         "in mN? Give lateral_force_n in newtons")
    if surface.TextureScale == "Friction level":
        normal = report.normal_force_n
        if normal is None:
            raise ValueError("the texture's level 1 is a friction level (static friction times the normal "
                             "force): the recordings carry no normal_force_n column, so its newtons cannot be "
                             "turned into levels; set 'Level 1 is' to Device force, or record the normal force")
        if surface.StaticFriction <= 0:
            raise ValueError("the texture's level 1 is a friction level, and the static friction is 0")
        return surface.StaticFriction * normal, {}, [
            f"level 1 = static friction {surface.StaticFriction:g} x the recorded normal force {normal:.3g} N"]
    if surface.TextureFullRange > 0:
        return surface.TextureFullRange, {}, []
    chosen = max(math.ceil(peak * 10 - 1e-9) / 10, 0.1)  # within the property's limit: peak <= most
    return chosen, {"TextureFullRange": chosen}, [
        f"Full range set to {chosen:g} N (it was the device's full range), so the recorded forces are felt "
        "as recorded"]


def _full_range_limit():
    from .surface_object import PROPERTIES

    return next(c[1] for name, _, _, _, _, c in PROPERTIES if name == "TextureFullRange")


def apply_to_surface(surface, report):
    """Sets ``surface``'s texture to the fit (Texture = Custom, its values and period).
    Returns the notes to show. Raises ValueError, changing nothing, if the fit cannot be
    expressed on this surface."""
    full, extra, notes = full_range_for(surface, report)
    values = levels(report.fit, full)
    values.update(extra)
    bad = [k for k, v in values.items() if not math.isfinite(v)]
    if bad:
        raise ValueError(f"the fit gave a non-finite {', '.join(bad)}")
    if report.fit.beta_h_n.intercept <= 0 or report.fit.alpha_h.intercept <= 0:
        raise ValueError(f"the fit is no grating of period {report.fit.period_m / MM:g} mm (beta_h "
                         f"{report.fit.beta_h_n.intercept:.3g} N, alpha_h {report.fit.alpha_h.intercept:.3g}: "
                         "its harmonics do not fall off); check the period")
    if values["TexturePeriod"] < 1e-3:
        raise ValueError("the grating period is below 0.001 mm")
    wrong = wrong_period(report.fit)
    if wrong:
        raise ValueError(wrong)
    from .similarity_study import pooled_runs, unpooling_notes

    pooled = pooled_runs(surface.Document)
    surface.Texture = "Custom"
    for name, value in values.items():
        setattr(surface, name, value)
    notes += unpooling_notes(surface.Document, pooled)
    peak = peak_force_n(report.fit) / full
    if peak > 1:
        notes.append(f"the fitted force reaches {peak:.2f} x level 1: above level 1 it is clipped")
    trough = trough_force_n(report.fit)
    if trough < 0:
        notes.append(f"the fitted force dips to {trough:.3g} N in the grating's troughs: below 0 it is clipped "
                     "(the texture only resists)")
    return report.notes + notes


def summary(report):
    """The fit as JSON-able data: per speed and the eq. 2 lines (N, per 400 mm/s)."""
    fit = report.fit
    return {
        "recordings": [{"path": r.path, "kind": r.kind, "samples": r.data.samples,
                        "sections": sum(1 for sec in fit.sections if sec.recording == i)}
                       for i, r in enumerate(report.recordings)],
        "normal_force_n": report.normal_force_n,
        "period_mm": fit.period_m / MM,
        "sections": len(fit.sections),
        "speeds": [{
            "target_mm_s": s.target_speed_mps / MM,
            "measured_mm_s": s.speed_mps / MM,
            "sections": s.sections,
            "samples_per_period": s.samples_per_period,
            "dc_n": s.dc_n,
            "dc_sd_n": s.dc_sd_n,
            "normal_force_n": report.normal_force_by_speed_n().get(round(s.target_speed_mps / MM)),
            "harmonic_beta_n": s.harmonic.beta,
            "harmonic_alpha": s.harmonic.alpha,
            "harmonic_r2": s.harmonic.r_squared,
            "background_beta_n": s.background.beta,
            "background_alpha": s.background.alpha,
            "background_points": s.background.points,
        } for s in fit.speeds],
        "speeds_without_sections_mm_s": [s / MM for s in fit.speeds_without_sections_mps],
        "period_found_mm": float(np.median([s.period_found_m for s in fit.sections])) / MM,
        "eq2_newtons": {
            "f_dc_n": fit.dc_n.intercept,
            "f_vis_n_per_400mm_s": fit.dc_n.slope,
            "beta_h_n": fit.beta_h_n.intercept,
            "beta_vis_n_per_400mm_s": fit.beta_h_n.slope,
            "alpha_h": fit.alpha_h.intercept,
            "alpha_vis_per_400mm_s": fit.alpha_h.slope,
        },
        # each line's standard errors (null with fewer than 3 speeds) and its slope's 95 %
        # interval, as the paper weighed whether a term changes with speed
        "eq2_standard_errors": {
            name: {"intercept": line.intercept_se, "slope": line.slope_se,
                   "slope_95": _slope_interval(line, len(fit.speeds))}
            for name, line in (("dc_n", fit.dc_n), ("beta_h_n", fit.beta_h_n), ("alpha_h", fit.alpha_h))},
        "peak_force_n": peak_force_n(fit),
        "notes": list(report.notes),
    }


def describe(result):
    """``summary()``'s data (and what --apply set) as text for a terminal."""
    count = result["sections"]
    lines = [f"grating period {result['period_mm']:g} mm, {count} section{'' if count == 1 else 's'} of constant speed"]
    lines.append("  speed mm/s  sections  DC N (sd)        harmonics beta N, alpha  background beta N, alpha")
    for s in result["speeds"]:
        lines.append(f"  {s['measured_mm_s']:9.1f}  {s['sections']:8d}  {s['dc_n']:.4f} ({s['dc_sd_n']:.4f})"
                     f"  {s['harmonic_beta_n']:.4f}, {s['harmonic_alpha']:.2f}"
                     f"          {s['background_beta_n']:.2e}, {s['background_alpha']:.2f}")
    e = result["eq2_newtons"]
    lines.append(f"eq. 2 in newtons (v in units of 400 mm/s): f_DC {e['f_dc_n']:.4f} + v {e['f_vis_n_per_400mm_s']:.4f}, "
                 f"beta_h {e['beta_h_n']:.4f} + v {e['beta_vis_n_per_400mm_s']:.4f}, "
                 f"alpha_h {e['alpha_h']:.3f} + v {e['alpha_vis_per_400mm_s']:.3f}")
    applied = result.get("applied")
    if applied:
        values = ", ".join(f"{k} {applied[k]:.4g}" for k in (*FIELDS, "TexturePeriod", "TextureFullRange"))
        lines.append(f"set on {applied['surface']} in {applied['document']}: {values}")
        result = {**result, "notes": applied["notes"]}
    lines += [f"note: {n}" for n in result["notes"]]
    if result.get("plot"):
        lines.append(f"plot: {result['plot']}")
    return "\n".join(lines)
