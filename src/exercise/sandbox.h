/* sandbox.h - the sandbox of make grade (sandbox.c): a command in
 * bubblewrap (new namespaces, no network, read-only /usr and what it is
 * given, a private /tmp of 64 MiB), under limits, as a user of its own
 * when run as root; its prints through a pipe that keeps LOG_MAX bytes;
 * whatever a run leaves behind killed. */
#ifndef TRISTEP_EXERCISE_SANDBOX_H
#define TRISTEP_EXERCISE_SANDBOX_H

#include <stdbool.h>
#include <sys/resource.h>
#include <sys/types.h>

#define LOG_MAX (256 << 10)         /* what is kept of a command's prints */

struct limits {
    rlim_t cpu, as, fsize, nproc;   /* seconds, bytes, bytes, processes */
};

extern bool sandbox_unsafe;         /* UNSAFE=1: commands run as they are, no bubblewrap */
extern uid_t sandbox_uid;           /* run as root: the user id commands run as (0: the caller's) */

/* In a child, before it runs a command: the limits ctx (a struct limits),
 * death with its parent, sandbox_uid. */
void sandbox_limits(void *ctx);
/* The processes of uid now (0: of sandbox_uid's, none if it is set; else
 * of the caller's user), which a process limit counts. */
rlim_t sandbox_processes(uid_t uid);
/* Every process of uid killed, and gone. */
void sandbox_kill_user(uid_t uid);
/* Every child of the caller killed and reaped, until none is left (the
 * caller a subreaper: orphans of what it started are its children). */
void sandbox_kill_children(void);
/* The write end of a pipe whose reader (a child, *reader) keeps the first
 * LOG_MAX bytes in path (appended), then a line that says so; -1 if it
 * cannot. sandbox_log_done closes it and waits for the reader. */
int sandbox_log(const char *path, pid_t *reader);
void sandbox_log_done(int fd, pid_t reader);
/* argv of cmd in the sandbox, binds ("--ro-bind" or "--bind", host path,
 * sandbox path, ..., NULL) added; cmd alone when sandbox_unsafe. */
int sandbox_argv(char **argv, const char *const *binds, const char *const *cmd);
/* argv run with limits L, its output into fd, for at most seconds: its
 * exit status (128 + a signal's), or -1 when it ran out of time (killed
 * with everything it started). */
int sandbox_run(char **argv, int fd, struct limits *L, double seconds);

#endif
