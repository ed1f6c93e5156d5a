/* Temporary files that a killed run leaves beside an output (cg/fs.h): a process killed with
 * SIGKILL while it writes leaves ".NAME.tmp-PID-N.EXT"; the next write of that output, by any
 * of the writers (images, atomic files, glTF export, the conegraph command), removes it, and
 * leaves alone the temporaries of a live process and those of other outputs. */
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "cg/fs.h"
#include "cg/image.h"
#include "cg/scene.h"
#include "test_support.h"

static bool
exists(const char *path)
{
    return access(path, F_OK) == 0;
}

/* Forks a child that opens the temporary of `target` as a writer would, writes a few bytes and
 * is killed with SIGKILL; returns the temporary's path (static storage). */
static const char *
killed_writer(const char *target)
{
    static char temp[4096];
    int fds[2];
    assert_int_equal(pipe(fds), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        char t[4096];
        if (!cg_temp_path_for(target, t, sizeof t))
            _exit(1);
        FILE *fp = fopen(t, "wb");
        if (!fp)
            _exit(1);
        fputs("half an image", fp);
        fflush(fp);
        if (write(fds[1], t, strlen(t) + 1) < 0)
            _exit(1);
        raise(SIGKILL);
        _exit(1);
    }
    close(fds[1]);
    ssize_t n = read(fds[0], temp, sizeof temp - 1);
    close(fds[0]);
    assert_true(n > 0);
    temp[n] = '\0';
    int status;
    assert_int_equal(waitpid(pid, &status, 0), pid);
    assert_true(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    assert_true(exists(temp));
    return temp;
}

/* A temporary named for a process that runs (init, pid 1), and one of another output. */
static void
bystanders(const char *dir, const char *name, const char *ext, char live[4200], char other[4200])
{
    snprintf(live, 4200, "%s/.%s.tmp-1-0%s", dir, name, ext);
    snprintf(other, 4200, "%s/.other.tmp-999999999-0%s", dir, ext);
    cg_test_write_file(strrchr(live, '/') + 1, "live", 0);
    cg_test_write_file(strrchr(other, '/') + 1, "other", 0);
}

static void
image_write_removes_what_a_killed_run_left(void **state)
{
    (void)state;
    const char *dir = cg_test_tmpdir();
    char target[4200], live[4200], other[4200], stale[4200];
    snprintf(target, sizeof target, "%s/frame.exr", dir);
    snprintf(stale, sizeof stale, "%s", killed_writer(target));
    bystanders(dir, "frame", ".exr", live, other);
    cg_image img;
    cg_error err = { 0 };
    assert_cg_ok(cg_image_alloc(&img, 4, 2, &err), &err);
    assert_cg_ok(cg_image_write(target, &img, CG_EXR_HALF, &err), &err);
    cg_image_free(&img);
    assert_true(exists(target));
    assert_false(exists(stale));
    assert_true(exists(live));
    assert_true(exists(other));
    unlink(live);
    unlink(other);
}

static void
atomic_file_and_export_remove_it_too(void **state)
{
    (void)state;
    const char *dir = cg_test_tmpdir();
    char target[4200], stale[4200];
    snprintf(target, sizeof target, "%s/report.json", dir);
    snprintf(stale, sizeof stale, "%s", killed_writer(target));
    cg_atomic_file f;
    cg_error err = { 0 };
    assert_cg_ok(cg_atomic_open(&f, target, &err), &err);
    fputs("{}\n", f.fp);
    assert_cg_ok(cg_atomic_commit(&f, &err), &err);
    assert_false(exists(stale));

    snprintf(target, sizeof target, "%s/scene.glb", dir);
    snprintf(stale, sizeof stale, "%s", killed_writer(target));
    cg_scene s;
    assert_cg_ok(cg_scene_load("builtin:cornell", &s, &err), &err);
    assert_cg_ok(cg_scene_export_gltf(&s, target, &err), &err);
    cg_scene_free(&s);
    assert_false(exists(stale));
    assert_true(exists(target));
}

static void
the_next_conegraph_run_removes_it(void **state)
{
    (void)state;
    const char *dir = cg_test_tmpdir();
    char target[4200], stale[4200], args[8600], out[4096];
    snprintf(target, sizeof target, "%s/exported.gltf", dir);
    snprintf(stale, sizeof stale, "%s", killed_writer(target));
    snprintf(args, sizeof args, "export builtin:furnace '%s'", target);
    assert_int_equal(cg_test_run_conegraph(args, true, out, sizeof out), 0);
    assert_false(exists(stale));
    assert_true(exists(target));
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(image_write_removes_what_a_killed_run_left),
             cmocka_unit_test(atomic_file_and_export_remove_it_too),
             cmocka_unit_test(the_next_conegraph_run_removes_it))
