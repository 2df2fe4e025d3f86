/* A small FMI 2.0 co-simulation host in plain C, as a tool vendor's importer would be: it opens an
 * extracted FMU, loads the binary for its own platform, runs the DefaultExperiment with a real
 * variadic logger and writes every Real output at every communication point as CSV.
 *
 *   fmu_host DIR [--guid GUID] [--cycles N] [--steps K]
 *
 * DIR: the extracted FMU; --guid: instantiate with another GUID; --cycles: load, run, free and
 * unload the library N times (the CSV is the last cycle's), as a host that reopens FMUs for
 * hours does; --steps: run only the experiment's first K steps.
 *
 * Build: gcc -O2 -o fmu_host fmu_host.c -ldl
 *        x86_64-w64-mingw32-gcc -O2 -o fmu_host.exe fmu_host.c
 *        aarch64-linux-gnu-gcc -O2 -DPLATFORM='"aarch64-linux"' -o fmu_host_aarch64 fmu_host.c -ldl
 *        (run with qemu-aarch64 -L /usr/aarch64-linux-gnu)
 * Exit status: 0 when every call returned fmi2OK; 1 when a call returned anything else (the
 * status is printed on stderr, with every message the FMU logged); 2 for a usage or load error.
 */
#define __USE_MINGW_ANSI_STDIO 1 /* C99 printf on Windows: %.17g round-trips a double */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _WIN32
#include <windows.h>
#define PLATFORM "win64"
#define EXTENSION ".dll"
#define SEPARATOR "\\"
#else
#include <dlfcn.h>
#include <limits.h>
/* An aarch64 build names FMI 3.0's folder (-DPLATFORM='"aarch64-linux"'): FMI 2.0 names no
 * aarch64 platform, and the aarch64 library is packed into the FMI 3.0 FMUs only. */
#ifndef PLATFORM
#define PLATFORM "linux64"
#endif
#define EXTENSION ".so"
#define SEPARATOR "/"
#endif

typedef void *fmi2Component;
typedef int fmi2Status;
typedef int fmi2Boolean;
typedef unsigned int fmi2ValueReference;
typedef struct {
    void (*logger)(void *, const char *, fmi2Status, const char *, const char *, ...);
    void *(*allocateMemory)(size_t, size_t);
    void (*freeMemory)(void *);
    void (*stepFinished)(void *, fmi2Status);
    void *componentEnvironment;
} fmi2CallbackFunctions;

typedef fmi2Component (*InstantiateT)(const char *, int, const char *, const char *,
                                      const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
typedef fmi2Status (*SetupExperimentT)(fmi2Component, fmi2Boolean, double, double, fmi2Boolean,
                                       double);
typedef fmi2Status (*ModeT)(fmi2Component);
typedef fmi2Status (*DoStepT)(fmi2Component, double, double, fmi2Boolean);
typedef fmi2Status (*GetRealT)(fmi2Component, const fmi2ValueReference *, size_t, double *);
typedef void (*FreeInstanceT)(fmi2Component);

#define MAX_OUTPUTS 64
#define MAX_TEXT 256

/* The FMU's messages, each with its status: printf-style, as FMI 2.0 defines the logger. */
static void logger(void *environment, const char *instance, fmi2Status status,
                   const char *category, const char *message, ...) {
    va_list args;
    (void)environment;
    fprintf(stderr, "log %s status %d [%s]: ", instance ? instance : "?", status,
            category ? category : "");
    va_start(args, message);
    vfprintf(stderr, message, args);
    va_end(args);
    fputc('\n', stderr);
}

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    char *text;
    long size;
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    size = ftell(f);
    fseek(f, 0, SEEK_SET);
    text = malloc((size_t)size + 1);
    if (text && fread(text, 1, (size_t)size, f) != (size_t)size) {
        free(text);
        text = NULL;
    }
    if (text) text[size] = '\0';
    fclose(f);
    return text;
}

/* The value of attribute `name` in the tag that starts at `tag` (up to its '>'), or 0. */
static int attribute(const char *tag, const char *name, char *value, size_t size) {
    const char *end = strchr(tag, '>');
    size_t length = strlen(name);
    const char *p = tag;
    while ((p = strstr(p, name)) && (!end || p < end)) {
        if (p[-1] == ' ' && p[length] == '=' && p[length + 1] == '"') {
            const char *start = p + length + 2, *stop = strchr(start, '"');
            size_t n = (size_t)(stop - start);
            if (!stop || n >= size) return 0;
            memcpy(value, start, n);
            value[n] = '\0';
            return 1;
        }
        p += length;
    }
    return 0;
}

/* What the host learnt from modelDescription.xml and its arguments. */
typedef struct {
    char guid[MAX_TEXT], identifier[MAX_TEXT];
    char names[MAX_OUTPUTS][MAX_TEXT];
    fmi2ValueReference references[MAX_OUTPUTS];
    size_t outputs;
    double start, stop, step;
    long steps;
} Experiment;

/* Reads modelDescription.xml under `directory`; 0 on success, else the exit status. */
static int read_experiment(const char *directory, Experiment *e) {
    char path[4096], text[MAX_TEXT];
    const char *p, *xml_end;
    char *xml;
    snprintf(path, sizeof path, "%s" SEPARATOR "modelDescription.xml", directory);
    xml = read_file(path);
    if (!xml) return fprintf(stderr, "cannot read %s\n", path), 2;
    p = strstr(xml, "<fmiModelDescription");
    if (!p || !attribute(p, "guid", e->guid, sizeof e->guid)) return fprintf(stderr, "no guid\n"), 2;
    p = strstr(xml, "<CoSimulation");
    if (!p || !attribute(p, "modelIdentifier", e->identifier, sizeof e->identifier))
        return fprintf(stderr, "no CoSimulation modelIdentifier\n"), 2;
    p = strstr(xml, "<DefaultExperiment");
    if (!p || !attribute(p, "startTime", text, sizeof text)) return fprintf(stderr, "no experiment\n"), 2;
    e->start = strtod(text, NULL);
    if (!attribute(p, "stopTime", text, sizeof text)) return fprintf(stderr, "no stopTime\n"), 2;
    e->stop = strtod(text, NULL);
    if (!attribute(p, "stepSize", text, sizeof text)) return fprintf(stderr, "no stepSize\n"), 2;
    e->step = strtod(text, NULL);
    e->steps = (long)((e->stop - e->start) / e->step + 0.5);
    e->outputs = 0;
    xml_end = strstr(xml, "</ModelVariables>");
    for (p = strstr(xml, "<ScalarVariable"); p && p < xml_end; p = strstr(p + 1, "<ScalarVariable")) {
        const char *type = strchr(p, '>') + 1;
        while (*type == ' ' || *type == '\n' || *type == '\r') type++;
        if (!attribute(p, "causality", text, sizeof text) || strcmp(text, "output") != 0 ||
            strncmp(type, "<Real", 5) != 0)
            continue;
        if (e->outputs == MAX_OUTPUTS) return fprintf(stderr, "more than %d outputs\n", MAX_OUTPUTS), 2;
        attribute(p, "name", e->names[e->outputs], MAX_TEXT);
        attribute(p, "valueReference", text, sizeof text);
        e->references[e->outputs++] = (fmi2ValueReference)strtoul(text, NULL, 10);
    }
    free(xml);
    return 0;
}

/* Loads the library, runs the experiment, frees the instance and unloads the library. Prints
 * the CSV when `print` is set. 0 when every call returned fmi2OK, 1 when one did not, 2 for a
 * load error. */
static int run(const char *directory, const Experiment *e, int print) {
    char path[4096], uri[4200];
    double values[MAX_OUTPUTS];
    size_t i;
    int failed = 0;
    long k;
    void *library;
    fmi2Component instance;
    fmi2Status status;

    snprintf(path, sizeof path, "%s" SEPARATOR "binaries" SEPARATOR PLATFORM SEPARATOR "%s" EXTENSION,
             directory, e->identifier);
#ifdef _WIN32
    library = (void *)LoadLibraryA(path);
    if (!library) return fprintf(stderr, "LoadLibrary %s: error %lu\n", path, GetLastError()), 2;
#define SYMBOL(name) (void *)GetProcAddress((HMODULE)library, name)
#define UNLOAD() FreeLibrary((HMODULE)library)
    {
        char full[4096];
        GetFullPathNameA(directory, sizeof full, full, NULL);
        for (i = 0; full[i]; i++)
            if (full[i] == '\\') full[i] = '/';
        snprintf(uri, sizeof uri, "file:///%s/resources", full);
    }
#else
    library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) return fprintf(stderr, "dlopen: %s\n", dlerror()), 2;
#define SYMBOL(name) dlsym(library, name)
#define UNLOAD() dlclose(library)
    {
        char full[PATH_MAX];
        if (!realpath(directory, full)) return fprintf(stderr, "no path %s\n", directory), 2;
        snprintf(uri, sizeof uri, "file://%s/resources", full);
    }
#endif
    {
        InstantiateT instantiate = (InstantiateT)SYMBOL("fmi2Instantiate");
        SetupExperimentT setup_experiment = (SetupExperimentT)SYMBOL("fmi2SetupExperiment");
        ModeT enter_initialization = (ModeT)SYMBOL("fmi2EnterInitializationMode");
        ModeT exit_initialization = (ModeT)SYMBOL("fmi2ExitInitializationMode");
        ModeT terminate = (ModeT)SYMBOL("fmi2Terminate");
        DoStepT do_step = (DoStepT)SYMBOL("fmi2DoStep");
        GetRealT get_real = (GetRealT)SYMBOL("fmi2GetReal");
        FreeInstanceT free_instance = (FreeInstanceT)SYMBOL("fmi2FreeInstance");
        fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
        if (!instantiate || !setup_experiment || !enter_initialization || !exit_initialization ||
            !terminate || !do_step || !get_real || !free_instance)
            return fprintf(stderr, "%s lacks an fmi2 function\n", path), 2;

        instance = instantiate("host", 1 /* fmi2CoSimulation */, e->guid, uri, &callbacks, 0, 0);
        if (!instance) {
            fprintf(stderr, "fmi2Instantiate: NULL\n");
            UNLOAD();
            return 1;
        }
#define CALL(call)                                                    \
    if ((status = (call)) != 0) {                                     \
        fprintf(stderr, "%s: status %d\n", #call, status);            \
        failed = 1;                                                   \
    }
        CALL(setup_experiment(instance, 0, 0.0, e->start, 1, e->stop));
        CALL(enter_initialization(instance));
        CALL(exit_initialization(instance));
        if (print) {
            printf("time");
            for (i = 0; i < e->outputs; i++) printf(",%s", e->names[i]);
            printf("\n");
        }
        for (k = 0; k <= e->steps && !failed; k++) {
            double t = e->start + (double)k * e->step;
            CALL(get_real(instance, e->references, e->outputs, values));
            if (print) {
                printf("%.17g", t);
                for (i = 0; i < e->outputs; i++) printf(",%.17g", values[i]);
                printf("\n");
            }
            /* Each step ends on the grid point start + (k + 1) step, as fmpy's master does. */
            if (k < e->steps) CALL(do_step(instance, t, e->start + (double)(k + 1) * e->step - t, 1));
        }
        CALL(terminate(instance));
        free_instance(instance);
    }
    UNLOAD();
    return failed;
}

int main(int argc, char **argv) {
    static Experiment experiment;
    const char *guid = NULL;
    long cycles = 1, steps = -1, cycle;
    int a, status = 0;

    for (a = 2; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], "--guid") == 0) guid = argv[a + 1];
        else if (strcmp(argv[a], "--cycles") == 0) cycles = strtol(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--steps") == 0) steps = strtol(argv[a + 1], NULL, 10);
        else break;
    }
    if (argc < 2 || a != argc || cycles < 1) {
        fprintf(stderr, "usage: %s EXTRACTED_FMU_DIR [--guid GUID] [--cycles N] [--steps K]\n", argv[0]);
        return 2;
    }
    if ((status = read_experiment(argv[1], &experiment)) != 0) return status;
    if (guid) snprintf(experiment.guid, sizeof experiment.guid, "%s", guid);
    if (steps >= 0 && steps < experiment.steps) experiment.steps = steps;
    for (cycle = 1; cycle <= cycles && status == 0; cycle++)
        status = run(argv[1], &experiment, cycle == cycles);
    return status;
}
