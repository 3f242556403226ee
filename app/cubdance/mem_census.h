/* mem_census — where this process's resident memory is, from
 * /proc/self/smaps, split into what is the box's own and what is the GL
 * driver's (Mesa llvmpipe and the LLVM it compiles shaders with on a PC,
 * V3D on the Pi), in kB. Reads with open/read into static buffers: taking a
 * census allocates nothing, so it can run inside a counted tick. Linux
 * only; on failure every figure is -1. */
#ifndef CUB_APP_MEM_CENSUS_H
#define CUB_APP_MEM_CENSUS_H

#include <stdio.h>

typedef struct cub_mem_census {
    long rss_kb;          /* all resident memory (VmRSS) */
    /* The box's own mappings. */
    long static_kb;       /* the executable's writable segments resident: .data, .bss, .got */
    long static_size_kb;  /* ... their size (a .bss page never touched is not resident) */
    long exe_code_kb;     /* the executable's code and read-only data resident */
    long stack_kb;        /* the main thread's stack and our other threads' */
    int threads, gl_threads;
    /* The GL driver: its libraries (libLLVM, libgallium / *_dri.so,
     * libEGL, libGLESv2, glapi / GLdispatch, libdrm, libgbm, and what they
     * pull in only for it), their static data, the JIT's code pages and its
     * threads' stacks. */
    long gl_kb;
    long gl_llvm_kb, gl_mesa_kb, gl_api_kb, gl_jit_kb, gl_stack_kb;
    /* The rest. */
    long libs_kb;         /* other libraries (libc, SDL2, FluidSynth, libstdc++ ...), file pages */
    long anon_kb;         /* anonymous memory not named above: malloc's heap and arenas,
                           * big allocations mapped alone, anything else mmap'd */
} cub_mem_census;

/* Take the census now; 0, or -1 (figures -1) when /proc cannot be read. */
int cub_mem_census_take(cub_mem_census *out);
/* Open file descriptors of this process, or -1. */
int cub_mem_fd_count(void);
/* VmRSS in kB, or -1. */
long cub_mem_rss_kb(void);
/* A field of /proc/self/status in kB ("RssAnon", "RssFile"), or -1. */
long cub_mem_status_kb(const char *field);

#endif
