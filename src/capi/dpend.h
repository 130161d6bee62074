/* dpend as a library: the C interface of src/capi/dpend_capi.f90 (docs/library.md).
 *
 * dpend_run runs one command in the calling thread, as `dpend COMMAND ARGS...` would:
 * the options are the command line's, checked by the same settings layer (a refusal
 * is the command line's line, word for word); the HDF5 file the command writes is
 * recorded in memory and handed over as a result: its datasets and attributes as
 * named arrays, and the file's image. Nothing
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

/* A run's settings as a handle: the command, then its options one by one by name and
 * value, checked when the run starts by the same settings layer as the command line
 * (the same refusals, word for word; an option given twice is refused). */
void *dpend_settings_new(const char *command);

/* Set an option: name as on the command line without its dashes ("t-end" or
 * "t_end"), value its text (NULL for a flag such as "fit-damping"); a NULL or empty
 * name gives a positional argument (fit's CSV file). Returns 0, or 2 for a NULL
 * handle, a name not of letters, digits, '-' and '_' (a letter first), or a
 * positional argument without a value. */
int dpend_settings_set(void *settings, const char *name, const char *value);

/* Run the command with the options set: as dpend_run_progress (fn NULL: none). */
int dpend_settings_run(void *settings, void **result, char *message, int msg_len,
                       dpend_progress_fn fn, void *user);

/* Release settings (NULL is ignored); a result outlives its settings. */
void dpend_settings_free(void *settings);

/* A result is the file the command writes, as named arrays (its items) and as an
 * HDF5 file image. The items are the file's datasets and attributes in the order
 * written; a sweep's result has its image only (0 items). */

/* Item types: IEEE double (itemsize 8), signed little-endian integer (4 or 8),
 * fixed-length NUL-padded string (itemsize its length), UTF-8 text (a scalar
 * attribute; itemsize its length, no NUL). */
enum { DPEND_REAL = 1, DPEND_INTEGER = 2, DPEND_STRING = 3, DPEND_TEXT = 4 };

/* The number of items (0 for NULL or a sweep's result). */
int dpend_result_items(void *result);

/* Item i (from 0): path (the dataset, or the object of an attribute, e.g.
 * "/trajectory/energy", "/"), name ("" for a dataset, else the attribute's, e.g.
 * "units"), type, bytes per element, rank and shape in C order (as the file and h5py
 * give it; dims holds 8). Returns 0, or 2 for no such item or a buffer too small. */
int dpend_result_item(void *result, int i, char *path, int path_len, char *name,
                      int name_len, int *type, long long *itemsize, int *rank,
                      long long *dims);

/* The index of item path, name ("" or NULL: the dataset), or -1. */
int dpend_result_find(void *result, const char *path, const char *name);

/* Bytes of item i's values, their address (C order, valid until dpend_result_free;
 * NULL when empty), and a copy into buf of n bytes (0, or 2: no such item, n too
 * small or buf NULL). */
long long dpend_result_item_bytes(void *result, int i);
const void *dpend_result_item_data(void *result, int i);
int dpend_result_item_copy(void *result, int i, void *buf, long long n);

/* Bytes of the result's file image (0 for NULL); the image is made from the items
 * the first time it is asked for. */
long long dpend_result_bytes(void *result);

/* Copy the image into buf of n bytes: 0, or 2 when n is too small or a pointer NULL. */
int dpend_result_copy(void *result, void *buf, long long n);

/* The image's address (dpend_result_bytes bytes), valid until dpend_result_free;
 * NULL for NULL. */
const void *dpend_result_data(void *result);

/* Release a result (NULL is ignored). */
void dpend_result_free(void *result);

/* Ask the call in progress in another thread to stop: a sweep's lanes stop taking
 * trajectories and its threads blocks (the trajectories in flight end first); every
 * other command stops within 256 steps of the method it integrates with. The call
 * returns kind 1, its result holding what was computed (a sweep's blocks done, a
 * trajectory's samples so far). Each dpend_run forgets an earlier request as it
 * starts. */
void dpend_cancel(void);

/* The version into buf (n bytes with the NUL); returns its length. */
int dpend_version(char *buf, int n);

#ifdef __cplusplus
}
#endif
#endif
