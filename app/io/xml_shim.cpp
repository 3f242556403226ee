// The C API of cub/xml.h over tinyxml2: the project's only C++. Every entry
// point catches everything (tinyxml2 allocates with new), so no exception
// ever reaches C code. Numbers are read and printed here, not by tinyxml2,
// to be strict on input and locale-independent and reproducible on output.
extern "C" {
#include "cub/io.h"
}
#include "cub/xml.h"

#include <tinyxml2.h>

#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

using tinyxml2::XMLAttribute;
using tinyxml2::XMLDocument;
using tinyxml2::XMLElement;
using tinyxml2::XMLNode;

// The document keeps its name for diagnostics; elements find it again
// through XMLNode::GetDocument (every document is made here).
struct cub_xml_doc : public XMLDocument {
    std::string name;
    cub_xml_doc() : XMLDocument(true, tinyxml2::PRESERVE_WHITESPACE) {}
};

namespace
{

XMLElement *to_el(const cub_xml_el *el)
{
    return reinterpret_cast<XMLElement *>(const_cast<cub_xml_el *>(el));
}

cub_xml_el *from_el(const XMLElement *el)
{
    return reinterpret_cast<cub_xml_el *>(const_cast<XMLElement *>(el));
}

const char *doc_name_of(const XMLElement *el)
{
    const cub_xml_doc *doc = static_cast<const cub_xml_doc *>(el->GetDocument());
    return doc ? doc->name.c_str() : "(xml)";
}

// tinyxml2's error names are for programmers; say it in words.
const char *parse_problem(tinyxml2::XMLError e)
{
    switch (e) {
    case tinyxml2::XML_ERROR_PARSING_ELEMENT: return "a malformed element tag";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE: return "a malformed attribute (name=\"value\")";
    case tinyxml2::XML_ERROR_PARSING_TEXT: return "malformed text";
    case tinyxml2::XML_ERROR_PARSING_CDATA: return "a malformed CDATA section";
    case tinyxml2::XML_ERROR_PARSING_COMMENT: return "a malformed or unclosed comment";
    case tinyxml2::XML_ERROR_PARSING_DECLARATION: return "a malformed <?xml ...?> declaration";
    case tinyxml2::XML_ERROR_PARSING_UNKNOWN: return "a malformed <! ...> section";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT: return "the document is empty";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
        return "the element that starts here has a missing or mismatched end tag";
    case tinyxml2::XML_ELEMENT_DEPTH_EXCEEDED: return "elements are nested too deeply";
    case tinyxml2::XML_ERROR_PARSING: return "malformed XML, or an element not closed";
    default: return "malformed XML";
    }
}

bool is_name_char(char c, bool first)
{
    bool alpha = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
    return alpha || (!first && ((c >= '0' && c <= '9') || c == '.' || c == '-'));
}

bool valid_name(const char *s)
{
    if (!s || !*s) return false;
    for (const char *p = s; *p; p++)
        if (!is_name_char(*p, p == s)) return false;
    return true;
}

bool is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// One plain decimal number in [s, e): digits, sign, '.', exponent only.
bool parse_number(const char *s, const char *e, double *out)
{
    char buf[64];
    size_t n = static_cast<size_t>(e - s);
    if (n == 0 || n >= sizeof(buf)) return false;
    for (size_t i = 0; i < n; i++) {
        char c = s[i];
        if (!((c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.' || c == 'e' || c == 'E'))
            return false;
    }
    std::memcpy(buf, s, n);
    buf[n] = '\0';
    // strtod honours the locale's decimal point; ours is always '.'. The
    // program never calls setlocale, so the "C" locale is in force.
    char *end = nullptr;
    errno = 0;
    double v = std::strtod(buf, &end);
    if (end != buf + n || !std::isfinite(v) || (errno == ERANGE && v != 0.0)) return false;
    *out = v;
    return true;
}

// Up to max numbers from a blank-separated list; returns how many, -1 if a
// token is not a number or there are more than max.
int parse_numbers(const char *s, double *out, int max)
{
    int count = 0;
    const char *p = s;
    for (;;) {
        while (*p && is_blank(*p))
            p++;
        if (!*p) return count;
        const char *start = p;
        while (*p && !is_blank(*p))
            p++;
        if (count == max || !parse_number(start, p, &out[count])) return -1;
        count++;
    }
}

cub_err set_attr(cub_xml_el *el, const char *attr, const char *value)
{
    if (!el || !valid_name(attr) || !value) return CUB_ERR_ARG;
    try {
        to_el(el)->SetAttribute(attr, value);
    } catch (...) {
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

} // namespace

extern "C" {

cub_err cub_xml_parse(const char *text, size_t len, const char *name, cub_xml_doc **out,
                      cub_diag *diag)
{
    const char *file = name ? name : "(memory)";
    if (!out) return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no output document");
    *out = nullptr;
    if (!text && len) return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no text");
    if (len == 0 || len == static_cast<size_t>(-1))
        return cub_diag_fail(diag, CUB_ERR_FORMAT, file, 0, "XML: the document is empty");
    cub_xml_doc *doc = nullptr;
    try {
        doc = new cub_xml_doc();
        doc->name = file;
        tinyxml2::XMLError e = doc->Parse(text, len);
        if (e != tinyxml2::XML_SUCCESS) {
            int line = doc->ErrorLineNum();
            delete doc;
            return cub_diag_fail(diag, CUB_ERR_FORMAT, file, line, "XML: %s", parse_problem(e));
        }
        if (!doc->RootElement()) {
            delete doc;
            return cub_diag_fail(diag, CUB_ERR_FORMAT, file, 0, "XML: no root element");
        }
    } catch (...) {
        delete doc;
        return cub_diag_fail(diag, CUB_ERR_NOMEM, file, 0, "out of memory reading XML");
    }
    *out = doc;
    return CUB_OK;
}

static cub_err parse_text(const cub_text *t, const void *, void *out)
{
    return cub_xml_parse(t->s, t->len, t->name, static_cast<cub_xml_doc **>(out), t->diag);
}

cub_err cub_xml_load(const char *path, cub_xml_doc **out, cub_diag *diag)
{
    if (out) *out = nullptr;
    cub_text_src src = {path, "XML file", CUB_TEXT_MAX_TAGS};
    return cub_text_load(&src, parse_text, NULL, out, diag);
}

cub_xml_doc *cub_xml_new(const char *root_name)
{
    if (!valid_name(root_name)) return nullptr;
    cub_xml_doc *doc = nullptr;
    try {
        doc = new cub_xml_doc();
        doc->name = "(new)";
        doc->InsertEndChild(doc->NewDeclaration());
        doc->InsertEndChild(doc->NewElement(root_name));
    } catch (...) {
        delete doc;
        return nullptr;
    }
    return doc;
}

void cub_xml_free(cub_xml_doc *doc)
{
    delete doc;
}

const char *cub_xml_doc_name(const cub_xml_doc *doc)
{
    return doc ? doc->name.c_str() : "";
}

cub_xml_el *cub_xml_root(const cub_xml_doc *doc)
{
    return doc ? from_el(doc->RootElement()) : nullptr;
}

cub_xml_el *cub_xml_child(const cub_xml_el *el, const char *name)
{
    return el ? from_el(to_el(el)->FirstChildElement(name)) : nullptr;
}

cub_xml_el *cub_xml_next(const cub_xml_el *el, const char *name)
{
    return el ? from_el(to_el(el)->NextSiblingElement(name)) : nullptr;
}

const char *cub_xml_name(const cub_xml_el *el)
{
    return el ? to_el(el)->Name() : "";
}

int cub_xml_line(const cub_xml_el *el)
{
    return el ? to_el(el)->GetLineNum() : 0;
}

const char *cub_xml_text(const cub_xml_el *el)
{
    return el ? to_el(el)->GetText() : nullptr;
}

int cub_xml_has(const cub_xml_el *el, const char *attr)
{
    return cub_xml_attr(el, attr) != nullptr;
}

const char *cub_xml_attr(const cub_xml_el *el, const char *attr)
{
    return (el && attr) ? to_el(el)->Attribute(attr) : nullptr;
}

const char *cub_xml_attr_name_at(const cub_xml_el *el, int i)
{
    if (!el || i < 0) return nullptr;
    const XMLAttribute *a = to_el(el)->FirstAttribute();
    for (; a && i > 0; i--)
        a = a->Next();
    return a ? a->Name() : nullptr;
}

const char *cub_xml_unknown_attr(const cub_xml_el *el, const char *const *known)
{
    for (const XMLAttribute *a = el ? to_el(el)->FirstAttribute() : nullptr; a; a = a->Next()) {
        bool found = false;
        for (int k = 0; known && known[k] && !found; k++)
            found = std::strcmp(known[k], a->Name()) == 0;
        if (!found) return a->Name();
    }
    return nullptr;
}

cub_err cub_xml_get_int(const cub_xml_el *el, const char *attr, int lo, int hi, int *out,
                        cub_diag *diag)
{
    cub_err e = cub_xml_attr_int(el, attr, out);
    if (e == CUB_ERR_EMPTY)
        return cub_xml_fail(el, diag, "<%s> needs %s=\"...\"", cub_xml_name(el), attr);
    if (e)
        return cub_xml_fail_attr(el, attr, diag, "%s=\"%s\" is not a whole number", attr,
                                 cub_xml_attr(el, attr));
    if (*out < lo || *out > hi)
        return cub_xml_fail_attr(el, attr, diag, "%s=%d is outside [%d, %d]", attr, *out, lo, hi);
    return CUB_OK;
}

cub_err cub_xml_attr_double(const cub_xml_el *el, const char *attr, double *out)
{
    return cub_xml_attr_doubles(el, attr, out, 1);
}

cub_err cub_xml_attr_int(const cub_xml_el *el, const char *attr, int *out)
{
    const char *s = cub_xml_attr(el, attr);
    if (!s) return CUB_ERR_EMPTY;
    while (is_blank(*s))
        s++;
    const char *p = s;
    if (*p == '-' || *p == '+') p++;
    if (!(*p >= '0' && *p <= '9')) return CUB_ERR_FORMAT;
    char *end = nullptr;
    errno = 0;
    long v = std::strtol(s, &end, 10);
    while (is_blank(*end))
        end++;
    if (*end || errno == ERANGE || v < INT32_MIN || v > INT32_MAX) return CUB_ERR_FORMAT;
    if (out) *out = static_cast<int>(v);
    return CUB_OK;
}

cub_err cub_xml_attr_doubles(const cub_xml_el *el, const char *attr, double *out, int n)
{
    const char *s = cub_xml_attr(el, attr);
    if (!s) return CUB_ERR_EMPTY;
    if (!out || n < 1) return CUB_ERR_ARG;
    return parse_numbers(s, out, n) == n ? CUB_OK : CUB_ERR_FORMAT;
}

cub_err cub_xml_fail(const cub_xml_el *el, cub_diag *diag, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    const char *file = el ? doc_name_of(to_el(el)) : "(xml)";
    cub_err e = cub_diag_vfail(diag, CUB_ERR_FORMAT, file, cub_xml_line(el), fmt, ap);
    va_end(ap);
    return e;
}

int cub_xml_attr_line(const cub_xml_el *el, const char *attr)
{
    const XMLAttribute *a = (el && attr) ? to_el(el)->FindAttribute(attr) : nullptr;
    return a ? a->GetLineNum() : cub_xml_line(el);
}

cub_err cub_xml_fail_attr(const cub_xml_el *el, const char *attr, cub_diag *diag, const char *fmt,
                          ...)
{
    va_list ap;
    va_start(ap, fmt);
    const char *file = el ? doc_name_of(to_el(el)) : "(xml)";
    cub_err e = cub_diag_vfail(diag, CUB_ERR_FORMAT, file, cub_xml_attr_line(el, attr), fmt, ap);
    va_end(ap);
    return e;
}

cub_xml_el *cub_xml_add(cub_xml_el *parent, const char *name)
{
    if (!parent || !valid_name(name)) return nullptr;
    try {
        XMLElement *p = to_el(parent);
        XMLElement *child = p->GetDocument()->NewElement(name);
        p->InsertEndChild(child);
        return from_el(child);
    } catch (...) {
        return nullptr;
    }
}

cub_err cub_xml_add_comment(cub_xml_el *parent, const char *text)
{
    if (!parent || !text || std::strstr(text, "--") || text[0] == '-' ||
        (*text && text[std::strlen(text) - 1] == '-'))
        return CUB_ERR_ARG;
    try {
        XMLElement *p = to_el(parent);
        p->InsertEndChild(p->GetDocument()->NewComment(text));
    } catch (...) {
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

cub_err cub_xml_set(cub_xml_el *el, const char *attr, const char *value)
{
    return set_attr(el, attr, value);
}

cub_err cub_xml_set_int(cub_xml_el *el, const char *attr, long value)
{
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%ld", value);
    return set_attr(el, attr, buf);
}

cub_err cub_xml_set_double(cub_xml_el *el, const char *attr, double value, int decimals)
{
    return cub_xml_set_doubles(el, attr, &value, 1, decimals);
}

cub_err cub_xml_set_doubles(cub_xml_el *el, const char *attr, const double *values, int n,
                            int decimals)
{
    if (!values || n < 1 || decimals < 0 || decimals > 9) return CUB_ERR_ARG;
    try {
        std::string s;
        for (int i = 0; i < n; i++) {
            char buf[48];
            if (!std::isfinite(values[i])) return CUB_ERR_ARG;
            if (i) s += ' ';
            s += cub_xml_format_double(values[i], decimals, buf, sizeof(buf));
        }
        return set_attr(el, attr, s.c_str());
    } catch (...) {
        return CUB_ERR_NOMEM;
    }
}

cub_err cub_xml_set_text(cub_xml_el *el, const char *text)
{
    if (!el || !text) return CUB_ERR_ARG;
    try {
        to_el(el)->SetText(text);
    } catch (...) {
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

cub_err cub_xml_print(const cub_xml_doc *doc, char **out, size_t *out_len)
{
    if (!doc || !out) return CUB_ERR_ARG;
    *out = nullptr;
    try {
        tinyxml2::XMLPrinter printer(nullptr, false, 0);
        doc->Print(&printer);
        // CStrSize counts the terminating NUL.
        size_t len = printer.CStrSize() > 0 ? static_cast<size_t>(printer.CStrSize()) - 1 : 0;
        char *buf = static_cast<char *>(std::malloc(len + 1));
        if (!buf) return CUB_ERR_NOMEM;
        std::memcpy(buf, printer.CStr(), len);
        buf[len] = '\0';
        *out = buf;
        if (out_len) *out_len = len;
    } catch (...) {
        return CUB_ERR_NOMEM;
    }
    return CUB_OK;
}

cub_err cub_xml_save(const cub_xml_doc *doc, const char *path, cub_diag *diag)
{
    const char *file = path ? path : "(null)";
    char *text = nullptr;
    size_t len = 0;
    if (!path) return cub_diag_fail(diag, CUB_ERR_ARG, file, 0, "no path");
    cub_err err = cub_xml_print(doc, &text, &len);
    if (err)
        return cub_diag_fail(diag, err, file, 0, "cannot print the XML document (%s)", cub_err_str(err));
    std::FILE *f = std::fopen(path, "wb");
    if (!f) {
        std::free(text);
        return cub_diag_fail(diag, CUB_ERR_IO, file, 0, "cannot create: %s", std::strerror(errno));
    }
    bool ok = std::fwrite(text, 1, len, f) == len;
    ok = (std::fclose(f) == 0) && ok;
    std::free(text);
    if (!ok) return cub_diag_fail(diag, CUB_ERR_IO, file, 0, "write failed: %s", std::strerror(errno));
    return CUB_OK;
}

const char *cub_xml_format_double(double value, int decimals, char *buf, size_t size)
{
    if (!buf || size == 0) return "";
    if (!std::isfinite(value) || decimals < 0 || decimals > 9) {
        std::snprintf(buf, size, "nan");
        return buf;
    }
    long long scale = 1;
    for (int i = 0; i < decimals; i++)
        scale *= 10;
    double scaled = value * static_cast<double>(scale);
    if (std::fabs(scaled) >= 9.0e15) { // beyond exact integers: no decimals to show
        std::snprintf(buf, size, "%.0f", value);
        return buf;
    }
    // Integer digits, so the output never depends on the locale.
    long long r = std::llround(scaled);
    bool neg = r < 0;
    unsigned long long mag = static_cast<unsigned long long>(neg ? -r : r);
    unsigned long long whole = mag / static_cast<unsigned long long>(scale);
    unsigned long long frac = mag % static_cast<unsigned long long>(scale);
    int n = std::snprintf(buf, size, "%s%llu", neg ? "-" : "", whole);
    if (frac && n > 0 && static_cast<size_t>(n) < size) {
        char digits[24];
        std::snprintf(digits, sizeof(digits), "%0*llu", decimals, frac);
        size_t k = std::strlen(digits);
        while (k > 0 && digits[k - 1] == '0')
            digits[--k] = '\0';
        std::snprintf(buf + n, size - static_cast<size_t>(n), ".%s", digits);
    }
    return buf;
}

} // extern "C"
