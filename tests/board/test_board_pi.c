/* The pi board's glue, on a machine without the box's hardware: with a
 * button script it needs no GPIO (replays on the box, tests); without one
 * it must name the GPIO chip it could not open rather than run buttonless. */
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

#include "cub/board.h"

static void test_script_replaces_gpio(void **state)
{
    char path[] = "/tmp/cub_pi_script_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    assert_int_equal(write(fd, "0 start\n", 8), 8);
    close(fd);
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_EMPTY,
                           .button_script = path};
    cub_board *b;
    char err[256];
    cub_err e = cub_board_open(&desc, &b, err, sizeof err);
    unlink(path);
    if (e) {
        fail_msg("pi board open with a script: %s: %s", cub_err_str(e), err);
    }
    assert_string_equal(cub_board_name(), "pi");
    cub_loop_desc ld = {0};
    size_t size = cub_loop_mem_size(&ld);
    void *mem = malloc(size);
    cub_loop loop;
    assert_int_equal(cub_loop_init(&loop, &ld, mem, size), CUB_OK);
    cub_board_poll_buttons(b, &loop, cub_board_now_us(b));
    cub_event ev;
    assert_int_equal(cub_queue_pop(&loop.queue, &ev), CUB_OK);
    assert_int_equal(ev.type, CUB_EV_BUTTON_DOWN);
    assert_int_equal(ev.a, CUB_BUTTON_START);
    free(mem);
    cub_board_close(b);
}

static void test_gpio_errors_are_named(void **state)
{
    cub_board_desc desc = {.display = CUB_DISPLAY_NONE, .depth = CUB_DEPTH_OFF};
    cub_board *b = (cub_board *)1;
    char err[256];
    if (access("/dev/gpiochip0", F_OK) == 0) {
        printf("pi: /dev/gpiochip0 exists here; not checking the missing-chip message\n");
        return;
    }
    /* built-in defaults: gpiochip0 */
    assert_int_equal(cub_board_open(&desc, &b, err, sizeof err), CUB_ERR_DEVICE);
    printf("pi: no GPIO here: %s\n", err);
    assert_non_null(strstr(err, "\"gpiochip0\""));
    assert_null(b);
    /* The config's chip reaches the board, named with the file. */
    cub_boxconf box;
    const char *text = "chip=gpiochip5\n";
    assert_int_equal(cub_boxconf_parse(text, strlen(text), "my.conf", &box, err, sizeof err),
                     CUB_OK);
    desc.gpio = &box.gpio;
    assert_int_equal(cub_board_open(&desc, &b, err, sizeof err), CUB_ERR_DEVICE);
    assert_non_null(strstr(err, "my.conf: cannot open GPIO chip \"gpiochip5\""));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_script_replaces_gpio),
        cmocka_unit_test(test_gpio_errors_are_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
