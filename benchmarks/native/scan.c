/* The four scan workloads of benchmarks/bench_language.py part 1 written in C,
 * with the IEC semantics of the generated Python: a reference for the physical
 * limit (benchmarks/bench_native.py compiles and drives this file).
 *
 *     cc -O2 -ffp-contract=off -o scan scan.c
 *     ./scan numeric|bits|timers|methods
 *
 * The program then reads commands on stdin, one a line:
 *     run N     run N cycles, answer "ns T" (T: their wall time in ns)
 *     state     answer the program's variables as one line of JSON
 * and ends at the end of its input.
 *
 * Semantics, as the generated Python has them:
 *  - DINT/INT/UINT/WORD/DWORD arithmetic wraps in two's complement: done
 *    explicitly in unsigned arithmetic (wrap32 / wrap16), never by relying on
 *    signed overflow (undefined in C);
 *  - MOD and / truncate toward zero (as C's % and / do);
 *  - REAL is float, every operation rounded to binary32: FLT_EVAL_METHOD must
 *    be 0 (checked below) and no a * b + c is fused into one rounding
 *    (-ffp-contract=off; gcc fuses by default where the CPU has FMA);
 *  - TIME() is the cycle's start on a virtual millisecond clock that advances
 *    10 ms a cycle from 0, wrapping like a DINT;
 *  - a call through an interface is a call through a table of function
 *    pointers the instance carries.
 * The driver calls each scan through a volatile function pointer (as a
 * runtime calls a task), so the compiler cannot fold cycles together or drop
 * stores a later cycle overwrites; the final state is printed and compared.
 */
#ifdef __clang__
#pragma STDC FP_CONTRACT OFF
#endif

#include <float.h>
#include <inttypes.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "REAL needs float arithmetic rounded to binary32 at each operation (FLT_EVAL_METHOD 0)"
#endif

typedef int32_t DINT;
typedef int16_t INT;
typedef uint16_t UINT;
typedef uint16_t WORD;
typedef uint32_t DWORD;
typedef float REAL;
typedef int32_t TIME; /* milliseconds */

/* two's complement wraps, done in unsigned arithmetic */
static inline DINT wrap32(uint32_t x) { return (DINT)x; }
static inline INT wrap16(uint32_t x) { return (INT)(uint16_t)x; }
static inline DINT add32(DINT a, DINT b) { return wrap32((uint32_t)a + (uint32_t)b); }
static inline DINT sub32(DINT a, DINT b) { return wrap32((uint32_t)a - (uint32_t)b); }
static inline DINT mul32(DINT a, DINT b) { return wrap32((uint32_t)a * (uint32_t)b); }
static inline WORD rol16(WORD w, unsigned n) { return (WORD)((w << n) | (w >> (16 - n))); }
static inline DWORD rol32(DWORD w, unsigned n) { return (w << n) | (w >> (32 - n)); }

static TIME now_ms; /* TIME(): the start of the current cycle */

/* ==================================================================== */
/* Output: JSON; a REAL as a string in C99 hex ("%a"), exact            */
/* ==================================================================== */

static void put_real(REAL x) { printf("\"%a\"", (double)x); }

static void put_key(const char *key, int *first) {
    printf("%s\"%s\": ", *first ? "" : ", ", key);
    *first = 0;
}

static void put_dint_array(const char *key, const DINT *a, int n, int *first) {
    put_key(key, first);
    putchar('[');
    for (int i = 0; i < n; i++) printf("%s%" PRId32, i ? ", " : "", a[i]);
    putchar(']');
}

static void put_word_array(const char *key, const WORD *a, int n, int *first) {
    put_key(key, first);
    putchar('[');
    for (int i = 0; i < n; i++) printf("%s%u", i ? ", " : "", (unsigned)a[i]);
    putchar(']');
}

static void put_bool_array(const char *key, const bool *a, int n, int *first) {
    put_key(key, first);
    putchar('[');
    for (int i = 0; i < n; i++) printf("%s%s", i ? ", " : "", a[i] ? "true" : "false");
    putchar(']');
}

static void put_real_array(const char *key, const REAL *a, int n, int *first) {
    put_key(key, first);
    putchar('[');
    for (int i = 0; i < n; i++) {
        if (i) printf(", ");
        put_real(a[i]);
    }
    putchar(']');
}

static void put_int(const char *key, long long v, int *first) {
    put_key(key, first);
    printf("%lld", v);
}

static void put_bool(const char *key, bool v, int *first) {
    put_key(key, first);
    printf("%s", v ? "true" : "false");
}

/* ==================================================================== */
/* a. numeric.st                                                        */
/* ==================================================================== */

static struct {
    DINT counts[1000];
    REAL samples[1000];
    REAL avg[1000];
    REAL integ[100];
    REAL lastErr[100];
    REAL outp[100];
    REAL kp, ki, kd;
    DINT cycle, checksum;
    REAL minAvg, maxAvg;
} nm = {.kp = 0.8f, .ki = 0.05f, .kd = 0.01f};

static void numeric_scan(void) {
    INT i; /* VAR_TEMP */
    REAL sum, err, u;

    nm.cycle = add32(nm.cycle, 1);

    for (i = 0; i <= 999; i++) {
        nm.counts[i] = add32(mul32(nm.counts[i], 3), add32(mul32(nm.cycle, 7), i) % 1000);
        nm.samples[i] = (REAL)(nm.counts[i] % 4096) * 0.01f;
    }

    sum = 0.0f;
    nm.minAvg = 1.0e30f;
    nm.maxAvg = -1.0e30f;
    for (i = 0; i <= 999; i++) {
        sum = sum + nm.samples[i];
        if (i >= 8) sum = sum - nm.samples[i - 8];
        nm.avg[i] = sum / 8.0f;
        if (nm.avg[i] < nm.minAvg) nm.minAvg = nm.avg[i];
        if (nm.avg[i] > nm.maxAvg) nm.maxAvg = nm.avg[i];
    }

    nm.checksum = 0;
    for (i = 0; i <= 999; i++)
        nm.checksum = add32(add32(mul32(nm.checksum, 31), nm.counts[i] / 3), nm.counts[i] % 7);

    for (i = 0; i <= 99; i++) {
        err = nm.avg[i * 10] - 20.0f;
        nm.integ[i] = nm.integ[i] + nm.ki * err;
        if (nm.integ[i] > 100.0f)
            nm.integ[i] = 100.0f;
        else if (nm.integ[i] < -100.0f)
            nm.integ[i] = -100.0f;
        u = nm.kp * err + nm.integ[i] + nm.kd * (err - nm.lastErr[i]);
        nm.outp[i] = u < -100.0f ? -100.0f : (u > 100.0f ? 100.0f : u); /* LIMIT(-100.0, u, 100.0) */
        nm.lastErr[i] = err;
    }
}

static void numeric_state(void) {
    int f = 1;
    put_dint_array("counts", nm.counts, 1000, &f);
    put_real_array("samples", nm.samples, 1000, &f);
    put_real_array("avg", nm.avg, 1000, &f);
    put_real_array("integ", nm.integ, 100, &f);
    put_real_array("lastErr", nm.lastErr, 100, &f);
    put_real_array("outp", nm.outp, 100, &f);
    put_int("cycle", nm.cycle, &f);
    put_int("checksum", nm.checksum, &f);
    put_key("minAvg", &f);
    put_real(nm.minAvg);
    put_key("maxAvg", &f);
    put_real(nm.maxAvg);
}

/* ==================================================================== */
/* b. bits.st                                                           */
/* ==================================================================== */

static struct {
    WORD words[256];
    WORD masks[256];
    bool flags[256];
    WORD packed[16];
    UINT cycle;
    WORD andAcc, orAcc, xorAcc;
    DWORD crc;
    INT ones;
    WORD status;
} bt;

static inline bool bit16(WORD w, unsigned n) { return (w >> n) & 1u; }
static inline WORD set16(WORD w, unsigned n, bool v) { return (WORD)((w & ~(1u << n)) | ((unsigned)v << n)); }

static void bits_scan(void) {
    INT i, j; /* VAR_TEMP */
    WORD w;
    DWORD dw;

    bt.cycle = (UINT)(bt.cycle + 1u);

    for (i = 0; i <= 255; i++) {
        w = rol16(bt.words[i], 3) ^ (WORD)i ^ (WORD)bt.cycle;
        bt.words[i] = w;
        bt.flags[i] = bit16(w, 3) ^ bit16(w, 12);
        bt.masks[i] = (WORD)((w & 0x0FF0u) | (w >> 12) | (WORD)((w & 0x000Fu) << 12));
    }

    bt.andAcc = 0xFFFF;
    bt.orAcc = 0;
    bt.xorAcc = 0;
    for (i = 0; i <= 255; i++) {
        bt.andAcc &= bt.masks[i];
        bt.orAcc |= bt.masks[i];
        bt.xorAcc ^= bt.words[i];
    }

    for (i = 0; i <= 15; i++) {
        w = 0;
        for (j = 0; j <= 15; j++)
            if (bt.flags[i * 16 + j]) w |= (WORD)(1u << j);
        bt.packed[i] = w;
    }

    for (i = 0; i <= 15; i++) {
        dw = ((DWORD)bt.packed[i] << 16) | (DWORD)bt.masks[i];
        bt.crc = rol32(bt.crc, 5) ^ dw;
        bt.crc = (bt.crc & ~1u) | (((bt.crc >> 31) ^ (bt.crc >> 7)) & 1u); /* crc.0 := crc.31 XOR crc.7 */
    }

    bt.ones = 0;
    w = bt.xorAcc;
    while (w != 0) {
        w = (WORD)(w & (WORD)(w - 1u));
        bt.ones = wrap16((uint32_t)bt.ones + 1u);
    }

    bt.status = set16(bt.status, 0, bt.andAcc != 0);
    bt.status = set16(bt.status, 1, bt.orAcc == 0xFFFF);
    bt.status = set16(bt.status, 2, bt.crc & 1u);
    bt.status = set16(bt.status, 15, !bit16(bt.status, 15));
}

static void bits_state(void) {
    int f = 1;
    put_word_array("words", bt.words, 256, &f);
    put_word_array("masks", bt.masks, 256, &f);
    put_bool_array("flags", bt.flags, 256, &f);
    put_word_array("packed", bt.packed, 16, &f);
    put_int("cycle", bt.cycle, &f);
    put_int("andAcc", bt.andAcc, &f);
    put_int("orAcc", bt.orAcc, &f);
    put_int("xorAcc", bt.xorAcc, &f);
    put_int("crc", bt.crc, &f);
    put_int("ones", bt.ones, &f);
    put_int("status", bt.status, &f);
}

/* ==================================================================== */
/* c. timers.st: 50 TON and 50 CTU instances                            */
/* ==================================================================== */

typedef struct { /* fblocks/iec/standard_fbs.st TON */
    bool IN;
    TIME PT;
    bool Q;
    TIME ET;
    bool running;
    TIME startTime, elapsed;
} TON;

typedef struct { /* CTU */
    bool CU, R;
    INT PV;
    bool Q;
    INT CV;
    bool lastCU;
} CTU;

static void TON_call(TON *t) {
    if (t->IN) {
        if (!t->running) {
            t->running = true;
            t->startTime = now_ms;
        }
        if (!t->Q) {
            t->elapsed = sub32(now_ms, t->startTime);
            if (t->elapsed >= t->PT) {
                t->Q = true;
                t->ET = t->PT;
            } else {
                t->ET = t->elapsed;
            }
        }
    } else {
        t->running = false;
        t->Q = false;
        t->ET = 0;
    }
}

static void CTU_call(CTU *c) {
    if (c->R)
        c->CV = 0;
    else if (c->CU && !c->lastCU && c->CV < 32767)
        c->CV = wrap16((uint32_t)c->CV + 1u);
    c->lastCU = c->CU;
    c->Q = c->CV >= c->PV;
}

#define CHANNELS 50

static struct {
    TON t[CHANNELS + 1]; /* t[1..50], as t1..t50 */
    CTU c[CHANNELS + 1];
    DINT cycle;
    INT running, full;
    DINT total;
} tm;

static void timers_scan(void) {
    tm.cycle = add32(tm.cycle, 1);
    tm.running = 0;
    tm.full = 0;
    tm.total = 0;
    /* the ST has the 50 channels written out; channel k is the same lines with k */
    for (DINT k = 1; k <= CHANNELS; k++) {
        TON *t = &tm.t[k];
        CTU *c = &tm.c[k];
        t->IN = add32(tm.cycle, k) % (2 * k + 5) < k + 2;
        t->PT = 10 * k;
        TON_call(t);
        c->CU = t->Q;
        c->R = c->CV >= 1000;
        c->PV = (INT)(40 + k);
        CTU_call(c);
        if (t->Q) tm.running = wrap16((uint32_t)tm.running + 1u);
        if (c->Q) tm.full = wrap16((uint32_t)tm.full + 1u);
        tm.total = add32(tm.total, c->CV);
    }
}

static void timers_state(void) {
    int f = 1;
    char key[16];
    put_int("cycle", tm.cycle, &f);
    put_int("running", tm.running, &f);
    put_int("full", tm.full, &f);
    put_int("total", tm.total, &f);
    for (int k = 1; k <= CHANNELS; k++) {
        snprintf(key, sizeof key, "t%d.Q", k);
        put_bool(key, tm.t[k].Q, &f);
        snprintf(key, sizeof key, "t%d.ET", k);
        put_int(key, tm.t[k].ET, &f);
        snprintf(key, sizeof key, "c%d.Q", k);
        put_bool(key, tm.c[k].Q, &f);
        snprintf(key, sizeof key, "c%d.CV", k);
        put_int(key, tm.c[k].CV, &f);
    }
}

/* ==================================================================== */
/* d. oop.st: methods and a property through an interface               */
/* ==================================================================== */

typedef struct I_Acc_vtable I_Acc_vtable;

typedef struct { /* FB_Acc: FB_Add and FB_Max add no variables */
    const I_Acc_vtable *vt;
    DINT sum;
} FB_Acc;

struct I_Acc_vtable { /* INTERFACE I_Acc */
    DINT (*Step)(FB_Acc *self, DINT x);
    DINT (*get_Total)(FB_Acc *self);
};

static DINT FB_Acc_get_Total(FB_Acc *self) { return self->sum; }

static DINT FB_Add_Step(FB_Acc *self, DINT x) {
    self->sum = add32(self->sum, x);
    return self->sum;
}

static DINT FB_Max_Step(FB_Acc *self, DINT x) {
    if (x > self->sum) self->sum = x;
    return self->sum;
}

static const I_Acc_vtable FB_Add_vt = {FB_Add_Step, FB_Acc_get_Total};
static const I_Acc_vtable FB_Max_vt = {FB_Max_Step, FB_Acc_get_Total};

static struct {
    FB_Acc adds[51], maxs[51]; /* [1..50] */
    FB_Acc *accs[101];         /* [1..100] OF I_Acc */
    INT i;
    bool started;
    DINT cycle, check, last;
} oo;

static void methods_init(void) {
    for (int k = 1; k <= 50; k++) {
        oo.adds[k].vt = &FB_Add_vt;
        oo.maxs[k].vt = &FB_Max_vt;
    }
}

static void methods_scan(void) {
    if (!oo.started) {
        for (oo.i = 1; oo.i <= 50; oo.i++) {
            oo.accs[2 * oo.i - 1] = &oo.adds[oo.i];
            oo.accs[2 * oo.i] = &oo.maxs[oo.i];
        }
        oo.started = true;
    }
    oo.cycle = add32(oo.cycle, 1);
    oo.check = 0;
    for (oo.i = 1; oo.i <= 100; oo.i++) {
        FB_Acc *acc = oo.accs[oo.i];
        oo.last = acc->vt->Step(acc, add32(oo.cycle, oo.i));
        oo.check = add32(oo.check, sub32(oo.last, acc->vt->get_Total(acc)));
    }
}

static void methods_state(void) {
    int f = 1;
    DINT sums[50];
    put_int("cycle", oo.cycle, &f);
    put_int("check", oo.check, &f);
    put_int("last", oo.last, &f);
    for (int k = 1; k <= 50; k++) sums[k - 1] = oo.adds[k].sum;
    put_dint_array("adds.sum", sums, 50, &f); /* the sum of adds[1..50] */
    for (int k = 1; k <= 50; k++) sums[k - 1] = oo.maxs[k].sum;
    put_dint_array("maxs.sum", sums, 50, &f);
}

/* ==================================================================== */
/* Driver                                                               */
/* ==================================================================== */

static const struct {
    const char *name;
    void (*init)(void);
    void (*scan)(void);
    void (*state)(void);
} WORKLOADS[] = {
    {"numeric", NULL, numeric_scan, numeric_state},
    {"bits", NULL, bits_scan, bits_state},
    {"timers", NULL, timers_scan, timers_state},
    {"methods", methods_init, methods_scan, methods_state},
};

static int64_t now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int main(int argc, char **argv) {
    int w = -1;
    for (size_t k = 0; argc == 2 && k < sizeof WORKLOADS / sizeof WORKLOADS[0]; k++)
        if (strcmp(argv[1], WORKLOADS[k].name) == 0) w = (int)k;
    if (w < 0) {
        fprintf(stderr, "usage: %s numeric|bits|timers|methods  (then commands on stdin: run N, state)\n", argv[0]);
        return 2;
    }
    if (WORKLOADS[w].init) WORKLOADS[w].init();
    void (*volatile scan)(void) = WORKLOADS[w].scan; /* called as a runtime calls a task */
    char line[64];
    while (fgets(line, sizeof line, stdin)) {
        long long n;
        if (sscanf(line, "run %lld", &n) == 1 && n >= 0) {
            int64_t t0 = now_ns();
            for (long long c = 0; c < n; c++) {
                scan();
                now_ms = add32(now_ms, 10); /* the next cycle's TIME() */
            }
            printf("ns %" PRId64 "\n", now_ns() - t0);
        } else if (strcmp(line, "state\n") == 0) {
            putchar('{');
            WORKLOADS[w].state();
            printf("}\n");
        } else {
            fprintf(stderr, "unknown command: %s", line);
            return 2;
        }
        fflush(stdout);
    }
    return 0;
}
