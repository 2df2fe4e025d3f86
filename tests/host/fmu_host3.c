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
#include "fmi3FunctionTypes.h"
#ifdef _WIN32
#define PLATFORM "x86_64-windows"
#define FALLBACK_PLATFORM "win64"
#elif defined(__aarch64__)
#define PLATFORM "aarch64-linux"
#else
#define PLATFORM "x86_64-linux"
#define FALLBACK_PLATFORM "linux64"
#endif
#include "host_common.h"

/* The FMU's messages, each with its status: FMI 3.0 passes the text as it is. */
static void log_message(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                        fmi3String message) {
    (void)environment;
    fprintf(stderr, "log status %d [%s]: %s\n", (int)status, category ? category : "",
            message ? message : "");
}

/* The Run of host_common.h: 0 when every call returned fmi3OK and every step ended where it was
 * asked to. */
static int run(const char *directory, const Experiment *e, int print) {
    char path[4096], full[4096], resources[4200];
    double values[MAX_OUTPUTS];
    int failed = 0;
    long k;
    void *library;
    fmi3Instance instance;
    fmi3Status status;

    if (!(library = open_fmu(directory, e, path, sizeof path, full, sizeof full))) return 2;
    snprintf(resources, sizeof resources, "%s" SEPARATOR "resources" SEPARATOR, full);
    {
        fmi3InstantiateCoSimulationTYPE *instantiate =
            (fmi3InstantiateCoSimulationTYPE *)symbol(library, "fmi3InstantiateCoSimulation");
        fmi3EnterInitializationModeTYPE *enter_initialization =
            (fmi3EnterInitializationModeTYPE *)symbol(library, "fmi3EnterInitializationMode");
        fmi3ExitInitializationModeTYPE *exit_initialization =
            (fmi3ExitInitializationModeTYPE *)symbol(library, "fmi3ExitInitializationMode");
        fmi3TerminateTYPE *terminate = (fmi3TerminateTYPE *)symbol(library, "fmi3Terminate");
        fmi3DoStepTYPE *do_step = (fmi3DoStepTYPE *)symbol(library, "fmi3DoStep");
        fmi3GetFloat64TYPE *get_float64 = (fmi3GetFloat64TYPE *)symbol(library, "fmi3GetFloat64");
        fmi3FreeInstanceTYPE *free_instance = (fmi3FreeInstanceTYPE *)symbol(library, "fmi3FreeInstance");
        if (!instantiate || !enter_initialization || !exit_initialization || !terminate || !do_step ||
            !get_float64 || !free_instance)
            return fprintf(stderr, "%s lacks an fmi3 function\n", path), 2;

        instance = instantiate("host", e->token, resources, fmi3False, fmi3False,
                               fmi3False /* eventModeUsed */, fmi3False /* earlyReturnAllowed */, NULL, 0,
                               NULL, log_message, NULL);
        if (!instance) {
            fprintf(stderr, "fmi3InstantiateCoSimulation: NULL\n");
            unload_library(library);
            return 1;
        }
        CALL(enter_initialization(instance, fmi3False, 0.0, e->start, fmi3True, e->stop));
        CALL(exit_initialization(instance));
        if (print) print_header(e);
        for (k = 0; k <= e->steps && !failed; k++) {
            double t = e->start + (double)k * e->step;
            CALL(get_float64(instance, e->references, e->outputs, values, e->outputs));
            if (print) print_row(e, t, values);
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
    unload_library(library);
    return failed;
}

int main(int argc, char **argv) {
    return host_main(argc, argv, "--token", "TOKEN", 1, run);
}
