# SPDX-License-Identifier: GPL-3.0-or-later
"""The lateral force of a servo-loop trace split into friction and texture as felt.

A trace (a structured array of _core TraceSample fields, or any with the four below)
holds the friction and texture forces as the renderer made them, before the device's
force limit; ``tangential_force_n`` is what was sent. Where the renderer clamped the
force, the two are scaled down together so that they add up to the lateral force sent.
No GUI; cheap (a few array operations), not for the servo thread.
"""
import numpy as np

from . import _core


def felt_lateral_parts(trace):
    """{"friction_force_n", "texture_force_n"} (N, one value per sample) of ``trace`` as
    felt. ``trace`` needs the fields friction_force_n, texture_force_n,
    tangential_force_n and flags; samples not clamped (no FLAG_FORCE_CLAMPED, or sent at
    least what was rendered) are returned as rendered."""
    friction = np.asarray(trace["friction_force_n"], float)
    texture = np.asarray(trace["texture_force_n"], float)
    lateral = friction + texture
    sent = np.asarray(trace["tangential_force_n"], float)
    clamped = ((np.asarray(trace["flags"]) & _core.FLAG_FORCE_CLAMPED) != 0) & (lateral > sent)
    factor = np.where(clamped, sent / np.where(lateral > 0, lateral, 1.0), 1.0)
    return {"friction_force_n": friction * factor, "texture_force_n": texture * factor}
