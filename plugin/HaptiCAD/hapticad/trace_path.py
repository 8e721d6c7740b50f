# SPDX-License-Identifier: GPL-3.0-or-later
"""How far the proxy slid over given faces in a servo-loop trace: what a finger has
stroked of a texture (a grating is felt by moving over it, not by resting on it).

A trace is a structured array of _core TraceSample fields (or any with ``proxy_m``,
``cad_face`` and ``flags``). No GUI; a few array operations, not for the servo thread.
"""
import numpy as np

from . import _core


def slid_mm(trace, faces):
    """Path length (mm) of the proxy between consecutive samples of ``trace`` that both
    touch one of ``faces`` (CAD face ids). The proxy, not the device: pressing deeper or
    dragging within the friction cone moves the device, not the finger on the surface.
    The step across two drains of the loop's trace is not seen (one tick a drain)."""
    if len(trace) < 2 or not len(faces):
        return 0.0
    touching = ((np.asarray(trace["flags"]) & _core.FLAG_CONTACT) != 0) & np.isin(trace["cad_face"], faces)
    steps = np.linalg.norm(np.diff(np.asarray(trace["proxy_m"], float), axis=0), axis=1)
    return float(steps[touching[1:] & touching[:-1]].sum()) * 1e3
