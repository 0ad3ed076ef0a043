// SPDX-License-Identifier: MIT
/* json_depth.c: see json_depth.h. Strings are skipped (with their escapes) so brackets inside
 * them do not count; the text need not be valid JSON: the parser says what else is wrong. */
#include "base/json_depth.h"

bool json_depth_check(const char *file, const char *text, size_t size, Error *err)
{
    int depth = 0, line = 1;
    bool in_string = false;
    for (size_t i = 0; i < size; i++) {
        char c = text[i];
        if (c == '\n')
            line++;
        if (in_string) {
            if (c == '\\')
                i++;
            else if (c == '"')
                in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            if (++depth > JSON_DEPTH_LIMIT) {
                error_set(err, ERR_JSON_SYNTAX, file, line, "%s:%d: JSON nested more than %d "
                          "levels deep (byte %zu)", file, line, JSON_DEPTH_LIMIT, i);
                return false;
            }
        } else if ((c == ']' || c == '}') && depth > 0) {
            depth--;
        }
    }
    return true;
}
