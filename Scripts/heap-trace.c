// SPDX-License-Identifier: BSD-3-Clause
// Heap trace for whole-process memory breakdowns (issue 21), preloaded into a program:
//   cc -O2 -shared -fPIC -o heap-trace.so Scripts/heap-trace.c -ldl -lpthread
//   xvfb-run -a env HEAP_TRACE_OUT=trace.txt LD_PRELOAD=$PWD/heap-trace.so
//     build/bin/vis4gs view LOG --benchmark        (one line; preload the program, not Xvfb)
//   python3 Scripts/heap-trace-report.py trace.txt [block|alloc]
// It counts the live heap bytes (malloc_usable_size), samples them with VmRSS and VmHWM every
// 200 ms ("sample" lines), and records every block of 4 MiB or more with its callers: those
// live at the peak of the live heap ("block" lines) and all of them ("alloc" lines, the
// fresh memory a run asks for). Small blocks are counted but not attributed. Fast enough for
// a 10M-Gaussian start-up (heaptrack and massif were not tried at that size). Not built.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <execinfo.h>
#include <malloc.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

extern void* __libc_malloc(size_t);
extern void* __libc_calloc(size_t, size_t);
extern void* __libc_realloc(void*, size_t);
extern void __libc_free(void*);
extern void* __libc_memalign(size_t, size_t);

#define BIG (4u << 20)
#define MAXB 8192
#define DEPTH 10
typedef struct
{
  void* p;
  size_t n;
  int nf;
  void* bt[DEPTH];
  double t;
} Block;
static Block blocks[MAXB], peakBlocks[MAXB], allBlocks[MAXB];
static int nblocks, npeak, nall;
static atomic_long live, peak, snapPeak;
static atomic_flag lock = ATOMIC_FLAG_INIT;
static __thread int guard;
static struct timespec t0;

static double Now(void)
{
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return (t.tv_sec - t0.tv_sec) + 1e-9 * (t.tv_nsec - t0.tv_nsec);
}
static void Lock(void)
{
  while (atomic_flag_test_and_set(&lock))
  {
  }
}
static void Unlock(void)
{
  atomic_flag_clear(&lock);
}

// Live-heap accounting; the live big blocks are copied whenever the peak grows by 8 MiB.
static void Note(long delta)
{
  const long v = atomic_fetch_add(&live, delta) + delta;
  long p = atomic_load(&peak);
  while (v > p && !atomic_compare_exchange_weak(&peak, &p, v))
  {
  }
  if (v > atomic_load(&snapPeak) + (8L << 20))
  {
    Lock();
    if (v > atomic_load(&snapPeak) + (8L << 20))
    {
      memcpy(peakBlocks, blocks, sizeof(Block) * nblocks);
      npeak = nblocks;
      atomic_store(&snapPeak, v);
    }
    Unlock();
  }
}
static void Add(void* p)
{
  if (!p)
  {
    return;
  }
  const size_t u = malloc_usable_size(p);
  if (u >= BIG && !guard)
  {
    guard = 1; // backtrace() may allocate
    Block b;
    b.p = p;
    b.n = u;
    b.t = Now();
    b.nf = backtrace(b.bt, DEPTH);
    guard = 0;
    Lock();
    if (nblocks < MAXB)
    {
      blocks[nblocks++] = b;
    }
    if (nall < MAXB)
    {
      allBlocks[nall++] = b;
    }
    Unlock();
  }
  Note((long)u);
}
static void Remove(void* p)
{
  if (!p)
  {
    return;
  }
  const size_t u = malloc_usable_size(p);
  if (u >= BIG)
  {
    Lock();
    for (int i = nblocks - 1; i >= 0; --i)
    {
      if (blocks[i].p == p)
      {
        blocks[i] = blocks[--nblocks];
        break;
      }
    }
    Unlock();
  }
  Note(-(long)u);
}

void* malloc(size_t n)
{
  void* p = __libc_malloc(n);
  Add(p);
  return p;
}
void* calloc(size_t a, size_t b)
{
  void* p = __libc_calloc(a, b);
  Add(p);
  return p;
}
void free(void* p)
{
  Remove(p);
  __libc_free(p);
}
void* realloc(void* q, size_t n)
{
  Remove(q);
  void* p = __libc_realloc(q, n);
  Add(p ? p : (n ? q : NULL));
  return p;
}
void* memalign(size_t a, size_t n)
{
  void* p = __libc_memalign(a, n);
  Add(p);
  return p;
}
void* aligned_alloc(size_t a, size_t n)
{
  return memalign(a, n);
}
int posix_memalign(void** r, size_t a, size_t n)
{
  void* p = __libc_memalign(a, n);
  if (!p)
  {
    return 12; // ENOMEM
  }
  Add(p);
  *r = p;
  return 0;
}

static long StatusKiB(const char* key)
{
  guard = 1;
  FILE* f = fopen("/proc/self/status", "r");
  char line[256];
  long v = -1;
  while (f && fgets(line, sizeof line, f))
  {
    if (!strncmp(line, key, strlen(key)))
    {
      v = atol(line + strlen(key) + 1);
      break;
    }
  }
  if (f)
  {
    fclose(f);
  }
  guard = 0;
  return v;
}
static void* Sampler(void* unused)
{
  (void)unused;
  const char* out = getenv("HEAP_TRACE_OUT");
  for (;;)
  {
    usleep(200000);
    FILE* f = out ? fopen(out, "a") : NULL;
    if (f)
    {
      fprintf(f,
        "sample t=%.2f live=%ld MiB rss=%ld MiB hwm=%ld MiB\n",
        Now(),
        atomic_load(&live) >> 20,
        StatusKiB("VmRSS") >> 10,
        StatusKiB("VmHWM") >> 10);
      fclose(f);
    }
  }
  return NULL;
}
static void PrintBlock(FILE* f, const char* kind, const Block* b)
{
  fprintf(f, "%s %.1f MiB t=%.2f", kind, b->n / 1048576.0, b->t);
  for (int k = 1; k < b->nf; ++k)
  {
    Dl_info d;
    if (dladdr(b->bt[k], &d) && d.dli_fname)
    {
      fprintf(f, " %s+%#lx", d.dli_fname, (unsigned long)((char*)b->bt[k] - (char*)d.dli_fbase));
    }
  }
  fprintf(f, "\n");
}
__attribute__((constructor)) static void Init(void)
{
  clock_gettime(CLOCK_MONOTONIC, &t0);
  pthread_t t;
  pthread_attr_t a;
  pthread_attr_init(&a);
  pthread_attr_setdetachstate(&a, PTHREAD_CREATE_DETACHED);
  pthread_create(&t, &a, Sampler, NULL);
}
__attribute__((destructor)) static void Fini(void)
{
  const char* out = getenv("HEAP_TRACE_OUT");
  FILE* f = out ? fopen(out, "a") : NULL;
  if (!f)
  {
    return;
  }
  guard = 1;
  fprintf(f,
    "peak live heap %ld MiB, VmHWM %ld MiB, blocks >= 4 MiB at the peak: %d\n",
    atomic_load(&peak) >> 20,
    StatusKiB("VmHWM") >> 10,
    npeak);
  for (int i = 0; i < npeak; ++i)
  {
    PrintBlock(f, "block", &peakBlocks[i]);
  }
  for (int i = 0; i < nall; ++i)
  {
    PrintBlock(f, "alloc", &allBlocks[i]);
  }
  fclose(f);
}
