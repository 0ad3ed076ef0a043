/* SPDX-License-Identifier: MIT */
/* xml_tree.h: an XML document (Mitsuba 3 scene files) read whole into a tree of elements with
 * their attributes and the line each starts on, so that a reader can walk it in any order and
 * name file:line in its messages. Text content is dropped (Mitsuba keeps everything in
 * attributes). Parsed by expat; DOCTYPE declarations are refused (no entity expansion, no
 * external files), and the depth and the element count are bounded. */
#ifndef PT_XML_TREE_H
#define PT_XML_TREE_H

#include <stdbool.h>
#include <stddef.h>

#include "base/error.h"

#define XML_DEPTH_LIMIT 64
#define XML_ELEMENT_LIMIT 1000000

typedef struct XmlElement {
    char *name;
    int line;
    char **attributes; /* name, value, name, value, ... */
    int num_attributes;
    struct XmlElement **children;
    int num_children;
    bool used; /* set by readers: a property element they have read (the rest are warned about) */
} XmlElement;

/* Parses text[size] (file names it in messages) into *root. False: err says file:line and what. */
bool xml_tree_parse(const char *file, const char *text, size_t size, XmlElement **root, Error *err);
/* Reads a regular file (io/input_file.h) of at most limit bytes and parses it. */
bool xml_tree_read(const char *path, size_t limit, XmlElement **root, Error *err);
/* The value of attribute name, or NULL. */
const char *xml_attribute(const XmlElement *e, const char *name);
/* Replaces attribute i's value by a copy of value. False: out of memory. */
bool xml_set_attribute(XmlElement *e, int i, const char *value);
void xml_tree_free(XmlElement *root);

#endif
