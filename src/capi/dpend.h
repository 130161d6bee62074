/* dpend as a library: the C interface of src/capi/dpend_capi.f90 (docs/library.md).
 *
 * dpend_run runs one command in the calling thread, as `dpend COMMAND ARGS...` would:
 * the options are the command line's, checked by the same settings layer (a refusal
 * is the command line's line, word for word); the HDF5 file the command writes is
 * written to memory and handed over as a result whose bytes are that file. Nothing
 * prints, stops or exits the process. Calls from several threads are safe and run one
 * at a time (each with its own OpenMP threads inside).
 *
 * Error kinds: 0 ok, 1 the run failed partway (the result holds what was computed and
 * the status), 2 refused input (no result), 3 not available in the library. */
#ifndef DPEND_H
#define DPEND_H

#ifdef __cplusplus
extern "C" {
#endif

/* Run `command` (simulate, lyapunov, indicators, divergence, poincare, fit, sweep;
 * models and methods without options give their text as the message) with its
 * nargs options args, e.g. {"--q1", "0", "--t-end", "1"} (not --output, --force or
 * --quiet). *result receives the result or NULL; message one line (the command's
 * closing text, its refusal or why the run failed; with --help the help text), at
 * most msg_len bytes with the terminating NUL. Returns the error kind. */
int dpend_run(const char *command, int nargs, const char *const *args, void **result,
              char *message, int msg_len);

/* A progress callback: `done` of `total` units (`what`: "traj" a sweep's
 * trajectories, "runs" the study's runs, "steps" a fit's step-equivalents, "" parts
 * of a simulation's horizon) of the report `label` (e.g. "dpend sweep"). */
typedef void (*dpend_progress_fn)(long long done, long long total, const char *what,
                                  const char *label, void *user);

/* dpend_run with a progress callback (NULL: none), called from the run's threads one
 * call at a time: when a report starts, at most every 0.1 s, and when it ends; `user`
 * is handed to it. It must return quickly and not call dpend_run (dpend_cancel may). */
int dpend_run_progress(const char *command, int nargs, const char *const *args,
                       void **result, char *message, int msg_len, dpend_progress_fn fn,
                       void *user);

/* Bytes of the result's file image (0 for NULL). */
long long dpend_result_bytes(void *result);

/* Copy the image into buf of n bytes: 0, or 2 when n is too small or a pointer NULL. */
int dpend_result_copy(void *result, void *buf, long long n);

/* The image's address (dpend_result_bytes bytes), valid until dpend_result_free;
 * NULL for NULL. */
const void *dpend_result_data(void *result);

/* Release a result (NULL is ignored). */
void dpend_result_free(void *result);

/* Ask the call in progress in another thread to stop: a sweep's lanes stop taking
 * trajectories and its threads blocks (the trajectories in flight end first), and it
 * returns kind 1, its result holding the blocks done. Each dpend_run forgets an
 * earlier request as it starts. */
void dpend_cancel(void);

/* The version into buf (n bytes with the NUL); returns its length. */
int dpend_version(char *buf, int n);

#ifdef __cplusplus
}
#endif
#endif
