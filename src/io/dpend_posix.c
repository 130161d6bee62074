/* POSIX services that Fortran cannot reach portably: the kind of a path (lstat),
 * a file's identity (device and inode), free disk space (statvfs), unique temporary files (mkstemp), fsync,
 * disk blocks for a sparse file (posix_fallocate), a move that
 * never replaces (renameat2 RENAME_NOREPLACE, else link + unlink), errno texts,
 * and running a program with an argument vector and no shell (posix_spawnp).
 * Called from dpend_os through bind(C) interfaces. Every function returns 0
 * or a positive errno value; nothing here prints or exits. */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <spawn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

extern char **environ;

/* 0 missing, 1 regular file, 2 directory, 3 symbolic link, 4 anything else
 * (device, FIFO, socket); -errno when (l)stat fails otherwise. With `follow`
 * nonzero, symbolic links are followed (stat), else not (lstat). */
int dpend_path_kind(const char *path, int follow)
{
    struct stat st;
    int r = follow ? stat(path, &st) : lstat(path, &st);
    if (r != 0) return errno == ENOENT || errno == ENOTDIR ? 0 : -errno;
    if (S_ISREG(st.st_mode)) return 1;
    if (S_ISDIR(st.st_mode)) return 2;
    if (S_ISLNK(st.st_mode)) return 3;
    return 4;
}

/* The device and inode of `path` (symbolic links followed): what identifies a
 * file whatever name reaches it (hard links, "./a", "dir/../a"). 0 or errno. */
int dpend_file_id(const char *path, long long *dev, long long *ino)
{
    struct stat st;
    if (stat(path, &st) != 0) return errno;
    *dev = (long long)st.st_dev;
    *ino = (long long)st.st_ino;
    return 0;
}

/* Bytes available to an unprivileged user on the file system of `path`, or -1. */
long long dpend_free_bytes(const char *path)
{
    struct statvfs s;
    if (statvfs(path, &s) != 0) return -1;
    return (long long)s.f_bavail * (long long)s.f_frsize;
}

/* Create a new empty file from `template` (ending in XXXXXX, replaced in place),
 * with the permissions an ordinary new file gets (0666 less the umask). */
int dpend_make_temp(char *template)
{
    int fd = mkstemp(template);
    if (fd < 0) return errno;
    mode_t mask = umask(0);
    umask(mask);
    int err = fchmod(fd, 0666 & ~mask) != 0 ? errno : 0;
    if (close(fd) != 0 && err == 0) err = errno;
    return err;
}

/* Flush a file's data (or a directory's entries) to the device. */
int dpend_sync_path(const char *path)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return errno;
    int err = fsync(fd) != 0 ? errno : 0;
    /* directories on some file systems refuse fsync: not an error for us */
    if (err == EINVAL || err == EROFS) err = 0;
    if (close(fd) != 0 && err == 0) err = errno;
    return err;
}

/* Give the file `path` disk blocks for all of its length (posix_fallocate), so
 * that later writes inside it cannot meet a full disk: a file made sparse (HDF5
 * datasets allocated and not written) takes its space now. The contents stay. */
int dpend_reserve_space(const char *path)
{
    int fd = open(path, O_RDWR | O_CLOEXEC);
    if (fd < 0) return errno;
    struct stat st;
    int err = fstat(fd, &st) != 0 ? errno : 0;
    if (err == 0 && st.st_size > 0) err = posix_fallocate(fd, 0, st.st_size);
    if (close(fd) != 0 && err == 0) err = errno;
    return err;
}

/* Move `from` to `to` in one step, failing with EEXIST if `to` exists. */
int dpend_move_noreplace(const char *from, const char *to)
{
    if (renameat2(AT_FDCWD, from, AT_FDCWD, to, RENAME_NOREPLACE) == 0) return 0;
    if (errno != EINVAL && errno != ENOSYS && errno != ENOTSUP) return errno;
    /* file systems without RENAME_NOREPLACE: a hard link is also exclusive */
    if (link(from, to) != 0) return errno;
    unlink(from);
    return 0;
}

/* Move `from` to `to` in one step, replacing `to`. */
int dpend_move_replace(const char *from, const char *to)
{
    return rename(from, to) == 0 ? 0 : errno;
}

int dpend_remove(const char *path)
{
    return unlink(path) == 0 ? 0 : errno;
}

/* The text of errno value `err` in `buf` (NUL-terminated, at most `len` bytes). */
void dpend_error_text(int err, char *buf, int len)
{
    if (len <= 0) return;
    snprintf(buf, (size_t)len, "%s", strerror(err));
}

int dpend_spawn_wait_err(char *const argv[], int *status, const char *errpath);

/* Run argv[0] (searched on PATH) with the argument vector `argv` (NULL-ended),
 * no shell, and wait for it. `status` is its exit status, or 128 + the signal
 * that ended it. Returns 0, or the errno of a failed start. */
int dpend_spawn_wait(char *const argv[], int *status)
{
    return dpend_spawn_wait_err(argv, status, NULL);
}

/* As dpend_spawn_wait, with the program's standard error written to the file
 * `errpath` (created or truncated, mode 0600) unless `errpath` is NULL or "". */
int dpend_spawn_wait_err(char *const argv[], int *status, const char *errpath)
{
    pid_t pid;
    int err;
    if (errpath != NULL && errpath[0] != '\0') {
        posix_spawn_file_actions_t fa;
        err = posix_spawn_file_actions_init(&fa);
        if (err != 0) return err;
        err = posix_spawn_file_actions_addopen(&fa, 2, errpath,
                                               O_WRONLY | O_CREAT | O_TRUNC, 0600);
        if (err == 0) err = posix_spawnp(&pid, argv[0], &fa, NULL, argv, environ);
        posix_spawn_file_actions_destroy(&fa);
    } else {
        err = posix_spawnp(&pid, argv[0], NULL, NULL, argv, environ);
    }
    if (err != 0) return err;
    int ws;
    while (waitpid(pid, &ws, 0) < 0) {
        if (errno != EINTR) return errno;
    }
    *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + (WIFSIGNALED(ws) ? WTERMSIG(ws) : 0);
    return 0;
}

/* ---- The optional GPU library (docs/gpu.md): loaded at run time with
 * dlopen, never linked, so that dpend builds and runs without CUDA. */
#include <dlfcn.h>

typedef int (*dpend_gpu_abi_fn)(void);
typedef int (*dpend_gpu_probe_fn)(int *, char *, int, int *, int *, char *, int);
typedef int (*dpend_gpu_run_fn)(const double *, const double *, double, double, long long,
                                int, long long, int, const double *, double *, double *,
                                double *, double *, double *, double *, double *, int *,
                                int *, double *, int *, char *, int);
static void *dpend_gpu_handle = NULL;
static dpend_gpu_probe_fn dpend_gpu_probe_ptr = NULL;
static dpend_gpu_run_fn dpend_gpu_run_ptr = NULL;

/* Load the library at `path` (once; later calls return 0 at once). 0, or 1 when it
 * cannot be loaded, 2 when it lacks a function or has another interface version;
 * `msg` (msg_len bytes) says why. */
int dpend_gpu_load(const char *path, char *msg, int msg_len)
{
    void *h;
    dpend_gpu_abi_fn abi;
    const char *e;
    if (msg_len > 0) msg[0] = '\0';
    if (dpend_gpu_handle != NULL) return 0;
    h = dlopen(path, RTLD_NOW | RTLD_LOCAL);
    if (h == NULL) {
        e = dlerror();
        if (msg_len > 0) snprintf(msg, (size_t)msg_len, "%s", e ? e : "dlopen failed");
        return 1;
    }
    abi = (dpend_gpu_abi_fn)dlsym(h, "dpend_gpu_abi");
    dpend_gpu_probe_ptr = (dpend_gpu_probe_fn)dlsym(h, "dpend_gpu_probe");
    dpend_gpu_run_ptr = (dpend_gpu_run_fn)dlsym(h, "dpend_gpu_run_block");
    if (abi == NULL || dpend_gpu_probe_ptr == NULL || dpend_gpu_run_ptr == NULL || abi() != 1) {
        if (msg_len > 0) snprintf(msg, (size_t)msg_len, "not a dpend GPU library of interface 1");
        dpend_gpu_probe_ptr = NULL;
        dpend_gpu_run_ptr = NULL;
        dlclose(h);
        return 2;
    }
    dpend_gpu_handle = h;
    return 0;
}

/* The loaded library's dpend_gpu_probe; -1 if none is loaded. */
int dpend_gpu_call_probe(int *count, char *name, int name_len, int *driver, int *runtime,
                         char *msg, int msg_len)
{
    if (dpend_gpu_probe_ptr == NULL) return -1;
    return dpend_gpu_probe_ptr(count, name, name_len, driver, runtime, msg, msg_len);
}

/* The loaded library's dpend_gpu_run_block (src/gpu/dpend_sweep_kernel.cu); -1 if none
 * is loaded. */
int dpend_gpu_call_run(const double *coef, const double *bounds, double escale, double h,
                       long long n_steps, int stop_rule, long long steps_per_launch, int n,
                       const double *y0, double *t_flip1, double *t_flip2, double *t_flip,
                       double *energy0, double *energy_error, double *t_stop, double *fin,
                       int *status, int *steps, double *kernel_ms, int *launches, char *msg,
                       int msg_len)
{
    if (dpend_gpu_run_ptr == NULL) return -1;
    return dpend_gpu_run_ptr(coef, bounds, escale, h, n_steps, stop_rule, steps_per_launch, n,
                             y0, t_flip1, t_flip2, t_flip, energy0, energy_error, t_stop, fin,
                             status, steps, kernel_ms, launches, msg, msg_len);
}

/* In-memory outputs of a library call (src/capi): while this thread captures, the
 * HDF5 files it creates live in memory (HDF5's core driver, no backing store) and
 * the image of the last one closed is kept here, in storage of this thread alone:
 * two library calls in two threads never see each other's. */
static _Thread_local int dpend_capturing = 0;
static _Thread_local unsigned char *dpend_captured = NULL;
static _Thread_local size_t dpend_captured_bytes = 0;

/* Start (on nonzero) or stop capturing; either drops an image not taken. */
void dpend_capture_set(int on)
{
    free(dpend_captured);
    dpend_captured = NULL;
    dpend_captured_bytes = 0;
    dpend_capturing = on != 0;
}

/* 1 while this thread captures its outputs, else 0. */
int dpend_capture_active(void) { return dpend_capturing; }

/* A buffer of n bytes for the image of the file being closed (replacing the last
 * one); NULL when memory is short. */
void *dpend_capture_buffer(size_t n)
{
    free(dpend_captured);
    dpend_captured = malloc(n > 0 ? n : 1);
    dpend_captured_bytes = dpend_captured != NULL ? n : 0;
    return dpend_captured;
}

/* The last image, handed over (the caller frees it with free()); NULL if none. */
void *dpend_capture_take(size_t *n)
{
    void *image = dpend_captured;
    *n = dpend_captured_bytes;
    dpend_captured = NULL;
    dpend_captured_bytes = 0;
    return image;
}

/* A new private directory from template (its last six characters XXXXXX are
 * replaced; mkdtemp). 0 or errno. */
int dpend_make_temp_dir(char *template)
{
    return mkdtemp(template) != NULL ? 0 : errno;
}

/* Remove an empty directory. 0 or errno. */
int dpend_remove_dir(const char *path)
{
    return rmdir(path) == 0 ? 0 : errno;
}

/* One library call at a time in the process (src/capi): gfortran 12 keeps the length
 * of a function's deferred-length character result in static storage of the caller,
 * so the settings and command code is not reentrant; each call still runs its own
 * OpenMP threads inside, whose code keeps off those lengths (scripts/check_threads.sh). */
#include <pthread.h>
static pthread_mutex_t dpend_library_mutex = PTHREAD_MUTEX_INITIALIZER;
void dpend_library_lock(void) { pthread_mutex_lock(&dpend_library_mutex); }
void dpend_library_unlock(void) { pthread_mutex_unlock(&dpend_library_mutex); }

