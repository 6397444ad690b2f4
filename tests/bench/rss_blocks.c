// LD_PRELOAD for `make bench-process` --blocks (tests/bench/process_bench.py):
// where a process's resident memory is, block by block. It remembers every
// live heap block of 64 KiB or more with its call stack; RSS_BLOCKS_AFTER
// seconds after the process starts it writes to RSS_BLOCKS_OUT, for each such
// block, its size, how much of it is resident (the present pages in
// /proc/self/pagemap, not counting the kernel's shared zero page, which a
// read of a never-written page maps) and its stack as backtrace_symbols_fd
// gives it (BINARY(+OFFSET) frames, for addr2line). A measuring aid only:
// never linked into anything, built by process_bench.py with cc.
#define _GNU_SOURCE
#include <execinfo.h>
#include <fcntl.h>
#include <malloc.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <unistd.h>

extern void *__libc_malloc(size_t);
extern void *__libc_calloc(size_t, size_t);
extern void *__libc_realloc(void *, size_t);
extern void *__libc_memalign(size_t, size_t);
extern void __libc_free(void *);

enum { kMinBlock = 65536, kMaxBlocks = 8192, kDepth = 14 };

struct Block {
	void *p;
	size_t n;
	int depth;
	void *stack[kDepth];
};

static struct Block blocks[kMaxBlocks];
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static __thread int inside; // backtrace() may allocate: not recorded

static void remember(void *p, size_t n)
{
	if (!p || n < kMinBlock || inside)
		return;
	inside = 1;
	void *stack[kDepth];
	int depth = backtrace(stack, kDepth);
	pthread_mutex_lock(&lock);
	for (int i = 0; i < kMaxBlocks; ++i)
		if (!blocks[i].p) {
			blocks[i].p = p;
			blocks[i].n = n;
			blocks[i].depth = depth;
			memcpy(blocks[i].stack, stack, sizeof stack);
			break;
		}
	pthread_mutex_unlock(&lock);
	inside = 0;
}

static void forget(void *p)
{
	if (!p || malloc_usable_size(p) < kMinBlock)
		return;
	pthread_mutex_lock(&lock);
	for (int i = 0; i < kMaxBlocks; ++i)
		if (blocks[i].p == p) {
			blocks[i].p = 0;
			break;
		}
	pthread_mutex_unlock(&lock);
}

void *malloc(size_t n)
{
	void *p = __libc_malloc(n);
	remember(p, n);
	return p;
}

void *calloc(size_t count, size_t size)
{
	void *p = __libc_calloc(count, size);
	remember(p, count * size);
	return p;
}

void *realloc(void *old, size_t n)
{
	forget(old);
	void *p = __libc_realloc(old, n);
	remember(p, n);
	return p;
}

void free(void *p)
{
	forget(p);
	__libc_free(p);
}

int posix_memalign(void **out, size_t alignment, size_t n)
{
	void *p = __libc_memalign(alignment, n);
	if (!p)
		return 12; // ENOMEM
	remember(p, n);
	*out = p;
	return 0;
}

void *aligned_alloc(size_t alignment, size_t n)
{
	void *p = __libc_memalign(alignment, n);
	remember(p, n);
	return p;
}

static uint64_t pageFrame(int pagemap, uintptr_t address)
{
	uint64_t entry = 0;
	if (pread(pagemap, &entry, 8, (off_t)(address / 4096) * 8) != 8 || !(entry >> 63))
		return 0; // not present
	return entry & ((UINT64_C(1) << 55) - 1);
}

static long residentKb(int pagemap, uint64_t zeroFrame, const struct Block *b)
{
	long pages = 0;
	for (uintptr_t a = (uintptr_t)b->p / 4096 * 4096; a < (uintptr_t)b->p + b->n; a += 4096) {
		uint64_t frame = pageFrame(pagemap, a);
		pages += frame && frame != zeroFrame;
	}
	return pages * 4;
}

static void *report(void *unused)
{
	(void)unused;
	inside = 1;
	const char *after = getenv("RSS_BLOCKS_AFTER");
	sleep(after ? (unsigned)atoi(after) : 10);
	FILE *out = fopen(getenv("RSS_BLOCKS_OUT"), "w");
	int pagemap = open("/proc/self/pagemap", O_RDONLY);
	if (!out || pagemap < 0)
		return 0;
	// The zero page: what a read of a fresh anonymous page maps.
	volatile char *fresh = mmap(0, 4096, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
	(void)fresh[0];
	const uint64_t zeroFrame = pageFrame(pagemap, (uintptr_t)fresh);
	pthread_mutex_lock(&lock);
	for (int i = 0; i < kMaxBlocks; ++i)
		if (blocks[i].p) {
			fprintf(out, "BLOCK %zu %ld\n", blocks[i].n, residentKb(pagemap, zeroFrame, &blocks[i]));
			fflush(out);
			backtrace_symbols_fd(blocks[i].stack, blocks[i].depth, fileno(out));
		}
	pthread_mutex_unlock(&lock);
	fclose(out);
	close(pagemap);
	return 0;
}

__attribute__((constructor)) static void start(void)
{
	if (!getenv("RSS_BLOCKS_OUT"))
		return;
	pthread_t thread;
	inside = 1;
	pthread_create(&thread, 0, report, 0);
	pthread_detach(thread);
	inside = 0;
}
