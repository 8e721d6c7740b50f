# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of SimilarityStudy objects: its icon, and its task panel on a double
click; a study draws nothing of its own (its surface's faces are drawn by the surface)."""
from .view_provider_base import DrawsNothing, EditsInTaskPanel


class ViewProviderSimilarityStudy(EditsInTaskPanel, DrawsNothing):
    ICON = "HaptiCAD_SimilarityStudy"

    def task_panel(self, obj):
        from .task_panel_similarity import SimilarityTaskPanel

        return SimilarityTaskPanel(obj)
