/* mem_census — see mem_census.h. Each mapping of /proc/self/smaps goes to
 * one owner: by its file's name (the GL driver's libraries are named
 * below), by the loaded object whose writable segment it lies in (a .bss
 * has no file name), by the thread whose stack pointer is in it, or, being
 * anonymous and executable, to the shader JIT (only LLVM writes code here). */
#define _GNU_SOURCE /* dl_iterate_phdr */
#include "mem_census.h"

#include <dirent.h>
#include <fcntl.h>
#include <link.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/syscall.h>
#include <unistd.h>

#define MAX_RANGES 512
#define MAX_THREADS 128

typedef enum owner { OWN_NONE, OWN_EXE, OWN_LLVM, OWN_MESA, OWN_GLAPI, OWN_LIB } owner;

typedef struct range {
    uintptr_t lo, hi;
    owner who;
} range;

typedef struct stack_ptr {
    uintptr_t sp;
    int gl;
} stack_ptr;

/* The census runs on the loop's thread only: its buffers are static so
 * that it allocates nothing. */
static range ranges[MAX_RANGES];
static int range_count;
static stack_ptr stacks[MAX_THREADS];
static int stack_count;
static struct {
    int fd;
    char buf[1 << 16];
    size_t len, pos;
} rd;

/* The libraries that are there for the GL driver only (Debian 12's Mesa
 * 22.3: llvmpipe through libgallium and LLVM 15, glvnd's dispatch). */
static const char *const llvm_libs[] = {"libLLVM", "libz3", "libedit", "libxml2", "libicu"};
static const char *const mesa_libs[] = {"libgallium", "_dri.so", "libEGL_mesa", "libglapi",
                                        "libgbm", "libdrm", "libxshmfence", "libsensors",
                                        "libwayland", "libxcb-dri", "libxcb-present",
                                        "libxcb-sync", "libxcb-xfixes", "libxcb-randr",
                                        "libxcb-shm", "libX11-xcb", "libvulkan", "/dev/dri/"};
static const char *const glapi_libs[] = {"libEGL.so", "libGLESv2", "libGLESv1", "libGLdispatch",
                                         "libGLX", "libOpenGL", "libGL.so"};

static int named(const char *path, const char *const *names, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (strstr(path, names[i])) return 1;
    return 0;
}

#define NAMED(path, list) named(path, list, sizeof list / sizeof *list)

static owner owner_of_file(const char *path)
{
    if (NAMED(path, llvm_libs)) return OWN_LLVM;
    if (NAMED(path, mesa_libs)) return OWN_MESA;
    if (NAMED(path, glapi_libs)) return OWN_GLAPI;
    return OWN_LIB;
}

/* Every loaded object's writable segments (data, bss, got): an anonymous
 * mapping inside one is that object's static data. */
static int add_object(struct dl_phdr_info *info, size_t size, void *first)
{
    int *is_first = first;
    owner who = *is_first ? OWN_EXE : owner_of_file(info->dlpi_name);
    *is_first = 0;
    uintptr_t page = (uintptr_t)sysconf(_SC_PAGESIZE);
    for (int i = 0; i < info->dlpi_phnum && range_count < MAX_RANGES; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type != PT_LOAD || !(ph->p_flags & PF_W)) continue;
        uintptr_t lo = info->dlpi_addr + ph->p_vaddr;
        uintptr_t hi = lo + ph->p_memsz;
        ranges[range_count++] = (range){lo & ~(page - 1), (hi + page - 1) & ~(page - 1), who};
    }
    return 0;
}

static int read_small(const char *path, char *buf, size_t size)
{
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) return -1;
    ssize_t n = read(fd, buf, size - 1);
    close(fd);
    if (n < 0) return -1;
    buf[n] = '\0';
    return (int)n;
}

/* The GL driver's threads by their names (llvmpipe's rasterisers, Mesa's
 * queues); the others are ours (the loop, SDL's, FluidSynth's). */
static int gl_thread(const char *comm)
{
    static const char *const prefixes[] = {"llvmpipe", "lp:", "gdrv", "disk$", "glsl", "mesa",
                                           "v3d", "drm"};
    for (size_t i = 0; i < sizeof prefixes / sizeof *prefixes; i++)
        if (!strncmp(comm, prefixes[i], strlen(prefixes[i]))) return 1;
    return 0;
}

/* A thread's stack pointer: the next-to-last field of its syscall file
 * ("running" has none: that thread is this one, reading). */
static int thread_sp(const char *tid, uintptr_t *sp)
{
    char path[64], line[512];
    snprintf(path, sizeof path, "/proc/self/task/%s/syscall", tid);
    if (read_small(path, line, sizeof line) <= 0) return -1;
    char *last = strrchr(line, ' ');
    if (!last || last == line) return -1;
    *last = '\0';
    char *prev = strrchr(line, ' ');
    if (!prev) return -1;
    *sp = (uintptr_t)strtoull(prev + 1, NULL, 16);
    return *sp ? 0 : -1;
}

struct linux_dirent64 {
    uint64_t d_ino;
    int64_t d_off;
    unsigned short d_reclen;
    unsigned char d_type;
    char d_name[];
};

/* Calls fn for each entry of a /proc directory, through getdents64:
 * opendir would allocate. Returns the entries seen, or -1. */
static int each_entry(const char *dir, void (*fn)(const char *name, void *u), void *u)
{
    static char buf[8192];
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0) return -1;
    int seen = 0;
    long n;
    while ((n = syscall(SYS_getdents64, fd, buf, sizeof buf)) > 0) {
        for (long off = 0; off < n;) {
            struct linux_dirent64 *e = (struct linux_dirent64 *)(buf + off);
            off += e->d_reclen;
            if (e->d_name[0] == '.') continue;
            seen++;
            if (fn) fn(e->d_name, u);
        }
    }
    close(fd);
    return seen;
}

static void add_thread(const char *tid, void *u)
{
    cub_mem_census *c = u;
    char path[64], comm[64];
    c->threads++;
    snprintf(path, sizeof path, "/proc/self/task/%s/comm", tid);
    int is_gl = read_small(path, comm, sizeof comm) > 0 && gl_thread(comm);
    c->gl_threads += is_gl;
    uintptr_t sp;
    if (stack_count < MAX_THREADS && thread_sp(tid, &sp) == 0)
        stacks[stack_count++] = (stack_ptr){sp, is_gl};
}

/* The next line of the file being read, NUL-terminated, or NULL at its end. */
static char *next_line(void)
{
    for (;;) {
        char *nl = memchr(rd.buf + rd.pos, '\n', rd.len - rd.pos);
        if (nl) {
            *nl = '\0';
            char *line = rd.buf + rd.pos;
            rd.pos = (size_t)(nl - rd.buf) + 1;
            return line;
        }
        memmove(rd.buf, rd.buf + rd.pos, rd.len - rd.pos);
        rd.len -= rd.pos;
        rd.pos = 0;
        ssize_t n = rd.len < sizeof rd.buf ? read(rd.fd, rd.buf + rd.len, sizeof rd.buf - rd.len)
                                           : 0;
        if (n <= 0) return NULL;
        rd.len += (size_t)n;
    }
}

typedef struct mapping {
    uintptr_t lo, hi;
    char perms[5];
    const char *path;
} mapping;

static int parse_header(char *line, mapping *m)
{
    char *end;
    m->lo = (uintptr_t)strtoull(line, &end, 16);
    if (*end != '-') return -1;
    m->hi = (uintptr_t)strtoull(end + 1, &end, 16);
    if (*end != ' ') return -1;
    memcpy(m->perms, end + 1, 4);
    m->perms[4] = '\0';
    /* offset, dev, inode, then the path (absent for anonymous memory) */
    char *p = end + 6;
    for (int field = 0; field < 3; field++) {
        while (*p == ' ') p++;
        while (*p && *p != ' ') p++;
    }
    while (*p == ' ') p++;
    m->path = p;
    return 0;
}

static owner static_owner(const mapping *m)
{
    for (int i = 0; i < range_count; i++)
        if (m->lo >= ranges[i].lo && m->hi <= ranges[i].hi) return ranges[i].who;
    return OWN_NONE;
}

static int stack_of(const mapping *m)
{
    for (int i = 0; i < stack_count; i++)
        if (stacks[i].sp >= m->lo && stacks[i].sp < m->hi) return stacks[i].gl ? 2 : 1;
    return 0;
}

static void add_gl(cub_mem_census *c, long *part, long kb)
{
    *part += kb;
    c->gl_kb += kb;
}

static void count(cub_mem_census *c, const mapping *m, long kb, const char *exe)
{
    int stack = !strcmp(m->path, "[stack]") ? 1 : m->path[0] ? 0 : stack_of(m);
    owner st = static_owner(m);
    if (stack == 1) c->stack_kb += kb;
    else if (stack == 2) add_gl(c, &c->gl_stack_kb, kb);
    else if (st == OWN_EXE) c->static_kb += kb;
    else if (!strcmp(m->path, exe)) c->exe_code_kb += kb;
    else if (st != OWN_NONE || m->path[0] == '/') {
        owner who = st != OWN_NONE ? st : owner_of_file(m->path);
        if (who == OWN_LLVM) add_gl(c, &c->gl_llvm_kb, kb);
        else if (who == OWN_MESA) add_gl(c, &c->gl_mesa_kb, kb);
        else if (who == OWN_GLAPI) add_gl(c, &c->gl_api_kb, kb);
        else c->libs_kb += kb;
    } else if (!m->path[0] && m->perms[2] == 'x') add_gl(c, &c->gl_jit_kb, kb);
    else c->anon_kb += kb; /* [heap], anonymous mappings, [vdso], memfd: ... */
}

static long static_size_kb(void)
{
    long kb = 0;
    for (int i = 0; i < range_count; i++)
        if (ranges[i].who == OWN_EXE) kb += (long)((ranges[i].hi - ranges[i].lo) / 1024);
    return kb;
}

int cub_mem_census_take(cub_mem_census *c)
{
    static char exe[4096];
    memset(c, 0, sizeof *c);
    range_count = stack_count = 0;
    int first = 1;
    dl_iterate_phdr(add_object, &first);
    each_entry("/proc/self/task", add_thread, c);
    ssize_t n = readlink("/proc/self/exe", exe, sizeof exe - 1);
    exe[n > 0 ? n : 0] = '\0';
    rd.fd = open("/proc/self/smaps", O_RDONLY | O_CLOEXEC);
    rd.len = rd.pos = 0;
    if (rd.fd < 0 || n <= 0) {
        if (rd.fd >= 0) close(rd.fd);
        memset(c, 0xff, sizeof *c); /* every figure -1 */
        return -1;
    }
    mapping m = {0};
    int have = 0;
    for (char *line; (line = next_line());) {
        /* a mapping's line starts with its address in lower-case hex; its
         * fields ("Rss:", "VmFlags:") with a capital */
        if (((line[0] >= '0' && line[0] <= '9') || (line[0] >= 'a' && line[0] <= 'f')) &&
            parse_header(line, &m) == 0)
            have = 1;
        else if (have && !strncmp(line, "Rss:", 4))
            count(c, &m, strtol(line + 4, NULL, 10), exe);
    }
    close(rd.fd);
    c->static_size_kb = static_size_kb();
    c->rss_kb = cub_mem_rss_kb();
    return 0;
}

int cub_mem_fd_count(void)
{
    /* The descriptor that reads the directory is one of them. */
    int n = each_entry("/proc/self/fd", NULL, NULL);
    return n < 0 ? -1 : n - 1;
}

long cub_mem_status_kb(const char *field)
{
    static char buf[4096];
    char key[32];
    if (read_small("/proc/self/status", buf, sizeof buf) <= 0) return -1;
    snprintf(key, sizeof key, "\n%s:", field);
    const char *p = strstr(buf, key);
    return p ? strtol(p + strlen(key), NULL, 10) : -1;
}

long cub_mem_rss_kb(void)
{
    return cub_mem_status_kb("VmRSS");
}
