/* GPIO buttons through their seam. These build machines have no GPIO kernel
 * support (no /dev/gpiochip*), so a fake chip stands in for libgpiod: the
 * test sets line levels and the time, the debouncer and the config parser
 * are the real code the box runs. */
#define _POSIX_C_SOURCE 200809L

#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "gpio.h"

/* ---- the fake chip ----------------------------------------------------- */

#define FAKE_LINES 4

typedef struct fake_gpio {
    const char *chip_name;
    const char *names[FAKE_LINES];
    int level[FAKE_LINES];      /* what get_value returns */
    int requested[FAKE_LINES];
    int output[FAKE_LINES];     /* requested as an output */
    cub_gpio_bias bias[FAKE_LINES];
    int chip_open, fail_request, fail_output, fail_reads;
} fake_gpio;

static fake_gpio fake;

static void *f_open_chip(void *ctx, const char *name)
{
    fake_gpio *f = ctx;
    if (strcmp(name, f->chip_name) != 0) {
        return NULL;
    }
    f->chip_open++;
    return f;
}

static void *f_find_line(void *ctx, void *chip, const char *name)
{
    fake_gpio *f = ctx;
    for (int i = 0; i < FAKE_LINES; i++) {
        if (strcmp(f->names[i], name) == 0) {
            return &f->level[i];
        }
    }
    return NULL;
}

static int index_of(fake_gpio *f, void *line)
{
    return (int)((int *)line - f->level);
}

static int f_request_input(void *ctx, void *line, const char *consumer, cub_gpio_bias bias)
{
    fake_gpio *f = ctx;
    if (f->fail_request) {
        return -1;
    }
    f->requested[index_of(f, line)]++;
    f->bias[index_of(f, line)] = bias;
    return 0;
}

static int f_get_value(void *ctx, void *line)
{
    fake_gpio *f = ctx;
    return f->fail_reads ? -1 : *(int *)line;
}

static int f_request_output(void *ctx, void *line, const char *consumer, int value)
{
    fake_gpio *f = ctx;
    if (f->fail_output) {
        return -1;
    }
    f->requested[index_of(f, line)]++;
    f->output[index_of(f, line)] = 1;
    *(int *)line = value;
    return 0;
}

static int f_set_value(void *ctx, void *line, int value)
{
    fake_gpio *f = ctx;
    assert_true(f->output[index_of(f, line)]); /* only outputs are driven */
    *(int *)line = value;
    return 0;
}

static void f_release(void *ctx, void *line)
{
    fake_gpio *f = ctx;
    f->requested[index_of(f, line)]--;
}

static void f_close_chip(void *ctx, void *chip)
{
    fake_gpio *f = ctx;
    f->chip_open--;
}

static const cub_gpio_ops fake_ops = {
    &fake,        f_open_chip,      f_find_line, f_request_input, f_get_value,
    f_request_output, f_set_value, f_release,   f_close_chip,
};

enum { L17, L27, L22, L23 };

static int setup(void **state)
{
    fake = (fake_gpio){.chip_name = "gpiochip0", .names = {"GPIO17", "GPIO27", "GPIO22", "GPIO23"}};
    /* Active low with pull-ups: released lines read 1. */
    for (int i = 0; i < FAKE_LINES; i++) {
        fake.level[i] = 1;
    }
    return 0;
}

static cub_gpio_buttons *open_default(int64_t now_us)
{
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    cub_gpio_buttons *b;
    char err[256];
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, now_us, &b, err, sizeof err), CUB_OK);
    return b;
}

/* Poll every step_us from t0 to t1 (exclusive); collect edges. */
static int run(cub_gpio_buttons *b, int64_t t0, int64_t t1, int64_t step_us, cub_event *edges,
               int max)
{
    int n = 0;
    for (int64_t t = t0; t < t1; t += step_us) {
        cub_event ev[CUB_BUTTON_COUNT];
        int k = cub_gpio_buttons_update(b, t, ev);
        for (int i = 0; i < k; i++) {
            assert_true(n < max);
            edges[n++] = ev[i];
        }
    }
    return n;
}

/* ---- opening ----------------------------------------------------------- */

static void test_missing_line_names_line_and_config_file(void **state)
{
    const char *text = "start_line=GPIO17\nstop_line=GPIO99\n";
    cub_boxconf box;
    char err[256];
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "/etc/cubdance/cubdance.conf", &box,
                                       err, sizeof err),
                     CUB_OK);
    cub_gpio_config cfg = box.gpio;
    cub_gpio_buttons *b = (cub_gpio_buttons *)1;
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, sizeof err),
                     CUB_ERR_DEVICE);
    printf("gpio open: %s\n", err);
    assert_null(b);
    assert_non_null(strstr(err, "/etc/cubdance/cubdance.conf:2: stop_line"));
    assert_non_null(strstr(err, "\"GPIO99\""));
    assert_non_null(strstr(err, "gpiochip0"));
    /* Nothing is left held. */
    assert_int_equal(fake.chip_open, 0);
    assert_int_equal(fake.requested[L17], 0);
}

static void test_missing_chip_and_busy_line(void **state)
{
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    snprintf(cfg.chip, sizeof cfg.chip, "gpiochip7");
    cub_gpio_buttons *b;
    char err[256];
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, sizeof err),
                     CUB_ERR_DEVICE);
    assert_non_null(strstr(err, "\"gpiochip7\""));
    assert_non_null(strstr(err, "built-in defaults"));
    cub_gpio_config_defaults(&cfg);
    fake.fail_request = 1;
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, sizeof err),
                     CUB_ERR_DEVICE);
    assert_non_null(strstr(err, "start_line"));
    assert_non_null(strstr(err, "as an input"));
    assert_int_equal(fake.chip_open, 0);
}

static void test_lines_requested_with_pull_and_released(void **state)
{
    cub_gpio_buttons *b = open_default(0);
    assert_int_equal(fake.chip_open, 1);
    assert_int_equal(fake.requested[L17], 1);
    assert_int_equal(fake.requested[L27], 1);
    assert_int_equal(fake.requested[L22], 0);
    assert_int_equal(fake.bias[L17], CUB_GPIO_BIAS_PULL_UP);
    cub_gpio_buttons_close(b);
    assert_int_equal(fake.chip_open, 0);
    assert_int_equal(fake.requested[L17], 0);
    assert_int_equal(fake.requested[L27], 0);
}

/* ---- the ready LED ---------------------------------------------------- */

static cub_gpio_buttons *open_with_led(int led_active_low, char *err, size_t err_size,
                                       cub_err want)
{
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    snprintf(cfg.line[CUB_BOXCONF_LINE_LED], CUB_BOXCONF_NAME_MAX, "GPIO22");
    cfg.led_active_low = led_active_low;
    cub_gpio_buttons *b = NULL;
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, err_size), want);
    return b;
}

static void test_led_lit_only_while_ready(void **state)
{
    char err[256];
    fake.level[L22] = 7; /* neither level: open must drive it */
    cub_gpio_buttons *b = open_with_led(0, err, sizeof err, CUB_OK);
    assert_true(fake.output[L22]);
    assert_int_equal(fake.requested[L22], 1);
    assert_int_equal(fake.level[L22], 0); /* dark until the app says ready */
    cub_gpio_buttons_set_ready(b, 1);
    assert_int_equal(fake.level[L22], 1);
    cub_gpio_buttons_set_ready(b, 0); /* dancing */
    assert_int_equal(fake.level[L22], 0);
    cub_gpio_buttons_set_ready(b, 1);
    /* Buttons still work with an LED beside them. */
    fake.level[L17] = 0;
    cub_event ev[CUB_BUTTON_COUNT];
    assert_int_equal(cub_gpio_buttons_update(b, 40000, ev), 0);
    assert_int_equal(cub_gpio_buttons_update(b, 80000, ev), 1);
    assert_int_equal(ev[0].type, CUB_EV_BUTTON_DOWN);
    cub_gpio_buttons_close(b); /* the program ends: dark, released */
    assert_int_equal(fake.level[L22], 0);
    assert_int_equal(fake.requested[L22], 0);
    assert_int_equal(fake.chip_open, 0);
    /* No LED configured: set_ready touches no line. */
    b = open_default(0);
    cub_gpio_buttons_set_ready(b, 1);
    assert_false(fake.output[L23]);
    cub_gpio_buttons_close(b);
}

static void test_led_active_low_and_errors(void **state)
{
    char err[256];
    cub_gpio_buttons *b = open_with_led(1, err, sizeof err, CUB_OK);
    assert_int_equal(fake.level[L22], 1); /* active low: high is dark */
    cub_gpio_buttons_set_ready(b, 1);
    assert_int_equal(fake.level[L22], 0);
    cub_gpio_buttons_close(b);
    assert_int_equal(fake.level[L22], 1);
    fake.fail_output = 1;
    assert_null(open_with_led(0, err, sizeof err, CUB_ERR_DEVICE));
    printf("gpio led: %s\n", err);
    assert_non_null(strstr(err, "led_line"));
    assert_non_null(strstr(err, "as an output"));
    assert_int_equal(fake.chip_open, 0);
    assert_int_equal(fake.requested[L17], 0);
    fake.fail_output = 0;
    cub_gpio_config cfg;
    cub_gpio_config_defaults(&cfg);
    snprintf(cfg.line[CUB_BOXCONF_LINE_LED], CUB_BOXCONF_NAME_MAX, "GPIO99");
    cfg.line_at[CUB_BOXCONF_LINE_LED] = 31;
    snprintf(cfg.file, sizeof cfg.file, "box.conf");
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, sizeof err),
                     CUB_ERR_DEVICE);
    assert_non_null(strstr(err, "box.conf:31: led_line: no GPIO line named \"GPIO99\""));
}

/* ---- debounce ---------------------------------------------------------- */

static void test_clean_press_gives_one_down_then_one_up(void **state)
{
    cub_gpio_buttons *b = open_default(0);
    cub_event e[8];
    int n = run(b, 0, 100000, 5000, e, 8);
    fake.level[L17] = 0; /* pressed at 100 ms ... */
    n += run(b, 100000, 300000, 5000, e + n, 8 - n);
    fake.level[L17] = 1; /* ... released at 300 ms */
    n += run(b, 300000, 500000, 5000, e + n, 8 - n);
    assert_int_equal(n, 2);
    assert_int_equal(e[0].type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(e[0].a, CUB_BUTTON_START);
    assert_int_equal(e[0].t_us, 100000); /* when the level was first seen */
    assert_int_equal(e[1].type, CUB_EV_BUTTON_UP);
    assert_int_equal(e[1].a, CUB_BUTTON_START);
    assert_int_equal(e[1].t_us, 300000);
    cub_gpio_buttons_close(b);
}

static void test_bounces_shorter_than_debounce_give_no_edge(void **state)
{
    cub_gpio_buttons *b = open_default(0);
    cub_event e[8];
    int n = 0;
    /* STOP chatters: low 20 ms, high 5 ms, for 400 ms (never 30 ms low). */
    for (int64_t t = 0; t < 400000; t += 5000) {
        fake.level[L27] = (t % 25000) < 20000 ? 0 : 1;
        n += run(b, t, t + 5000, 5000, e + n, 8 - n);
    }
    fake.level[L27] = 1;
    n += run(b, 400000, 600000, 5000, e + n, 8 - n);
    assert_int_equal(n, 0);
    cub_gpio_buttons_close(b);
}

static void test_bouncy_press_gives_one_edge_each_way(void **state)
{
    cub_gpio_buttons *b = open_default(0);
    cub_event e[8];
    int n = 0;
    /* Contact bounce for 15 ms on press and on release, solid in between. */
    int64_t t = 0;
    for (; t < 15000; t += 1000) {
        fake.level[L27] = (t / 1000) % 2;
        n += run(b, t, t + 1000, 1000, e + n, 8 - n);
    }
    fake.level[L27] = 0;
    n += run(b, t, 200000, 1000, e + n, 8 - n);
    for (t = 200000; t < 215000; t += 1000) {
        fake.level[L27] = 1 - (t / 1000) % 2;
        n += run(b, t, t + 1000, 1000, e + n, 8 - n);
    }
    fake.level[L27] = 1;
    n += run(b, t, 400000, 1000, e + n, 8 - n);
    assert_int_equal(n, 2);
    assert_int_equal(e[0].type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(e[0].a, CUB_BUTTON_STOP);
    assert_true(e[0].t_us >= 14000 && e[0].t_us <= 15000); /* the last bounce's end */
    assert_int_equal(e[1].type, CUB_EV_BUTTON_UP);
    assert_true(e[1].t_us >= 214000 && e[1].t_us <= 215000);
    cub_gpio_buttons_close(b);
}

static void test_held_at_start_gives_no_edge_until_released(void **state)
{
    fake.level[L17] = 0; /* held before the program started */
    cub_gpio_buttons *b = open_default(0);
    cub_event e[8];
    int n = run(b, 0, 200000, 5000, e, 8);
    assert_int_equal(n, 0);
    fake.level[L17] = 1;
    n = run(b, 200000, 300000, 5000, e, 8);
    assert_int_equal(n, 1);
    assert_int_equal(e[0].type, CUB_EV_BUTTON_UP);
    cub_gpio_buttons_close(b);
}

static void test_active_high_and_failed_reads(void **state)
{
    const char *text = "active_low=0\ndebounce_ms=0\n";
    cub_boxconf box;
    char err[256];
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "c.conf", &box, err, sizeof err),
                     CUB_OK);
    cub_gpio_config cfg = box.gpio;
    fake.level[L17] = fake.level[L27] = 0; /* released, pulled down */
    cub_gpio_buttons *b;
    assert_int_equal(cub_gpio_buttons_open(&cfg, &fake_ops, 0, &b, err, sizeof err), CUB_OK);
    assert_int_equal(fake.bias[L27], CUB_GPIO_BIAS_PULL_DOWN);
    cub_event e[2];
    fake.level[L27] = 1;
    fake.fail_reads = 1; /* a failed read changes nothing */
    assert_int_equal(cub_gpio_buttons_update(b, 1000, e), 0);
    fake.fail_reads = 0;
    assert_int_equal(cub_gpio_buttons_update(b, 2000, e), 1); /* debounce 0: at once */
    assert_int_equal(e[0].type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(e[0].a, CUB_BUTTON_STOP);
    cub_gpio_buttons_close(b);
}

static void test_poll_posts_edges_to_the_loop(void **state)
{
    cub_loop_desc desc = {0};
    size_t size = cub_loop_mem_size(&desc);
    void *mem = malloc(size);
    cub_loop loop;
    assert_int_equal(cub_loop_init(&loop, &desc, mem, size), CUB_OK);
    cub_gpio_buttons *b = open_default(0);
    fake.level[L17] = 0;
    fake.level[L27] = 0;
    cub_gpio_buttons_poll(b, &loop, 10000);
    cub_gpio_buttons_poll(b, &loop, 40000);
    cub_event ev;
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
    assert_int_equal(ev.type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(ev.a, CUB_BUTTON_START);
    assert_int_equal(ev.t_us, 10000);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
    assert_int_equal(ev.a, CUB_BUTTON_STOP);
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_ERR_EMPTY);
    cub_gpio_buttons_close(b);
    free(mem);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_led_lit_only_while_ready, setup),
        cmocka_unit_test_setup(test_led_active_low_and_errors, setup),
        cmocka_unit_test_setup(test_missing_line_names_line_and_config_file, setup),
        cmocka_unit_test_setup(test_missing_chip_and_busy_line, setup),
        cmocka_unit_test_setup(test_lines_requested_with_pull_and_released, setup),
        cmocka_unit_test_setup(test_clean_press_gives_one_down_then_one_up, setup),
        cmocka_unit_test_setup(test_bounces_shorter_than_debounce_give_no_edge, setup),
        cmocka_unit_test_setup(test_bouncy_press_gives_one_edge_each_way, setup),
        cmocka_unit_test_setup(test_held_at_start_gives_no_edge_until_released, setup),
        cmocka_unit_test_setup(test_active_high_and_failed_reads, setup),
        cmocka_unit_test_setup(test_poll_posts_edges_to_the_loop, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
