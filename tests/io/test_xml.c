/* cub/xml.h, the C API over tinyxml2: parse errors carry the line, numbers
 * are read strictly, and writing gives the same bytes every time. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "cub/xml.h"

static cub_xml_doc *parse_ok(const char *text)
{
    cub_xml_doc *doc = NULL;
    cub_diag d = {0};
    cub_err err = cub_xml_parse(text, strlen(text), "t.xml", &doc, &d);
    if (err) print_error("unexpected failure: %s:%d: %s\n", d.file, d.line, d.msg);
    assert_int_equal(err, CUB_OK);
    assert_non_null(doc);
    return doc;
}

static void expect_parse_error(const char *text, int line, const char *words)
{
    cub_xml_doc *doc = (cub_xml_doc *)1;
    cub_diag d = {0};
    char buf[600];
    assert_int_equal(cub_xml_parse(text, strlen(text), "t.xml", &doc, &d), CUB_ERR_FORMAT);
    assert_null(doc);
    cub_diag_str(&d, buf, sizeof(buf));
    printf("xml: rejected: %s\n", buf);
    assert_string_equal(d.file, "t.xml");
    assert_int_equal(d.line, line);
    assert_non_null(strstr(d.msg, words));
}

static void test_parse_errors_name_the_line(void **state)
{
    (void)state;
    expect_parse_error("<a>\n  <b>\n  </c>\n</a>\n", 2, "mismatched end tag");
    expect_parse_error("<a>\n<!-- never closed\n</a>\n", 2, "comment");
    expect_parse_error("<a>\n\n  <b x=\"1\" y=2/>\n</a>", 3, "attribute");
    expect_parse_error("   \n  ", 0, "empty");
    expect_parse_error("<a>\n<b>\n", 2, "not closed");
    cub_xml_doc *doc = NULL;
    cub_diag d = {0};
    assert_int_equal(cub_xml_parse("", 0, "e.xml", &doc, &d), CUB_ERR_FORMAT);
    assert_int_equal(cub_xml_parse(NULL, 3, "e.xml", &doc, &d), CUB_ERR_ARG);
    assert_int_equal(cub_xml_load("/nonexistent/x.xml", &doc, &d), CUB_ERR_IO);
    assert_null(doc);
    assert_non_null(strstr(d.file, "x.xml"));
}

static void test_input_need_not_be_terminated(void **state)
{
    (void)state;
    /* The buffer runs on past len: only len bytes are read. */
    const char text[] = "<a v=\"1\"/><junk that is not xml";
    cub_xml_doc *doc = NULL;
    cub_diag d = {0};
    assert_int_equal(cub_xml_parse(text, 10, "n.xml", &doc, &d), CUB_OK);
    assert_string_equal(cub_xml_name(cub_xml_root(doc)), "a");
    cub_xml_free(doc);
}

static void test_numbers_are_read_strictly(void **state)
{
    (void)state;
    cub_xml_doc *doc = parse_ok("<a ok=\" -1.5e2 \" i=\"42\" big=\"99999999999\" nan=\"nan\" "
                                "inf=\"inf\" hex=\"0x10\" junk=\"12abc\" empty=\"\" "
                                "v3=\"0 285 -1.25\" v2=\"1 2\" v4=\"1 2 3 4\" f=\"2.5\"/>");
    cub_xml_el *a = cub_xml_root(doc);
    double x = 0, v[3] = {0};
    int i = 0;
    assert_int_equal(cub_xml_attr_double(a, "ok", &x), CUB_OK);
    assert_true(x == -150.0);
    assert_int_equal(cub_xml_attr_int(a, "i", &i), CUB_OK);
    assert_int_equal(i, 42);
    assert_int_equal(cub_xml_attr_int(a, "big", &i), CUB_ERR_FORMAT);
    assert_int_equal(cub_xml_attr_int(a, "f", &i), CUB_ERR_FORMAT);
    const char *bad[] = {"nan", "inf", "hex", "junk", "empty"};
    for (size_t k = 0; k < sizeof(bad) / sizeof(bad[0]); k++)
        assert_int_equal(cub_xml_attr_double(a, bad[k], &x), CUB_ERR_FORMAT);
    assert_int_equal(cub_xml_attr_double(a, "missing", &x), CUB_ERR_EMPTY);
    assert_int_equal(cub_xml_attr_doubles(a, "v3", v, 3), CUB_OK);
    assert_true(v[0] == 0 && v[1] == 285 && v[2] == -1.25);
    assert_int_equal(cub_xml_attr_doubles(a, "v2", v, 3), CUB_ERR_FORMAT);
    assert_int_equal(cub_xml_attr_doubles(a, "v4", v, 3), CUB_ERR_FORMAT);
    assert_int_equal(cub_xml_attr_doubles(a, "none", v, 3), CUB_ERR_EMPTY);
    cub_xml_free(doc);
}

static void test_walk_elements_and_lines(void **state)
{
    (void)state;
    cub_xml_doc *doc = parse_ok("<?xml version=\"1.0\"?>\n"
                                "<root>\n"
                                "  <joint name=\"a\"/>\n"
                                "  <other/>\n"
                                "  <joint name=\"b\"\n"
                                "         parent=\"a\"/>\n"
                                "  <note>hello &amp; bye</note>\n"
                                "</root>\n");
    cub_xml_el *root = cub_xml_root(doc);
    assert_string_equal(cub_xml_name(root), "root");
    assert_int_equal(cub_xml_line(root), 2);
    cub_xml_el *j = cub_xml_child(root, "joint");
    assert_string_equal(cub_xml_attr(j, "name"), "a");
    assert_int_equal(cub_xml_line(j), 3);
    assert_null(cub_xml_attr(j, "parent"));
    assert_false(cub_xml_has(j, "parent"));
    j = cub_xml_next(j, "joint");
    assert_string_equal(cub_xml_attr(j, "name"), "b");
    assert_int_equal(cub_xml_line(j), 5);
    assert_int_equal(cub_xml_attr_line(j, "parent"), 6);
    assert_int_equal(cub_xml_attr_line(j, "absent"), 5);
    assert_string_equal(cub_xml_attr_name_at(j, 1), "parent");
    assert_null(cub_xml_attr_name_at(j, 2));
    assert_null(cub_xml_next(j, "joint"));
    assert_string_equal(cub_xml_name(cub_xml_next(cub_xml_child(root, NULL), NULL)), "other");
    assert_string_equal(cub_xml_text(cub_xml_child(root, "note")), "hello & bye");
    assert_null(cub_xml_text(j));

    const char *known[] = {"name", NULL};
    assert_string_equal(cub_xml_unknown_attr(j, known), "parent");
    const char *both[] = {"name", "parent", NULL};
    assert_null(cub_xml_unknown_attr(j, both));

    cub_diag d = {0};
    assert_int_equal(cub_xml_fail_attr(j, "parent", &d, "parent '%s' is odd", "a"), CUB_ERR_FORMAT);
    assert_string_equal(d.file, "t.xml");
    assert_int_equal(d.line, 6);
    assert_string_equal(d.msg, "parent 'a' is odd");
    assert_int_equal(cub_xml_fail(root, &d, "x"), CUB_ERR_FORMAT);
    assert_int_equal(d.line, 2);
    cub_xml_free(doc);
}

static void test_format_double(void **state)
{
    (void)state;
    char b[48];
    assert_string_equal(cub_xml_format_double(1.5, 3, b, sizeof(b)), "1.5");
    assert_string_equal(cub_xml_format_double(2.0, 3, b, sizeof(b)), "2");
    assert_string_equal(cub_xml_format_double(-0.0001, 3, b, sizeof(b)), "0");
    assert_string_equal(cub_xml_format_double(-0.25, 1, b, sizeof(b)), "-0.3");
    assert_string_equal(cub_xml_format_double(0.2143, 3, b, sizeof(b)), "0.214");
    assert_string_equal(cub_xml_format_double(-12.0625, 4, b, sizeof(b)), "-12.0625");
    assert_string_equal(cub_xml_format_double(0.05, 2, b, sizeof(b)), "0.05");
    assert_string_equal(cub_xml_format_double(123456789.0, 0, b, sizeof(b)), "123456789");
    assert_string_equal(cub_xml_format_double(1e16, 3, b, sizeof(b)), "10000000000000000");
    assert_string_equal(cub_xml_format_double(INFINITY, 3, b, sizeof(b)), "nan");
}

static const char expected_doc[] =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<tags version=\"1\">\n"
    "    <!-- made by test_xml -->\n"
    "    <tag clip=\"cl&lt;a&gt;p &amp; &quot;go&quot;\" frame=\"17\" d=\"0.214\"/>\n"
    "    <tag clip=\"wave\" frame=\"-3\" d=\"0\" pos=\"1.5 -2 0.001\">some text</tag>\n"
    "</tags>\n";

static cub_xml_doc *build_doc(void)
{
    cub_xml_doc *doc = cub_xml_new("tags");
    assert_non_null(doc);
    cub_xml_el *root = cub_xml_root(doc);
    assert_int_equal(cub_xml_set_int(root, "version", 1), CUB_OK);
    assert_int_equal(cub_xml_add_comment(root, " made by test_xml "), CUB_OK);
    cub_xml_el *t = cub_xml_add(root, "tag");
    assert_int_equal(cub_xml_set(t, "clip", "x"), CUB_OK);
    assert_int_equal(cub_xml_set_int(t, "frame", 17), CUB_OK);
    assert_int_equal(cub_xml_set_double(t, "d", 0.2143, 3), CUB_OK);
    /* Replacing keeps the attribute's place. */
    assert_int_equal(cub_xml_set(t, "clip", "cl<a>p & \"go\""), CUB_OK);
    t = cub_xml_add(root, "tag");
    cub_xml_set(t, "clip", "wave");
    cub_xml_set_int(t, "frame", -3);
    cub_xml_set_double(t, "d", -0.0000001, 3);
    double pos[3] = {1.5, -2.0, 0.00104};
    assert_int_equal(cub_xml_set_doubles(t, "pos", pos, 3, 3), CUB_OK);
    assert_int_equal(cub_xml_set_text(t, "some text"), CUB_OK);
    return doc;
}

static void test_writing_is_exact_and_reproducible(void **state)
{
    (void)state;
    cub_xml_doc *doc = build_doc();
    char *text = NULL;
    size_t len = 0;
    assert_int_equal(cub_xml_print(doc, &text, &len), CUB_OK);
    assert_int_equal(len, strlen(expected_doc));
    assert_string_equal(text, expected_doc);

    /* Save, load, save again: the same bytes, the same values. */
    char path[512], path2[512];
    const char *dir = getenv("CUB_BUILD_DIR");
    snprintf(path, sizeof(path), "%s/test_xml_out.xml", dir ? dir : ".");
    snprintf(path2, sizeof(path2), "%s/test_xml_out2.xml", dir ? dir : ".");
    cub_diag d = {0};
    assert_int_equal(cub_xml_save(doc, path, &d), CUB_OK);
    cub_xml_doc *back = NULL;
    assert_int_equal(cub_xml_load(path, &back, &d), CUB_OK);
    cub_xml_el *t = cub_xml_child(cub_xml_root(back), "tag");
    assert_string_equal(cub_xml_attr(t, "clip"), "cl<a>p & \"go\"");
    assert_int_equal(cub_xml_save(back, path2, &d), CUB_OK);
    char *again = NULL;
    size_t again_len = 0;
    assert_int_equal(cub_xml_print(back, &again, &again_len), CUB_OK);
    assert_string_equal(again, expected_doc);
    printf("xml: wrote %zu bytes; save -> load -> save gives identical bytes\n", len);
    free(text);
    free(again);
    cub_xml_free(back);
    cub_xml_free(doc);
    remove(path);
    remove(path2);
}

static void test_writing_refuses_bad_names(void **state)
{
    (void)state;
    assert_null(cub_xml_new("not a name"));
    assert_null(cub_xml_new(""));
    cub_xml_doc *doc = cub_xml_new("r");
    cub_xml_el *root = cub_xml_root(doc);
    assert_null(cub_xml_add(root, "1abc"));
    assert_null(cub_xml_add(NULL, "a"));
    assert_int_equal(cub_xml_set(root, "a b", "x"), CUB_ERR_ARG);
    assert_int_equal(cub_xml_set(root, "a", NULL), CUB_ERR_ARG);
    assert_int_equal(cub_xml_set_double(root, "a", INFINITY, 3), CUB_ERR_ARG);
    assert_int_equal(cub_xml_set_double(root, "a", 1.0, 12), CUB_ERR_ARG);
    assert_int_equal(cub_xml_add_comment(root, "a -- b"), CUB_ERR_ARG);
    assert_int_equal(cub_xml_add_comment(root, "ends-"), CUB_ERR_ARG);
    cub_diag d = {0};
    assert_int_equal(cub_xml_save(doc, "/nonexistent/dir/x.xml", &d), CUB_ERR_IO);
    assert_non_null(strstr(d.msg, "cannot create"));
    cub_xml_free(doc);
    cub_xml_free(NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_parse_errors_name_the_line),
        cmocka_unit_test(test_input_need_not_be_terminated),
        cmocka_unit_test(test_numbers_are_read_strictly),
        cmocka_unit_test(test_walk_elements_and_lines),
        cmocka_unit_test(test_format_double),
        cmocka_unit_test(test_writing_is_exact_and_reproducible),
        cmocka_unit_test(test_writing_refuses_bad_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
