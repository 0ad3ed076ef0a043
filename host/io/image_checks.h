/* SPDX-License-Identifier: MIT */
/* image_checks.h: structural checks of image files in memory, run before stb_image (2.27, Debian's)
 * decodes them, for the inputs on which stb itself misbehaves. Found by the corpus and libFuzzer
 * (tests/fuzz/): stb loops forever on a truncated RLE .hdr scanline, writes past its Huffman
 * tables on a JPEG whose DHT declares more than 256 codes, and allocates whatever length a PNG
 * chunk declares before reading it. Each returns why the file is corrupt, or
 * NULL when stb may decode it (stb still reports the errors it does catch itself). */
#ifndef PT_IMAGE_CHECKS_H
#define PT_IMAGE_CHECKS_H

#include <stddef.h>

/* Radiance .hdr with its declared width and height (from stbi_info): every scanline present,
 * no zero-length RLE run. */
const char *image_check_hdr(const unsigned char *data, size_t size, int width, int height);
/* JPEG: every marker segment lies inside the file and every Huffman table has at most 256 codes. */
const char *image_check_jpeg(const unsigned char *data, size_t size);

/* PNG: every chunk up to IEND fits in the file. */
const char *image_check_png(const unsigned char *data, size_t size);

#endif
