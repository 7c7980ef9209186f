/* Directory listing for fracas_files (list_dir): the names of the entries of a
 * directory, without "." and "..", each followed by a NUL byte, in buf.
 * Returns the number of bytes the whole list needs (call again with a larger
 * buffer if that exceeds buflen), or -1 if the directory cannot be opened. */
#include <dirent.h>
#include <string.h>

long fracas_list_dir(const char *path, char *buf, long buflen)
{
    DIR *dir = opendir(path);
    struct dirent *e;
    long need = 0;
    if (dir == NULL) return -1;
    while ((e = readdir(dir)) != NULL) {
        long n;
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        n = (long)strlen(e->d_name) + 1;
        if (need + n <= buflen) memcpy(buf + need, e->d_name, (size_t)n);
        need += n;
    }
    closedir(dir);
    return need;
}

/* Size in bytes of the file PATH on disk (what reached the file system), or -1
 * if it cannot be found (for fracas_files: close_written, check_written). */
#include <sys/stat.h>

long long fracas_file_size(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0) return -1;
    return (long long)st.st_size;
}

/* Take an exclusive lock on PATH (created if missing) for the rest of the process:
 * flock, released by the kernel when the process ends, even by SIGKILL. The pid is
 * written into the file for the message of a run that finds it locked. Returns 0,
 * -1 if the file cannot be opened, -2 if another process holds the lock. */
#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <unistd.h>

int fracas_lock_file(const char *path)
{
    char pid[32];
    int n;
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) return -1;
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        close(fd);
        return -2;
    }
    n = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) == 0 && write(fd, pid, (size_t)n) != n) { /* the pid is only informative */ }
    return 0;
}
