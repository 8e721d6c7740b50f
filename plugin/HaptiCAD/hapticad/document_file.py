# SPDX-License-Identifier: GPL-3.0-or-later
"""Opening a .FCStd file to read it, checked first: FreeCAD opens a damaged file without
a word and reads what it can, so what is missing looked gone from the design (every face
reference broken, a study absent) rather than the file damaged. ``hapticad feel``,
``cohort``, ``similarity``, ``fit-texture --apply`` and ``demo`` open their documents so.
"""
import os
import zipfile
import zlib
from xml.etree import ElementTree


def document_xml(path):
    """The parsed Document.xml of the .FCStd at ``path``. Raises ValueError naming the file
    when it is missing, not a zip archive (cut short in a copy or a download: FreeCAD opened
    it as parts without their shapes, every face looking gone), or holds no readable
    Document.xml (FreeCAD opened that as objects without their properties)."""
    if not os.path.exists(path):
        raise ValueError(f"{path}: no such file")
    if not zipfile.is_zipfile(path):
        raise ValueError(f"{path}: not a FreeCAD document, or a damaged one (cut short in a copy or "
                         "download?): it is not a readable zip archive")
    try:
        with zipfile.ZipFile(path) as archive:
            return ElementTree.fromstring(archive.read("Document.xml"))
    except KeyError:
        raise ValueError(f"{path}: not a FreeCAD document: the archive holds no Document.xml") from None
    except (ElementTree.ParseError, zipfile.BadZipFile, zlib.error) as exc:
        raise ValueError(f"{path}: a damaged FreeCAD document: its Document.xml cannot be read ({exc})") from None


def open_document(App, path):
    """The document at ``path`` opened in FreeCAD (``App``), once document_xml has read it
    whole. Raises ValueError, with nothing left open, as document_xml does, or when this
    FreeCAD could not load some of its objects (FreeCAD leaves out, without a word, an
    object whose type no loaded workbench makes: read on, a part is missed; saved, it is
    lost)."""
    xml = document_xml(path)
    doc = App.openDocument(os.path.abspath(path))
    held = {o.Name for o in doc.Objects}
    lost = [f"{o.get('name')} ({o.get('type')})" for o in xml.iterfind("./Objects/Object")
            if o.get("type") and o.get("name") not in held]
    if lost:
        App.closeDocument(doc.Name)
        raise ValueError(f"{path}: this FreeCAD could not load {len(lost)} of its objects: {', '.join(lost)} "
                         "(a workbench it needs is missing); nothing was read or changed")
    return doc
