# SPDX-License-Identifier: GPL-3.0-or-later
"""Make FreeCAD importable from a plain ``/usr/bin/python3`` (the ``hapticad`` CLI).

Inside FreeCAD this does nothing. Debian 12 puts FreeCAD's Python modules (FreeCAD,
Part, Mesh, MeshPart) in /usr/lib/freecad-python3/lib; set HAPTICAD_FREECAD_LIB to
point elsewhere.
"""
import os
import sys

FREECAD_LIB = os.environ.get("HAPTICAD_FREECAD_LIB", "/usr/lib/freecad-python3/lib")


def ensure_freecad():
    """Import and return the FreeCAD module, adding its library folder if needed.

    Importing FreeCAD runs its start-up, which puts every Mod folder it knows first on
    sys.path, an installed HaptiCAD among them: this Mod folder goes back in front, so
    `import HaptiCAD` loads the same copy as this package, never a stale install."""
    from . import MOD_DIR

    try:
        import FreeCAD  # noqa: F401  (already importable: inside FreeCAD)
    except ImportError:
        if FREECAD_LIB not in sys.path:
            sys.path.append(FREECAD_LIB)
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
