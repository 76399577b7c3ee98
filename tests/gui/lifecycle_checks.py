# SPDX-License-Identifier: LGPL-2.1-or-later
"""GUI checks of a document's life cycle (called by gui_test.py, ``g`` is the gui_test
module for its helpers).

A Planarized object made and recomputed at once, as the Planarize panel's OK and a macro
do: the live re-solve its new view provider asked for (attaching it passes every property
to ``updateData``) ran after that recompute, which had solved it already, and solved it a
second time, leaving the PanelSet made from it marked for recompute although nothing had
changed. A PanelSet the designer hid (to look at its mesh) was shown again by every
recompute of it; Part objects stay as they were left.
"""

import time

from ui_checks import settle


def recompute_and_settle(doc):
    """Recompute ``doc``, then let the live re-solves it left pending run (30 s at most)."""
    import FreeCADGui as Gui

    from facetwb import live_parameters

    doc.recompute()
    end = time.monotonic() + 30
    while live_parameters.pending() and time.monotonic() < end:
        Gui.updateGui()
        time.sleep(0.02)
    settle(10)


def check_made_and_recomputed_solves_once(check, g):
    import FreeCAD as App
    import FreeCADGui as Gui

    import facet
    import facetwb
    from facetwb import live_parameters

    doc = App.newDocument("MadeAndRecomputed")
    control = facetwb.make_polymesh(facet.read_mesh(g.MESH), label="control")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    panels = facetwb.make_panelset(result, thickness=0.5, gap=0.0)  # (a 1 mm mesh)
    panels.Tolerance = 1e-2  # the result is planar to 1e-3 only
    solves = []
    original = facet.planarize

    def slow(*args, **kwargs):
        # a solve longer than the live delay, the event loop running meanwhile (as the
        # progress dialog runs it)
        solves.append(1)
        end = time.monotonic() + 2 * live_parameters.DELAY_MS / 1000.0
        while time.monotonic() < end:
            Gui.updateGui()
            time.sleep(0.01)
        return original(*args, **kwargs)

    facet.planarize = slow
    try:
        recompute_and_settle(doc)
    finally:
        facet.planarize = original
    check(len(solves) == 1, f"a Planarized made and recomputed at once is solved once "
                            f"({len(solves)} solves)")
    check([o.State for o in (result, panels)] == [["Up-to-date"]] * 2
          and result.isValid() and panels.isValid(),
          f"and it and its PanelSet are up to date ({result.State}, {panels.State})")
    App.closeDocument(doc.Name)


def check_expression_change_solves_once(check, g):
    """A Planarized whose Tolerance is a spreadsheet cell's: a new value in the cell and a
    Recompute solve it once. The expression set the Tolerance during the recompute, just
    before the solve that used it, and that change was taken for one made during the
    recompute: solved a second time after it."""
    import FreeCAD as App

    import facet
    import facetwb

    doc = App.newDocument("ExpressionTolerance")
    control = facetwb.make_polymesh(facet.read_mesh(g.MESH), label="control")
    result = facetwb.make_planarized(control, tolerance=1e-3)
    sheet = doc.addObject("Spreadsheet::Sheet", "Spreadsheet")
    sheet.set("A1", "0.001")
    sheet.setAlias("A1", "tolerance")
    result.setExpression("Tolerance", "Spreadsheet.tolerance")
    solves = []
    original = facet.planarize

    def counted(*args, **kwargs):
        solves.append(1)
        return original(*args, **kwargs)

    def recompute():
        del solves[:]
        recompute_and_settle(doc)
        return len(solves)

    facet.planarize = counted
    try:
        recompute()
        sheet.set("A1", "0.002")
        count = recompute()
    finally:
        facet.planarize = original
    check(count == 1 and abs(result.Tolerance - 0.002) < 1e-12
          and result.State == ["Up-to-date"] and result.isValid(),
          f"a Tolerance bound to a spreadsheet cell, the cell changed: solved once "
          f"({count} solves, Tolerance {result.Tolerance}, {result.State})")
    App.closeDocument(doc.Name)


def check_hidden_panels_stay_hidden(check, g):
    import FreeCAD as App

    import facet
    import facetwb

    doc = App.newDocument("HiddenPanels")
    control = facetwb.make_polymesh(facet.read_mesh(g.MESH), label="control")
    panels = facetwb.make_panelset(control, thickness=0.5, gap=0.0)  # (a 1 mm mesh)
    panels.Tolerance = 1.0  # (the hypar as it is)
    doc.recompute()
    check(panels.isValid() and panels.ViewObject.Visibility,
          f"a new PanelSet is shown ({panels.getStatusString()})")
    panels.ViewObject.Visibility = False
    panels.Thickness = 0.6
    doc.recompute()
    check(panels.isValid() and not panels.ViewObject.Visibility,
          "a PanelSet hidden by the designer stays hidden when it recomputes")
    panels.OnePerPanel = True
    doc.recompute()
    children = list(panels.PanelObjects)
    check(children and all(c.ViewObject.Visibility for c in children)
          and not panels.ViewObject.Visibility,
          "OnePerPanel: the panels' objects shown, the compound hidden")
    panels.OnePerPanel = False
    doc.recompute()
    settle(5)
    check(not panels.PanelObjects and panels.ViewObject.Visibility,
          "OnePerPanel off: the compound shown again")
    App.closeDocument(doc.Name)


def run(check, out_dir, g):
    check_made_and_recomputed_solves_once(check, g)
    check_expression_change_solves_once(check, g)
    check_hidden_panels_stay_hidden(check, g)
