/* What the plain-C hosts of both standards share (tests/host/fmu_host.c for FMI 2.0,
 * tests/host/fmu_host3.c for FMI 3.0): reading the extracted FMU's modelDescription.xml, finding,
 * loading and unloading its library, the CSV they print, and their command line.
 *
 * A header of static functions, included by each host: the build commands stay one source file a
 * host. The includer defines PLATFORM (the folder under binaries/ its library is read from), and
 * may define FALLBACK_PLATFORM, the folder tried when PLATFORM's library is missing.
 */
#ifndef HOST_COMMON_H
#define HOST_COMMON_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#ifdef _WIN32
#include <windows.h>
#define EXTENSION ".dll"
#define SEPARATOR "\\"
#else
#include <dlfcn.h>
#include <limits.h>
#define EXTENSION ".so"
#define SEPARATOR "/"
#endif

#define MAX_OUTPUTS 64
#define MAX_TEXT 256

/* Calls `call`, an FMI function of either standard (OK is 0 in both), and marks the run failed
 * with the call and its status on stderr when it returns anything else. */
#define CALL(call)                                              \
    if ((status = (call)) != 0) {                               \
        fprintf(stderr, "%s: status %d\n", #call, (int)status); \
        failed = 1;                                             \
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

/* What the host learnt from modelDescription.xml and its arguments. The value references are
 * unsigned int, the type of fmi2ValueReference and of fmi3ValueReference (uint32_t) alike. */
typedef struct {
    /* FMI 2.0's guid or FMI 3.0's instantiationToken. */
    char token[MAX_TEXT], identifier[MAX_TEXT];
    char names[MAX_OUTPUTS][MAX_TEXT];
    unsigned int references[MAX_OUTPUTS];
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
    e->references[e->outputs++] = (unsigned int)strtoul(text, NULL, 10);
    return 0;
}

/* Reads modelDescription.xml under `directory`; 0 on success, else the exit status. FMI 2.0's
 * description: its guid, and its <ScalarVariable> outputs of type <Real>. With `fmi3` set, FMI
 * 3.0's too: its instantiationToken, and its <Float64> outputs. */
static int read_experiment(const char *directory, Experiment *e, int fmi3) {
    char path[4096], text[MAX_TEXT];
    const char *p, *xml_end;
    char *xml;
    int status;
    snprintf(path, sizeof path, "%s" SEPARATOR "modelDescription.xml", directory);
    xml = read_file(path);
    if (!xml) return fprintf(stderr, "cannot read %s\n", path), 2;
    p = strstr(xml, "<fmiModelDescription");
    if (!p || !((fmi3 && attribute(p, "instantiationToken", e->token, sizeof e->token)) ||
                attribute(p, "guid", e->token, sizeof e->token)))
        return fprintf(stderr, fmi3 ? "no instantiationToken\n" : "no guid\n"), 2;
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
    for (; p && p < xml_end; p = strchr(p + 1, '<')) {
        if (fmi3 && strncmp(p, "<Float64", 8) == 0 && (p[8] == ' ' || p[8] == '\n')) {
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

/* The library's path: binaries/PLATFORM, or binaries/FALLBACK_PLATFORM where that is missing. */
static void library_path(const char *directory, const Experiment *e, char *path, size_t size) {
    snprintf(path, size, "%s" SEPARATOR "binaries" SEPARATOR PLATFORM SEPARATOR "%s" EXTENSION, directory,
             e->identifier);
#ifdef FALLBACK_PLATFORM
    {
        FILE *f = fopen(path, "rb");
        if (f) {
            fclose(f);
            return;
        }
        snprintf(path, size, "%s" SEPARATOR "binaries" SEPARATOR FALLBACK_PLATFORM SEPARATOR "%s" EXTENSION,
                 directory, e->identifier);
    }
#endif
}

/* The FMU's library, loaded; NULL (said on stderr) when it cannot be. */
static void *load_library(const char *path) {
#ifdef _WIN32
    void *library = (void *)LoadLibraryA(path);
    if (!library) fprintf(stderr, "LoadLibrary %s: error %lu\n", path, GetLastError());
#else
    void *library = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (!library) fprintf(stderr, "dlopen: %s\n", dlerror());
#endif
    return library;
}

static void *symbol(void *library, const char *name) {
#ifdef _WIN32
    return (void *)GetProcAddress((HMODULE)library, name);
#else
    return dlsym(library, name);
#endif
}

static void unload_library(void *library) {
#ifdef _WIN32
    FreeLibrary((HMODULE)library);
#else
    dlclose(library);
#endif
}

/* The absolute path of `directory`, with the platform's separators; 0 (said on stderr) when it
 * has none. */
static int full_path(const char *directory, char *full, size_t size) {
#ifdef _WIN32
    DWORD length = GetFullPathNameA(directory, (DWORD)size, full, NULL);
    if (length == 0 || length >= size) return fprintf(stderr, "no path %s\n", directory), 0;
#else
    char resolved[PATH_MAX];
    if (!realpath(directory, resolved) || strlen(resolved) >= size)
        return fprintf(stderr, "no path %s\n", directory), 0;
    strcpy(full, resolved);
#endif
    return 1;
}

/* The FMU's library, loaded from binaries/ (its path in `path`), and the FMU's absolute directory
 * in `full`; NULL (said on stderr) when either cannot be had. */
static void *open_fmu(const char *directory, const Experiment *e, char *path, size_t path_size, char *full,
                      size_t full_size) {
    void *library;
    library_path(directory, e, path, path_size);
    if (!(library = load_library(path))) return NULL;
    if (!full_path(directory, full, full_size)) {
        unload_library(library);
        return NULL;
    }
    return library;
}

/* The CSV's first line: time, then each output's name. */
static void print_header(const Experiment *e) {
    size_t i;
    printf("time");
    for (i = 0; i < e->outputs; i++) printf(",%s", e->names[i]);
    printf("\n");
}

/* One line of the CSV: the time, then the outputs' values, each to the last bit. */
static void print_row(const Experiment *e, double t, const double *values) {
    size_t i;
    printf("%.17g", t);
    for (i = 0; i < e->outputs; i++) printf(",%.17g", values[i]);
    printf("\n");
}

/* Loads the library, runs the experiment, frees the instance and unloads the library; prints
 * the CSV when `print` is set. 0 when every call succeeded, 1 when one did not, 2 for a load
 * error. */
typedef int (*Run)(const char *directory, const Experiment *e, int print);

/* The command line both hosts take, DIR [OPTION TOKEN] [--cycles N] [--steps K] (see each host's
 * first comment), then `run` once a cycle; the exit status. `token_option` names the option
 * (--guid, --token), `token_name` what it takes (GUID, TOKEN). */
static int host_main(int argc, char **argv, const char *token_option, const char *token_name, int fmi3,
                     Run run) {
    static Experiment experiment;
    const char *token = NULL;
    long cycles = 1, steps = -1, cycle;
    int a, status = 0;

    for (a = 2; a + 1 < argc; a += 2) {
        if (strcmp(argv[a], token_option) == 0) token = argv[a + 1];
        else if (strcmp(argv[a], "--cycles") == 0) cycles = strtol(argv[a + 1], NULL, 10);
        else if (strcmp(argv[a], "--steps") == 0) steps = strtol(argv[a + 1], NULL, 10);
        else break;
    }
    if (argc < 2 || a != argc || cycles < 1) {
        fprintf(stderr, "usage: %s EXTRACTED_FMU_DIR [%s %s] [--cycles N] [--steps K]\n", argv[0],
                token_option, token_name);
        return 2;
    }
    if ((status = read_experiment(argv[1], &experiment, fmi3)) != 0) return status;
    if (token) snprintf(experiment.token, sizeof experiment.token, "%s", token);
    if (steps >= 0 && steps < experiment.steps) experiment.steps = steps;
    for (cycle = 1; cycle <= cycles && status == 0; cycle++)
        status = run(argv[1], &experiment, cycle == cycles);
    return status;
}

#endif
