// SPDX-License-Identifier: MIT
#include "io/image_checks.h"

#include <stdbool.h>
#include <string.h>

/* stb loops forever on a truncated RLE scanline (a zero-length dump read at the end of the file)
 * and reads zeros past the end of a flat one: walk the scanlines as stb will. */
/* stbi__hdr_gettoken over memory: a line up to '\n' (at most 1023 bytes kept, the rest skipped);
 * reading past the end gives 0 and the last byte of the file is dropped, as stb does. Returns
 * the token's first byte, 0 for an empty token (stb's end of the header). */
static int hdr_token(const unsigned char *data, size_t size, size_t *at, char *token, size_t cap)
{
    size_t length = 0;
    int c = *at < size ? data[(*at)++] : 0;
    while (*at < size && c != '\n') {
        if (length + 1 < cap)
            token[length] = (char)c;
        length++;
        if (length == 1023) {
            while (*at < size && data[(*at)++] != '\n')
                ;
            break;
        }
        c = *at < size ? data[(*at)++] : 0;
    }
    token[length + 1 < cap ? length : cap - 1] = '\0';
    return length ? (unsigned char)token[0] : 0;
}

const char *image_check_hdr(const unsigned char *data, size_t size, int width, int height)
{
    /* Header as stb reads it: the identifier, lines up to an empty one, the resolution line. */
    char token[16];
    size_t at = 0;
    hdr_token(data, size, &at, token, sizeof token);
    while (hdr_token(data, size, &at, token, sizeof token) != 0)
        ;
    hdr_token(data, size, &at, token, sizeof token);
    size_t left = size - at;
    const unsigned char *p = data + at;
    size_t flat_bytes = 4 * (size_t)width * (size_t)height;
    if (width < 8 || width >= 32768)
        return left < flat_bytes ? "truncated pixel data" : NULL;
    for (int y = 0; y < height; y++) {
        if (left < 4)
            return "truncated scanline";
        if (p[0] != 2 || p[1] != 2 || (p[2] & 0x80)) /* stb restarts flat from pixel 0 here */
            return left < flat_bytes ? "truncated pixel data" : NULL;
        if (((int)p[2] << 8 | p[3]) != width)
            return NULL; /* stb reports this one itself */
        p += 4, left -= 4;
        for (int channel = 0; channel < 4; channel++) {
            for (int x = 0; x < width;) {
                if (left < 1)
                    return "truncated RLE scanline";
                int count = *p++;
                left--;
                if (count > 128) {
                    count -= 128;
                    if (left < 1)
                        return "truncated RLE scanline";
                    p++, left--;
                } else {
                    if (count == 0)
                        return "zero-length RLE run";
                    if ((size_t)count > left)
                        return "truncated RLE scanline";
                    p += count, left -= (size_t)count;
                }
                if (count > width - x)
                    return NULL; /* stb reports "bad RLE data" itself */
                x += count;
            }
        }
    }
    return NULL;
}

/* Segments are walked from the start of image; entropy-coded data (after SOS) is skipped up to
 * the next marker, so a DHT between the scans of a progressive JPEG is checked too. */
const char *image_check_jpeg(const unsigned char *data, size_t size)
{
    if (size < 2 || data[0] != 0xff || data[1] != 0xd8)
        return NULL; /* not a JPEG */
    size_t at = 2;
    while (at + 4 <= size) {
        if (data[at] != 0xff) {
            at++; /* entropy-coded bytes or padding */
            continue;
        }
        unsigned marker = data[at + 1];
        if (marker == 0xff || marker == 0x00 || (marker >= 0xd0 && marker <= 0xd7) ||
            marker == 0x01) {
            at += marker == 0xff ? 1 : 2; /* fill byte, stuffed zero, restart: no length */
            continue;
        }
        if (marker == 0xd9)
            return NULL; /* end of image */
        size_t length = (size_t)data[at + 2] << 8 | data[at + 3];
        if (marker == 0xc4) {
            /* As stb reads it: by the declared length, with zeros past the end of the file. */
            size_t p = at + 4;
            long left = (long)length - 2;
            while (left > 0) {
                size_t codes = 0;
                for (size_t i = 1; i <= 16; i++)
                    codes += p + i < size ? data[p + i] : 0;
                if (codes > 256)
                    return "Huffman table with more than 256 codes";
                p += 17 + codes;
                left -= 17 + (long)codes;
            }
        }
        if (length < 2)
            return NULL; /* stb reports a bad length itself */
        at += 2 + length;
    }
    return NULL;
}

/* stb grows its IDAT buffer to a chunk's declared length before reading the chunk: a 100-byte
 * file declaring a 2 GiB chunk allocates 2 GiB. Every chunk must fit in the file. */
const char *image_check_png(const unsigned char *data, size_t size)
{
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (size < 8 || memcmp(data, signature, 8) != 0)
        return NULL; /* not a PNG */
    size_t at = 8;
    while (at + 8 <= size) {
        size_t length = (size_t)data[at] << 24 | (size_t)data[at + 1] << 16 |
                        (size_t)data[at + 2] << 8 | data[at + 3];
        if (memcmp(data + at + 4, "IEND", 4) == 0)
            return NULL;
        if (length > size - at - 8)
            return "a chunk declares more bytes than the file holds";
        at += 12 + length; /* length, type, data, CRC */
    }
    return NULL;
}
