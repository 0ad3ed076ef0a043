// SPDX-License-Identifier: MIT
/* xml_tree.c: the XML document as a tree (io/xml_tree.h), built from expat's start/end events. */
#include "io/xml_tree.h"

#include <expat.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "io/input_file.h"

typedef struct {
    XML_Parser parser;
    const char *file;
    XmlElement *root;
    XmlElement *stack[XML_DEPTH_LIMIT];
    int depth;
    long count;
    Error *err;
} TreeBuilder;

static void stop(TreeBuilder *b, ErrorCode code, const char *what)
{
    int line = (int)XML_GetCurrentLineNumber(b->parser);
    error_set(b->err, code, b->file, line, "%s:%d: %s", b->file, line, what);
    XML_StopParser(b->parser, XML_FALSE);
}

static bool append_child(XmlElement *parent, XmlElement *child)
{
    XmlElement **grown = realloc(parent->children, (size_t)(parent->num_children + 1) * sizeof *grown);
    if (!grown)
        return false;
    parent->children = grown;
    parent->children[parent->num_children++] = child;
    return true;
}

static XmlElement *new_element(const XML_Char *name, const XML_Char **attributes, int line)
{
    XmlElement *e = calloc(1, sizeof *e);
    int n = 0;
    while (attributes[n])
        n++;
    if (!e || !(e->name = strdup(name)) || (n && !(e->attributes = calloc((size_t)n, sizeof(char *))))) {
        xml_tree_free(e);
        return NULL;
    }
    e->line = line;
    e->num_attributes = n / 2; /* the array is zeroed: a failed copy leaves NULLs to free */
    for (int i = 0; i < n; i++)
        if (!(e->attributes[i] = strdup(attributes[i]))) {
            xml_tree_free(e);
            return NULL;
        }
    return e;
}

/* Adds the element to the tree; the reason when it cannot (NULL: added). */
static const char *add_element(TreeBuilder *b, const XML_Char *name, const XML_Char **attributes,
                               ErrorCode *code)
{
    *code = ERR_TOO_LARGE;
    if (b->depth >= XML_DEPTH_LIMIT)
        return "elements nested too deeply";
    if (++b->count > XML_ELEMENT_LIMIT)
        return "too many elements";
    *code = ERR_OUT_OF_MEMORY;
    XmlElement *e = new_element(name, attributes, (int)XML_GetCurrentLineNumber(b->parser));
    if (!e)
        return "out of memory";
    if (b->depth == 0) {
        b->root = e; /* expat refuses a second root element itself */
    } else if (!append_child(b->stack[b->depth - 1], e)) {
        xml_tree_free(e);
        return "out of memory";
    }
    b->stack[b->depth++] = e;
    return NULL;
}

static void XMLCALL on_start(void *data, const XML_Char *name, const XML_Char **attributes)
{
    TreeBuilder *b = data;
    ErrorCode code;
    const char *reason = add_element(b, name, attributes, &code);
    if (reason)
        stop(b, code, reason);
}

static void XMLCALL on_end(void *data, const XML_Char *name)
{
    (void)name;
    TreeBuilder *b = data;
    if (b->depth > 0) /* a start refused by stop() pushed nothing */
        b->depth--;
}

/* Mitsuba files have no DTD; refusing one refuses entity expansion (billion laughs) with it. */
static void XMLCALL on_doctype(void *data, const XML_Char *name, const XML_Char *sysid,
                               const XML_Char *pubid, int has_internal_subset)
{
    (void)name, (void)sysid, (void)pubid, (void)has_internal_subset;
    stop(data, ERR_FILE_READ, "DOCTYPE declarations are not read");
}

bool xml_tree_parse(const char *file, const char *text, size_t size, XmlElement **root, Error *err)
{
    *root = NULL;
    TreeBuilder b = {.file = file, .err = err};
    if (size > (size_t)INT32_MAX || !(b.parser = XML_ParserCreate(NULL))) {
        error_set(err, ERR_OUT_OF_MEMORY, file, 0, "%s: out of memory for the XML parser", file);
        return false;
    }
    XML_SetUserData(b.parser, &b);
    XML_SetElementHandler(b.parser, on_start, on_end);
    XML_SetStartDoctypeDeclHandler(b.parser, on_doctype);
    bool ok = XML_Parse(b.parser, text, (int)size, XML_TRUE) == XML_STATUS_OK;
    if (!ok && !error_is_set(err)) {
        int line = (int)XML_GetCurrentLineNumber(b.parser);
        error_set(err, ERR_FILE_READ, file, line, "%s:%d: malformed XML: %s", file, line,
                  XML_ErrorString(XML_GetErrorCode(b.parser)));
    }
    if (ok && !b.root) {
        error_set(err, ERR_FILE_READ, file, 0, "%s: no XML element", file);
        ok = false;
    }
    XML_ParserFree(b.parser);
    if (!ok) {
        xml_tree_free(b.root);
        return false;
    }
    *root = b.root;
    return true;
}

bool xml_tree_read(const char *path, size_t limit, XmlElement **root, Error *err)
{
    char *text;
    size_t size;
    *root = NULL;
    if (!input_file_read(path, "an XML file", limit, &text, &size, err))
        return false;
    bool ok = xml_tree_parse(path, text, size, root, err);
    free(text);
    return ok;
}

const char *xml_attribute(const XmlElement *e, const char *name)
{
    for (int i = 0; i < e->num_attributes; i++)
        if (strcmp(e->attributes[2 * i], name) == 0)
            return e->attributes[2 * i + 1];
    return NULL;
}

bool xml_set_attribute(XmlElement *e, int i, const char *value)
{
    char *copy = strdup(value);
    if (!copy)
        return false;
    free(e->attributes[2 * i + 1]);
    e->attributes[2 * i + 1] = copy;
    return true;
}

void xml_tree_free(XmlElement *root)
{
    if (!root)
        return;
    for (int i = 0; i < root->num_children; i++)
        xml_tree_free(root->children[i]);
    free(root->children);
    for (int i = 0; root->attributes && i < 2 * root->num_attributes; i++)
        free(root->attributes[i]);
    free(root->attributes);
    free(root->name);
    free(root);
}
