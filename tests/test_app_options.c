/* The option parsers every app shares (apps/common): memory sizes, and the common options as
 * app_parse_options reads them. */
#include <stdint.h>
#include <string.h>

#include "app_common.h"
#include "app_options.h"
#include "test_support.h"

static void
test_memory_sizes_need_a_unit(void **state)
{
    (void)state;
    size_t v = 0;
    assert_true(app_parse_bytes("512M", &v));
    assert_int_equal(v, (size_t)512 << 20);
    assert_true(app_parse_bytes("512MiB", &v));
    assert_int_equal(v, (size_t)512 << 20);
    assert_true(app_parse_bytes("2g", &v));
    assert_int_equal(v, (size_t)2 << 30);
    assert_true(app_parse_bytes("1.5G", &v));
    assert_int_equal(v, (size_t)3 << 29);
    assert_true(app_parse_bytes("4096B", &v));
    assert_int_equal(v, 4096);
    assert_true(app_parse_bytes("64k", &v));
    assert_int_equal(v, 65536);
    assert_true(app_parse_bytes("1T", &v));
    assert_int_equal(v, (size_t)1 << 40);
    assert_true(app_parse_bytes("0.5K", &v));
    assert_int_equal(v, 512);
    /* Ambiguous or malformed: refused, *out untouched. */
    const char *bad[] = { "512", "0", "0M", "0.0001B", "1MB", "1GB", "1kb", "M", "", "-1M", "+1M", "1e3M",
                          "0x10M", "infM", "nanG", "1.M5", "1..5M", "1 M", " 1M", "1M ", "17000000T" };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        v = 7;
        if (app_parse_bytes(bad[i], &v))
            fail_msg("'%s' was taken as %zu bytes", bad[i], v);
        assert_int_equal(v, 7);
    }
}

CG_TEST_MAIN(NULL, NULL,
             cmocka_unit_test(test_memory_sizes_need_a_unit))
