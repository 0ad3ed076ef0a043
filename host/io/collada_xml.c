// SPDX-License-Identifier: MIT
/* collada_xml.c: the COLLADA reader's helpers (io/collada_internal.h): warnings and errors,
 * element and attribute access, the sorted id table every URL is looked up in, numbers and
 * colours read from element text. */
#include "io/collada_internal.h"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void collada_warn_once(Reader *r, Drop what, const char *fmt, const char *detail)
{
    if (r->warned & (1u << what))
        return;
    r->warned |= 1u << what;
    char message[512];
    snprintf(message, sizeof message, fmt, detail);
    warn("%s: %s", r->path, message);
}

bool collada_fail(Reader *r, const xmlNode *at, ErrorCode code, const char *fmt, const char *a,
                  const char *b)
{
    int line = at ? (int)xmlGetLineNo(at) : 0;
    char message[768];
    snprintf(message, sizeof message, fmt, a ? a : "", b ? b : "");
    error_set(r->err, code, r->path, line, "%s:%d: <%s>: %s", r->path, line,
              at ? (const char *)at->name : "COLLADA", message);
    return false;
}

bool collada_is(const xmlNode *n, const char *name)
{
    return n && n->type == XML_ELEMENT_NODE && strcmp((const char *)n->name, name) == 0;
}

xmlNode *collada_child(const xmlNode *n, const char *name)
{
    for (xmlNode *c = n ? n->children : NULL; c; c = c->next)
        if (collada_is(c, name))
            return c;
    return NULL;
}

xmlNode *collada_next_named(xmlNode *c, const char *name)
{
    for (c = c ? c->next : NULL; c; c = c->next)
        if (collada_is(c, name))
            return c;
    return NULL;
}

/* collada_child(collada_child(...)) along a path "a/b/c". */
xmlNode *collada_path_child(const xmlNode *n, const char *path)
{
    char part[64];
    while (n && *path) {
        size_t len = strcspn(path, "/");
        if (len >= sizeof part)
            return NULL;
        memcpy(part, path, len);
        part[len] = '\0';
        n = collada_child(n, part);
        path += len + (path[len] == '/');
    }
    return (xmlNode *)n;
}

/* An attribute's value (libxml2 owns the memory through the node), NULL when absent. */
const char *collada_attr(const xmlNode *n, const char *name)
{
    for (xmlAttr *a = n ? n->properties : NULL; a; a = a->next)
        if (strcmp((const char *)a->name, name) == 0 && a->children &&
            a->children->type == XML_TEXT_NODE)
            return (const char *)a->children->content;
    return NULL;
}

/* The first text child's content ("" when none): COLLADA's values are plain text. */
const char *collada_text(const xmlNode *n)
{
    for (xmlNode *c = n ? n->children : NULL; c; c = c->next)
        if (c->type == XML_TEXT_NODE || c->type == XML_CDATA_SECTION_NODE)
            return c->content ? (const char *)c->content : "";
    return "";
}

static int compare_ids(const void *a, const void *b)
{
    return strcmp(((const IdEntry *)a)->id, ((const IdEntry *)b)->id);
}

bool collada_collect_ids(Reader *r, xmlNode *n)
{
    /* Iterative walk: a hostile file may nest elements deeper than the stack allows. */
    while (n) {
        if (n->type == XML_ELEMENT_NODE) {
            const char *id = collada_attr(n, "id");
            if (id) {
                if (r->num_ids == r->cap_ids) {
                    size_t cap = r->cap_ids ? 2 * r->cap_ids : 256;
                    IdEntry *grown = realloc(r->ids, cap * sizeof *grown);
                    if (!grown)
                        return collada_fail(r, n, ERR_OUT_OF_MEMORY, "out of memory", NULL, NULL);
                    r->ids = grown, r->cap_ids = cap;
                }
                r->ids[r->num_ids++] = (IdEntry){id, n};
            }
            if (n->children) {
                n = n->children;
                continue;
            }
        }
        while (n && !n->next)
            n = n->parent && n->parent->type == XML_ELEMENT_NODE ? n->parent : NULL;
        if (n)
            n = n->next;
    }
    if (r->num_ids > 0) /* qsort and bsearch take no NULL array, even empty */
        qsort(r->ids, r->num_ids, sizeof *r->ids, compare_ids);
    return true;
}

/* The element a "#id" URL (or a bare id) names, NULL when none. */
xmlNode *collada_lookup(const Reader *r, const char *url)
{
    if (!url || r->num_ids == 0)
        return NULL;
    IdEntry key = {url[0] == '#' ? url + 1 : url, NULL};
    IdEntry *hit = bsearch(&key, r->ids, r->num_ids, sizeof *r->ids, compare_ids);
    return hit ? hit->node : NULL;
}

/* Reads up to n numbers of a node's text; returns how many it read (fewer: the text ended or a
 * word is not a number, which *bad reports). */
size_t collada_read_numbers(const char *s, double *out, size_t n, bool *bad)
{
    size_t i = 0;
    *bad = false;
    while (i < n) {
        while (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')
            s++;
        if (!*s)
            break;
        char *end;
        double v = strtod(s, &end);
        if (end == s || !isfinite(v)) {
            *bad = true;
            break;
        }
        out[i++] = v;
        s = end;
    }
    return i;
}

bool collada_read_exact(Reader *r, const xmlNode *n, double *out, size_t count)
{
    bool bad;
    if (collada_read_numbers(collada_text(n), out, count, &bad) == count)
        return true;
    char expected[16];
    snprintf(expected, sizeof expected, "%zu", count);
    return collada_fail(r, n, ERR_OBJ_PARSE, bad ? "a value is not a finite number%s" : "expected %s numbers",
                bad ? "" : expected, NULL);
}

void collada_color_of(const xmlNode *n, float rgb[3], float *alpha)
{
    double v[4] = {0, 0, 0, 1};
    bool bad;
    size_t got = collada_read_numbers(collada_text(n), v, 4, &bad);
    if (got >= 3 && !bad) {
        for (int c = 0; c < 3; c++)
            rgb[c] = (float)v[c];
        if (alpha)
            *alpha = (float)v[3];
    }
}
