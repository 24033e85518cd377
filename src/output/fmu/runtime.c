/* romdyn's FMI 2.0 runtime of a linear ROM: model exchange and co-simulation.
 *
 * The generated part before this text defines N (states), M (inputs), P (outputs),
 * DISCRETE (0: x' = A x + B u; 1: x[k+1] = A x[k] + B u[k] every SAMPLE_TIME s),
 * SAMPLE_TIME, the matrices A (N x N), B (N x M), C (P x N), D (P x M) row by row, each
 * padded by one entry so that no array is empty, and GUID.
 *
 * Value references: inputs 0..M-1, outputs M..M+P-1, states M+P..M+P+N-1, and for a
 * continuous ROM the state derivatives M+P+N..M+P+2N-1.
 *
 * A discrete ROM samples at t0 + k SAMPLE_TIME (k = 1, 2, ...): x <- A x + B u_k with u_k the
 * input at the previous sample (zero-order hold), in co-simulation within doStep, in model
 * exchange at the time events it announces (no continuous states).
 *
 * Co-simulation of a continuous ROM steps exactly for inputs held over the step (zero-order
 * hold): x(t+h) = e^{A h} x(t) + (integral_0^h e^{A s} ds) B u, both blocks of the
 * exponential of [[A h, B h], [0, 0]] (scaling and squaring of its Taylor series). */

#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#if defined(_WIN32)
#define FMI2_EXPORT __declspec(dllexport)
#else
#define FMI2_EXPORT __attribute__((visibility("default")))
#endif

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
typedef char fmi2Byte;
typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;
typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
typedef void *(*fmi2CallbackAllocateMemory)(size_t, size_t);
typedef void (*fmi2CallbackFreeMemory)(void *);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);
typedef struct {
    fmi2CallbackLogger logger;
    fmi2CallbackAllocateMemory allocateMemory;
    fmi2CallbackFreeMemory freeMemory;
    fmi2StepFinished stepFinished;
    fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;
typedef struct {
    fmi2Boolean newDiscreteStatesNeeded;
    fmi2Boolean terminateSimulation;
    fmi2Boolean nominalsOfContinuousStatesChanged;
    fmi2Boolean valuesOfContinuousStatesChanged;
    fmi2Boolean nextEventTimeDefined;
    fmi2Real nextEventTime;
} fmi2EventInfo;

#define K (N + M)
/* The continuous states model exchange integrates. */
#define NC (DISCRETE ? 0 : N)

typedef struct {
    fmi2Type type;
    double time, next_sample;
    double x[N + 1], u[M + 1];
    /* A discrete ROM's input at the last sample (model exchange). */
    double held[M + 1];
    /* The co-simulation step's blocks for the step size `h` (0: none yet). */
    double h, phi[N * N + 1], gamma[N * M + 1];
} Instance;

/* y = C x + D u, or x' = A x + B u (when `c` is A and `d` is B). */
static void affine(const double *c, const double *d, int rows, const double *x, const double *u, double *y) {
    for (int i = 0; i < rows; i++) {
        double s = 0.0;
        for (int j = 0; j < N; j++) s += c[i * N + j] * x[j];
        for (int j = 0; j < M; j++) s += d[i * M + j] * u[j];
        y[i] = s;
    }
}

static void matmul(const double *a, const double *b, double *c, int n) {
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++) {
            double s = 0.0;
            for (int k = 0; k < n; k++) s += a[i * n + k] * b[k * n + j];
            c[i * n + j] = s;
        }
}

/* phi = e^{A h}, gamma = (integral_0^h e^{A s} ds) B from the exponential of the
 * augmented K x K matrix Z = [[A h, B h], [0, 0]]: Z / 2^s has norm below 1/2, its Taylor
 * series is summed to rounding, then squared s times. */
static int step_blocks(Instance *c, double h) {
    double *z = calloc(K * K + 1, sizeof(double)), *e = calloc(K * K + 1, sizeof(double));
    double *term = calloc(K * K + 1, sizeof(double)), *tmp = calloc(K * K + 1, sizeof(double));
    if (!z || !e || !term || !tmp) {
        free(z); free(e); free(term); free(tmp);
        return 0;
    }
    double norm = 0.0;
    for (int i = 0; i < N; i++) {
        double row = 0.0;
        for (int j = 0; j < N; j++) row += fabs(z[i * K + j] = A[i * N + j] * h);
        for (int j = 0; j < M; j++) row += fabs(z[i * K + N + j] = B[i * M + j] * h);
        if (row > norm) norm = row;
    }
    int s = 0;
    while (norm > 0.5 && s < 1000) { norm /= 2.0; s++; }
    double scale = ldexp(1.0, -s);
    for (int i = 0; i < K * K; i++) z[i] *= scale;
    for (int i = 0; i < K; i++) e[i * K + i] = term[i * K + i] = 1.0;
    for (int k = 1; k < 40; k++) {
        matmul(term, z, tmp, K);
        double largest = 0.0;
        for (int i = 0; i < K * K; i++) {
            term[i] = tmp[i] / k;
            e[i] += term[i];
            if (fabs(term[i]) > largest) largest = fabs(term[i]);
        }
        if (largest < 1e-18) break;
    }
    for (int k = 0; k < s; k++) {
        matmul(e, e, tmp, K);
        memcpy(e, tmp, sizeof(double) * K * K);
    }
    for (int i = 0; i < N; i++) {
        for (int j = 0; j < N; j++) c->phi[i * N + j] = e[i * K + j];
        for (int j = 0; j < M; j++) c->gamma[i * M + j] = e[i * K + N + j];
    }
    c->h = h;
    free(z); free(e); free(term); free(tmp);
    return 1;
}

FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI2_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }
FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean on, size_t n, const fmi2String cats[]) {
    (void)c; (void)on; (void)n; (void)cats;
    return fmi2OK;
}

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                                          const fmi2CallbackFunctions *functions, fmi2Boolean visible, fmi2Boolean logging) {
    (void)name; (void)resources; (void)functions; (void)visible; (void)logging;
    if (!guid || strcmp(guid, GUID) != 0) return NULL;
    Instance *c = calloc(1, sizeof(Instance));
    if (!c) return NULL;
    c->type = type;
    return c;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component c) { free(c); }

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tol_defined, fmi2Real tol, fmi2Real start,
                                           fmi2Boolean stop_defined, fmi2Real stop) {
    (void)tol_defined; (void)tol; (void)stop_defined; (void)stop;
    Instance *i = c;
    i->time = start;
    i->next_sample = start + SAMPLE_TIME;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) { (void)c; return fmi2OK; }
FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component c) { (void)c; return fmi2OK; }

FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component c) {
    Instance *i = c;
    fmi2Type type = i->type;
    memset(i, 0, sizeof(Instance));
    i->type = type;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
    Instance *i = c;
    double y[P + 1], dx[N + 1];
    affine(C, D, P, i->x, i->u, y);
    if (!DISCRETE) affine(A, B, N, i->x, i->u, dx);
    for (size_t k = 0; k < n; k++) {
        unsigned int r = vr[k];
        if (r < M) value[k] = i->u[r];
        else if (r < M + P) value[k] = y[r - M];
        else if (r < M + P + N) value[k] = i->x[r - M - P];
        else if (!DISCRETE && r < M + P + 2 * N) value[k] = dx[r - M - P - N];
        else return fmi2Error;
    }
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
    Instance *i = c;
    for (size_t k = 0; k < n; k++) {
        unsigned int r = vr[k];
        if (r < M) i->u[r] = value[k];
        else if (r >= M + P && r < M + P + N) i->x[r - M - P] = value[k];
        else return fmi2Error;
    }
    return fmi2OK;
}

#define NO_SUCH_VARIABLE(kind, type)                                                                            \
    FMI2_EXPORT fmi2Status fmi2Get##kind(fmi2Component c, const fmi2ValueReference vr[], size_t n, type value[]) { \
        (void)c; (void)vr; (void)value;                                                                         \
        return n == 0 ? fmi2OK : fmi2Error;                                                                     \
    }                                                                                                           \
    FMI2_EXPORT fmi2Status fmi2Set##kind(fmi2Component c, const fmi2ValueReference vr[], size_t n, const type value[]) { \
        (void)c; (void)vr; (void)value;                                                                         \
        return n == 0 ? fmi2OK : fmi2Error;                                                                     \
    }
NO_SUCH_VARIABLE(Integer, fmi2Integer)
NO_SUCH_VARIABLE(Boolean, fmi2Boolean)
NO_SUCH_VARIABLE(String, fmi2String)

/* No FMU state and no directional derivatives (canGetAndSetFMUstate and
 * providesDirectionalDerivative are false). */
FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate s) { (void)c; (void)s; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *s) { (void)c; (void)s; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate s, size_t *n) { (void)c; (void)s; (void)n; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate s, fmi2Byte b[], size_t n) { (void)c; (void)s; (void)b; (void)n; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte b[], size_t n, fmi2FMUstate *s) { (void)c; (void)b; (void)n; (void)s; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference u[], size_t nu, const fmi2ValueReference z[],
                                                    size_t nz, const fmi2Real du[], fmi2Real dz[]) {
    (void)c; (void)u; (void)nu; (void)z; (void)nz; (void)du; (void)dz;
    return fmi2Error;
}

/* Model exchange: no events; the states are x. */
FMI2_EXPORT fmi2Status fmi2EnterEventMode(fmi2Component c) { (void)c; return fmi2OK; }
FMI2_EXPORT fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *info) {
    Instance *i = c;
    memset(info, 0, sizeof(fmi2EventInfo));
    if (DISCRETE) {
        double next[N + 1];
        if (i->time >= i->next_sample - 1e-9 * SAMPLE_TIME) {
            affine(A, B, N, i->x, i->held, next);
            memcpy(i->x, next, sizeof(double) * N);
            i->next_sample += SAMPLE_TIME;
        }
        memcpy(i->held, i->u, sizeof(double) * M);
        info->nextEventTimeDefined = 1;
        info->nextEventTime = i->next_sample;
    }
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { (void)c; return fmi2OK; }
FMI2_EXPORT fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean no_prior, fmi2Boolean *enter_event, fmi2Boolean *terminate) {
    (void)c; (void)no_prior;
    *enter_event = 0;
    *terminate = 0;
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2SetTime(fmi2Component c, fmi2Real t) {
    ((Instance *)c)->time = t;
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t n) {
    if (n != NC) return fmi2Error;
    memcpy(((Instance *)c)->x, x, sizeof(double) * NC);
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real dx[], size_t n) {
    Instance *i = c;
    if (n != NC) return fmi2Error;
    if (NC) affine(A, B, N, i->x, i->u, dx);
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real z[], size_t n) { (void)c; (void)z; return n == 0 ? fmi2OK : fmi2Error; }
FMI2_EXPORT fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t n) {
    if (n != NC) return fmi2Error;
    memcpy(x, ((Instance *)c)->x, sizeof(double) * NC);
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x[], size_t n) {
    (void)c;
    for (size_t k = 0; k < n; k++) x[k] = 1.0;
    return fmi2OK;
}

/* Co-simulation. */
FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer order[], const fmi2Real value[]) {
    (void)c; (void)vr; (void)order; (void)value;
    return n == 0 ? fmi2OK : fmi2Error;
}
FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Integer order[], fmi2Real value[]) {
    (void)c; (void)vr; (void)order; (void)value;
    return n == 0 ? fmi2OK : fmi2Error;
}

FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean no_prior) {
    (void)no_prior;
    Instance *i = c;
    double next[N + 1];
    if (!(h >= 0.0)) return fmi2Error;
    if (DISCRETE) {
        /* A sample at every multiple of SAMPLE_TIME in (t, t + h]. */
        while (i->next_sample <= t + h + 1e-9 * SAMPLE_TIME) {
            affine(A, B, N, i->x, i->u, next);
            memcpy(i->x, next, sizeof(double) * N);
            i->next_sample += SAMPLE_TIME;
        }
    } else if (h > 0.0) {
        if (h != i->h && !step_blocks(i, h)) return fmi2Error;
        for (int r = 0; r < N; r++) {
            double s = 0.0;
            for (int j = 0; j < N; j++) s += i->phi[r * N + j] * i->x[j];
            for (int j = 0; j < M; j++) s += i->gamma[r * M + j] * i->u[j];
            next[r] = s;
        }
        memcpy(i->x, next, sizeof(double) * N);
    }
    i->time = t + h;
    return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) { (void)c; return fmi2Error; }
FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *v) { (void)c; (void)s; (void)v; return fmi2Discard; }
FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s, fmi2Real *v) {
    if (s != fmi2LastSuccessfulTime) return fmi2Discard;
    *v = ((Instance *)c)->time;
    return fmi2OK;
}
FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s, fmi2Integer *v) { (void)c; (void)s; (void)v; return fmi2Discard; }
FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s, fmi2Boolean *v) { (void)c; (void)s; (void)v; return fmi2Discard; }
FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s, fmi2String *v) { (void)c; (void)s; (void)v; return fmi2Discard; }
