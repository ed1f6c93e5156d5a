/* tests/support/test_support.h: helpers shared by the cmocka tests.
 *
 * Declares: cg_test_tmpdir, cg_test_write_file, assert_cg_ok, assert_cg_status.
 */
#ifndef CG_TEST_SUPPORT_H
#define CG_TEST_SUPPORT_H

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include "cg/error.h"

/* A fresh directory under $TMPDIR for this test process, removed at exit. */
const char *cg_test_tmpdir(void);
/* Writes `size` bytes (strlen when size is 0) to DIR/name and returns the full path (static storage per call slot). */
const char *cg_test_write_file(const char *name, const void *data, size_t size);

/* Fails the test with the error's message when a call did not succeed. */
#define assert_cg_ok(call, errp)                                                          \
    do {                                                                                  \
        if (!(call))                                                                      \
            fail_msg("%s failed: %s: %s", #call, cg_status_name((errp)->status),          \
                     (errp)->message);                                                    \
    } while (0)

/* Asserts that a call failed with the named status. */
#define assert_cg_status(call, errp, expected)                                            \
    do {                                                                                  \
        cg_error_clear(errp);                                                             \
        if (call)                                                                         \
            fail_msg("%s succeeded; expected %s", #call, cg_status_name(expected));       \
        if ((errp)->status != (expected))                                                 \
            fail_msg("%s failed with %s (%s); expected %s", #call,                        \
                     cg_status_name((errp)->status), (errp)->message,                     \
                     cg_status_name(expected));                                           \
    } while (0)

#endif
