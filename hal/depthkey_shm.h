/*
 * depthkey shared-memory frame rings: the layout and a reader for consumers.
 *
 * depthkeyd publishes each stream as one POSIX shared-memory object
 * ("/depthkey.composite" RGB24, "/depthkey.lecturer" RGBA32 straight alpha):
 * a fixed header, a table of DK_SHM_MAX_SLOTS slot descriptors, then
 * slot_count pixel slots starting at data_offset. Frame n (n >= 1) is written
 * into slot n % slot_count under that slot's seqlock, then latest_frame = n.
 * The writer never waits for readers; a reader that is lapped mid-copy sees the
 * sequence number change and retries.
 *
 * Readers cannot write the frames or the header (version 3): the object is
 * mode 0640, so the output group opens it read-only and maps it PROT_READ;
 * it can neither scribble on the header nor shrink the object under the
 * writer's mapping (which would kill the writer with SIGBUS). A reader that
 * crashes or stalls cannot harm the writer or other readers' frames.
 *
 * Reader presence: a second, small object of its own, the stream's name plus
 * DK_SHM_PRESENCE_SUFFIX ("/depthkey.composite.readers", mode 0660), holds at
 * reader_offset a table of DK_SHM_MAX_READERS reader slots. The only thing a
 * reader may write. A reader in the group maps it read-write, claims a free
 * slot and bumps its beat counter on every
 * dk_shm_latest / dk_shm_read_latest / dk_shm_heartbeat call. The writer
 * reads the table with pread (never through a mapping, so a reader that
 * shrinks it cannot fault the writer; the writer restores its size) and
 * samples the counters; a slot whose counter has not moved for
 * DK_SHM_READER_TIMEOUT_MS is counted gone and freed, so a reader that dies
 * is gone within about a second, and a clean dk_shm_close frees it at once.
 * A reader calls one of those functions at least every 500 ms to stay
 * counted. Presence needs no clock in the reader; the writer never waits on
 * it. A reader without write access still reads (presence_error says why it
 * is not counted). A reader of the group can still shrink the presence
 * object: until the writer restores it (within 250 ms) other readers' beats
 * into the cut part fault (SIGBUS); their frames are untouched.
 *
 * Every field has a fixed width and offset (checked below) so that C, C++ and
 * other languages agree on the layout whatever the ABI. Multi-byte fields are
 * in host byte order: producer and consumers share one machine.
 *
 * This header compiles as strict C99 (gcc -std=c99 -pedantic, no feature
 * macros needed: what strict mode hides, O_CLOEXEC, is replaced by
 * fcntl(FD_CLOEXEC)), as C11 and as C++. It uses GCC/Clang __atomic builtins.
 * Link with -lrt on old glibc. 64-bit atomic loads must be plain loads (true
 * on x86-64, arm64 and armv7 with LPAE), because the frame mapping is
 * read-only.
 */
#ifndef DEPTHKEY_SHM_H
#define DEPTHKEY_SHM_H

#include <errno.h>
#include <fcntl.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef __cplusplus
extern "C" {
#endif

#define DK_SHM_MAGIC 0x48534b44u /* "DKSH" in memory on little-endian */
#define DK_SHM_VERSION 3u /* 2: reader presence table; 3: in its own object */
#define DK_SHM_MIN_SLOTS 2u
#define DK_SHM_MAX_SLOTS 8u
#define DK_SHM_MAX_DIMENSION 16384u
/* Pixels start on a page boundary so that slots can be mapped or DMA'd alone. */
#define DK_SHM_DATA_ALIGN 4096u
/* Bounded so that a reader facing a very fast writer still returns promptly. */
#define DK_SHM_READ_RETRIES 16
/* Reader slots in the presence table; a 17th concurrent reader reads but is
 * not counted (presence_error -EBUSY). */
#define DK_SHM_MAX_READERS 16u
/* A reader whose beat counter did not move for this long is counted gone. */
#define DK_SHM_READER_TIMEOUT_MS 1000u
/* Bound on reader_offset, so that offset + table size cannot overflow. */
#define DK_SHM_MAX_PRESENCE_OFFSET ((uint64_t)1 << 32)
/* The presence object's name is the stream's name plus this suffix. */
#define DK_SHM_PRESENCE_SUFFIX ".readers"
/* Longest stream name, its leading '/' included, whose presence name still
 * fits glibc's bound (253 characters after the slash before glibc 2.34). */
#define DK_SHM_NAME_MAX (254u - (sizeof(DK_SHM_PRESENCE_SUFFIX) - 1))

#ifdef O_CLOEXEC
#define DK_SHM_O_CLOEXEC O_CLOEXEC
#else
#define DK_SHM_O_CLOEXEC 0 /* hidden by strict C99: FD_CLOEXEC is set after open */
#endif

#define DK_SHM_FOURCC(a, b, c, d) \
	((uint32_t)(a) | ((uint32_t)(b) << 8) | ((uint32_t)(c) << 16) | ((uint32_t)(d) << 24))
#define DK_SHM_FORMAT_RGB24 DK_SHM_FOURCC('R', 'G', 'B', '3')  /* V4L2_PIX_FMT_RGB24: R,G,B */
#define DK_SHM_FORMAT_RGBA32 DK_SHM_FOURCC('A', 'B', '2', '4') /* V4L2_PIX_FMT_RGBA32: R,G,B,A */

/* Per-frame flags (dk_shm_slot.flags). */
#define DK_SHM_FLAG_ONLINE 0x1u    /* both cameras are delivering */
#define DK_SHM_FLAG_COLOUR_OK 0x2u /* the colour camera is delivering */
#define DK_SHM_FLAG_DEPTH_OK 0x4u  /* the depth camera is delivering */
/* Added in version 2 without a layout change (issue 29; older readers
 * ignore unknown bits, which is safe: the frame is a good one either way). */
#define DK_SHM_FLAG_DEPTH_STALE 0x8u /* keyed with depth beyond pairing.max_skew_ms
				      * (the superset grown for the gap) */
#define DK_SHM_FLAG_REPEATED 0x10u   /* the previous frame again, stamped with this
				      * capture slot: its own frame was shed or late */

struct dk_shm_slot {
	uint32_t sequence;      /* seqlock: odd while the writer fills the slot */
	uint32_t flags;         /* DK_SHM_FLAG_* */
	uint64_t frame;         /* frame number, 1.. within a generation */
	uint64_t timestamp_ns;  /* capture time, CLOCK_MONOTONIC */
	uint64_t payload_bytes; /* stride * height */
	uint8_t reserved[32];   /* one cache line per slot: no false sharing */
};

struct dk_shm_header {
	uint32_t magic;         /* DK_SHM_MAGIC */
	uint32_t version;       /* DK_SHM_VERSION */
	uint32_t header_size;   /* sizeof(struct dk_shm_header) */
	uint32_t slot_count;    /* DK_SHM_MIN_SLOTS..DK_SHM_MAX_SLOTS */
	uint64_t generation;    /* new on every writer (re)start; 0 = header being written, or object retired */
	uint32_t width;
	uint32_t height;
	uint32_t stride;        /* bytes per row */
	uint32_t fourcc;        /* DK_SHM_FORMAT_* */
	uint64_t slot_size;     /* bytes between slots, >= stride * height */
	uint64_t data_offset;   /* offset of slot 0's pixels from the object start */
	uint64_t latest_frame;  /* newest complete frame, 0 = none yet */
	uint32_t online;        /* 1 while a writer has the stream open */
	uint32_t reader_slots;  /* slots in the presence table, <= DK_SHM_MAX_READERS */
	uint64_t reader_offset; /* offset of struct dk_shm_reader_table in the presence object, page-aligned */
	uint8_t reserved[48];   /* slots start on their own cache line */
	struct dk_shm_slot slots[DK_SHM_MAX_SLOTS];
};

/* One reader's slot: a cache line of its own, so readers do not contend. */
struct dk_shm_reader_slot {
	uint64_t owner;         /* 0 = free, else the token of the reader holding it */
	uint64_t beats;         /* bumped by the reader; the writer watches it move */
	uint64_t frames_read;   /* frames the reader copied, for statistics */
	uint32_t pid;           /* the reader's process, for diagnostics */
	uint8_t reserved[36];
};

struct dk_shm_reader_table {
	uint64_t next_token;    /* readers take tokens from here: unique per claim */
	uint8_t reserved[56];
	struct dk_shm_reader_slot readers[DK_SHM_MAX_READERS];
};

#if defined(__cplusplus)
#define DK_SHM_STATIC_ASSERT(cond, tag) static_assert(cond, #tag)
#elif defined(__STDC_VERSION__) && __STDC_VERSION__ >= 201112L
#define DK_SHM_STATIC_ASSERT(cond, tag) _Static_assert(cond, #tag)
#else
#define DK_SHM_STATIC_ASSERT(cond, tag) typedef char dk_shm_assert_##tag[(cond) ? 1 : -1]
#endif

DK_SHM_STATIC_ASSERT(sizeof(struct dk_shm_slot) == 64, slot_size);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_slot, frame) == 8, slot_frame);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_slot, timestamp_ns) == 16, slot_timestamp);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_slot, payload_bytes) == 24, slot_payload);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, generation) == 16, hdr_generation);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, width) == 24, hdr_width);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, fourcc) == 36, hdr_fourcc);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, slot_size) == 40, hdr_slot_size);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, data_offset) == 48, hdr_data_offset);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, latest_frame) == 56, hdr_latest);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, online) == 64, hdr_online);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, reader_slots) == 68, hdr_reader_slots);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, reader_offset) == 72, hdr_reader_offset);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_header, slots) == 128, hdr_slots);
DK_SHM_STATIC_ASSERT(sizeof(struct dk_shm_header) == 640, hdr_size);
DK_SHM_STATIC_ASSERT(sizeof(struct dk_shm_reader_slot) == 64, reader_slot_size);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_reader_slot, beats) == 8, reader_slot_beats);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_reader_slot, pid) == 24, reader_slot_pid);
DK_SHM_STATIC_ASSERT(offsetof(struct dk_shm_reader_table, readers) == 64, reader_table_slots);
DK_SHM_STATIC_ASSERT(sizeof(struct dk_shm_reader_table) <= 4096, reader_table_page);

/* Bytes per pixel of a known format, 0 for an unknown one. */
static inline uint32_t dk_shm_bytes_per_pixel(uint32_t fourcc)
{
	if (fourcc == DK_SHM_FORMAT_RGB24)
		return 3;
	if (fourcc == DK_SHM_FORMAT_RGBA32)
		return 4;
	return 0;
}

struct dk_shm_reader {
	const struct dk_shm_header *header;
	const uint8_t *base;
	size_t map_size;
	/* Geometry copied at open time: the reader never trusts the shared header
	 * for bounds after validating it, so a writer cannot make it overrun. */
	uint64_t generation;
	uint32_t width, height, stride, fourcc, slot_count;
	uint64_t slot_size, data_offset, frame_bytes;
	/* Copies dropped because the writer overwrote the slot meanwhile: a
	 * consumer that sees this grow fast copies too slowly for slot_count. */
	uint64_t torn_copies;
	/* Presence: the read-write mapping of the reader table (NULL when the
	 * reader is not counted), the claimed slot and its token. */
	struct dk_shm_reader_table *presence;
	uint32_t presence_slots;
	uint32_t presence_index;
	uint64_t presence_token;
	/* 0 while counted, else why not: -EACCES (no write access to the
	 * presence object: not in the output group), -ENOENT (no presence
	 * object), -EBUSY (all reader slots taken; retried on every beat),
	 * -EPROTO (presence object too small), -ENAMETOOLONG, or the errno of
	 * mapping the table. */
	int presence_error;
};

struct dk_shm_frame_info {
	uint64_t frame;
	uint64_t timestamp_ns;
	uint32_t flags;
	uint32_t online; /* the writer had the stream open */
	uint32_t width, height, stride, fourcc;
	uint64_t bytes;  /* bytes copied: stride * height */
};

static inline int dk_shm_check_layout(const struct dk_shm_header *h, uint64_t size,
				      struct dk_shm_reader *r)
{
	uint32_t bpp = dk_shm_bytes_per_pixel(h->fourcc);

	r->width = h->width;
	r->height = h->height;
	r->stride = h->stride;
	r->fourcc = h->fourcc;
	r->slot_count = h->slot_count;
	r->slot_size = h->slot_size;
	r->data_offset = h->data_offset;
	r->frame_bytes = (uint64_t)r->stride * r->height;

	/* Dimensions are bounded first, so none of the products below overflow. */
	if (h->header_size != sizeof(struct dk_shm_header) || bpp == 0 ||
	    r->width == 0 || r->width > DK_SHM_MAX_DIMENSION ||
	    r->height == 0 || r->height > DK_SHM_MAX_DIMENSION ||
	    r->stride < (uint64_t)r->width * bpp || r->stride > 4 * DK_SHM_MAX_DIMENSION ||
	    r->slot_count < DK_SHM_MIN_SLOTS || r->slot_count > DK_SHM_MAX_SLOTS ||
	    r->slot_size < r->frame_bytes || r->slot_size > ((uint64_t)1 << 32) ||
	    r->data_offset < sizeof(struct dk_shm_header) || r->data_offset > size ||
	    (size - r->data_offset) / r->slot_count < r->slot_size)
		return -EPROTO;
	/* The presence table is in the presence object; its size is checked
	 * when it is mapped. */
	r->presence_slots = h->reader_slots;
	if (r->presence_slots == 0 || r->presence_slots > DK_SHM_MAX_READERS ||
	    h->reader_offset % DK_SHM_DATA_ALIGN || h->reader_offset > DK_SHM_MAX_PRESENCE_OFFSET)
		return -EPROTO;
	return 0;
}

/* Claims a free reader slot with a fresh token; -EBUSY when all are taken. */
static inline int dk_shm_claim_reader_slot(struct dk_shm_reader *r)
{
	struct dk_shm_reader_table *t = r->presence;
	uint64_t token;
	uint32_t i;

	do
		token = __atomic_add_fetch(&t->next_token, 1, __ATOMIC_RELAXED);
	while (token == 0);
	for (i = 0; i < r->presence_slots; i++) {
		uint64_t expected = 0;
		if (__atomic_compare_exchange_n(&t->readers[i].owner, &expected, token, 0,
						__ATOMIC_ACQ_REL, __ATOMIC_RELAXED)) {
			__atomic_store_n(&t->readers[i].pid, (uint32_t)getpid(), __ATOMIC_RELAXED);
			__atomic_add_fetch(&t->readers[i].beats, 1, __ATOMIC_RELEASE);
			r->presence_index = i;
			r->presence_token = token;
			r->presence_error = 0;
			return 0;
		}
	}
	r->presence_token = 0;
	r->presence_error = -EBUSY;
	return -EBUSY;
}

/*
 * Tells the writer this reader is still there. The read functions call it;
 * a reader that waits without reading calls it at least every 500 ms. If the
 * writer freed the slot (the reader was stopped for longer than
 * DK_SHM_READER_TIMEOUT_MS) or no slot was free, it claims one again.
 * Returns 0 while counted, else presence_error. Never blocks.
 */
static inline int dk_shm_heartbeat(struct dk_shm_reader *r)
{
	struct dk_shm_reader_slot *slot;

	if (!r->presence)
		return r->presence_error;
	slot = &r->presence->readers[r->presence_index];
	if (r->presence_token == 0 ||
	    __atomic_load_n(&slot->owner, __ATOMIC_ACQUIRE) != r->presence_token)
		return dk_shm_claim_reader_slot(r);
	__atomic_add_fetch(&slot->beats, 1, __ATOMIC_RELEASE);
	return 0;
}

/* Opens the presence object of stream `name` read-write, maps its reader
 * table and claims a slot. Failing only leaves the reader uncounted
 * (presence_error says why). */
static inline void dk_shm_join_presence(struct dk_shm_reader *r, const char *name)
{
	char presence[DK_SHM_NAME_MAX + sizeof(DK_SHM_PRESENCE_SUFFIX)];
	uint64_t offset = r->header->reader_offset;
	size_t length = strlen(name);
	struct stat st;
	void *map;
	int fd;

	if (length > DK_SHM_NAME_MAX) {
		r->presence_error = -ENAMETOOLONG;
		return;
	}
	memcpy(presence, name, length);
	memcpy(presence + length, DK_SHM_PRESENCE_SUFFIX, sizeof(DK_SHM_PRESENCE_SUFFIX));
	fd = shm_open(presence, O_RDWR | DK_SHM_O_CLOEXEC, 0);
	if (fd < 0) {
		r->presence_error = -errno;
		return;
	}
	if (fstat(fd, &st) < 0)
		r->presence_error = -errno;
	else if ((uint64_t)st.st_size < offset + sizeof(struct dk_shm_reader_table))
		r->presence_error = -EPROTO; /* shrunk by someone, or not ours */
	if (r->presence_error) {
		close(fd);
		return;
	}
	map = mmap(NULL, sizeof(struct dk_shm_reader_table), PROT_READ | PROT_WRITE, MAP_SHARED, fd,
		   (off_t)offset);
	r->presence_error = map == MAP_FAILED ? -errno : 0;
	close(fd); /* the mapping keeps the object alive */
	if (map == MAP_FAILED)
		return;
	r->presence = (struct dk_shm_reader_table *)map;
	dk_shm_claim_reader_slot(r);
}

/* Frees the reader's slot (the writer counts it gone at once) and unmaps. */
static inline void dk_shm_close(struct dk_shm_reader *r)
{
	if (r->presence) {
		uint64_t token = r->presence_token;
		if (token)
			__atomic_compare_exchange_n(&r->presence->readers[r->presence_index].owner,
						    &token, 0, 0, __ATOMIC_RELEASE, __ATOMIC_RELAXED);
		munmap((void *)r->presence, sizeof(struct dk_shm_reader_table));
	}
	if (r->base)
		munmap((void *)r->base, r->map_size);
	memset(r, 0, sizeof(*r));
}

/*
 * Maps the object read-only and validates it against its real size.
 * Returns 0, or -ENOENT (no such object), -EACCES, -EAGAIN (a writer is
 * creating or restarting it: try again shortly), -EPROTO (not a depthkey ring
 * of this version, or inconsistent/too small), or another negative errno.
 */
static inline int dk_shm_open(const char *name, struct dk_shm_reader *r)
{
	const struct dk_shm_header *h;
	struct stat st;
	uint64_t gen;
	void *map;
	int fd, ret;

	memset(r, 0, sizeof(*r));
	/* Read-only: the frames and the header are the writer's alone. */
	fd = shm_open(name, O_RDONLY | DK_SHM_O_CLOEXEC, 0);
	if (fd < 0)
		return -errno;
	if (!DK_SHM_O_CLOEXEC)
		fcntl(fd, F_SETFD, FD_CLOEXEC);
	if (fstat(fd, &st) < 0) {
		ret = -errno;
		close(fd);
		return ret;
	}
	if (st.st_size == 0) {
		close(fd);
		return -EAGAIN; /* just created, not sized yet */
	}
	if ((uint64_t)st.st_size < sizeof(struct dk_shm_header)) {
		close(fd);
		return -EPROTO;
	}
	map = mmap(NULL, (size_t)st.st_size, PROT_READ, MAP_SHARED, fd, 0);
	if (map == MAP_FAILED) {
		ret = -errno;
		close(fd);
		return ret;
	}
	r->base = (const uint8_t *)map;
	r->map_size = (size_t)st.st_size;
	r->header = h = (const struct dk_shm_header *)map;

	/* The header is itself guarded like a seqlock: the writer zeroes the
	 * generation while it rewrites the fields. */
	gen = __atomic_load_n(&h->generation, __ATOMIC_ACQUIRE);
	if (h->magic != DK_SHM_MAGIC && h->magic != 0)
		ret = -EPROTO; /* something else entirely */
	else if (gen == 0)
		ret = -EAGAIN; /* sized but not yet written, or being rewritten */
	else if (h->magic != DK_SHM_MAGIC || h->version != DK_SHM_VERSION)
		ret = -EPROTO;
	else
		ret = dk_shm_check_layout(h, (uint64_t)st.st_size, r);
	__atomic_thread_fence(__ATOMIC_ACQUIRE);
	if (ret == 0 && __atomic_load_n(&h->generation, __ATOMIC_RELAXED) != gen)
		ret = -EAGAIN;
	if (ret) {
		close(fd);
		dk_shm_close(r);
		return ret;
	}
	r->generation = gen;
	close(fd); /* the mapping keeps the object alive */
	dk_shm_join_presence(r, name);
	return 0;
}

/* The newest complete frame number (0 = none yet) in *frame, for cheap polling.
 * Returns 0, or -ESTALE when the writer restarted: close and open again. */
static inline int dk_shm_latest(struct dk_shm_reader *r, uint64_t *frame)
{
	const struct dk_shm_header *h = r->header;

	dk_shm_heartbeat(r);
	*frame = __atomic_load_n(&h->latest_frame, __ATOMIC_ACQUIRE);
	if (__atomic_load_n(&h->generation, __ATOMIC_ACQUIRE) != r->generation)
		return -ESTALE;
	return 0;
}

/*
 * Copies the newest complete frame (stride * height bytes) into dst.
 * Returns 0, or -ESTALE (writer restarted: close and open again), -ENODATA (no
 * frame written yet), -ENOBUFS (dst_size too small), -EAGAIN (the writer kept
 * overwriting the slot being copied: try again). info may be NULL.
 */
static inline int dk_shm_read_latest(struct dk_shm_reader *r, void *dst, size_t dst_size,
				     struct dk_shm_frame_info *info)
{
	const struct dk_shm_header *h = r->header;
	int attempt;

	dk_shm_heartbeat(r);
	if (dst_size < r->frame_bytes)
		return -ENOBUFS;

	for (attempt = 0; attempt < DK_SHM_READ_RETRIES; attempt++) {
		const struct dk_shm_slot *slot;
		uint64_t latest, frame, timestamp;
		uint32_t seq, flags, index;

		if (__atomic_load_n(&h->generation, __ATOMIC_ACQUIRE) != r->generation)
			return -ESTALE;
		latest = __atomic_load_n(&h->latest_frame, __ATOMIC_ACQUIRE);
		if (latest == 0)
			return -ENODATA;
		index = (uint32_t)(latest % r->slot_count);
		slot = &h->slots[index];

		seq = __atomic_load_n(&slot->sequence, __ATOMIC_ACQUIRE);
		if (seq & 1) {
			r->torn_copies++; /* lapped: the writer is refilling it already */
			continue;
		}
		frame = __atomic_load_n(&slot->frame, __ATOMIC_RELAXED);
		timestamp = __atomic_load_n(&slot->timestamp_ns, __ATOMIC_RELAXED);
		flags = __atomic_load_n(&slot->flags, __ATOMIC_RELAXED);
		memcpy(dst, r->base + r->data_offset + index * r->slot_size, (size_t)r->frame_bytes);
		/* Orders the copy before the re-check (seqlock reader side). */
		__atomic_thread_fence(__ATOMIC_ACQUIRE);
		if (__atomic_load_n(&slot->sequence, __ATOMIC_RELAXED) != seq) {
			r->torn_copies++;
			continue;
		}
		/* A restart may have changed the geometry under the copy. */
		if (__atomic_load_n(&h->generation, __ATOMIC_RELAXED) != r->generation)
			return -ESTALE;
		if (frame == 0)
			continue; /* slot reset by a restarting writer */

		if (r->presence && r->presence_token)
			__atomic_add_fetch(&r->presence->readers[r->presence_index].frames_read, 1,
					   __ATOMIC_RELAXED);
		if (info) {
			info->frame = frame;
			info->timestamp_ns = timestamp;
			info->flags = flags;
			info->online = __atomic_load_n(&h->online, __ATOMIC_RELAXED);
			info->width = r->width;
			info->height = r->height;
			info->stride = r->stride;
			info->fourcc = r->fourcc;
			info->bytes = r->frame_bytes;
		}
		return 0;
	}
	return -EAGAIN;
}

#ifdef __cplusplus
}
#endif

#endif /* DEPTHKEY_SHM_H */
