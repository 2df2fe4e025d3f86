/* A small FMI 3.0 co-simulation host in plain C, compiled against the standard's own headers
 * (fmi3FunctionTypes.h, fmi3PlatformTypes.h), as a tool vendor's importer would be: it opens an
 * extracted FMU, loads the binary for its own platform, runs the DefaultExperiment through
 * fmi3InstantiateCoSimulation .. fmi3DoStep .. fmi3FreeInstance and writes every Float64 output at
 * every communication point as CSV, as tests/host/fmu_host.c does for FMI 2.0.
 *
 *   fmu_host3 DIR [--token TOKEN] [--cycles N] [--steps K]
 *
 * DIR: the extracted FMU; --token: instantiate with another instantiationToken; --cycles: load,
 * run, free and unload the library N times (the CSV is the last cycle's); --steps: run only the
 * experiment's first K steps.
 *
 * An FMI 2.0 FMU's directory works too, as every library of this project exports both standards:
 * its GUID is the token, its Real outputs the Float64 ones, and binaries/linux64 (win64) stands in
 * for binaries/x86_64-linux (x86_64-windows) when that is missing.
 *
 * Build: gcc -O2 -I HEADERS -o fmu_host3 fmu_host3.c -ldl
 *        x86_64-w64-mingw32-gcc -O2 -I HEADERS -o fmu_host3.exe fmu_host3.c
 * HEADERS: the FMI 3.0 headers (fmpy ships them in fmpy/c-code; tests/python/test_host_fmi3.py
 * finds them). Exit status: 0 when every call returned fmi3OK and every step ended where it was
 * asked to; 1 otherwise (printed on stderr, with every message the FMU logged); 2 for a usage or
 * load error.
 */
#define __USE_MINGW_ANSI_STDIO 1 /* C99 printf on Windows: %.17g round-trips a double */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "fmi3FunctionTypes.h"
#ifdef _WIN32
#include <windows.h>
#define PLATFORM "x86_64-windows"
#define FMI2_PLATFORM "win64"
#define EXTENSION ".dll"
#define SEPARATOR "\\"
#else
#include <dlfcn.h>
#include <limits.h>
#if defined(__aarch64__)
#define PLATFORM "aarch64-linux"
#define FMI2_PLATFORM "aarch64-linux"
#else
#define PLATFORM "x86_64-linux"
#define FMI2_PLATFORM "linux64"
#endif
#define EXTENSION ".so"
#define SEPARATOR "/"
#endif

#define MAX_OUTPUTS 64
#define MAX_TEXT 256

/* The FMU's messages, each with its status: FMI 3.0 passes the text as it is. */
static void log_message(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                        fmi3String message) {
    (void)environment;
    fprintf(stderr, "log status %d [%s]: %s\n", (int)status, category ? category : "",
            message ? message : "");
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
        if ((p[-1] == ' ' || p[-1] == '\n' || p[-1] == '\t') && p[length] == '=' && p[length + 1] == '"') {
            const char *start = p + length + 2, *stop = strchr(start, '"');
            size_t n;
            if (!stop) return 0;
            n = (size_t)(stop - start);
            if (n >= size) return 0;
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
    char token[MAX_TEXT], identifier[MAX_TEXT];
    char names[MAX_OUTPUTS][MAX_TEXT];
    fmi3ValueReference references[MAX_OUTPUTS];
    size_t outputs;
    double start, stop, step;
    long steps;
} Experiment;

/* Adds the output the variable tag at `p` declares, if it is one; 0 or the exit status. */
static int add_output(Experiment *e, const char *p) {
    char text[MAX_TEXT];
    if (!attribute(p, "causality", text, sizeof text) || strcmp(text, "output") != 0) return 0;
    if (e->outputs == MAX_OUTPUTS) return fprintf(stderr, "more than %d outputs\n", MAX_OUTPUTS), 2;
    attribute(p, "name", e->names[e->outputs], MAX_TEXT);
    attribute(p, "valueReference", text, sizeof text);
    e->references[e->outputs++] = (fmi3ValueReference)strtoul(text, NULL, 10);
    return 0;
}

/* Reads modelDescription.xml under `directory` (FMI 3.0's, or FMI 2.0's); 0 on success, else the
 * exit status. */
static int read_experiment(const char *directory, Experiment *e) {
    char path[4096], text[MAX_TEXT];
    const char *p, *xml_end;
    char *xml;
    int status;
    snprintf(path, sizeof path, "%s" SEPARATOR "modelDescription.xml", directory);
    xml = read_file(path);
    if (!xml) return fprintf(stderr, "cannot read %s\n", path), 2;
    p = strstr(xml, "<fmiModelDescription");
    if (!p || !(attribute(p, "instantiationToken", e->token, sizeof e->token) ||
                attribute(p, "guid", e->token, sizeof e->token)))
        return fprintf(stderr, "no instantiationToken\n"), 2;
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
    p = strstr(xml, "<ModelVariables");
    if (!p || !xml_end) return fprintf(stderr, "no ModelVariables\n"), 2;
    /* FMI 3.0: <Float64 .../>. FMI 2.0: <ScalarVariable ...><Real .../>. */
    for (; p && p < xml_end; p = strchr(p + 1, '<')) {
        if (strncmp(p, "<Float64", 8) == 0 && (p[8] == ' ' || p[8] == '\n')) {
            if ((status = add_output(e, p)) != 0) return status;
        } else if (strncmp(p, "<ScalarVariable", 15) == 0) {
            const char *type = strchr(p, '>') + 1;
            while (*type == ' ' || *type == '\n' || *type == '\r') type++;
            if (strncmp(type, "<Real", 5) == 0 && (status = add_output(e, p)) != 0) return status;
        }
    }
    free(xml);
    return 0;
}

/* The library's path: binaries/PLATFORM, or FMI 2.0's name of the platform for an FMI 2.0 FMU. */
static void library_path(const char *directory, const Experiment *e, char *path, size_t size) {
    FILE *f;
    snprintf(path, size, "%s" SEPARATOR "binaries" SEPARATOR PLATFORM SEPARATOR "%s" EXTENSION, directory,
             e->identifier);
    if ((f = fopen(path, "rb")) != NULL) {
        fclose(f);
        return;
    }
    snprintf(path, size, "%s" SEPARATOR "binaries" SEPARATOR FMI2_PLATFORM SEPARATOR "%s" EXTENSION, directory,
             e->identifier);
}

/* Loads the library, runs the experiment, frees the instance and unloads the library. Prints the
 * CSV when `print` is set. 0 when every call returned fmi3OK, 1 when one did not, 2 for a load
 * error. */
static int run(const char *directory, const Experiment *e, int print) {
    char path[4096], resources[4200];
    double values[MAX_OUTPUTS];
    size_t i;
    int failed = 0;
    long k;
    void *library;
    fmi3Instance instance;
    fmi3Status status;

    library_path(directory, e, path, sizeof path);
#ifdef _WIN32
    library = (void *)LoadLibraryA(path);
    if (!library) return fprintf(stderr, "LoadLibrary %s: error %lu\n", path, GetLastError()), 2;
#define SYMBOL(name) (void *)GetProcAddress((HMODULE)library, name)
#define UNLOAD() FreeLibrary((HMODULE)library)
    {
        char full[4096];
        GetFullPathNameA(directory, sizeof full, full, NULL);
        snprintf(resources, sizeof resources, "%s\\resources\\", full);
    }
#else
    library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) return fprintf(stderr, "dlopen: %s\n", dlerror()), 2;
#define SYMBOL(name) dlsym(library, name)
#define UNLOAD() dlclose(library)
    {
        char full[PATH_MAX];
        if (!realpath(directory, full)) return fprintf(stderr, "no path %s\n", directory), 2;
        snprintf(resources, sizeof resources, "%s/resources/", full);
    }
#endif
    {
        fmi3InstantiateCoSimulationTYPE *instantiate =
            (fmi3InstantiateCoSimulationTYPE *)SYMBOL("fmi3InstantiateCoSimulation");
        fmi3EnterInitializationModeTYPE *enter_initialization =
            (fmi3EnterInitializationModeTYPE *)SYMBOL("fmi3EnterInitializationMode");
        fmi3ExitInitializationModeTYPE *exit_initialization =
            (fmi3ExitInitializationModeTYPE *)SYMBOL("fmi3ExitInitializationMode");
        fmi3TerminateTYPE *terminate = (fmi3TerminateTYPE *)SYMBOL("fmi3Terminate");
        fmi3DoStepTYPE *do_step = (fmi3DoStepTYPE *)SYMBOL("fmi3DoStep");
        fmi3GetFloat64TYPE *get_float64 = (fmi3GetFloat64TYPE *)SYMBOL("fmi3GetFloat64");
        fmi3FreeInstanceTYPE *free_instance = (fmi3FreeInstanceTYPE *)SYMBOL("fmi3FreeInstance");
        if (!instantiate || !enter_initialization || !exit_initialization || !terminate || !do_step ||
            !get_float64 || !free_instance)
            return fprintf(stderr, "%s lacks an fmi3 function\n", path), 2;

        instance = instantiate("host", e->token, resources, fmi3False, fmi3False,
                               fmi3False /* eventModeUsed */, fmi3False /* earlyReturnAllowed */, NULL, 0,
                               NULL, log_message, NULL);
        if (!instance) {
            fprintf(stderr, "fmi3InstantiateCoSimulation: NULL\n");
            UNLOAD();
            return 1;
        }
#define CALL(call)                                                    \
    if ((status = (call)) != fmi3OK) {                                \
        fprintf(stderr, "%s: status %d\n", #call, (int)status);       \
        failed = 1;                                                   \
    }
        CALL(enter_initialization(instance, fmi3False, 0.0, e->start, fmi3True, e->stop));
        CALL(exit_initialization(instance));
        if (print) {
            printf("time");
            for (i = 0; i < e->outputs; i++) printf(",%s", e->names[i]);
            printf("\n");
        }
        for (k = 0; k <= e->steps && !failed; k++) {
            double t = e->start + (double)k * e->step;
            CALL(get_float64(instance, e->references, e->outputs, values, e->outputs));
            if (print) {
                printf("%.17g", t);
                for (i = 0; i < e->outputs; i++) printf(",%.17g", values[i]);
                printf("\n");
            }
            /* Each step ends on the grid point start + (k + 1) step, as fmpy's master does. */
            if (k < e->steps) {
                double end = e->start + (double)(k + 1) * e->step, last = -1.0;
                fmi3Boolean event = fmi3True, stop = fmi3True, early = fmi3True;
                CALL(do_step(instance, t, end - t, fmi3True, &event, &stop, &early, &last));
                if (!failed && (event || stop || early || last != t + (end - t))) {
                    fprintf(stderr, "fmi3DoStep(%.17g, %.17g): eventHandlingNeeded %d, terminateSimulation %d, "
                            "earlyReturn %d, lastSuccessfulTime %.17g\n", t, end - t, event, stop, early, last);
                    failed = 1;
                }
            }
        }
        CALL(terminate(instance));
        free_instance(instance);
    }
    UNLOAD();
    return failed;
}

int main(int argc, char **argv) {
    static Experiment experiment;
    const char *token = NULL;
    long cycles = 1, steps = -1, cycle;
    int a, status = 0;

    for (a = 2; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], "--token") == 0) token = argv[a + 1];
        else if (strcmp(argv[a], "--cycles") == 0) cycles = strtol(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--steps") == 0) steps = strtol(argv[a + 1], NULL, 10);
        else break;
    }
    if (argc < 2 || a != argc || cycles < 1) {
        fprintf(stderr, "usage: %s EXTRACTED_FMU_DIR [--token TOKEN] [--cycles N] [--steps K]\n", argv[0]);
        return 2;
    }
    if ((status = read_experiment(argv[1], &experiment)) != 0) return status;
    if (token) snprintf(experiment.token, sizeof experiment.token, "%s", token);
    if (steps >= 0 && steps < experiment.steps) experiment.steps = steps;
    for (cycle = 1; cycle <= cycles && status == 0; cycle++)
        status = run(argv[1], &experiment, cycle == cycles);
    return status;
}
