/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.panels: panel geometry (facet_panels). */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <string.h>

enum { N_OUT = 16 };

static PyObject *core_panels(PyObject *module, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"xyz", "face_start", "face_vertices", "thickness", "offset",
                               "gap", "edge", "flip", "tol_abs", "tol_rel", "plane", "top",
                               "bottom", "frame", "reversed", "neighbor", "dihedral", "bevel",
                               "node_deviation", "planarity", "nonplanar", "dropped", "squared",
                               "joint", "node_clash", "clash", "progress", "repair_consumed",
                               "length_unit", NULL};
    PyObject *xyz, *start, *faces, *progress = Py_None;
    PyObject *outs[N_OUT];
    for (int k = 0; k < N_OUT; ++k)
        outs[k] = Py_None;
    facet_panel_options o;
    facet_panel_options_default(&o);
    const char *offset = "outer", *edge = "square";
    int flip = 0, repair = 1;
    if (!PyArg_ParseTupleAndKeywords(
            args, kwargs, "OOO|$dsdspddOOOOOOOOOOOOOOOOOpz:panels", keywords, &xyz, &start, &faces,
            &o.thickness, &offset, &o.gap, &edge, &flip, &o.planarity_tol_abs,
            &o.planarity_tol_rel, &outs[0], &outs[1], &outs[2], &outs[3], &outs[4], &outs[5],
            &outs[6], &outs[7], &outs[8], &outs[9], &outs[10], &outs[11], &outs[12], &outs[13],
            &outs[14], &outs[15], &progress,
            &repair, &o.length_unit))
        return NULL;
    if (strcmp(offset, "outer") == 0)
        o.offset = FACET_PANEL_OFFSET_OUTER;
    else if (strcmp(offset, "inner") == 0)
        o.offset = FACET_PANEL_OFFSET_INNER;
    else if (strcmp(offset, "center") == 0)
        o.offset = FACET_PANEL_OFFSET_CENTER;
    else
        return PyErr_Format(PyExc_ValueError, "offset must be 'outer', 'inner' or 'center', not '%s'",
                            offset);
    if (strcmp(edge, "square") == 0)
        o.edge = FACET_PANEL_EDGE_SQUARE;
    else if (strcmp(edge, "bisector") == 0)
        o.edge = FACET_PANEL_EDGE_BISECTOR;
    else
        return PyErr_Format(PyExc_ValueError, "edge must be 'square' or 'bisector', not '%s'",
                            edge);
    o.flip = flip;
    o.repair_consumed = repair;
    if (progress != Py_None && !PyCallable_Check(progress)) {
        PyErr_SetString(PyExc_TypeError, "progress must be callable or None");
        return NULL;
    }
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    const Py_ssize_t nf = m.mesh.n_faces, nv = m.mesh.n_vertices;
    const Py_ssize_t nc = m.mesh.face_start[nf];
    static const char *names[N_OUT] = {"plane",    "top",      "bottom", "frame",
                                       "reversed", "neighbor", "dihedral", "bevel",
                                       "node_deviation", "planarity", "nonplanar", "dropped",
                                       "squared", "joint", "node_clash", "clash"};
    const char codes[N_OUT] = {'d', 'd', 'd', 'd', 'i', 'i', 'd',
                               'd', 'd', 'd', 'i', 'i', 'i', 'd', 'd', 'd'};
    const Py_ssize_t sizes[N_OUT] = {4 * nf, 3 * nc, 3 * nc, 12 * nf, nf, nc,
                                     nc,     nc,     nv,     nf,      nf, nc, nc, nc, nv, nf};
    Py_buffer views[N_OUT];
    void *ptrs[N_OUT];
    int got = 0;
    for (; got < N_OUT; ++got) {
        ptrs[got] = NULL;
        if (outs[got] == Py_None)
            continue;
        if (py_get_buffer(outs[got], names[got], codes[got], 1, sizes[got], &views[got]) < 0)
            break;
        ptrs[got] = views[got].buf;
    }
    PyObject *ret = NULL;
    if (got == N_OUT) {
        facet_panel_output out = {ptrs[0], ptrs[1], ptrs[2], ptrs[3], ptrs[4], ptrs[5],
                                  ptrs[6], ptrs[7], ptrs[8], ptrs[9], ptrs[10], ptrs[11], ptrs[12],
                                  ptrs[13], ptrs[14], ptrs[15]};
        py_count_progress_state ps = {progress == Py_None ? NULL : progress, NULL, NULL, NULL};
        o.progress = py_count_progress;
        o.progress_user = &ps;
        facet_panel_result r;
        memset(&r, 0, sizeof r);
        r.failed_joint_faces[0] = r.failed_joint_faces[1] = -1;
        facet_error error;
        facet_status status;
        Py_BEGIN_ALLOW_THREADS
        status = facet_panels(&m.mesh, &o, &out, &r, &error);
        Py_END_ALLOW_THREADS
        if (ps.exc_type) {
            PyErr_Restore(ps.exc_type, ps.exc_value, ps.exc_tb);
        } else if (status < 0) {
            py_raise_status(py_state(module), status, &error);
            if (r.failed_joint_faces[0] >= 0 && PyErr_Occurred()) {
                /* the joint that had to be square on both panels: its faces and
                 * overlap on the exception (joint_faces, joint_overlap) */
                PyObject *type, *value, *tb;
                PyErr_Fetch(&type, &value, &tb);
                PyErr_NormalizeException(&type, &value, &tb);
                if (value &&
                    (py_set_attr(value, "joint_faces",
                                 Py_BuildValue("(ii)", (int)r.failed_joint_faces[0],
                                               (int)r.failed_joint_faces[1])) < 0 ||
                     py_set_attr(value, "joint_overlap",
                                 PyFloat_FromDouble(r.failed_joint_overlap)) < 0)) {
                    Py_XDECREF(type);
                    Py_XDECREF(value);
                    Py_XDECREF(tb);
                } else {
                    PyErr_Restore(type, value, tb);
                }
            }
        } else {
            ret = Py_BuildValue(
                "{s:L,s:L,s:L,s:i,s:L,s:d,s:d,s:L,s:L,s:L,s:d,s:d,s:L,s:(ii),s:L,s:d,s:L,s:d,s:L,"
                "s:(ii),s:d,s:s}",
                "n_nonplanar", (long long)r.n_nonplanar,
                "n_non_manifold_edges", (long long)r.n_non_manifold_edges, "n_reversed",
                (long long)r.n_reversed, "n_components", (int)r.n_components, "worst_node",
                (long long)r.worst_node, "max_node_deviation", r.max_node_deviation,
                "max_planarity", r.max_planarity, "n_dropped_edges", (long long)r.n_dropped_edges,
                "n_squared_edges", (long long)r.n_squared_edges, "n_butt_edges",
                (long long)r.n_butt_edges,
                "narrowest_repaired_joint", r.narrowest_repaired_joint,
                "narrowest_joint", r.narrowest_joint, "narrowest_joint_vertex",
                (long long)r.narrowest_joint_vertex, "narrowest_joint_faces",
                (int)r.narrowest_joint_faces[0], (int)r.narrowest_joint_faces[1],
                "n_overlapping_joints", (long long)r.n_overlapping_joints, "clearing_gap",
                r.clearing_gap, "n_node_clashes", (long long)r.n_node_clashes,
                "deepest_node_clash", r.deepest_node_clash, "node_clash_vertex",
                (long long)r.node_clash_vertex, "node_clash_faces", (int)r.node_clash_faces[0],
                (int)r.node_clash_faces[1], "seconds", r.seconds, "warning",
                status > 0 ? error.message : "");
        }
    }
    for (int k = 0; k < got; ++k)
        if (ptrs[k])
            PyBuffer_Release(&views[k]);
    py_release_mesh(&m);
    return ret;
}

static PyMethodDef panel_methods[] = {
    {"panels", (PyCFunction)(void (*)(void))core_panels, METH_VARARGS | METH_KEYWORDS,
     "panels(xyz, face_start, face_vertices, *, thickness=1, offset='outer', gap=0,\n"
     "       edge='square', flip=False, tol_abs=0, tol_rel=1e-6, plane=None, top=None,\n"
     "       bottom=None, frame=None, reversed=None, neighbor=None, dihedral=None,\n"
     "       bevel=None, node_deviation=None, planarity=None, nonplanar=None,\n"
     "       dropped=None, squared=None, joint=None, node_clash=None, clash=None,\n"
     "       progress=None, repair_consumed=True, length_unit=None) -> dict\n\n"
     "Panel geometry (facet_panels) into the given writable buffers (float64 or int32,\n"
     "sizes as in facet.h). progress(done, total) returning True cancels. length_unit\n"
     "(\"mm\") follows every length in an error message. The error of a joint\n"
     "square on both panels that overlaps has joint_faces and joint_overlap."},
    {NULL, NULL, 0, NULL}};

int py_add_panel(PyObject *module)
{
    return PyModule_AddFunctions(module, panel_methods);
}
