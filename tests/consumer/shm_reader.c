/*
 * A recorder as a consumer writes it: hal/depthkey_shm.h alone, compiled by
 * tests/process/shm_consumer_compile_test.cpp as strict C99 (gcc -std=c99 -pedantic,
 * no feature macros) and as C++17. It opens the stream named by argv[1],
 * copies one frame, prints "frame N bytes B sum S presence P" and keeps its
 * reader slot until stdin closes, so the test can count it.
 */
#include "hal/depthkey_shm.h"

#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
	struct dk_shm_reader reader;
	struct dk_shm_frame_info info;
	unsigned char *pixels;
	unsigned long sum = 0;
	uint64_t i;
	int ret, tries;

	if (argc != 2) {
		fprintf(stderr, "usage: shm_reader /name\n");
		return 2;
	}
	ret = dk_shm_open(argv[1], &reader);
	if (ret) {
		fprintf(stderr, "dk_shm_open %s: %s\n", argv[1], strerror(-ret));
		return 1;
	}
	pixels = (unsigned char *)malloc((size_t)reader.frame_bytes);
	if (!pixels)
		return 1;
	for (tries = 0; tries < 1000; tries++) {
		ret = dk_shm_read_latest(&reader, pixels, (size_t)reader.frame_bytes, &info);
		if (ret != -EAGAIN && ret != -ENODATA)
			break;
	}
	if (ret) {
		fprintf(stderr, "dk_shm_read_latest: %s\n", strerror(-ret));
		return 1;
	}
	for (i = 0; i < info.bytes; i++)
		sum += pixels[i];
	printf("frame %lu bytes %lu sum %lu presence %d\n", (unsigned long)info.frame,
	       (unsigned long)info.bytes, sum, reader.presence_error);
	fflush(stdout);
	while (getchar() != EOF)
		dk_shm_heartbeat(&reader);
	free(pixels);
	dk_shm_close(&reader);
	return 0;
}
