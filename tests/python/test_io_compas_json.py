# SPDX-License-Identifier: LGPL-2.1-or-later
"""Reading compas, RhinoVAULT and compas_tno JSON meshes."""

import json

import numpy as np
import pytest

from facet import MeshError
from facet.io import read_compas_json, read_mesh, read_off


def test_old_compas_format_matches_the_off_tube(data_dir):
    mesh = read_compas_json(data_dir / "tubemesh2.json")
    tube = read_off(data_dir / "tubemesh.off")  # the same mesh, rounded to 3 decimals
    assert (mesh.n_vertices, mesh.n_faces) == (200, 171)
    assert mesh.faces() == tube.faces()
    assert np.abs(mesh.vertices - tube.vertices).max() <= 0.0005 + 1e-12
    assert mesh.vertices[0].tolist() == [
        -11.708264391175128, -2.3646505090427805, 2.3507584996633533
    ]
    assert mesh.info["format"] == "compas-json"
    assert mesh.info["openings_skipped"] == 0


def test_compas_tno_form_diagram(data_dir):
    mesh = read_mesh(data_dir / "crossvault_form.json")
    assert (mesh.n_vertices, mesh.n_faces) == (225, 224)
    assert mesh.info["dtype"] == "compas_tno.diagrams/FormDiagram"
    assert mesh.info["face_keys"][:3] == [1, 2, 3]  # face keys start at 1 in this file
    assert sorted(np.unique(mesh.degrees).tolist()) == [3, 4]
    assert mesh.info["support_vertices"][:2] == [0, 28]
    assert mesh.vertices[0].tolist() == [0.0, 0.0, 2.550395006756676]


def test_unused_vertices_are_dropped(data_dir):
    mesh = read_mesh(data_dir / "hex_mesh_min_surface.json")
    assert (mesh.n_vertices, mesh.n_faces) == (102, 37)
    assert mesh.info["unused_vertices_dropped"] == 558
    assert set(mesh.degrees.tolist()) == {6}
    keys = mesh.info["vertex_keys"]
    assert keys == sorted(keys)
    assert mesh.validate()["n_isolated_vertices"] == 0
    raw = json.loads((data_dir / "hex_mesh_min_surface.json").read_text())["data"]["vertex"]
    first = raw[str(keys[0])]
    assert mesh.vertices[0].tolist() == [first["x"], first["y"], first["z"]]


def test_rhinovault_session_reads_the_thrust_diagram_without_openings(data_dir):
    mesh = read_mesh(data_dir / "examples_cross_vault_6.json")
    assert mesh.info["item"] == "ThrustDiagram"
    assert mesh.info["openings_skipped"] == 4
    assert mesh.info["opening_keys"] == [121, 122, 123, 124]
    assert mesh.n_faces == 120
    assert mesh.vertices[:, 2].max() == pytest.approx(3.535509717684376)
    assert 121 not in mesh.info["face_keys"]


def test_rhinovault_session_other_item_by_name(data_dir):
    form = read_compas_json(data_dir / "examples_cross_vault_6.json", item="FormDiagram")
    assert form.info["item"] == "FormDiagram"
    assert np.all(form.vertices[:, 2] == 0.0)
    with pytest.raises(MeshError, match=r"no mesh named 'Roof' .*found: .*ThrustDiagram"):
        read_compas_json(data_dir / "examples_cross_vault_6.json", item="Roof")


def test_old_tna_form_diagram(data_dir):
    mesh = read_mesh(data_dir / "formdiagram.json")
    assert (mesh.n_vertices, mesh.n_faces) == (121, 100)


def compas2(vertices, faces, facedata=None, **defaults):
    data = {
        "default_vertex_attributes": {"x": 0.0, "y": 0.0, "z": 0.0},
        "default_face_attributes": {},
        "vertex": vertices,
        "face": faces,
        "facedata": facedata or {},
    }
    for key, value in defaults.items():
        data[key].update(value)
    return json.dumps({"dtype": "compas.datastructures/Mesh", "data": data}, indent=1)


def test_keys_out_of_order_defaults_and_openings(write_file):
    text = compas2(
        {
            "10": {"x": 1.0, "y": 1.0},  # z from the default
            "2": {"x": 0.0, "y": 0.0, "z": 0.5},
            "7": {"x": 1.0, "y": 0.0, "z": 0.0},
            "40": {"x": 9.0, "y": 9.0, "z": 9.0},  # used by no kept face
            "3": {"x": 0.0, "y": 1.0, "z": 0.0},
        },
        {"5": [2, 7, 10, 3], "1": ["2", "7", "40"]},
        facedata={"1": {"_is_loaded": False}},
        default_vertex_attributes={"z": 2.0},
    )
    mesh = read_compas_json(write_file("keys.json", text))
    assert mesh.info["vertex_keys"] == [2, 3, 7, 10]
    assert mesh.vertices.tolist() == [[0, 0, 0.5], [0, 1, 0], [1, 0, 0], [1, 1, 2.0]]
    assert mesh.faces() == [[0, 2, 3, 1]]
    assert mesh.info["face_keys"] == [5]
    assert mesh.info["openings_skipped"] == 1
    assert mesh.info["unused_vertices_dropped"] == 1


def test_openings_by_default_attribute(write_file):
    text = compas2(
        {"0": {"x": 0}, "1": {"x": 1}, "2": {"y": 1}, "3": {"x": 1, "y": 1}},
        {"0": [0, 1, 3, 2], "1": [0, 1, 3]},
        facedata={"0": {"_is_loaded": True}},
        default_face_attributes={"_is_loaded": False},
    )
    mesh = read_compas_json(write_file("defaults.json", text))
    assert mesh.info["face_keys"] == [0]
    assert mesh.info["opening_keys"] == [1]


def test_all_faces_openings(write_file):
    text = compas2({"0": {}, "1": {"x": 1}, "2": {"y": 1}}, {"0": [0, 1, 2]},
                   facedata={"0": {"_is_loaded": False}})
    with pytest.raises(MeshError, match=r"no faces \(all 1 faces are openings\)"):
        read_compas_json(write_file("x.json", text))


def test_invalid_json_names_the_line(write_file):
    path = write_file("x.json", '{\n  "vertex": {\n    "0": {"x": 1,}\n  }\n}\n')
    with pytest.raises(MeshError) as caught:
        read_compas_json(path)
    assert caught.value.line == 3
    assert str(caught.value).startswith(f"{path}: line 3: not valid JSON")


def test_json_without_a_mesh(write_file):
    with pytest.raises(MeshError, match="no compas mesh found"):
        read_compas_json(write_file("x.json", '{"settings": {}}'))


def test_face_with_unknown_vertex_key(write_file):
    text = compas2({"0": {}, "1": {"x": 1}, "2": {"y": 1}}, {"4": [0, 1, 9]})
    with pytest.raises(MeshError, match=r"face key '4' uses vertex key '9', which the file"):
        read_compas_json(write_file("x.json", text))


def test_vertex_without_a_coordinate(write_file):
    text = json.dumps({"vertex": {"0": {"x": 0, "y": 0}, "1": {}, "2": {}},
                       "face": {"0": [0, 1, 2]}, "dva": {"x": 0.0, "y": 0.0}})
    with pytest.raises(MeshError, match=r"vertex key '0' has no z coordinate"):
        read_compas_json(write_file("x.json", text))


def test_face_with_two_vertices(write_file):
    text = compas2({"0": {}, "1": {"x": 1}}, {"3": [0, 1]})
    with pytest.raises(MeshError, match=r"face key '3' has 2 vertices \(at least 3 needed\)"):
        read_compas_json(write_file("x.json", text))


def test_non_finite_coordinate(write_file):
    text = compas2({"0": {"x": float("nan")}, "1": {"x": 1}, "2": {"y": 1}}, {"0": [0, 1, 2]})
    with pytest.raises(MeshError, match=r"vertex 0 has a non-finite coordinate \(vertex key 0"):
        read_compas_json(write_file("x.json", text))


def test_repeated_vertex_names_the_compas_face_key(write_file):
    text = compas2(
        {"0": {}, "1": {"x": 1}, "2": {"x": 1, "y": 1}, "3": {"y": 1}},
        {"0": [0, 1, 2], "8": [0, 1, 2, 1]},
    )
    with pytest.raises(MeshError) as caught:
        read_compas_json(write_file("x.json", text))
    assert caught.value.face == 1
    assert "face key 8" in str(caught.value)
    assert caught.value.status_name == "FACET_ERROR_REPEATED_VERTEX"


@pytest.mark.parametrize("section", ["vertex", "face"])
def test_keys_that_name_the_same_element_are_refused(write_file, section):
    # "1" and "01" (or 1.0) are one key once normalised: one record would replace the other
    vertices = {"0": {}, "1": {"x": 1}, "2": {"y": 1}, "3": {"x": 1, "y": 1}}
    faces = {"0": [0, 1, 3], "1": [0, 3, 2]}
    if section == "vertex":
        vertices["01"] = {"x": 5, "y": 5, "z": 5}
    else:
        faces["01"] = [0, 1, 2]
    with pytest.raises(MeshError, match=rf"{section} keys '1' and '01' both name {section} 1"):
        read_compas_json(write_file("x.json", compas2(vertices, faces)))


@pytest.mark.parametrize("x, shown", [("1_000", "1_000"), ("\u0661", "\u0661"), (10**400, "1000")])
def test_coordinates_only_as_mesh_files_write_numbers(write_file, x, shown):
    # "1_000" was read as 1000 and an Arabic-Indic digit as 1 (the OBJ reader refuses them);
    # a 401-digit integer ended in an OverflowError traceback
    text = compas2({"0": {"x": x}, "1": {"x": 1}, "2": {"y": 1}}, {"0": [0, 1, 2]})
    with pytest.raises(MeshError, match=f"vertex key '0': cannot read '{shown}"):
        read_compas_json(write_file("x.json", text))


def test_a_byte_order_mark_is_read_past(tmp_path):
    # .NET tools, Grasshopper's C# and PowerShell 5 write UTF-8 JSON with a BOM: refused with
    # "Unexpected UTF-8 BOM"
    text = compas2({"0": {}, "1": {"x": 1}, "2": {"y": 1}}, {"0": [0, 1, 2]})
    path = tmp_path / "bom.json"
    path.write_bytes(b"\xef\xbb\xbf" + text.encode())
    assert read_compas_json(path).n_faces == 1


def test_keys_with_digit_separators_are_not_numbers(write_file):
    # key "1_0" became "10"
    text = compas2({"0": {}, "1_0": {"x": 1}, "2": {"y": 1}}, {"0": [0, "1_0", 2]})
    mesh = read_compas_json(write_file("x.json", text))
    assert "1_0" in mesh.info["vertex_keys"] and "10" not in mesh.info["vertex_keys"]
