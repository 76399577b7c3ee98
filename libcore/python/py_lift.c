/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.Lifter: optimal liftings of a plan graph. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <string.h>

typedef struct {
    PyObject_HEAD
    facet_lifter *handle;
    int32_t n_vertices, n_faces;
    int busy;
} lifter_object;

static int lifter_init(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    lifter_object *self = (lifter_object *)self_obj;
    static char *keywords[] = {"xyz",      "face_start", "face_vertices", "weights",
                               "rank_tol", "progress",   NULL};
    PyObject *xyz, *start, *faces, *weights = Py_None, *progress = Py_None;
    double rank_tol = 0.0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOO|OdO:Lifter", keywords, &xyz, &start,
                                     &faces, &weights, &rank_tol, &progress))
        return -1;
    if (progress != Py_None && !PyCallable_Check(progress)) {
        PyErr_SetString(PyExc_TypeError, "progress must be callable or None");
        return -1;
    }
    if (self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Lifter is already initialised");
        return -1;
    }
    mesh_views m;
    if (py_get_mesh(xyz, start, faces, -1, &m) < 0)
        return -1;
    Py_buffer wview;
    int have_w = 0;
    if (weights != Py_None) {
        if (py_get_buffer(weights, "weights", 'd', 0, m.mesh.n_vertices, &wview) < 0) {
            py_release_mesh(&m);
            return -1;
        }
        have_w = 1;
    }
    py_count_progress_state ps = {progress == Py_None ? NULL : progress, NULL, NULL, NULL};
    facet_lift_options o = {rank_tol, py_count_progress, &ps};
    facet_error error;
    facet_status status;
    Py_BEGIN_ALLOW_THREADS
    status = facet_lifter_create(&m.mesh, have_w ? wview.buf : NULL, &o, &self->handle, &error);
    Py_END_ALLOW_THREADS
    self->n_vertices = m.mesh.n_vertices;
    self->n_faces = m.mesh.n_faces;
    if (have_w)
        PyBuffer_Release(&wview);
    py_release_mesh(&m);
    if (ps.exc_type) { /* (the callback raised: its exception, not "cancelled") */
        facet_lifter_free(&self->handle);
        PyErr_Restore(ps.exc_type, ps.exc_value, ps.exc_tb);
        return -1;
    }
    if (status < 0) {
        py_raise_status(py_state(PyType_GetModule(Py_TYPE(self_obj))), status, &error);
        return -1;
    }
    return 0;
}

static void lifter_dealloc(PyObject *self_obj)
{
    lifter_object *self = (lifter_object *)self_obj;
    PyTypeObject *type = Py_TYPE(self_obj);
    facet_lifter_free(&self->handle);
    type->tp_free(self_obj);
    Py_DECREF(type);
}

static int lifter_ready(lifter_object *self)
{
    if (!self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Lifter is not initialised");
        return 0;
    }
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Lifter is already working in another thread");
        return 0;
    }
    return 1;
}

static PyObject *lifter_solve(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    lifter_object *self = (lifter_object *)self_obj;
    static char *keywords[] = {"targets", "heights", NULL};
    PyObject *t_obj, *z_obj;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO:solve", keywords, &t_obj, &z_obj))
        return NULL;
    if (!lifter_ready(self))
        return NULL;
    module_state *st = py_state(PyType_GetModule(Py_TYPE(self_obj)));
    Py_buffer tv, zv;
    if (py_get_buffer(t_obj, "targets", 'd', 0, self->n_vertices, &tv) < 0)
        return NULL;
    if (py_get_buffer(z_obj, "heights", 'd', 1, self->n_vertices, &zv) < 0) {
        PyBuffer_Release(&tv);
        return NULL;
    }
    facet_lift_result r;
    memset(&r, 0, sizeof r);
    facet_error error;
    facet_status status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    status = facet_lifter_solve(self->handle, tv.buf, zv.buf, &r, &error);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyBuffer_Release(&tv);
    PyBuffer_Release(&zv);
    if (status < 0)
        return py_raise_status(st, status, &error);
    return Py_BuildValue("{s:i,s:i,s:d,s:d,s:d,s:d,s:i,s:d,s:s,s:s}", "dimension",
                         (int)r.dimension, "trivial_dimension", (int)r.trivial_dimension,
                         "planarity_max_abs", r.planarity_max_abs, "planarity_max_rel",
                         r.planarity_max_rel, "target_rms", r.target_rms, "target_max",
                         r.target_max, "target_max_vertex", (int)r.target_max_vertex, "seconds",
                         r.seconds, "status", py_status_name(status), "message",
                         status == FACET_OK ? "" : error.message);
}

static PyObject *lifter_fundamental(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    lifter_object *self = (lifter_object *)self_obj;
    static char *keywords[] = {"vertex", "heights", NULL};
    int vertex;
    PyObject *z_obj;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "iO:fundamental", keywords, &vertex, &z_obj))
        return NULL;
    if (!lifter_ready(self))
        return NULL;
    module_state *st = py_state(PyType_GetModule(Py_TYPE(self_obj)));
    Py_buffer zv;
    if (py_get_buffer(z_obj, "heights", 'd', 1, self->n_vertices, &zv) < 0)
        return NULL;
    facet_error error;
    facet_status status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    status = facet_lifter_fundamental(self->handle, vertex, zv.buf, &error);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyBuffer_Release(&zv);
    if (status < 0)
        return py_raise_status(st, status, &error);
    Py_RETURN_NONE;
}

static PyObject *lifter_basis(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    lifter_object *self = (lifter_object *)self_obj;
    static char *keywords[] = {"kind", "count", "basis", "values", NULL};
    const char *kind_name;
    int count;
    PyObject *b_obj, *v_obj;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "siOO:basis", keywords, &kind_name, &count,
                                     &b_obj, &v_obj))
        return NULL;
    if (!lifter_ready(self))
        return NULL;
    facet_basis_kind kind;
    if (strcmp(kind_name, "orthonormal") == 0)
        kind = FACET_BASIS_ORTHONORMAL;
    else if (strcmp(kind_name, "eigen") == 0)
        kind = FACET_BASIS_EIGEN;
    else {
        PyErr_Format(PyExc_ValueError, "kind must be 'orthonormal' or 'eigen', not '%s'",
                     kind_name);
        return NULL;
    }
    if (count < 0) {
        PyErr_SetString(PyExc_ValueError, "count must be >= 0");
        return NULL;
    }
    module_state *st = py_state(PyType_GetModule(Py_TYPE(self_obj)));
    Py_buffer bv, vv;
    if (py_get_buffer(b_obj, "basis", 'd', 1, (Py_ssize_t)count * self->n_vertices, &bv) < 0)
        return NULL;
    if (py_get_buffer(v_obj, "values", 'd', 1, count, &vv) < 0) {
        PyBuffer_Release(&bv);
        return NULL;
    }
    facet_error error;
    facet_status status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    status = facet_lifter_basis(self->handle, kind, count, bv.buf, vv.buf, &error);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyBuffer_Release(&bv);
    PyBuffer_Release(&vv);
    if (status < 0)
        return py_raise_status(st, status, &error);
    Py_RETURN_NONE;
}

static PyObject *lifter_get_dimension(PyObject *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(facet_lifter_dimension(((lifter_object *)self)->handle));
}

static PyObject *lifter_get_factor_seconds(PyObject *self, void *closure)
{
    (void)closure;
    return PyFloat_FromDouble(facet_lifter_factor_seconds(((lifter_object *)self)->handle));
}

static PyObject *lifter_get_n_vertices(PyObject *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(((lifter_object *)self)->n_vertices);
}

static PyMethodDef lifter_methods[] = {
    {"solve", (PyCFunction)(void (*)(void))lifter_solve, METH_VARARGS | METH_KEYWORDS,
     "solve(targets, heights) -> dict\n\nThe optimal lifting of targets (float64, n_vertices) "
     "into heights.\nThe dict has status 'FACET_OK' or a warning name, and message."},
    {"fundamental", (PyCFunction)(void (*)(void))lifter_fundamental,
     METH_VARARGS | METH_KEYWORDS,
     "fundamental(vertex, heights)\n\nThe fundamental lifting of a vertex into heights."},
    {"basis", (PyCFunction)(void (*)(void))lifter_basis, METH_VARARGS | METH_KEYWORDS,
     "basis(kind, count, basis, values)\n\nThe first count functions of the 'orthonormal' or "
     "'eigen' basis\ninto basis (count*n_vertices) and their Dirichlet energies into values."},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef lifter_getset[] = {
    {"dimension", lifter_get_dimension, NULL, "dimension of the lifting space", NULL},
    {"factor_seconds", lifter_get_factor_seconds, NULL, "time of the factorization", NULL},
    {"n_vertices", lifter_get_n_vertices, NULL, "number of vertices", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyType_Slot lifter_slots[] = {
    {Py_tp_doc, "Lifter(xyz, face_start, face_vertices, weights=None, rank_tol=0, "
                "progress=None)\n\n"
                "Optimal liftings of a plan (x, y of xyz; z ignored), from one sparse QR.\n"
                "progress(done, 3) as the create step's stages end (a true result, an\n"
                "exception or Ctrl+C cancels: Cancelled)."},
    {Py_tp_init, lifter_init},
    {Py_tp_dealloc, lifter_dealloc},
    {Py_tp_methods, lifter_methods},
    {Py_tp_getset, lifter_getset},
    {0, NULL}};

static PyType_Spec lifter_spec = {"facet._core.Lifter", sizeof(lifter_object), 0,
                                  Py_TPFLAGS_DEFAULT, lifter_slots};

int py_add_lift(PyObject *module)
{
    PyObject *type = PyType_FromModuleAndSpec(module, &lifter_spec, NULL);
    if (!type)
        return -1;
    int r = PyModule_AddObjectRef(module, "Lifter", type);
    Py_DECREF(type);
    return r;
}
