# SPDX-License-Identifier: GPL-3.0-or-later
"""FreeCAD GUI code of the workbench: view providers, commands, task panels.

Only this subpackage imports FreeCADGui; the logic it calls lives one level up.
"""
