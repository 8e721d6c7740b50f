# SPDX-License-Identifier: GPL-3.0-or-later
"""Make FreeCAD importable from a plain ``/usr/bin/python3`` (the ``hapticad`` CLI).

Inside FreeCAD this does nothing. Debian 12 puts FreeCAD's Python modules (FreeCAD,
Part, Mesh, MeshPart) in /usr/lib/freecad-python3/lib and its workbenches in
/usr/lib/freecad/Mod; set HAPTICAD_FREECAD_LIB and HAPTICAD_FREECAD_MOD to point
elsewhere.

Imported from there, FreeCAD looks for its workbenches beside that library folder
(/usr/lib/freecad-python3/Mod, which Debian does not have): a document's PartDesign
Body, Pad and Pocket were then left out without a word when it opened, and a document
saved after that had lost them. So the workbenches' folders go on sys.path as FreeCAD's
own start-up puts them (the folder and each workbench in it).
"""
import os
import sys

FREECAD_LIB = os.environ.get("HAPTICAD_FREECAD_LIB", "/usr/lib/freecad-python3/lib")
FREECAD_MOD = os.environ.get("HAPTICAD_FREECAD_MOD", "/usr/lib/freecad/Mod")


def _workbench_folders(mod):
    """``mod`` and each workbench folder in it, as FreeCAD's start-up adds them."""
    if not os.path.isdir(mod):
        return []
    return [mod] + sorted(os.path.join(mod, name) for name in os.listdir(mod)
                          if os.path.isdir(os.path.join(mod, name)))


def ensure_freecad():
    """Import and return the FreeCAD module, adding its library folder if needed.

    Importing FreeCAD runs its start-up, which puts every Mod folder it knows first on
    sys.path, an installed HaptiCAD among them: this Mod folder goes back in front, so
    `import HaptiCAD` loads the same copy as this package, never a stale install."""
    from . import MOD_DIR

    try:
        import FreeCAD  # noqa: F401  (already importable: inside FreeCAD)
    except ImportError:
        for folder in [FREECAD_LIB, *_workbench_folders(FREECAD_MOD)]:
            if folder not in sys.path:
                sys.path.append(folder)
        try:
            import FreeCAD  # noqa: F401
        except ImportError as exc:
            raise RuntimeError(
                f"cannot import FreeCAD from {FREECAD_LIB}: install Debian's 'freecad' "
                "package (packaging/install-deps.sh) or set HAPTICAD_FREECAD_LIB"
            ) from exc
    import FreeCAD

    if sys.path[0] != MOD_DIR:
        sys.path[:] = [MOD_DIR] + [p for p in sys.path if p != MOD_DIR]
    stale = sys.modules.get("HaptiCAD")
    if stale is not None and not os.path.abspath(stale.__file__).startswith(MOD_DIR + os.sep):
        del sys.modules["HaptiCAD"]
    return FreeCAD
