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
#ifdef _WIN32
#define PLATFORM "win64"
#endif
/* An aarch64 build names FMI 3.0's folder (-DPLATFORM='"aarch64-linux"'): FMI 2.0 names no
 * aarch64 platform, and the aarch64 library is packed into the FMI 3.0 FMUs only. */
#ifndef PLATFORM
#define PLATFORM "linux64"
#endif
#include "host_common.h"

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

/* The Run of host_common.h: 0 when every call returned fmi2OK. */
static int run(const char *directory, const Experiment *e, int print) {
    char path[4096], full[4096], uri[4200];
    double values[MAX_OUTPUTS];
    int failed = 0;
    long k;
    void *library;
    fmi2Component instance;
    fmi2Status status;

    if (!(library = open_fmu(directory, e, path, sizeof path, full, sizeof full))) return 2;
#ifdef _WIN32
    {
        size_t i;
        for (i = 0; full[i]; i++)
            if (full[i] == '\\') full[i] = '/';
    }
    snprintf(uri, sizeof uri, "file:///%s/resources", full);
#else
    snprintf(uri, sizeof uri, "file://%s/resources", full);
#endif
    {
        InstantiateT instantiate = (InstantiateT)symbol(library, "fmi2Instantiate");
        SetupExperimentT setup_experiment = (SetupExperimentT)symbol(library, "fmi2SetupExperiment");
        ModeT enter_initialization = (ModeT)symbol(library, "fmi2EnterInitializationMode");
        ModeT exit_initialization = (ModeT)symbol(library, "fmi2ExitInitializationMode");
        ModeT terminate = (ModeT)symbol(library, "fmi2Terminate");
        DoStepT do_step = (DoStepT)symbol(library, "fmi2DoStep");
        GetRealT get_real = (GetRealT)symbol(library, "fmi2GetReal");
        FreeInstanceT free_instance = (FreeInstanceT)symbol(library, "fmi2FreeInstance");
        fmi2CallbackFunctions callbacks = {logger, calloc, free, NULL, NULL};
        if (!instantiate || !setup_experiment || !enter_initialization || !exit_initialization ||
            !terminate || !do_step || !get_real || !free_instance)
            return fprintf(stderr, "%s lacks an fmi2 function\n", path), 2;

        instance = instantiate("host", 1 /* fmi2CoSimulation */, e->token, uri, &callbacks, 0, 0);
        if (!instance) {
            fprintf(stderr, "fmi2Instantiate: NULL\n");
            unload_library(library);
            return 1;
        }
        CALL(setup_experiment(instance, 0, 0.0, e->start, 1, e->stop));
        CALL(enter_initialization(instance));
        CALL(exit_initialization(instance));
        if (print) print_header(e);
        for (k = 0; k <= e->steps && !failed; k++) {
            double t = e->start + (double)k * e->step;
            CALL(get_real(instance, e->references, e->outputs, values));
            if (print) print_row(e, t, values);
            /* Each step ends on the grid point start + (k + 1) step, as fmpy's master does. */
            if (k < e->steps) CALL(do_step(instance, t, e->start + (double)(k + 1) * e->step - t, 1));
        }
        CALL(terminate(instance));
        free_instance(instance);
    }
    unload_library(library);
    return failed;
}

int main(int argc, char **argv) {
    return host_main(argc, argv, "--guid", "GUID", 0, run);
}
