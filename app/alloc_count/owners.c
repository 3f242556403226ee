/* owners — see owners.h. The owner is the library of the innermost frame
 * that is not an allocation wrapper; libraries are told apart by the
 * address ranges of their code (dl_iterate_phdr), looked up anew when a
 * frame is in none of them (a library dlopen'ed since). */
#define _GNU_SOURCE
#include "owners.h"

#include <execinfo.h>
#include <link.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>

#define TABLE_BITS 20
#define TABLE_SLOTS (1u << TABLE_BITS)
#define TABLE_MAX (TABLE_SLOTS / 4 * 3) /* linear probing stays short below 3/4 */
#define MAX_CODE 512
#define STACK_FRAMES 20
#define WRAPPER (-1)

typedef struct slot {
    uintptr_t p;
    uint32_t bytes;
    int32_t owner;
} slot;

typedef struct code_range {
    uintptr_t lo, hi;
    int owner; /* a cub_alloc_owner, or WRAPPER */
} code_range;

static int on;
static slot *table;
static uint32_t used;
static atomic_flag lock = ATOMIC_FLAG_INIT;
static int64_t live[CUB_ALLOC_OWNER_COUNT], peak[CUB_ALLOC_OWNER_COUNT];
static int64_t not_gl_live, not_gl_peak;
static uint64_t allocs[CUB_ALLOC_OWNER_COUNT];
static code_range code[MAX_CODE];
static atomic_int code_count;
static atomic_flag code_lock = ATOMIC_FLAG_INIT;
static __thread int walking __attribute__((tls_model("initial-exec")));

static const struct {
    const char *name;
    int owner;
} libraries[] = {
    {"liballoc_count", WRAPPER}, {"libcub_alloc_count", WRAPPER}, {"libc.so", WRAPPER},
    {"libstdc++", WRAPPER}, {"libglib", WRAPPER}, {"libgcc_s", WRAPPER}, {"libpng", WRAPPER},
    {"libtinyxml2", WRAPPER}, {"libz.so", WRAPPER}, {"ld-linux", WRAPPER},
    {"libfluidsynth", CUB_ALLOC_MUSIC}, {"libgomp", CUB_ALLOC_MUSIC},
    {"libinstpatch", CUB_ALLOC_MUSIC}, {"libsndfile", CUB_ALLOC_MUSIC},
    {"fakenect", CUB_ALLOC_CAMERA}, {"libfreenect", CUB_ALLOC_CAMERA},
    {"libusb", CUB_ALLOC_CAMERA}, {"libSDL2", CUB_ALLOC_SDL}, {"_dri.so", CUB_ALLOC_GL},
    {"libgallium", CUB_ALLOC_GL}, {"libLLVM", CUB_ALLOC_GL}, {"libEGL", CUB_ALLOC_GL},
    {"libGLES", CUB_ALLOC_GL}, {"libGLdispatch", CUB_ALLOC_GL}, {"libglapi", CUB_ALLOC_GL},
    {"libgbm", CUB_ALLOC_GL}, {"libdrm", CUB_ALLOC_GL}, {"libz3", CUB_ALLOC_GL},
    {"libxml2", CUB_ALLOC_GL}, {"libedit", CUB_ALLOC_GL},
};

static int owner_of_library(const char *path, int is_program)
{
    if (is_program) return CUB_ALLOC_OURS;
    for (size_t i = 0; i < sizeof libraries / sizeof *libraries; i++)
        if (strstr(path, libraries[i].name)) return libraries[i].owner;
    return CUB_ALLOC_OTHER;
}

static int add_code(struct dl_phdr_info *info, size_t size, void *n)
{
    int *count = n;
    int owner = owner_of_library(info->dlpi_name, *count == 0 && !info->dlpi_name[0]);
    for (int i = 0; i < info->dlpi_phnum && *count < MAX_CODE; i++) {
        const ElfW(Phdr) *ph = &info->dlpi_phdr[i];
        if (ph->p_type != PT_LOAD || !(ph->p_flags & PF_X)) continue;
        uintptr_t lo = info->dlpi_addr + ph->p_vaddr;
        code[(*count)++] = (code_range){lo, lo + ph->p_memsz, owner};
    }
    return 0;
}

static void learn_code(void)
{
    if (atomic_flag_test_and_set(&code_lock)) return; /* another thread is at it */
    int n = 0;
    atomic_store(&code_count, 0);
    dl_iterate_phdr(add_code, &n);
    atomic_store(&code_count, n);
    atomic_flag_clear(&code_lock);
}

/* -2: in no library known yet. */
static int owner_of_address(uintptr_t a)
{
    int n = atomic_load(&code_count);
    for (int i = 0; i < n; i++)
        if (a >= code[i].lo && a < code[i].hi) return code[i].owner;
    return -2;
}

static int owner_of_caller(void)
{
    if (walking) return CUB_ALLOC_OTHER; /* the unwinder's own */
    walking = 1;
    void *frames[STACK_FRAMES];
    int depth = backtrace(frames, STACK_FRAMES);
    int owner = CUB_ALLOC_OTHER;
    for (int i = 0; i < depth; i++) {
        int o = owner_of_address((uintptr_t)frames[i]);
        if (o == -2) {
            learn_code();
            o = owner_of_address((uintptr_t)frames[i]);
        }
        if (o >= 0) {
            owner = o;
            break;
        }
    }
    walking = 0;
    return owner;
}

static uint32_t home(uintptr_t p)
{
    return (uint32_t)(((uint64_t)(p >> 4) * 0x9E3779B97F4A7C15ull) >> (64 - TABLE_BITS));
}

static void take(int owner, int64_t n)
{
    live[owner] += n;
    if (live[owner] > peak[owner]) peak[owner] = live[owner];
    if (owner == CUB_ALLOC_GL) return;
    not_gl_live += n;
    if (not_gl_live > not_gl_peak) not_gl_peak = not_gl_live;
}

int cub_owners_start(void)
{
    const char *want = getenv("CUB_ALLOC_OWNERS");
    if (!want || strcmp(want, "1") != 0) return 0;
    void *t = mmap(NULL, TABLE_SLOTS * sizeof(slot), PROT_READ | PROT_WRITE,
                   MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (t == MAP_FAILED) return 0;
    table = t;
    walking = 1;
    void *prime[2];
    backtrace(prime, 2); /* loads the unwinder now, not inside an allocation */
    walking = 0;
    learn_code();
    on = 1;
    return 1;
}

void cub_owners_add(void *p, int64_t n)
{
    if (!on) return;
    int owner = owner_of_caller();
    while (atomic_flag_test_and_set_explicit(&lock, memory_order_acquire)) {
    }
    if (used < TABLE_MAX) {
        uint32_t i = home((uintptr_t)p);
        while (table[i].p) i = (i + 1) & (TABLE_SLOTS - 1);
        table[i] = (slot){(uintptr_t)p, (uint32_t)n, owner};
        used++;
    } else {
        owner = CUB_ALLOC_UNTRACKED;
    }
    take(owner, n);
    allocs[owner]++;
    atomic_flag_clear_explicit(&lock, memory_order_release);
}

/* Linear probing's deletion: shift back the entries that would no longer
 * be found past the hole. */
static void drop_slot(uint32_t i)
{
    uint32_t j = i;
    for (;;) {
        j = (j + 1) & (TABLE_SLOTS - 1);
        if (!table[j].p) break;
        uint32_t k = home(table[j].p);
        int keep = i <= j ? (i < k && k <= j) : (i < k || k <= j);
        if (!keep) {
            table[i] = table[j];
            i = j;
        }
    }
    table[i].p = 0;
    used--;
}

void cub_owners_remove(void *p, int64_t n)
{
    if (!on) return;
    while (atomic_flag_test_and_set_explicit(&lock, memory_order_acquire)) {
    }
    uint32_t i = home((uintptr_t)p);
    while (table[i].p && table[i].p != (uintptr_t)p) i = (i + 1) & (TABLE_SLOTS - 1);
    int owner = CUB_ALLOC_UNTRACKED; /* handed out before tracking began */
    if (table[i].p) {
        owner = table[i].owner;
        drop_slot(i);
    }
    live[owner] -= n;
    if (owner != CUB_ALLOC_GL) not_gl_live -= n;
    atomic_flag_clear_explicit(&lock, memory_order_release);
}

int cub_owners_read(cub_alloc_owners *out)
{
    memset(out, 0, sizeof *out);
    if (!on) return 0;
    while (atomic_flag_test_and_set_explicit(&lock, memory_order_acquire)) {
    }
    memcpy(out->allocs, allocs, sizeof allocs);
    memcpy(out->live_bytes, live, sizeof live);
    memcpy(out->peak_bytes, peak, sizeof peak);
    out->not_gl_peak_bytes = not_gl_peak;
    atomic_flag_clear_explicit(&lock, memory_order_release);
    return 1;
}
