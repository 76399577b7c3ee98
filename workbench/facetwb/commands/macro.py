# SPDX-License-Identifier: LGPL-2.1-or-later
"""Run a command's work as macro lines inside one undo transaction."""

import FreeCAD as App
import FreeCADGui as Gui


def run_as_macro(doc, title, lines, modules=("facetwb",), keep=None):
    """Run ``lines`` through Gui.doCommand (so they are recorded in macros and shown in the
    Python console) inside the undo transaction ``title``.

    ``keep()``, when given, is asked after the lines ran: False aborts the transaction (the
    lines changed nothing to undo: an import cancelled), and True is still returned.

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
    if keep is not None and not keep():
        doc.abortTransaction()
        return True
    doc.commitTransaction()
    return True


def object_expression(obj):
    """Python expression that finds ``obj`` again when a macro replays."""
    return f'FreeCAD.getDocument("{obj.Document.Name}").getObject("{obj.Name}")'


def selected(test):
    """The selected objects for which ``test(obj)`` holds, in selection order."""
    return [obj for obj in Gui.Selection.getSelection() if test(obj)]


def derive(doc, title, lines, is_result, summary, select=False):
    """Run ``lines`` and a recompute of ``doc`` as the macro ``title`` (run_as_macro), then
    print ``summary(obj)`` for each new object for which ``is_result(obj)`` holds: in the
    report view's message colour when it is valid, as an error when not.

    With ``select`` the new objects become the selection. Returns them, or None when the
    macro failed (the document is then as it was).
    """
    before = set(doc.Objects)
    lines = list(lines) + [f'FreeCAD.getDocument("{doc.Name}").recompute()']
    if not run_as_macro(doc, title, lines):
        return None
    made = [obj for obj in doc.Objects if obj not in before and is_result(obj)]
    for obj in made:
        printer = App.Console.PrintMessage if obj.isValid() else App.Console.PrintError
        printer(summary(obj) + "\n")
    if select:
        Gui.Selection.clearSelection()
        for obj in made:
            Gui.Selection.addSelection(obj)
    return made
