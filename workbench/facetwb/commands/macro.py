# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run a command's work as macro lines inside one undo transaction."""

import FreeCAD as App
import FreeCADGui as Gui


def run_as_macro(doc, title, lines, modules=("facetwb",)):
    """Run ``lines`` through Gui.doCommand (so they are recorded in macros and shown in the
    Python console) inside the undo transaction ``title``.

    On an exception the transaction is aborted (the document is left as it was), the error is
    printed as one line in the report view and False is returned.
    """
    doc.openTransaction(title)
    try:
        for module in modules:
            Gui.addModule(module)
        for line in lines:
            Gui.doCommand(line)
    except Exception as error:  # noqa: BLE001 - any failure must leave the document clean
        doc.abortTransaction()
        App.Console.PrintError(f"Facet: {title} failed: {error}\n")
        return False
    doc.commitTransaction()
    return True


def object_expression(obj):
    """Python expression that finds ``obj`` again when a macro replays."""
    return f'FreeCAD.getDocument("{obj.Document.Name}").getObject("{obj.Name}")'
