/* The tag file reader: a hand-written file against the hand-made library,
 * then one mutation per validation rule, each expected to fail with
 * CUB_ERR_FORMAT at the right line with a message naming the problem. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/tags.h"
#include "synth_lib.h"

/* Line numbers in the comments are the ones the cases below expect. */
static const char BASE[] =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"                           /* 1 */
    "<cubtags version=\"1\" library=\"synth.cubclips\" threshold=\"0.4\">\n" /* 2 */
    "    <weights RH=\"0.15\" RHE=\"0.15\" LH=\"0.15\" LHE=\"0.15\" Posture=\"0.15\" "
    "Trunk=\"0.1\" RF=\"0.0375\" RFK=\"0.0375\" LF=\"0.0375\" LFK=\"0.0375\"/>\n" /* 3 */
    "    <tagging class_share=\"0.02\" class_clips=\"3\" head_dps=\"90\" "
    "spacing_ms=\"200\" max_links=\"3\"/>\n"                       /* 4 */
    "    <clip name=\"arms_up\" frames=\"90\">\n"                  /* 5 */
    "        <bridge frame=\"0\" class=\"0x00000\"/>\n"            /* 6 */
    "        <bridge frame=\"60\" class=\"0x00001\"/>\n"           /* 7 */
    "    </clip>\n"                                                /* 8 */
    "    <clip name=\"right_wave\" frames=\"90\">\n"               /* 9 */
    "        <bridge frame=\"10\" class=\"0x00000\"/>\n"           /* 10 */
    "        <bridge frame=\"80\" class=\"0x00000\"/>\n"           /* 11 */
    "    </clip>\n"                                                /* 12 */
    "    <clip name=\"squat\" frames=\"90\"/>\n"                   /* 13 */
    "    <clip name=\"head_shake\" frames=\"90\"/>\n"              /* 14 */
    "    <clip name=\"idle\" frames=\"60\"/>\n"                    /* 15 */
    "    <links from=\"arms_up\" to=\"right_wave\">\n"             /* 16 */
    "        <link a=\"0\" b=\"10\" d=\"0.1\" half=\"front\"/>\n"  /* 17 */
    "        <link a=\"0\" b=\"80\" d=\"0.2\" half=\"back\"/>\n"   /* 18 */
    "        <link a=\"60\" b=\"10\" d=\"0.3\" half=\"front\"/>\n" /* 19 */
    "    </links>\n"                                               /* 20 */
    "</cubtags>\n";                                                /* 21 */

typedef struct bad_case {
    const char *from, *to; /* replace every occurrence */
    int line;              /* expected diag line */
    const char *msg;       /* expected in the message */
} bad_case;

static const bad_case CASES[] = {
    {"</links>", "</linkz>", 16, "XML"},
    {"cubtags", "tags", 2, "expected <cubtags>"},
    {"version=\"1\"", "version=\"2\"", 2, "version=2 is outside"},
    {"library=\"synth.cubclips\"", "library=\"\"", 2, "needs library"},
    {"threshold=\"0.4\"", "threshold=\"nan\"", 2, "threshold=\"nan\" is not a number"},
    {"threshold=\"0.4\"", "threshold=\"1.5\"", 2, "threshold=1.5 is outside"},
    {"threshold=\"0.4\"", "threshold=\"0\"", 2, "would link nothing"},
    {"threshold=\"0.4\"", "", 2, "needs threshold"},
    {" RH=\"0.15\"", " RH=\"x\"", 3, "RH=\"x\" is not a number"},
    {" RH=\"0.15\"", " RH=\"0.5\"", 3, "sum to 1.35"},
    {" RH=\"0.15\"", "", 3, "needs RH"},
    {"Trunk=\"0.1\"", "Trunk=\"0.1\" Neck=\"0\"", 3, "unknown attribute 'Neck'"},
    {"max_links=\"3\"", "max_links=\"0\"", 4, "max_links=0"},
    {"head_dps=\"90\"", "head_dps=\"-5\"", 4, "head_dps=-5 is outside"},
    {"class_clips=\"3\"", "class_clips=\"three\"", 4, "not a whole number"},
    {"<clip name=\"squat\"", "<clip name=\"salsa\"", 13, "no clip 'salsa'"},
    {"frames=\"60\"", "frames=\"61\"", 15, "has 60 frames in the library, not 61"},
    {"    <clip name=\"idle\" frames=\"60\"/>\n", "", 2, "clip 'idle' is not tagged"},
    {"<clip name=\"squat\"", "<clip name=\"arms_up\"", 13, "tagged twice"},
    {"<clip name=\"squat\" frames=\"90\"/>", "<clip name=\"squat\"/>", 13, "needs frames"},
    {"frame=\"60\" class", "frame=\"90\" class", 7, "frame=90 is outside [0, 89]"},
    {"frame=\"60\" class", "frame=\"0\" class", 7, "must ascend"},
    {"class=\"0x00001\"", "class=\"0x100000\"", 7, "not a pose class"},
    {"class=\"0x00001\"", "class=\"12\"", 7, "not a pose class"},
    {"class=\"0x00001\"", "class=\"0xg\"", 7, "not a pose class"},
    {"<bridge frame=\"0\"", "<bridgee frame=\"0\"", 6, "unexpected <bridgee>"},
    {"<clip name=\"squat\"", "<extra/><clip name=\"squat\"", 13, "unknown element <extra>"},
    {"    <tagging", "    <weights RH=\"1\"/><tagging", 4, "<weights> appears twice"},
    {"    <weights", "    <weightz", 3, "unknown element <weightz>"},
    {"to=\"right_wave\"", "to=\"nope\"", 16, "no clip 'nope'"},
    {"to=\"right_wave\"", "", 16, "needs from"},
    {"<link a=\"0\" b=\"10\"", "<link a=\"5\" b=\"10\"", 17,
     "a=5 is not a bridge frame of clip 'arms_up'"},
    {"b=\"80\"", "b=\"81\"", 18, "b=81 is not a bridge frame of clip 'right_wave'"},
    {"b=\"80\"", "b=\"95\"", 18, "b=95 is outside [0, 89]"},
    {"d=\"0.2\"", "d=\"0.45\"", 18, "not below the threshold"},
    {"d=\"0.2\"", "d=\"-0.1\"", 18, "d=-0.1 is outside"},
    {"d=\"0.2\"", "d=\"inf\"", 18, "d=\"inf\" is not a number"},
    {"d=\"0.2\" half=\"back\"", "d=\"0.2\" half=\"front\"", 18, "lies in the back half"},
    {"d=\"0.2\" half=\"back\"", "d=\"0.2\" half=\"middle\"", 18, "half=\"front\" or"},
    {"d=\"0.3\"", "d=\"0.3\" x=\"1\"", 19, "unknown attribute 'x'"},
    {"a=\"60\" b=\"10\"", "a=\"0\" b=\"10\"", 19, "links must come by a"},
    {"max_links=\"3\"", "max_links=\"1\"", -1, ""}, /* still valid: one per half */
    {"    </links>\n",
     "    </links>\n    <links from=\"arms_up\" to=\"right_wave\">"
     "<link a=\"0\" b=\"10\" d=\"0.1\" half=\"front\"/></links>\n",
     21, "listed twice"},
    {"    </links>\n", "    </links>\n    <links from=\"idle\" to=\"squat\"/>\n", 21,
     "holds no <link>"},
    {"<link a=\"0\" b=\"10\"", "<lnk a=\"0\" b=\"10\"", 17, "unexpected <lnk>"},
};

static char *replace_all(const char *text, const char *from, const char *to)
{
    size_t nf = strlen(from), nt = strlen(to), n = strlen(text);
    char *out = malloc(n * 4 + nt * 8 + 1), *o = out;
    for (const char *p = text; *p;) {
        if (strncmp(p, from, nf) == 0) {
            memcpy(o, to, nt);
            o += nt;
            p += nf;
        } else {
            *o++ = *p++;
        }
    }
    *o = '\0';
    return out;
}

static cub_library g_lib;
static cub_character g_bear;

static int setup(void **state)
{
    (void)state;
    return synth_library(&g_bear, &g_lib);
}

static int teardown(void **state)
{
    (void)state;
    synth_library_free(&g_lib);
    return 0;
}

static void test_reader_rejects_bad_arguments(void **state)
{
    (void)state;
    cub_tags t;
    cub_diag d;
    assert_int_equal(cub_tags_parse(NULL, 0, "x", &g_lib, &t, &d), CUB_ERR_ARG);
    assert_int_equal(cub_tags_parse(BASE, sizeof BASE - 1, "x", NULL, &t, &d), CUB_ERR_ARG);
    assert_int_equal(cub_tags_read("/nonexistent/tags.xml", &g_lib, &t, &d), CUB_ERR_IO);
    assert_non_null(strstr(d.file, "/nonexistent/tags.xml"));
    assert_int_equal(cub_tags_parse("", 0, "empty.xml", &g_lib, &t, &d), CUB_ERR_FORMAT);
    assert_string_equal(d.file, "empty.xml");
    assert_true(d.msg[0] != '\0');
    assert_int_equal(cub_tags_print(NULL, NULL, NULL), CUB_ERR_ARG);
    cub_tags_free(NULL);
}

static void test_hand_written_file_reads(void **state)
{
    (void)state;
    cub_tags t;
    cub_diag d = {0};
    cub_err e = cub_tags_parse(BASE, sizeof BASE - 1, "base.xml", &g_lib, &t, &d);
    if (e) fail_msg("%s:%d: %s", d.file, d.line, d.msg);
    assert_string_equal(t.library, "synth.cubclips");
    assert_int_equal(t.params.fuzzy.threshold, 26214);
    assert_int_equal(t.params.max_links, 3);
    assert_int_equal(t.clip_count, SYNTH_CLIPS);
    assert_int_equal(t.clips[SYNTH_ARMS_UP].bridge_count, 2);
    assert_int_equal(t.clips[SYNTH_ARMS_UP].bridges[1].frame, 60);
    assert_int_equal(t.clips[SYNTH_ARMS_UP].bridges[1].crisp_class, 1);
    assert_int_equal(t.clips[SYNTH_IDLE].bridge_count, 0);
    const cub_tag_pair *p = &t.pairs[SYNTH_ARMS_UP * SYNTH_CLIPS + SYNTH_RIGHT_WAVE];
    assert_int_equal(p->link_count, 3);
    assert_int_equal(p->links[1].b, 80);
    assert_int_equal(p->links[1].half, CUB_TAG_BACK);
    assert_int_equal(p->links[1].d, 13107); /* 0.2 */
    assert_int_equal(t.pairs[SYNTH_RIGHT_WAVE * SYNTH_CLIPS + SYNTH_ARMS_UP].link_count, 0);
    cub_tags_free(&t);
}

static void test_every_validation_error_names_file_and_line(void **state)
{
    (void)state;
    int checked = 0;
    for (size_t i = 0; i < sizeof CASES / sizeof *CASES; i++) {
        const bad_case *c = &CASES[i];
        char *text = replace_all(BASE, c->from, c->to);
        assert_string_not_equal(text, BASE);
        cub_tags t;
        cub_diag d = {0};
        cub_err e = cub_tags_parse(text, strlen(text), "bad.tags.xml", &g_lib, &t, &d);
        char buf[600];
        free(text);
        if (c->line < 0) {
            if (e) fail_msg("case %zu should read: %s", i, cub_diag_str(&d, buf, sizeof buf));
            cub_tags_free(&t);
        } else {
            if (e != CUB_ERR_FORMAT)
                fail_msg("case %zu (%s -> %s): got %s, expected format", i, c->from, c->to,
                         cub_err_str(e));
            cub_diag_str(&d, buf, sizeof buf);
            if (d.line != c->line || !strstr(d.msg, c->msg) || strcmp(d.file, "bad.tags.xml"))
                fail_msg("case %zu (%s -> %s): got \"%s\", expected line %d and \"%s\"", i, c->from,
                         c->to, buf, c->line, c->msg);
            assert_null(t.clips); /* nothing leaks on failure */
            checked++;
        }
    }
    printf("tag: %d bad tag files rejected, each with file:line and the problem\n", checked);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_reader_rejects_bad_arguments),
        cmocka_unit_test(test_hand_written_file_reads),
        cmocka_unit_test(test_every_validation_error_names_file_and_line),
    };
    return cmocka_run_group_tests_name("tags_xml", tests, setup, teardown);
}
