/* mem_stats — see mem_stats.h. Nothing here allocates inside a tick: the
 * song line is formatted on the stack and written with write(2), so the
 * counting does not count itself. */
#define _GNU_SOURCE /* RTLD_DEFAULT, mallinfo2 */
#include "mem_stats.h"

#include <dlfcn.h>
#include <malloc.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mem_census.h"

#if defined(__SANITIZE_ADDRESS__)
#define CUB_MEM_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CUB_MEM_SANITIZED 1
#endif
#endif

static const char *const phase_names[CUB_MEM_PHASE_COUNT] = {"before_start", "first_song",
                                                             "steady"};

void cub_mem_stats_open(cub_mem_stats *m)
{
    memset(m, 0, sizeof *m);
#ifdef CUB_MEM_SANITIZED
    m->heap_missing = "unavailable in a sanitizer build (its allocator is not malloc's)";
#else
    m->read = (cub_alloc_count_read_fn *)dlsym(RTLD_DEFAULT, CUB_ALLOC_COUNT_READ);
    m->trace = (cub_alloc_count_trace_fn *)dlsym(RTLD_DEFAULT, CUB_ALLOC_COUNT_TRACE);
    m->owners = (cub_alloc_count_owners_fn *)dlsym(RTLD_DEFAULT, CUB_ALLOC_COUNT_OWNERS);
    if (m->read) m->read(&m->last);
    m->owners_on = m->owners && m->owners(&m->last_owners);
#endif
    const char *n = getenv("CUB_ALLOC_TRACE");
    m->trace_n = n ? atoi(n) : 0;
}

/* Without the counter: malloc's in-use bytes (all arenas, and the blocks
 * mapped alone), sampled now; the peak is then the highest tick's. */
static void sample_heap(cub_mem_stats *m)
{
#ifndef CUB_MEM_SANITIZED
    if (m->read) {
        cub_alloc_stats now;
        m->read(&now);
        m->heap_bytes = now.live_bytes;
        m->heap_peak_bytes = now.peak_bytes;
        return;
    }
    struct mallinfo2 mi = mallinfo2();
    m->heap_bytes = (int64_t)(mi.uordblks + mi.hblkhd);
    if (m->heap_bytes > m->heap_peak_bytes) m->heap_peak_bytes = m->heap_bytes;
#else
    (void)m;
#endif
}

static void count_tick(cub_mem_stats *m)
{
    cub_mem_phase *p = &m->phases[m->phase];
    p->ticks++;
    if (!m->read) return;
    cub_alloc_stats now;
    m->read(&now);
    uint64_t allocs = now.allocs - m->last.allocs;
    p->allocs += allocs;
    p->frees += now.frees - m->last.frees;
    if (allocs) p->ticks_allocating++;
    if (allocs > p->max_tick_allocs) p->max_tick_allocs = (uint32_t)allocs;
    m->last = now;
    cub_alloc_owners o;
    if (!m->owners_on || !m->owners(&o)) return;
    for (int i = 0; i < CUB_ALLOC_OWNER_COUNT; i++)
        p->owner_allocs[i] += o.allocs[i] - m->last_owners.allocs[i];
    m->last_owners = o;
}

/* One line per song start, for a soak to compare song by song. */
static void song_line(cub_mem_stats *m, int64_t t_us)
{
    char line[320];
    int n = snprintf(line, sizeof line,
                     "stats: song n=%u t=%lld.%03lld rss_kb=%ld fds=%d rss_anon_kb=%ld "
                     "rss_file_kb=%ld",
                     m->songs, (long long)(t_us / 1000000), (long long)(t_us / 1000 % 1000),
                     cub_mem_rss_kb(), cub_mem_fd_count(), cub_mem_status_kb("RssAnon"),
                     cub_mem_status_kb("RssFile"));
    if (m->heap_missing)
        n += snprintf(line + n, sizeof line - (size_t)n, " heap=unavailable");
    else
        n += snprintf(line + n, sizeof line - (size_t)n,
                      " heap_peak_kb=%lld heap_kb=%lld heap_peak_b=%lld heap_b=%lld",
                      (long long)(m->heap_peak_bytes / 1024), (long long)(m->heap_bytes / 1024),
                      (long long)m->heap_peak_bytes, (long long)m->heap_bytes);
    if (m->read)
        n += snprintf(line + n, sizeof line - (size_t)n, " allocs=%llu",
                      (unsigned long long)m->last.allocs);
    line[n++] = '\n';
    if (write(1, line, (size_t)n) < 0) return;
}

static void enter_phase(cub_mem_stats *m, cub_mem_phase_id phase)
{
    m->phase = phase;
    if (!m->trace || m->trace_n <= 0) return;
    /* The traces that follow are this phase's (scripts/alloc_sites.py). */
    char line[64];
    int n = snprintf(line, sizeof line, "alloc-phase: %s\n", phase_names[phase]);
    if (write(2, line, (size_t)n) < 0) return;
    m->trace(m->trace_n);
}

void cub_mem_stats_tick(cub_mem_stats *m, int64_t t_us, int dancing)
{
    if (dancing && !m->dancing && m->phase == CUB_MEM_BEFORE_START)
        enter_phase(m, CUB_MEM_FIRST_SONG);
    else if (!dancing && m->dancing && m->phase == CUB_MEM_FIRST_SONG)
        enter_phase(m, CUB_MEM_STEADY);
    count_tick(m);
    sample_heap(m);
    if (dancing && !m->dancing) {
        m->songs++;
        song_line(m, t_us);
    }
    m->dancing = dancing;
}

static const char *const owner_names[CUB_ALLOC_OWNER_COUNT] = {
    "ours", "gl_driver", "fluidsynth", "camera", "sdl", "other", "untracked"};

static double mb(long kb)
{
    return kb / 1024.0;
}

static void print_phases(const cub_mem_stats *m, FILE *out)
{
    if (!m->read) {
        fprintf(out, "stats: allocations per tick: not counted (%s)\n",
                m->heap_missing ? m->heap_missing
                                : "run with LD_PRELOAD=<build>/app/alloc_count/libcub_alloc_count.so");
        return;
    }
    fprintf(out, "stats: allocations per tick (malloc family, the whole process):");
    for (int i = 0; i < CUB_MEM_PHASE_COUNT; i++) {
        const cub_mem_phase *p = &m->phases[i];
        fprintf(out, " %s=%.3f (%llu in %u of %u ticks, max %u", phase_names[i],
                p->ticks ? (double)p->allocs / p->ticks : 0.0, (unsigned long long)p->allocs,
                p->ticks_allocating, p->ticks, p->max_tick_allocs);
        for (int k = 0; m->owners_on && k < CUB_ALLOC_OWNER_COUNT; k++)
            fprintf(out, "%s%s=%llu", k ? " " : "; by owner: ", owner_names[k],
                    (unsigned long long)p->owner_allocs[k]);
        fputc(')', out);
    }
    fputc('\n', out);
}

/* The heap by owner, each at its own high-water; 0 when not tracked. */
static int print_owners(const cub_mem_stats *m, FILE *out, cub_alloc_owners *o)
{
    if (!m->owners || !m->owners(o)) return 0;
    fprintf(out, "stats: memory heap by owner, each at its high-water (MB):");
    for (int i = 0; i < CUB_ALLOC_OWNER_COUNT; i++)
        fprintf(out, " %s=%.1f", owner_names[i], o->peak_bytes[i] / 1048576.0);
    fprintf(out, "; all but the GL driver's together: %.1f; in use now:",
            o->not_gl_peak_bytes / 1048576.0);
    for (int i = 0; i < CUB_ALLOC_OWNER_COUNT; i++)
        fprintf(out, " %s=%.1f", owner_names[i], o->live_bytes[i] / 1048576.0);
    fputc('\n', out);
    return 1;
}

/* Over the goal with the GL driver's blocks in the heap says nothing. */
static const char *verdict(int by_owner, long ours_kb)
{
    if (ours_kb <= CUB_MEM_GOAL_KB) return "met";
    return by_owner ? "MISSED" : "unknown";
}

void cub_mem_stats_print(const cub_mem_stats *m, FILE *out)
{
    cub_mem_census c;
    if (cub_mem_census_take(&c)) {
        fprintf(out, "stats: memory: /proc/self/smaps cannot be read\n");
        print_phases(m, out);
        return;
    }
    cub_alloc_owners o;
    int by_owner = !m->heap_missing && print_owners(m, out, &o);
    /* With owners, our heap is every block but the GL driver's (FluidSynth's
     * SoundFont samples are ours: we load them); without, the whole heap. */
    long heap_kb = (long)((by_owner ? o.not_gl_peak_bytes : m->heap_peak_bytes) / 1024);
    long ours_kb = (m->heap_missing ? 0 : heap_kb) + c.static_kb + c.stack_kb;
    fprintf(out, "stats: memory ours=%.1fMB", mb(ours_kb));
    if (m->heap_missing) {
        fprintf(out, " (the heap left out: %s) = static=%.1fMB (resident, of %.1fMB .data+.bss) + "
                     "stacks=%.1fMB\n",
                m->heap_missing, mb(c.static_kb), mb(c.static_size_kb), mb(c.stack_kb));
    } else {
        fprintf(out,
                " goal<=%dMB %s = heap_peak=%.1fMB (%s) + static=%.1fMB (resident, of %.1fMB "
                ".data+.bss) + stacks=%.1fMB\n",
                CUB_MEM_GOAL_KB / 1024, verdict(by_owner, ours_kb), mb(heap_kb),
                by_owner  ? "every block but the GL driver's"
                : m->read ? "every block, the GL driver's too: CUB_ALLOC_OWNERS=1 splits it"
                          : "every block, sampled per tick",
                mb(c.static_kb), mb(c.static_size_kb), mb(c.stack_kb));
    }
    fprintf(out,
            "stats: memory gl_driver=%.1fMB resident mappings, not ours (llvm=%.1f mesa=%.1f "
            "egl_gles_dispatch=%.1f jit_code=%.1f stacks=%.1f MB, %d of %d threads)%s\n",
            mb(c.gl_kb), mb(c.gl_llvm_kb), mb(c.gl_mesa_kb), mb(c.gl_api_kb), mb(c.gl_jit_kb),
            mb(c.gl_stack_kb), c.gl_threads, c.threads,
            by_owner || m->heap_missing ? "" : "; its heap blocks are in the heap above");
    fprintf(out,
            "stats: memory rss=%.1fMB: static+stacks, gl_driver, exe_code=%.1fMB, "
            "other_libs=%.1fMB (libc, SDL2, FluidSynth ... code: shared file pages), "
            "anon=%.1fMB (the heap's resident pages, everyone's)\n",
            mb(c.rss_kb), mb(c.exe_code_kb), mb(c.libs_kb), mb(c.anon_kb));
    print_phases(m, out);
}
