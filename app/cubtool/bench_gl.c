/* bench_gl — the GL wrappers (see bench_gl.h). Each wrapper reads the
 * thread CPU clock before and after the real call; the bench measures what
 * one clock read costs and takes it back out of both sides. Only the GL
 * functions named in CUB_BENCH_GL_WRAPPED (app/cubtool/CMakeLists.txt) may
 * be wrapped here: a wrapper without its --wrap option is dead code, an
 * option without its wrapper fails the link. */
#include <GLES2/gl2.h>
#include <time.h>

#include "bench_gl.h"

static int g_on;
static int64_t g_inside_ns, g_calls;

static int64_t clock_ns(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return (int64_t)ts.tv_sec * 1000000000 + ts.tv_nsec;
}

int64_t cub_bench_thread_ns(void) { return clock_ns(CLOCK_THREAD_CPUTIME_ID); }
int64_t cub_bench_process_ns(void) { return clock_ns(CLOCK_PROCESS_CPUTIME_ID); }

void cub_bench_gl_timing(int on)
{
    g_on = on;
    g_inside_ns = g_calls = 0;
}

void cub_bench_gl_take(int64_t *inside_ns, int64_t *calls)
{
    *inside_ns = g_inside_ns;
    *calls = g_calls;
    g_inside_ns = g_calls = 0;
}

static int64_t enter(void) { return g_on ? cub_bench_thread_ns() : 0; }

static void leave(int64_t t0)
{
    if (!g_on)
        return;
    g_inside_ns += cub_bench_thread_ns() - t0;
    g_calls++;
}

/* WRAP_V: a void function; WRAP_R: one that returns a value. PARAMS is the
 * parameter list with types, ARGS the same names without. */
#define WRAP_V(NAME, PARAMS, ARGS)                                                                \
    void __real_##NAME PARAMS;                                                                    \
    void __wrap_##NAME PARAMS;                                                                    \
    void __wrap_##NAME PARAMS                                                                     \
    {                                                                                             \
        int64_t t0 = enter();                                                                     \
        __real_##NAME ARGS;                                                                       \
        leave(t0);                                                                                \
    }
#define WRAP_R(RET, NAME, PARAMS, ARGS)                                                           \
    RET __real_##NAME PARAMS;                                                                     \
    RET __wrap_##NAME PARAMS;                                                                     \
    RET __wrap_##NAME PARAMS                                                                      \
    {                                                                                             \
        int64_t t0 = enter();                                                                     \
        RET v = __real_##NAME ARGS;                                                               \
        leave(t0);                                                                                \
        return v;                                                                                 \
    }

WRAP_V(glActiveTexture, (GLenum t), (t))
WRAP_V(glAttachShader, (GLuint p, GLuint s), (p, s))
WRAP_V(glBindBuffer, (GLenum t, GLuint b), (t, b))
WRAP_V(glBindTexture, (GLenum t, GLuint x), (t, x))
WRAP_V(glBlendFunc, (GLenum s, GLenum d), (s, d))
WRAP_V(glBufferData, (GLenum t, GLsizeiptr n, const void *d, GLenum u), (t, n, d, u))
WRAP_V(glClear, (GLbitfield m), (m))
WRAP_V(glClearColor, (GLfloat r, GLfloat g, GLfloat b, GLfloat a), (r, g, b, a))
WRAP_V(glClearDepthf, (GLfloat d), (d))
WRAP_V(glCompileShader, (GLuint s), (s))
WRAP_R(GLuint, glCreateProgram, (void), ())
WRAP_R(GLuint, glCreateShader, (GLenum t), (t))
WRAP_V(glDeleteBuffers, (GLsizei n, const GLuint *b), (n, b))
WRAP_V(glDeleteProgram, (GLuint p), (p))
WRAP_V(glDeleteShader, (GLuint s), (s))
WRAP_V(glDeleteTextures, (GLsizei n, const GLuint *t), (n, t))
WRAP_V(glDepthFunc, (GLenum f), (f))
WRAP_V(glDepthMask, (GLboolean f), (f))
WRAP_V(glDisable, (GLenum c), (c))
WRAP_V(glDisableVertexAttribArray, (GLuint i), (i))
WRAP_V(glDrawArrays, (GLenum m, GLint f, GLsizei n), (m, f, n))
WRAP_V(glDrawElements, (GLenum m, GLsizei n, GLenum t, const void *i), (m, n, t, i))
WRAP_V(glEnable, (GLenum c), (c))
WRAP_V(glEnableVertexAttribArray, (GLuint i), (i))
WRAP_V(glFinish, (void), ())
WRAP_V(glGenBuffers, (GLsizei n, GLuint *b), (n, b))
WRAP_V(glGenTextures, (GLsizei n, GLuint *t), (n, t))
WRAP_R(GLint, glGetAttribLocation, (GLuint p, const GLchar *n), (p, n))
WRAP_R(GLenum, glGetError, (void), ())
WRAP_V(glGetProgramInfoLog, (GLuint p, GLsizei n, GLsizei *l, GLchar *s), (p, n, l, s))
WRAP_V(glGetProgramiv, (GLuint p, GLenum e, GLint *v), (p, e, v))
WRAP_V(glGetShaderInfoLog, (GLuint p, GLsizei n, GLsizei *l, GLchar *s), (p, n, l, s))
WRAP_V(glGetShaderiv, (GLuint s, GLenum e, GLint *v), (s, e, v))
WRAP_R(GLint, glGetUniformLocation, (GLuint p, const GLchar *n), (p, n))
WRAP_V(glLinkProgram, (GLuint p), (p))
WRAP_V(glPixelStorei, (GLenum e, GLint v), (e, v))
WRAP_V(glScissor, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))
WRAP_V(glShaderSource, (GLuint s, GLsizei n, const GLchar *const *t, const GLint *l), (s, n, t, l))
WRAP_V(glTexImage2D,
       (GLenum t, GLint l, GLint f, GLsizei w, GLsizei h, GLint b, GLenum pf, GLenum ty,
        const void *p),
       (t, l, f, w, h, b, pf, ty, p))
WRAP_V(glTexParameteri, (GLenum t, GLenum e, GLint v), (t, e, v))
WRAP_V(glTexSubImage2D,
       (GLenum t, GLint l, GLint x, GLint y, GLsizei w, GLsizei h, GLenum f, GLenum ty,
        const void *p),
       (t, l, x, y, w, h, f, ty, p))
WRAP_V(glUniform1i, (GLint l, GLint v), (l, v))
WRAP_V(glUniform3fv, (GLint l, GLsizei n, const GLfloat *v), (l, n, v))
WRAP_V(glUniform4fv, (GLint l, GLsizei n, const GLfloat *v), (l, n, v))
WRAP_V(glUniformMatrix4fv, (GLint l, GLsizei n, GLboolean t, const GLfloat *v), (l, n, t, v))
WRAP_V(glUseProgram, (GLuint p), (p))
WRAP_V(glVertexAttribPointer, (GLuint i, GLint n, GLenum t, GLboolean k, GLsizei s, const void *p),
       (i, n, t, k, s, p))
WRAP_V(glViewport, (GLint x, GLint y, GLsizei w, GLsizei h), (x, y, w, h))
