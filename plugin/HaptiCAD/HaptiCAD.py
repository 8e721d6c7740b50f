# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's scripting API, in FreeCAD's style.

    import HaptiCAD
    surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS",
                                    roughness_category=3)
    HaptiCAD.reference_status(surface)  # [("Box", "Face6", "ok"), ...]
"""
from hapticad.surface_object import (  # noqa: F401
    PATTERNS,
    is_haptic_surface,
    make_surface,
    reference_pairs,
    reference_status,
    surfaces_of,
)
from hapticad.vibration_object import is_haptic_vibration, make_vibration, vibrations_of  # noqa: F401
from hapticad.stiffness_study import make_study, record_preference, studies_of  # noqa: F401
from hapticad.similarity_study import make_similarity_study, similarity_studies_of  # noqa: F401
