# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD: tag CAD faces with physical surface properties and feel them.

This package holds the workbench's logic. Modules that need no GUI import no
FreeCADGui and are tested headless; GUI code lives in ``hapticad.gui``. The physics is
in the C++ core, reached through ``hapticad._core``.
"""
import os

__version__ = "0.1.0"

PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
MOD_DIR = os.path.dirname(PACKAGE_DIR)
RESOURCES_DIR = os.path.join(MOD_DIR, "resources")
ICONS_DIR = os.path.join(RESOURCES_DIR, "icons")
EXAMPLES_DIR = os.path.join(RESOURCES_DIR, "examples")
MATERIALS_FILE = os.path.join(RESOURCES_DIR, "materials", "materials.csv")


def icon(name):
    """Path of an icon shipped with the workbench, e.g. icon("HaptiCAD_Surface")."""
    return os.path.join(ICONS_DIR, name + ".svg")
