/* xml — a small C API over tinyxml2, for the project's XML files (the
 * character, the bridge tags). The one C++ file is app/io/xml_shim.cpp;
 * nothing here throws, and every failure is a cub_err plus, where a file is
 * involved, a cub_diag naming the file and the line.
 *
 * Reading:
 *   cub_xml_doc *doc;
 *   if (cub_xml_load("bear.xml", &doc, &diag)) ...        // diag: file:line: what
 *   cub_xml_el *root = cub_xml_root(doc);                  // <character>
 *   for (cub_xml_el *j = cub_xml_child(skel, "joint"); j; j = cub_xml_next(j, "joint"))
 *       name = cub_xml_attr(j, "name");                    // NULL when absent
 *   cub_xml_attr_double(el, "radius", &r)                  // OK, EMPTY (absent), FORMAT
 *   cub_xml_fail(el, &diag, "radius %g is not positive", r) // "bear.xml:40: radius ..."
 *
 * Writing (deterministic: the same calls always give the same bytes):
 *   cub_xml_doc *doc = cub_xml_new("tags");                // declaration + <tags>
 *   cub_xml_el *t = cub_xml_add(cub_xml_root(doc), "tag");
 *   cub_xml_set(t, "clip", "clap");
 *   cub_xml_set_int(t, "frame", 17);
 *   cub_xml_set_double(t, "d", 0.2143, 3);                 // d="0.214"
 *   cub_xml_save(doc, "tags.xml", &diag);
 *   cub_xml_free(doc);
 *
 * Output format: UTF-8, the declaration <?xml version="1.0" encoding="UTF-8"?>,
 * one element per line indented by 4 spaces per level, attributes in the order
 * they were first set, "\n" line ends, a final newline. Numbers are printed
 * by cub_xml_format_double: fixed decimals, trailing zeros dropped, never
 * "-0", never exponent notation, independent of the C locale.
 *
 * Elements (cub_xml_el) belong to their document: they stay valid until
 * cub_xml_free(doc). Strings returned are owned by the document too.
 */
#ifndef CUB_XML_H
#define CUB_XML_H

#include <stddef.h>

#include "cub/err.h"
#include "cub/io.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct cub_xml_doc cub_xml_doc; /* opaque */
typedef struct cub_xml_el cub_xml_el;   /* opaque, borrowed from its document */

/* ---- documents ---------------------------------------------------------- */

/* Parse len bytes of XML (need not be NUL-terminated). name is the file name
 * diagnostics use. On failure *out is NULL and diag says where and what:
 * "tags.xml:7: XML: the element that starts here has a missing or mismatched end tag". */
cub_err cub_xml_parse(const char *text, size_t len, const char *name, cub_xml_doc **out,
                      cub_diag *diag);
/* Read and parse a file (the name in diagnostics is path). */
cub_err cub_xml_load(const char *path, cub_xml_doc **out, cub_diag *diag);
/* A new document holding the declaration and an empty root element; NULL
 * on a bad root name or out of memory. */
cub_xml_doc *cub_xml_new(const char *root_name);
/* Free the document and everything in it; NULL is fine. */
void cub_xml_free(cub_xml_doc *doc);
/* The document's name for diagnostics ("(new)" for cub_xml_new). */
const char *cub_xml_doc_name(const cub_xml_doc *doc);
/* The root element, NULL if there is none. */
cub_xml_el *cub_xml_root(const cub_xml_doc *doc);

/* ---- walking ------------------------------------------------------------ */

/* First child element with this name (NULL name: any element), or NULL. */
cub_xml_el *cub_xml_child(const cub_xml_el *el, const char *name);
/* Next sibling element with this name (NULL name: any element), or NULL. */
cub_xml_el *cub_xml_next(const cub_xml_el *el, const char *name);
/* The element's tag name ("" for NULL). */
const char *cub_xml_name(const cub_xml_el *el);
/* The line the element starts on in the parsed text (1-based; 0 for
 * elements made by cub_xml_add). */
int cub_xml_line(const cub_xml_el *el);
/* The element's text content (<a>text</a>), or NULL when it has none. */
const char *cub_xml_text(const cub_xml_el *el);

/* ---- reading attributes ------------------------------------------------- */

/* 1 if the element has the attribute. */
int cub_xml_has(const cub_xml_el *el, const char *attr);
/* The attribute's value, or NULL when absent. */
const char *cub_xml_attr(const cub_xml_el *el, const char *attr);
/* The i-th attribute's name (in document order), NULL past the last. */
const char *cub_xml_attr_name_at(const cub_xml_el *el, int i);
/* The first attribute whose name is not in known (NULL-terminated list),
 * or NULL when all are known. Catches typos such as raduis="3". */
const char *cub_xml_unknown_attr(const cub_xml_el *el, const char *const *known);
/* Numbers, strictly: optional blanks around one plain decimal number
 * ("-1.5", "2e3"; no "nan", "inf", hex or trailing junk). Return CUB_OK,
 * CUB_ERR_EMPTY when the attribute is absent, CUB_ERR_FORMAT when it is
 * not such a number (doubles must be finite; ints must fit an int). */
cub_err cub_xml_attr_double(const cub_xml_el *el, const char *attr, double *out);
cub_err cub_xml_attr_int(const cub_xml_el *el, const char *attr, int *out);
/* A required whole-number attribute in [lo, hi]; otherwise CUB_ERR_FORMAT
 * with diag saying what is wrong at the attribute's line (missing, not a
 * whole number, out of range). */
cub_err cub_xml_get_int(const cub_xml_el *el, const char *attr, int lo, int hi, int *out,
                        cub_diag *diag);
/* A blank-separated list of exactly n doubles ("0 285 0"). CUB_ERR_EMPTY
 * when absent, CUB_ERR_FORMAT when a value is bad or the count is not n. */
cub_err cub_xml_attr_doubles(const cub_xml_el *el, const char *attr, double *out, int n);

/* The line the attribute is on (elements may span lines), or the
 * element's line when the attribute is absent. */
int cub_xml_attr_line(const cub_xml_el *el, const char *attr);

/* Fill diag with the element's document name and line and the message;
 * returns CUB_ERR_FORMAT, so parsers can `return cub_xml_fail(...)`. */
cub_err cub_xml_fail(const cub_xml_el *el, cub_diag *diag, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* The same at the line of the attribute attr (cub_xml_attr_line). */
cub_err cub_xml_fail_attr(const cub_xml_el *el, const char *attr, cub_diag *diag, const char *fmt,
                          ...) __attribute__((format(printf, 4, 5)));

/* ---- writing ------------------------------------------------------------ */

/* Append a new child element; NULL on a bad name (not [A-Za-z_][A-Za-z0-9_.-]*)
 * or out of memory. */
cub_xml_el *cub_xml_add(cub_xml_el *parent, const char *name);
/* Append a comment (<!-- text -->) as the element's next child; the text
 * must not contain "--". */
cub_err cub_xml_add_comment(cub_xml_el *parent, const char *text);
/* Set (or replace, keeping its place) an attribute. Values are escaped
 * (&, <, >, "), so any string round-trips. CUB_ERR_ARG on a bad name. */
cub_err cub_xml_set(cub_xml_el *el, const char *attr, const char *value);
cub_err cub_xml_set_int(cub_xml_el *el, const char *attr, long value);
/* value with at most `decimals` (0..9) decimals, see cub_xml_format_double;
 * CUB_ERR_ARG for a non-finite value. */
cub_err cub_xml_set_double(cub_xml_el *el, const char *attr, double value, int decimals);
/* n values, blank-separated, each as cub_xml_set_double prints it. */
cub_err cub_xml_set_doubles(cub_xml_el *el, const char *attr, const double *values, int n,
                            int decimals);
/* Replace the element's text content. */
cub_err cub_xml_set_text(cub_xml_el *el, const char *text);

/* The document as text (heap, NUL-terminated, free with free()). */
cub_err cub_xml_print(const cub_xml_doc *doc, char **out, size_t *out_len);
/* Write the document to a file (as cub_xml_print gives it). */
cub_err cub_xml_save(const cub_xml_doc *doc, const char *path, cub_diag *diag);

/* Format value rounded to `decimals` (0..9) decimals, trailing zeros and a
 * trailing '.' dropped, "-0" written as "0": 1.50 -> "1.5", -0.0001 at 3
 * decimals -> "0". Returns buf; "nan" for a non-finite value. */
const char *cub_xml_format_double(double value, int decimals, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
