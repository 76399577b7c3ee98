/* SPDX-License-Identifier: LGPL-2.1-or-later */
/* facet._core.Planarizer: the planarization solver handle. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "py_common.h"

#include <math.h>
#include <string.h>

/* ---- Planarizer ---------------------------------------------------------- */

typedef struct {
    PyObject_HEAD
    facet_planarizer *handle;
    int32_t n_vertices, n_faces;
    int busy;
    PyObject *reference; /* the Surface in use, kept alive while the handle borrows it */
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
    if (py_get_mesh(NULL, start, faces, n_vertices, &m) < 0)
        return -1;
    facet_error error;
    facet_status status = facet_planarizer_create(&m.mesh, &self->handle, &error);
    self->n_vertices = m.mesh.n_vertices;
    self->n_faces = m.mesh.n_faces;
    py_release_mesh(&m);
    if (status < 0) {
        PyObject *module = PyType_GetModule(Py_TYPE(self_obj));
        py_raise_status(py_state(module), status, &error);
        return -1;
    }
    return 0;
}

static void planarizer_dealloc(PyObject *self_obj)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    PyTypeObject *type = Py_TYPE(self_obj);
    facet_planarizer_free(&self->handle);
    Py_CLEAR(self->reference);
    type->tp_free(self_obj);
    Py_DECREF(type);
}

typedef struct {
    PyObject *callback; /* may be NULL */
    PyObject *exc_type, *exc_value, *exc_tb;
    PyObject *stage;    /* stage(stage, stages) when a quality re-solve or one of method
                           auto's comparison solves (stage FACET_STAGE_COMPARE or
                           FACET_STAGE_FINER) or its fallback (FACET_STAGE_FALLBACK)
                           starts; may be NULL */
    const facet_planarizer *handle;
    int32_t stage_seen;
} progress_state;

/* Runs with the GIL released: takes it for the callback and for Ctrl+C. */
static int progress_trampoline(void *user, int32_t iteration, int32_t max_iter, double planarity)
{
    progress_state *ps = user;
    PyGILState_STATE gil = PyGILState_Ensure();
    int cancel = 0;
    int32_t stages = 0;
    const int32_t stage = ps->stage ? facet_planarizer_stage(ps->handle, &stages) : 0;
    if (PyErr_CheckSignals() < 0) {
        cancel = 1;
    } else if (stage != ps->stage_seen) { /* a re-solve or the comparison started: said before
                                             its first iteration */
        ps->stage_seen = stage;
        PyObject *r = PyObject_CallFunction(ps->stage, "ii", (int)stage, (int)stages);
        cancel = !r;
        Py_XDECREF(r);
    }
    if (!cancel && ps->callback)
        cancel = py_callback_cancels(PyObject_CallFunction(
            ps->callback, "iid", (int)iteration, (int)max_iter, planarity));
    py_keep_exception(&ps->exc_type, &ps->exc_value, &ps->exc_tb);
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
    case FACET_STOP_TIME:
        return "time";
    case FACET_STOP_NONE:
        break;
    }
    return "none";
}

/* The solve's figures, as planarizer_solve returns them. */
static PyObject *result_dict(const facet_planarize_result *r)
{
    static const char *const quality_names[] = {"not_checked", "ok", "recovered", "narrow"};
    /* compare_*: (L/L, L/G), facet_method's order */
    return Py_BuildValue("{s:i,s:s,s:d,s:d,s:d,s:d,s:d,s:i,s:i,s:O,s:s,s:s,s:i,s:i,s:O,s:i,s:i,s:(dd),s:(dd),s:(dd),s:(dd),s:i,s:O,s:i,s:d}",
                         "iterations",
                         (int)r->iterations, "stop_reason", stop_reason_name(r->stop_reason), "mu",
                         r->mu, "planarity_max_abs", r->planarity_max_abs, "planarity_max_rel",
                         r->planarity_max_rel, "constraint_max_rel", r->constraint_max_rel,
                         "seconds", r->seconds, "anderson_accepted", (int)r->anderson_accepted,
                         "anderson_rejected", (int)r->anderson_rejected, "converged",
                         (r->stop_reason == FACET_STOP_TOLERANCE) ? Py_True : Py_False, "method",
                         r->method == FACET_METHOD_LOCAL_LOCAL ? "ll" : "lg", "quality",
                         quality_names[r->quality >= 0 && r->quality <= 3 ? r->quality : 0],
                         "narrow_corners", (int)r->narrow_corners, "quality_resolves",
                         (int)r->quality_resolves, "quality_timed_out",
                         r->quality == FACET_QUALITY_NARROW && r->quality_timed_out ? Py_True : Py_False,
                         "first_iterations", (int)r->first_iterations,
                         "compare_iterations", (int)r->compare_iterations, "compare_distance_rms",
                         r->compare_distance_rms[0], r->compare_distance_rms[1], "compare_min_angle",
                         r->compare_min_angle[0], r->compare_min_angle[1], "compare_displacement_rms",
                         r->compare_displacement_rms[0], r->compare_displacement_rms[1],
                         "compare_edge_ratio", r->compare_edge_ratio[0], r->compare_edge_ratio[1],
                         "finer_iterations", (int)r->finer_iterations, "finer_kept",
                         r->finer_kept ? Py_True : Py_False, "threads", (int)r->threads,
                         "data_tangent", r->data_tangent);
}

static PyObject *planarizer_solve(PyObject *self_obj, PyObject *args, PyObject *kwargs)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    static char *keywords[] = {"xyz_in", "xyz_out", "method", "mu0", "ratio", "mu_min",
                               "tol_abs", "tol_rel", "max_iter", "iterations", "threads", "warm",
                               "progress", "data_tangent", "data_normal", "laplacian",
                               "laplacian_weights", "normal_laplacian", "boundary_fairness",
                               "shape", "shape_weight", "boundary", "circular", "parallelogram",
                               "anderson", "time_budget", "hold_tol", "hold_max", "surface_weight",
                               "live", "rings", "angle_floor", "quality_angle", "stage", NULL};
    PyObject *in_obj, *out_obj, *progress = Py_None, *stage = Py_None;
    const char *method = "auto", *lap_weights = NULL, *shape = NULL, *boundary = NULL;
    /* The method's defaults first, so that what the caller did not pass keeps
     * them and what it passed reaches the core as given, to be checked there:
     * a NaN weight or a negative count is refused, not taken for "not given". */
    PyObject *method_obj = kwargs ? PyDict_GetItemString(kwargs, "method") : NULL;
    if (method_obj && PyUnicode_Check(method_obj) && !(method = PyUnicode_AsUTF8(method_obj)))
        return NULL;
    facet_method m;
    if (strcmp(method, "ll") == 0)
        m = FACET_METHOD_LOCAL_LOCAL;
    else if (strcmp(method, "lg") == 0)
        m = FACET_METHOD_LOCAL_GLOBAL;
    else
        m = FACET_METHOD_AUTO; /* "auto", or a bad name that the parse below refuses */
    facet_planarize_options o;
    facet_planarize_options_default(m, &o);
    int hold_max = o.hold_max, live = 0, rings = 0;
    int max_iter = o.max_iter, iterations = 0, threads = 0, warm = 0, anderson = o.anderson;
    if (!PyArg_ParseTupleAndKeywords(
            args, kwargs, "OO|$sdddddiiipOdddzddzdzddiddidpiddO:solve", keywords, &in_obj, &out_obj,
            &method, &o.mu0, &o.ratio, &o.mu_min, &o.tol_abs, &o.tol_rel, &max_iter, &iterations,
            &threads, &warm, &progress, &o.data_tangent, &o.data_normal, &o.laplacian, &lap_weights,
            &o.normal_laplacian, &o.boundary_fairness, &shape, &o.shape_weight, &boundary,
            &o.circular, &o.parallelogram, &anderson, &o.time_budget, &o.hold_tol, &hold_max,
            &o.surface_weight, &live, &rings, &o.angle_floor, &o.quality_angle, &stage))
        return NULL;
    module_state *st = py_state(PyType_GetModule(Py_TYPE(self_obj)));
    if (!self->handle) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is not initialised");
        return NULL;
    }
    if (self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is already solving in another thread");
        return NULL;
    }
    if (strcmp(method, "ll") != 0 && strcmp(method, "lg") != 0 && strcmp(method, "auto") != 0) {
        PyErr_Format(PyExc_ValueError, "method must be 'auto', 'll' or 'lg', not '%s'", method);
        return NULL;
    }
    if (progress != Py_None && !PyCallable_Check(progress)) {
        PyErr_SetString(PyExc_TypeError, "progress must be callable or None");
        return NULL;
    }
    if (stage != Py_None && !PyCallable_Check(stage)) {
        PyErr_SetString(PyExc_TypeError, "stage must be callable or None");
        return NULL;
    }
    if (rings < 0) {
        PyErr_Format(PyExc_ValueError, "rings must be >= 0, not %d", rings);
        return NULL;
    }
    o.max_iter = max_iter;
    o.iterations = iterations;
    o.threads = threads;
    o.warm = warm;
    o.anderson = anderson;
    o.hold_max = hold_max;
    if (lap_weights) {
        if (strcmp(lap_weights, "uniform") == 0)
            o.laplacian_weights = FACET_LAPLACIAN_UNIFORM;
        else if (strcmp(lap_weights, "inverse_edge") == 0)
            o.laplacian_weights = FACET_LAPLACIAN_INVERSE_EDGE;
        else {
            PyErr_Format(PyExc_ValueError,
                         "laplacian_weights must be 'uniform' or 'inverse_edge', not '%s'", lap_weights);
            return NULL;
        }
    }
    if (shape) {
        if (strcmp(shape, "none") == 0)
            o.shape = FACET_SHAPE_NONE;
        else if (strcmp(shape, "asap") == 0)
            o.shape = FACET_SHAPE_ASAP;
        else if (strcmp(shape, "arap") == 0)
            o.shape = FACET_SHAPE_ARAP;
        else {
            PyErr_Format(PyExc_ValueError, "shape must be 'none', 'asap' or 'arap', not '%s'", shape);
            return NULL;
        }
    }
    if (boundary) {
        if (strcmp(boundary, "free") == 0)
            o.boundary = FACET_BOUNDARY_FREE;
        else if (strcmp(boundary, "fixed") == 0)
            o.boundary = FACET_BOUNDARY_FIXED;
        else if (strcmp(boundary, "sliding") == 0)
            o.boundary = FACET_BOUNDARY_SLIDING;
        else {
            PyErr_Format(PyExc_ValueError, "boundary must be 'free', 'fixed' or 'sliding', not '%s'",
                         boundary);
            return NULL;
        }
    }
    progress_state ps = {progress == Py_None ? NULL : progress, NULL, NULL, NULL,
                         stage == Py_None ? NULL : stage, self->handle, 0};
    o.progress = progress_trampoline;
    o.progress_user = &ps;

    Py_buffer in_view, out_view;
    const Py_ssize_t n = 3 * (Py_ssize_t)self->n_vertices;
    if (py_get_buffer(in_obj, "xyz_in", 'd', 0, n, &in_view) < 0)
        return NULL;
    if (py_get_buffer(out_obj, "xyz_out", 'd', 1, n, &out_view) < 0) {
        PyBuffer_Release(&in_view);
        return NULL;
    }
    facet_planarize_result r;
    memset(&r, 0, sizeof r);
    facet_error error;
    facet_status status;
    self->busy = 1;
    Py_BEGIN_ALLOW_THREADS
    status = live ? facet_planarizer_update(self->handle, in_view.buf, &o, rings, out_view.buf, &r, &error)
                  : facet_planarizer_solve(self->handle, in_view.buf, &o, out_view.buf, &r, &error);
    Py_END_ALLOW_THREADS
    self->busy = 0;
    PyBuffer_Release(&in_view);
    PyBuffer_Release(&out_view);
    if (ps.exc_type) {
        /* The callback raised (or Ctrl+C): that exception wins. */
        PyErr_Restore(ps.exc_type, ps.exc_value, ps.exc_tb);
        return NULL;
    }
    if (status == FACET_ERROR_CANCELLED && r.stop_reason == FACET_STOP_TOLERANCE) {
        /* cancelled after a result that reached the tolerance (a quality
         * re-solve, method auto's comparison or fallback: facet.h): xyz_out
         * holds it, and the exception carries its figures as `result` */
        py_raise_status(st, status, &error);
        PyObject *type, *value, *tb;
        PyErr_Fetch(&type, &value, &tb);
        PyErr_NormalizeException(&type, &value, &tb);
        if (value && py_set_attr(value, "result", result_dict(&r)) < 0) {
            Py_XDECREF(type), Py_XDECREF(value), Py_XDECREF(tb);
            return NULL;
        }
        PyErr_Restore(type, value, tb);
        return NULL;
    }
    if (status < 0)
        return py_raise_status(st, status, &error);
    return result_dict(&r);
}

/* The handle of a planarizer that may be configured now; NULL with an error set. */
static facet_planarizer *idle_handle(PyObject *self_obj)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    if (!self->handle || self->busy) {
        PyErr_SetString(PyExc_RuntimeError, "Planarizer is not initialised or is solving");
        return NULL;
    }
    return self->handle;
}

/* A setter taking a buffer ('i' any length, or 'd' of n_faces) or None. */
static PyObject *set_array(PyObject *self_obj, PyObject *arg, const char *name, char code)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    module_state *st = py_state(PyType_GetModule(Py_TYPE(self_obj)));
    facet_planarizer *handle = idle_handle(self_obj);
    if (!handle)
        return NULL;
    Py_buffer view;
    const int given = arg != Py_None;
    if (given && py_get_buffer(arg, name, code, 0, code == 'd' ? self->n_faces : -1, &view) < 0)
        return NULL;
    facet_error error;
    const facet_status status =
        code == 'i' ? facet_planarizer_set_fixed(handle, given ? (int32_t)(view.len / 4) : 0,
                                                 given ? view.buf : NULL, &error)
                    : facet_planarizer_set_face_weights(handle, given ? view.buf : NULL, &error);
    if (given)
        PyBuffer_Release(&view);
    if (status < 0)
        return py_raise_status(st, status, &error);
    Py_RETURN_NONE;
}

/* set_fixed(vertices): int32 buffer of vertex indices, or None to clear. */
static PyObject *planarizer_set_fixed(PyObject *self_obj, PyObject *arg)
{
    return set_array(self_obj, arg, "vertices", 'i');
}

/* set_face_weights(weights): float64 buffer of n_faces weights, or None for all 1. */
static PyObject *planarizer_set_face_weights(PyObject *self_obj, PyObject *arg)
{
    return set_array(self_obj, arg, "weights", 'd');
}

/* set_reference(surface): a facet._core.Surface, or None. */
static PyObject *planarizer_set_reference(PyObject *self_obj, PyObject *arg)
{
    planarizer_object *self = (planarizer_object *)self_obj;
    PyObject *module = PyType_GetModule(Py_TYPE(self_obj));
    module_state *st = py_state(module);
    if (!idle_handle(self_obj))
        return NULL;
    const facet_surface *surface = NULL;
    if (arg != Py_None && !(surface = py_surface_handle(module, arg)))
        return NULL;
    facet_error error;
    const facet_status status = facet_planarizer_set_reference(self->handle, surface, &error);
    if (status < 0)
        return py_raise_status(st, status, &error);
    Py_XINCREF(arg == Py_None ? NULL : arg);
    Py_XSETREF(self->reference, arg == Py_None ? NULL : arg);
    Py_RETURN_NONE;
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
     "solve(xyz_in, xyz_out, *, method='auto', mu0, ratio, mu_min, tol_abs, tol_rel, max_iter,\n"
     "      iterations=0, threads=0, warm=False, progress=None, data_tangent, data_normal,\n"
     "      laplacian, laplacian_weights, normal_laplacian, boundary_fairness, shape,\n"
     "      shape_weight, boundary, circular, parallelogram, anderson, time_budget,\n"
     "      hold_tol, hold_max, surface_weight, live=False, rings=0, angle_floor,\n"
     "      quality_angle, stage=None) -> dict\n\n"
     "Planarize the control positions xyz_in (float64, 3*n_vertices) into xyz_out.\n"
     "live=True: a live update of the region around the vertices edited since the\n"
     "last solve, `rings` edges deep (0: 4) (facet_planarizer_update).\n"
     "The GIL is released while solving; progress(iteration, max_iter, planarity_max_rel)\n"
     "returning True cancels. It counts on through the quality re-solves (iteration up to\n"
     "the result's iterations, max_iter a bound of the whole solve that never grows);\n"
     "stage(stage, stages) is called when the stage-th of at most `stages` re-solves\n"
     "starts, stage(STAGE_COMPARE, stages) when method auto's comparison solve by L/L\n"
     "starts, stage(STAGE_FINER, stages) when its L/G solve with a finer hold starts and\n"
     "stage(STAGE_FALLBACK, stages) when its L/G solve after an L/L result with a closed\n"
     "panel starts, each before its first progress call (facet_planarizer_stage)."},
    {"set_fixed", planarizer_set_fixed, METH_O,
     "set_fixed(vertices) -> None\n\nHard-fix these vertices (int32 indices) at their control\n"
     "positions in every later solve; None clears."},
    {"set_reference", planarizer_set_reference, METH_O,
     "set_reference(surface) -> None\n\nThe reference surface (facet._core.Surface, model units) of\n"
     "the surface_weight term; None clears."},
    {"set_face_weights", planarizer_set_face_weights, METH_O,
     "set_face_weights(weights) -> None\n\nPer-face planarity weights (float64, n_faces, >= 0;\n"
     "0 exempts a face); None restores 1."},
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

int py_add_planarize(PyObject *module)
{
    PyObject *type = PyType_FromModuleAndSpec(module, &planarizer_spec, NULL);
    if (!type)
        return -1;
    int r = PyModule_AddObjectRef(module, "Planarizer", type);
    Py_DECREF(type);
    if (r == 0) /* stage(STAGE_COMPARE, stages): method auto's comparison solve */
        r = PyModule_AddIntConstant(module, "STAGE_COMPARE", FACET_STAGE_COMPARE);
    if (r == 0) /* stage(STAGE_FINER, stages): its L/G solve with a finer hold */
        r = PyModule_AddIntConstant(module, "STAGE_FINER", FACET_STAGE_FINER);
    if (r == 0) /* stage(STAGE_FALLBACK, stages): its L/G solve after L/L closed a panel */
        r = PyModule_AddIntConstant(module, "STAGE_FALLBACK", FACET_STAGE_FALLBACK);
    if (r == 0) /* method auto: L/G up to this many face corners, L/L above */
        r = PyModule_AddIntConstant(module, "AUTO_LG_MAX_CORNERS", FACET_AUTO_LG_MAX_CORNERS);
    if (r == 0) /* the deepest Anderson history (option anderson) */
        r = PyModule_AddIntConstant(module, "ANDERSON_MAX", FACET_ANDERSON_MAX);
    const struct {
        const char *name;
        double value;
    } limits[] = {{"WEIGHT_SPAN", FACET_WEIGHT_SPAN}, {"FACE_WEIGHT_MAX", FACET_FACE_WEIGHT_MAX}};
    for (size_t k = 0; r == 0 && k < sizeof limits / sizeof limits[0]; ++k) {
        PyObject *value = PyFloat_FromDouble(limits[k].value);
        r = value ? PyModule_AddObjectRef(module, limits[k].name, value) : -1;
        Py_XDECREF(value);
    }
    return r;
}
