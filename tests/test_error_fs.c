/* Unit tests of the error table and the file helpers (atomic writes). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cg/error.h"
#include "cg/fs.h"
#include "test_support.h"

static void
first_failure_wins(void **state)
{
    (void)state;
    cg_error err = {0};
    assert_false(cg_fail(&err, CG_ERR_IO, "first %d", 1));
    assert_false(cg_fail(&err, CG_ERR_USAGE, "second"));
    assert_int_equal(err.status, CG_ERR_IO);
    assert_string_equal(err.message, "first 1");
    cg_error_clear(&err);
    assert_int_equal(err.status, CG_OK);
    assert_false(cg_fail(NULL, CG_ERR_IO, "no record"));
}

static void
every_status_has_a_name_and_exit_code(void **state)
{
    (void)state;
    for (int s = 0; s < CG_STATUS_COUNT; s++) {
        assert_non_null(strstr(cg_status_name((cg_status)s), "CG_"));
        assert_true(strlen(cg_status_summary((cg_status)s)) > 0);
        int code = cg_status_exit_code((cg_status)s);
        assert_true(s == CG_OK ? code == 0 : (code == 1 || code == 2));
    }
    assert_int_equal(cg_status_exit_code(CG_ERR_GRAPH_CYCLE), 2);
    assert_int_equal(cg_status_exit_code(CG_ERR_PASS), 1);
}

static void
atomic_write_replaces_only_on_commit(void **state)
{
    (void)state;
    cg_error err = {0};
    const char *path = cg_test_write_file("target.txt", "old", 0);

    cg_atomic_file f;
    assert_cg_ok(cg_atomic_open(&f, path, &err), &err);
    fputs("new contents", f.fp);
    cg_atomic_abort(&f);
    char *data;
    size_t size;
    assert_cg_ok(cg_read_file(path, &data, &size, &err), &err);
    assert_string_equal(data, "old");
    free(data);
    assert_int_not_equal(access(f.temp_path, F_OK), 0);

    assert_cg_ok(cg_atomic_open(&f, path, &err), &err);
    fputs("new contents", f.fp);
    assert_cg_ok(cg_atomic_commit(&f, &err), &err);
    assert_cg_ok(cg_read_file(path, &data, &size, &err), &err);
    assert_string_equal(data, "new contents");
    assert_int_equal(size, strlen("new contents"));
    free(data);
}

static void
atomic_open_in_missing_dir_fails(void **state)
{
    (void)state;
    cg_error err = {0};
    cg_atomic_file f;
    char path[4200];
    snprintf(path, sizeof path, "%s/no/such/dir/out.txt", cg_test_tmpdir());
    assert_cg_status(cg_atomic_open(&f, path, &err), &err, CG_ERR_IO);
    assert_non_null(strstr(err.message, "out.txt"));
}

static void
read_missing_file_names_it(void **state)
{
    (void)state;
    cg_error err = {0};
    char *data;
    assert_cg_status(cg_read_file("/nonexistent/file.json", &data, NULL, &err), &err,
                     CG_ERR_FILE_NOT_FOUND);
    assert_non_null(strstr(err.message, "/nonexistent/file.json"));
}

static void
temp_path_keeps_extension_last(void **state)
{
    (void)state;
    char tmp[256];
    assert_true(cg_temp_path_for("dir/image.exr", tmp, sizeof tmp));
    assert_true(strncmp(tmp, "dir/.image.tmp-", 15) == 0);
    assert_string_equal(tmp + strlen(tmp) - 4, ".exr");
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(first_failure_wins),
             cmocka_unit_test(every_status_has_a_name_and_exit_code),
             cmocka_unit_test(atomic_write_replaces_only_on_commit),
             cmocka_unit_test(atomic_open_in_missing_dir_fails),
             cmocka_unit_test(read_missing_file_names_it),
             cmocka_unit_test(temp_path_keeps_extension_last))
