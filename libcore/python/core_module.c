/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core: the thin CPython binding of libfacet.
 *
 * Arrays pass through the buffer protocol (C-contiguous float64 and int32),
 * so numpy arrays go in and come out without copies and without tying the
 * module to one numpy ABI. Solves release the GIL; C status codes become
 * exceptions in one place (raise_status). Multi-phase init with module state
 * and heap types, after CPython's Modules/xxlimited.c. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "facet.h"

#include <math.h>
#include <string.h>

typedef struct {
    PyObject *core_error;
    PyObject *cancelled;
    PyObject *planarizer_type;
} module_state;

static module_state *get_state(PyObject *module)
{
    return (module_state *)PyModule_GetState(module);
}

static const char *status_name(facet_status status)
{
    switch (status) {
#define NAME_CASE(name, value, text) \
    case name:                        \
        return #name;
        FACET_STATUS_LIST(NAME_CASE)
#undef NAME_CASE
    }
    return "FACET_UNKNOWN";
}

/* Sets obj.name = value and drops the reference to value. */
static int set_attr(PyObject *obj, const char *name, PyObject *value)
{
    if (!value)
        return -1;
    int r = PyObject_SetAttrString(obj, name, value);
    Py_DECREF(value);
    return r;
}

/* Raises CoreError (or Cancelled, or MemoryError) for a failed call. */
static PyObject *raise_status(module_state *st, facet_status status, const facet_error *error)
{
    if (status == FACET_ERROR_OUT_OF_MEMORY)
        return PyErr_NoMemory();
    PyObject *type = status == FACET_ERROR_CANCELLED ? st->cancelled : st->core_error;
    const char *message = error && error->message[0] ? error->message : facet_status_string(status);
    PyObject *value = PyObject_CallFunction(type, "s", message);
    if (!value)
        return NULL;
    if (set_attr(value, "status", PyLong_FromLong((long)status)) < 0 ||
        set_attr(value, "status_name", PyUnicode_FromString(status_name(status))) < 0 ||
        set_attr(value, "face", PyLong_FromLongLong(error ? error->face : -1)) < 0 ||
        set_attr(value, "vertex", PyLong_FromLongLong(error ? error->vertex : -1)) < 0) {
        Py_DECREF(value);
        return NULL;
    }
    PyErr_SetObject(type, value);
    Py_DECREF(value);
    return NULL;
}

/* ---- buffers ----------------------------------------------------------- */

static int format_is(const char *format, char code)
{
    if (!format)
        return code == 'B';
    if (format[0] == '@' || format[0] == '=' || format[0] == '<')
        ++format;
    return format[0] == code && format[1] == '\0';
}

/* Gets a C-contiguous buffer of doubles ('d') or int32 ('i'). expected < 0
 * means any length. Sets a TypeError/ValueError naming the argument. */
static int get_buffer(PyObject *obj, const char *name, char code, int writable, Py_ssize_t expected,
                      Py_buffer *view)
{
    int flags = PyBUF_C_CONTIGUOUS | PyBUF_FORMAT | (writable ? PyBUF_WRITABLE : 0);
    if (PyObject_GetBuffer(obj, view, flags) < 0) {
        PyErr_Format(PyExc_TypeError, "%s must be a C-contiguous%s buffer of %s", name,
                     writable ? " writable" : "", code == 'd' ? "float64" : "int32");
        return -1;
    }
    const Py_ssize_t itemsize = code == 'd' ? 8 : 4;
    if (!format_is(view->format, code) || view->itemsize != itemsize) {
        PyErr_Format(PyExc_TypeError, "%s must hold %s values, not format '%s'", name,
                     code == 'd' ? "float64" : "int32", view->format ? view->format : "B");
        PyBuffer_Release(view);
        return -1;
    }
    const Py_ssize_t n = view->len / itemsize;
    if (expected >= 0 && n != expected) {
        PyErr_Format(PyExc_ValueError, "%s has %zd values, %zd expected", name, n, expected);
        PyBuffer_Release(view);
        return -1;
    }
    return 0;
}

typedef struct {
    Py_buffer xyz, start, faces;
    int have_xyz, have_start, have_faces;
    facet_mesh mesh;
} mesh_views;

static void release_mesh(mesh_views *m)
{
    if (m->have_xyz)
        PyBuffer_Release(&m->xyz);
    if (m->have_start)
        PyBuffer_Release(&m->start);
    if (m->have_faces)
        PyBuffer_Release(&m->faces);
    m->have_xyz = m->have_start = m->have_faces = 0;
}

/* xyz may be NULL (topology only, then n_vertices is given). */
static int get_mesh(PyObject *xyz, PyObject *start, PyObject *faces, Py_ssize_t n_vertices,
                    mesh_views *m)
{
    memset(m, 0, sizeof *m);
    if (xyz) {
        if (get_buffer(xyz, "xyz", 'd', 0, -1, &m->xyz) < 0)
            return -1;
        m->have_xyz = 1;
        if ((m->xyz.len / 8) % 3 != 0) {
            PyErr_Format(PyExc_ValueError, "xyz has %zd values, not a multiple of 3", m->xyz.len / 8);
            goto fail;
        }
        n_vertices = m->xyz.len / 24;
    }
    if (get_buffer(start, "face_start", 'i', 0, -1, &m->start) < 0)
        goto fail;
    m->have_start = 1;
    const Py_ssize_t n_faces = m->start.len / 4 - 1;
    if (n_faces < 0) {
        PyErr_SetString(PyExc_ValueError, "face_start must have n_faces + 1 values");
        goto fail;
    }
    const int32_t *fs = m->start.buf;
    if (get_buffer(faces, "face_vertices", 'i', 0, -1, &m->faces) < 0)
        goto fail;
    m->have_faces = 1;
    if (n_faces > 0 && fs[n_faces] != m->faces.len / 4) {
        PyErr_Format(PyExc_ValueError, "face_start ends at %d but face_vertices has %zd values",
                     (int)fs[n_faces], m->faces.len / 4);
        goto fail;
    }
    if (n_vertices > INT32_MAX || n_faces > INT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "mesh too large");
        goto fail;
    }
    m->mesh.n_vertices = (int32_t)n_vertices;
    m->mesh.n_faces = (int32_t)n_faces;
    m->mesh.xyz = xyz ? m->xyz.buf : NULL;
    m->mesh.face_start = fs;
    m->mesh.face_vertices = m->faces.buf;
    return 0;
fail:
    release_mesh(m);
    return -1;
}

/* ---- validate, planarity ------------------------------------------------ */

static PyObject *core_validate(PyObject *module, PyObject *args)
{
    PyObject *xyz, *start, *faces;
    if (!PyArg_ParseTuple(args, "OOO:validate", &xyz, &start, &faces))
        return NULL;
    mesh_views m;
    if (get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    facet_mesh_report report;
    facet_error error;
    facet_status status;
    Py_BEGIN_ALLOW_THREADS
    status = facet_mesh_validate(&m.mesh, &report, &error);
    Py_END_ALLOW_THREADS
    release_mesh(&m);
    if (status < 0)
        return raise_status(get_state(module), status, &error);
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
    if (get_mesh(xyz, start, faces, 0, &m) < 0)
        return NULL;
    static const char *names[4] = {"max_abs", "rms_abs", "mean_edge", "diagonal"};
    Py_buffer views[4];
    double *ptrs[4] = {NULL, NULL, NULL, NULL};
    int got = 0;
    for (; got < 4; ++got) {
        if (outs[got] == Py_None)
            continue;
        if (get_buffer(outs[got], names[got], 'd', 1, m.mesh.n_faces, &views[got]) < 0)
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
            raise_status(get_state(module), status, &error);
        else
            result = Py_NewRef(Py_None);
    }
    for (int k = 0; k < got; ++k)
        if (ptrs[k])
            PyBuffer_Release(&views[k]);
    release_mesh(&m);
    return result;
}

/* ---- Planarizer ---------------------------------------------------------- */

typedef struct {
    PyObject_HEAD
    facet_planarizer *handle;
    int32_t n_vertices, n_faces;
    int busy;
} planarizer_object;

static int planarizer_init(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    static char *keywords[] = {"face_start", "face_vertices", "n_vertices", NULL};
    PyObject *start, *faces;
    Py_ssize_t n_vertices;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OOn:Planarizer", keywords, &start, &faces,
                                     &n_vertices))
        return -1;
    if (self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is already initialised");
        return -1;
    }
    mesh_views m;
    if (get_mesh(NULL, start, faces, n_vertices, &m) < 0)
        return -1;
    facet_error error;
    facet_status status = facet_planarizer_create(&m.mesh, &self->handle, &error);
    self->n_vertices = m.mesh.n_vertices;
    self->n_faces = m.mesh.n_faces;
    release_mesh(&m);
    if (status < 0) {
        PyObject *module = PyType_GetModule(Py_TYPE(self_obj));
        raise_status(get_state(module), status, &error);
        return -1;
    }
    return 0;
}

static void planarizer_dealloc(PyObject *self_obj)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    PyTypeObject *type = Py_TYPE(self_obj);
    facet_planarizer_free(&self->handle);
    type->tp_free(self_obj);
    Py_DECREF(type);
}

typedef struct {
    PyObject *callback; /* may be NULL */
    PyObject *exc_type, *exc_value, *exc_tb;
} progress_state;

/* Runs with the GIL released: takes it for the callback and for Ctrl+C. */
static int progress_trampoline(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    progress_state *ps = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    int cancel = 0;
    if (PyErr_CheckSignals() < 0) {
        cancel = 1;
    } else if (ps->callback) {
        PyObject *r = PyObject_CallFunction(ps->callback, "iid", (int)iteration, (int)max_iter,
                                            planarity);
        if (!r) {
            cancel = 1;
        } else {
            cancel = PyObject_IsTrue(r) == 1;
            Py_DECREF(r);
        }
    }
    if (PyErr_Occurred() && !ps->exc_type)
        PyErr_Fetch(&ps->exc_type, &ps->exc_value, &ps->exc_tb);
    PyErr_Clear();
    PyGILState_Release(gil);
    return cancel;
}

static const char *stop_reason_name(facet_stop_reason reason)
{
    switch (reason) {
    case FACET_STOP_TOLERANCE:
        return "tolerance";
    case FACET_STOP_MAX_ITER:
        return "max_iter";
    case FACET_STOP_ITERATIONS:
        return "iterations";
    case FACET_STOP_STAGNATION:
        return "stagnation";
    case FACET_STOP_CANCELLED:
        return "cancelled";
    case FACET_STOP_NONE:
        break;
    }
    return "none";
}

static PyObject *planarizer_solve(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    static char *keywords[] = {"xyz_in", "xyz_out", "method", "mu0", "ratio", "mu_min",
                               "tol_abs", "tol_rel", "max_iter", "iterations", "threads", "warm",
                               "progress", NULL};
    PyObject *in_obj, *out_obj, *progress = Py_None;
    const char *method = "lg";
    double mu0 = NAN, ratio = NAN, mu_min = NAN, tol_abs = NAN, tol_rel = NAN;
    int max_iter = -1, iterations = 0, threads = 0, warm = 0;
    if (!PyArg_ParseTupleAndKeywords(args, kwargs, "OO|$sdddddiiipO:solve", keywords, &in_obj,
                                     &out_obj, &method, &mu0, &ratio, &mu_min, &tol_abs, &tol_rel,
                                     &max_iter, &iterations, &threads, &warm, &progress))
        return NULL;
    module_state *st = get_state(PyType_GetModule(Py_TYPE(self_obj)));
    if (!self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is not initialised");
        return NULL;
    }
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is already solving in another thread");
        return NULL;
    }
    facet_method m;
    if (strcmp(method, "ll") == 0)
        m = FACET_METHOD_LOCAL_LOCAL;
    else if (strcmp(method, "lg") == 0)
        m = FACET_METHOD_LOCAL_GLOBAL;
    else {
        PyErr_Format(PyExc_ValueError, "method must be 'll' or 'lg', not '%s'", method);
        return NULL;
    }
    if (progress != Py_None && !PyCallable_Check(progress)) {
        PyErr_SetString(PyExc_TypeError, "progress must be callable or None");
        return NULL;
    }
    facet_planarize_options o;
    facet_planarize_options_default(m, &o);
    if (!isnan(mu0))
        o.mu0 = mu0;
    if (!isnan(ratio))
        o.ratio = ratio;
    if (!isnan(mu_min))
        o.mu_min = mu_min;
    if (!isnan(tol_abs))
        o.tol_abs = tol_abs;
    if (!isnan(tol_rel))
        o.tol_rel = tol_rel;
    if (max_iter >= 0)
        o.max_iter = max_iter;
    o.iterations = iterations;
    o.threads = threads;
    o.warm = warm;
    progress_state ps = {progress == Py_None ? NULL : progress, NULL, NULL, NULL};
    o.progress = progress_trampoline;
    o.progress_user = &ps;

    Py_buffer in_view, out_view;
    const Py_ssize_t n = 3 * (Py_ssize_t)self->n_vertices;
    if (get_buffer(in_obj, "xyz_in", 'd', 0, n, &in_view) < 0)
        return NULL;
    if (get_buffer(out_obj, "xyz_out", 'd', 1, n, &out_view) < 0) {
        PyBuffer_Release(&in_view);
        return NULL;
    }
    facet_planarize_result r;
    memset(&r, 0, sizeof r);
    facet_error error;
    facet_status status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    status = facet_planarizer_solve(self->handle, in_view.buf, &o, out_view.buf, &r, &error);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyBuffer_Release(&in_view);
    PyBuffer_Release(&out_view);
    if (ps.exc_type) {
        /* The callback raised (or Ctrl+C): that exception wins. */
        PyErr_Restore(ps.exc_type, ps.exc_value, ps.exc_tb);
        return NULL;
    }
    if (status < 0)
        return raise_status(st, status, &error);
    return Py_BuildValue("{s:i,s:s,s:d,s:d,s:d,s:d,s:O}", "iterations", (int)r.iterations,
                         "stop_reason", stop_reason_name(r.stop_reason), "mu", r.mu,
                         "planarity_max_abs", r.planarity_max_abs, "planarity_max_rel",
                         r.planarity_max_rel, "seconds", r.seconds, "converged",
                         (r.stop_reason == FACET_STOP_TOLERANCE) ? Py_True : Py_False);
}

static PyObject *planarizer_get_n_vertices(PyObject *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(((planarizer_object *)self)->n_vertices);
}

static PyObject *planarizer_get_n_faces(PyObject *self, void *closure)
{
    (void)closure;
    return PyLong_FromLong(((planarizer_object *)self)->n_faces);
}

static PyMethodDef planarizer_methods[] = {
    {"solve", (PyCFunction)(void (*)(void))planarizer_solve, METH_VARARGS | METH_KEYWORDS,
     "solve(xyz_in, xyz_out, *, method='lg', mu0, ratio, mu_min, tol_abs, tol_rel, max_iter,\n"
     "      iterations=0, threads=0, warm=False, progress=None) -> dict\n\n"
     "Planarize the control positions xyz_in (float64, 3*n_vertices) into xyz_out.\n"
     "The GIL is released while solving; progress(iteration, max_iter, planarity_max_rel)\n"
     "returning True cancels."},
    {NULL, NULL, 0, NULL}};

static PyGetSetDef planarizer_getset[] = {
    {"n_vertices", planarizer_get_n_vertices, NULL, "number of vertices", NULL},
    {"n_faces", planarizer_get_n_faces, NULL, "number of faces", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyType_Slot planarizer_slots[] = {
    {Py_tp_doc, "Planarizer(face_start, face_vertices, n_vertices)\n\n"
                "A planarization solver for one mesh topology; it keeps its workspace\n"
                "between solves so a re-solve after an edit can start warm."},
    {Py_tp_init, planarizer_init},
    {Py_tp_dealloc, planarizer_dealloc},
    {Py_tp_methods, planarizer_methods},
    {Py_tp_getset, planarizer_getset},
    {0, NULL}};

static PyType_Spec planarizer_spec = {"facet._core.Planarizer", sizeof(planarizer_object), 0,
                                      Py_TPFLAGS_DEFAULT, planarizer_slots};

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
    module_state *st = get_state(module);
    st->core_error = PyErr_NewExceptionWithDoc(
        "facet._core.CoreError", "An error reported by libfacet (attributes status, status_name, "
        "face, vertex).", NULL, NULL);
    if (!st->core_error || PyModule_AddObjectRef(module, "CoreError", st->core_error) < 0)
        return -1;
    st->cancelled = PyErr_NewExceptionWithDoc("facet._core.Cancelled",
                                              "A solve was cancelled.", st->core_error, NULL);
    if (!st->cancelled || PyModule_AddObjectRef(module, "Cancelled", st->cancelled) < 0)
        return -1;
    st->planarizer_type = PyType_FromModuleAndSpec(module, &planarizer_spec, NULL);
    if (!st->planarizer_type ||
        PyModule_AddObjectRef(module, "Planarizer", st->planarizer_type) < 0)
        return -1;
    return 0;
}

static int core_traverse(PyObject *module, visitproc visit, void *arg)
{
    module_state *st = get_state(module);
    Py_VISIT(st->core_error);
    Py_VISIT(st->cancelled);
    Py_VISIT(st->planarizer_type);
    return 0;
}

static int core_clear(PyObject *module)
{
    module_state *st = get_state(module);
    Py_CLEAR(st->core_error);
    Py_CLEAR(st->cancelled);
    Py_CLEAR(st->planarizer_type);
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
