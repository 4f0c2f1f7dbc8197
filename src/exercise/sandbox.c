/* sandbox.c - the sandbox of make grade (sandbox.h): bubblewrap's argv,
 * the limits a sandboxed command runs under, its prints through a pipe
 * that keeps LOG_MAX bytes, and the killing of whatever a run leaves. */
#define _GNU_SOURCE

#include "exercise/sandbox.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

bool sandbox_unsafe;
uid_t sandbox_uid;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

void sandbox_limits(void *ctx)
{
    const struct limits *L = ctx;
    struct rlimit r;
    r.rlim_cur = r.rlim_max = L->cpu;
    setrlimit(RLIMIT_CPU, &r);
    r.rlim_cur = r.rlim_max = L->as;
    setrlimit(RLIMIT_AS, &r);
    r.rlim_cur = r.rlim_max = L->fsize;
    setrlimit(RLIMIT_FSIZE, &r);
    r.rlim_cur = r.rlim_max = 0;
    setrlimit(RLIMIT_CORE, &r);
    r.rlim_cur = r.rlim_max = 256;
    setrlimit(RLIMIT_NOFILE, &r);
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (sandbox_uid) {    /* root is above every process limit: a user of its own */
        setgroups(0, NULL);
        if (setgid(sandbox_uid) != 0 || setuid(sandbox_uid) != 0)
            _exit(126);
    }
    r.rlim_cur = r.rlim_max = L->nproc;
    setrlimit(RLIMIT_NPROC, &r);
}

/* Processes the user who runs the sandbox has now (the process limit
 * counts them all), or, with uid, those of uid. */
rlim_t sandbox_processes(uid_t uid)
{
    if (sandbox_uid && !uid)
        return 0;       /* a user of its own: none yet */
    rlim_t n = 0;
    DIR *d = opendir("/proc");
    struct dirent *e;
    while (d && (e = readdir(d))) {
        char p[300];
        struct stat st;
        snprintf(p, sizeof p, "/proc/%s", e->d_name);
        if (e->d_name[0] >= '0' && e->d_name[0] <= '9' && stat(p, &st) == 0
            && st.st_uid == (uid ? uid : getuid()))
            n++;
    }
    if (d)
        closedir(d);
    return n;
}

/* Kill every process of the user id uid (the sandbox's: nothing else runs
 * as it), and wait until the kernel has let them go (until then they count
 * against a process limit). */
void sandbox_kill_user(uid_t uid)
{
    for (int round = 0; round < 400 && sandbox_processes(uid) > 0; round++) {
        pid_t k = fork();
        if (k == 0) {
            if (setgid(uid) == 0 && setuid(uid) == 0)
                kill(-1, SIGKILL);      /* as uid: every process of uid, and nothing else */
            _exit(0);
        }
        if (k > 0)
            waitpid(k, NULL, 0);
        nanosleep(&(struct timespec){ 0, 5000000 }, NULL);
    }
}

/* The children of this process (a subreaper: orphans of what it started
 * become its children), killed and reaped until none is left. */
void sandbox_kill_children(void)
{
    for (int round = 0; round < 1000; round++) {
        int found = 0;
        DIR *d = opendir("/proc");
        struct dirent *e;
        while (d && (e = readdir(d))) {
            if (e->d_name[0] < '0' || e->d_name[0] > '9')
                continue;
            char p[300], buf[512];
            snprintf(p, sizeof p, "/proc/%s/stat", e->d_name);
            FILE *f = fopen(p, "r");
            size_t k = f ? fread(buf, 1, sizeof buf - 1, f) : 0;
            if (f)
                fclose(f);
            buf[k] = '\0';
            const char *close_paren = strrchr(buf, ')');     /* the name may hold anything */
            char state;
            int ppid;
            if (close_paren && sscanf(close_paren + 1, " %c %d", &state, &ppid) == 2 && ppid == getpid()) {
                kill(atoi(e->d_name), SIGKILL);
                found++;
            }
        }
        if (d)
            closedir(d);
        while (waitpid(-1, NULL, WNOHANG) > 0)
            found++;
        if (!found && waitpid(-1, NULL, WNOHANG) < 0 && errno == ECHILD)
            return;
        nanosleep(&(struct timespec){ 0, 2000000 }, NULL);
    }
}

/* A pipe whose reader keeps the first LOG_MAX bytes written to it in the
 * file path (then a line that says so, the rest dropped): the write end,
 * or -1. The reader is a child of ours; *reader its pid. */
int sandbox_log(const char *path, pid_t *reader)
{
    int fds[2];
    *reader = -1;
    int file = open(path, O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (file < 0 || pipe2(fds, O_CLOEXEC) != 0) {
        if (file >= 0)
            close(file);
        return -1;
    }
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        close(fds[1]);
        struct stat st;
        size_t kept = fstat(file, &st) == 0 ? (size_t)st.st_size : 0;
        char buf[1 << 14];
        ssize_t n;
        bool cut = false;
        while ((n = read(fds[0], buf, sizeof buf)) != 0) {
            if (n < 0) {
                if (errno == EINTR)
                    continue;
                break;
            }
            size_t keep = kept < LOG_MAX ? LOG_MAX - kept : 0;
            if ((size_t)n < keep)
                keep = (size_t)n;
            if (keep && write(file, buf, keep) != (ssize_t)keep)
                break;
            kept += keep;
            if (keep < (size_t)n && !cut) {
                static const char note[] = "\n[the rest of the output is not kept: more than 256 KiB]\n";
                if (write(file, note, sizeof note - 1) < 0)
                    break;
                cut = true;
            }
        }
        _exit(0);
    }
    close(fds[0]);
    close(file);
    if (pid < 0) {
        close(fds[1]);
        return -1;
    }
    *reader = pid;
    return fds[1];
}

/* The reader's end: it has its last bytes once every writer is gone. */
void sandbox_log_done(int fd, pid_t reader)
{
    if (fd >= 0)
        close(fd);
    if (reader <= 0)
        return;
    for (int k = 0; k < 400; k++) {
        if (waitpid(reader, NULL, WNOHANG) == reader)
            return;
        nanosleep(&(struct timespec){ 0, 5000000 }, NULL);
    }
    kill(reader, SIGKILL);      /* a writer still holds it: it is killed next */
    waitpid(reader, NULL, 0);
}

/* argv of a command in the sandbox: binds given as pairs "--ro-bind" or
 * "--bind", host path, sandbox path; the command after. */
int sandbox_argv(char **argv, const char *const *binds, const char *const *cmd)
{
    int n = 0;
    if (!sandbox_unsafe) {
        static const char *const head[] = {
            "bwrap", "--unshare-all", "--die-with-parent", "--new-session", "--cap-drop", "ALL",
            "--ro-bind", "/usr", "/usr", "--proc", "/proc", "--dev", "/dev",
            "--size", "67108864", "--tmpfs", "/tmp", "--setenv", "PATH", "/usr/bin:/bin",
            "--setenv", "TMPDIR", "/tmp", "--chdir", "/tmp", NULL };
        for (int i = 0; head[i]; i++)
            argv[n++] = (char *)head[i];
        static const char *const top[] = { "/lib", "/lib64", "/bin", "/sbin", NULL };
        for (int i = 0; top[i]; i++) {
            struct stat st;
            if (lstat(top[i], &st) != 0)
                continue;
            if (S_ISLNK(st.st_mode)) {
                static char targets[4][64];
                ssize_t k = readlink(top[i], targets[i], sizeof targets[i] - 1);
                if (k <= 0)
                    continue;
                targets[i][k] = '\0';
                argv[n++] = "--symlink", argv[n++] = targets[i], argv[n++] = (char *)top[i];
            } else {
                argv[n++] = "--ro-bind", argv[n++] = (char *)top[i], argv[n++] = (char *)top[i];
            }
        }
        for (int i = 0; binds[i]; i += 3)
            argv[n++] = (char *)binds[i], argv[n++] = (char *)binds[i + 1], argv[n++] = (char *)binds[i + 2];
        argv[n++] = "--";
    }
    for (int i = 0; cmd[i]; i++)
        argv[n++] = (char *)cmd[i];
    argv[n] = NULL;
    return n;
}

/* Run argv with limits, its output into out, for at most `seconds`: its
 * exit status, or -1 when it ran out of time (killed with everything it
 * started). */
int sandbox_run(char **argv, int fd, struct limits *L, double seconds)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0) {
        setpgid(0, 0);
        int null = open("/dev/null", O_RDONLY);
        dup2(null, 0);
        dup2(fd >= 0 ? fd : null, 1);
        dup2(fd >= 0 ? fd : null, 2);
        for (int k = 3; k < 1024; k++)
            close(k);
        sandbox_limits(L);
        execvp(argv[0], argv);
        _exit(127);
    }
    if (pid < 0)
        return 127;
    setpgid(pid, pid);
    double end = now() + seconds;
    int status = 0;
    for (;;) {
        pid_t w = waitpid(pid, &status, WNOHANG);
        if (w == pid)
            break;
        if (now() > end) {
            kill(-pid, SIGKILL);
            kill(pid, SIGKILL);
            waitpid(pid, &status, 0);
            return -1;
        }
        nanosleep(&(struct timespec){ 0, 5000000 }, NULL);
    }
    kill(-pid, SIGKILL);    /* anything it left behind in its group */
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}
