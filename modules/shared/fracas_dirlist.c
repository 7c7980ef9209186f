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
