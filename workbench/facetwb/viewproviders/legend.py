# SPDX-License-Identifier: LGPL-2.1-or-later
"""The planarity legend: a colour bar with its scale in model units, drawn over the 3D view.

It is a Coin subgraph (part of the view provider's "Planarity" display mode), so it shows
wherever the view is drawn, including ``saveImage`` renders:

- an SoAnnotation, drawn after the scene without depth test, holding its own orthographic
  camera whose view volume is the viewport: coordinates are -1 .. 1 across and up the view,
  whatever the window's size and the scene's camera;
- inside FreeCAD's SoSkipBoundingGroup, so "Fit all" ignores it, and unpickable;
- labels are SoText2 (screen-aligned, fixed pixel size), in the length unit FreeCAD shows
  for the largest value (the user's unit schema: mm for small panels' deviations, or um).
"""

import math

import FreeCAD as App
from pivy import coin

from facetwb.viewproviders import colormap

# Layout in viewport coordinates (-1 .. 1): right-hand side, below the navigation cube.
BAR_X = (0.86, 0.89)
BAR_Y = (-0.55, 0.35)
PANEL = ((0.64, -0.70), (0.92, 0.50))
TEXT_X = 0.845
TICKS = 5
TEXT_COLOR = (1.0, 1.0, 1.0)
PANEL_COLOR = (0.13, 0.14, 0.17)
FONT_SIZE = 15


def tick_labels(vmax, count=TICKS, kind="length"):
    """Labels for ``count`` evenly spaced ticks from 0 to ``vmax``, in one unit.

    kind "length": ``vmax`` in mm, shown in the unit FreeCAD's unit schema picks for it
    (an imperial schema's in inches down to a thou, then microinches);
    "angle": degrees; "ratio": plain numbers. Decimals give three significant digits at the
    top, the same for all ticks so they line up.
    """
    if kind in ("angle", "ratio"):
        unit = " deg" if kind == "angle" else ""
        if not vmax > 0.0:
            return [f"0{unit}"]
        decimals = max(0, 2 - int(math.floor(math.log10(vmax))))
        return [f"{vmax * i / (count - 1):.{decimals}f}{unit}" for i in range(count)]
    if not vmax > 0.0:
        return ["0 mm"]
    from facetwb.units import imperial, user_unit

    factor, unit = user_unit(vmax)
    top = vmax / factor
    if top < 0.1 and imperial() and vmax / 25.4 >= 1e-3:
        # an imperial schema's: inches down to a thou (0.05 in was "1270 µm")
        unit, factor, top = "in", 25.4, vmax / 25.4
    elif top < 0.1:
        # below the schema's smallest unit (nm): a planar mesh is often at picometres;
        # an imperial schema's in microinches first
        smaller = (("\u00b5in", 25.4e-6),) if imperial() else ()
        for name, size in smaller + (("\u00b5m", 1e-3), ("nm", 1e-6), ("pm", 1e-9)):
            if vmax / size >= 1.0:
                unit, factor, top = name, size, vmax / size
                break
        else:
            return [f"{vmax * i / (count - 1):.2e} mm" for i in range(count)]
    decimals = max(0, 2 - int(math.floor(math.log10(top))))
    return [f"{top * i / (count - 1):.{decimals}f} {unit}" for i in range(count)]


def _material(rgb):
    material = coin.SoMaterial()
    material.diffuseColor.setValue(*rgb)
    return material


def _text(x, y, string, justification=coin.SoText2.RIGHT):
    node = coin.SoSeparator()
    translation = coin.SoTranslation()
    translation.translation.setValue(x, y, 0.0)
    text = coin.SoText2()
    text.string.setValue(string)
    text.justification = justification
    node.addChild(translation)
    node.addChild(text)
    return node


def _skip_bounding_group():
    """FreeCAD's SoSkipBoundingGroup (excluded from "Fit all"), or a plain SoSeparator."""
    node_type = coin.SoType.fromName("SoSkipBoundingGroup")
    if node_type.isBad():
        return coin.SoSeparator()
    node = node_type.createInstance()
    node.getField("mode").set("EXCLUDE_BBOX")
    return node


class PlanarityLegend:
    """A colour bar and its labels; ``root`` goes into a display mode's scene graph."""

    def __init__(self):
        self.root = coin.SoSwitch()
        self.root.whichChild = coin.SO_SWITCH_ALL
        skip = _skip_bounding_group()
        annotation = coin.SoAnnotation()
        skip.addChild(annotation)
        self.root.addChild(skip)

        pick_style = coin.SoPickStyle()
        pick_style.style = coin.SoPickStyle.UNPICKABLE
        camera = coin.SoOrthographicCamera()
        camera.viewportMapping = coin.SoCamera.LEAVE_ALONE
        camera.position.setValue(0.0, 0.0, 1.0)
        camera.height = 2.0
        camera.aspectRatio = 1.0
        camera.nearDistance = 0.5
        camera.farDistance = 1.5
        light_model = coin.SoLightModel()
        light_model.model = coin.SoLightModel.BASE_COLOR
        font = coin.SoFont()
        font.size = FONT_SIZE
        for node in (pick_style, camera, light_model, font):
            annotation.addChild(node)

        annotation.addChild(self._panel())
        annotation.addChild(self._bar())
        annotation.addChild(self._ticks())
        self.labels = coin.SoSeparator()
        annotation.addChild(self.labels)
        self.update(0.0)

    def set_visible(self, visible):
        self.root.whichChild = coin.SO_SWITCH_ALL if visible else coin.SO_SWITCH_NONE

    def update(self, vmax, actual_max=None, title="Planarity", kind="length", reverse=False,
               extreme_name="max", note=None):
        """Label the bar for the scale 0 .. ``vmax`` (mm, degrees or a ratio: ``kind``);
        ``actual_max`` is the worst value, written under the bar as "``extreme_name`` value";
        ``reverse`` puts 0 at the top (red) end. ``note`` (instead of ``actual_max``) goes
        under the bar too, not after the title, which is as wide as the panel allows."""
        self.labels.removeAllChildren()
        self.labels.addChild(_material(TEXT_COLOR))
        labels = tick_labels(vmax, kind=kind)
        if reverse:
            labels = labels[::-1]
        for i, label in enumerate(labels):
            fraction = i / (len(labels) - 1) if len(labels) > 1 else 0.0
            y = BAR_Y[0] + fraction * (BAR_Y[1] - BAR_Y[0])
            self.labels.addChild(_text(TEXT_X, y - 0.012, label))
        self.labels.addChild(_text(BAR_X[1], BAR_Y[1] + 0.07, title))
        if actual_max is not None:
            note = f"{extreme_name} " + tick_labels(actual_max, 2, kind=kind)[-1]
        if note:
            self.labels.addChild(_text(BAR_X[1], BAR_Y[0] - 0.09, note))

    @staticmethod
    def _panel():
        (x0, y0), (x1, y1) = PANEL
        node = coin.SoSeparator()
        node.addChild(_material(PANEL_COLOR))
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, 4, [(x0, y0, -0.1), (x1, y0, -0.1), (x1, y1, -0.1),
                                      (x0, y1, -0.1)])
        faces = coin.SoFaceSet()
        faces.numVertices.setValue(4)
        node.addChild(coords)
        node.addChild(faces)
        return node

    @staticmethod
    def _bar():
        """One quad per pair of colour stops, colours per vertex: exactly the face map."""
        (x0, x1), (y0, y1) = BAR_X, BAR_Y
        stops = colormap.stop_colors()
        points, colors = [], []
        for (t0, c0), (t1, c1) in zip(stops[:-1], stops[1:]):
            ya, yb = y0 + t0 * (y1 - y0), y0 + t1 * (y1 - y0)
            points += [(x0, ya, 0.0), (x1, ya, 0.0), (x1, yb, 0.0), (x0, yb, 0.0)]
            colors += [c0, c0, c1, c1]
        node = coin.SoSeparator()
        material = coin.SoMaterial()
        material.diffuseColor.setValues(0, len(colors), colors)
        binding = coin.SoMaterialBinding()
        binding.value = coin.SoMaterialBinding.PER_VERTEX
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points), points)
        faces = coin.SoFaceSet()
        faces.numVertices.setValues(0, len(stops) - 1, [4] * (len(stops) - 1))
        for child in (binding, material, coords, faces):
            node.addChild(child)
        return node

    @staticmethod
    def _ticks():
        (x0, x1), (y0, y1) = BAR_X, BAR_Y
        points = []
        for i in range(TICKS):
            y = y0 + i / (TICKS - 1) * (y1 - y0)
            points += [(x0 - 0.008, y, 0.05), (x0, y, 0.05)]
        # Outline of the bar.
        outline = [(x0, y0, 0.05), (x1, y0, 0.05), (x1, y1, 0.05), (x0, y1, 0.05), (x0, y0, 0.05)]
        node = coin.SoSeparator()
        node.addChild(_material(TEXT_COLOR))
        coords = coin.SoCoordinate3()
        coords.point.setValues(0, len(points) + len(outline), points + outline)
        lines = coin.SoLineSet()
        counts = [2] * TICKS + [len(outline)]
        lines.numVertices.setValues(0, len(counts), counts)
        node.addChild(coords)
        node.addChild(lines)
        return node
