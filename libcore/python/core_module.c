/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core: the thin CPython binding of libfacet.
 *
 * Arrays pass through the buffer protocol (C-contiguous float64 and int32),
 * so numpy arrays go in and come out without copies and without tying the
 * module to one numpy ABI. Solves release the GIL; C status codes become
 * exceptions in one place (py_raise_status, py_common.c). Multi-phase init with module state
 * and heap types, after CPython's Modules/xxlimited.c. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <math.h>
#include <string.h>

/* ---- validate, planarity ------------------------------------------------ */

static PyObject *core_validate(PyObject *module, PyObject *args)
{
    PyObject *xyz, *start, *faces;
    if (!PyArg_ParseTuple(args, "OOO:validate", &xyz, &start, &faces))
        return NULL;
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    facet_mesh_report report;
    facet_error error;
    facet_status status;
    Py_BEGIN_ALLOW_THREADS
    status = facet_mesh_validate(&m.mesh, &report, &error);
    Py_END_ALLOW_THREADS
    py_release_mesh(&m);
    if (status < 0)
        return py_raise_status(py_state(module), status, &error);
    PyObject *edge = Py_None, *isolated = Py_None;
    Py_INCREF(Py_None);
    Py_INCREF(Py_None);
    if (report.n_non_manifold_edges > 0) {
        Py_DECREF(edge);
        edge = Py_BuildValue("(LL)", (long long)report.first_non_manifold_edge[0],
                             (long long)report.first_non_manifold_edge[1]);
    }
    if (report.n_isolated_vertices > 0) {
        Py_DECREF(isolated);
        isolated = PyLong_FromLongLong(report.first_isolated_vertex);
    }
    if (!edge || !isolated) {
        Py_XDECREF(edge);
        Py_XDECREF(isolated);
        return NULL;
    }
    return Py_BuildValue("{s:L,s:L,s:L,s:L,s:N,s:N,s:i}", "n_edges", (long long)report.n_edges,
                         "n_boundary_edges", (long long)report.n_boundary_edges,
                         "n_non_manifold_edges", (long long)report.n_non_manifold_edges,
                         "n_isolated_vertices", (long long)report.n_isolated_vertices,
                         "first_non_manifold_edge", edge, "first_isolated_vertex", isolated,
                         "max_degree", (int)report.max_degree);
}

static PyObject *core_planarity(PyObject *module, PyObject *args, PyObject *kwargs)
{
    static char *keywords[] = {"xyz", "face_start", "face_vertices", "max_abs", "rms_abs",
                               "mean_edge", "diagonal", "threads", NULL};
    PyObject *xyz, *start, *faces, *outs[4] = {Py_None, Py_None, Py_None, Py_None};
    int threads = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|OOOOi:planarity", keywords, &xyz, &start,
                                     &faces, &outs[0], &outs[1], &outs[2], &outs[3], &threads))
        return NULL;
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    static const char *names[4] = {"max_abs", "rms_abs", "mean_edge", "diagonal"};
    Py_buffer views[4];
    double *ptrs[4] = {NULL, NULL, NULL, NULL};
    int got = 0;
    for (; got < 4; ++got) {
        if (outs[got] == Py_None)
            continue;
        if (py_get_buffer(outs[got], names[got], 'd', 1, m.mesh.n_faces, &views[got]) < 0)
            break;
        ptrs[got] = views[got].buf;
    }
    PyObject *result = NULL;
    if (got == 4) {
        facet_error error;
        facet_status status;
        Py_BEGIN_ALLOW_THREADS
        status = facet_planarity(&m.mesh, threads, ptrs[0], ptrs[1], ptrs[2], ptrs[3], &error);
        Py_END_ALLOW_THREADS
        if (status < 0)
            py_raise_status(py_state(module), status, &error);
        else
            result = Py_NewRef(Py_None);
    }
    for (int k = 0; k < got; ++k)
        if (ptrs[k])
            PyBuffer_Release(&views[k]);
    py_release_mesh(&m);
    return result;
}
/* ---- module ---------------------------------------------------------------- */

static PyObject *core_version(PyObject *module, PyObject *unused)
{
    (void)module, (void)unused;
    return PyUnicode_FromString(facet_version());
}

static PyMethodDef core_methods[] = {
    {"validate", core_validate, METH_VARARGS,
     "validate(xyz, face_start, face_vertices) -> dict\n\nCheck a mesh; raise CoreError."},
    {"planarity", (PyCFunction)(void (*)(void))core_planarity, METH_VARARGS | METH_KEYWORDS,
     "planarity(xyz, face_start, face_vertices, max_abs=None, rms_abs=None, mean_edge=None,\n"
     "          diagonal=None, threads=0) -> None\n\nWrite per-face planarity measures."},
    {"version", core_version, METH_NOARGS, "version() -> str"},
    {NULL, NULL, 0, NULL}};

static int core_exec(PyObject *module)
{
    module_state *st = py_state(module);
    st->core_error = PyErr_NewExceptionWithDoc(
        "facet._core.CoreError", "An error reported by libfacet (attributes status, status_name, "
        "face, vertex).", NULL, NULL);
    if (!st->core_error || PyModule_AddObjectRef(module, "CoreError", st->core_error) < 0)
        return -1;
    st->cancelled = PyErr_NewExceptionWithDoc("facet._core.Cancelled",
                                              "A solve was cancelled.", st->core_error, NULL);
    if (!st->cancelled || PyModule_AddObjectRef(module, "Cancelled", st->cancelled) < 0)
        return -1;
    /* One line per binding file (py_common.h). */
    if (py_add_planarize(module) < 0)
        return -1;
    if (py_add_surface(module) < 0 || py_add_quality(module) < 0 || py_add_cleanup(module) < 0 ||
        py_add_lift(module) < 0 || py_add_panel(module) < 0)
        return -1;
    return 0;
}

static int core_traverse(PyObject *module, visitproc visit, void *arg)
{
    module_state *st = py_state(module);
    Py_VISIT(st->core_error);
    Py_VISIT(st->cancelled);
    return 0;
}

static int core_clear(PyObject *module)
{
    module_state *st = py_state(module);
    Py_CLEAR(st->core_error);
    Py_CLEAR(st->cancelled);
    return 0;
}

static void core_free(void *module)
{
    core_clear((PyObject *)module);
}

static PyModuleDef_Slot core_slots[] = {{Py_mod_exec, core_exec}, {0, NULL}};

static struct PyModuleDef core_module = {
    PyModuleDef_HEAD_INIT,
    .m_name = "facet._core",
    .m_doc = "libfacet, Facet's C solver library: validation, planarity, planarization.",
    .m_size = sizeof(module_state),
    .m_methods = core_methods,
    .m_slots = core_slots,
    .m_traverse = core_traverse,
    .m_clear = core_clear,
    .m_free = core_free,
};

PyMODINIT_FUNC PyInit__core(void)
{
    return PyModuleDef_Init(&core_module);
}
