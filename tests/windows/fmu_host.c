/* A minimal FMI co-simulation host for the Windows test (scripts/test.d/70-windows.sh):
 * loads the binary of an extracted raceway FMU, runs one co-simulation and prints outputs.
 * The same source builds for Windows (x86_64-w64-mingw32-gcc, LoadLibrary, run under Wine)
 * and for Linux (cc, dlopen), so both platforms' binaries take the same calls and their
 * printed numbers can be compared line by line.
 *
 *   fmu_host DIR fmi2|fmi3 STEPS STEP_S [NAME=VALUE]... [NAME]...
 *
 * DIR is the extracted FMU (modelDescription.xml, binaries/, resources/). NAME=VALUE sets a
 * real input or parameter before initialisation; each bare NAME is a real variable printed
 * ("NAME VALUE", %.17g) after the last step. The GUID / instantiation token and the value
 * references are read from DIR/modelDescription.xml. Exit status 0 only if every call
 * returned OK (or Warning).
 *
 * The FMI types are declared here from the standards' headers' definitions (FMI 2.0.4
 * fmi2FunctionTypes.h, FMI 3.0 fmi3FunctionTypes.h): only what this host calls. */
#ifndef _WIN32
#define _XOPEN_SOURCE 700 /* realpath, dlopen */
#endif
#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef _WIN32
#include <windows.h>
#define PLATFORM2 "win64"
#define PLATFORM3 "x86_64-windows"
#define LIBNAME "raceway.dll"
typedef HMODULE lib_t;
static lib_t lib_open(const char *path) { return LoadLibraryA(path); }
static void *lib_sym(lib_t l, const char *name) { return (void *)GetProcAddress(l, name); }
static void lib_close(lib_t l) { FreeLibrary(l); }
#else
#include <dlfcn.h>
#define PLATFORM2 "linux64"
#define PLATFORM3 "x86_64-linux"
#define LIBNAME "raceway.so"
typedef void *lib_t;
static lib_t lib_open(const char *path) { return dlopen(path, RTLD_NOW | RTLD_LOCAL); }
static void *lib_sym(lib_t l, const char *name) { return dlsym(l, name); }
static void lib_close(lib_t l) { dlclose(l); }
#endif

/* ---- FMI 2.0 (co-simulation subset) ---- */
typedef void *fmi2Component;
typedef unsigned int fmi2ValueReference;
typedef int fmi2Boolean;
typedef int fmi2Status; /* fmi2OK = 0, fmi2Warning = 1, fmi2Discard, fmi2Error, ... */
typedef struct {
  void (*logger)(void *env, const char *instance, fmi2Status status, const char *category,
                 const char *message, ...);
  void *(*allocateMemory)(size_t n, size_t size);
  void (*freeMemory)(void *p);
  void (*stepFinished)(void *env, fmi2Status status);
  void *componentEnvironment;
} fmi2CallbackFunctions;
typedef fmi2Component (*fmi2InstantiateTYPE)(const char *, int, const char *, const char *,
                                             const fmi2CallbackFunctions *, fmi2Boolean,
                                             fmi2Boolean);
typedef fmi2Status (*fmi2SetupExperimentTYPE)(fmi2Component, fmi2Boolean, double, double,
                                              fmi2Boolean, double);
typedef fmi2Status (*fmi2ComponentTYPE)(fmi2Component);
typedef void (*fmi2FreeInstanceTYPE)(fmi2Component);
typedef fmi2Status (*fmi2RealTYPE)(fmi2Component, const fmi2ValueReference *, size_t,
                                   double *);
typedef fmi2Status (*fmi2DoStepTYPE)(fmi2Component, double, double, fmi2Boolean);

/* ---- FMI 3.0 (co-simulation subset) ---- */
typedef void *fmi3Instance;
typedef uint32_t fmi3ValueReference;
typedef int fmi3Status; /* fmi3OK = 0, fmi3Warning = 1, ... (a C enum) */
typedef void (*fmi3LogMessageCallback)(void *env, fmi3Status status, const char *category,
                                       const char *message);
typedef fmi3Instance (*fmi3InstantiateCoSimulationTYPE)(
    const char *, const char *, const char *, bool, bool, bool, bool,
    const fmi3ValueReference *, size_t, void *, fmi3LogMessageCallback, void *);
typedef fmi3Status (*fmi3EnterInitializationModeTYPE)(fmi3Instance, bool, double, double, bool,
                                                      double);
typedef fmi3Status (*fmi3InstanceTYPE)(fmi3Instance);
typedef void (*fmi3FreeInstanceTYPE)(fmi3Instance);
typedef fmi3Status (*fmi3GetFloat64TYPE)(fmi3Instance, const fmi3ValueReference *, size_t,
                                         double *, size_t);
typedef fmi3Status (*fmi3SetFloat64TYPE)(fmi3Instance, const fmi3ValueReference *, size_t,
                                         const double *, size_t);
typedef fmi3Status (*fmi3DoStepTYPE)(fmi3Instance, double, double, bool, bool *, bool *, bool *,
                                     double *);

static void logger2(void *env, const char *instance, fmi2Status status, const char *category,
                 const char *message, ...) {
  va_list ap;
  (void)env;
  fprintf(stderr, "[%s %d %s] ", instance ? instance : "", status, category ? category : "");
  va_start(ap, message);
  vfprintf(stderr, message, ap);
  va_end(ap);
  fputc('\n', stderr);
}

static void logger3(void *env, fmi3Status status, const char *category, const char *message) {
  (void)env;
  fprintf(stderr, "[%d %s] %s\n", status, category ? category : "", message ? message : "");
}

static char *read_file(const char *path) {
  FILE *f = fopen(path, "rb");
  char *text;
  long n;
  if (!f) return NULL;
  fseek(f, 0, SEEK_END);
  n = ftell(f);
  fseek(f, 0, SEEK_SET);
  text = malloc((size_t)n + 1);
  if (text && fread(text, 1, (size_t)n, f) != (size_t)n) n = 0;
  if (text) text[n] = '\0';
  fclose(f);
  return text;
}

/* The value of attribute `attr` that follows `after` in the XML (copied into out). */
static int attribute(const char *xml, const char *after, const char *attr, char *out,
                     size_t size) {
  char key[160];
  const char *p = strstr(xml, after), *end;
  if (!p) return 0;
  snprintf(key, sizeof key, " %s=\"", attr);
  p = strstr(p, key);
  if (!p) return 0;
  p += strlen(key);
  end = strchr(p, '"');
  if (!end || (size_t)(end - p) >= size) return 0;
  memcpy(out, p, (size_t)(end - p));
  out[end - p] = '\0';
  return 1;
}

static int value_reference(const char *xml, const char *name, unsigned *vr) {
  char after[200], text[32];
  snprintf(after, sizeof after, " name=\"%s\"", name);
  if (!attribute(xml, after, "valueReference", text, sizeof text)) return 0;
  *vr = (unsigned)strtoul(text, NULL, 10);
  return 1;
}

#define CHECK(call)                                                          \
  do {                                                                       \
    int s_ = (call);                                                         \
    if (s_ > 1) {                                                            \
      fprintf(stderr, "fmu_host: %s returned status %d\n", #call, s_);      \
      return 1;                                                              \
    }                                                                        \
  } while (0)

int main(int argc, char **argv) {
  char path[4096], token[128], uri[4200], *xml;
  const char *dir, *version;
  unsigned set_vr[32], out_vr[32];
  double set_val[32], out_val[32];
  const char *out_name[32];
  size_t n_set = 0, n_out = 0, i;
  long steps, k;
  double h, t = 0.0;
  int fmi3;
  lib_t lib;

  if (argc < 5) {
    fprintf(stderr, "usage: fmu_host DIR fmi2|fmi3 STEPS STEP_S [NAME=VALUE]... [NAME]...\n");
    return 2;
  }
  dir = argv[1];
  version = argv[2];
  fmi3 = strcmp(version, "fmi3") == 0;
  steps = strtol(argv[3], NULL, 10);
  h = strtod(argv[4], NULL);
  snprintf(path, sizeof path, "%s/modelDescription.xml", dir);
  xml = read_file(path);
  if (!xml) {
    fprintf(stderr, "fmu_host: cannot read %s\n", path);
    return 2;
  }
  if (!attribute(xml, "<fmiModelDescription", fmi3 ? "instantiationToken" : "guid", token,
                 sizeof token)) {
    fprintf(stderr, "fmu_host: no GUID / instantiationToken in %s\n", path);
    return 2;
  }
  for (i = 5; i < (size_t)argc && n_set < 32 && n_out < 32; i++) {
    char name[160];
    const char *eq = strchr(argv[i], '=');
    size_t len = eq ? (size_t)(eq - argv[i]) : strlen(argv[i]);
    unsigned vr;
    if (len >= sizeof name) return 2;
    memcpy(name, argv[i], len);
    name[len] = '\0';
    if (!value_reference(xml, name, &vr)) {
      fprintf(stderr, "fmu_host: no variable `%s` in the model description\n", name);
      return 2;
    }
    if (eq) {
      set_vr[n_set] = vr;
      set_val[n_set++] = strtod(eq + 1, NULL);
    } else {
      out_vr[n_out] = vr;
      out_name[n_out++] = argv[i];
    }
  }

  /* the resources folder as the standards want it: a file URI (FMI 2), a path with a
   * trailing separator (FMI 3); under Wine the Unix root is drive Z: */
#ifdef _WIN32
  {
    char full[4096], *c;
    snprintf(path, sizeof path, "%s/resources", dir);
    if (!GetFullPathNameA(path, sizeof full, full, NULL)) return 2;
    for (c = full; *c; c++)
      if (*c == '\\') *c = '/';
    snprintf(uri, sizeof uri, fmi3 ? "%s/" : "file:///%s", full);
  }
#else
  {
    char full[4096]; /* realpath writes at most PATH_MAX (4096 on Linux) */
    if (!realpath(dir, full)) return 2;
    snprintf(uri, sizeof uri, fmi3 ? "%s/resources/" : "file://%s/resources", full);
  }
#endif

  snprintf(path, sizeof path, "%s/binaries/%s/%s", dir, fmi3 ? PLATFORM3 : PLATFORM2, LIBNAME);
  lib = lib_open(path);
  if (!lib) {
    fprintf(stderr, "fmu_host: cannot load %s\n", path);
    return 1;
  }

  if (!fmi3) {
    fmi2CallbackFunctions cb = {logger2, calloc, free, NULL, NULL};
    fmi2InstantiateTYPE inst = (fmi2InstantiateTYPE)lib_sym(lib, "fmi2Instantiate");
    fmi2SetupExperimentTYPE setup = (fmi2SetupExperimentTYPE)lib_sym(lib, "fmi2SetupExperiment");
    fmi2ComponentTYPE enter = (fmi2ComponentTYPE)lib_sym(lib, "fmi2EnterInitializationMode");
    fmi2ComponentTYPE exit_ = (fmi2ComponentTYPE)lib_sym(lib, "fmi2ExitInitializationMode");
    fmi2ComponentTYPE term = (fmi2ComponentTYPE)lib_sym(lib, "fmi2Terminate");
    fmi2FreeInstanceTYPE freei = (fmi2FreeInstanceTYPE)lib_sym(lib, "fmi2FreeInstance");
    fmi2RealTYPE set = (fmi2RealTYPE)lib_sym(lib, "fmi2SetReal");
    fmi2RealTYPE get = (fmi2RealTYPE)lib_sym(lib, "fmi2GetReal");
    fmi2DoStepTYPE step = (fmi2DoStepTYPE)lib_sym(lib, "fmi2DoStep");
    fmi2Component c;
    if (!inst || !setup || !enter || !exit_ || !term || !freei || !set || !get || !step) {
      fprintf(stderr, "fmu_host: an fmi2 function is missing from %s\n", path);
      return 1;
    }
    c = inst("host", 1 /* fmi2CoSimulation */, token, uri, &cb, 0, 0);
    if (!c) {
      fprintf(stderr, "fmu_host: fmi2Instantiate failed\n");
      return 1;
    }
    CHECK(setup(c, 0, 0.0, 0.0, 0, 0.0));
    CHECK(set(c, set_vr, n_set, set_val));
    CHECK(enter(c));
    CHECK(exit_(c));
    for (k = 0; k < steps; k++, t += h) CHECK(step(c, t, h, 1));
    CHECK(get(c, out_vr, n_out, out_val));
    CHECK(term(c));
    freei(c);
  } else {
    fmi3InstantiateCoSimulationTYPE inst =
        (fmi3InstantiateCoSimulationTYPE)lib_sym(lib, "fmi3InstantiateCoSimulation");
    fmi3EnterInitializationModeTYPE enter =
        (fmi3EnterInitializationModeTYPE)lib_sym(lib, "fmi3EnterInitializationMode");
    fmi3InstanceTYPE exit_ = (fmi3InstanceTYPE)lib_sym(lib, "fmi3ExitInitializationMode");
    fmi3InstanceTYPE term = (fmi3InstanceTYPE)lib_sym(lib, "fmi3Terminate");
    fmi3FreeInstanceTYPE freei = (fmi3FreeInstanceTYPE)lib_sym(lib, "fmi3FreeInstance");
    fmi3SetFloat64TYPE set = (fmi3SetFloat64TYPE)lib_sym(lib, "fmi3SetFloat64");
    fmi3GetFloat64TYPE get = (fmi3GetFloat64TYPE)lib_sym(lib, "fmi3GetFloat64");
    fmi3DoStepTYPE step = (fmi3DoStepTYPE)lib_sym(lib, "fmi3DoStep");
    fmi3Instance c;
    if (!inst || !enter || !exit_ || !term || !freei || !set || !get || !step) {
      fprintf(stderr, "fmu_host: an fmi3 function is missing from %s\n", path);
      return 1;
    }
    c = inst("host", token, uri, false, false, false, false, NULL, 0, NULL, logger3, NULL);
    if (!c) {
      fprintf(stderr, "fmu_host: fmi3InstantiateCoSimulation failed\n");
      return 1;
    }
    CHECK(set(c, set_vr, n_set, set_val, n_set));
    CHECK(enter(c, false, 0.0, 0.0, false, 0.0));
    CHECK(exit_(c));
    for (k = 0; k < steps; k++, t += h) {
      bool event = false, terminate = false, early = false;
      double last = 0.0;
      CHECK(step(c, t, h, true, &event, &terminate, &early, &last));
      if (terminate) {
        fprintf(stderr, "fmu_host: the FMU asked to terminate at t = %g s\n", t);
        return 1;
      }
    }
    CHECK(get(c, out_vr, n_out, out_val, n_out));
    CHECK(term(c));
    freei(c);
  }
  lib_close(lib);
  for (i = 0; i < n_out; i++) printf("%s %.17g\n", out_name[i], out_val[i]);
  free(xml);
  return 0;
}
