/* cg/progress.h against a clock the test moves by hand (no test here depends on timing): into a
 * file one line per 10% (or per unit when there are fewer than 10) and never a '\r', nothing
 * before the delay, the time left, one updating line on a terminal, nothing when quiet. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cg/log.h"
#include "cg/progress.h"
#include "test_support.h"

static double
fake_clock(void *user)
{
    return *(double *)user;
}

/* What the reporter wrote into its stream. */
static const char *
read_back(FILE *f)
{
    static char text[1 << 14];
    fflush(f);
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    return text;
}

static int
count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

static void
into_a_file_tenths_and_no_carriage_return(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    assert_non_null(f);
    double now = 100;
    cg_progress p;
    cg_progress_begin(&p, &(cg_progress_desc){ .what = "tracing", .total = 1000, .out = f, .terminal = -1,
                                               .delay_s = 2, .clock = fake_clock, .clock_user = &now });
    /* 1000 updates over 10 s: the first second and a half stays silent (below the delay). */
    for (int k = 1; k <= 1000; k++) {
        now = 100 + k * 0.01;
        cg_progress_update(&p, k);
    }
    cg_progress_end(&p);
    const char *out = read_back(f);
    assert_null(strchr(out, '\r'));
    /* 20% when the delay passed (2 s), then 30% .. 100%: 9 lines. */
    assert_int_equal(count_lines(out), 9);
    assert_non_null(strstr(out, "conegraph: tracing: 20%, 2.0 s, about 8.0 s left\n"));
    assert_non_null(strstr(out, "conegraph: tracing: 50%, 5.0 s, about 5.0 s left\n"));
    assert_non_null(strstr(out, "conegraph: tracing: 100%, 10.0 s\n"));
    assert_null(strstr(out, "tracing: 10%"));
    fclose(f);
}

static void
few_units_a_line_each(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    double now = 0;
    cg_progress p;
    cg_progress_begin(&p, &(cg_progress_desc){ .what = "rendering", .total = 3, .unit = "frames", .out = f,
                                               .terminal = -1, .delay_s = 2, .clock = fake_clock, .clock_user = &now });
    for (int k = 1; k <= 3; k++) {
        now = 4.0 * k;
        cg_progress_update(&p, k);
    }
    cg_progress_end(&p);
    const char *out = read_back(f);
    assert_int_equal(count_lines(out), 3);
    assert_non_null(strstr(out, "conegraph: rendering: 33% (1/3 frames), 4.0 s, about 8.0 s left\n"));
    assert_non_null(strstr(out, "conegraph: rendering: 100% (3/3 frames), 12.0 s\n"));
    fclose(f);
}

static void
short_work_is_silent(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    double now = 0;
    cg_progress p;
    cg_progress_begin(&p, &(cg_progress_desc){ .what = "loading", .total = 10, .out = f, .terminal = -1,
                                               .delay_s = 2, .clock = fake_clock, .clock_user = &now });
    for (int k = 1; k <= 10; k++) {
        now = 0.1 * k;
        cg_progress_update(&p, k);
    }
    cg_progress_end(&p);
    assert_string_equal(read_back(f), "");
    fclose(f);
}

static void
on_a_terminal_one_line(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    double now = 0;
    cg_progress p;
    cg_progress_begin(&p, &(cg_progress_desc){ .what = "tracing", .total = 100, .out = f, .terminal = 1,
                                               .delay_s = -1, .clock = fake_clock, .clock_user = &now });
    for (int k = 1; k <= 100; k++) {
        now = 0.06 * k; /* more often than the line is redrawn (every 0.1 s) */
        cg_progress_update(&p, k);
    }
    cg_progress_end(&p);
    const char *out = read_back(f);
    assert_int_equal(count_lines(out), 1); /* the newline of cg_progress_end alone */
    int redraws = 0;
    for (const char *c = out; *c; c++)
        redraws += *c == '\r';
    assert_true(redraws >= 45 && redraws <= 52);
    assert_non_null(strstr(out, "\rconegraph: tracing: 100%, 6.0 s\033[K\n"));
    fclose(f);
}

static void
quiet_prints_nothing(void **state)
{
    (void)state;
    FILE *f = tmpfile();
    double now = 0;
    cg_log_level level = cg_log_get_level();
    cg_log_set_level(CG_LOG_ERROR);
    cg_progress p;
    cg_progress_begin(&p, &(cg_progress_desc){ .what = "tracing", .total = 10, .out = f, .terminal = -1,
                                               .delay_s = -1, .clock = fake_clock, .clock_user = &now });
    for (int k = 1; k <= 10; k++) {
        now = 10.0 * k;
        cg_progress_update(&p, k);
    }
    cg_progress_end(&p);
    cg_log_set_level(level);
    assert_string_equal(read_back(f), "");
    fclose(f);
}

static void
delay_from_the_environment(void **state)
{
    (void)state;
    setenv("CONEGRAPH_PROGRESS_DELAY", "0", 1);
    assert_float_equal(cg_progress_delay(), 0, 0);
    setenv("CONEGRAPH_PROGRESS_DELAY", "0.5", 1);
    assert_float_equal(cg_progress_delay(), 0.5, 0);
    setenv("CONEGRAPH_PROGRESS_DELAY", "soon", 1);
    assert_float_equal(cg_progress_delay(), CG_PROGRESS_DELAY_S, 0);
    unsetenv("CONEGRAPH_PROGRESS_DELAY");
    assert_float_equal(cg_progress_delay(), CG_PROGRESS_DELAY_S, 0);
}

/* Progress is info-level output: the tests' CONEGRAPH_LOG=warn would hide it. */
static int
log_info(void **state)
{
    (void)state;
    cg_log_set_level(CG_LOG_INFO);
    return 0;
}

CG_TEST_MAIN(log_info, NULL,
             cmocka_unit_test(into_a_file_tenths_and_no_carriage_return),
             cmocka_unit_test(few_units_a_line_each),
             cmocka_unit_test(short_work_is_silent),
             cmocka_unit_test(on_a_terminal_one_line),
             cmocka_unit_test(quiet_prints_nothing),
             cmocka_unit_test(delay_from_the_environment))
