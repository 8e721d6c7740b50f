# SPDX-License-Identifier: GPL-3.0-or-later
"""The texture fit's options (texture_fit.fit_files, `hapticad fit-texture`, the surface
panel): their defaults, as seed 001 §III ran the fit, and the ranges offered. The core
checks them again (TextureFitOptions). No imports: the CLI reads these without the core.
"""
DEFAULT_TOLERANCE_PERCENT = 2.5  # how far a section's speed may stray from its target
TOLERANCE_RANGE_PERCENT = (0.1, 25.0)
DEFAULT_LOWPASS_HZ = 1000.0  # first-order low-pass on the force, as the paper's rig; 0: none
LOWPASS_RANGE_HZ = (0.0, 20000.0)
DEFAULT_HARMONICS = 3  # harmonic peaks fitted, as the paper
HARMONICS_RANGE = (2, 8)
DEFAULT_MIN_PERIODS = 6  # the shortest section, in periods of the grating
# no fewer than 6 periods make a spectrum (the core's floor); more than 100000 is longer
# than any rig's recording
MIN_PERIODS_RANGE = (6, 100000)
MAX_MIN_PERIODS = MIN_PERIODS_RANGE[1]
