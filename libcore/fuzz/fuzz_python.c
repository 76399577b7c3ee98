/* SPDX-License-Identifier: LGPL-2.1-or-later */
/*
 * fuzz_python.c -- a libFuzzer target that embeds CPython and runs Facet's
 * Python readers (OBJ, OFF, compas JSON, plan drawings in DXF/CSV/mesh form,
 * CSV targets) on the fuzz bytes through tools/fuzz/harness.py, which also
 * hands what was read on to the compiled core.
 *
 * Coverage: libFuzzer sees the C code it was compiled with, not Python
 * lines. A C-level trace function (PyEval_SetTrace) hashes each executed
 * Python line with the previous one (AFL-style edges) into libFuzzer's
 * "extra counters" section, so the fuzzer is guided by Python line
 * coverage too.
 *
 * A finding is any exception other than facet.errors.InputError (the
 * harness decides; see its docstring): printed with its traceback, then
 * abort().
 *
 * Environment: FACET_FUZZ_WORKBENCH (the workbench/ directory),
 * FACET_FUZZ_HARNESS (tools/fuzz/), FACET_FUZZ_CORE (a directory holding a
 * sanitizer build of facet._core to use instead of the one in workbench/).
 * Defaults are compiled in from the source tree.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <frameobject.h>

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#ifndef FACET_SOURCE_DIR
#define FACET_SOURCE_DIR "."
#endif
#ifndef FACET_CORE_DIR
#define FACET_CORE_DIR ""
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define N_COUNTERS (1u << 16)
__attribute__((section("__libfuzzer_extra_counters"), used)) static uint8_t counters[N_COUNTERS];
static uint32_t previous;
static PyObject *one_input;

static int trace(PyObject *obj, PyFrameObject *frame, int what, PyObject *arg)
{
    (void)obj;
    (void)arg;
    if (what != PyTrace_LINE && what != PyTrace_CALL) return 0;
    PyCodeObject *code = PyFrame_GetCode(frame);
    uint64_t h = (uint64_t)(uintptr_t)code * 0x9E3779B97F4A7C15ull;
    Py_DECREF(code);
    h ^= (uint64_t)PyFrame_GetLineNumber(frame) * 0xC2B2AE3D27D4EB4Full;
    uint32_t here = (uint32_t)(h >> 32) ^ (uint32_t)h;
    uint8_t *c = &counters[(here ^ previous) % N_COUNTERS];
    if (*c < 255) ++*c;
    previous = here >> 1;
    return 0;
}

static const char *env_or(const char *name, const char *fallback)
{
    const char *v = getenv(name);
    return v && *v ? v : fallback;
}

static void fail_python(const char *what)
{
    fprintf(stderr, "fuzz_python: %s\n", what);
    if (PyErr_Occurred()) PyErr_Print();
    abort();
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *workbench = env_or("FACET_FUZZ_WORKBENCH", FACET_SOURCE_DIR "/workbench");
    const char *harness = env_or("FACET_FUZZ_HARNESS", FACET_SOURCE_DIR "/tools/fuzz");
    const char *core = env_or("FACET_FUZZ_CORE", FACET_CORE_DIR);
    PyConfig config;
    PyConfig_InitPythonConfig(&config);
    config.install_signal_handlers = 0; /* libFuzzer owns SIGINT and friends */
    config.parse_argv = 0;
    PyStatus status = Py_InitializeFromConfig(&config);
    PyConfig_Clear(&config);
    if (PyStatus_Exception(status)) {
        fprintf(stderr, "fuzz_python: cannot start Python: %s\n", status.err_msg ? status.err_msg : "?");
        abort();
    }
    /* sys.path: the harness and the workbench; a sanitizer-built facet._core
     * (FACET_FUZZ_CORE) is found first through facet.__path__. */
    PyObject *globals = PyDict_New();
    PyDict_SetItemString(globals, "__builtins__", PyEval_GetBuiltins());
    PyDict_SetItemString(globals, "workbench", PyUnicode_FromString(workbench));
    PyDict_SetItemString(globals, "harness_dir", PyUnicode_FromString(harness));
    PyDict_SetItemString(globals, "core_dir", PyUnicode_FromString(core));
    PyObject *r = PyRun_String(
        "import sys, importlib.machinery, importlib.util\n"
        "sys.path[:0] = [harness_dir, workbench]\n"
        "if core_dir:\n"
        "    import glob\n"
        "    found = glob.glob(core_dir + '/_core*.so')\n"
        "    if found:\n"
        "        spec = importlib.util.spec_from_file_location('facet._core', found[0])\n"
        "        class CoreFinder:\n"
        "            @staticmethod\n"
        "            def find_spec(name, path=None, target=None):\n"
        "                return spec if name == 'facet._core' else None\n"
        "        sys.meta_path.insert(0, CoreFinder)\n"
        "import harness\n"
        "import facet._core, facet.planarize, facet.lift, facet.panels, facet.plan, facet.io\n"
        "import ezdxf, shapely, scipy.spatial\n"
        "sys.stderr.write('fuzz_python: facet._core from %s\\n' % facet._core.__file__)\n"
        "one_input = harness.one_input\n",
        Py_file_input, globals, globals);
    if (r == NULL) fail_python("cannot import the harness");
    Py_DECREF(r);
    one_input = PyDict_GetItemString(globals, "one_input");
    Py_XINCREF(one_input);
    Py_DECREF(globals);
    if (one_input == NULL) fail_python("harness.one_input missing");
    PyEval_SetTrace(trace, NULL);
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (one_input == NULL) LLVMFuzzerInitialize(NULL, NULL);
    PyObject *bytes = PyBytes_FromStringAndSize((const char *)data, (Py_ssize_t)size);
    if (bytes == NULL) fail_python("out of memory");
    previous = 0;
    PyObject *r = PyObject_CallOneArg(one_input, bytes);
    Py_DECREF(bytes);
    if (r == NULL) fail_python("FINDING: the harness raised");
    Py_DECREF(r);
    return 0;
}
