/* test_file.c: regular-file reads with limits (no FIFO, device or directory is ever read)
 * and atomic writes (a failed write leaves the old file and no temporary file). */
#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "file.h"
#include "test.h"

TEST(read_file_returns_every_byte_nul_terminated)
{
    const char *path = "tests/data/obj/checker2x2.png"; /* binary: holds NUL bytes */
    struct stat st;
    if (stat(path, &st) != 0) {
        test_fail(t, __FILE__, __LINE__, "%s missing (run from the repository root)", path);
        return;
    }
    char *text;
    size_t len;
    REQUIRE(file_read(path, FILE_MAX_IMAGE, &text, &len) == 0);
    CHECK_EQ_INT(len, st.st_size);
    CHECK(memcmp(text, "\x89PNG\r\n\x1a\n", 8) == 0);
    CHECK(memchr(text, '\0', len) != NULL);
    CHECK_EQ_INT(text[len], '\0');
    FILE *f = fopen(path, "rb");
    REQUIRE(f);
    char *want = malloc(len + 1);
    REQUIRE(want);
    CHECK_EQ_INT(fread(want, 1, len + 1, f), len);
    fclose(f);
    CHECK(memcmp(text, want, len) == 0);
    free(want);
    free(text);
}

TEST(read_file_refuses_special_files_and_oversize)
{
    char *text = (char *)1;
    size_t len = 7;
    CHECK_EQ_INT(file_read("tests/data/obj/no_such.obj", 100, &text, &len), ENOENT);
    CHECK(text == NULL);
    CHECK_EQ_INT(len, 0);
    CHECK_EQ_INT(file_read("tests/data/obj", 100, &text, &len), EISDIR);
    /* devices: /dev/zero would never end, /dev/null is no file either */
    CHECK_EQ_INT(file_read("/dev/zero", FILE_MAX_TEXT, &text, &len), FILE_E_DEVICE);
    CHECK_EQ_INT(file_read("/dev/urandom", FILE_MAX_TEXT, &text, &len), FILE_E_DEVICE);
    CHECK_EQ_INT(file_read("/dev/null", FILE_MAX_TEXT, &text, &len), FILE_E_DEVICE);
    CHECK(text == NULL);
    /* a FIFO without a writer: opening it must not block */
    char fifo[64];
    snprintf(fifo, sizeof fifo, "/tmp/rastty-test-fifo-%d", (int)getpid());
    unlink(fifo);
    REQUIRE(mkfifo(fifo, 0600) == 0);
    CHECK_EQ_INT(file_read(fifo, FILE_MAX_TEXT, &text, &len), FILE_E_FIFO);
    unlink(fifo);
    CHECK_STR_CONTAINS(file_strerror(FILE_E_FIFO), "FIFO");
    /* over the limit: refused before reading */
    CHECK_EQ_INT(file_read("tests/data/obj/checker2x2.png", 10, &text, &len), FILE_E_TOO_BIG);
    CHECK(text == NULL);
}

static int count_temp_files(const char *dir, const char *prefix)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *de;
    while (d && (de = readdir(d)))
        n += strncmp(de->d_name, prefix, strlen(prefix)) == 0;
    if (d)
        closedir(d);
    return n;
}

TEST(atomic_write_replaces_only_on_success)
{
    char dir[64], path[96], text[200];
    snprintf(dir, sizeof dir, "/tmp/rastty-test-out-%d", (int)getpid());
    mkdir(dir, 0700);
    snprintf(path, sizeof path, "%s/out.txt", dir);
    FILE *f = fopen(path, "w");
    REQUIRE(f);
    fputs("old contents\n", f);
    fclose(f);

    struct file_out o;
    struct err e;
    REQUIRE(file_out_open(&o, path, &e) == 0);
    fputs("new", o.f);
    /* nothing replaced until commit */
    f = fopen(path, "r");
    REQUIRE(f && fgets(text, sizeof text, f));
    fclose(f);
    CHECK(strcmp(text, "old contents\n") == 0);
    CHECK_EQ_INT(count_temp_files(dir, ".out.txt."), 1);
    file_out_abort(&o);
    CHECK_EQ_INT(count_temp_files(dir, ".out.txt."), 0);

    /* a write that fails (file size limit, as a full disk would) leaves the old file */
    REQUIRE(file_out_open(&o, path, &e) == 0);
    struct rlimit old, small = {4096, 4096};
    getrlimit(RLIMIT_FSIZE, &old);
    small.rlim_max = old.rlim_max;
    void (*prev)(int) = signal(SIGXFSZ, SIG_IGN);
    setrlimit(RLIMIT_FSIZE, &small);
    for (int i = 0; i < 10000; i++)
        fputs("0123456789", o.f);
    int rc = file_out_commit(&o, &e);
    setrlimit(RLIMIT_FSIZE, &old);
    signal(SIGXFSZ, prev);
    CHECK_EQ_INT(rc, -1);
    CHECK_STR_CONTAINS(e.msg, "out.txt: write failed: File too large");
    f = fopen(path, "r");
    REQUIRE(f && fgets(text, sizeof text, f));
    fclose(f);
    CHECK(strcmp(text, "old contents\n") == 0);
    CHECK_EQ_INT(count_temp_files(dir, ".out.txt."), 0);

    /* success: the new contents, the file's mode as a plain create gives it */
    REQUIRE(file_out_open(&o, path, &e) == 0);
    fputs("new contents\n", o.f);
    REQUIRE(file_out_commit(&o, &e) == 0);
    f = fopen(path, "r");
    REQUIRE(f && fgets(text, sizeof text, f));
    fclose(f);
    CHECK(strcmp(text, "new contents\n") == 0);
    struct stat st;
    REQUIRE(stat(path, &st) == 0);
    mode_t um = umask(0);
    umask(um);
    CHECK_EQ_INT(st.st_mode & 0777, 0666 & ~um);
    CHECK_EQ_INT(count_temp_files(dir, ".out.txt."), 0);
    unlink(path);
    rmdir(dir);

    /* a directory that does not exist: the message names the target, quoted */
    CHECK_EQ_INT(file_out_open(&o, "/nonexistent-dir/\x1b[31mx.png", &e), -1);
    CHECK(strcmp(e.msg, "/nonexistent-dir/?[31mx.png: cannot create: No such file or "
                        "directory") == 0);
}
