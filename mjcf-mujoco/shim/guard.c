/* The one place where MuJoCo's fatal errors are caught (mjcf-mujoco, src/guard.rs).
 *
 * MuJoCo reports a fatal error (mju_error: out of memory, a stack overflow of mjData's
 * arena, ...) to the active log handler and expects it not to return. This file's
 * handler, installed with mju_setLogHandler, jumps back (longjmp) to the guard of the
 * call that entered MuJoCo on this thread: every call the crate makes into MuJoCo that
 * can fail this way is one of the mjr_* functions below, which call MuJoCo directly, so
 * the jump crosses MuJoCo's C frames and this file's, never a Rust frame. A fatal error
 * on a thread with no guard (a thread MuJoCo started itself) prints the message and
 * aborts: returning to MuJoCo is not an option, and unwinding through C is not either.
 * Warnings and other messages go to the sink given by the Rust side (collected per
 * call, never written to MUJOCO_LOG.TXT).
 */
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <stddef.h>
#include <string.h>

typedef struct mjModel_ mjModel;
typedef struct mjData_ mjData;
typedef struct mjVFS_ mjVFS;

/* MuJoCo 4.0's mjLogMessage (mjtype.h); the Rust side checks its size and offsets
 * against the generated bindings (guard.rs, tests). */
typedef struct {
  int level;
  int topic;
  char subject[1024];
  const char* body;
  const char* func;
  const char* file;
  int line;
  _Bool timestamp;
} mjr_log_message;

typedef void (*mjr_sink_fn)(int level, const char* func, const char* subject, const char* body);

static mjr_sink_fn sink = 0;
static _Thread_local jmp_buf* guard = 0;
static _Thread_local char fatal[1400];

enum { LEVEL_ERROR = 3 };

size_t mjr_log_message_size(void) { return sizeof(mjr_log_message); }
size_t mjr_log_message_body_offset(void) { return offsetof(mjr_log_message, body); }

void mjr_set_sink(mjr_sink_fn s) { sink = s; }

void mjr_log_handler(const mjr_log_message* m) {
  if (m->level >= LEVEL_ERROR) {
    if (guard) {
      snprintf(fatal, sizeof fatal, "%s%s%s", m->func ? m->func : "", m->func ? ": " : "",
               m->subject);
      longjmp(*guard, 1);
    }
    fprintf(stderr, "MuJoCo fatal error on a thread with no guarded call: %s\n", m->subject);
    abort();
  }
  if (sink) sink(m->level, m->func, m->subject, m->body);
}

const char* mjr_fatal_message(void) { return fatal; }

/* Runs BODY; returns 0, or 1 when MuJoCo raised a fatal error (mjr_fatal_message). */
#define GUARDED(BODY)                  \
  do {                                 \
    jmp_buf here;                      \
    jmp_buf* outer = guard;            \
    if (setjmp(here)) {                \
      guard = outer;                   \
      return 1;                        \
    }                                  \
    guard = &here;                     \
    BODY;                              \
    guard = outer;                     \
    return 0;                          \
  } while (0)

typedef void (*model_data_fn)(const mjModel*, mjData*);

int mjr_step(model_data_fn step, const mjModel* m, mjData* d, long n) {
  GUARDED(for (long i = 0; i < n; i++) step(m, d));
}

int mjr_call(model_data_fn f, const mjModel* m, mjData* d) { GUARDED(f(m, d)); }

int mjr_set_const(void (*f)(mjModel*, mjData*), mjModel* m, mjData* d) { GUARDED(f(m, d)); }

int mjr_reset_key(void (*f)(const mjModel*, mjData*, int), const mjModel* m, mjData* d, int key) {
  GUARDED(f(m, d, key));
}

int mjr_make_data(mjData* (*f)(const mjModel*), const mjModel* m, mjData** out) {
  GUARDED(*out = f(m));
}

int mjr_copy_model(mjModel* (*f)(mjModel*, const mjModel*), const mjModel* src, mjModel** out) {
  GUARDED(*out = f(0, src));
}

int mjr_load_xml(mjModel* (*f)(const char*, const mjVFS*, char*, int), const char* name,
                 const mjVFS* vfs, char* error, int error_sz, mjModel** out) {
  GUARDED(*out = f(name, vfs, error, error_sz));
}

int mjr_add_buffer(int (*f)(mjVFS*, const char*, const void*, int), mjVFS* vfs, const char* name,
                   const void* buffer, int n, int* out) {
  GUARDED(*out = f(vfs, name, buffer, n));
}
