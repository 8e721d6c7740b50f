# SPDX-License-Identifier: GPL-3.0-or-later
# FreeCAD runs this file at start-up, with or without a GUI. HaptiCAD registers no
# importers; its objects are created through `import HaptiCAD`.
