# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of StiffnessStudy objects: its icon, and its task panel on a double
click; a study draws nothing of its own (its surface's faces are drawn by the surface)."""
from .view_provider_base import DrawsNothing, EditsInTaskPanel


class ViewProviderStiffnessStudy(EditsInTaskPanel, DrawsNothing):
    ICON = "HaptiCAD_Study"

    def task_panel(self, obj):
        from .task_panel_study import StudyTaskPanel

        return StudyTaskPanel(obj)
