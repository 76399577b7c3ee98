# SPDX-License-Identifier: LGPL-2.1-or-later
"""The workbench's resources: every command has an SVG icon, every .ui field a tooltip,
every form field and command string is in the translation template (no FreeCAD needed)."""

import ast
import glob
import os
import xml.etree.ElementTree as ET

import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
UI = sorted(glob.glob(os.path.join(ROOT, "resources", "ui", "*.ui")))
TS = os.path.join(ROOT, "resources", "translations", "Facet.ts")
INPUTS = {"QLineEdit", "QSpinBox", "QDoubleSpinBox", "QComboBox", "QCheckBox",
          "Gui::QuantitySpinBox"}


def commands():
    tree = ast.parse(open(os.path.join(ROOT, "workbench", "facetwb", "commands",
                                       "__init__.py")).read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and node.targets[0].id == "COMMANDS":
            return ast.literal_eval(node.value)
    raise AssertionError("no COMMANDS list")


def ts_sources():
    root = ET.parse(TS).getroot()
    return {(c.findtext("name"), m.findtext("source"))
            for c in root.iter("context") for m in c.iter("message")}


def test_every_command_has_a_valid_svg_icon():
    for name in commands():
        path = os.path.join(ROOT, "resources", "icons", name + ".svg")
        assert os.path.isfile(path), f"{name} has no icon"
        root = ET.parse(path).getroot()
        assert root.tag.endswith("svg") and root.get("viewBox") == "0 0 64 64", path


@pytest.mark.parametrize("path", UI, ids=os.path.basename)
def test_every_field_has_a_tooltip_and_is_translatable(path):
    sources = {source for _context, source in ts_sources()}
    fields = 0
    for widget in ET.parse(path).getroot().iter("widget"):
        if widget.get("class") not in INPUTS:
            continue
        fields += 1
        tip = widget.find("property[@name='toolTip']/string")
        assert tip is not None and tip.text, f"{widget.get('name')} in {path} has no tooltip"
        assert tip.text in sources, f"{widget.get('name')}'s tooltip is not in Facet.ts: " \
                                    "run make translations"
    assert fields >= 1


def test_every_command_string_is_in_the_template():
    pairs = ts_sources()
    for path in glob.glob(os.path.join(ROOT, "workbench", "facetwb", "commands", "*.py")):
        for node in ast.walk(ast.parse(open(path).read())):
            if (isinstance(node, ast.Call) and getattr(node.func, "id", "") == "QT_TRANSLATE_NOOP"):
                context, text = (ast.literal_eval(arg) for arg in node.args)
                assert (context, text) in pairs, f"{path}: {text[:40]!r} is not in Facet.ts: " \
                                                 "run make translations"
    contexts = {context for context, _source in pairs}
    assert set(commands()) <= contexts, "a command's strings are missing from Facet.ts"


def test_documents_show_screenshots_taken_by_the_gui_test():
    import re

    makefile = open(os.path.join(ROOT, "Makefile")).read()
    listed = re.search(r"SCREENSHOTS = ((?:[\w ]|\\\n)+)", makefile).group(1).split()
    listed = [name for name in listed if name != "\\"]
    gui_sources = "".join(open(p).read() for p in glob.glob(os.path.join(ROOT, "tests", "gui",
                                                                           "*.py")))
    for name in listed:
        assert f'"{name}.png"' in gui_sources, f"{name}.png is not taken by tests/gui"
    for doc in ("docs/tutorial.md", "README.md"):
        text = open(os.path.join(ROOT, doc)).read()
        for image in re.findall(r"\(((?:docs/)?images/[\w.]+\.png)\)", text):
            name = os.path.basename(image)[:-4]
            assert name in listed, f"{doc} shows {image}, which make screenshots does not copy"
            assert os.path.isfile(os.path.join(ROOT, "docs", "images", name + ".png")), \
                f"{doc}: docs/images/{name}.png is missing: run make screenshots"
