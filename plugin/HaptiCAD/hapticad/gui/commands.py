# SPDX-License-Identifier: GPL-3.0-or-later
"""Registers every HaptiCAD command; lists what goes in the toolbar and the menu."""
from . import command_feel, command_overlay, command_preferences, command_similarity, command_study, command_surface

STUDIES = [command_study.NAME, command_similarity.NAME]
TOOLBAR = [command_surface.NAME, command_surface.EDIT_NAME, *STUDIES, "Separator", command_overlay.NAME,
           command_overlay.COLOUR_NAME, "Separator", command_feel.NAME]
MENU = [command_surface.NAME, command_surface.EDIT_NAME, *STUDIES, "Separator", command_overlay.NAME,
        command_overlay.COLOUR_NAME, "Separator", command_feel.NAME, "Separator", command_preferences.NAME]
