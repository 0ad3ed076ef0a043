/* SPDX-License-Identifier: MIT */
/* json_depth.h: the nesting depth of JSON text, measured by a flat scan before any parser sees
 * it. Parsers and the code that walks their trees recurse once per level (cJSON stops at 1000,
 * tinygltf's JSON-to-Value conversion does not stop at all): a file of 100,000 '[' would overflow
 * the stack. One limit for every JSON pt reads, so the message is the same everywhere. */
#ifndef PT_JSON_DEPTH_H
#define PT_JSON_DEPTH_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

/* The deepest nesting pt accepts (cJSON's own limit, CJSON_NESTING_LIMIT). */
#define JSON_DEPTH_LIMIT 1000

/* True when no '[' or '{' outside strings opens level JSON_DEPTH_LIMIT + 1 in text[0, size);
 * else ERR_JSON_SYNTAX naming `file`, the line and the byte offset of that bracket. */
bool json_depth_check(const char *file, const char *text, size_t size, Error *err);

#endif
