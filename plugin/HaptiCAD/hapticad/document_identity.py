# SPDX-License-Identifier: GPL-3.0-or-later
"""What tells a saved document from another when its path has changed (moved or renamed
in a file manager): for the journals (study_journal, run_journal), which find the files a
document left under its earlier path.

FreeCAD's ``Uid`` alone does not: it is made once and kept through Save As and Save a
Copy, so every document saved from one template shares it. With it, the time of the
document's last save (``LastModifiedDate``, to the second, kept in the file and unchanged
by opening it) tells the documents saved from one template apart, and a moved file keeps
both. App-only."""


def identity(doc):
    """The fields a journal writes about ``doc`` (a saved FreeCAD document), as they are now."""
    return {"document_uid": doc.Uid, "document_saved": doc.LastModifiedDate}


def same_document(state, doc):
    """True when ``state`` (a journal's JSON) was written for ``doc`` as it was last saved:
    the same Uid and the same last save. A journal written before the save time was kept
    (none recorded) never matches."""
    return (isinstance(state, dict) and bool(state.get("document_saved"))
            and (state.get("document_uid"), state.get("document_saved")) == (doc.Uid, doc.LastModifiedDate))
