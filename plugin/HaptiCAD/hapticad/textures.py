# SPDX-License-Identifier: GPL-3.0-or-later
"""Viscous-grating presets of seed 001: the paper's nine experiment textures.

Each preset is (f_DC, f_vis, beta_h, alpha_h, beta_vis, alpha_vis) in the paper's
normalised units, with the values the experiment held fixed (beta_h = 0.125,
alpha_h = 2.5, beta_vis = alpha_vis = 0). The numbers come from the C++ core.
"""
from . import _core


def _preset_name(dc, vis):
    return f"Paper f_DC {dc:.3f} f_vis {vis:+.1f}"


PRESETS = {}
for _i, _dc in enumerate(_core.PAPER_DC_LEVELS):
    for _j, _vis in enumerate(_core.PAPER_VISCOSITIES):
        _p = _core.paper_preset(_i, _j)
        PRESETS[_preset_name(_dc, _vis)] = (_p.f_dc, _p.f_vis, _p.beta_h, _p.alpha_h, _p.beta_vis, _p.alpha_vis)

CHOICES = ["None", "Custom", *PRESETS]
